// Heavy overdraw against a depth-buffered reference: the tile stage skips an
// 8x8 block where a triangle's depth lies behind everything the block holds
// (tile/tile_kernel_impl.h BlockDepthTest), which must change the work only,
// never a sample. Layers at one depth (ties: the first drawn stays), tilted
// triangles each in a depth slab of its own, drawn in random order over each
// other, partly off screen; every pixel's stored depth is compared with a
// double-precision z-buffer over the reference rasterizer's coverage.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

#include "lab/reference/reference_raster.h"
#include "lab/scene/hard_case_scenes.h"
#include "render_helpers.h"
#include "tile/tile_stage.h"

namespace quadra {
namespace {

// The hard cases' pixel-exact camera: world (x, y) lands on window
// (x + 128, 128 - y) exactly, so both sides snap the same positions.
constexpr int kSize = kPixelExactSize;

struct Layer {
  std::array<glm::dvec2, 3> window;
  std::array<float, 3> worldZ;
};

Scene sceneOf(const std::vector<Layer>& layers) {
  Mesh mesh;
  for (const Layer& layer : layers)
    for (int k = 0; k < 3; ++k) {
      mesh.indices.push_back(std::uint32_t(mesh.positions.size()));
      glm::vec3 world = worldFromWindow(layer.window[k].x, layer.window[k].y);
      world.z = layer.worldZ[k];
      mesh.positions.push_back(world);
    }
  return doubleSidedMeshScene(std::move(mesh));
}

// 48 even depth levels hold constant-depth triangles (several per level, so
// layers tie), 48 odd levels one tilted triangle each, within a third of the
// level spacing: no two triangles at different levels intersect, so which
// one is nearest at a pixel is decided by far more than float rounding.
std::vector<Layer> overdrawLayers(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> across(-60.0, kSize + 60.0);
  std::uniform_int_distribution<int> evenLevel(0, 47);
  std::uniform_real_distribution<double> tilt(-1.0 / 3.0, 1.0 / 3.0);
  constexpr double kNearZ = -0.7, kSpacing = 2.8 / 96.0;
  const auto snap = [](double p) { return std::round(p * 256.0) / 256.0; };
  const auto corner = [&] { return glm::dvec2(snap(across(rng)), snap(across(rng))); };
  std::vector<Layer> layers;
  for (int n = 0; n < 144; ++n) {
    Layer layer{{corner(), corner(), corner()}, {}};
    const int level = 2 * evenLevel(rng);
    for (float& z : layer.worldZ) z = float(kNearZ - kSpacing * level);
    layers.push_back(layer);
  }
  for (int level = 1; level < 96; level += 2) {
    Layer layer{{corner(), corner(), corner()}, {}};
    for (float& z : layer.worldZ) z = float(kNearZ - kSpacing * (level + tilt(rng)));
    layers.push_back(layer);
  }
  std::shuffle(layers.begin(), layers.end(), rng);
  return layers;
}

// The nearest depth at each pixel centre (standard depth, clear 1), first
// drawn on ties, from the reference's coverage and double-precision depth
// interpolated over the unsnapped window positions.
std::vector<double> referenceDepth(const Scene& scene, const Camera& camera) {
  const std::vector<ref::ProjectedTriangle> projected =
      ref::projectScene(scene, camera, kSize, kSize);
  std::vector<double> depth(std::size_t(kSize) * kSize, 1.0);
  for (const ref::ProjectedTriangle& t : projected) {
    const ref::GridTriangle grid = t.grid();
    const glm::dvec2 a = t.v[0].windowExact, b = t.v[1].windowExact, c = t.v[2].windowExact;
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (area == 0.0) continue;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        if (!ref::coversPixelCentre(grid, x, y)) continue;
        const glm::dvec2 p(x + 0.5, y + 0.5);
        const double wb = ((p.x - a.x) * (c.y - a.y) - (p.y - a.y) * (c.x - a.x)) / area;
        const double wc = ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / area;
        const double z = (1.0 - wb - wc) * t.v[0].depth + wb * t.v[1].depth + wc * t.v[2].depth;
        double& stored = depth[std::size_t(y) * kSize + x];
        if (z < stored) stored = z;
      }
  }
  return depth;
}

TEST(HierarchicalDepth, OverdrawKeepsTheNearestSampleOnEveryPath) {
  const Camera camera = pixelExactCamera();
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const Scene scene = sceneOf(overdrawLayers(seed));
    const std::vector<double> expected = referenceDepth(scene, camera);
    int covered = 0;
    for (double z : expected) covered += z < 1.0;
    ASSERT_GT(covered, kSize * kSize * 9 / 10) << "the layers should cover most of the frame";
    for (DepthMode mode : {DepthMode::Standard, DepthMode::Reversed}) {
      RenderSettings settings;
      settings.width = settings.height = kSize;
      settings.depth = mode;
      for (Isa isa : supportedIsas()) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed << " isa " << isaName(isa)
                                          << (mode == DepthMode::Reversed ? " reversed" : ""));
        const Frame frame = renderOnce(scene, camera, settings, 2, isa);
        ASSERT_EQ(frame.depth.size(), expected.size());
        int mismatches = 0;
        std::ostringstream first;
        for (std::size_t i = 0; i < expected.size(); ++i) {
          // Reversed orthographic depth is 1 - standard; the levels are 0.01
          // apart in depth, float depth is good to 1e-6.
          const double want = mode == DepthMode::Reversed ? 1.0 - expected[i] : expected[i];
          if (std::abs(frame.depth[i] - want) < 1e-4) continue;
          if (++mismatches <= 4)
            first << " (" << i % kSize << "," << i / kSize << "): " << frame.depth[i] << " want "
                  << want;
        }
        EXPECT_EQ(mismatches, 0) << "first:" << first.str();
      }
    }
  }
}

// `count` small triangles over the first tile, each flat in depth and colour,
// each nearer than the one before when backToFront (else the same triangles
// in the reverse order); colours[i] is triangle i's colour in the
// back-to-front order.
Scene stackOverOneTile(int count, bool backToFront, std::vector<glm::vec4>& colours) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> corner(0.0, 58.0), size(2.0, 6.0);
  const auto snap = [](double p) { return std::round(p * 256.0) / 256.0; };
  Mesh mesh;
  colours.clear();
  for (int i = 0; i < count; ++i) {
    const glm::dvec2 a(snap(corner(rng)), snap(corner(rng)));
    const double w = snap(size(rng)), h = snap(size(rng));
    const glm::dvec2 window[3] = {a, a + glm::dvec2(w, 0.0), a + glm::dvec2(0.0, h)};
    // Nearer as i grows, inside the camera's depth range (0.5 to 4).
    const float z = float(-3.9 + 3.3 * (i + 1) / (count + 1));
    const glm::vec4 colour(float(i % 61) / 60.0f, float(i / 61 % 59) / 58.0f,
                           float(i / 3599 % 7) / 6.0f, 1.0f);
    colours.push_back(colour);
    for (const glm::dvec2& point : window) {
      glm::vec3 world = worldFromWindow(point.x, point.y);
      world.z = z;
      mesh.positions.push_back(world);
      mesh.colors.push_back(colour);
    }
  }
  for (int i = 0; i < count; ++i) {
    const int source = backToFront ? i : count - 1 - i;
    for (int k = 0; k < 3; ++k) mesh.indices.push_back(std::uint32_t(3 * source + k));
  }
  return doubleSidedMeshScene(std::move(mesh));
}

// Drawn back to front, every triangle of a stack wins samples and is later
// overwritten: twice maxVisibleTriangles of them in one tile, so the
// visibility pass drops the overwritten ones as it goes (tile_stage.cpp
// dropOverwrittenTriangles) and renumbers the rest. At one sample each pixel
// must show the last-drawn triangle over its centre, by the reference's
// coverage; at 1 and 4 samples the frame must be the one the same triangles
// give drawn front to back, where only the first at a spot ever wins and
// nothing is dropped.
TEST(HierarchicalDepth, BackToFrontStacksDropTheirOverwrittenTriangles) {
  const Camera camera = pixelExactCamera();
  for (int samples : {1, 4}) {
    SCOPED_TRACE(::testing::Message() << samples << " samples");
    const int count = 2 * maxVisibleTriangles(samples) + 1000;
    std::vector<glm::vec4> colours;
    const Scene frontToBack = stackOverOneTile(count, false, colours);
    const Scene backToFront = stackOverOneTile(count, true, colours);
    RenderSettings settings;
    settings.width = settings.height = kSize;
    settings.samples = samples;
    settings.frameDepth = true;
    const Frame dropped = renderOnce(backToFront, camera, settings);
    const Frame kept = renderOnce(frontToBack, camera, settings);
    EXPECT_TRUE(dropped.rgba == kept.rgba) << "colour differs from the front-to-back frame";
    EXPECT_TRUE(dropped.depth == kept.depth) << "depth differs from the front-to-back frame";
    if (samples != 1) continue;
    // The last triangle drawn over each pixel centre, by the reference.
    std::vector<int> last(std::size_t(kSize) * kSize, -1);
    for (const ref::ProjectedTriangle& t : ref::projectScene(backToFront, camera, kSize, kSize)) {
      const ref::GridTriangle grid = t.grid();
      double minX = kSize, minY = kSize, maxX = 0.0, maxY = 0.0;
      for (const ref::ProjectedVertex& v : t.v) {
        minX = std::min(minX, v.windowExact.x), maxX = std::max(maxX, v.windowExact.x);
        minY = std::min(minY, v.windowExact.y), maxY = std::max(maxY, v.windowExact.y);
      }
      for (int y = std::max(0, int(minY) - 1); y <= std::min(kSize - 1, int(maxY) + 1); ++y)
        for (int x = std::max(0, int(minX) - 1); x <= std::min(kSize - 1, int(maxX) + 1); ++x)
          if (ref::coversPixelCentre(grid, x, y)) last[std::size_t(y) * kSize + x] = t.triangle;
    }
    int covered = 0, mismatches = 0;
    for (std::size_t p = 0; p < last.size(); ++p) {
      const glm::vec4 want = last[p] < 0 ? glm::vec4(0.0f) : colours[std::size_t(last[p])];
      covered += last[p] >= 0;
      for (int c = 0; c < 4; ++c)
        if (std::abs(dropped.rgba[4 * p + std::size_t(c)] - want[c]) > 1e-5f) {
          if (++mismatches <= 4)
            ADD_FAILURE() << "pixel (" << p % kSize << "," << p / kSize << ") channel " << c << ": "
                          << dropped.rgba[4 * p + std::size_t(c)] << ", want " << want[c]
                          << " (triangle " << last[p] << ")";
          break;
        }
    }
    EXPECT_GT(covered, 3000) << "the stack should cover most of its tile";
    EXPECT_EQ(mismatches, 0);
  }
}

}  // namespace
}  // namespace quadra
