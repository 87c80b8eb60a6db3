// Where a pixel's samples lie: the multisample patterns, written down once for
// setup (which pixels a triangle can reach), the tile stage (coverage and depth
// per sample) and the lab's references. The positions are Direct3D's standard
// patterns (D3D11_STANDARD_MULTISAMPLE_PATTERN; Mesa's SWR rasterizer lists
// the same), in 1/16 pixel from the pixel centre, y down. On the 1/256-pixel
// grid of window/window_space.h each is a whole 16 units, so coverage and the
// top-left rule stay exact at every sample.
#pragma once

#include <cstdint>
#include <type_traits>

namespace quadra {

constexpr int kSampleUnitsPerPixel = 16;
constexpr int kMaxSamples = 16;

struct SampleOffset {
  std::int8_t x = 0, y = 0;  // 1/16 pixel from the pixel centre
};

struct SamplePattern {
  int count = 1;
  SampleOffset offsets[kMaxSamples] = {};
  // Each offset four times over, widened: entry 4k + j is sample k's, for
  // pixel j of a quad, as the quad-samples kernels take a register of them
  // per triangle (tile_kernel_impl.h visibilityQuadSamples).
  alignas(64) std::int32_t quadLaneX[4 * kMaxSamples] = {};
  alignas(64) std::int32_t quadLaneY[4 * kMaxSamples] = {};
  // Each offset in pixels (1/16 of it, exact), as the sample depth planes
  // take them (tile/tile_kernel.h SampleDepths); zero past `count`.
  double pixelOffsetX[kMaxSamples] = {};
  double pixelOffsetY[kMaxSamples] = {};
  // The largest |x| or |y| of any offset, in 1/256 pixel: how far beyond a
  // pixel centre a sample reaches.
  int reachSubpixels() const;
};

// How often a multisampled frame shades (api/renderer.h RenderSettings).
// Pixel: once per pixel and visible triangle (multisampling): at the pixel
// centre where one triangle holds every sample, else at the mean position of
// the samples the triangle holds there (inside the triangle, so nothing is
// extrapolated); the colour goes to those samples. glTF BLEND draws too,
// each covered sample blended at its own depth; draws with an embedder's
// blend state, and any with quad derivatives, are shaded per sample
// (ShadeState::shadedPerSampleAtPixelRate). Sample: every sample is shaded
// at its own position (supersampling). A lookup shaded per sample filters
// for the sample spacing (footprints scaled by 1/sqrt(samples)).
enum class ShadingRate : std::uint8_t { Pixel, Sample };

// How a frame's samples become its pixels (api/renderer.h RenderSettings).
enum class PixelFilter : std::uint8_t {
  Box,  // each pixel the mean of its own samples
  // Every sample within 2 px of the pixel's centre, weighted by a
  // Blackman–Harris window, across tile borders (tile/pixel_filter.h).
  BlackmanHarris,
};

// Where sample k is shaded at the sample rate: for 4 and 16 samples the
// centre of its own cell of the pixel's 2x2 or 4x4 grid (cells 1/2 or 1/4
// pixel wide, the footprint a sample's lookups filter), elsewhere the sample
// itself. A sample's colour is its texture's filtered average over a
// footprint of 1/N of the pixel's area around where it is shaded; the
// standard positions are not one per cell, so footprints there overlap and
// leave gaps, and their mean misses the pixel's box by more than the filters
// do (builtin:checker-plane at 16 samples with the anisotropic filter: 37.9
// dB against the exact box at the positions, 49.8 with one sample a cell;
// even the exact area filter reaches only 38.1 at the positions). Coverage
// and depth stay at the positions. Each sample takes the cell it lies in (a
// position on a cell's edge the cell on its right or below), but two of
// the sixteen, 3 and 7, whose cells the neighbours 13 and 9 hold: they take the
// empty cells beside them (sample 3 lies on that cell's edge, 7 within 1/16
// pixel of it).
SampleOffset shadingOffset(const SamplePattern& pattern, int k);

// Whether N is a sample count the engine renders: 1, 2, 4, 8 or 16.
constexpr bool isSampleCount(int n) {
  return n == 1 || n == 2 || n == 4 || n == 8 || n == 16;
}

// The pattern of N samples (isSampleCount(N)); 1 is the pixel centre.
const SamplePattern& samplePattern(int count);

// visit(std::integral_constant<int, N>()) for a multisample count N (2, 4,
// 8 or 16), so that loops over a pixel's samples know N when compiled.
template <class Visit>
decltype(auto) withSampleCount(int count, Visit&& visit) {
  switch (count) {
    case 2:
      return visit(std::integral_constant<int, 2>());
    case 4:
      return visit(std::integral_constant<int, 4>());
    case 8:
      return visit(std::integral_constant<int, 8>());
    default:
      return visit(std::integral_constant<int, 16>());
  }
}

}  // namespace quadra
