// Blended surfaces composited per sample in depth order
// (engine/tile/blended_fragments.h): the store against a double-precision
// "over" of the sorted fragments, and whole frames of interpenetrating and
// self-overlapping transparent surfaces against the reference tracer's exact
// compositing and against themselves drawn in another order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"
#include "render_helpers.h"
#include "tile/blended_fragments.h"
#include "tile/tile_kernel.h"

namespace quadra {
namespace {

struct Layer {
  float depth;
  glm::vec4 color;  // straight colour and alpha
};

// "Over" of the layers far to near onto `base`, in double; equal depths in
// the order given.
glm::dvec4 exactOver(std::vector<Layer> layers, glm::dvec4 base, bool depthGreater) {
  std::stable_sort(layers.begin(), layers.end(), [&](const Layer& a, const Layer& b) {
    return depthGreater ? a.depth < b.depth : a.depth > b.depth;
  });
  for (const Layer& l : layers) {
    const double a = l.color.a;
    base = glm::dvec4(glm::dvec3(l.color) * a, a) + base * (1.0 - a);
  }
  return base;
}

// The layers through the store at pixel 5 of plane 1 of a 2-plane tile, in
// the order given, all kept (as the order pass marks them late).
glm::dvec4 throughStore(const std::vector<Layer>& layers, glm::vec4 base, bool depthGreater) {
  static TileBuffers planes[2];
  constexpr int kPixel = 5;
  BlendedFragments store;
  store.begin(2, depthGreater);
  for (int c = 0; c < 4; ++c) planes[1].color[c][kPixel] = base[c];
  for (const Layer& l : layers) {
    const float a = l.color.a;
    const float premultiplied[4] = {l.color.r * a, l.color.g * a, l.color.b * a, a};
    const float* const color[4] = {&premultiplied[0], &premultiplied[1], &premultiplied[2],
                                   &premultiplied[3]};
    const float keep = 1.0f - a;
    store.add(1, kPixel, 1u, &l.depth, color, &keep);  // lane 0 alone
  }
  tileKernels(Isa::Scalar).compositeBlended(store, planes);
  EXPECT_TRUE(store.empty());
  glm::dvec4 out;
  for (int c = 0; c < 4; ++c) out[c] = planes[1].color[c][kPixel];
  return out;
}

std::vector<Layer> randomLayers(int count, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Layer> layers;
  for (int i = 0; i < count; ++i)
    layers.push_back({unit(rng), {unit(rng), unit(rng), unit(rng), 0.2f + 0.6f * unit(rng)}});
  return layers;
}

double largestDifference(const glm::dvec4& a, const glm::dvec4& b) {
  const glm::dvec4 d = glm::abs(a - b);
  return std::max({d.r, d.g, d.b, d.a});
}

TEST(BlendedFragments, CompositeAnyArrivalOrderFarToNear) {
  std::mt19937 rng(11);
  const glm::vec4 base(0.2f, 0.5f, 0.7f, 1.0f);
  for (const bool depthGreater : {false, true})
    for (int count = 1; count <= BlendedFragments::kMaxPerSample; ++count)
      for (int trial = 0; trial < 20; ++trial) {
        std::vector<Layer> layers = randomLayers(count, rng);
        std::shuffle(layers.begin(), layers.end(), rng);
        const double error = largestDifference(throughStore(layers, base, depthGreater),
                                               exactOver(layers, base, depthGreater));
        ASSERT_LT(error, 1e-6) << count << " layers, depthGreater " << depthGreater;
      }
}

TEST(BlendedFragments, EqualDepthsKeepTheirArrivalOrder) {
  const glm::vec4 base(0.0f, 0.0f, 0.0f, 1.0f);
  const std::vector<Layer> redThenBlue = {{0.5f, {1, 0, 0, 0.5f}}, {0.5f, {0, 0, 1, 0.5f}}};
  const glm::dvec4 out = throughStore(redThenBlue, base, false);
  EXPECT_EQ(out.r, 0.25);  // red first, then half of it covered by blue
  EXPECT_EQ(out.b, 0.5);
}

// Beyond the budget the two farthest fragments merge: exact while every
// later fragment lies beyond both (front to back, the order a sorted draw
// list reversed sends), which keeps the merged step's place right.
TEST(BlendedFragments, BeyondTheBudgetFrontToBackStaysExact) {
  std::mt19937 rng(5);
  const glm::vec4 base(0.9f, 0.1f, 0.3f, 1.0f);
  for (int count : {BlendedFragments::kMaxPerSample + 1, 20, 100}) {
    std::vector<Layer> layers = randomLayers(count, rng);
    std::sort(layers.begin(), layers.end(),
              [](const Layer& a, const Layer& b) { return a.depth < b.depth; });
    const double error =
        largestDifference(throughStore(layers, base, false), exactOver(layers, base, false));
    EXPECT_LT(error, 1e-5) << count << " layers";
  }
}

// A lane group's samples are sorted at once (compositeBlended): samples
// holding from none to over the budget of fragments side by side, with
// equal depths among them, composite as each alone would, on every ISA and
// to the same bits.
TEST(BlendedFragments, ALaneGroupOfMixedCountsCompositesAlikeOnEveryIsa) {
  constexpr int kGroup = BlendedFragments::kGroupSlots, kFirst = 3 * kGroup, kPlane = 1;
  std::mt19937 rng(17);
  std::vector<std::vector<Layer>> perSample(kGroup);
  for (int k = 0; k < kGroup; ++k) {
    perSample[std::size_t(k)] = randomLayers(k % 11, rng);  // 0 to 10: over the budget of 8
    if (k % 3 == 0 && perSample[std::size_t(k)].size() > 2)
      perSample[std::size_t(k)][1].depth = perSample[std::size_t(k)][0].depth;
  }
  const glm::vec4 base(0.3f, 0.6f, 0.1f, 1.0f);
  static TileBuffers planes[2];
  std::vector<float> firstIsa;
  for (const Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
    if (!isaSupported(isa)) continue;
    BlendedFragments store;
    store.begin(2, false);
    for (int k = 0; k < kGroup; ++k)
      for (int c = 0; c < 4; ++c) planes[kPlane].color[c][kFirst + k] = base[c];
    // Arrival interleaved across the samples, as a triangle's pixels in turn.
    for (std::size_t layer = 0; layer < 10; ++layer)
      for (int k = 0; k < kGroup; ++k) {
        if (layer >= perSample[std::size_t(k)].size()) continue;
        const Layer& l = perSample[std::size_t(k)][layer];
        const float a = l.color.a, keep = 1.0f - a;
        const float premultiplied[4] = {l.color.r * a, l.color.g * a, l.color.b * a, a};
        const float* const color[4] = {&premultiplied[0], &premultiplied[1], &premultiplied[2],
                                       &premultiplied[3]};
        store.add(kPlane, kFirst + k, 1u, &l.depth, color, &keep);
      }
    tileKernels(isa).compositeBlended(store, planes);
    EXPECT_TRUE(store.empty());
    std::vector<float> out;
    for (int k = 0; k < kGroup; ++k) {
      glm::dvec4 got;
      for (int c = 0; c < 4; ++c)
        out.push_back(float(got[c] = planes[kPlane].color[c][kFirst + k]));
      const std::vector<Layer>& layers = perSample[std::size_t(k)];
      EXPECT_EQ(got, throughStore(layers, base, false)) << "sample " << k << ", isa " << int(isa);
      if (layers.size() <= std::size_t(BlendedFragments::kMaxPerSample)) {  // else merged
        EXPECT_LT(largestDifference(got, exactOver(layers, base, false)), 1e-6)
            << "sample " << k << ", " << layers.size() << " layers, isa " << int(isa);
      }
    }
    if (firstIsa.empty()) firstIsa = out;
    EXPECT_EQ(std::memcmp(out.data(), firstIsa.data(), out.size() * sizeof(float)), 0)
        << "isa " << int(isa);
  }
}

// One store serves a worker's tiles in turn, at whatever plane count each
// frame has: what one tile kept must not reach the next.
TEST(BlendedFragments, AReusedStoreStartsEachTileEmpty) {
  std::mt19937 rng(3);
  static TileBuffers planes[4];
  BlendedFragments reused;
  const auto addLayers = [&](int plane, const std::vector<Layer>& layers) {
    for (const Layer& l : layers) {
      const float a = l.color.a, keep = 1.0f - a;
      const float premultiplied[4] = {l.color.r * a, l.color.g * a, l.color.b * a, a};
      const float* const color[4] = {&premultiplied[0], &premultiplied[1], &premultiplied[2],
                                     &premultiplied[3]};
      reused.add(plane, 9, 1u, &l.depth, color, &keep);
    }
  };
  int tile = 0;
  for (const int planeCount : {2, 2, 4, 1, 4, 4}) {
    const int plane = planeCount - 1;
    reused.begin(planeCount, false);
    if (tile++ % 2 == 1) {
      // A tile whose kept fragments were never composited: begin clears them too.
      addLayers(plane, randomLayers(3, rng));
      reused.begin(planeCount, false);
      EXPECT_TRUE(reused.empty());
    }
    for (int c = 0; c < 4; ++c) planes[plane].color[c][9] = 0.25f;
    const std::vector<Layer> layers = randomLayers(5, rng);
    addLayers(plane, layers);
    tileKernels(Isa::Scalar).compositeBlended(reused, planes);
    const glm::dvec4 expected = exactOver(layers, glm::dvec4(0.25), false);
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(planes[plane].color[c][9], expected[c], 1e-6) << planeCount << " planes";
  }
}

// ---- frames --------------------------------------------------------------------

constexpr int kWidth = 160, kHeight = 90;

Frame renderAt(const Scene& scene, int samples, int threads = 2,
               std::optional<Isa> isa = std::nullopt) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.samples = samples;
  return renderOnce(scene, firstCameraOrDefault(scene), settings, threads, isa);
}

// The pixels inside surfaces: those whose 3x3 neighbourhood in the ideal
// frame varies by less than 0.05 in every channel, so edges (silhouettes and
// the lines where surfaces cross), which only samples resolve, are left out.
std::vector<bool> interiorOf(const Image& ideal) {
  std::vector<bool> inside(std::size_t(kWidth) * kHeight, false);
  for (int y = 1; y + 1 < kHeight; ++y)
    for (int x = 1; x + 1 < kWidth; ++x) {
      float spread = 0.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          for (int c = 0; c < 3; ++c)
            spread =
                std::max(spread, std::abs(ideal.texel(x + dx, y + dy)[c] - ideal.texel(x, y)[c]));
      inside[std::size_t(y) * kWidth + x] = spread < 0.05f;
    }
  return inside;
}

// PSNR (peak 1) over R, G, B of the pixels `inside`.
double interiorPsnr(const Frame& frame, const Image& ideal, const std::vector<bool>& inside) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t p = 0; p < inside.size(); ++p) {
    if (!inside[p]) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = double(frame.rgba[p * 4 + c]) - double(ideal.rgba[p * 4 + c]);
      sum += d * d;
      ++count;
    }
  }
  return 10.0 * std::log10(double(count) / sum);
}

TEST(BlendedOrder, TransparentSurfacesMatchTheExactComposite) {
  for (const std::string name : {"intersecting-glass", "overlapping-glass"}) {
    SCOPED_TRACE(name);
    const Scene scene = makeBuiltinScene(name);
    const Image ideal =
        ref::ReferenceTracer(scene, firstCameraOrDefault(scene), kWidth, kHeight).render(16);
    const std::vector<bool> inside = interiorOf(ideal);
    const auto insideCount = std::count(inside.begin(), inside.end(), true);
    ASSERT_GT(insideCount, kWidth * kHeight / 2);
    const double one = interiorPsnr(renderAt(scene, 1), ideal, inside);
    const double sixteen = interiorPsnr(renderAt(scene, 16), ideal, inside);
    std::printf("[ %s %dx%d, %ld interior pixels ] interior PSNR dB: 1 sample %.2f, 16 %.2f\n",
                name.c_str(), kWidth, kHeight, long(insideCount), one, sixteen);
    EXPECT_GE(sixteen, 45.0);
    EXPECT_GE(one, 45.0);
  }
}

// Reversing the order of the draws and of every mesh's triangles changes the
// order fragments arrive in, not the frame.
TEST(BlendedOrder, DrawAndTriangleOrderDoNotChangeTheFrame) {
  for (const std::string name : {"intersecting-glass", "overlapping-glass"}) {
    SCOPED_TRACE(name);
    const Scene scene = makeBuiltinScene(name);
    Scene reversed = scene;
    std::reverse(reversed.instances.begin() + 1, reversed.instances.end());  // the backdrop stays
    for (Mesh& mesh : reversed.meshes) {
      std::vector<std::uint32_t> triangles;
      for (std::size_t i = mesh.indices.size(); i >= 3; i -= 3)
        triangles.insert(triangles.end(), mesh.indices.begin() + std::ptrdiff_t(i - 3),
                         mesh.indices.begin() + std::ptrdiff_t(i));
      mesh.indices = triangles;
    }
    for (const int samples : {1, 4}) {
      const Frame a = renderAt(scene, samples), b = renderAt(reversed, samples);
      ASSERT_EQ(a.rgba.size(), b.rgba.size());
      std::size_t differing = 0;
      for (std::size_t i = 0; i < a.rgba.size(); ++i) differing += a.rgba[i] != b.rgba[i];
      EXPECT_EQ(differing, 0u) << samples << " samples";
    }
  }
}

// A tile whose blended triangles arrive far to near over all of it skips
// the order pass (tile_stage.cpp blendedArriveFarToNear); one where any
// arrives behind an earlier one must not. builtin:alpha-quads' five
// camera-facing quads (each at one depth: the exact, margin-free case),
// merged into one blended draw so that their triangles arrive in the
// mesh's order: near to far it must composite as far to near does, to the
// bit, at every sample count and in both depth directions.
TEST(BlendedOrder, LayersOfOneDrawArrivingNearToFarCompositeInDepthOrder) {
  const Scene quads = makeBuiltinScene("alpha-quads");
  const auto merged = [&](bool farFirst) {
    Scene scene = quads;
    Mesh layers;
    layers.material = quads.meshes[std::size_t(quads.instances[1].mesh)].material;
    for (std::size_t n = 1; n < quads.instances.size(); ++n) {
      const std::size_t i = farFirst ? n : quads.instances.size() - n;  // drawn far first
      const Instance& instance = quads.instances[i];
      const Mesh& quad = quads.meshes[std::size_t(instance.mesh)];
      const auto base = std::uint32_t(layers.positions.size());
      for (std::size_t v = 0; v < quad.positions.size(); ++v) {
        layers.positions.push_back(glm::vec3(instance.world * glm::vec4(quad.positions[v], 1.0f)));
        layers.texcoords[0].push_back(quad.texcoords[0][v]);
      }
      for (const std::uint32_t index : quad.indices) layers.indices.push_back(base + index);
    }
    scene.meshes.push_back(std::move(layers));
    scene.instances.resize(1);  // the opaque background
    scene.instances.push_back({int(scene.meshes.size() - 1), glm::mat4(1.0f)});
    return scene;
  };
  const Scene farToNear = merged(true), nearToFar = merged(false);
  for (const DepthMode depth : {DepthMode::Standard, DepthMode::Reversed})
    for (const int samples : {1, 4}) {
      RenderSettings settings;
      settings.width = kWidth;
      settings.height = kHeight;
      settings.samples = samples;
      settings.depth = depth;
      const Frame a = renderOnce(farToNear, firstCameraOrDefault(farToNear), settings);
      const Frame b = renderOnce(nearToFar, firstCameraOrDefault(nearToFar), settings);
      ASSERT_EQ(a.rgba.size(), b.rgba.size());
      EXPECT_EQ(std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)), 0)
          << samples << " samples, " << (depth == DepthMode::Reversed ? "reversed" : "standard");
    }
}

// The order pass and the kept fragments give every thread count and ISA the
// same bits.
TEST(BlendedOrder, IdenticalAcrossThreadsAndIsas) {
  const Scene scene = makeBuiltinScene("intersecting-glass");
  for (const int samples : {1, 4}) {
    const Frame expected = renderAt(scene, samples, 1, Isa::Scalar);
    for (const Isa isa : supportedIsas())
      for (const int threads : {1, 2}) {
        const Frame frame = renderAt(scene, samples, threads, isa);
        EXPECT_EQ(std::memcmp(frame.rgba.data(), expected.rgba.data(), frame.rgba.size() * 4), 0)
            << isaName(isa) << ", " << threads << " threads, " << samples << " samples";
      }
  }
}

}  // namespace
}  // namespace quadra
