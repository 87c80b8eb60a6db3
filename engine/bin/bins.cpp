// Binning by bounding box in two passes (count, then fill), so each chunk's
// bins are two flat arrays rather than a vector per tile.
#include "bin/bins.h"

#include "window/window_space.h"

namespace quadra {

TileGrid TileGrid::forViewport(int width, int height) {
  TileGrid g;
  g.width = width;
  g.height = height;
  g.tilesX = (width + kTileSize - 1) / kTileSize;
  g.tilesY = (height + kTileSize - 1) / kTileSize;
  return g;
}

void binTriangles(const std::vector<TriangleRecord>& triangles, const TileGrid& grid,
                  TileBins& out) {
  out.tileStart.assign(std::size_t(grid.tileCount()) + 1, 0);
  auto forEachTile = [&](const TriangleRecord& t, auto&& visit) {
    for (int ty = t.minY / kTileSize; ty <= t.maxY / kTileSize; ++ty)
      for (int tx = t.minX / kTileSize; tx <= t.maxX / kTileSize; ++tx)
        visit(ty * grid.tilesX + tx);
  };
  for (const TriangleRecord& t : triangles)
    forEachTile(t, [&](int tile) { ++out.tileStart[tile + 1]; });
  for (int tile = 0; tile < grid.tileCount(); ++tile)
    out.tileStart[tile + 1] += out.tileStart[tile];
  out.triangleIndex.resize(out.tileStart.back());
  std::vector<std::uint32_t> cursor(out.tileStart.begin(), out.tileStart.end() - 1);
  for (std::uint32_t i = 0; i < triangles.size(); ++i)
    forEachTile(triangles[i], [&](int tile) { out.triangleIndex[cursor[tile]++] = i; });
}

}  // namespace quadra
