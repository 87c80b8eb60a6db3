// Tile stage: binned triangles → the frame. Tiles are independent tasks; each
// walks the front-end chunks in submission order and rasterizes into its own
// L2-resident buffers, then writes its pixels of the frame once.
#pragma once

#include <cstdint>
#include <memory>
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
  // A lit frame's environment behind the uncovered pixels; null: the clear
  // colour stays.
  const BackgroundView* background = nullptr;
};

// The tile stage's working memory, kept by its owner (a Renderer) from frame
// to frame: a scratch per worker thread (tile planes, lists, fragment
// store). Made every frame, its pages were faulted in again and, freed,
// stayed with the allocator or were unmapped with TLB shootdowns across the
// threads; resident memory then moved from frame to frame with the
// allocator's state. Dropped when a frame differs from the one before in
// what sizes it (tileMemoryBytes' inputs), so what is kept stays within
// each frame's charge. One frame at a time.
class TileWorkspace {
 public:
  TileWorkspace();
  ~TileWorkspace();
  TileWorkspace(const TileWorkspace&) = delete;
  TileWorkspace& operator=(const TileWorkspace&) = delete;

  struct Kept;  // tile_stage.cpp
  std::unique_ptr<Kept> kept;
};

// times: resized to the tile count, one entry per tile.
void renderTiles(const TileFrame& frame, const Executor& executor, TileWorkspace& workspace,
                 Frame& out, std::vector<TileTimes>& times);

// The most triangles a tile's visibility pass keeps as visible at once at
// `samples` samples: one a sample slot and a plane more. At that, the ones no
// sample holds any more are dropped (at most one a slot is still held, so a
// drop frees a plane's worth at least): a scene drawn back to front costs at
// most `samples` id reads a triangle for it, and a tile's lists stay bounded
// by its samples whatever the scene.
constexpr int maxVisibleTriangles(int samples) {
  return (samples + 1) * TileBuffers::kPixels;
}

// An upper bound on the memory renderTiles holds besides the frame (and a
// TileWorkspace keeps between frames of the same settings), on `threads`
// threads: each worker's scratch (a TileBuffers per
// sample plane; the lists and shading planes of at most maxVisibleTriangles
// triangles, with AOVs their AOV records too (and the shading AOVs' terms); the shading jobs, at
// most one a sample; when some draw is composited in depth order the blended
// fragments at their per-sample bound; a wide pixel filter's tile planes)
// and, for a wide pixel filter (channels: 4, or 5 with coverage; 0 for the
// box filter), every tile's border ring. The renderer charges it to its
// memory budget before the frame is allocated.
std::uint64_t tileMemoryBytes(const TileGrid& grid, int samples, int threads,
                              int pixelFilterChannels, AovSet aovs, const std::vector<Draw>& draws);

}  // namespace quadra
