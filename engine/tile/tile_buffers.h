// TileBuffers: one tile's depth, visibility and colour while it is being
// rendered. Pixels are stored quad by quad (2x2), quads row by row, so a group
// of 1, 2 or 4 horizontally adjacent quads — one SIMD register on any ISA — is
// a contiguous, aligned run of floats.
#pragma once

#include <cstdint>

#include "window/window_space.h"

namespace quadra {

// TileBuffers::visible of a sample no triangle of the visibility pass covers.
constexpr std::uint32_t kNoTriangle = 0xFFFFFFFFu;

struct alignas(64) TileBuffers {
  static constexpr int kPixels = kTileSize * kTileSize;

  // The planes are padded apart by a cache line: unpadded, all five sit 16 KiB
  // apart, alias in the L1 sets and the 4K store-forwarding check, and the
  // resolve copy ran 4x slower (measured: 13 ms vs 3 ms per 1080p frame).
  static constexpr int kPlaneStride = kPixels + 16;

  float depth[kPlaneStride];
  // Per sample, the tile-local index of the triangle the visibility pass kept
  // there (tile_kernel.h TileTriangle), or kNoTriangle.
  std::uint32_t visible[kPlaneStride];
  float color[4][kPlaneStride];  // premultiplied linear R, G, B, A planes
  // Per 8x8 block (row-major, kBlocksPerRow to a row), bounds on the depths
  // its samples hold: a triangle whose depth over the block lies wholly
  // behind them fails the depth test at every sample there, and the block is
  // skipped before its coverage is computed (hierarchical depth). Kept
  // conservative: exact after a triangle visits every lane group of the
  // block, widened by what a partial visit wrote otherwise.
  static constexpr int kBlocksPerRow = kTileSize / kBlockSize;
  float blockDepthMin[kBlocksPerRow * kBlocksPerRow];
  float blockDepthMax[kBlocksPerRow * kBlocksPerRow];
  int originX = 0, originY = 0;  // window position of the tile's top-left pixel
  int width = 0, height = 0;     // pixels of the tile inside the viewport

  // Index of pixel (x, y), local to the tile, in the quad layout.
  static int index(int x, int y) {
    return ((y >> 1) * (kTileSize / 2) + (x >> 1)) * 4 + (y & 1) * 2 + (x & 1);
  }
  // Index of the block holding pixel (x, y), local to the tile, in
  // blockDepthMin and blockDepthMax.
  static int blockAt(int x, int y) { return (y / kBlockSize) * kBlocksPerRow + x / kBlockSize; }
  // The inverse of index: pixel (x, y) at a given index.
  static int xAt(int index) { return ((index >> 2) % (kTileSize / 2)) * 2 + (index & 1); }
  static int yAt(int index) { return ((index >> 2) / (kTileSize / 2)) * 2 + ((index >> 1) & 1); }
};

}  // namespace quadra
