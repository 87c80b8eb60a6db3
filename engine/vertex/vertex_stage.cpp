// Vertex stage: batched model-view-projection with GLM, in parallel over
// fixed-size vertex ranges (each vertex is independent, so any split gives the
// same bits). Skinned and morphed draws deform each vertex first
// (scene/deformation.h), in a separate instantiation of the loop so the
// others pay nothing for it.
#include "vertex/vertex_stage.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/large_buffer.h"
#include "core/parallel.h"
#include "scene/deformation.h"

namespace quadra {

namespace {

// floats: the position and every attribute the draw reads. A NaN or Inf in any
// of them makes every triangle using the vertex invalid (dropped and counted):
// a non-finite attribute has no meaningful interpolation, and a NaN texture
// coordinate would otherwise reach the sampler's address arithmetic.
std::uint8_t outcodeOf(const float* v, int floats, double guardX, double guardY) {
  // A float is Inf or NaN when its exponent bits are all set: adding one to
  // the exponent then carries into the top bit. One test for the vertex
  // instead of a branch per float.
  std::uint32_t carries = 0;
  for (int k = 0; k < floats; ++k) {
    std::uint32_t bits;
    std::memcpy(&bits, &v[k], sizeof bits);
    carries |= (bits & 0x7F800000u) + 0x00800000u;
  }
  if (carries & 0x80000000u) return kNotFinite;
  const double x = v[0], y = v[1], z = v[2], w = v[3];
  // (0, 0, 0, 0) is no point at all and passes every plane test below; its
  // projection would be 0/0 (found by the render fuzz target with a
  // degenerate matrix). Dropped like a non-finite vertex.
  if (x == 0.0 && y == 0.0 && z == 0.0 && w == 0.0) return kNotFinite;
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

// Clip-space position, attributes and outcode of vertices [first, last),
// deformed by `deformer` when kDeformed.
template <bool kDeformed>
void transformBlock(const DrawGeometry& g, const VertexDeformer& deformer,
                    const glm::mat4& modelViewProjection, const glm::mat3& normalMatrix,
                    const std::vector<glm::vec2>& texcoords, double guardX, double guardY,
                    std::size_t first, std::size_t last, TransformedVertices& out) {
  const Mesh& mesh = *g.mesh;
  const AttributeLayout& a = g.attributes;
  for (std::size_t i = first; i < last; ++i) {
    float* v = &out.data[i * std::size_t(out.stride)];
    glm::mat4 skin(1.0f);
    glm::vec3 position;
    if constexpr (kDeformed) {
      skin = deformer.skinMatrix(i);
      position = deformer.position(i, skin);
    } else {
      position = mesh.positions[i];
    }
    const glm::vec4 clip = modelViewProjection * glm::vec4(position, 1.0f);
    v[0] = clip.x;
    v[1] = clip.y;
    v[2] = clip.z;
    v[3] = clip.w;
    float* attr = v + 4;
    if (a.texcoord >= 0) {
      glm::vec2 uv;
      if constexpr (kDeformed) {
        uv = deformer.texcoord(i, g.texcoordSet);
      } else {
        uv = texcoords.empty() ? glm::vec2(0.0f) : texcoords[i];
      }
      if (g.transformTexcoords) uv = g.texcoordTransform * glm::vec3(uv, 1.0f);
      attr[a.texcoord] = uv.x;
      attr[a.texcoord + 1] = uv.y;
    }
    if (a.color >= 0) {
      glm::vec4 c;
      if constexpr (kDeformed) {
        c = deformer.color(i);
      } else {
        c = mesh.colors.empty() ? glm::vec4(1.0f) : mesh.colors[i];
      }
      for (int k = 0; k < 4; ++k) attr[a.color + k] = c[k];
    }
    if (a.normal >= 0) {
      glm::vec3 n(0.0f, 0.0f, 1.0f);
      if (!mesh.normals.empty()) {
        if constexpr (kDeformed) {
          n = normalMatrix * deformer.normal(i, skin);
        } else {
          n = normalMatrix * mesh.normals[i];
        }
      }
      for (int k = 0; k < 3; ++k) attr[a.normal + k] = n[k];
    }
    if (a.position >= 0) {
      const glm::vec4 p = g.modelView * glm::vec4(position, 1.0f);
      for (int k = 0; k < 3; ++k) attr[a.position + k] = p[k];
    }
    if (a.tangent >= 0) {
      glm::vec4 t;
      if constexpr (kDeformed) {
        t = deformer.tangent(i, skin);
      } else {
        t = mesh.tangents.empty() ? glm::vec4(1.0f, 0.0f, 0.0f, 1.0f) : mesh.tangents[i];
      }
      const glm::vec3 view = glm::mat3(g.modelView) * glm::vec3(t);
      for (int k = 0; k < 3; ++k) attr[a.tangent + k] = view[k];
      // B = w N x T of the moved N and T, as LIGHTING.md reads it (and the
      // Khronos Sample Viewer computes it): a mirroring matrix does not flip w.
      attr[a.tangent + 3] = t.w;
    }
    if (a.texcoord1 >= 0) {
      glm::vec2 uv;
      if constexpr (kDeformed) {
        uv = deformer.texcoord(i, 1);
      } else {
        uv = mesh.texcoords[1].empty() ? glm::vec2(0.0f) : mesh.texcoords[1][i];
      }
      attr[a.texcoord1] = uv.x;
      attr[a.texcoord1 + 1] = uv.y;
    }
    out.outcode[i] = outcodeOf(v, out.stride, guardX, guardY);
  }
}

// Window position and snapped position of vertices [first, last), without a
// branch per vertex so the compiler runs the divisions and the snap in SIMD
// lanes (each lane's operations are the scalar ones, so the same bits). A
// vertex that needs clipping or is not finite is projected as the origin
// instead: its results are never read, and nothing non-finite reaches the
// integer conversion.
void projectBlock(const Viewport& viewport, std::size_t first, std::size_t last,
                  TransformedVertices& out) {
  for (std::size_t i = first; i < last; ++i) {
    const float* v = &out.data[i * std::size_t(out.stride)];
    const float x = v[0], y = v[1], z = v[2], w = v[3];
    const bool valid = !(out.outcode[i] & (kNeedsClipping | kNotFinite));
    const ScreenVertex s = projectToWindow(valid ? x : 0.0f, valid ? y : 0.0f, valid ? z : 0.0f,
                                           valid ? w : 1.0f, viewport);
    out.screen[i] = s;
    out.subpixel[i] = snapToSubpixel(s.windowX, s.windowY);
  }
}

void transformRange(const DrawGeometry& g, const Viewport& viewport, std::size_t begin,
                    std::size_t end, TransformedVertices& out) {
  double guardX, guardY;
  guardBand(viewport, guardX, guardY);
  const glm::mat4 modelViewProjection = g.projection * g.modelView;
  // Normals go to view space with the inverse transpose (non-uniform scale).
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(g.modelView)));
  const auto& texcoords = g.mesh->texcoords[g.texcoordSet];
  const VertexDeformer deformer(*g.mesh, g.morphWeights, g.jointMatrices);
  // Blocks small enough to stay in L1 between the two passes.
  constexpr std::size_t kBlock = 256;
  for (std::size_t first = begin; first < end; first += kBlock) {
    const std::size_t last = std::min(end, first + kBlock);
    if (deformer.active()) {
      transformBlock<true>(g, deformer, modelViewProjection, normalMatrix, texcoords, guardX,
                           guardY, first, last, out);
    } else {
      transformBlock<false>(g, deformer, modelViewProjection, normalMatrix, texcoords, guardX,
                            guardY, first, last, out);
    }
    projectBlock(viewport, first, last, out);
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
