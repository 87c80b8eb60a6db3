// EWA through the batch sampler: exact on a constant texture, finite and in
// range for hostile inputs (NaN/Inf, zero and enormous footprints), identical
// on every ISA path, closer to the box ground truth than bilinear on
// minified footprints, and within a fifth of its own double-precision ideal's
// error (lab/texture/ewa_ideal.h), which is checked analytically first.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "core/parallel.h"
#include "lab/texture/ewa_ideal.h"
#include "lab/texture/footprints.h"
#include "lab/texture/ground_truth.h"
#include "lab/texture/test_textures.h"
#include "lab/texture/texture_error.h"
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

// The ideal itself, on a texture whose answer is known: texel values linear in
// the texel index make the bilinear reconstruction that linear function, and
// a radial weight averages it to its value at the centre, whatever the
// ellipse; a constant texture stays constant under any weight.
TEST(EwaIdeal, LinearRampAveragesToTheCentreValue) {
  Image image(16, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      float* t = image.texel(x, y);
      t[0] = 0.05f * float(x) + 0.02f * float(y), t[1] = 0.03f * float(y);
      t[2] = 0.5f, t[3] = 1.0f;
    }
  const BilinearReference reference(image, samplerWith(WrapMode::ClampToEdge));
  const double tx = 7.3, ty = 8.6;  // texel space: the ellipse stays inside the ramp
  for (const double anisotropy : {1.0, 4.0})
    for (const double major : {0.5, 3.0}) {
      const Footprint f =
          makeFootprint((tx + 0.5) / 16, (ty + 0.5) / 16, major, anisotropy, 0.7, 0.4, 16, 16);
      const GroundTruthValue value = ewaIdeal(reference, f, kEwaShape);
      EXPECT_NEAR(value.rgba[0], 0.05 * tx + 0.02 * ty, 1e-6) << major << " " << anisotropy;
      EXPECT_NEAR(value.rgba[1], 0.03 * ty, 1e-6) << major << " " << anisotropy;
      EXPECT_NEAR(value.rgba[2], 0.5, 1e-12);
    }
}

// RMSE over R, G, B of `got` (4 floats a lookup) against `want` (4 doubles).
double rmseAgainst(const std::vector<float>& got, const std::vector<double>& want) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < got.size(); i += 4)
    for (int c = 0; c < 3; ++c, ++n) sum += (got[i + c] - want[i + c]) * (got[i + c] - want[i + c]);
  return std::sqrt(sum / double(n));
}

// The criterion: against the box ground truth, quadra's EWA is at most
// 1.2x as far as the exact Gaussian average of the same footprint (kEwaShape,
// integrated in double by lab/texture/ewa_ideal.h); the gap between that
// ideal and the box is the shape's own, the rest is the filter's shortcuts
// (mip levels, texel centres, the eccentricity clamp, float). And directly:
// quadra within 0.006 of the ideal, where the old filter (pbrt's level and
// added unit disk on a half-pixel ellipse, truncated) was 0.023 from it.
// The report's footprint stream (every scale, anisotropy and orientation,
// seams and edges) on per-texel noise and a 2-texel checker.
TEST(Ewa, WithinAFifthOfItsDoublePrecisionIdealsErrorAgainstTheBox) {
  const Executor executor(0);
  const int size = 128;
  const FootprintSet footprints =
      makeFootprintSet({.count = 36 * 16, .seed = 6, .textureWidth = size, .textureHeight = size});
  const std::vector<Footprint> list = footprints.footprints();
  for (const bool checker : {false, true}) {
    const auto image = std::make_shared<Image>(checker ? makeCheckerTexture(size, size, 2)
                                                       : makeValueNoiseTexture(size, size, 6));
    const BilinearReference reference(*image, SamplerState{});
    const GroundTruthSet box = groundTruthSet(reference, list, {}, executor);
    const GroundTruthSet ideal = ewaIdealSet(reference, list, kEwaShape, {}, executor);
    const Texture texture(image, SamplerState{});
    std::vector<float> quadra(footprints.size() * 4),
        idealFloat(ideal.rgba.begin(), ideal.rgba.end());
    TextureSampler(texture, FilterSettings(Filter::Ewa, 16), Isa::Scalar)
        .sample(footprints.batch(), 0, footprints.size(), quadra.data());
    const double filterToBox = rmseAgainst(quadra, box.rgba);
    const double idealToBox = rmseAgainst(idealFloat, box.rgba);
    const double filterToIdeal = rmseAgainst(quadra, ideal.rgba);
    std::printf(
        "[ ewa ] %s: RMSE against the box ideal %.4f, the EWA ideal's %.4f (%.2fx); "
        "against the EWA ideal %.4f\n",
        checker ? "checker" : "noise", filterToBox, idealToBox, filterToBox / idealToBox,
        filterToIdeal);
    EXPECT_LE(filterToBox, 1.2 * idealToBox) << (checker ? "checker" : "noise");
    EXPECT_LE(filterToIdeal, 0.006) << (checker ? "checker" : "noise");
  }
}

}  // namespace
}  // namespace quadra
