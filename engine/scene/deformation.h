// Vertex deformation of a skinned or morphed instance (glTF 2.0 §3.7.2.2
// morph targets, §3.7.3 skins): the mesh's attributes plus its targets'
// deltas times the instance's weights, then the position (and normal)
// through the weighted sum of the instance's joint matrices. The vertex
// stage and the scene's bounds both read vertices through it, so a draw and
// the framing of its scene see the same positions. Each vertex is evaluated
// alone, in a fixed order of operations: the same bits for any thread count
// and ISA.
#pragma once

#include <cstddef>
#include <span>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace quadra {

class VertexDeformer {
 public:
  // weights: one per mesh.targets entry (or none); joints: the instance's
  // joint matrices (or none), every JOINTS_n index of the mesh below their count.
  VertexDeformer(const Mesh& mesh, std::span<const float> weights,
                 std::span<const glm::mat4> joints);
  VertexDeformer(const Mesh& mesh, const Instance& instance)
      : VertexDeformer(mesh, instance.morphWeights, instance.jointMatrices) {}

  // False when nothing deforms the mesh: its attributes are read as stored.
  bool active() const { return morphed_ || skinned_; }

  // The skin's blended matrix for vertex i: sum of weight * joint matrix
  // over its influences (the identity without a skin).
  glm::mat4 skinMatrix(std::size_t i) const;
  // Position morphed then skinned (through skinMatrix(i), passed in so a
  // vertex whose normal is read too blends it once).
  glm::vec3 position(std::size_t i, const glm::mat4& skin) const;
  // Normal morphed then skinned by the inverse transpose of skin's upper 3x3
  // (its cofactor matrix, which has the same direction for det > 0 and is
  // negated for det < 0, so it is multiplied by the determinant's sign);
  // not normalized. (0, 0, 1) when the mesh has no normals.
  glm::vec3 normal(std::size_t i, const glm::mat4& skin) const;
  // TANGENT morphed then skinned by skin's upper 3x3 (a tangent lies in the
  // surface, so it moves as positions do), w as stored; not normalized.
  // (1, 0, 0, 1) when the mesh has no tangents.
  glm::vec4 tangent(std::size_t i, const glm::mat4& skin) const;
  // TEXCOORD_set and COLOR_0 with the targets' deltas (morphs only move them).
  glm::vec2 texcoord(std::size_t i, int set) const;
  glm::vec4 color(std::size_t i) const;

 private:
  const Mesh& mesh_;
  std::span<const float> weights_;
  std::span<const glm::mat4> joints_;
  bool morphed_ = false;
  bool skinned_ = false;
};

}  // namespace quadra
