// Scene members: triangle counts and world-space bounds; re-storing textures.
#include "scene/scene.h"

#include <cmath>
#include <limits>

namespace quadra {

TextureAlpha textureAlphaOf(const Material& material) {
  switch (material.alphaMode) {
    case AlphaMode::Opaque:
      return {};
    case AlphaMode::Blend:
      return {TextureAlpha::Use::Blended};
    case AlphaMode::Mask: {
      // The test compares texture alpha times the factor's with the cutoff.
      // Vertex colour alpha, per pixel, cannot be folded in and is left out.
      const float factor = material.baseColorFactor.a;
      return {TextureAlpha::Use::Tested, factor > 0.0f ? material.alphaCutoff / factor : 2.0f};
    }
  }
  return {};
}

void setTextureStorage(Scene& scene, TexelFormat format) {
  for (std::shared_ptr<const Texture>& texture : scene.textures)
    texture = std::make_shared<const Texture>(texture->sharedImage(), texture->sampler(), format,
                                              texture->alpha());
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
