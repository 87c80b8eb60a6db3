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

void resolveTile(const TileBuffers& tile, Frame& frame) {
  const std::size_t stride = std::size_t(frame.width);
  float* const rgba = frame.rgba.data();
  float* const depth = frame.depth.empty() ? nullptr : frame.depth.data();
  QUADRA_CHECK(reinterpret_cast<std::uintptr_t>(rgba) % 16 == 0);  // streaming stores
  for (int y = 0; y < tile.height; y += 2) {
    const bool secondRow = y + 1 < tile.height;
    const std::size_t row0 = std::size_t(tile.originY + y) * stride + std::size_t(tile.originX);
    const std::size_t row1 = row0 + stride;
    for (int x = 0; x < tile.width; x += 2) {
      const int quad = TileBuffers::index(x, y);
      const bool secondColumn = x + 1 < tile.width;
      const float* const in[4] = {tile.color[0] + quad, tile.color[1] + quad, tile.color[2] + quad,
                                  tile.color[3] + quad};
      // Quad lanes: (0,0), (1,0), (0,1), (1,1).
      float* const out[4] = {rgba + (row0 + x) * 4,
                             secondColumn ? rgba + (row0 + x + 1) * 4 : nullptr,
                             secondRow ? rgba + (row1 + x) * 4 : nullptr,
                             secondRow && secondColumn ? rgba + (row1 + x + 1) * 4 : nullptr};
      simd::transposeToPixelsStreaming(in, out);
      if (depth == nullptr) continue;  // the frame holds no depth
      depth[row0 + x] = tile.depth[quad];
      if (secondColumn) depth[row0 + x + 1] = tile.depth[quad + 1];
      if (secondRow) {
        depth[row1 + x] = tile.depth[quad + 2];
        if (secondColumn) depth[row1 + x + 1] = tile.depth[quad + 3];
      }
    }
  }
  simd::streamFence();
}

}  // namespace quadra
