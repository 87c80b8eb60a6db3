// Texture: the derived structures, each built once on first use.
#include "texture/texture.h"

#include "texture/mip_chain.h"
#include "texture/padded_level.h"
#include "texture/ripmap.h"
#include "texture/summed_area.h"

namespace quadra {

Texture::Texture(std::shared_ptr<const Image> image, SamplerState sampler, TexelFormat storage)
    : image_(std::move(image)), sampler_(sampler), storage_(storage) {}

// Out of line: MipChain is only forward-declared in the header.
Texture::~Texture() = default;

const MipChain& Texture::mips(const Executor* executor) const {
  std::call_once(mipsOnce_, [&] { mips_ = std::make_unique<MipChain>(*image_, executor); });
  return *mips_;
}

const PaddedLevel& Texture::sampledLevel0(const Executor* executor) const {
  std::call_once(level0Once_,
                 [&] { level0_ = std::make_unique<PaddedLevel>(*image_, storage_, executor); });
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
  std::call_once(ripmapOnce_,
                 [&] { ripmap_ = std::make_unique<Ripmap>(*image_, storage_, executor); });
  return *ripmap_;
}

}  // namespace quadra
