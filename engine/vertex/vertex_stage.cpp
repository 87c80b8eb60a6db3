// Vertex stage: batched model-view-projection with GLM, in parallel over
// fixed-size vertex ranges (each vertex is independent, so any split gives the
// same bits).
#include "vertex/vertex_stage.h"

#include "core/parallel.h"

namespace quadra {

namespace {

void transformRange(const DrawGeometry& g, std::size_t begin, std::size_t end,
                    TransformedVertices& out) {
  const Mesh& mesh = *g.mesh;
  const glm::mat4 modelViewProjection = g.projection * g.modelView;
  // Normals go to view space with the inverse transpose (non-uniform scale).
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(g.modelView)));
  const AttributeLayout& a = g.attributes;
  const auto& texcoords = mesh.texcoords[g.texcoordSet];
  for (std::size_t i = begin; i < end; ++i) {
    float* v = &out.data[i * std::size_t(out.stride)];
    const glm::vec4 clip = modelViewProjection * glm::vec4(mesh.positions[i], 1.0f);
    v[0] = clip.x;
    v[1] = clip.y;
    v[2] = clip.z;
    v[3] = clip.w;
    float* attr = v + 4;
    if (a.texcoord >= 0) {
      const glm::vec2 uv = texcoords.empty() ? glm::vec2(0.0f) : texcoords[i];
      attr[a.texcoord] = uv.x;
      attr[a.texcoord + 1] = uv.y;
    }
    if (a.color >= 0) {
      const glm::vec4 c = mesh.colors.empty() ? glm::vec4(1.0f) : mesh.colors[i];
      for (int k = 0; k < 4; ++k) attr[a.color + k] = c[k];
    }
    if (a.normal >= 0) {
      const glm::vec3 n =
          mesh.normals.empty() ? glm::vec3(0.0f, 0.0f, 1.0f) : normalMatrix * mesh.normals[i];
      for (int k = 0; k < 3; ++k) attr[a.normal + k] = n[k];
    }
  }
}

}  // namespace

void transformVertices(const DrawGeometry& geometry, const Executor& executor,
                       TransformedVertices& out) {
  const std::size_t count = geometry.mesh->positions.size();
  out.stride = 4 + geometry.attributes.count;
  out.data.resize(count * std::size_t(out.stride));
  executor.parallelFor(count, 16384, [&](std::size_t begin, std::size_t end) {
    transformRange(geometry, begin, end, out);
  });
}

}  // namespace quadra
