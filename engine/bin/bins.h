// Bin stage: a chunk of set-up triangles → per-tile lists of triangle indices,
// in submission order. Each front-end chunk bins its own triangles (no locks);
// the tile stage walks the chunks in order, which is the merge.
#pragma once

#include <cstdint>
#include <vector>

#include "setup/triangle_record.h"

namespace quadra {

struct TileGrid {
  int width = 0, height = 0;  // viewport in pixels
  int tilesX = 0, tilesY = 0;
  int tileCount() const { return tilesX * tilesY; }
  static TileGrid forViewport(int width, int height);
};

// Compressed per-tile lists: the triangles of tile t are
// triangleIndex[tileStart[t] .. tileStart[t+1]), ascending.
struct TileBins {
  std::vector<std::uint32_t> tileStart;
  std::vector<std::uint32_t> triangleIndex;
  // Working memory of binTriangles, kept for the next frame: per triangle,
  // its tile when it lies in one, else -1.
  std::vector<std::int32_t> singleTile;
};

// reach: how far (1/256 pixel) a pixel's samples lie from its centre
// (SamplePattern::reachSubpixels).
void binTriangles(const std::vector<TriangleRecord>& triangles, const TileGrid& grid, int reach,
                  TileBins& out);

}  // namespace quadra
