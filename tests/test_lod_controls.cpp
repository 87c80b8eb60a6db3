// LOD bias and min/max LOD (OpenGL semantics: λ' = clamp(λ + bias, min, max))
// through the batch sampler, on every ISA path, against independent
// expectations: a bias of +1 is the footprint doubled, maxLod 0 is level-0
// bilinear, minLod 2 is the double-precision bilinear of mip level 2; and the
// nearest-texel mipmap filters against the texels of the levels they choose.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "lab/image/image_difference.h"
#include "lab/scene/builtin_scenes.h"
#include "lab/texture/ground_truth.h"
#include "lab/texture/test_textures.h"
#include "render_helpers.h"
#include "texture/mip_chain.h"
#include "texture/texture_sampler.h"

namespace quadra {
namespace {

struct Batch {
  std::vector<float> u, v, dudx, dvdx, dudy, dvdy;
  LookupBatch view() const {
    return {u.data(), v.data(), dudx.data(), dvdx.data(), dudy.data(), dvdy.data(), u.size()};
  }
};

// Random positions with isotropic footprints of `texelsPerPixel` on a 256^2 texture.
Batch makeBatch(int count, double texelsPerPixel, double scale = 1.0) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> position(0.05f, 0.95f), angle(0.0f, 6.2831853f);
  Batch b;
  for (int i = 0; i < count; ++i) {
    const float a = angle(rng), length = float(texelsPerPixel * scale / 256.0);
    b.u.push_back(position(rng));
    b.v.push_back(position(rng));
    b.dudx.push_back(length * std::cos(a));
    b.dvdx.push_back(length * std::sin(a));
    b.dudy.push_back(-length * std::sin(a));
    b.dvdy.push_back(length * std::cos(a));
  }
  return b;
}

std::vector<float> sample(const Texture& texture, const FilterSettings& settings, Isa isa,
                          const Batch& batch) {
  const TextureSampler sampler(texture, settings, isa);
  std::vector<float> rgba(batch.u.size() * 4);
  sampler.sample(batch.view(), 0, batch.u.size(), rgba.data());
  return rgba;
}

class LodControls : public ::testing::Test {
 protected:
  LodControls()
      : image_(std::make_shared<Image>(makeValueNoiseTexture(256, 256, 5))),
        texture_(image_, SamplerState{}) {}
  std::shared_ptr<const Image> image_;
  Texture texture_;
};

TEST_F(LodControls, BiasOfOneEqualsADoubledFootprint) {
  const Batch small = makeBatch(500, 3.0), doubled = makeBatch(500, 3.0, 2.0);
  for (Isa isa : supportedIsas()) {
    FilterSettings biased(Filter::Trilinear);
    biased.lodBias = 1.0f;
    const std::vector<float> a = sample(texture_, biased, isa, small);
    const std::vector<float> b = sample(texture_, FilterSettings(Filter::Trilinear), isa, doubled);
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
      worst = std::max(worst, double(std::fabs(a[i] - b[i])));
    // log2(2L) = log2(L) + 1 up to float rounding of the LOD (~1e-6 of a level).
    EXPECT_LT(worst, 1e-5) << isaName(isa);
    // And the bias matters: unbiased lookups of the small footprint differ.
    const std::vector<float> c = sample(texture_, FilterSettings(Filter::Trilinear), isa, small);
    double moved = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
      moved = std::max(moved, double(std::fabs(a[i] - c[i])));
    EXPECT_GT(moved, 0.01) << isaName(isa);
  }
}

TEST_F(LodControls, MaxLodZeroIsLevelZeroBilinear) {
  const Batch minified = makeBatch(500, 12.0);
  for (Isa isa : supportedIsas()) {
    FilterSettings clamped(Filter::Trilinear);
    clamped.maxLod = 0.0f;
    EXPECT_EQ(sample(texture_, clamped, isa, minified),
              sample(texture_, FilterSettings(Filter::Bilinear), isa, minified))
        << isaName(isa);
  }
}

TEST_F(LodControls, MinLodTwoReadsLevelTwoUnderMagnification) {
  const Batch magnified = makeBatch(500, 0.25);
  const MipChain& mips = texture_.mips();
  const BilinearReference level2(mips.level(2), SamplerState{});
  for (Isa isa : supportedIsas()) {
    FilterSettings floor(Filter::Trilinear);
    floor.minLod = 2.0f;
    const std::vector<float> got = sample(texture_, floor, isa, magnified);
    double worst = 0.0;
    for (std::size_t i = 0; i < magnified.u.size(); ++i) {
      double expected[4];
      level2.lookup(magnified.u[i], magnified.v[i], expected);
      for (int c = 0; c < 4; ++c)
        worst = std::max(worst, std::fabs(double(got[i * 4 + c]) - expected[c]));
    }
    // Float bilinear weights against double: a few ulps of values in [0, 1].
    EXPECT_LT(worst, 2e-6) << isaName(isa);
  }
}

// GL's magnification rule, λ + bias <= 0, decided at the footprint length
// 2^-bias: just inside it a nearest-magnifying sampler returns exactly the
// nearest texels; just outside it minifies (trilinear, nearly level 0).
TEST_F(LodControls, MagnificationEndsWhereTheBiasedFootprintReachesOneTexel) {
  SamplerState nearestMagnification;
  nearestMagnification.magLinear = false;
  const Texture texture(image_, nearestMagnification);
  // The box rule (the default) moves trilinear's level by kBoxLodOffset, so
  // magnification ends 2^-kBoxLodOffset texels later.
  for (const LodRule rule : {LodRule::Gl, LodRule::Box})
    for (const float bias : {-1.0f, 0.0f, 1.5f}) {
      const double offset = rule == LodRule::Box ? double(kBoxLodOffset) : 0.0;
      const double limit = std::exp2(-(double(bias) + offset));
      const Batch inside = makeBatch(300, limit * 0.999), outside = makeBatch(300, limit * 1.001);
      for (Isa isa : supportedIsas()) {
        FilterSettings biased;
        biased.lodBias = bias;
        biased.lodRule = rule;
        EXPECT_EQ(sample(texture, biased, isa, inside),
                  sample(texture, FilterSettings(Filter::Nearest), isa, inside))
            << isaName(isa) << " bias " << bias;
        const std::vector<float> minified = sample(texture, biased, isa, outside);
        const std::vector<float> bilinear =
            sample(texture, FilterSettings(Filter::Bilinear), isa, outside);
        const std::vector<float> nearest =
            sample(texture, FilterSettings(Filter::Nearest), isa, outside);
        double fromBilinear = 0.0, fromNearest = 0.0;
        for (std::size_t i = 0; i < minified.size(); ++i) {
          fromBilinear = std::max(fromBilinear, double(std::fabs(minified[i] - bilinear[i])));
          fromNearest = std::max(fromNearest, double(std::fabs(minified[i] - nearest[i])));
        }
        // λ' = log2(1.001) ≈ 0.0014: level 1 weighs in by that much at most.
        EXPECT_LT(fromBilinear, 2e-3) << isaName(isa) << " bias " << bias;
        EXPECT_GT(fromNearest, 0.05) << isaName(isa) << " bias " << bias;
      }
    }
}

// glTF's NEAREST_MIPMAP_NEAREST and NEAREST_MIPMAP_LINEAR (OpenGL's
// semantics): the nearest texel of the nearest level, or the nearest texels
// of the two levels around λ blended by its fraction; and, with linear
// magnification, bilinear level 0 up to λ = 0.5 (GL's switch-over point).
class NearestMipmaps : public LodControls {
 protected:
  Texture textureWith(Filter filter) const {
    SamplerState sampler;
    sampler.minFilter = filter;
    sampler.minLinear = false;
    return Texture(image_, sampler);
  }
  // The texel of mip level `level` whose square holds (u, v), in double.
  void nearestTexel(int level, float u, float v, double out[4]) const {
    const Image& image = texture_.mips().level(level);
    const float* t = image.texel(int(std::floor(double(u) * image.width)),
                                 int(std::floor(double(v) * image.height)));
    for (int c = 0; c < 4; ++c) out[c] = t[c];
  }
  static FilterSettings glRule() {
    FilterSettings settings;
    settings.lodRule = LodRule::Gl;
    return settings;
  }
};

TEST_F(NearestMipmaps, NearestMipmapNearestReadsTheNearestTexelOfTheNearestLevel) {
  const Texture texture = textureWith(Filter::NearestMip);
  // λ = log2(3) = 1.58 rounds to level 2, log2(5) = 2.32 to 2, log2(2.3) = 1.2 to 1.
  for (const auto& [texelsPerPixel, level] : {std::pair{3.0, 2}, {5.0, 2}, {2.3, 1}}) {
    const Batch batch = makeBatch(400, texelsPerPixel);
    for (Isa isa : supportedIsas()) {
      const std::vector<float> got = sample(texture, glRule(), isa, batch);
      for (std::size_t i = 0; i < batch.u.size(); ++i) {
        double expected[4];
        nearestTexel(level, batch.u[i], batch.v[i], expected);
        for (int c = 0; c < 4; ++c)
          ASSERT_EQ(got[i * 4 + c], float(expected[c]))
              << isaName(isa) << " lookup " << i << " at " << texelsPerPixel;
      }
    }
  }
}

TEST_F(NearestMipmaps, NearestMipmapLinearBlendsTheNearestTexelsOfTwoLevels) {
  const Texture texture = textureWith(Filter::Trilinear);
  for (const double texelsPerPixel : {3.0, 6.5}) {
    const double lod = std::log2(texelsPerPixel);
    const int fine = int(std::floor(lod));
    const Batch batch = makeBatch(400, texelsPerPixel);
    for (Isa isa : supportedIsas()) {
      const std::vector<float> got = sample(texture, glRule(), isa, batch);
      double worst = 0.0;
      for (std::size_t i = 0; i < batch.u.size(); ++i) {
        double a[4], b[4];
        nearestTexel(fine, batch.u[i], batch.v[i], a);
        nearestTexel(fine + 1, batch.u[i], batch.v[i], b);
        for (int c = 0; c < 4; ++c) {
          const double expected = a[c] + (b[c] - a[c]) * (lod - fine);
          worst = std::max(worst, std::fabs(double(got[i * 4 + c]) - expected));
        }
      }
      // The float LOD's rounding (~1e-6 of a level) times texel differences <= 1.
      EXPECT_LT(worst, 1e-5) << isaName(isa) << " at " << texelsPerPixel;
    }
  }
}

TEST_F(NearestMipmaps, LinearMagnificationHoldsUpToHalfALevel) {
  for (const Filter filter : {Filter::NearestMip, Filter::Trilinear}) {
    const Texture texture = textureWith(filter);
    // λ = log2(1.3) = 0.38: magnified by GL's rule, bilinear on level 0.
    const Batch below = makeBatch(300, 1.3);
    // λ = log2(1.6) = 0.68: minified, nearest texels (of level 1 for
    // nearest-mip; of levels 0 and 1 for the linear blend).
    const Batch above = makeBatch(300, 1.6);
    for (Isa isa : supportedIsas()) {
      EXPECT_EQ(sample(texture, glRule(), isa, below),
                sample(texture, FilterSettings(Filter::Bilinear), isa, below))
          << isaName(isa) << " " << filterName(filter);
      EXPECT_NE(sample(texture, glRule(), isa, above),
                sample(texture, FilterSettings(Filter::Bilinear), isa, above))
          << isaName(isa) << " " << filterName(filter);
    }
  }
}

// The box rule exists to bring trilinear frames nearer the ideal image (each
// pixel's footprint average of the bilinear texture, the area filter): on the
// ground plane to the horizon it must be nearer than GL's λ, which is in turn
// nearer than a level chosen 0.5 coarser (measured at 320x180: 23.34, 22.62
// and 20.43 dB).
TEST(LodRule, BoxRuleBringsTrilinearFramesNearerTheIdealImage) {
  const Scene scene = makeBuiltinScene("checker-plane");
  RenderSettings settings;
  settings.width = 320;
  settings.height = 180;
  settings.frameDepth = false;
  const auto render = [&](Filter filter, LodRule rule, float bias) {
    RenderSettings s = settings;
    s.filter = filter, s.lodRule = rule, s.lodBias = bias;
    const Frame frame = renderOnce(scene, scene.cameras[0], s);
    Image image(frame.width, frame.height);
    image.rgba = frame.rgba;
    return image;
  };
  const Image ideal = render(Filter::Area, LodRule::Box, 0.0f);
  const double box = imageDifference(render(Filter::Trilinear, LodRule::Box, 0.0f), ideal).psnr;
  const double gl = imageDifference(render(Filter::Trilinear, LodRule::Gl, 0.0f), ideal).psnr;
  const double coarse = imageDifference(render(Filter::Trilinear, LodRule::Gl, 0.5f), ideal).psnr;
  std::printf(
      "[ checker-plane 320x180 against the area filter: box %.2f dB, GL %.2f dB, "
      "GL + 0.5 %.2f dB ]\n",
      box, gl, coarse);
  EXPECT_GT(box, gl + 0.3);
  EXPECT_GT(gl, coarse);
}

}  // namespace
}  // namespace quadra
