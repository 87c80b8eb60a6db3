// The exact reference rasterizer and the double-precision scene projection
// (self-tests in tests/test_reference_raster.cpp).
#include "lab/reference/reference_raster.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.h"

namespace quadra::ref {

std::int64_t snapToGrid(double windowCoordinate) {
  const double scaled = windowCoordinate * kSubpixelUnits;
  // 2^62 grid units leave headroom for the 128-bit products below and are far
  // beyond any coordinate a test produces.
  QUADRA_CHECK(std::isfinite(scaled) && std::fabs(scaled) < 0x1p62);
  // nearbyint follows the default rounding mode: to nearest, ties to even.
  return static_cast<std::int64_t>(std::nearbyint(scaled));
}

GridTriangle snapTriangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                          CullMode cull) {
  GridTriangle t;
  const glm::dvec2* corners[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) t.v[i] = {snapToGrid(corners[i]->x), snapToGrid(corners[i]->y)};
  t.cull = cull;
  return t;
}

namespace {

int sign(__int128 v) {
  return (v > 0) - (v < 0);
}

// The spec's words, evaluated literally. "Top": the edge is exactly horizontal
// and the third vertex lies below it (larger y). "Left": the edge is not
// horizontal and the triangle lies to its right, i.e. the third vertex is to
// the right of the edge's line at the third vertex's height.
bool isTopOrLeftEdge(const GridPoint& a, const GridPoint& b, const GridPoint& third) {
  if (a.y == b.y) return third.y > a.y;
  // third.x - lineX(third.y), scaled by (b.y - a.y), whose sign is undone below.
  const __int128 scaledOffset =
      __int128(third.x - a.x) * (b.y - a.y) - __int128(b.x - a.x) * (third.y - a.y);
  return sign(scaledOffset) * sign(__int128(b.y - a.y)) > 0;
}

}  // namespace

__int128 cross(const GridPoint& origin, const GridPoint& towards, const GridPoint& p) {
  const __int128 ex = towards.x - origin.x, ey = towards.y - origin.y;
  const __int128 px = p.x - origin.x, py = p.y - origin.y;
  return ex * py - ey * px;
}

__int128 doubleSignedArea(const GridTriangle& t) {
  return cross(t.v[0], t.v[1], t.v[2]);
}

bool coversPixelCentre(const GridTriangle& t, std::int64_t px, std::int64_t py) {
  return coversPoint(t, samplePoint(px, py, 0, 1));
}

GridPoint samplePoint(std::int64_t px, std::int64_t py, int sample, int samplesPerPixel) {
  // Positions from the pixel's top-left corner in 1/16 pixel, x then y per
  // sample (Direct3D 11's D3D11_STANDARD_MULTISAMPLE_PATTERN, as Mesa's SWR
  // rasterizer tabulates it).
  static constexpr int kOne[] = {8, 8};
  static constexpr int kTwo[] = {12, 12, 4, 4};
  static constexpr int kFour[] = {6, 2, 14, 6, 2, 10, 10, 14};
  static constexpr int kEight[] = {9, 5, 7, 11, 13, 9, 5, 3, 3, 13, 1, 7, 11, 15, 15, 1};
  static constexpr int kSixteen[] = {9, 9,  7, 5, 5, 10, 12, 7,  3, 6, 10, 13, 13, 11, 11, 3,
                                     6, 14, 8, 1, 4, 2,  2,  12, 0, 8, 15, 4,  14, 15, 1,  0};
  const int* table = samplesPerPixel == 16  ? kSixteen
                     : samplesPerPixel == 8 ? kEight
                     : samplesPerPixel == 4 ? kFour
                     : samplesPerPixel == 2 ? kTwo
                                            : kOne;
  constexpr std::int64_t kUnit = kSubpixelUnits / 16;
  return {px * kSubpixelUnits + table[2 * sample] * kUnit,
          py * kSubpixelUnits + table[2 * sample + 1] * kUnit};
}

bool coversPoint(const GridTriangle& t, const GridPoint& centre) {
  const int interiorSign = sign(doubleSignedArea(t));
  if (interiorSign == 0) return false;
  for (int i = 0; i < 3; ++i) {
    const GridPoint& a = t.v[i];
    const GridPoint& b = t.v[(i + 1) % 3];
    const GridPoint& third = t.v[(i + 2) % 3];
    const __int128 inside = cross(a, b, centre) * interiorSign;
    if (inside < 0) return false;
    if (inside == 0 && !isTopOrLeftEdge(a, b, third)) return false;
  }
  return true;
}

bool survivesCulling(const GridTriangle& t) {
  const __int128 area = doubleSignedArea(t);
  switch (t.cull) {
    case CullMode::None:
      return true;
    case CullMode::Back:
      return area < 0;
    case CullMode::Front:
      return area > 0;
  }
  return true;
}

CoverageImage rasterizeCoverage(const std::vector<GridTriangle>& triangles, int width, int height,
                                int samplesPerPixel) {
  CoverageImage image{width, height, std::vector<int>(std::size_t(width) * height, 0),
                      std::vector<int>(std::size_t(width) * height, -1)};
  for (std::size_t index = 0; index < triangles.size(); ++index) {
    const GridTriangle& t = triangles[index];
    if (!survivesCulling(t)) continue;
    // Pixel rows/columns whose centres can lie inside the bounding box.
    std::int64_t lo[2] = {t.v[0].x, t.v[0].y}, hi[2] = {t.v[0].x, t.v[0].y};
    for (const GridPoint& p : t.v) {
      lo[0] = std::min(lo[0], p.x), hi[0] = std::max(hi[0], p.x);
      lo[1] = std::min(lo[1], p.y), hi[1] = std::max(hi[1], p.y);
    }
    const auto firstPixel = [](std::int64_t g) { return g / kSubpixelUnits - 1; };
    const auto lastPixel = [](std::int64_t g) { return g / kSubpixelUnits + 1; };
    const std::int64_t x0 = std::max<std::int64_t>(0, firstPixel(lo[0]));
    const std::int64_t x1 = std::min<std::int64_t>(width - 1, lastPixel(hi[0]));
    const std::int64_t y0 = std::max<std::int64_t>(0, firstPixel(lo[1]));
    const std::int64_t y1 = std::min<std::int64_t>(height - 1, lastPixel(hi[1]));
    for (std::int64_t y = y0; y <= y1; ++y) {
      for (std::int64_t x = x0; x <= x1; ++x) {
        int covered = 0;
        for (int sample = 0; sample < samplesPerPixel; ++sample)
          covered += coversPoint(t, samplePoint(x, y, sample, samplesPerPixel));
        if (covered == 0) continue;
        const std::size_t at = std::size_t(y) * width + std::size_t(x);
        image.count[at] += covered;
        image.lastTriangle[at] = int(index);
      }
    }
  }
  return image;
}

// ---------------------------------------------------------------------------
// Projection.

glm::dmat4 referenceViewMatrix(const Camera& camera) {
  glm::dmat4 rigid(camera.world);
  for (int axis = 0; axis < 3; ++axis) {
    const glm::dvec3 column = glm::normalize(glm::dvec3(rigid[axis]));
    rigid[axis] = glm::dvec4(column, 0.0);
  }
  return glm::inverse(rigid);
}

glm::dvec4 referenceClip(const Camera& camera, double aspect, const glm::dvec3& viewPoint) {
  const double distance = -viewPoint.z;  // along the viewing direction
  const double znear = camera.znear, zfar = camera.zfar;
  if (camera.type == Camera::Type::Orthographic) {
    const double ymag = camera.ymag;
    const double z = zfar > znear ? (distance - znear) / (zfar - znear) : distance - znear;
    return {viewPoint.x / (ymag * aspect), viewPoint.y / ymag, z, 1.0};
  }
  const double f = 1.0 / std::tan(double(camera.yfov) / 2.0);
  const double z = zfar == 0.0 ? distance - znear : zfar * (distance - znear) / (zfar - znear);
  return {f / aspect * viewPoint.x, f * viewPoint.y, z, distance};
}

namespace {

struct ClipVertex {
  glm::dvec4 clip;
  glm::dvec3 bary;
};

// Sutherland-Hodgman against one plane given as a signed distance (>= 0 kept).
template <typename Distance>
std::vector<ClipVertex> clipPolygon(const std::vector<ClipVertex>& polygon, Distance distance) {
  std::vector<ClipVertex> out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const ClipVertex& a = polygon[i];
    const ClipVertex& b = polygon[(i + 1) % polygon.size()];
    const double da = distance(a.clip), db = distance(b.clip);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) {
      // From the end nearer the plane: a short step stays accurate when the
      // other end is 1e30 away.
      const bool fromA = std::fabs(da) <= std::fabs(db);
      const ClipVertex& from = fromA ? a : b;
      const ClipVertex& to = fromA ? b : a;
      const double t = (fromA ? da : db) / (fromA ? da - db : db - da);
      out.push_back({from.clip + t * (to.clip - from.clip), from.bary + t * (to.bary - from.bary)});
    }
  }
  return out;
}

ProjectedVertex toWindow(const ClipVertex& v, int width, int height) {
  ProjectedVertex p;
  const glm::dvec3 ndc = glm::dvec3(v.clip) / v.clip.w;
  p.windowExact = {(ndc.x + 1.0) * width / 2.0, (1.0 - ndc.y) * height / 2.0};
  p.window = {double(snapToGrid(p.windowExact.x)) / kSubpixelUnits,
              double(snapToGrid(p.windowExact.y)) / kSubpixelUnits};
  p.depth = ndc.z;
  p.clipW = v.clip.w;
  p.sourceBary = v.bary;
  return p;
}

CullMode cullModeOf(const Scene& scene, const Instance& instance) {
  const int material = scene.meshes[instance.mesh].material;
  const bool doubleSided = material >= 0 && scene.materials[material].doubleSided;
  if (doubleSided) return CullMode::None;
  return glm::determinant(glm::dmat4(instance.world)) < 0.0 ? CullMode::Front : CullMode::Back;
}

}  // namespace

GridTriangle ProjectedTriangle::grid() const {
  GridTriangle t;
  for (int i = 0; i < 3; ++i) t.v[i] = {snapToGrid(v[i].window.x), snapToGrid(v[i].window.y)};
  t.cull = cull;
  return t;
}

std::vector<ProjectedTriangle> projectScene(const Scene& scene, const Camera& camera, int width,
                                            int height) {
  const double aspect = double(width) / double(height);
  const glm::dmat4 view = referenceViewMatrix(camera);
  const bool finiteFar =
      camera.type == Camera::Type::Orthographic ? camera.zfar > camera.znear : camera.zfar != 0.0f;
  std::vector<ProjectedTriangle> out;
  for (std::size_t instanceIndex = 0; instanceIndex < scene.instances.size(); ++instanceIndex) {
    const Instance& instance = scene.instances[instanceIndex];
    const Mesh& mesh = scene.meshes[instance.mesh];
    const glm::dmat4 modelView = view * glm::dmat4(instance.world);
    const CullMode cull = cullModeOf(scene, instance);
    for (std::size_t tri = 0; tri * 3 < mesh.indices.size(); ++tri) {
      std::vector<ClipVertex> polygon;
      for (int corner = 0; corner < 3; ++corner) {
        const glm::dvec3 p(mesh.positions[mesh.indices[tri * 3 + corner]]);
        glm::dvec3 bary(0.0);
        bary[corner] = 1.0;
        polygon.push_back(
            {referenceClip(camera, aspect, glm::dvec3(modelView * glm::dvec4(p, 1.0))), bary});
      }
      polygon = clipPolygon(polygon, [](const glm::dvec4& c) { return c.z; });
      if (finiteFar) polygon = clipPolygon(polygon, [](const glm::dvec4& c) { return c.w - c.z; });
      // Sides only far beyond the view (see kReferenceGuard), where a clipped
      // vertex moves the edges inside the viewport by nothing measurable.
      polygon =
          clipPolygon(polygon, [](const glm::dvec4& c) { return kReferenceGuard * c.w - c.x; });
      polygon =
          clipPolygon(polygon, [](const glm::dvec4& c) { return kReferenceGuard * c.w + c.x; });
      polygon =
          clipPolygon(polygon, [](const glm::dvec4& c) { return kReferenceGuard * c.w - c.y; });
      polygon =
          clipPolygon(polygon, [](const glm::dvec4& c) { return kReferenceGuard * c.w + c.y; });
      for (std::size_t k = 2; k < polygon.size(); ++k) {
        ProjectedTriangle t;
        t.v = {toWindow(polygon[0], width, height), toWindow(polygon[k - 1], width, height),
               toWindow(polygon[k], width, height)};
        t.instance = int(instanceIndex);
        t.triangle = int(tri);
        t.cull = cull;
        out.push_back(t);
      }
    }
  }
  return out;
}

std::vector<GridTriangle> gridTriangles(const std::vector<ProjectedTriangle>& projected) {
  std::vector<GridTriangle> out;
  out.reserve(projected.size());
  for (const ProjectedTriangle& t : projected) out.push_back(t.grid());
  return out;
}

double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec2 ab = b - a;
  const double length2 = glm::dot(ab, ab);
  const double s = length2 > 0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + s * ab));
}

double distanceToEdges(const std::vector<ProjectedTriangle>& triangles, const glm::dvec2& p) {
  double nearest = HUGE_VAL;
  for (const ProjectedTriangle& t : triangles)
    for (int k = 0; k < 3; ++k)
      nearest = std::min(nearest, distanceToSegment(p, t.v[k].window, t.v[(k + 1) % 3].window));
  return nearest;
}

}  // namespace quadra::ref
