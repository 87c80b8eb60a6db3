// Setup's culling and its counters: each kind of triangle the front end drops
// (degenerate, NaN/Inf, back-facing, outside) is counted once and draws
// nothing, and a good triangle beside them still draws exactly its pixels.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "api/renderer.h"
#include "render_helpers.h"

namespace quadra {
namespace {

constexpr int kSize = 64;

// Orthographic camera mapping world (x, y) in [-32, 32] to the 64x64 window.
Camera pixelCamera() {
  Camera camera;
  camera.type = Camera::Type::Orthographic;
  camera.ymag = kSize / 2.0f;
  camera.znear = 0.5f;
  camera.zfar = 10.0f;
  camera.world[3] = glm::vec4(0.0f, 0.0f, 5.0f, 1.0f);
  return camera;
}

struct Counted {
  FrameStats stats;
  double coverage = 0.0;  // sum of per-pixel coverage counts
};

Counted renderTriangles(const std::vector<glm::vec3>& positions, bool doubleSided = false) {
  Scene scene;
  Mesh mesh;
  mesh.positions = positions;
  for (std::uint32_t i = 0; i < positions.size(); ++i) mesh.indices.push_back(i);
  mesh.material = 0;
  Material material;
  material.doubleSided = doubleSided;
  scene.materials.push_back(material);
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, glm::mat4(1.0f)});
  RenderSettings settings;
  settings.width = settings.height = kSize;
  settings.debugView = DebugView::CoverageCount;
  Counted c;
  const Frame frame = renderOnce(scene, pixelCamera(), settings, 2, std::nullopt, &c.stats);
  for (int i = 0; i < kSize * kSize; ++i) c.coverage += frame.rgba[std::size_t(i) * 4];
  return c;
}

// A counter-clockwise (front-facing) right triangle with legs of `leg` pixels.
std::vector<glm::vec3> frontTriangle(float x, float y, float leg) {
  return {{x, y, 0.0f}, {x + leg, y, 0.0f}, {x, y + leg, 0.0f}};
}

TEST(SetupCounters, GoodTriangleCoversItsAnalyticPixelCount) {
  // Legs of 16 px from a pixel corner: 120 pixel centres lie strictly inside
  // and 16 exactly on the hypotenuse, which the fill rule may or may not
  // take, so the count lies between 120 and 136 whatever the tie rule.
  const Counted c = renderTriangles(frontTriangle(-8.0f, -8.0f, 16.0f));
  EXPECT_EQ(c.stats.trianglesIn, 1u);
  EXPECT_EQ(c.stats.trianglesDrawn, 1u);
  EXPECT_GE(c.coverage, 120.0);
  EXPECT_LE(c.coverage, 136.0);
}

TEST(SetupCounters, EachDroppedKindIsCountedAndDrawsNothing) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const Counted good = renderTriangles(frontTriangle(-8.0f, -8.0f, 16.0f));
  std::vector<glm::vec3> p = frontTriangle(-8.0f, -8.0f, 16.0f);
  const std::vector<glm::vec3> extra[] = {
      {{0, 0, 0}, {4, 4, 0}, {8, 8, 0}},                    // collinear: degenerate
      {{1, 1, 0}, {1, 1, 0}, {5, 9, 0}},                    // repeated vertex: degenerate
      {{nan, 0, 0}, {5, 0, 0}, {0, 5, 0}},                  // NaN position
      {{0, 0, 0}, {inf, 0, 0}, {0, 5, 0}},                  // Inf position
      {{-10, -10, 0}, {-10, 5, 0}, {5, -10, 0}},            // clockwise: back face
      {{100, 100, 0}, {120, 100, 0}, {100, 120, 0}},        // outside the view
      {{0.1f, 0.1f, 0}, {0.3f, 0.1f, 0}, {0.1f, 0.3f, 0}},  // no pixel centre inside
  };
  for (const auto& tri : extra) p.insert(p.end(), tri.begin(), tri.end());
  const Counted c = renderTriangles(p);
  EXPECT_EQ(c.stats.trianglesIn, 8u);
  EXPECT_EQ(c.stats.trianglesDrawn, 1u);
  EXPECT_EQ(c.stats.droppedDegenerate, 2u);
  EXPECT_EQ(c.stats.droppedInvalid, 2u);
  EXPECT_EQ(c.stats.culledBackFace, 1u);
  EXPECT_EQ(c.stats.culledOutside, 2u);
  EXPECT_EQ(c.coverage, good.coverage);
}

TEST(SetupCounters, DoubleSidedKeepsBackFaces) {
  const std::vector<glm::vec3> back = {{-10, -10, 0}, {-10, 5, 0}, {5, -10, 0}};
  EXPECT_EQ(renderTriangles(back, false).stats.culledBackFace, 1u);
  const Counted kept = renderTriangles(back, true);
  EXPECT_EQ(kept.stats.trianglesDrawn, 1u);
  EXPECT_GT(kept.coverage, 0.0);
}

// The stage times account for the frame: none negative, and together no more
// than the render call's own wall time (they are measured inside it).
TEST(FrameStats, StagesAreWithinTheFrame) {
  Scene scene;
  Mesh mesh;
  for (int i = 0; i < 3000; ++i) {
    const float x = float(i % 60) - 30.0f, y = float(i / 60) - 25.0f;
    mesh.positions.insert(mesh.positions.end(), {{x, y, 0}, {x + 1.5f, y, 0}, {x, y + 1.5f, 0}});
  }
  for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) mesh.indices.push_back(i);
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, glm::mat4(1.0f)});
  RendererConfig config;
  config.threads = 2;
  Renderer renderer(config);
  Frame frame;
  RenderSettings settings;
  settings.width = settings.height = kSize;
  for (int round = 0; round < 3; ++round) {
    const auto start = std::chrono::steady_clock::now();
    const StageTimes t = renderer.render(scene, pixelCamera(), settings, frame).stages;
    const double wall =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const double parts[] = {t.draws, t.vertex, t.setup, t.bin, t.raster, t.shade, t.resolve};
    double sum = 0.0;
    for (double part : parts) {
      EXPECT_GE(part, 0.0);
      sum += part;
    }
    EXPECT_LE(sum, wall * (1.0 + 1e-9)) << "round " << round;
    EXPECT_GT(t.raster, 0.0);
  }
}

}  // namespace
}  // namespace quadra
