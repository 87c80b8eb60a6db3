// VertexDeformer: morph target blending and linear blend skinning, one
// vertex at a time, targets and influences in file order.
#include "scene/deformation.h"

namespace quadra {

VertexDeformer::VertexDeformer(const Mesh& mesh, std::span<const float> weights,
                               std::span<const glm::mat4> joints)
    : mesh_(mesh), weights_(weights), joints_(joints) {
  morphed_ = !weights_.empty() && !mesh_.targets.empty();
  skinned_ = !joints_.empty() && !mesh_.joints[0].empty();
}

glm::mat4 VertexDeformer::skinMatrix(std::size_t i) const {
  if (!skinned_) return glm::mat4(1.0f);
  glm::mat4 blended(0.0f);
  for (int set = 0; set < 2; ++set) {
    if (mesh_.joints[set].empty()) continue;
    const glm::u16vec4 joint = mesh_.joints[set][i];
    const glm::vec4 weight = mesh_.weights[set][i];
    for (int k = 0; k < 4; ++k) {
      // A zero weight adds nothing; skipping it also keeps an unused joint
      // slot's matrix (often joint 0's) out of the sum.
      if (weight[k] != 0.0f) blended += weight[k] * joints_[joint[k]];
    }
  }
  return blended;
}

glm::vec3 VertexDeformer::position(std::size_t i, const glm::mat4& skin) const {
  glm::vec3 p = mesh_.positions[i];
  if (morphed_) {
    for (std::size_t t = 0; t < mesh_.targets.size(); ++t) {
      const MorphTarget& target = mesh_.targets[t];
      if (weights_[t] != 0.0f && !target.positions.empty()) p += weights_[t] * target.positions[i];
    }
  }
  if (!skinned_) return p;
  return glm::vec3(skin * glm::vec4(p, 1.0f));
}

glm::vec3 VertexDeformer::normal(std::size_t i, const glm::mat4& skin) const {
  if (mesh_.normals.empty()) return glm::vec3(0.0f, 0.0f, 1.0f);
  glm::vec3 n = mesh_.normals[i];
  if (morphed_) {
    for (std::size_t t = 0; t < mesh_.targets.size(); ++t) {
      const MorphTarget& target = mesh_.targets[t];
      if (weights_[t] != 0.0f && !target.normals.empty()) n += weights_[t] * target.normals[i];
    }
  }
  if (!skinned_) return n;
  const glm::vec3 c0(skin[0]), c1(skin[1]), c2(skin[2]);
  const glm::mat3 cofactor(glm::cross(c1, c2), glm::cross(c2, c0), glm::cross(c0, c1));
  const float sign = glm::dot(c0, cofactor[0]) < 0.0f ? -1.0f : 1.0f;
  return sign * (cofactor * n);
}

glm::vec4 VertexDeformer::tangent(std::size_t i, const glm::mat4& skin) const {
  if (mesh_.tangents.empty()) return glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  glm::vec4 t = mesh_.tangents[i];
  if (morphed_) {
    for (std::size_t k = 0; k < mesh_.targets.size(); ++k) {
      const MorphTarget& target = mesh_.targets[k];
      if (weights_[k] != 0.0f && !target.tangents.empty())
        t += glm::vec4(weights_[k] * target.tangents[i], 0.0f);
    }
  }
  if (!skinned_) return t;
  return glm::vec4(glm::mat3(skin) * glm::vec3(t), t.w);
}

glm::vec2 VertexDeformer::texcoord(std::size_t i, int set) const {
  glm::vec2 uv = mesh_.texcoords[set].empty() ? glm::vec2(0.0f) : mesh_.texcoords[set][i];
  if (!morphed_ || mesh_.texcoords[set].empty()) return uv;
  for (std::size_t t = 0; t < mesh_.targets.size(); ++t) {
    const MorphTarget& target = mesh_.targets[t];
    if (weights_[t] != 0.0f && !target.texcoords[set].empty())
      uv += weights_[t] * target.texcoords[set][i];
  }
  return uv;
}

glm::vec4 VertexDeformer::color(std::size_t i) const {
  glm::vec4 c = mesh_.colors.empty() ? glm::vec4(1.0f) : mesh_.colors[i];
  if (!morphed_ || mesh_.colors.empty()) return c;
  for (std::size_t t = 0; t < mesh_.targets.size(); ++t) {
    const MorphTarget& target = mesh_.targets[t];
    if (weights_[t] != 0.0f && !target.colors.empty()) c += weights_[t] * target.colors[i];
  }
  return c;
}

}  // namespace quadra
