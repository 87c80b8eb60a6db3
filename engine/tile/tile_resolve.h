// Tile resolve, the tile stage's last step: a finished tile (quad layout,
// colour planes) → its pixels of the frame (row-major interleaved RGBA, depth).
#pragma once

#include "io/frame.h"
#include "tile/tile_buffers.h"

namespace quadra {

void resolveTile(const TileBuffers& tile, Frame& frame);

}  // namespace quadra
