// The clip stage (engine/clip) on edges whose ends are 1e30 apart: the crossings
// it makes must keep the exact relations every point of the infinite
// perspective projection satisfies (z_c = w_c - near), whichever end the
// polygon lists first; and whole frames of triangles at every scale from 0.1
// to 1e30, ahead and behind, against the exact reference rasterizer.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "api/camera.h"
#include "api/renderer.h"
#include "clip/clip.h"
#include "lab/reference/reference_raster.h"
#include "render_helpers.h"
#include "vertex/vertex_stage.h"

namespace quadra {
namespace {

using ClipCoords = std::array<float, 4>;

ClipCoords clipOf(const glm::mat4& projection, const glm::vec3& view) {
  const glm::vec4 c = projection * glm::vec4(view, 1.0f);
  return {c.x, c.y, c.z, c.w};
}

// Clips the triangle in each of its three rotations and checks every output
// vertex: in front of the near plane, inside the guard band, and on the
// projection's z_c = w_c - near line (so a vertex on the near plane has
// w = near, not the difference of two values ~1e30).
void expectExactCrossings(const std::array<glm::vec3, 3>& view) {
  Camera camera;
  camera.znear = 0.125f;  // exact in float, so z_c = w_c - near holds at the vertices
  camera.zfar = 0.0f;
  const Viewport viewport{256, 160};
  const glm::mat4 projection = projectionMatrix(camera, 256.0 / 160.0);
  double guardX, guardY;
  guardBand(viewport, guardX, guardY);
  for (int rotation = 0; rotation < 3; ++rotation) {
    std::array<ClipCoords, 3> coords;
    for (int i = 0; i < 3; ++i) coords[i] = clipOf(projection, view[(i + rotation) % 3]);
    const float* const vertices[3] = {coords[0].data(), coords[1].data(), coords[2].data()};
    ClipPolygon polygon;
    ASSERT_EQ(clipTriangle(vertices, 4, guardX, guardY, polygon), ClipResult::Clipped);
    ASSERT_GE(polygon.count, 3);
    for (int i = 0; i < polygon.count; ++i) {
      const double* v = polygon.vertices[i].v;
      const double scale = std::max({1.0, std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[3])});
      SCOPED_TRACE(::testing::Message() << "rotation " << rotation << ", vertex " << i << ": "
                                        << v[0] << " " << v[1] << " " << v[2] << " " << v[3]);
      EXPECT_GE(v[3], 0.125 * (1.0 - 1e-12));
      EXPECT_NEAR(v[2], v[3] - 0.125, 1e-12 * scale);
      EXPECT_LE(std::fabs(v[0]), guardX * v[3] * (1.0 + 1e-12));
      EXPECT_LE(std::fabs(v[1]), guardY * v[3] * (1.0 + 1e-12));
    }
  }
}

TEST(Clip, NearPlaneCrossingsOfEdgesToVerticesFarAhead) {
  // One vertex behind the eye, two 1e30 ahead and to the sides: both edges
  // from the near vertex cross the near plane a hair in front of the eye.
  expectExactCrossings(
      {glm::vec3(0.0f, -1.0f, 0.5f), {6e29f, -1.0f, -8e29f}, {-6e29f, -1.0f, -8e29f}});
}

TEST(Clip, EdgesBetweenVerticesFarAheadAndFarBehind) {
  // An edge from 1e30 ahead to 1e30 behind crosses w = 0 1e30 to the side;
  // the near vertex's edges cross the near plane next to the eye.
  expectExactCrossings(
      {glm::vec3(0.0f, -1.0f, 0.5f), {1e30f, -1.0f, -1e30f}, {1e30f, -1.0f, 1e30f}});
}

// 400 triangles whose vertices lie in random directions (ahead, behind, to
// the sides) at distances 10^k, k uniform in [-1, 30]: most are clipped by
// the near plane and the guard band, many span the eye. Their coverage must
// equal the exact reference's at every pixel centre farther than 1/128 px
// from a reference edge (float clip coordinates may snap a vertex one grid
// unit away), and no vertex may reach the window unprojectable.
TEST(Clip, TrianglesAtEveryScaleMatchTheReference) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<float> exponent(-1.0f, 30.0f), axis(-1.0f, 1.0f);
  Scene scene;
  Mesh mesh;
  for (int v = 0; v < 3 * 400; ++v) {
    glm::vec3 direction(axis(rng), axis(rng), axis(rng));
    while (glm::length(direction) < 0.1f) direction = {axis(rng), axis(rng), axis(rng)};
    mesh.positions.push_back(glm::normalize(direction) * std::pow(10.0f, exponent(rng)));
    mesh.indices.push_back(std::uint32_t(v));
  }
  Material material;
  material.doubleSided = true;
  scene.materials.push_back(material);
  mesh.material = 0;
  scene.meshes.push_back(mesh);
  scene.instances.push_back(Instance{});
  Camera camera;
  camera.yfov = 0.9f;
  camera.znear = 0.1f;
  camera.zfar = 0.0f;

  constexpr int kWidth = 256, kHeight = 160;
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.debugView = DebugView::CoverageCount;
  FrameStats stats;
  const Frame frame = renderOnce(scene, camera, settings, 2, std::nullopt, &stats);
  EXPECT_GT(stats.clipped, 150u);  // the clip stage is what is exercised
  EXPECT_GT(stats.trianglesDrawn, 200u);

  const auto projected = ref::projectScene(scene, camera, kWidth, kHeight);
  const ref::CoverageImage expected =
      ref::rasterizeCoverage(ref::gridTriangles(projected), kWidth, kHeight);
  int mismatches = 0, covered = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const float got = frame.rgba[(std::size_t(y) * kWidth + std::size_t(x)) * 4];
      covered += expected.at(x, y) > 0;
      if (got != float(expected.at(x, y)) &&
          ref::distanceToEdges(projected, {x + 0.5, y + 0.5}) > 1.0 / 128)
        if (++mismatches <= 5)
          ADD_FAILURE() << "pixel " << x << "," << y << ": engine " << got << ", reference "
                        << expected.at(x, y);
    }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(covered, kWidth * kHeight / 2);
}

}  // namespace
}  // namespace quadra
