// Tile → frame copy; each tile writes a disjoint part of the frame. Walks the
// tile in its storage order (quad by quad), transposes each quad's planar
// channels into RGBA pixels and streams them to two frame rows. (A plain
// per-pixel, per-channel copy was the single largest cost of a textured frame.)
#include "tile/tile_resolve.h"

#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "simd/transpose.h"

namespace quadra {

namespace {

// The pixels of a quad cut by the tile's (viewport's) right or bottom edge.
void resolvePartialQuad(const TileBuffers& tile, int x, int y, float* rgba, float* depth,
                        std::size_t row0, std::size_t row1) {
  const int quad = TileBuffers::index(x, y);
  const bool secondRow = y + 1 < tile.height, secondColumn = x + 1 < tile.width;
  const float* const in[4] = {tile.color[0] + quad, tile.color[1] + quad, tile.color[2] + quad,
                              tile.color[3] + quad};
  // Quad lanes: (0,0), (1,0), (0,1), (1,1).
  float* const out[4] = {rgba + (row0 + x) * 4, secondColumn ? rgba + (row0 + x + 1) * 4 : nullptr,
                         secondRow ? rgba + (row1 + x) * 4 : nullptr,
                         secondRow && secondColumn ? rgba + (row1 + x + 1) * 4 : nullptr};
  simd::transposeToPixelsStreaming(in, out);
  if (depth == nullptr) return;  // the frame holds no depth
  depth[row0 + x] = tile.depth[quad];
  if (secondColumn) depth[row0 + x + 1] = tile.depth[quad + 1];
  if (secondRow) {
    depth[row1 + x] = tile.depth[quad + 2];
    if (secondColumn) depth[row1 + x + 1] = tile.depth[quad + 3];
  }
}

}  // namespace

void resolveTile(const TileBuffers& tile, Frame& frame) {
  const std::size_t stride = std::size_t(frame.width);
  float* const rgba = frame.colorPixels();
  float* const depth = frame.depthPixels();
  QUADRA_CHECK(reinterpret_cast<std::uintptr_t>(rgba) % 16 == 0);  // streaming stores
  const int fullWidth = tile.width & ~1;
  for (int y = 0; y < tile.height; y += 2) {
    const std::size_t row0 = std::size_t(tile.originY + y) * stride + std::size_t(tile.originX);
    const std::size_t row1 = row0 + stride;
    int x = 0;
    if (y + 1 < tile.height) {
      // Whole quads, the common case, without a test per pixel: quad x/2 of
      // the row pair is 4 floats further in every plane.
      const int first = TileBuffers::index(0, y);
      for (; x < fullWidth; x += 2) {
        const int quad = first + 2 * x;
        simd::transposeQuadToRowsStreaming(tile.color[0] + quad, tile.color[1] + quad,
                                           tile.color[2] + quad, tile.color[3] + quad,
                                           rgba + (row0 + x) * 4, rgba + (row1 + x) * 4);
        if (depth) {
          depth[row0 + x] = tile.depth[quad], depth[row0 + x + 1] = tile.depth[quad + 1];
          depth[row1 + x] = tile.depth[quad + 2], depth[row1 + x + 1] = tile.depth[quad + 3];
        }
      }
    }
    for (; x < tile.width; x += 2) resolvePartialQuad(tile, x, y, rgba, depth, row0, row1);
  }
  simd::streamFence();
}

}  // namespace quadra
