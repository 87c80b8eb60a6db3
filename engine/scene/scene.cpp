// Scene and Texture members: the lazily built mip chain and sampled levels,
// triangle counts and world-space bounds.
#include "scene/scene.h"

#include <cmath>
#include <limits>

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

const PaddedLevel& Texture::sampledLevel0() const {
  std::call_once(level0Once_, [&] { level0_ = std::make_unique<PaddedLevel>(*image_, storage_); });
  return *level0_;
}

const std::vector<PaddedLevel>& Texture::sampledMipLevels(const Executor* executor) const {
  std::call_once(mipLevelsOnce_, [&] {
    const MipChain& chain = mips(executor);
    for (int i = 1; i < chain.levelCount(); ++i) mipLevels_.emplace_back(chain.level(i), storage_);
  });
  return mipLevels_;
}

const SummedAreaTable& Texture::summedAreaTable(const Executor* executor) const {
  std::call_once(summedAreaOnce_, [&] {
    summedArea_ = std::make_unique<SummedAreaTable>(sampledLevel0().view(), storage_, executor);
  });
  return *summedArea_;
}

const Ripmap& Texture::ripmap(const Executor* executor) const {
  std::call_once(ripmapOnce_,
                 [&] { ripmap_ = std::make_unique<Ripmap>(*image_, storage_, executor); });
  return *ripmap_;
}

void setTextureStorage(Scene& scene, TexelFormat format) {
  for (std::shared_ptr<const Texture>& texture : scene.textures)
    texture = std::make_shared<const Texture>(texture->sharedImage(), texture->sampler(), format);
}

std::size_t Scene::triangleCount() const {
  std::size_t count = 0;
  for (const Instance& instance : instances) {
    count += meshes[std::size_t(instance.mesh)].indices.size() / 3;
  }
  return count;
}

void Scene::bounds(glm::vec3& lo, glm::vec3& hi) const {
  lo = glm::vec3(std::numeric_limits<float>::infinity());
  hi = -lo;
  for (const Instance& instance : instances) {
    for (const glm::vec3& p : meshes[std::size_t(instance.mesh)].positions) {
      const glm::vec3 world = glm::vec3(instance.world * glm::vec4(p, 1.0f));
      // Vertices with NaN or Inf are dropped by the renderer, so they bound nothing.
      if (!std::isfinite(world.x) || !std::isfinite(world.y) || !std::isfinite(world.z)) continue;
      lo = glm::min(lo, world);
      hi = glm::max(hi, world);
    }
  }
}

}  // namespace quadra
