// Scene members: triangle counts and world-space bounds (of the posed vertices); re-storing
// textures; the texture transform's matrix; the camera transform of a node.
#include "scene/scene.h"

#include <cmath>
#include <limits>

#include "scene/deformation.h"

namespace quadra {

glm::mat3x2 TextureTransform::matrix() const {
  // T * R * S of KHR_texture_transform, multiplied out: the first column is
  // S's x scale carried through R's first column (cos r, -sin r), the second
  // S's y scale through (sin r, cos r). Double, so each entry rounds once.
  const double c = std::cos(double(rotation)), s = std::sin(double(rotation));
  const double sx = scale.x, sy = scale.y;
  return glm::mat3x2(float(c * sx), float(-s * sx), float(s * sy), float(c * sy), offset.x,
                     offset.y);
}

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

glm::mat4 cameraWorldOf(glm::mat4 nodeWorld) {
  for (int axis = 0; axis < 3; ++axis) {
    const float length = glm::length(glm::vec3(nodeWorld[axis]));
    if (length > 0.0f && std::isfinite(length)) nodeWorld[axis] /= length;
  }
  return nodeWorld;
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
    const Mesh& mesh = meshes[std::size_t(instance.mesh)];
    const VertexDeformer deformer(mesh, instance);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const glm::vec3 p =
          deformer.active() ? deformer.position(i, deformer.skinMatrix(i)) : mesh.positions[i];
      const glm::vec3 world = glm::vec3(instance.world * glm::vec4(p, 1.0f));
      // Vertices with NaN or Inf are dropped by the renderer, so they bound nothing.
      if (!std::isfinite(world.x) || !std::isfinite(world.y) || !std::isfinite(world.z)) continue;
      lo = glm::min(lo, world);
      hi = glm::max(hi, world);
    }
  }
}

}  // namespace quadra
