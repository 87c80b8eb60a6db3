// Vertex stage: batched model-view-projection with GLM, in parallel over
// fixed-size vertex ranges (each vertex is independent, so any split gives the
// same bits).
#include "vertex/vertex_stage.h"

#include <algorithm>
#include <cmath>

#include "core/large_buffer.h"
#include "core/parallel.h"

namespace quadra {

namespace {

// floats: the position and every attribute the draw reads. A NaN or Inf in any
// of them makes every triangle using the vertex invalid (dropped and counted):
// a non-finite attribute has no meaningful interpolation, and a NaN texture
// coordinate would otherwise reach the sampler's address arithmetic.
std::uint8_t outcodeOf(const float* v, int floats, double guardX, double guardY) {
  for (int k = 0; k < floats; ++k)
    if (!std::isfinite(v[k])) return kNotFinite;
  const double x = v[0], y = v[1], z = v[2], w = v[3];
  std::uint8_t code = 0;
  if (z < 0.0) code |= kOutsideNear;
  if (z > w) code |= kOutsideFar;
  if (std::fabs(x) > guardX * w || std::fabs(y) > guardY * w) code |= kOutsideGuard;
  if (x < -w) code |= kOutsideLeft;
  if (x > w) code |= kOutsideRight;
  if (y < -w) code |= kOutsideBottom;
  if (y > w) code |= kOutsideTop;
  return code;
}

void transformRange(const DrawGeometry& g, const Viewport& viewport, std::size_t begin,
                    std::size_t end, TransformedVertices& out) {
  double guardX, guardY;
  guardBand(viewport, guardX, guardY);
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
    const std::uint8_t code = outcodeOf(v, out.stride, guardX, guardY);
    out.outcode[i] = code;
    if (!(code & (kNeedsClipping | kNotFinite))) {
      const ScreenVertex s = projectToWindow(v[0], v[1], v[2], v[3], viewport);
      out.screen[i] = s;
      out.subpixel[i] = snapToSubpixel(s.windowX, s.windowY);
    }
  }
}

}  // namespace

void transformVertices(const DrawGeometry& geometry, const Viewport& viewport,
                       const Executor& executor, TransformedVertices& out) {
  const std::size_t count = geometry.mesh->positions.size();
  out.stride = 4 + geometry.attributes.count;
  resizeLarge(out.data, count * std::size_t(out.stride), 0.0f, &executor);
  resizeLarge(out.screen, count, ScreenVertex{}, &executor);
  resizeLarge(out.subpixel, count, SubpixelPosition{}, &executor);
  resizeLarge(out.outcode, count, std::uint8_t(0), &executor);
  executor.parallelFor(count, 16384, [&](std::size_t begin, std::size_t end) {
    transformRange(geometry, viewport, begin, end, out);
  });
}

}  // namespace quadra
