// Texture: the derived structures, each built once on first use.
#include "texture/texture.h"

#include "texture/mip_chain.h"
#include "texture/padded_level.h"
#include "texture/ripmap.h"
#include "texture/summed_area.h"

namespace quadra {

Texture::Texture(std::shared_ptr<const Image> image, SamplerState sampler, TexelFormat storage,
                 TextureAlpha alpha)
    : image_(std::move(image)), sampler_(sampler), storage_(storage), alpha_(alpha) {}

// Out of line: MipChain is only forward-declared in the header.
Texture::~Texture() = default;

const Texture& Texture::forAlpha(const TextureAlpha& alpha) const {
  if (alpha == alpha_) return *this;
  std::call_once(opaqueOnce_, [&] { opaque_ = isOpaque(*image_); });
  if (opaque_ && alpha_ == TextureAlpha{}) return *this;
  const std::lock_guard<std::mutex> lock(variantsMutex_);
  for (const std::unique_ptr<Texture>& variant : variants_)
    if (variant->alpha() == alpha) return *variant;
  variants_.push_back(std::make_unique<Texture>(image_, sampler_, storage_, alpha));
  return *variants_.back();
}

const Image& Texture::filteredLevel0(const Executor* executor) const {
  if (!alpha_.premultiplied()) return *image_;
  std::call_once(premultipliedOnce_, [&] {
    premultiplied_ = std::make_unique<Image>(premultiplied(*image_, executor));
  });
  return *premultiplied_;
}

namespace {

std::optional<float> coverageCutoffOf(const TextureAlpha& alpha) {
  if (alpha.use != TextureAlpha::Use::Tested) return std::nullopt;
  return alpha.cutoff;
}

}  // namespace

const MipChain& Texture::mips(const Executor* executor) const {
  std::call_once(mipsOnce_, [&] {
    mips_ =
        std::make_unique<MipChain>(filteredLevel0(executor), executor, coverageCutoffOf(alpha_));
  });
  return *mips_;
}

const PaddedLevel& Texture::sampledLevel0(const Executor* executor) const {
  std::call_once(level0Once_, [&] {
    level0_ = std::make_unique<PaddedLevel>(filteredLevel0(executor), storage_, executor);
  });
  return *level0_;
}

const std::vector<PaddedLevel>& Texture::sampledMipLevels(const Executor* executor) const {
  std::call_once(mipLevelsOnce_, [&] {
    const MipChain& chain = mips(executor);
    for (int i = 1; i < chain.levelCount(); ++i)
      mipLevels_.emplace_back(chain.level(i), storage_, executor);
  });
  return mipLevels_;
}

const SummedAreaTable& Texture::summedAreaTable(const Executor* executor) const {
  std::call_once(summedAreaOnce_, [&] {
    summedArea_ =
        std::make_unique<SummedAreaTable>(sampledLevel0(executor).view(), storage_, executor);
  });
  return *summedArea_;
}

const Ripmap& Texture::ripmap(const Executor* executor) const {
  std::call_once(ripmapOnce_, [&] {
    ripmap_ = std::make_unique<Ripmap>(filteredLevel0(executor), storage_, executor,
                                       coverageCutoffOf(alpha_));
  });
  return *ripmap_;
}

}  // namespace quadra
