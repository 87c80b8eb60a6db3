// Binning (bin/bins.h): every tile holding a pixel centre a triangle covers
// lists it, in submission order, and edge-tested binning leaves the empty
// tiles of a thin diagonal triangle's bounding box out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "bin/bins.h"
#include "window/window_space.h"

namespace quadra {
namespace {

// The tiles holding a covered pixel centre, by brute force over the box.
std::set<int> coveredTiles(const TriangleRecord& t, const TileGrid& grid) {
  std::set<int> tiles;
  for (int y = t.minY; y <= t.maxY; ++y)
    for (int x = t.minX; x <= t.maxX; ++x)
      if (t.edges[0].at(x, y) > 0 && t.edges[1].at(x, y) > 0 && t.edges[2].at(x, y) > 0)
        tiles.insert((y / kTileSize) * grid.tilesX + x / kTileSize);
  return tiles;
}

std::vector<std::set<int>> listedTiles(const TileBins& bins, std::size_t triangles) {
  std::vector<std::set<int>> listed(triangles);
  for (std::size_t tile = 0; tile + 1 < bins.tileStart.size(); ++tile) {
    std::uint32_t previous = 0;
    for (std::uint32_t i = bins.tileStart[tile]; i < bins.tileStart[tile + 1]; ++i) {
      const std::uint32_t triangle = bins.triangleIndex[i];
      if (i > bins.tileStart[tile]) {
        EXPECT_GT(triangle, previous) << "tile " << tile;
      }
      previous = triangle;
      listed[triangle].insert(int(tile));
    }
  }
  return listed;
}

// Random half-plane triples (any convex region, not only snapped triangles'):
// the bins must hold every tile with a covered centre.
TEST(Bins, EveryTileWithACoveredPixelListsTheTriangle) {
  const TileGrid grid = TileGrid::forViewport(300, 200);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> step(-(1 << 12), 1 << 12), px(0, 299), py(0, 199);
  std::vector<TriangleRecord> triangles(400);
  for (TriangleRecord& t : triangles) {
    const int x0 = px(rng), x1 = px(rng), y0 = py(rng), y1 = py(rng);
    t.minX = std::int16_t(std::min(x0, x1)), t.maxX = std::int16_t(std::max(x0, x1));
    t.minY = std::int16_t(std::min(y0, y1)), t.maxY = std::int16_t(std::max(y0, y1));
    const int cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;  // keep the box's centre inside
    for (EdgeFunction& e : t.edges) {
      e.a = step(rng), e.b = step(rng);
      e.c = -std::int64_t(e.a) * cx - std::int64_t(e.b) * cy + (std::int64_t(1) << 14);
    }
  }
  TileBins bins;
  binTriangles(triangles, grid, 0, bins);
  const std::vector<std::set<int>> listed = listedTiles(bins, triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (const int tile : coveredTiles(triangles[i], grid))
      EXPECT_EQ(listed[i].count(tile), 1u) << "triangle " << i << " tile " << tile;
}

TEST(Bins, AThinDiagonalTriangleSkipsTheEmptyTilesOfItsBox) {
  const TileGrid grid = TileGrid::forViewport(640, 640);  // 10 x 10 tiles
  // Edges of the sliver between the diagonals y = x and y = x + 3 (pixel
  // centres, x <= y <= x + 3), closed off at x <= 639: inside is E > 0.
  TriangleRecord t;
  t.minX = 0, t.minY = 0, t.maxX = 639, t.maxY = 639;
  t.edges[0] = {-1, 1, 1};    // y - x + 1 > 0
  t.edges[1] = {1, -1, 4};    // x - y + 4 > 0
  t.edges[2] = {-1, 0, 640};  // 640 - x > 0
  TileBins bins;
  binTriangles({t}, grid, 0, bins);
  const std::set<int> listed = listedTiles(bins, 1)[0];
  const std::set<int> covered = coveredTiles(t, grid);
  for (const int tile : covered) EXPECT_EQ(listed.count(tile), 1u) << tile;
  EXPECT_EQ(covered.size(), 19u);  // the diagonal's 10 tiles and the 9 beside it
  EXPECT_LE(listed.size(), 28u);   // of the box's 100
}

}  // namespace
}  // namespace quadra
