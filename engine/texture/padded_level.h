// PaddedLevel: one texture level as the sampling kernels read it, encoded in
// its texture's storage format (texel_format.h). Rows are width + 1 texels
// long; the extra texel repeats the row's first one. A
// bilinear lookup then always reads its left and right texels of a row as one
// contiguous pair (x, x + 1), under every wrap mode: repeat wraps x = width - 1
// onto the copy of texel 0, and clamp and mirror clamp the coordinate so the
// right texel of the last column has weight 0 (sample_lanes.h). One pair load
// per row replaces two texel loads, and its transpose is half the shuffles.
#pragma once

#include <cstdint>
#include <vector>

#include "texture/image.h"
#include "texture/texel_format.h"
#include "texture/texture_view.h"

namespace quadra {

class Executor;

struct PaddedLevel {
  std::vector<std::uint8_t> texels;  // height rows of stride texels, encoded
  int width = 0;
  int height = 0;
  int stride = 0;  // texels per row: width + 1

  // Rows are encoded in parallel on `executor` when one is given.
  PaddedLevel(const Image& image, TexelFormat format, const Executor* executor = nullptr);
  TextureLevel view() const { return {texels.data(), width, height, stride}; }
};

}  // namespace quadra
