// Perspective-correct interpolation and clipping, engine against double
// precision: DebugView::TexCoord on a steep plane must match the exact
// ray-plane value (and must not match screen-space affine interpolation);
// triangles crossing the near plane or reaching ~1e4 units sideways must keep
// their coverage and texture coordinates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "api/renderer.h"
#include "lab/reference/reference_raster.h"
#include "lab/reference/reference_tracer.h"
#include "render_helpers.h"

namespace quadra {
namespace {

constexpr int kWidth = 256;
constexpr int kHeight = 160;

using UvOfPosition = std::function<glm::vec2(const glm::vec3&)>;

// One double-sided mesh whose TEXCOORD_0 is uvOf(position): uv is then an
// affine function on each triangle's plane, so the exact value anywhere on the
// plane follows from the ray-plane hit.
Scene planeScene(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices,
                 const UvOfPosition& uvOf) {
  Scene scene;
  Mesh mesh;
  mesh.positions = positions;
  for (const glm::vec3& p : positions) mesh.texcoords[0].push_back(uvOf(p));
  mesh.indices = indices;
  mesh.material = 0;
  Material material;
  material.doubleSided = true;
  material.baseColorTexture = 0;  // a material that reads TEXCOORD_0
  scene.materials.push_back(material);
  scene.textures.push_back(
      std::make_shared<Texture>(std::make_shared<Image>(2, 2), SamplerState{}));
  scene.meshes.push_back(mesh);
  scene.instances.push_back(Instance{});
  return scene;
}

Camera perspectiveCamera(float znear, float zfar) {
  Camera camera;
  camera.yfov = 0.9f;
  camera.znear = znear;
  camera.zfar = zfar;
  return camera;
}

Frame render(const Scene& scene, const Camera& camera, DebugView view,
             FrameStats* stats = nullptr) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.debugView = view;
  return renderOnce(scene, camera, settings, 2, std::nullopt, stats);
}

const float* pixel(const Frame& frame, int x, int y) {
  return &frame.rgba[(std::size_t(y) * std::size_t(frame.width) + x) * 4];
}

glm::dvec2 pixelCentre(int x, int y) {
  return {x + 0.5, y + 0.5};
}

// The exact value where the primary ray through a window point meets the plane
// of triangle `triangle` of the scene's one instance (inside it or not).
glm::dvec2 rayPlaneUv(const ref::ReferenceTracer& tracer, int triangle, const glm::dvec2& window) {
  ref::TracerHit source;
  source.triangle = triangle;
  return tracer.planeTexCoord(source, tracer.primaryRay(window), 0);
}

// Screen-space barycentrics of a point in a projected triangle.
glm::dvec3 screenBary(const ref::ProjectedTriangle& t, const glm::dvec2& p) {
  const auto area = [](const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  };
  const glm::dvec2 &a = t.v[0].window, &b = t.v[1].window, &c = t.v[2].window;
  const double total = area(a, b, c);
  return {area(p, b, c) / total, area(a, p, c) / total, area(a, b, p) / total};
}

glm::dvec2 vertexUv(const Scene& scene, const ref::ProjectedTriangle& t, int k) {
  const Mesh& mesh = scene.meshes[0];
  glm::dvec2 uv(0.0);
  for (int s = 0; s < 3; ++s)
    uv += t.v[k].sourceBary[s] * glm::dvec2(mesh.texcoords[0][mesh.indices[t.triangle * 3 + s]]);
  return uv;
}

// What a rasterizer without perspective correction would produce.
glm::dvec2 affineUv(const Scene& scene, const ref::ProjectedTriangle& t, const glm::dvec2& p) {
  const glm::dvec3 l = screenBary(t, p);
  return l.x * vertexUv(scene, t, 0) + l.y * vertexUv(scene, t, 1) + l.z * vertexUv(scene, t, 2);
}

double maxAbs(const glm::dvec2& v) {
  return std::max(std::fabs(v.x), std::fabs(v.y));
}

// A rectangle on the ground (y = -1) from 1.5 to 12 units ahead, 8 wide, seen
// at a grazing angle; uv spans [0, 1]^2 over it, so errors are fractions of
// the uv extent. At its far edge uv moves ~0.08 per pixel of screen motion.
//
// Bound 1e-4: the float pipeline interpolates u/w and 1/w as planes over at
// most 256 px; each evaluation carries a few ulps (6e-8 relative) of terms up
// to ~100x the result near the far edge, i.e. ~1e-5, and the divide adds one
// ulp more, so 1e-4 holds with a 10x margin. It still catches an approximate
// reciprocal for 1/w (12 bits: 2.4e-4 relative) and any sub-pixel offset.
// Snapping needs no allowance: it moves coverage only, the planes go through
// the unsnapped vertex positions, so uv is compared with the ray-plane value.
TEST(Perspective, SteepPlaneTexCoordIsPerspectiveCorrect) {
  const std::vector<glm::vec3> corners = {
      {-4, -1, -1.5f}, {4, -1, -1.5f}, {4, -1, -12}, {-4, -1, -12}};
  const Scene scene = planeScene(corners, {0, 1, 2, 0, 2, 3}, [](const glm::vec3& p) {
    return glm::vec2((p.x + 4.0f) / 8.0f, (-1.5f - p.z) / 10.5f);
  });
  const Camera camera = perspectiveCamera(0.1f, 100.0f);
  const Frame frame = render(scene, camera, DebugView::TexCoord);
  ASSERT_EQ(frame.width, kWidth);
  ASSERT_EQ(frame.height, kHeight);

  const auto projected = ref::projectScene(scene, camera, kWidth, kHeight);
  ASSERT_EQ(projected.size(), 2u);
  const ref::CoverageImage coverage =
      ref::rasterizeCoverage(ref::gridTriangles(projected), kWidth, kHeight);
  const ref::ReferenceTracer tracer(scene, camera, kWidth, kHeight);
  const auto exactUv = [&](const glm::dvec2& at) { return rayPlaneUv(tracer, 0, at); };

  constexpr double kBound = 1e-4;
  double worstRay = 0, worstAffine = 0;
  int compared = 0, coverageMismatches = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const glm::dvec2 at = pixelCentre(x, y);
      const bool engineCovered = pixel(frame, x, y)[3] > 0.0f;
      const bool refCovered = coverage.at(x, y) > 0;
      // Window positions are computed in float by the engine: a vertex may
      // snap one grid unit away, which matters only this close to an edge.
      if (engineCovered != refCovered && ref::distanceToEdges(projected, at) > 1.0 / 128)
        ++coverageMismatches;
      if (!engineCovered || !refCovered) continue;
      ++compared;
      const ref::ProjectedTriangle& t = projected[coverage.lastTriangle[y * kWidth + x]];
      const glm::dvec2 got(pixel(frame, x, y)[0], pixel(frame, x, y)[1]);
      const double rayError = maxAbs(got - exactUv(at));
      worstRay = std::max(worstRay, rayError);
      worstAffine = std::max(worstAffine, maxAbs(affineUv(scene, t, at) - exactUv(at)));
      ASSERT_LE(rayError, kBound) << "pixel " << x << "," << y;
    }
  std::printf("[ perspective ] %d px: max error %.3g (ray-plane); affine interpolation %.3g\n",
              compared, worstRay, worstAffine);
  EXPECT_EQ(coverageMismatches, 0);
  EXPECT_GT(compared, 5000);
  // The test has teeth: skipping the perspective divide would fail it 100x over.
  EXPECT_GT(worstAffine, 100 * kBound);
}

struct ClipCase {
  const char* name;
  std::vector<glm::vec3> positions;
  UvOfPosition uvOf;
  Camera camera;
};

// Coverage and uv of a single triangle that the engine must clip: pixels
// farther than kMargin from every reference edge (the clipped polygon's edges
// may sit that far from where exact arithmetic puts them) must match the
// reference's coverage exactly, and their uv the exact ray-plane value to
// within kBound: the pieces of a clipped polygon all lie on the source
// triangle's plane, so their attribute planes are the source's.
void checkClippedTriangle(const ClipCase& c) {
  SCOPED_TRACE(c.name);
  constexpr double kMargin = 1.0 / 32;
  constexpr double kBound = 1e-4;
  const Scene scene = planeScene(c.positions, {0, 1, 2}, c.uvOf);
  FrameStats stats;
  const Frame count = render(scene, c.camera, DebugView::CoverageCount, &stats);
  const Frame uv = render(scene, c.camera, DebugView::TexCoord);
  EXPECT_GT(stats.clipped, 0u);  // the case exercises the clip stage

  const auto projected = ref::projectScene(scene, c.camera, kWidth, kHeight);
  const ref::CoverageImage coverage =
      ref::rasterizeCoverage(ref::gridTriangles(projected), kWidth, kHeight);
  const ref::ReferenceTracer tracer(scene, c.camera, kWidth, kHeight);
  const auto exactUv = [&](const glm::dvec2& at) { return rayPlaneUv(tracer, 0, at); };
  int covered = 0, nearEdge = 0, coverageMismatches = 0;
  double worstUv = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const glm::dvec2 at = pixelCentre(x, y);
      if (ref::distanceToEdges(projected, at) <= kMargin) {
        ++nearEdge;
        continue;
      }
      const int expected = coverage.at(x, y);
      if (pixel(count, x, y)[0] != float(expected)) {
        if (++coverageMismatches <= 5)
          ADD_FAILURE() << "coverage at " << x << "," << y << ": engine " << pixel(count, x, y)[0]
                        << ", reference " << expected;
        continue;
      }
      if (expected == 0) continue;
      ++covered;
      const glm::dvec2 got(pixel(uv, x, y)[0], pixel(uv, x, y)[1]);
      const double error = maxAbs(got - exactUv(at));
      worstUv = std::max(worstUv, error);
      EXPECT_LE(error, kBound) << "uv at " << x << "," << y;
    }
  std::printf("[ perspective ] %s: %d px covered, %d near edges, worst uv error %.3g\n", c.name,
              covered, nearEdge, worstUv);
  EXPECT_EQ(coverageMismatches, 0);
  EXPECT_GT(covered, 500);
}

// A ground triangle with two vertices 5 units behind the camera and 1e4 to
// either side, and its tip 60 ahead: the near plane (2 units) cuts it along a
// visible horizontal line; its long sides reach the view only near the tip.
TEST(Perspective, GroundTriangleBehindCameraClipsAtNearPlane) {
  checkClippedTriangle({"ground",
                        {{-1e4f, -0.5f, 5}, {1e4f, -0.5f, 5}, {0, -0.5f, -60}},
                        [](const glm::vec3& p) { return glm::vec2(p.x / 100, -p.z / 100); },
                        perspectiveCamera(2.0f, 0.0f)});
}

// A wall triangle 6 units ahead with one vertex 1e4 units to the side: the
// guard band, not the near plane, does the clipping.
TEST(Perspective, WallTriangleFarOutsideViewport) {
  checkClippedTriangle({"wall",
                        {{1e4f, 0.3f, -6}, {-3, -1, -6}, {-3, 2, -6}},
                        [](const glm::vec3& p) { return glm::vec2(p.x / 100, p.y / 10); },
                        perspectiveCamera(0.1f, 100.0f)});
}

// An oblique plane through the near plane, one vertex far behind and aside.
TEST(Perspective, ObliqueTriangleThroughNearPlane) {
  checkClippedTriangle(
      {"oblique",
       {{-5, -3, -4}, {6, 2, -20}, {3e3f, 1e3f, 2e3f}},
       [](const glm::vec3& p) { return glm::vec2(p.x / 50 + p.y / 70, p.z / 60 - p.x / 200); },
       perspectiveCamera(0.5f, 0.0f)});
}

}  // namespace
}  // namespace quadra
