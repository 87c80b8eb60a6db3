// Tile stage: binned triangles → the frame. Tiles are independent tasks; each
// walks the front-end chunks in submission order and rasterizes into its own
// L2-resident buffers, then writes its pixels of the frame once.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "bin/bins.h"
#include "io/frame.h"
#include "setup/triangle_setup.h"
#include "tile/tile_kernel.h"
#include "vertex/draw.h"

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

// times: resized to the tile count, one entry per tile.
void renderTiles(const TileGrid& grid, const std::vector<Draw>& draws,
                 const std::vector<FrontEndChunk>& chunks, const TileKernelSelection& kernels,
                 const glm::vec4& clearColor, float clearDepth, const Executor& executor,
                 Frame& frame, std::vector<TileTimes>& times);

}  // namespace quadra
