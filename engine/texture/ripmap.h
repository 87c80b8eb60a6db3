// Ripmap: a texture's levels reduced along each axis on its own (Williams'
// mip pyramid generalized: width halved i times and height j times, every
// (i, j)), so a footprint long in u and short in v reads a level prefiltered
// to exactly that shape. It fixes the blur of trilinear for axis-aligned
// anisotropy at the cost of one bilinear lookup per level blended (4), and of
// memory: about 4x level 0 instead of 4/3.
#pragma once

#include <optional>
#include <vector>

#include "texture/image.h"
#include "texture/padded_level.h"
#include "texture/texel_format.h"
#include "texture/texture_view.h"

namespace quadra {

class Executor;

struct Ripmap {
  int countX = 0, countY = 0;        // levels along u and v, down to 1 texel (at most kMaxLevels)
  std::vector<PaddedLevel> storage;  // level (i, j) at j * countX + i, in the texel format
  std::vector<TextureLevel> levels;  // their views, in the same order

  // Levels of `level0` with exact box-area weights (mip_chain.h
  // downsampleBox, so non-power-of-two sizes lose no row or column), each
  // from its left neighbour (or, in column 0, the one above), in parallel on
  // `executor` when given; level (i, j) is max(1, w >> i) x max(1, h >> j).
  // With coverageCutoff, each level's alpha is rescaled to level 0's coverage
  // as the mip chain's (mip_chain.h scaleAlphaToCoverage), after it is reduced.
  Ripmap(const Image& level0, TexelFormat format, const Executor* executor,
         std::optional<float> coverageCutoff = std::nullopt);
};

}  // namespace quadra
