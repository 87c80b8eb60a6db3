// Textures whose alpha is read: premultiplied filtering (no colour from
// transparent texels at edges or in mips) against double-precision
// expectations, coverage-preserving mip alpha for alpha-tested textures, and
// the shaded frame of such a texture against the reference tracer, on every
// kernel path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "lab/reference/reference_tracer.h"
#include "render_helpers.h"
#include "sampler_helpers.h"
#include "texture/mip_chain.h"
#include "texture/texture.h"

namespace quadra {
namespace {

constexpr int kDiscSize = 32;
constexpr double kDiscRadius = 0.3 * kDiscSize;  // texels

// An opaque white disc on fully transparent pure red: filtered straight, the
// red bleeds into the disc's edge.
std::shared_ptr<const Image> whiteDiscOnClearRed() {
  auto image = std::make_shared<Image>(kDiscSize, kDiscSize);
  for (int y = 0; y < kDiscSize; ++y)
    for (int x = 0; x < kDiscSize; ++x) {
      const double dx = x + 0.5 - 0.5 * kDiscSize, dy = y + 0.5 - 0.5 * kDiscSize;
      const bool inside = dx * dx + dy * dy < kDiscRadius * kDiscRadius;
      const float texel[4] = {1.0f, inside ? 1.0f : 0.0f, inside ? 1.0f : 0.0f,
                              inside ? 1.0f : 0.0f};
      std::copy_n(texel, 4, image->texel(x, y));
    }
  return image;
}

// Foliage-like: thin opaque strokes (one texel wide, in both directions, at
// seeded positions about every 16 texels) on transparent green.
std::shared_ptr<const Image> thinStrokes(int size, std::uint32_t seed) {
  auto image = std::make_shared<Image>(size, size);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> jitter(0, 15);
  std::vector<bool> column(std::size_t(size), false), row(std::size_t(size), false);
  for (int k = 0; k + 16 <= size; k += 16) {
    column[std::size_t(k + jitter(rng))] = true;
    row[std::size_t(k + jitter(rng))] = true;
  }
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float alpha = column[std::size_t(x)] || row[std::size_t(y)] ? 1.0f : 0.0f;
      const float texel[4] = {0.1f, 0.6f, 0.1f, alpha};
      std::copy_n(texel, 4, image->texel(x, y));
    }
  return image;
}

glm::dvec4 meanTexel(const Image& image, bool premultiply) {
  glm::dvec4 sum(0.0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* t = image.texel(x, y);
      const double weight = premultiply ? double(t[3]) : 1.0;
      sum += glm::dvec4(t[0] * weight, t[1] * weight, t[2] * weight, t[3]);
    }
  return sum / double(image.width * image.height);
}

TEST(TextureAlpha, PremultipliedMipsKeepLevelZerosMeanPremultipliedColour) {
  const Texture straight(whiteDiscOnClearRed(), samplerWith(WrapMode::ClampToEdge));
  const Texture& blended = straight.forAlpha({TextureAlpha::Use::Blended});
  ASSERT_NE(&blended, &straight);
  EXPECT_EQ(&blended, &straight.forAlpha({TextureAlpha::Use::Blended}));  // made once
  // The expectation in double from the straight level 0.
  const glm::dvec4 expected = meanTexel(straight.image(), true);
  const MipChain& mips = blended.mips();
  ASSERT_EQ(mips.levelCount(), 6);
  for (int level = 1; level < mips.levelCount(); ++level) {
    const glm::dvec4 mean = meanTexel(mips.level(level), false);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(mean[c], expected[c], 1e-6) << level << " " << c;
  }
  // Straight mips average the transparent red in: the test tells them apart.
  EXPECT_GT(meanTexel(straight.mips().level(1), false).r - expected.r, 0.5);
}

// Lookups on a ring across the disc's edge, every footprint the same size.
std::vector<Lookup> edgeLookups(double texelsPerPixel) {
  std::vector<Lookup> lookups;
  const float d = float(texelsPerPixel / kDiscSize);
  for (int i = 0; i < 360; ++i) {
    const double angle = 0.0174533 * i, radius = kDiscRadius - 2.0 + 4.0 * ((i * 7) % 360) / 360.0;
    const float u = float(0.5 + radius * std::cos(angle) / kDiscSize);
    const float v = float(0.5 + radius * std::sin(angle) / kDiscSize);
    lookups.push_back({u, v, d, 0.0f, 0.0f, d});
  }
  return lookups;
}

// The largest distance from white of the straight colour (rgb / a for a
// premultiplied lookup) of the lookups with alpha of at least 0.02.
double worstDistanceFromWhite(const std::vector<float>& rgba, bool premultiplied) {
  double worst = 0.0;
  for (std::size_t i = 0; i < rgba.size(); i += 4) {
    if (rgba[i + 3] < 0.02f) continue;
    const double divisor = premultiplied ? double(rgba[i + 3]) : 1.0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(rgba[i + c] / divisor - 1.0));
  }
  return worst;
}

TEST(TextureAlpha, NoFringeFromTransparentTexelsMagnifiedOrMinified) {
  const SamplerState sampler = samplerWith(WrapMode::ClampToEdge);
  const Texture straight(whiteDiscOnClearRed(), sampler);
  const Texture& blended = straight.forAlpha({TextureAlpha::Use::Blended});
  const std::vector<Lookup> magnified = edgeLookups(0.25), minified = edgeLookups(4.0);
  // Every texel with alpha above 0 is white, so the double-precision
  // premultiplied lookup's straight colour is exactly white: the expectation.
  for (const Lookup& l : magnified) {
    const glm::dvec4 exact =
        ref::sampleBilinearPremultiplied(straight.image(), sampler, {l[0], l[1]});
    if (exact.a > 0.0) {
      ASSERT_EQ(exact, glm::dvec4(1.0, 1.0, 1.0, exact.a));
    }
  }
  for (Isa isa : supportedIsas()) {
    SCOPED_TRACE(isaName(isa));
    const std::vector<float> bilinear = sampleAll(blended, Filter::Bilinear, isa, magnified);
    const std::vector<float> trilinear = sampleAll(blended, Filter::Trilinear, isa, minified);
    // Float rounding of rgb·a and of the weights, divided by alpha >= 0.02.
    EXPECT_LE(worstDistanceFromWhite(bilinear, true), 1e-5);
    EXPECT_LE(worstDistanceFromWhite(trilinear, true), 1e-5);
    // The magnified lookups match the double-precision ones in alpha.
    for (std::size_t i = 0; i < magnified.size(); ++i) {
      const Lookup& l = magnified[i];
      EXPECT_NEAR(bilinear[i * 4 + 3],
                  ref::sampleBilinearPremultiplied(straight.image(), sampler, {l[0], l[1]}).a,
                  1e-5);
    }
    // Filtered straight, the same lookups are red at the edge.
    EXPECT_GT(worstDistanceFromWhite(sampleAll(straight, Filter::Trilinear, isa, minified), false),
              0.3);
  }
}

// Every filter reads levels built from the premultiplied level 0 (mips,
// ripmap, summed-area table): minified across the disc's edge, the straight
// colour stays white on each, where the straight levels turn it red (on
// every filter that averages texels).
TEST(TextureAlpha, EveryFilterReadsPremultipliedLevels) {
  const Texture straight(whiteDiscOnClearRed(), samplerWith(WrapMode::ClampToEdge));
  const Texture& blended = straight.forAlpha({TextureAlpha::Use::Blended});
  std::vector<Lookup> lookups = edgeLookups(3.0);
  for (const Lookup& l : edgeLookups(3.0))
    lookups.push_back({l[0], l[1], l[2] * 4.0f, 0.0f, 0.0f, l[5]});
  for (Filter filter : {Filter::Nearest, Filter::NearestMip, Filter::Anisotropic, Filter::Ewa,
                        Filter::Area, Filter::SummedArea, Filter::Ripmap}) {
    SCOPED_TRACE(filterName(filter));
    for (Isa isa : supportedIsas()) {
      SCOPED_TRACE(isaName(isa));
      // 1e-4 leaves room for the summed-area table's fixed point, which
      // rounds rgb and alpha apart (summed_area.h).
      EXPECT_LE(worstDistanceFromWhite(sampleAll(blended, filter, isa, lookups), true), 1e-4);
    }
    if (filter == Filter::Nearest) continue;  // one texel a lookup: nothing to bleed
    EXPECT_GT(worstDistanceFromWhite(sampleAll(straight, filter, Isa::Scalar, lookups), false),
              0.3);
  }
}

// Levels whose texels are smaller than the strokes' spacing (16 level-0
// texels) are held to the bound; on coarser ones every texel holds the same
// share of stroke, so the alpha test keeps all of the level or none.
constexpr int kSmallestBoundLevel = 32;
constexpr double kCoverageTolerance = 0.03;

TEST(TextureAlpha, AlphaTestedCoverageHoldsDownTheMipChain) {
  constexpr float kCutoff = 0.5f;
  const Texture straight(thinStrokes(256, 7), SamplerState{});
  const Texture& tested = straight.forAlpha({TextureAlpha::Use::Tested, kCutoff});
  const Texture& blended = straight.forAlpha({TextureAlpha::Use::Blended});
  const double coverage0 = alphaCoverage(straight.image(), kCutoff);
  ASSERT_GT(coverage0, 0.05);
  double thinnest = 1.0;  // the smallest level coverage without the fix, over level 0's
  int checked = 0;
  for (int level = 1; level < tested.mips().levelCount(); ++level) {
    const Image& image = tested.mips().level(level);
    if (image.width < kSmallestBoundLevel) break;
    EXPECT_NEAR(alphaCoverage(image, kCutoff), coverage0, kCoverageTolerance) << "level " << level;
    const double unscaled = alphaCoverage(blended.mips().level(level), kCutoff);
    std::printf("[ coverage ] level %d: %.4f kept, %.4f without the rescale (level 0 %.4f)\n",
                level, alphaCoverage(image, kCutoff), unscaled, coverage0);
    thinnest = std::min(thinnest, unscaled / coverage0);
    ++checked;
  }
  EXPECT_EQ(checked, 3);
  // Without the rescale the strokes thin out to nothing: the bound above fails.
  EXPECT_LT(thinnest, 0.1);
  // The straight colour of every scaled texel is kept.
  const Image& level2 = tested.mips().level(2);
  for (int y = 0; y < level2.height; ++y)
    for (int x = 0; x < level2.width; ++x) {
      const float* t = level2.texel(x, y);
      if (t[3] > 0.0f) {
        ASSERT_NEAR(t[1] / t[3], 0.6, 1e-5);
      }
    }
}

// The disc texture on a square filling an orthographic view, magnified 4x;
// alphaMode chooses how its alpha is read.
Scene discScene(AlphaMode mode) {
  Scene scene;
  Mesh quad;
  quad.positions = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}};
  quad.texcoords[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = 0;
  Material material;
  material.baseColorTexture = 0;
  material.alphaMode = mode;
  scene.materials.push_back(material);
  scene.textures.push_back(
      std::make_shared<Texture>(whiteDiscOnClearRed(), samplerWith(WrapMode::ClampToEdge)));
  scene.meshes.push_back(quad);
  scene.instances.push_back(Instance{});
  return scene;
}

TEST(TextureAlpha, ShadedDiscMatchesTheReferenceTracerOnEveryPath) {
  constexpr int kSize = 4 * kDiscSize;
  Camera camera;
  camera.type = Camera::Type::Orthographic;
  camera.zfar = 10.0f;
  RenderSettings settings;
  settings.width = settings.height = kSize;
  settings.filter = Filter::Bilinear;
  for (AlphaMode mode : {AlphaMode::Blend, AlphaMode::Mask}) {
    const Scene scene = discScene(mode);
    const ref::ReferenceTracer tracer(scene, camera, kSize, kSize);
    std::vector<ref::TracerHit> scratch;
    for (Isa isa : supportedIsas()) {
      SCOPED_TRACE(std::string(isaName(isa)) + (mode == AlphaMode::Mask ? " mask" : " blend"));
      const Frame frame = renderOnce(scene, camera, settings, 2, isa);
      double worst = 0.0;
      int edgePixels = 0;
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          const glm::dvec4 expected = tracer.shade({x + 0.5, y + 0.5}, scratch);
          const float* got = &frame.rgba[(std::size_t(y) * kSize + std::size_t(x)) * 4];
          // A mask pixel whose alpha is this close to the cutoff may go either way.
          const glm::dvec2 uv = glm::dvec2(x + 0.5, y + 0.5) / double(kSize);
          const double alpha = ref::sampleBilinearPremultiplied(scene.textures[0]->image(),
                                                                scene.textures[0]->sampler(), uv)
                                   .a;
          if (mode == AlphaMode::Mask && std::abs(alpha - 0.5) < 1e-3) continue;
          for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(got[c] - expected[c]));
          // The straight colour at the edge is white: no red fringe.
          if (got[3] > 0.02f && got[3] < 0.98f) {
            ++edgePixels;
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c] / got[3], 1.0, 1e-4);
          }
        }
      EXPECT_LE(worst, 1e-4);
      EXPECT_EQ(edgePixels > 0, mode == AlphaMode::Blend);
    }
  }
}

}  // namespace
}  // namespace quadra
