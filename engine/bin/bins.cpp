// Binning by bounding box and edges in two passes (count, then fill), so each
// chunk's bins are two flat arrays rather than a vector per tile.
#include "bin/bins.h"

#include <algorithm>
#include <cstdlib>

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

namespace {

// Whether some sample of the rectangle [x0, x1] x [y0, y1] (inclusive pixel
// indices; samples within `reach` 1/256 pixel of their centres) may lie
// inside all three edges: each edge's largest value over the rectangle, at
// the corner its steps point to, widened by what a sample's offset can add,
// must be positive. Exact (64-bit edge functions; a and b are multiples of
// 256), and conservative: a rectangle that passes may still hold no covered
// sample, one that fails holds none.
bool mayCover(const TriangleRecord& t, int x0, int y0, int x1, int y1, int reach) {
  for (const EdgeFunction& e : t.edges) {
    const int x = e.a > 0 ? x1 : x0, y = e.b > 0 ? y1 : y0;
    const std::int64_t widen =
        (std::abs(std::int64_t(e.a)) + std::abs(std::int64_t(e.b))) / kSubpixelScale * reach;
    if (e.at(x, y) + widen <= 0) return false;
  }
  return true;
}

}  // namespace

// A triangle goes to the tiles its bounding box overlaps, except, when the
// box spans several tiles both ways, those its edges leave empty: a thin
// diagonal triangle is listed along its length, not in every tile of its box.
// Most triangles of a dense mesh lie in one tile: the count pass notes it
// (out.singleTile), and the fill pass lists them without another walk.
void binTriangles(const std::vector<TriangleRecord>& triangles, const TileGrid& grid, int reach,
                  TileBins& out) {
  out.tileStart.assign(std::size_t(grid.tileCount()) + 1, 0);
  out.singleTile.resize(triangles.size());
  // Boxes lie in the viewport: non-negative, so tiles are unsigned quotients.
  const auto tileOf = [](int pixel) { return int(unsigned(pixel) / kTileSize); };
  auto forEachTile = [&](const TriangleRecord& t, auto&& visit) {
    const int tx0 = tileOf(t.minX), tx1 = tileOf(t.maxX);
    const int ty0 = tileOf(t.minY), ty1 = tileOf(t.maxY);
    const bool edgeTested = tx1 > tx0 && ty1 > ty0;
    for (int ty = ty0; ty <= ty1; ++ty) {
      const int y0 = std::max<int>(ty * kTileSize, t.minY);
      const int y1 = std::min<int>(ty * kTileSize + kTileSize - 1, t.maxY);
      for (int tx = tx0; tx <= tx1; ++tx) {
        const int x0 = std::max<int>(tx * kTileSize, t.minX);
        const int x1 = std::min<int>(tx * kTileSize + kTileSize - 1, t.maxX);
        if (edgeTested && !mayCover(t, x0, y0, x1, y1, reach)) continue;
        visit(ty * grid.tilesX + tx);
      }
    }
  };
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const TriangleRecord& t = triangles[i];
    const int tx = tileOf(t.minX), ty = tileOf(t.minY);
    if (tx == tileOf(t.maxX) && ty == tileOf(t.maxY)) {
      const int tile = ty * grid.tilesX + tx;
      out.singleTile[i] = tile;
      ++out.tileStart[tile + 1];
      continue;
    }
    out.singleTile[i] = -1;
    forEachTile(t, [&](int tile) { ++out.tileStart[tile + 1]; });
  }
  for (int tile = 0; tile < grid.tileCount(); ++tile)
    out.tileStart[tile + 1] += out.tileStart[tile];
  out.triangleIndex.resize(out.tileStart.back());
  std::vector<std::uint32_t> cursor(out.tileStart.begin(), out.tileStart.end() - 1);
  for (std::uint32_t i = 0; i < triangles.size(); ++i) {
    if (const int tile = out.singleTile[i]; tile >= 0) {
      out.triangleIndex[cursor[tile]++] = i;
      continue;
    }
    forEachTile(triangles[i], [&](int tile) { out.triangleIndex[cursor[tile]++] = i; });
  }
}

}  // namespace quadra
