// Surface AOVs of one tile: per pixel the nearest sample's triangle, its
// barycentrics at the pixel centre from the triangle's inverted clip-space
// matrix (surface_aov.h), weighting the vertex data prepared once per
// triangle and tile. Scalar double code in a baseline translation unit: the
// same bits for every ISA and thread count.
#include "tile/surface_aov.h"

#include <cmath>
#include <cstddef>

#include "scene/deformation.h"

namespace quadra {

namespace {

void prepare(const AovFrame& aov, const TileTriangle& visible, std::uint32_t source,
             AovTriangle& t) {
  const AovDraw& draw = aov.draws[visible.draw];
  const Mesh& mesh = *draw.mesh;
  const VertexDeformer deformer(mesh, draw.morphWeights, draw.jointMatrices);
  // The previous pose's deformation, where it differs from this one's.
  const bool deformedBefore = aov.hasPreviousPose && hasAov(aov.aovs, Aov::Motion) &&
                              (draw.previousMorphWeights.data() != draw.morphWeights.data() ||
                               draw.previousJointMatrices.data() != draw.jointMatrices.data());
  const VertexDeformer before(mesh, draw.previousMorphWeights, draw.previousJointMatrices);
  std::uint32_t index[3];
  glm::dvec3 object[3];
  glm::mat4 skin[3];
  glm::dmat3 corners;  // columns: the corners' clip-space x, y, w
  for (int i = 0; i < 3; ++i) {
    index[i] = mesh.indices[3 * std::size_t(source) + std::size_t(i)];
    if (deformer.active()) {
      skin[i] = deformer.skinMatrix(index[i]);
      object[i] = glm::dvec3(deformer.position(index[i], skin[i]));
    } else {
      object[i] = glm::dvec3(mesh.positions[index[i]]);
    }
    const glm::dvec4 clip = draw.objectToClip * glm::dvec4(object[i], 1.0);
    corners[i] = glm::dvec3(clip.x, clip.y, clip.w);
    t.world[i] = glm::dvec3(draw.world * glm::dvec4(object[i], 1.0));
    if (deformer.active())
      t.uv[i] = glm::dvec2(deformer.texcoord(index[i], 0));
    else
      t.uv[i] =
          mesh.texcoords[0].empty() ? glm::dvec2(0.0) : glm::dvec2(mesh.texcoords[0][index[i]]);
    const glm::dvec3 previousObject =
        deformedBefore ? glm::dvec3(before.position(index[i], before.skinMatrix(index[i])))
                       : object[i];
    t.previousClip[i] = draw.previousObjectToClip * glm::dvec4(previousObject, 1.0);
  }
  // The vertex normals, or without them the face's, by the winding glTF
  // calls front (the inverse transpose keeps that side under a mirroring
  // world matrix); normalized per pixel.
  const glm::dvec3 face = glm::cross(object[1] - object[0], object[2] - object[0]);
  for (int i = 0; i < 3; ++i) {
    glm::dvec3 normal = face;
    if (!mesh.normals.empty())
      normal = deformer.active() ? glm::dvec3(deformer.normal(index[i], skin[i]))
                                 : glm::dvec3(mesh.normals[index[i]]);
    t.normal[i] = draw.normalToWorld * normal;
  }
  // A triangle whose plane holds the eye (edge-on, yet it won a sample
  // after snapping) has no inverse: it takes its centroid.
  const double det = glm::determinant(corners);
  t.flat = !(std::fabs(det) > 0.0);
  if (!t.flat) t.clipToWeights = glm::inverse(corners);
  t.primitive = source;
  t.node = draw.node;
  t.material = draw.material;
  t.ready = true;
}

void writeClear(AovSet set, std::size_t pixel, Frame& out) {
  if (hasAov(set, Aov::Normal))
    for (std::size_t c = 0; c < 3; ++c) out.normal[3 * pixel + c] = 0.0f;
  if (hasAov(set, Aov::Position))
    for (std::size_t c = 0; c < 3; ++c) out.position[3 * pixel + c] = 0.0f;
  if (hasAov(set, Aov::Uv)) out.uv[2 * pixel] = out.uv[2 * pixel + 1] = 0.0f;
  if (hasAov(set, Aov::Motion)) out.motion[2 * pixel] = out.motion[2 * pixel + 1] = 0.0f;
  if (hasAov(set, Aov::Ids))
    out.primitiveId[pixel] = out.nodeId[pixel] = out.materialId[pixel] = kNoId;
}

template <class V>
V weigh(const V (&v)[3], const glm::dvec3& w) {
  return w.x * v[0] + w.y * v[1] + w.z * v[2];
}

void writePixel(const AovFrame& aov, const AovTriangle& t, int px, int py, Frame& out) {
  const std::size_t pixel = std::size_t(py) * std::size_t(aov.width) + std::size_t(px);
  const AovSet set = aov.aovs;
  // The weights of the point of the triangle's plane that the pixel centre
  // sees: M w = s (x, y, 1) for the NDC centre (x, y), normalized to sum 1.
  const double ndcX = 2.0 * (px + 0.5) / aov.width - 1.0;
  const double ndcY = 1.0 - 2.0 * (py + 0.5) / aov.height;
  glm::dvec3 w(1.0 / 3.0);
  if (!t.flat) {
    const glm::dvec3 q = t.clipToWeights * glm::dvec3(ndcX, ndcY, 1.0);
    const double sum = q.x + q.y + q.z;
    if (std::fabs(sum) > 0.0) w = q * (1.0 / sum);  // one division, not three
  }
  if (hasAov(set, Aov::Normal)) {
    glm::dvec3 n = weigh(t.normal, w);
    const double length = glm::length(n);
    n = length > 0.0 ? n * (1.0 / length) : glm::dvec3(0.0);
    for (int c = 0; c < 3; ++c) out.normal[3 * pixel + std::size_t(c)] = float(n[c]);
  }
  if (hasAov(set, Aov::Position)) {
    const glm::dvec3 p = weigh(t.world, w);
    for (int c = 0; c < 3; ++c) out.position[3 * pixel + std::size_t(c)] = float(p[c]);
  }
  if (hasAov(set, Aov::Uv)) {
    const glm::dvec2 uv = weigh(t.uv, w);
    out.uv[2 * pixel] = float(uv.x), out.uv[2 * pixel + 1] = float(uv.y);
  }
  if (hasAov(set, Aov::Motion)) {
    // From where the previous pose put this point of the object to the
    // pixel centre, where this pose puts it; 0 where it was behind the
    // previous camera.
    glm::dvec2 motion(0.0);
    const glm::dvec4 clip = weigh(t.previousClip, w);
    if (aov.hasPreviousPose && clip.w > 0.0) {
      const double invW = 1.0 / clip.w;
      const double x = (clip.x * invW + 1.0) * 0.5 * aov.width;
      const double y = (1.0 - clip.y * invW) * 0.5 * aov.height;
      motion = glm::dvec2(px + 0.5 - x, py + 0.5 - y);
    }
    out.motion[2 * pixel] = float(motion.x), out.motion[2 * pixel + 1] = float(motion.y);
  }
  if (hasAov(set, Aov::Ids)) {
    out.primitiveId[pixel] = t.primitive;
    out.nodeId[pixel] = t.node;
    out.materialId[pixel] = t.material;
  }
}

}  // namespace

std::uint32_t nearestSampleTriangle(const TileBuffers* samplePlanes, int samples, bool depthGreater,
                                    int p) {
  // As nearestSampleDepth keeps its depth: the first of equal ones.
  int nearest = 0;
  for (int k = 1; k < samples; ++k) {
    const float depth = samplePlanes[k].depth[p], best = samplePlanes[nearest].depth[p];
    if (depthGreater ? depth > best : depth < best) nearest = k;
  }
  return samplePlanes[nearest].visible[p];
}

void writeSurfaceAovs(const AovFrame& aov, const TileBuffers* samplePlanes, int samples,
                      bool depthGreater, const std::vector<TileTriangle>& visible,
                      const std::vector<std::uint32_t>& sources,
                      std::vector<AovTriangle>& triangles, Frame& out) {
  const TileBuffers& tile = samplePlanes[0];
  triangles.resize(visible.size());
  for (AovTriangle& t : triangles) t.ready = false;
  for (int y = 0; y < tile.height; ++y)
    for (int x = 0; x < tile.width; ++x) {
      const std::uint32_t id =
          nearestSampleTriangle(samplePlanes, samples, depthGreater, TileBuffers::index(x, y));
      const int px = tile.originX + x, py = tile.originY + y;
      if (id == kNoTriangle) {
        writeClear(aov.aovs, std::size_t(py) * std::size_t(aov.width) + std::size_t(px), out);
        continue;
      }
      AovTriangle& t = triangles[id];
      if (!t.ready) prepare(aov, visible[id], sources[id], t);
      writePixel(aov, t, px, py, out);
    }
}

}  // namespace quadra
