// Surface AOVs of one tile: per pixel the nearest sample's triangle, met by
// the ray through the pixel centre (Möller–Trumbore in view space, double),
// its barycentrics weighting the mesh's own vertex data. Scalar code in a
// baseline translation unit: the same bits for every ISA and thread count.
#include "tile/surface_aov.h"

#include <cmath>
#include <cstddef>

namespace quadra {

namespace {

// One triangle's data, kept while consecutive pixels share it.
struct SurfaceTriangle {
  std::uint32_t id = kNoTriangle;  // tile triangle id it was made for
  const AovDraw* draw = nullptr;
  std::uint32_t source = 0;
  std::uint32_t index[3] = {0, 0, 0};
  glm::dvec3 v0{0.0}, e1{0.0}, e2{0.0};  // view space
};

void prepare(const AovFrame& aov, const std::vector<TileTriangle>& visible,
             const std::vector<std::uint32_t>& sources, std::uint32_t id, SurfaceTriangle& t) {
  t.id = id;
  t.draw = &aov.draws[visible[id].draw];
  t.source = sources[id];
  const Mesh& mesh = *t.draw->mesh;
  glm::dvec3 view[3];
  for (int i = 0; i < 3; ++i) {
    t.index[i] = mesh.indices[3 * std::size_t(t.source) + std::size_t(i)];
    view[i] =
        glm::dvec3(t.draw->modelView * glm::dvec4(glm::dvec3(mesh.positions[t.index[i]]), 1.0));
  }
  t.v0 = view[0];
  t.e1 = view[1] - view[0];
  t.e2 = view[2] - view[0];
}

// The barycentric weights of vertices 1 and 2 where the ray meets the
// triangle's plane (outside the triangle too: a pixel centre a hair beyond
// the exact edge that the snapped edges gave the triangle). A ray in the
// plane (an edge-on triangle that still won a sample) takes the centroid.
glm::dvec2 planeWeights(const SurfaceTriangle& t, const glm::dvec3& origin,
                        const glm::dvec3& direction) {
  const glm::dvec3 p = glm::cross(direction, t.e2);
  const double det = glm::dot(t.e1, p);
  if (!(std::fabs(det) > 0.0)) return glm::dvec2(1.0 / 3.0);
  const glm::dvec3 s = origin - t.v0;
  const glm::dvec3 q = glm::cross(s, t.e1);
  return glm::dvec2(glm::dot(s, p), glm::dot(direction, q)) / det;
}

template <class T>
T interpolate(const std::vector<T>& values, const SurfaceTriangle& t, const glm::dvec3& w) {
  using D = glm::vec<T::length(), double>;
  return T(w.x * D(values[t.index[0]]) + w.y * D(values[t.index[1]]) + w.z * D(values[t.index[2]]));
}

// The pixel's values, or the clear values when `t` is null.
void writePixel(const AovFrame& aov, const SurfaceTriangle* t, int px, int py, Frame& out) {
  const std::size_t pixel = std::size_t(py) * std::size_t(aov.width) + std::size_t(px);
  const AovSet set = aov.aovs;
  if (t == nullptr) {
    if (hasAov(set, Aov::Normal))
      for (int c = 0; c < 3; ++c) out.normal[3 * pixel + c] = 0.0f;
    if (hasAov(set, Aov::Position))
      for (int c = 0; c < 3; ++c) out.position[3 * pixel + c] = 0.0f;
    if (hasAov(set, Aov::Uv)) out.uv[2 * pixel] = out.uv[2 * pixel + 1] = 0.0f;
    if (hasAov(set, Aov::Motion)) out.motion[2 * pixel] = out.motion[2 * pixel + 1] = 0.0f;
    if (hasAov(set, Aov::Ids))
      out.primitiveId[pixel] = out.nodeId[pixel] = out.materialId[pixel] = kNoId;
    return;
  }
  // The ray through the pixel centre, in view space: two points of it
  // unprojected at depths that are finite for every projection quadra
  // builds (standard or reversed, finite or infinite far).
  const double ndcX = 2.0 * (px + 0.5) / aov.width - 1.0;
  const double ndcY = 1.0 - 2.0 * (py + 0.5) / aov.height;
  const glm::dvec4 a = aov.clipToView * glm::dvec4(ndcX, ndcY, 0.25, 1.0);
  const glm::dvec4 b = aov.clipToView * glm::dvec4(ndcX, ndcY, 0.75, 1.0);
  const glm::dvec3 origin = glm::dvec3(a) / a.w;
  const glm::dvec3 direction = glm::dvec3(b) / b.w - origin;
  const glm::dvec2 w12 = planeWeights(*t, origin, direction);
  const glm::dvec3 w(1.0 - w12.x - w12.y, w12.x, w12.y);
  const Mesh& mesh = *t->draw->mesh;
  const glm::dvec3 object = w.x * glm::dvec3(mesh.positions[t->index[0]]) +
                            w.y * glm::dvec3(mesh.positions[t->index[1]]) +
                            w.z * glm::dvec3(mesh.positions[t->index[2]]);
  if (hasAov(set, Aov::Normal)) {
    // The interpolated vertex normal, or without normals the face's, by the
    // winding glTF calls front.
    const glm::dvec3 objectNormal =
        mesh.normals.empty()
            ? glm::cross(glm::dvec3(mesh.positions[t->index[1]] - mesh.positions[t->index[0]]),
                         glm::dvec3(mesh.positions[t->index[2]] - mesh.positions[t->index[0]]))
            : w.x * glm::dvec3(mesh.normals[t->index[0]]) +
                  w.y * glm::dvec3(mesh.normals[t->index[1]]) +
                  w.z * glm::dvec3(mesh.normals[t->index[2]]);
    glm::dvec3 n = t->draw->normalToWorld * objectNormal;
    const double length = glm::length(n);
    n = length > 0.0 ? n / length : glm::dvec3(0.0);
    for (int c = 0; c < 3; ++c) out.normal[3 * pixel + c] = float(n[c]);
  }
  if (hasAov(set, Aov::Position)) {
    const glm::dvec3 p = glm::dvec3(t->draw->world * glm::dvec4(object, 1.0));
    for (int c = 0; c < 3; ++c) out.position[3 * pixel + c] = float(p[c]);
  }
  if (hasAov(set, Aov::Uv)) {
    const glm::vec2 uv =
        mesh.texcoords[0].empty() ? glm::vec2(0.0f) : interpolate(mesh.texcoords[0], *t, w);
    out.uv[2 * pixel] = uv.x, out.uv[2 * pixel + 1] = uv.y;
  }
  if (hasAov(set, Aov::Motion)) {
    // From where the previous pose put this point of the object to the
    // pixel centre, where this pose puts it; 0 where it was behind the
    // previous camera.
    glm::dvec2 motion(0.0);
    const glm::dvec4 clip = t->draw->previousObjectToClip * glm::dvec4(object, 1.0);
    if (aov.hasPreviousPose && clip.w > 0.0) {
      const double x = (clip.x / clip.w + 1.0) * 0.5 * aov.width;
      const double y = (1.0 - clip.y / clip.w) * 0.5 * aov.height;
      motion = glm::dvec2(px + 0.5 - x, py + 0.5 - y);
    }
    out.motion[2 * pixel] = float(motion.x), out.motion[2 * pixel + 1] = float(motion.y);
  }
  if (hasAov(set, Aov::Ids)) {
    out.primitiveId[pixel] = t->source;
    out.nodeId[pixel] = t->draw->node;
    out.materialId[pixel] = t->draw->material;
  }
}

}  // namespace

void writeSurfaceAovs(const AovFrame& aov, const TileBuffers* samplePlanes, int samples,
                      bool depthGreater, const std::vector<TileTriangle>& visible,
                      const std::vector<std::uint32_t>& sources, Frame& out) {
  const TileBuffers& tile = samplePlanes[0];
  SurfaceTriangle cached;
  for (int y = 0; y < tile.height; ++y)
    for (int x = 0; x < tile.width; ++x) {
      const int p = TileBuffers::index(x, y);
      // The nearest sample, as nearestSampleDepth keeps its depth; the
      // first of equal ones.
      int nearest = 0;
      for (int k = 1; k < samples; ++k) {
        const float depth = samplePlanes[k].depth[p], best = samplePlanes[nearest].depth[p];
        if (depthGreater ? depth > best : depth < best) nearest = k;
      }
      const std::uint32_t id = samplePlanes[nearest].visible[p];
      if (id != kNoTriangle && id != cached.id) prepare(aov, visible, sources, id, cached);
      writePixel(aov, id == kNoTriangle ? nullptr : &cached, tile.originX + x, tile.originY + y,
                 out);
    }
}

}  // namespace quadra
