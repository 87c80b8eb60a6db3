// Tile stage scheduling and the per-tile loop; the per-pixel work is in the
// ISA kernels (tile_kernel_impl.h).
#include "tile/tile_stage.h"

#include <algorithm>
#include <memory>

#include "core/parallel.h"
#include "core/stage_clock.h"
#include "tile/tile_resolve.h"

namespace quadra {

namespace {

void clearTile(TileBuffers& tile, const glm::vec4& clearColor, float clearDepth) {
  std::fill(std::begin(tile.depth), std::end(tile.depth), clearDepth);
  for (int c = 0; c < 4; ++c)
    std::fill(std::begin(tile.color[c]), std::end(tile.color[c]), clearColor[c]);
}

void renderTile(int tileIndex, const TileGrid& grid, const std::vector<Draw>& draws,
                const std::vector<FrontEndChunk>& chunks, const TileKernelSelection& kernels,
                const glm::vec4& clearColor, float clearDepth, TileBuffers& tile, Frame& frame,
                TileTimes& times) {
  const double start = stageClockMs();
  tile.originX = (tileIndex % grid.tilesX) * kTileSize;
  tile.originY = (tileIndex / grid.tilesX) * kTileSize;
  tile.width = std::min(kTileSize, grid.width - tile.originX);
  tile.height = std::min(kTileSize, grid.height - tile.originY);
  clearTile(tile, clearColor, clearDepth);
  for (const FrontEndChunk& chunk : chunks) {
    const std::uint32_t begin = chunk.bins.tileStart[tileIndex];
    const std::uint32_t end = chunk.bins.tileStart[tileIndex + 1];
    for (std::uint32_t i = begin; i < end; ++i) {
      const TriangleRecord& t = chunk.setup.triangles[chunk.bins.triangleIndex[i]];
      kernels.forWidth(t.maxX - t.minX + 1)
          .rasterize(t, &chunk.setup.planes[t.firstPlane], draws[t.draw].shade, tile);
    }
  }
  const double rastered = stageClockMs();
  resolveTile(tile, frame);
  times.raster = rastered - start;
  times.resolve = stageClockMs() - rastered;
}

}  // namespace

void renderTiles(const TileGrid& grid, const std::vector<Draw>& draws,
                 const std::vector<FrontEndChunk>& chunks, const TileKernelSelection& kernels,
                 const glm::vec4& clearColor, float clearDepth, const Executor& executor,
                 Frame& frame, std::vector<TileTimes>& times) {
  times.assign(std::size_t(grid.tileCount()), TileTimes{});
  executor.parallelFor(std::size_t(grid.tileCount()), 1, [&](std::size_t begin, std::size_t end) {
    auto tile = std::make_unique<TileBuffers>();
    for (std::size_t t = begin; t < end; ++t)
      renderTile(int(t), grid, draws, chunks, kernels, clearColor, clearDepth, *tile, frame,
                 times[t]);
  });
}

}  // namespace quadra
