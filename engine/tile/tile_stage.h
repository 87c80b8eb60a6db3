// Tile stage: binned triangles → the frame. Tiles are independent tasks; each
// walks the front-end chunks in submission order and rasterizes into its own
// L2-resident buffers, then writes its pixels of the frame once.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bin/bins.h"
#include "io/frame.h"
#include "setup/triangle_setup.h"
#include "tile/pixel_filter.h"
#include "tile/surface_aov.h"
#include "tile/tile_kernel.h"
#include "vertex/draw.h"
#include "window/sample_pattern.h"

namespace quadra {

class Executor;

// One front-end chunk: triangles in submission order and their bins, and the
// thread time (ms) its setup and binning took.
struct FrontEndChunk {
  SetupOutput setup;
  TileBins bins;
  double setupMs = 0.0, binMs = 0.0;
};

// Thread time (ms) one tile spent in each of its steps.
struct TileTimes {
  double raster = 0.0, shade = 0.0, resolve = 0.0;
};

// What every tile of a frame shares.
struct TileFrame {
  const TileGrid& grid;
  const std::vector<Draw>& draws;
  const std::vector<FrontEndChunk>& chunks;
  const TileKernelSelection& kernels;
  glm::vec4 clearColor;
  float clearDepth;
  bool depthGreater;  // reversed depth: the nearest sample holds the greatest depth
  // Coverage and depth per sample at these positions; with shadeSamples every
  // sample is shaded, else each pixel's visible triangles once.
  const SamplePattern& samples;
  bool shadeSamples;
  // The samples' reconstruction filter: null for the pixel box filter, else
  // tile/pixel_filter.h's weights for these samples.
  const PixelFilterWeights* pixelFilter = nullptr;
  bool coverage = false;  // fill Frame::coverage
  // The surface AOVs to fill (tile/surface_aov.h); null for none. With
  // them, every two-pass triangle goes through the visibility pass (no tile
  // sends them forward), so every pixel's nearest sample has its triangle.
  const AovFrame* aov = nullptr;
};

// times: resized to the tile count, one entry per tile.
void renderTiles(const TileFrame& frame, const Executor& executor, Frame& out,
                 std::vector<TileTimes>& times);

// An upper bound on the memory renderTiles holds at once besides the frame,
// on `threads` threads: each running task's scratch (a TileBuffers per
// sample plane, the shading planes of as many visible triangles as samples,
// and when some draw is composited in depth order the blended fragments at
// their per-sample bound) and, for a wide pixel filter (channels: 4, or 5
// with coverage; 0 for the box filter), every tile's border ring. The
// renderer charges it to its memory budget before the frame is allocated.
std::uint64_t tileMemoryBytes(const TileGrid& grid, int samples, int threads,
                              int pixelFilterChannels, const std::vector<Draw>& draws);

}  // namespace quadra
