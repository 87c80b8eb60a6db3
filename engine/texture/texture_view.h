// TextureView: what a sampling kernel reads for one texture, resolved once per
// draw: the levels it may touch, the wrap modes, and the filter to run.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "texture/sampler_state.h"
#include "texture/texel_format.h"

namespace quadra {

class SummedAreaTable;

struct TextureLevel {
  const std::uint8_t* texels = nullptr;  // row-major, in the view's format
  int width = 0;
  int height = 0;
  int stride = 0;  // texels from one row to the next: width + 1 (texture/padded_level.h)
};

// A set of levels the kernels index per lane: the mip chain, or a ripmap's
// levels (level (i, j) at j * countX + i).
struct LevelTable {
  const TextureLevel* levels = nullptr;
  int count = 0;
};

struct TextureView {
  static constexpr int kMaxLevels = 16;  // 32768^2 at most; textures are capped below that

  TextureLevel levels[kMaxLevels];
  int levelCount = 0;                         // 1 when the filter does not use mips
  TexelFormat format = TexelFormat::Rgba32F;  // of every level
  // The levels (and border colour) hold rgb premultiplied by alpha, so a
  // lookup returns premultiplied colour (texture/texture.h TextureAlpha).
  bool premultiplied = false;
  // rgba8srgb's colour decode (srgb8ToLinearTable), held here so the kernels
  // read a pointer instead of calling out: a call spills every live vector
  // register.
  const float* srgbTable = nullptr;
  WrapMode wrapU = WrapMode::Repeat;
  WrapMode wrapV = WrapMode::Repeat;
  float border[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  Filter minFilter = Filter::Trilinear;  // used when the footprint is minified (LOD > 0)
  bool magLinear = true;                 // used when magnified (LOD <= 0)
  bool minLinear = true;                 // within a level, minified (SamplerState)
  int maxAniso = 16;
  // RGBA32F bilinear rows through hardware gathers instead of pair loads (the
  // benchmarked alternative; AVX2 and AVX-512 paths only).
  bool gatherTexels = false;
  // Filter::Ripmap's levels: width halved i times and height j times at
  // ripLevels[j * ripCountX + i].
  const TextureLevel* ripLevels = nullptr;
  int ripCountX = 0, ripCountY = 0;
  // The level-0 summed-area table, for Filter::SummedArea only.
  const SummedAreaTable* summedArea = nullptr;
  // LOD controls, as in OpenGL: λ' = clamp(λ + lodBias, minLod, maxLod),
  // magnified when λ' <= 0.
  float lodBias = 0.0f;
  float minLod = 0.0f;
  float maxLod = 1000.0f;
  // The squared footprint length (level-0 texels) at or below which those
  // controls give λ' <= 0: 2^(-2 lodBias), +inf when maxLod <= 0, -1 when
  // minLod > 0. Set with the controls (setLodControls).
  float magnifiedLengthSq = 1.0f;

  LevelTable mipTable() const { return {levels, levelCount}; }
  LevelTable ripTable() const { return {ripLevels, ripCountX * ripCountY}; }

  void setLodControls(float bias, float min, float max) {
    lodBias = bias, minLod = min, maxLod = max;
    magnifiedLengthSq = max <= 0.0f  ? std::numeric_limits<float>::infinity()
                        : min > 0.0f ? -1.0f
                                     : float(std::exp2(-2.0 * double(bias)));
  }
};

}  // namespace quadra
