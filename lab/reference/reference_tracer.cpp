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

// rgb times alpha, exact in double (a product of two floats fits).
glm::dvec4 premultipliedTexel(const glm::dvec4& straight) {
  return {straight.r * straight.a, straight.g * straight.a, straight.b * straight.a, straight.a};
}

glm::dvec4 bilinear(const Image& image, const SamplerState& sampler, const glm::dvec2& uv,
                    bool premultiply) {
  const auto texel = [&](std::int64_t x, std::int64_t y) {
    const glm::dvec4 t = fetch(image, sampler, x, y);
    return premultiply ? premultipliedTexel(t) : t;
  };
  // A non-finite coordinate (a NaN vertex's) reads at 0, as the engine's
  // samplers do (texture/sample_lanes.h, reduceCoordinate); so does one
  // beyond 2^62 texels, which has no fraction left and no int64 to floor to.
  const auto texels = [](double coordinate, int size) {
    const double x = coordinate * size - 0.5;
    return std::fabs(x) < 0x1p62 ? x : -0.5;  // NaN fails the test too
  };
  const double x = texels(uv.x, image.width), y = texels(uv.y, image.height);
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  const auto ix = std::int64_t(x0), iy = std::int64_t(y0);
  const glm::dvec4 top = (1 - fx) * texel(ix, iy) + fx * texel(ix + 1, iy);
  const glm::dvec4 bottom = (1 - fx) * texel(ix, iy + 1) + fx * texel(ix + 1, iy + 1);
  return (1 - fy) * top + fy * bottom;
}

}  // namespace

glm::dvec4 sampleBilinear(const Image& image, const SamplerState& sampler, const glm::dvec2& uv) {
  return bilinear(image, sampler, uv, false);
}

glm::dvec4 sampleBilinearPremultiplied(const Image& image, const SamplerState& sampler,
                                       const glm::dvec2& uv) {
  const glm::dvec4 filtered = bilinear(image, sampler, uv, true);
  if (!(filtered.a > 0.0)) return glm::dvec4(0.0);
  return {filtered.r / filtered.a, filtered.g / filtered.a, filtered.b / filtered.a, filtered.a};
}

ReferenceTracer::ReferenceTracer(const Scene& scene, const Camera& camera, int width, int height,
                                 TracerSearch search)
    : scene_(scene),
      camera_(camera),
      width_(width),
      height_(height),
      aspect_(double(width) / double(height)),
      search_(search) {
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
    const std::vector<glm::dvec3> modelPositions = posedPositions(*prepared.mesh, instance);
    for (const glm::dvec3& p : modelPositions) {
      const glm::dvec3 v(modelView * glm::dvec4(p, 1.0));
      prepared.viewPositions.push_back(v);
      prepared.boundsLo = glm::min(prepared.boundsLo, v);
      prepared.boundsHi = glm::max(prepared.boundsHi, v);
    }
    const std::vector<glm::dvec3>& p = modelPositions;
    const std::vector<std::uint32_t>& corners = prepared.mesh->indices;
    prepared.degenerate.resize(corners.size() / 3);
    for (std::size_t t = 0; t < prepared.degenerate.size(); ++t) {
      // Differences of floats of like magnitude are exact in double, and the
      // two products of a component round alike when they are equal, so
      // collinear corners give exactly zero (for stored positions; posed
      // ones are doubles, where only exact degeneracy is caught).
      const glm::dvec3 a(p[corners[t * 3]]), b(p[corners[t * 3 + 1]]), c(p[corners[t * 3 + 2]]);
      prepared.degenerate[t] = glm::cross(b - a, c - a) == glm::dvec3(0.0);
    }
    instances_.push_back(std::move(prepared));
  }
  znear_ = camera_.znear;
  zfar_ = camera_.type == Camera::Type::Orthographic
              ? (camera_.zfar > camera_.znear ? camera_.zfar : HUGE_VAL)
              : (camera_.zfar != 0.0f ? camera_.zfar : HUGE_VAL);
  if (search_ == TracerSearch::ScreenGrid) buildScreenGrid();
}

std::vector<glm::dvec3> ReferenceTracer::posedPositions(const Mesh& mesh,
                                                        const Instance& instance) {
  std::vector<glm::dvec3> positions(mesh.positions.begin(), mesh.positions.end());
  if (!instance.morphWeights.empty()) {
    for (std::size_t t = 0; t < mesh.targets.size(); ++t) {
      const std::vector<glm::vec3>& deltas = mesh.targets[t].positions;
      for (std::size_t v = 0; v < deltas.size(); ++v)
        positions[v] += double(instance.morphWeights.at(t)) * glm::dvec3(deltas[v]);
    }
  }
  if (instance.jointMatrices.empty() || mesh.joints[0].empty()) return positions;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    glm::dvec3 skinned(0.0);
    for (int set = 0; set < 2; ++set) {
      if (mesh.joints[set].empty()) continue;
      for (int k = 0; k < 4; ++k) {
        const glm::dmat4 joint(instance.jointMatrices.at(mesh.joints[set][v][k]));
        skinned +=
            double(mesh.weights[set][v][k]) * glm::dvec3(joint * glm::dvec4(positions[v], 1.0));
      }
    }
    positions[v] = skinned;
  }
  return positions;
}

void ReferenceTracer::buildScreenGrid() {
  // Window-space bounds of a triangle, padded far beyond the rounding of the
  // projection (~1e-16 relative) so that every ray the exact inside test
  // accepts lands in a cell that lists the triangle; false when it has none.
  // A primary ray's line meets a triangle wholly in front of a perspective
  // eye (z < 0) exactly where the window point lies in the projected
  // triangle; an orthographic ray's, where (x, y) lies in the triangle's.
  const bool orthographic = camera_.type == Camera::Type::Orthographic;
  const double f = 1.0 / std::tan(double(camera_.yfov) / 2.0);
  const auto windowBounds = [&](const PreparedInstance& instance, std::size_t triangle,
                                glm::dvec2& lo, glm::dvec2& hi) {
    lo = glm::dvec2(HUGE_VAL);
    hi = -lo;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 v = instance.viewPositions[instance.mesh->indices[triangle * 3 + k]];
      if (!orthographic && !(v.z < 0.0)) return false;
      const double xNdc =
          orthographic ? v.x / (double(camera_.ymag) * aspect_) : v.x / -v.z * f / aspect_;
      const double yNdc = orthographic ? v.y / double(camera_.ymag) : v.y / -v.z * f;
      const glm::dvec2 w((xNdc + 1.0) * 0.5 * width_, (1.0 - yNdc) * 0.5 * height_);
      if (!std::isfinite(w.x) || !std::isfinite(w.y)) return false;
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
    const double pad = 1.0 / 1024 + 1e-9 * std::max({std::fabs(lo.x), std::fabs(lo.y),
                                                     std::fabs(hi.x), std::fabs(hi.y)});
    lo -= pad;
    hi += pad;
    return true;
  };
  // Calls visit(ref, first cell, last cell) for every triangle with bounds
  // that reach the screen (no on-screen ray meets the others), and collects
  // those without bounds.
  ScreenGrid& grid = grid_;
  const auto forEachBinned = [&](const auto& visit) {
    grid.everywhere.clear();
    for (std::size_t index = 0; index < instances_.size(); ++index) {
      const PreparedInstance& instance = instances_[index];
      for (std::size_t tri = 0; tri * 3 < instance.mesh->indices.size(); ++tri) {
        const TriangleRef ref{std::uint32_t(index), std::uint32_t(tri)};
        glm::dvec2 lo, hi;
        if (!windowBounds(instance, tri, lo, hi)) {
          grid.everywhere.push_back(ref);
          continue;
        }
        if (hi.x < 0.0 || hi.y < 0.0 || lo.x > width_ || lo.y > height_) continue;
        // Clamped before the conversion: a vertex 1e30 away projects far beyond int.
        const auto cell = [&](double at, int count) {
          return int(std::clamp(std::floor(at / grid.cellSize), 0.0, double(count - 1)));
        };
        visit(ref, glm::ivec2(cell(lo.x, grid.columns), cell(lo.y, grid.rows)),
              glm::ivec2(cell(hi.x, grid.columns), cell(hi.y, grid.rows)));
      }
    }
  };
  // One-pixel cells unless the lists would pass ~16M entries (128 MiB), as
  // many large triangles on a large frame would make them; then coarser.
  constexpr std::size_t kEntryBudget = std::size_t(1) << 24;
  for (grid.cellSize = 1;; grid.cellSize *= 2) {
    grid.columns = (width_ + grid.cellSize - 1) / grid.cellSize;
    grid.rows = (height_ + grid.cellSize - 1) / grid.cellSize;
    std::size_t entries = 0;
    forEachBinned([&](const TriangleRef&, glm::ivec2 first, glm::ivec2 last) {
      entries += std::size_t(last.x - first.x + 1) * std::size_t(last.y - first.y + 1);
    });
    if (entries <= kEntryBudget || grid.cellSize >= std::max(width_, height_)) break;
  }
  const std::size_t cells = std::size_t(grid.columns) * std::size_t(grid.rows);
  grid.cellStart.assign(cells + 1, 0);
  forEachBinned([&](const TriangleRef&, glm::ivec2 first, glm::ivec2 last) {
    for (int y = first.y; y <= last.y; ++y)
      for (int x = first.x; x <= last.x; ++x)
        ++grid.cellStart[std::size_t(y * grid.columns + x) + 1];
  });
  for (std::size_t c = 0; c < cells; ++c) grid.cellStart[c + 1] += grid.cellStart[c];
  grid.entries.resize(grid.cellStart[cells]);
  std::vector<std::uint32_t> next(grid.cellStart.begin(), grid.cellStart.end() - 1);
  // Scene order within each cell, so hits come out as the exhaustive loop finds them.
  forEachBinned([&](const TriangleRef& ref, glm::ivec2 first, glm::ivec2 last) {
    for (int y = first.y; y <= last.y; ++y)
      for (int x = first.x; x <= last.x; ++x)
        grid.entries[next[std::size_t(y * grid.columns + x)]++] = ref;
  });
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

void ReferenceTracer::testTriangle(std::size_t index, std::size_t triangle, const Ray& ray,
                                   std::vector<TracerHit>& out) const {
  const PreparedInstance& instance = instances_[index];
  if (instance.degenerate[triangle]) return;
  const std::vector<std::uint32_t>& indices = instance.mesh->indices;
  const glm::dvec3 w = planeWeights(instance, triangle, ray);
  // Edges are inclusive: a ray through a shared edge hits both
  // neighbours, never neither.
  const bool inside =
      (w.x >= 0.0 && w.y >= 0.0 && w.z >= 0.0) || (w.x <= 0.0 && w.y <= 0.0 && w.z <= 0.0);
  const double sum = w.x + w.y + w.z;  // dot(direction, e1 x e2)
  if (!inside || sum == 0.0) return;   // missed, or edge-on: zero projected area
  // sum < 0: the ray sees the counter-clockwise (front) side; a mirroring
  // instance matrix swaps which side that is.
  const bool front = (sum < 0.0) != instance.mirrored;
  if (instance.cullBack && !front) return;
  const glm::dvec3 bary = w / sum;
  double distance = 0.0;
  for (int k = 0; k < 3; ++k)
    distance -= bary[k] * instance.viewPositions[indices[triangle * 3 + k]].z;
  if (distance < znear_ || distance > zfar_) return;
  out.push_back({int(index), int(triangle), distance, bary});
}

namespace {

// Equal distances keep scene order, as the engine's LESS depth test does.
void sortByDistance(std::vector<TracerHit>& hits) {
  std::stable_sort(hits.begin(), hits.end(), [](const TracerHit& a, const TracerHit& b) {
    return a.viewDistance < b.viewDistance;
  });
}

}  // namespace

void ReferenceTracer::allHits(const Ray& ray, std::vector<TracerHit>& out) const {
  out.clear();
  for (std::size_t index = 0; index < instances_.size(); ++index) {
    if (!rayMayHit(instances_[index], ray)) continue;
    for (std::size_t tri = 0; tri * 3 < instances_[index].mesh->indices.size(); ++tri)
      testTriangle(index, tri, ray, out);
  }
  sortByDistance(out);
}

void ReferenceTracer::hitsAt(const glm::dvec2& window, std::vector<TracerHit>& out) const {
  const Ray ray = primaryRay(window);
  const bool onScreen =
      window.x >= 0.0 && window.y >= 0.0 && window.x <= width_ && window.y <= height_;
  if (search_ == TracerSearch::Exhaustive || !onScreen) return allHits(ray, out);
  out.clear();
  const ScreenGrid& grid = grid_;
  const int column = std::min(int(window.x / grid.cellSize), grid.columns - 1);
  const int row = std::min(int(window.y / grid.cellSize), grid.rows - 1);
  const std::size_t cell = std::size_t(row * grid.columns + column);
  const TriangleRef* binned = grid.entries.data() + grid.cellStart[cell];
  const TriangleRef* binnedEnd = grid.entries.data() + grid.cellStart[cell + 1];
  const TriangleRef* everywhere = grid.everywhere.data();
  const TriangleRef* everywhereEnd = everywhere + grid.everywhere.size();
  const auto before = [](const TriangleRef& a, const TriangleRef& b) {
    return a.instance < b.instance || (a.instance == b.instance && a.triangle < b.triangle);
  };
  // Both lists are in scene order; merged, they are visited as allHits
  // visits them, with the same per-instance bounds test.
  std::uint32_t boundsInstance = ~0u;
  bool mayHit = false;
  while (binned != binnedEnd || everywhere != everywhereEnd) {
    const bool takeBinned =
        everywhere == everywhereEnd || (binned != binnedEnd && before(*binned, *everywhere));
    const TriangleRef ref = takeBinned ? *binned++ : *everywhere++;
    if (ref.instance != boundsInstance) {
      boundsInstance = ref.instance;
      mayHit = rayMayHit(instances_[ref.instance], ray);
    }
    if (mayHit) testTriangle(ref.instance, ref.triangle, ray, out);
  }
  sortByDistance(out);
}

std::optional<TracerHit> ReferenceTracer::nearestHit(const glm::dvec2& window) const {
  std::vector<TracerHit> hits;
  hitsAt(window, hits);
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

// KHR_texture_transform in double, step by step as the extension defines it
// (scale, then rotation, then offset), apart from the engine's matrix
// (TextureTransform::matrix) so that the comparison checks it.
glm::dvec2 transformed(const TextureTransform& transform, glm::dvec2 uv) {
  uv *= glm::dvec2(transform.scale);
  const double c = std::cos(double(transform.rotation)), s = std::sin(double(transform.rotation));
  uv = glm::dvec2(c * uv.x + s * uv.y, c * uv.y - s * uv.x);
  return uv + glm::dvec2(transform.offset);
}

glm::dvec4 ReferenceTracer::surfaceColour(const TracerHit& hit) const {
  const PreparedInstance& instance = instances_[hit.instance];
  glm::dvec4 colour(1.0);
  if (instance.material) {
    const Material& material = *instance.material;
    colour = glm::dvec4(material.baseColorFactor);
    if (material.baseColorTexture >= 0) {
      const Texture& texture = *scene_.textures.at(material.baseColorTexture);
      const glm::dvec2 uv =
          transformed(material.baseColorTransform, texCoord(hit, material.baseColorTexCoord));
      // Filtered as the renderer filters it: premultiplied where alpha is read.
      colour *= textureAlphaOf(material).premultiplied()
                    ? sampleBilinearPremultiplied(texture.image(), texture.sampler(), uv)
                    : sampleBilinear(texture.image(), texture.sampler(), uv);
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
  return shadeWith(window, scratch,
                   [](const TracerHit&, const Ray&, const glm::dvec4& surface) { return surface; });
}

glm::dvec4 ReferenceTracer::shadeWith(const glm::dvec2& window, std::vector<TracerHit>& scratch,
                                      const HitColour& colourOf, int* surface) const {
  hitsAt(window, scratch);
  if (surface) *surface = -1;
  const Ray ray = primaryRay(window);
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
    if (surface && *surface < 0) *surface = hit.instance;
    const double alpha = colour.a;
    colour = colourOf(hit, ray, colour);
    const glm::dvec4 premultiplied(glm::dvec3(colour) * alpha, alpha);
    result += (1.0 - result.a) * premultiplied;
    if (mode != AlphaMode::Blend) break;  // an opaque surface hides what lies behind
  }
  return result;
}

int ReferenceTracer::visibleSurface(const glm::dvec2& window,
                                    std::vector<TracerHit>& scratch) const {
  int surface = -1;
  shadeWith(
      window, scratch,
      [](const TracerHit&, const Ray&, const glm::dvec4&) { return glm::dvec4(0.0); }, &surface);
  return surface;
}

glm::dvec2 ReferenceTracer::stratumPoint(int x, int y, int k, int samplesPerAxis,
                                         const glm::dvec2& within) {
  const int i = k % samplesPerAxis, j = k / samplesPerAxis;
  return {x + (i + within.x) / samplesPerAxis, y + (j + within.y) / samplesPerAxis};
}

Image ReferenceTracer::integrate(int samplesPerPixel, const PixelSample& sample) const {
  QUADRA_CHECK(samplesPerPixel > 0);
  Image image(width_, height_);
  const double weight = 1.0 / double(samplesPerPixel);
  tbb::parallel_for(tbb::blocked_range<int>(0, height_), [&](const tbb::blocked_range<int>& rows) {
    std::vector<TracerHit> scratch;
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < width_; ++x) {
        glm::dvec4 sum(0.0);
        for (int k = 0; k < samplesPerPixel; ++k) sum += sample(x, y, k, scratch);
        float* out = image.texel(x, y);
        for (int c = 0; c < 4; ++c) out[c] = float(sum[c] * weight);
      }
    }
  });
  return image;
}

Image ReferenceTracer::render(int samplesPerAxis) const {
  QUADRA_CHECK(samplesPerAxis > 0);
  return integrate(samplesPerAxis * samplesPerAxis,
                   [&](int x, int y, int k, std::vector<TracerHit>& scratch) {
                     return shade(stratumPoint(x, y, k, samplesPerAxis, glm::dvec2(0.5)), scratch);
                   });
}

std::vector<std::uint8_t> ReferenceTracer::interiorOf(const std::vector<int>& pixelSurfaces,
                                                      int width, int height) {
  QUADRA_CHECK(pixelSurfaces.size() == std::size_t(width) * std::size_t(height));
  std::vector<std::uint8_t> interior(pixelSurfaces.size(), 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int own = pixelSurfaces[std::size_t(y) * std::size_t(width) + std::size_t(x)];
      bool one = own != kMixedSurface;
      for (int dy = -1; dy <= 1 && one; ++dy)
        for (int dx = -1; dx <= 1 && one; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          one = pixelSurfaces[std::size_t(ny) * std::size_t(width) + std::size_t(nx)] == own;
        }
      interior[std::size_t(y) * std::size_t(width) + std::size_t(x)] = one ? 1 : 0;
    }
  return interior;
}

std::vector<std::uint8_t> ReferenceTracer::interiorMask(int samplesPerAxis) const {
  QUADRA_CHECK(samplesPerAxis > 0);
  std::vector<int> surfaces(std::size_t(width_) * std::size_t(height_));
  tbb::parallel_for(tbb::blocked_range<int>(0, height_), [&](const tbb::blocked_range<int>& rows) {
    std::vector<TracerHit> scratch;
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < width_; ++x) {
        int seen = 0;
        for (int k = 0; k < samplesPerAxis * samplesPerAxis; ++k) {
          const int s =
              visibleSurface(stratumPoint(x, y, k, samplesPerAxis, glm::dvec2(0.5)), scratch);
          if (k == 0) seen = s;
          if (s != seen) seen = kMixedSurface;
        }
        surfaces[std::size_t(y) * std::size_t(width_) + std::size_t(x)] = seen;
      }
  });
  return interiorOf(surfaces, width_, height_);
}

std::array<glm::dvec3, 3> ReferenceTracer::viewCorners(const TracerHit& hit) const {
  const PreparedInstance& instance = instances_[std::size_t(hit.instance)];
  const std::uint32_t* corner = &instance.mesh->indices[std::size_t(hit.triangle) * 3];
  return {instance.viewPositions[corner[0]], instance.viewPositions[corner[1]],
          instance.viewPositions[corner[2]]};
}

bool ReferenceTracer::frontFacing(const TracerHit& hit, const Ray& ray) const {
  const PreparedInstance& instance = instances_[std::size_t(hit.instance)];
  const glm::dvec3 w = planeWeights(instance, std::size_t(hit.triangle), ray);
  return (w.x + w.y + w.z < 0.0) != instance.mirrored;  // as testTriangle decides it
}

const Material* ReferenceTracer::materialOf(const TracerHit& hit) const {
  return instances_[std::size_t(hit.instance)].material;
}

Image ReferenceTracer::renderPoints(const std::vector<glm::dvec2>& offsets) const {
  QUADRA_CHECK(!offsets.empty());
  Image image(width_, height_);
  const double weight = 1.0 / double(offsets.size());
  tbb::parallel_for(tbb::blocked_range<int>(0, height_), [&](const tbb::blocked_range<int>& rows) {
    std::vector<TracerHit> scratch;
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < width_; ++x) {
        glm::dvec4 sum(0.0);
        for (const glm::dvec2& offset : offsets)
          sum += shade(glm::dvec2(x + 0.5, y + 0.5) + offset, scratch);
        float* out = image.texel(x, y);
        for (int c = 0; c < 4; ++c) out[c] = float(sum[c] * weight);
      }
  });
  return image;
}

}  // namespace quadra::ref
