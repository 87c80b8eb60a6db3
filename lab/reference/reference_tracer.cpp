// The double-precision reference ray caster (self-tests in
// tests/test_reference_tracer.cpp).
#include "lab/reference/reference_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "core/error.h"
#include "lab/reference/reference_raster.h"

namespace quadra::ref {

std::int64_t wrapTexel(std::int64_t i, std::int64_t n, WrapMode mode) {
  switch (mode) {
    case WrapMode::Repeat:
      return ((i % n) + n) % n;
    case WrapMode::MirroredRepeat: {
      const std::int64_t k = ((i % (2 * n)) + 2 * n) % (2 * n);
      return k < n ? k : 2 * n - 1 - k;
    }
    case WrapMode::ClampToEdge:
      return std::clamp<std::int64_t>(i, 0, n - 1);
    case WrapMode::ClampToBorder:
      return (i < 0 || i >= n) ? -1 : i;
  }
  return 0;
}

namespace {

glm::dvec4 fetch(const Image& image, const SamplerState& sampler, std::int64_t x, std::int64_t y) {
  const std::int64_t wx = wrapTexel(x, image.width, sampler.wrapU);
  const std::int64_t wy = wrapTexel(y, image.height, sampler.wrapV);
  if (wx < 0 || wy < 0) {
    const float* b = sampler.borderColor;
    return {b[0], b[1], b[2], b[3]};
  }
  const float* t = image.texel(int(wx), int(wy));
  return {t[0], t[1], t[2], t[3]};
}

}  // namespace

glm::dvec4 sampleBilinear(const Image& image, const SamplerState& sampler, const glm::dvec2& uv) {
  const double x = uv.x * image.width - 0.5, y = uv.y * image.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  const auto ix = std::int64_t(x0), iy = std::int64_t(y0);
  const glm::dvec4 top =
      (1 - fx) * fetch(image, sampler, ix, iy) + fx * fetch(image, sampler, ix + 1, iy);
  const glm::dvec4 bottom =
      (1 - fx) * fetch(image, sampler, ix, iy + 1) + fx * fetch(image, sampler, ix + 1, iy + 1);
  return (1 - fy) * top + fy * bottom;
}

ReferenceTracer::ReferenceTracer(const Scene& scene, const Camera& camera, int width, int height)
    : scene_(scene),
      camera_(camera),
      width_(width),
      height_(height),
      aspect_(double(width) / double(height)) {
  const glm::dmat4 view = referenceViewMatrix(camera);
  for (const Instance& instance : scene.instances) {
    PreparedInstance prepared;
    prepared.mesh = &scene.meshes.at(instance.mesh);
    const int material = prepared.mesh->material;
    prepared.material = material >= 0 ? &scene.materials.at(material) : nullptr;
    prepared.cullBack = prepared.material == nullptr || !prepared.material->doubleSided;
    prepared.mirrored = glm::determinant(glm::dmat4(instance.world)) < 0.0;
    const glm::dmat4 modelView = view * glm::dmat4(instance.world);
    prepared.boundsLo = glm::dvec3(std::numeric_limits<double>::infinity());
    prepared.boundsHi = -prepared.boundsLo;
    for (const glm::vec3& p : prepared.mesh->positions) {
      const glm::dvec3 v(modelView * glm::dvec4(glm::dvec3(p), 1.0));
      prepared.viewPositions.push_back(v);
      prepared.boundsLo = glm::min(prepared.boundsLo, v);
      prepared.boundsHi = glm::max(prepared.boundsHi, v);
    }
    instances_.push_back(std::move(prepared));
  }
}

Ray ReferenceTracer::primaryRay(const glm::dvec2& window) const {
  const double xNdc = 2.0 * window.x / width_ - 1.0;
  const double yNdc = 1.0 - 2.0 * window.y / height_;
  if (camera_.type == Camera::Type::Orthographic) {
    const double ymag = camera_.ymag;
    return {{xNdc * ymag * aspect_, yNdc * ymag, 0.0}, {0.0, 0.0, -1.0}};
  }
  const double f = 1.0 / std::tan(double(camera_.yfov) / 2.0);
  return {{0.0, 0.0, 0.0}, {xNdc * aspect_ / f, yNdc / f, -1.0}};
}

bool ReferenceTracer::rayMayHit(const PreparedInstance& instance, const Ray& ray) const {
  double tLo = -std::numeric_limits<double>::infinity();
  double tHi = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const double o = ray.origin[axis], d = ray.direction[axis];
    const double lo = instance.boundsLo[axis], hi = instance.boundsHi[axis];
    if (d == 0.0) {
      if (o < lo || o > hi) return false;
      continue;
    }
    const double a = (lo - o) / d, b = (hi - o) / d;
    tLo = std::max(tLo, std::min(a, b));
    tHi = std::min(tHi, std::max(a, b));
  }
  return tLo <= tHi && tHi >= 0.0;
}

glm::dvec3 ReferenceTracer::planeWeights(const PreparedInstance& instance, std::size_t triangle,
                                         const Ray& ray) const {
  // Each vertex's weight is the signed volume the ray spans with the opposite
  // edge (both relative to the ray origin): computed from that edge's two
  // vertices alone, so a vertex 1e30 away spoils no other weight
  // (Moller-Trumbore's 1 - b1 - b2 would lose a weight of 1e-30 entirely),
  // and the two triangles of a shared edge get exactly opposite values.
  const std::uint32_t* corner = &instance.mesh->indices[triangle * 3];
  const glm::dvec3 a = instance.viewPositions[corner[0]] - ray.origin,
                   b = instance.viewPositions[corner[1]] - ray.origin,
                   c = instance.viewPositions[corner[2]] - ray.origin;
  return {glm::dot(ray.direction, glm::cross(b, c)), glm::dot(ray.direction, glm::cross(c, a)),
          glm::dot(ray.direction, glm::cross(a, b))};
}

glm::dvec2 ReferenceTracer::planeTexCoord(const TracerHit& hit, const Ray& ray, int set) const {
  const glm::dvec3 w =
      planeWeights(instances_[std::size_t(hit.instance)], std::size_t(hit.triangle), ray);
  TracerHit onPlane = hit;
  onPlane.bary = w / (w.x + w.y + w.z);
  return texCoord(onPlane, set);
}

void ReferenceTracer::allHits(const Ray& ray, std::vector<TracerHit>& out) const {
  out.clear();
  const double znear = camera_.znear;
  const double zfar = camera_.type == Camera::Type::Orthographic
                          ? (camera_.zfar > camera_.znear ? camera_.zfar : HUGE_VAL)
                          : (camera_.zfar != 0.0f ? camera_.zfar : HUGE_VAL);
  for (std::size_t index = 0; index < instances_.size(); ++index) {
    const PreparedInstance& instance = instances_[index];
    if (!rayMayHit(instance, ray)) continue;
    const std::vector<std::uint32_t>& indices = instance.mesh->indices;
    for (std::size_t tri = 0; tri * 3 < indices.size(); ++tri) {
      const glm::dvec3 w = planeWeights(instance, tri, ray);
      // Edges are inclusive: a ray through a shared edge hits both
      // neighbours, never neither.
      const bool inside =
          (w.x >= 0.0 && w.y >= 0.0 && w.z >= 0.0) || (w.x <= 0.0 && w.y <= 0.0 && w.z <= 0.0);
      const double sum = w.x + w.y + w.z;   // dot(direction, e1 x e2)
      if (!inside || sum == 0.0) continue;  // missed, or edge-on: zero projected area
      // sum < 0: the ray sees the counter-clockwise (front) side; a mirroring
      // instance matrix swaps which side that is.
      const bool front = (sum < 0.0) != instance.mirrored;
      if (instance.cullBack && !front) continue;
      const glm::dvec3 bary = w / sum;
      double distance = 0.0;
      for (int k = 0; k < 3; ++k)
        distance -= bary[k] * instance.viewPositions[indices[tri * 3 + k]].z;
      if (distance < znear || distance > zfar) continue;
      out.push_back({int(index), int(tri), distance, bary});
    }
  }
  // Equal distances keep submission order, as the engine's LESS depth test does.
  std::stable_sort(out.begin(), out.end(), [](const TracerHit& a, const TracerHit& b) {
    return a.viewDistance < b.viewDistance;
  });
}

std::optional<TracerHit> ReferenceTracer::nearestHit(const glm::dvec2& window) const {
  std::vector<TracerHit> hits;
  allHits(primaryRay(window), hits);
  if (hits.empty()) return std::nullopt;
  return hits.front();
}

glm::dvec2 ReferenceTracer::texCoord(const TracerHit& hit, int set) const {
  const Mesh& mesh = *instances_[hit.instance].mesh;
  const std::vector<glm::vec2>& uv = mesh.texcoords[set];
  if (uv.empty()) return glm::dvec2(0.0);
  glm::dvec2 sum(0.0);
  for (int k = 0; k < 3; ++k)
    sum += hit.bary[k] * glm::dvec2(uv[mesh.indices[hit.triangle * 3 + k]]);
  return sum;
}

glm::dvec4 ReferenceTracer::surfaceColour(const TracerHit& hit) const {
  const PreparedInstance& instance = instances_[hit.instance];
  glm::dvec4 colour(1.0);
  if (instance.material) {
    const Material& material = *instance.material;
    colour = glm::dvec4(material.baseColorFactor);
    if (material.baseColorTexture >= 0) {
      const Texture& texture = *scene_.textures.at(material.baseColorTexture);
      colour *= sampleBilinear(texture.image(), texture.sampler(),
                               texCoord(hit, material.baseColorTexCoord));
    }
  }
  const Mesh& mesh = *instance.mesh;
  if (!mesh.colors.empty()) {
    glm::dvec4 vertexColour(0.0);
    for (int k = 0; k < 3; ++k)
      vertexColour += hit.bary[k] * glm::dvec4(mesh.colors[mesh.indices[hit.triangle * 3 + k]]);
    colour *= vertexColour;
  }
  return colour;
}

glm::dvec4 ReferenceTracer::shade(const glm::dvec2& window, std::vector<TracerHit>& scratch) const {
  allHits(primaryRay(window), scratch);
  // Front to back "under" compositing, which equals back-to-front "over".
  glm::dvec4 result(0.0);
  const TracerHit* lastBlended = nullptr;
  for (const TracerHit& hit : scratch) {
    const Material* material = instances_[hit.instance].material;
    const AlphaMode mode = material ? material->alphaMode : AlphaMode::Opaque;
    glm::dvec4 colour = surfaceColour(hit);
    if (mode == AlphaMode::Mask && colour.a < material->alphaCutoff) continue;  // discarded
    if (mode != AlphaMode::Blend) colour.a = 1.0;
    if (mode == AlphaMode::Blend) {
      const bool sameSurface = lastBlended && lastBlended->instance == hit.instance &&
                               std::fabs(lastBlended->viewDistance - hit.viewDistance) <=
                                   1e-9 * std::max(1.0, hit.viewDistance);
      if (sameSurface) continue;
      lastBlended = &hit;
    }
    const glm::dvec4 premultiplied(glm::dvec3(colour) * colour.a, colour.a);
    result += (1.0 - result.a) * premultiplied;
    if (mode != AlphaMode::Blend) break;  // an opaque surface hides what lies behind
  }
  return result;
}

Image ReferenceTracer::render(int samplesPerAxis) const {
  QUADRA_CHECK(samplesPerAxis > 0);
  Image image(width_, height_);
  const double weight = 1.0 / (double(samplesPerAxis) * samplesPerAxis);
  tbb::parallel_for(tbb::blocked_range<int>(0, height_), [&](const tbb::blocked_range<int>& rows) {
    std::vector<TracerHit> scratch;
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < width_; ++x) {
        glm::dvec4 sum(0.0);
        for (int j = 0; j < samplesPerAxis; ++j)
          for (int i = 0; i < samplesPerAxis; ++i) {
            const glm::dvec2 at(x + (i + 0.5) / samplesPerAxis, y + (j + 0.5) / samplesPerAxis);
            sum += shade(at, scratch);
          }
        float* out = image.texel(x, y);
        for (int c = 0; c < 4; ++c) out[c] = float(sum[c] * weight);
      }
    }
  });
  return image;
}

}  // namespace quadra::ref
