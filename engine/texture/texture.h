// Texture: one image as the sampler reads it: its level-0 image in linear
// float and its sampler state, and everything derived from them that a filter
// may need (mip chain, padded levels in the storage format, summed-area table,
// ripmap). Each derived structure is built on first use, once, and only for
// textures whose filter reads it ("model only what a scene needs"); the scene
// holds textures, the renderer and the batch sampler ask them for levels.
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "texture/image.h"
#include "texture/sampler_state.h"
#include "texture/texel_format.h"

namespace quadra {

class Executor;
class MipChain;
struct PaddedLevel;
class SummedAreaTable;
struct Ripmap;

// How a material reads a texture's alpha.
struct TextureAlpha {
  enum class Use : std::uint8_t {
    Ignored,  // OPAQUE: straight texels
    Blended,  // BLEND: premultiplied texels
    Tested,   // MASK: premultiplied, and each mip level's alpha rescaled so that
              // the fraction of texels at or above `cutoff` stays level 0's
  };
  Use use = Use::Ignored;
  float cutoff = 0.5f;  // Tested: the texture alpha at which a texel counts as covered

  bool premultiplied() const { return use != Use::Ignored; }
  bool operator==(const TextureAlpha&) const = default;
};

// The derived structures are a thread-safe cache (std::call_once): logically
// const, so frames drawn at once from one scene share them.
class Texture {
 public:
  // storage: the format the sampling kernels read (texture/texel_format.h).
  // image: level 0 in straight (not premultiplied) linear float.
  Texture(std::shared_ptr<const Image> image, SamplerState sampler,
          TexelFormat storage = TexelFormat::Rgba32F, TextureAlpha alpha = {});
  ~Texture();

  // The straight level 0, as decoded.
  const Image& image() const { return *image_; }
  const std::shared_ptr<const Image>& sharedImage() const { return image_; }
  const SamplerState& sampler() const { return sampler_; }
  TexelFormat storage() const { return storage_; }
  const TextureAlpha& alpha() const { return alpha_; }
  // The variant of this texture for a material that reads its alpha as
  // `alpha`: this texture itself when it already is that, or when the image
  // is opaque everywhere (premultiplying changes nothing and coverage is 1 at
  // every level); otherwise one sharing the image, made once, with its own
  // levels. Thread-safe; the variant lives as long as this texture.
  const Texture& forAlpha(const TextureAlpha& alpha) const;
  // The level 0 every filter reads, in linear float: the image, or its
  // premultiplied copy (made once) when alpha().premultiplied().
  const Image& filteredLevel0(const Executor* executor = nullptr) const;
  // Thread-safe; the first call builds the chain, in parallel on `executor`
  // when one is given.
  const MipChain& mips(const Executor* executor = nullptr) const;
  // The levels as the sampling kernels read them (texture/padded_level.h),
  // each built once on first use: level 0, and levels 1.. of the chain.
  const PaddedLevel& sampledLevel0(const Executor* executor = nullptr) const;
  const std::vector<PaddedLevel>& sampledMipLevels(const Executor* executor = nullptr) const;
  // The summed-area table of the sampled level 0 (texture/summed_area.h),
  // built on first use: 32 bytes per texel, only for the `sat` filter.
  const SummedAreaTable& summedAreaTable(const Executor* executor = nullptr) const;
  // The ripmap (texture/ripmap.h), built on first use: about 4x level 0,
  // only for the `ripmap` filter.
  const Ripmap& ripmap(const Executor* executor = nullptr) const;

 private:
  std::shared_ptr<const Image> image_;
  SamplerState sampler_;
  TexelFormat storage_;
  TextureAlpha alpha_;
  mutable std::once_flag opaqueOnce_, premultipliedOnce_;
  mutable bool opaque_ = false;
  mutable std::unique_ptr<Image> premultiplied_;
  mutable std::mutex variantsMutex_;
  mutable std::vector<std::unique_ptr<Texture>> variants_;
  mutable std::once_flag mipsOnce_, level0Once_, mipLevelsOnce_, summedAreaOnce_, ripmapOnce_;
  mutable std::unique_ptr<MipChain> mips_;
  mutable std::unique_ptr<PaddedLevel> level0_;
  mutable std::vector<PaddedLevel> mipLevels_;
  mutable std::unique_ptr<SummedAreaTable> summedArea_;
  mutable std::unique_ptr<Ripmap> ripmap_;
};

}  // namespace quadra
