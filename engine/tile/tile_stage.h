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

// One front-end chunk: triangles in submission order and their bins.
struct FrontEndChunk {
  SetupOutput setup;
  TileBins bins;
};

void renderTiles(const TileGrid& grid, const std::vector<Draw>& draws,
                 const std::vector<FrontEndChunk>& chunks, const TileKernelSelection& kernels,
                 const glm::vec4& clearColor, float clearDepth, const Executor& executor,
                 Frame& frame);

}  // namespace quadra
