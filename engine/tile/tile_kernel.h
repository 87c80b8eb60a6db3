// The tile kernels, compiled once per ISA (tile_kernel_isa.cpp.in) and reached
// through one table chosen at start-up. Opaque and masked draws go through two
// passes per tile: visibility (coverage and depth per sample, remembering the
// triangle that won each sample) and shading (the visible pixels of one draw,
// packed densely into SIMD lanes whatever their triangles' sizes). Blended
// draws and test views take the forward path, which shades as it rasterizes.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "setup/triangle_record.h"
#include "shading/background_view.h"
#include "simd/double_pairs.h"
#include "simd/isa.h"
#include "tile/blended_fragments.h"
#include "tile/tile_buffers.h"
#include "vertex/draw.h"
#include "window/sample_pattern.h"

namespace quadra {

// A triangle the visibility pass kept in a tile: its index in the tile's list
// is what TileBuffers::visible holds.
struct TileTriangle {
  const TriangleRecord* triangle;
  const Plane* planes;
  std::uint32_t draw;
};

// A triangle's plane rebased to a tile: its value at tile-local pixel centre
// (x, y) is c + dx*x + dy*y. In double, once per triangle and tile, so the
// per-pixel float evaluation only ever spans one tile.
inline Plane planeInTile(const Plane& p, const TriangleRecord& t, const TileBuffers& tile) {
  const double c = double(p.c) + double(p.dx) * double(tile.originX - t.minX) +
                   double(p.dy) * double(tile.originY - t.minY);
  return {p.dx, p.dy, float(c)};
}

// Each sample's depth plane rebased to a tile: c of
// planeInTile(depth.atSample(pattern.offsets[k]), t, tile), the plane moved
// to sample k and rebased, rounded to float at both steps, two samples at a
// time. The rounding between the steps is written out (simd/double_pairs.h):
// GCC 12 vectorized a scalar loop of them into one step and dropped it (one
// ulp off the other paths' depths). Always inlined into the kernels that
// take it per small triangle, where a call computing every sample (with the
// offsets converted there) was ~6% of a 4-sample
// MetalRoughSpheresNoTextures frame (perf, AVX2).
struct SampleDepths {
  simd::DoublePair dx, dy, c, stepX, stepY;
  QUADRA_DOUBLE_PAIR_INLINE SampleDepths(const Plane& depth, const TriangleRecord& t,
                                         const TileBuffers& tile)
      : dx(depth.dx),
        dy(depth.dy),
        c(depth.c),
        stepX(double(depth.dx) * double(tile.originX - t.minX)),
        stepY(double(depth.dy) * double(tile.originY - t.minY)) {}
  // Samples k and k + 1 (k + 1 < kMaxSamples; past the pattern's count an
  // offset of zero) in the low two floats. The offset in pixels is the
  // division of Plane::atSample: dividing each product by 16 before their
  // sum or after it rounds the same.
  QUADRA_DOUBLE_PAIR_INLINE __m128 pair(const SamplePattern& pattern, int k) const {
    using simd::DoublePair;
    const DoublePair shift = dx * DoublePair::load(pattern.pixelOffsetX + k) +
                             dy * DoublePair::load(pattern.pixelOffsetY + k);
    const DoublePair moved = (c + shift).roundedToFloat();  // Plane::atSample's rounding
    return ((moved + stepX) + stepY).asFloats();
  }
  // Samples k to k + 3 (k + 3 < kMaxSamples), as pair().
  QUADRA_DOUBLE_PAIR_INLINE __m128 four(const SamplePattern& pattern, int k) const {
    return _mm_movelh_ps(pair(pattern, k), pair(pattern, k + 2));
  }
};

// c[k] for each of the pattern's first `samples` samples (an even count, 2
// to 16), as SampleDepths; inlined, a constant count unrolls.
QUADRA_DOUBLE_PAIR_INLINE void sampleDepthsInTile(const Plane& depth, const SamplePattern& pattern,
                                                  const TriangleRecord& t, const TileBuffers& tile,
                                                  int samples, float* c) {
  const SampleDepths depths(depth, t, tile);
  for (int k = 0; k < samples; k += 2)
    _mm_storel_pi(reinterpret_cast<__m64*>(c + k), depths.pair(pattern, k));
}

// How far a float evaluation of a depth plane may stray from the exact
// plane within `span` pixels of where c holds: 2^-20 of the plane's largest
// term, far past the roundings of rebasing it and of its lane evaluation.
// A constant plane evaluates exactly (c + 0x + 0y): no margin, so coplanar
// layers at one depth (orthographic scenes, camera-facing quads) stay
// apart. Hierarchical depth and the blended order pass's skip widen depth
// ranges by it.
inline double depthPlaneMargin(double c, double dx, double dy, double span) {
  if (dx == 0.0 && dy == 0.0) return 0.0;
  return (std::abs(c) + span * (std::abs(dx) + std::abs(dy))) * 0x1p-20 + 1e-37;
}

// Shading planes of a tile's triangles, rebased to the tile (the value at
// tile-local pixel centre (x, y) is c + dx*x + dy*y): per triangle, 1/w and
// then each attribute/w, kShadePlaneStride floats apart.
// Lit shading: position 3, normal 3, tangent 4, two texcoord sets, colour 4.
constexpr int kMaxShadedAttributes = 18;
constexpr int kShadePlaneStride = 3 * (1 + kMaxShadedAttributes);

// The visible pixels of one draw in a tile: its whole lane groups (aligned
// runs of `lanes` pixels, all this draw's) are shaded in place, the rest of
// its pixels packed into lanes. Either the tile stage lists them (groups,
// pixels), or with scanTile the kernel finds them by scanning the tile's
// TileBuffers::visible for ids in [firstTriangle, endTriangle) (a draw's
// triangles are consecutive; cheaper when one draw has the whole tile).
constexpr std::uint32_t kMaxScannedTriangles = 1u << 24;  // exact as float ids

// A multisampled pixel's visible triangle, shaded once at its own tile-local
// position (pixel centres at whole numbers): the pixels whose samples
// several triangles share.
struct ShadeJob {
  float x, y;
  std::uint32_t triangle;  // tile triangle id
  std::uint16_t pixel;     // TileBuffers index
};

struct ShadeRun {
  bool scanTile = false;
  std::uint32_t firstTriangle = 0, endTriangle = 0;
  const std::uint16_t* groups = nullptr;  // first pixel index of each whole group
  int groupCount = 0;
  const std::uint16_t* pixels = nullptr;  // the other pixels, in tile order
  int pixelCount = 0;
  const float* planes = nullptr;  // kShadePlaneStride floats per tile triangle, one more after
  // Instead of the above: jobs, whose colours (R, G, B; alpha is 1) go to
  // jobColor, 3 floats each, not to the tile.
  const ShadeJob* jobs = nullptr;
  int jobCount = 0;
  float* jobColor = nullptr;
};

// Where each shading AOV's floats start in TileKernels::shadingAovs' output.
enum ShadingAovChannel : int {
  kAlbedoChannel = 0,     // R, G, B
  kRoughnessChannel = 3,  // 1
  kMetallicChannel = 4,   // 1
  kEmissionChannel = 5,   // R, G, B
  kDiffuseChannel = 8,    // R, G, B
  kSpecularChannel = 11,  // R, G, B
  kShadingAovFloats = 14,
};

struct TileKernels {
  Isa isa;
  int lanes;  // SIMD width in pixels (4 per quad)
  // Forward path: coverage, depth test, perspective-correct attributes, LOD,
  // texture sample, blend, for the part of the triangle inside the tile.
  // With `deferred`, a blended ("over") draw's fragments at the samples
  // orderBlended marked late go there, as sample plane `plane`'s, instead of
  // blending now (tile/blended_fragments.h).
  void (*rasterize)(const TriangleRecord& triangle, const Plane* planes, const ShadeState& shade,
                    TileBuffers& tile, BlendedFragments* deferred, int plane);
  // The order pass over a blended draw's triangle, before any is shaded:
  // marks the samples of plane `plane` where it arrives behind an earlier one.
  void (*orderBlended)(const TriangleRecord& triangle, const Plane* planes, const ShadeState& shade,
                       TileBuffers& tile, BlendedFragments& fragments, int plane);
  // A blended draw composed in depth order, shaded once per pixel (the pixel
  // rate, several samples): first coverBlended at every sample plane, the
  // triangle and its depth plane moved to that sample, marking in
  // fragments.covered() the samples it covers and that pass the depth test;
  // then shadeBlendedPixels with the triangle's own planes, which shades each
  // marked pixel once and blends it into, or defers it at, each marked sample.
  void (*coverBlended)(const TriangleRecord& triangle, const Plane* planes, const ShadeState& shade,
                       TileBuffers& tile, BlendedFragments& fragments, int plane);
  void (*shadeBlendedPixels)(const TriangleRecord& triangle, const Plane* planes,
                             const ShadeState& shade, const SamplePattern& pattern,
                             TileBuffers* samplePlanes, BlendedFragments& fragments);
  // After a tile's last draw: every sample's kept fragments composited over
  // its colour in `planes` (one TileBuffers per sample plane), far to near,
  // fragments at equal depths in the order they arrived; a lane group's
  // samples sorted at once. Leaves the store empty.
  void (*compositeBlended)(BlendedFragments& fragments, TileBuffers* planes);
  // Visibility pass: coverage and depth test (and a masked draw's alpha
  // test); the samples the triangle wins get its depth and `id`. Returns
  // whether it won any.
  bool (*visibility)(const TriangleRecord& triangle, const Plane* planes, const ShadeState& shade,
                     std::uint32_t id, TileBuffers& tile);
  // The same at every sample of a multisampled tile, plane k holding sample k
  // of `pattern`, for a draw that is not masked (`planes`: its depth plane);
  // the same bits as `visibility` on each plane with the triangle moved to
  // its sample (atSample), the small triangles' work shared between samples.
  bool (*visibilityAtSamples)(const TriangleRecord& triangle, const Plane* planes,
                              const ShadeState& shade, std::uint32_t id,
                              const SamplePattern& pattern, TileBuffers* samplePlanes);
  // Shading pass: the colour of every pixel of the run, all of one draw.
  void (*shade)(const ShadeState& shade, const ShadeRun& run, TileBuffers& tile);
  // Whole-plane loops over a multisampled tile (one TileBuffers a sample),
  // here so that they compile for the ISA: in the tile stage they were
  // SSE2, a sixth of alpha-quads' 16-sample frame. copyAgreeingSamples:
  // plane 0's colour to the other planes where differs[pixel] is 0.
  // averageSamples: the samples' mean into plane 0's colour, summed pairwise
  // (planes k and k + w for w = 1, 2, 4, ...), as the shading pass sums a
  // pixel's jobs, so samples of one colour average to that colour.
  // nearestSampleDepth: each pixel's nearest sample's depth into plane 0.
  void (*copyAgreeingSamples)(TileBuffers* planes, int samples, const std::uint32_t* differs);
  void (*averageSamples)(TileBuffers* planes, int samples);
  void (*nearestSampleDepth)(TileBuffers* planes, int samples, bool depthGreater);
  // The lod and anisotropy AOVs of a textured draw's jobs (each at its
  // tile-local position with its own triangle's planes, rebased as the
  // shading pass's): the footprint the shading pass takes there and the
  // level and probe count the draw's filter chooses for it, one float each.
  void (*footprintLevels)(const ShadeState& shade, const float* planes, const ShadeJob* jobs,
                          int count, float* lod, float* anisotropy);
  // The shading AOVs (io/frame.h kShadingAovs) of a draw's jobs, each at its
  // position with its triangle's planes as footprintLevels takes them: a lit
  // draw's material terms and lobes (shading/material_lanes.h materialAovs),
  // another draw's base colour and zeros. kShadingAovFloats floats a job, in
  // ShadingAovChannel order: channel c of job j at out[c * count + j].
  void (*shadingAovs)(const ShadeState& shade, const float* planes, const ShadeJob* jobs, int count,
                      float* out);
  // A lit frame's environment behind each pixel of `tile` that its surfaces
  // leave uncovered: colour + (1 - alpha) x the environment seen through the
  // pixel (shading/background_lanes.h), alpha 1.
  void (*compositeBackground)(const BackgroundView& view, TileBuffers& tile);
};

// The table for an ISA; the caller has checked isaSupported(isa).
const TileKernels& tileKernels(Isa isa);

// The kernels a frame runs: `wide` for most triangles, and for triangles
// narrower than `narrowBelow` pixels the next narrower SIMD path, which such a
// triangle fills better. Every path writes the same bits (the precision
// contract), so mixing them changes speed only. Measured on the dense mesh
// (2M triangles, 1080p, 2 threads): AVX-512 alone 117 ms, AVX2 alone 109 ms.
struct TileKernelSelection {
  const TileKernels* wide = nullptr;
  const TileKernels* narrow = nullptr;
  int narrowBelow = 0;
  const TileKernels& forWidth(int pixels) const { return pixels < narrowBelow ? *narrow : *wide; }
  // For visibilityAtSamples: a triangle whose box is at most 8x8 pixels
  // (kQuadSamplesBox) takes the path whose registers hold one quad's samples
  // (quadSampleRegisters), which tests them all at once, where the frame has
  // one; others as forWidth.
  static constexpr int kQuadSamplesBox = 8;
  const TileKernels& forSamples(int pixelsWide, int pixelsHigh, int samples) const {
    if (pixelsWide <= kQuadSamplesBox && pixelsHigh <= kQuadSamplesBox)
      if (const TileKernels* quad = quadSamples[std::countr_zero(unsigned(samples))]) return *quad;
    return forWidth(pixelsWide);
  }
  // Per sample count 2^i, at index i: the first of wide and narrow with a
  // quad-samples path at that count, or null. Chosen once by
  // selectTileKernels, where choosing per triangle ran ~25 instructions a
  // call (callgrind, MetalRoughSpheresNoTextures at 4 samples).
  const TileKernels* quadSamples[std::countr_zero(unsigned(kMaxSamples)) + 1] = {};
  // How many registers of `lanes` lanes hold one quad's `samples` samples
  // on the quad-samples path (lane 4k + j of register r: pixel j of the quad
  // at sample r * lanes / 4 + k), or 0 where that path is not taken: more
  // than 4 registers, or more lanes than a quad's samples, left to each
  // sample's lane groups in turn, as is the scalar path, so that the
  // cross-ISA tests hold the two ways against each other. Lanes are a power
  // of two (other widths take no such path): masks and a shift, where two
  // integer divisions by a run-time width ran once per triangle (perf put
  // 1.5% of a 4-sample MetalRoughSpheresNoTextures frame on that line).
  static constexpr int kMaxQuadSampleRegisters = 4;
  static constexpr int quadSampleRegisters(Isa isa, int lanes, int samples) {
    if (isa == Isa::Scalar || lanes < 4 || (lanes & (lanes - 1)) != 0 ||
        ((4 * samples) & (lanes - 1)) != 0)
      return 0;
    const int registers = (4 * samples) >> __builtin_ctz(unsigned(lanes));
    return registers <= kMaxQuadSampleRegisters ? registers : 0;
  }
};
TileKernelSelection selectTileKernels(Isa isa);

const TileKernels& tileKernelsScalar();
const TileKernels& tileKernelsSse2();
const TileKernels& tileKernelsAvx2();
const TileKernels& tileKernelsAvx512();

}  // namespace quadra
