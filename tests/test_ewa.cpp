// EWA through the batch sampler: exact on a constant texture, finite and in
// range for hostile inputs (NaN/Inf, zero and enormous footprints), identical
// on every ISA path, and closer to the box ground truth than bilinear on
// minified footprints.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "lab/texture/ground_truth.h"
#include "lab/texture/test_textures.h"
#include "sampler_helpers.h"
#include "texture/texture_sampler.h"

namespace quadra {
namespace {

TEST(Ewa, ConstantTextureIsReproducedExactly) {
  auto image = std::make_shared<Image>(64, 64);
  for (std::size_t i = 0; i < image->rgba.size(); i += 4) {
    image->rgba[i] = 0.25f, image->rgba[i + 1] = 0.5f, image->rgba[i + 2] = 0.75f;
    image->rgba[i + 3] = 1.0f;
  }
  const Texture texture(image, SamplerState{});
  const std::vector<float> got =
      sampleAll(texture, Filter::Ewa, Isa::Scalar, randomLookups(300, 3));
  for (std::size_t i = 0; i < got.size(); i += 4) {
    EXPECT_NEAR(got[i], 0.25f, 1e-6f);
    EXPECT_NEAR(got[i + 2], 0.75f, 1e-6f);
  }
}

TEST(Ewa, HostileInputsStayFiniteAndInRange) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(37, 5, 9));
  for (WrapMode wrap : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge,
                        WrapMode::ClampToBorder}) {
    SamplerState state;
    state.wrapU = state.wrapV = wrap;
    const Texture texture(image, state);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = INFINITY;
    const std::vector<Lookup> lookups = {{nan, 0.5f, 0.01f, 0, 0, 0.01f},
                                         {0.5f, inf, 0.01f, 0, 0, 0.01f},
                                         {0.5f, 0.5f, nan, nan, nan, nan},
                                         {0.5f, 0.5f, inf, 0, 0, inf},
                                         {0.5f, 0.5f, 0, 0, 0, 0},
                                         {1e4f, -1e4f, 1e3f, 0, 0, 1e-3f},
                                         {0.3f, 0.7f, 1e6f, 1e6f, -1e6f, 1e6f}};
    for (const float value : sampleAll(texture, Filter::Ewa, Isa::Scalar, lookups)) {
      EXPECT_TRUE(std::isfinite(value)) << wrapName(wrap);
      EXPECT_GE(value, -1e-6f);
      EXPECT_LE(value, 1.0f + 1e-6f);
    }
  }
}

TEST(Ewa, EveryIsaMatchesScalar) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(128, 96, 4));
  const Texture texture(image, SamplerState{});
  const auto lookups = randomLookups(200, 5);
  const std::vector<float> scalar = sampleAll(texture, Filter::Ewa, Isa::Scalar, lookups);
  for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
    if (isaSupported(isa)) {
      EXPECT_EQ(sampleAll(texture, Filter::Ewa, isa, lookups), scalar) << isaName(isa);
    }
  }
}

TEST(Ewa, BeatsBilinearOnMinifiedFootprints) {
  const auto image = std::make_shared<Image>(makeCheckerTexture(128, 128, 2));
  const Texture texture(image, SamplerState{});
  const BilinearReference reference(*image, SamplerState{});
  std::vector<Lookup> lookups;
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> position(0.0f, 1.0f), angle(0.0f, 6.2831853f);
  for (int i = 0; i < 150; ++i) {  // isotropic footprints of 8 texels
    const float a = angle(rng), length = 8.0f / 128.0f;
    lookups.push_back({position(rng), position(rng), length * std::cos(a), length * std::sin(a),
                       -length * std::sin(a), length * std::cos(a)});
  }
  const auto error = [&](Filter filter) {
    const std::vector<float> got = sampleAll(texture, filter, Isa::Scalar, lookups);
    double sum = 0.0;
    for (std::size_t i = 0; i < lookups.size(); ++i) {
      const auto& l = lookups[i];
      const Footprint footprint{l[0], l[1], l[2], l[3], l[4], l[5]};
      const GroundTruthValue truth = groundTruth(reference, footprint);
      const double d = got[i * 4] - truth.rgba[0];
      sum += d * d;
    }
    return std::sqrt(sum / double(lookups.size()));
  };
  const double ewa = error(Filter::Ewa), bilinear = error(Filter::Bilinear);
  std::printf("[ ewa ] 8-texel footprints on a 2-texel checker: RMSE ewa %.4f bilinear %.4f\n", ewa,
              bilinear);
  EXPECT_LT(ewa, 0.5 * bilinear);
}

}  // namespace
}  // namespace quadra
