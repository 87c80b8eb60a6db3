// TextureView: what a sampling kernel reads for one texture, resolved once per
// draw: the levels it may touch, the wrap modes, and the filter to run.
#pragma once

#include <cstddef>
#include <cstdint>

#include "texture/sampler_state.h"

namespace quadra {

struct TextureLevel {
  const float* texels = nullptr;  // linear RGBA float, row-major
  int width = 0;
  int height = 0;
};

struct TextureView {
  static constexpr int kMaxLevels = 16;  // 32768^2 at most; textures are capped below that

  TextureLevel levels[kMaxLevels];
  int levelCount = 0;  // 1 when the filter does not use mips
  WrapMode wrapU = WrapMode::Repeat;
  WrapMode wrapV = WrapMode::Repeat;
  float border[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  Filter minFilter = Filter::Trilinear;  // used when the footprint is minified (LOD > 0)
  bool magLinear = true;                 // used when magnified (LOD <= 0)
  int maxAniso = 16;

  // For hardware gathers: every level's texels as a 32-bit float offset from
  // levels[0].texels. gatherable is false when some offset (plus the level's
  // size) does not fit in int32; kernels then use scalar loads.
  std::int32_t levelOffset[kMaxLevels] = {};
  bool gatherable = false;

  // Fills levelOffset/gatherable from levels[0..levelCount).
  void computeGatherOffsets() {
    gatherable = true;
    for (int i = 0; i < levelCount; ++i) {
      const std::ptrdiff_t offset = levels[i].texels - levels[0].texels;
      const std::ptrdiff_t end =
          offset + std::ptrdiff_t(levels[i].width) * std::ptrdiff_t(levels[i].height) * 4;
      if (offset < INT32_MIN || end > INT32_MAX || offset > INT32_MAX) gatherable = false;
      levelOffset[i] = gatherable ? std::int32_t(offset) : 0;
    }
  }
};

}  // namespace quadra
