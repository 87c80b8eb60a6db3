// Pixel reconstruction filters wider than a pixel: the samples of a tile →
// its pixels of the frame, with the pixels near a tile border finished by a
// second pass from what each neighbouring tile left for them. (The pixel box
// filter, which needs no neighbour, stays in tile_stage.cpp.)
//
// Blackman–Harris, radius 2 px (4 px wide, pbrt's default filter width):
// separable, weight(sample) = bh(dx) * bh(dy) with (dx, dy) the sample's
// position from the output pixel's centre and bh(x) = a0 + a1 cos(pi x/2) +
// a2 cos(pi x) + a3 cos(3 pi x/2), 0 for |x| >= 2. Chosen over Mitchell–
// Netravali because it has no negative lobes: premultiplied colour and alpha
// never ring below 0 or above the largest sample at an opaque silhouette.
// Each output pixel is the weighted sum of every sample within the radius of
// its centre (the samples of the 5x5 pixels around it), divided by the sum of
// those weights (the samples inside the image only, so the image's edge pixels
// are not darkened). At one sample it is a blur of the pixel centres.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "io/frame.h"
#include "tile/tile_buffers.h"
#include "window/sample_pattern.h"

namespace quadra {

constexpr int kPixelFilterRadius = 2;                         // pixels
constexpr int kPixelFilterTaps = 2 * kPixelFilterRadius + 1;  // source pixels a row

// The Blackman–Harris weight at distance x (pixels) from an output pixel's centre.
double blackmanHarris(double x);

// The filter's weights for one sample pattern, in float as the sums use them.
struct PixelFilterWeights {
  int samples = 1;
  // [k][dy + 2][dx + 2]: sample k of the pixel (dx, dy) away from the output pixel.
  float sample[kMaxSamples][kPixelFilterTaps][kPixelFilterTaps] = {};
  // The same summed over the samples (in double, then rounded): the weight of
  // a pixel whose samples all agree, which is then read once, not N times.
  float pixel[kPixelFilterTaps][kPixelFilterTaps] = {};
  double interiorSum = 0.0;  // pixel's weights summed, for pixels 2 or more from the image edge

  static PixelFilterWeights blackmanHarris(const SamplePattern& pattern);
  // The sum of the weights of the samples inside a width x height image that
  // reach output pixel (x, y): what its weighted sum is divided by.
  float weightSum(int x, int y, int width, int height) const;
};

// The part of a tile's filtered sums that belongs to pixels outside it: the
// ring of pixels up to 2 away from its four sides, corners included (528 for
// a 64x64 tile), `channels` floats each (RGBA, then coverage when asked).
constexpr int kBorderRingPixels = 4 * (kTileSize + 2 * kPixelFilterRadius) + 4 * kTileSize;

// One task's working memory for filtering a tile, reused from tile to tile.
struct PixelFilterScratch {
  std::vector<float> source;         // channels planes of the tile, row-major, zero-padded by 4 px
  std::vector<float> sums;           // channels planes of the sums over the tile grown by 2 px
  std::vector<std::uint16_t> mixed;  // pixels whose samples differ, in tile order
};

// An upper bound on what a PixelFilterScratch holds for `channels` channels
// (tileMemoryBytes).
constexpr std::uint64_t pixelFilterScratchBytes(int channels) {
  constexpr std::uint64_t kSourceSide = kTileSize + 4 * kPixelFilterRadius;
  constexpr std::uint64_t kSumsSide = kTileSize + 2 * kPixelFilterRadius;
  return std::uint64_t(channels) * (kSourceSide * kSourceSide + kSumsSide * kSumsSide) *
             sizeof(float) +
         2 * std::uint64_t(kTileSize) * kTileSize * sizeof(std::uint16_t);  // mixed, doubling
}

// What the filter passes of one frame share.
struct PixelFilterFrame {
  const PixelFilterWeights& weights;
  int tilesX = 0, tilesY = 0;
  float clearDepth = 1.0f;       // a sample still at it holds no depth-writing triangle
  bool coverage = false;         // also filter the coverage into Frame::coverage
  float* borderRings = nullptr;  // a ring per tile, kBorderRingPixels * channels() floats each

  int channels() const { return coverage ? 5 : 4; }
};

// First pass, one tile: its samples (one plane per sample) filtered. The
// pixels whose whole footprint lies in the tile (or off the image) get their
// final colour in planes[0]; the others within 2 px of a shared tile border
// get this tile's partial weighted sum there (and in Frame::coverage), and
// the sums for the neighbours' pixels go to the tile's ring. sampleDiffers:
// per pixel, non-zero where its samples may differ, the others holding their
// colour in planes[0] alone (shading per pixel); null: every plane holds
// every sample, compared here.
void filterTileSamples(int tileIndex, const PixelFilterFrame& filter, TileBuffers* planes,
                       const std::uint32_t* sampleDiffers, PixelFilterScratch& scratch, Frame& out);

// Second pass, one tile, after every tile's first pass: its pixels near a
// shared border finished from its own partial sums and the neighbours' rings,
// added in a fixed order (its own, then the neighbours' in tile order), so
// the frame is the same for any thread count and schedule.
void finishTileBorders(int tileIndex, const PixelFilterFrame& filter, Frame& out);

// The box filter's coverage: the fraction of each pixel's samples a
// depth-writing triangle holds, into Frame::coverage. Reads the samples'
// depth, so it runs before the resolve keeps only the nearest.
void boxCoverage(const TileBuffers* planes, int samples, float clearDepth, Frame& out);

}  // namespace quadra
