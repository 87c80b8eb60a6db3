// MipChain: the successively halved levels of a texture, built in linear float
// with exact area weights, so non-power-of-two sizes lose no row or column.
#pragma once

#include <vector>

#include "texture/image.h"

namespace quadra {

class Executor;

class MipChain {
 public:
  // Builds levels 1..n from level0 down to 1x1; level l has size
  // max(1, floor(w / 2^l)) x max(1, floor(h / 2^l)). Each destination texel is the
  // average of the source texels over exactly its footprint (fractional edge
  // texels weighted by their covered fraction). executor may be null (serial).
  MipChain(const Image& level0, const Executor* executor);

  int levelCount() const { return int(levels_.size()) + 1; }
  const Image& level(int i) const { return i == 0 ? *level0_ : levels_[i - 1]; }

 private:
  const Image* level0_;
  std::vector<Image> levels_;
};

// One level down: the exact box-area reduction of src to (dstW, dstH).
Image downsampleBox(const Image& src, int dstW, int dstH, const Executor* executor);

}  // namespace quadra
