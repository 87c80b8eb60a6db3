// MipChain: the successively halved levels of a texture, built in linear float
// with exact area weights, so non-power-of-two sizes lose no row or column.
#pragma once

#include <optional>
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
  // With coverageCutoff (alpha-tested textures), each level is reduced from the
  // previous one as filtered, and then its alpha is rescaled to keep level 0's
  // coverage at that cutoff (scaleAlphaToCoverage).
  MipChain(const Image& level0, const Executor* executor,
           std::optional<float> coverageCutoff = std::nullopt);

  int levelCount() const { return int(levels_.size()) + 1; }
  const Image& level(int i) const { return i == 0 ? *level0_ : levels_[i - 1]; }

 private:
  const Image* level0_;
  std::vector<Image> levels_;
};

// One level down: the exact box-area reduction of src to (dstW, dstH).
Image downsampleBox(const Image& src, int dstW, int dstH, const Executor* executor);

// The fraction of the image's area where its bilinearly reconstructed alpha
// is at least `cutoff` (sampled n x n per texel, mip_chain.cpp): what an alpha
// test at that cutoff keeps of a surface covered by the image.
// Rows in parallel on `executor` when given, here and below.
double alphaCoverage(const Image& image, float cutoff, const Executor* executor = nullptr);

// Alpha-to-coverage preserving mip levels (Castaño, "Computing Alpha
// Mipmaps", 2010). Averaging thin opaque texels with transparent ones drops
// their alpha below the cutoff, so at a distance an alpha-tested surface
// (foliage, fences) thins out and vanishes. This scales the level's alpha by
// the s whose alphaCoverage(level, cutoff) is nearest `coverage` (level 0's),
// found by bisection (coverage grows with s), clamping alpha at 1. The level is
// premultiplied, so each texel's rgb is scaled by the same factor as its alpha,
// which keeps its straight colour. Nothing changes for a cutoff outside
// (0, 1] (all or nothing passes at any scale) or a level with no alpha above 0.
void scaleAlphaToCoverage(Image& level, float cutoff, double coverage,
                          const Executor* executor = nullptr);

}  // namespace quadra
