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

}  // namespace
}  // namespace quadra
