// Tone maps (engine/io/tone_map.h) against double-precision evaluations
// of their published formulas, and their properties: PBR Neutral only offsets
// colours below its compression threshold, ACES maps 0 to 0 and is
// monotone, exposure scales by 2^EV, and the 8-bit row encoder is the sRGB
// one of io/srgb8.h after the curve.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "io/srgb8.h"
#include "io/tone_map.h"

namespace quadra {
namespace {

// Khronos PBR Neutral, the reference formula, in double.
void pbrNeutralRef(const double in[3], double out[3]) {
  const double start = 0.8 - 0.04, desaturation = 0.15;
  const double x = std::min(in[0], std::min(in[1], in[2]));
  const double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  double c[3] = {in[0] - offset, in[1] - offset, in[2] - offset};
  const double peak = std::max(c[0], std::max(c[1], c[2]));
  if (peak < start) {
    std::copy(c, c + 3, out);
    return;
  }
  const double d = 1 - start;
  const double newPeak = 1 - d * d / (peak + d - start);
  const double g = 1 - 1 / (desaturation * (peak - newPeak) + 1);
  for (int k = 0; k < 3; ++k) out[k] = c[k] * newPeak / peak * (1 - g) + newPeak * g;
}

// Hill's ACES fit, in double.
void acesRef(const double in[3], double out[3]) {
  const double m1[3][3] = {
      {0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}};
  const double m2[3][3] = {
      {1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}};
  double f[3];
  for (int r = 0; r < 3; ++r) {
    const double v = m1[r][0] * in[0] + m1[r][1] * in[1] + m1[r][2] * in[2];
    f[r] = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
  }
  for (int r = 0; r < 3; ++r)
    out[r] = std::clamp(m2[r][0] * f[0] + m2[r][1] * f[1] + m2[r][2] * f[2], 0.0, 1.0);
}

TEST(ToneMap, NamesRoundTrip) {
  for (ToneMap map : {ToneMap::PbrNeutral, ToneMap::Aces, ToneMap::None})
    EXPECT_EQ(parseToneMap(toneMapName(map)), map);
  EXPECT_FALSE(parseToneMap("filmic").has_value());
}

TEST(ToneMap, CurvesMatchTheirPublishedFormulas) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> exponent(-8.0, 6.0);
  double worst[2] = {0, 0};
  for (int i = 0; i < 20000; ++i) {
    float in[3];
    double ind[3], want[2][3];
    for (int k = 0; k < 3; ++k) ind[k] = in[k] = float(std::exp2(exponent(rng)));
    pbrNeutralRef(ind, want[0]);
    acesRef(ind, want[1]);
    float got[2][3];
    pbrNeutral(in, got[0]);
    acesHill(in, got[1]);
    for (int t = 0; t < 2; ++t)
      for (int k = 0; k < 3; ++k) worst[t] = std::max(worst[t], std::fabs(got[t][k] - want[t][k]));
  }
  std::printf("worst absolute error: pbr-neutral %.2g, aces %.2g\n", worst[0], worst[1]);
  EXPECT_LT(worst[0], 2e-6);
  EXPECT_LT(worst[1], 2e-6);
}

TEST(ToneMap, PbrNeutralOnlyOffsetsBelowItsCompressionThreshold) {
  const float in[3] = {0.5f, 0.3f, 0.2f};  // min >= 0.08: offset 0.04; peak 0.46 < 0.76
  float out[3];
  pbrNeutral(in, out);
  for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(out[k], in[k] - 0.04f);
  const float dark[3] = {0.05f, 0.05f, 0.05f};  // toe: x - offset = 6.25 x^2
  pbrNeutral(dark, out);
  EXPECT_NEAR(out[0], 6.25f * 0.05f * 0.05f, 1e-7);
  const float bright[3] = {40.0f, 40.0f, 40.0f};  // compressed toward 1, never above
  pbrNeutral(bright, out);
  EXPECT_GT(out[0], 0.99f);
  EXPECT_LE(out[0], 1.0f);
}

TEST(ToneMap, AcesMapsZeroToZeroAndIsMonotone) {
  float out[3], previous = -1.0f;
  const float zero[3] = {0, 0, 0};
  acesHill(zero, out);
  for (float v : out) EXPECT_EQ(v, 0.0f);
  for (int i = 0; i <= 4000; ++i) {
    const float g = std::exp2(-10.0f + i * 0.005f);
    const float in[3] = {g, g, g};
    acesHill(in, out);
    EXPECT_GE(out[1], previous) << g;
    previous = out[1];
  }
  EXPECT_GT(previous, 0.99f);
}

TEST(ToneMap, ExposureScalesByPowersOfTwoAndNoneClamps) {
  ToneMapping mapping{ToneMap::None, 1.0f};
  const float in[3] = {0.25f, 0.1f, 3.0f};
  float out[3];
  mapping.apply(in, out);
  EXPECT_FLOAT_EQ(out[0], 0.5f);
  EXPECT_FLOAT_EQ(out[1], 0.2f);
  EXPECT_FLOAT_EQ(out[2], 1.0f);
  mapping.exposure = -2.0f;
  mapping.apply(in, out);
  EXPECT_FLOAT_EQ(out[0], 0.0625f);
  const float bad[3] = {NAN, -1.0f, 0.5f};
  mapping = {ToneMap::PbrNeutral, 0.0f};
  mapping.apply(bad, out);
  EXPECT_EQ(out[0], 0.0f);
  EXPECT_EQ(out[1], 0.0f);
}

TEST(ToneMap, EightBitRowsAreTheSrgbCodesOfTheMappedValues) {
  const float rgba[8] = {0.2f, 0.5f, 0.9f, 1.0f, 0.1f, 0.05f, 0.3f, 0.5f};  // premultiplied
  std::uint8_t tone[8], plain[8];
  toneMapSrgb8Row({ToneMap::None, 0.0f}, rgba, 2, tone);
  encodeSrgb8Row(rgba, 2, plain);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(tone[k], plain[k]) << k;
  toneMapSrgb8Row({ToneMap::PbrNeutral, 0.0f}, rgba, 2, tone);
  float mapped[3];
  const float straight[3] = {0.2f, 0.1f, 0.6f};
  pbrNeutral(straight, mapped);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(tone[4 + k], srgb8Code(mapped[k]));
  EXPECT_EQ(tone[7], plain[7]);
}

}  // namespace
}  // namespace quadra
