// Texel format conversions against independent double-precision references:
// every one of the 65536 halves decodes to its exact value; float → half
// rounds to the nearest half (ties to even) and overflows to infinity;
// UNORM8 decodes code/255 within one float rounding; sRGB8 decodes every
// code to the correctly rounded exact curve and encodes to the nearest code;
// names round-trip.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "texture/texel_format.h"

namespace quadra {
namespace {

// The value a half's bits stand for, from the IEEE 754 definition.
double halfValue(std::uint16_t h) {
  const int sign = h >> 15, exponent = (h >> 10) & 0x1F, mantissa = h & 0x3FF;
  const double s = sign ? -1.0 : 1.0;
  if (exponent == 31)
    return mantissa ? std::numeric_limits<double>::quiet_NaN()
                    : s * std::numeric_limits<double>::infinity();
  if (exponent == 0) return s * std::ldexp(double(mantissa), -24);
  return s * std::ldexp(double(1024 + mantissa), exponent - 25);
}

TEST(TexelFormat, EveryHalfDecodesToItsExactValue) {
  for (std::uint32_t h = 0; h < 65536; ++h) {
    const double want = halfValue(std::uint16_t(h));
    const float got = halfToFloat(std::uint16_t(h));
    if (std::isnan(want)) {
      EXPECT_TRUE(std::isnan(got)) << h;
    } else {
      ASSERT_EQ(double(got), want) << "half bits " << h;
      ASSERT_EQ(std::signbit(got), std::signbit(want)) << h;
    }
  }
}

TEST(TexelFormat, FloatToHalfRoundsToTheNearestHalfTiesToEven) {
  // Every finite half round-trips exactly.
  for (std::uint32_t h = 0; h < 65536; ++h) {
    if (((h >> 10) & 0x1F) == 31) continue;
    ASSERT_EQ(floatToHalf(halfToFloat(std::uint16_t(h))), h) << h;
  }
  // Random floats over the whole half range: the result is a nearest half,
  // and of two equally near ones the even one.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> logMagnitude(-27.0, 16.0);
  for (int i = 0; i < 200000; ++i) {
    const float x = float((i & 1 ? -1.0 : 1.0) * std::exp2(logMagnitude(rng)));
    const std::uint16_t h = floatToHalf(x);
    const double got = halfValue(h);
    if (std::isinf(got)) {
      EXPECT_GE(std::fabs(double(x)), 65520.0) << x;
      continue;
    }
    const std::uint16_t below = std::uint16_t(h - 1), above = std::uint16_t(h + 1);
    const double error = std::fabs(got - double(x));
    for (const std::uint16_t neighbour : {below, above}) {
      if ((neighbour & 0x7FFF) >= 0x7C00 || (neighbour ^ h) & 0x8000) continue;
      const double other = std::fabs(halfValue(neighbour) - double(x));
      ASSERT_LE(error, other) << x;
      if (error == other) {
        EXPECT_EQ(h & 1, 0) << "tie not to even at " << x;
      }
    }
  }
  EXPECT_EQ(floatToHalf(65519.0f), 0x7BFF);  // 65504, the largest half
  EXPECT_EQ(floatToHalf(65520.0f), 0x7C00);  // infinity
  EXPECT_EQ(floatToHalf(std::numeric_limits<float>::quiet_NaN()) & 0x7C00, 0x7C00);
}

// Texture levels are encoded in runs (encodeTexels, branch-free so it
// vectorizes); every value must come out as the scalar floatToHalf gives it,
// NaN as +0: every exponent, the mantissa's rounding bits and neighbours of
// each half, both signs.
TEST(TexelFormat, RunsOfHalvesEqualTheScalarConversion) {
  std::vector<float> values;
  for (std::uint32_t exponent = 0; exponent < 256; ++exponent)
    for (const std::uint32_t mantissa :
         {0x000000u, 0x000001u, 0x000FFFu, 0x001000u, 0x001001u, 0x001FFFu, 0x002000u, 0x003000u,
          0x3FF000u, 0x3FFFFFu, 0x400000u, 0x7FE000u, 0x7FEFFFu, 0x7FF000u, 0x7FF001u, 0x7FFFFFu})
      for (const std::uint32_t sign : {0u, 0x80000000u}) {
        const std::uint32_t bits = sign | exponent << 23 | mantissa;
        float f;
        std::memcpy(&f, &bits, 4);
        values.push_back(f);
      }
  std::mt19937 rng(7);
  for (int i = 0; i < 200000; ++i) {
    const std::uint32_t bits = rng();
    float f;
    std::memcpy(&f, &bits, 4);
    values.push_back(f);
  }
  while (values.size() % 4) values.push_back(0.0f);
  std::vector<std::uint8_t> encoded(values.size() * 2);
  encodeTexels(TexelFormat::Rgba16F, values.data(), values.size() / 4, encoded.data());
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::uint16_t got;
    std::memcpy(&got, &encoded[2 * i], 2);
    const std::uint16_t expected = std::isnan(values[i]) ? 0 : floatToHalf(values[i]);
    ASSERT_EQ(got, expected) << "value " << values[i] << " (index " << i << ")";
  }
}

TEST(TexelFormat, EncodeMapsNanToZeroAndUnorm8RoundsAndClamps) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float in[4] = {nan, 0.5f, -0.25f, 1.75f};
  for (const TexelFormat format : {TexelFormat::Rgba32F, TexelFormat::Rgba16F,
                                   TexelFormat::Rgba8Unorm, TexelFormat::Rgba8Srgb}) {
    std::uint8_t stored[16];
    float out[4];
    encodeTexel(format, in, stored);
    decodeTexel(format, stored, out);
    EXPECT_EQ(out[0], 0.0f) << formatName(format);
  }
  std::uint8_t codes[4];
  encodeTexel(TexelFormat::Rgba8Unorm, in, codes);
  EXPECT_EQ(codes[1], 128);  // 127.5 rounds to even
  EXPECT_EQ(codes[2], 0);
  EXPECT_EQ(codes[3], 255);
  for (int code = 0; code < 256; ++code) {
    const std::uint8_t texel[4] = {std::uint8_t(code), 0, 0, 0};
    float rgba[4];
    decodeTexel(TexelFormat::Rgba8Unorm, texel, rgba);
    EXPECT_NEAR(rgba[0], code / 255.0, 1e-7) << code;
  }
}

// The sRGB curve (IEC 61966-2-1) in double, independent of the float code.
double srgbDecodeReference(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}
double srgbEncodeReference(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

TEST(TexelFormat, Srgb8DecodesEveryCodeToTheCorrectlyRoundedCurveAndEncodesItBack) {
  for (int code = 0; code < 256; ++code) {
    const std::uint8_t c = std::uint8_t(code);
    const std::uint8_t texel[4] = {c, c, c, c};
    float rgba[4];
    decodeTexel(TexelFormat::Rgba8Srgb, texel, rgba);
    const float linear = float(srgbDecodeReference(code / 255.0));
    for (int ch = 0; ch < 3; ++ch) ASSERT_EQ(rgba[ch], linear) << "code " << code;
    ASSERT_EQ(rgba[3], float(code) * kUnorm8Scale) << "alpha is UNORM8, code " << code;
    // Decode then encode is the identity, and so is encoding the reference value.
    std::uint8_t again[4];
    encodeTexel(TexelFormat::Rgba8Srgb, rgba, again);
    for (int ch = 0; ch < 4; ++ch) ASSERT_EQ(again[ch], c) << "code " << code << " channel " << ch;
    const float fromReference[4] = {linear, linear, linear, float(code / 255.0)};
    encodeTexel(TexelFormat::Rgba8Srgb, fromReference, again);
    for (int ch = 0; ch < 4; ++ch) ASSERT_EQ(again[ch], c) << "code " << code << " channel " << ch;
  }
}

TEST(TexelFormat, Srgb8EncodesToTheNearestCodeAndClamps) {
  // Random linear values in [0, 1]: the code is nearest on the sRGB scale
  // (within float rounding of the encode, 1e-4 of a step).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> logValue(-16.0, 0.0);
  for (int i = 0; i < 100000; ++i) {
    const float x = float(std::exp2(logValue(rng)));
    const float in[4] = {x, x, x, x};
    std::uint8_t codes[4];
    encodeTexel(TexelFormat::Rgba8Srgb, in, codes);
    ASSERT_LE(std::fabs(srgbEncodeReference(double(x)) * 255.0 - codes[0]), 0.5 + 1e-4) << x;
    ASSERT_EQ(codes[1], codes[0]);
    ASSERT_LE(std::fabs(double(x) * 255.0 - codes[3]), 0.5 + 1e-4) << x;
  }
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const struct {
    float value;
    std::uint8_t code;
  } edges[] = {{nan, 0},  {-nan, 0},   {-0.25f, 0},  {-inf, 0},
               {0.0f, 0}, {1.0f, 255}, {1.75f, 255}, {inf, 255}};
  for (const auto& e : edges) {
    const float in[4] = {e.value, e.value, e.value, e.value};
    std::uint8_t codes[4];
    encodeTexel(TexelFormat::Rgba8Srgb, in, codes);
    for (int ch = 0; ch < 4; ++ch) EXPECT_EQ(codes[ch], e.code) << e.value << " channel " << ch;
  }
}

TEST(TexelFormat, NamesAndSizesRoundTrip) {
  for (const TexelFormat format : {TexelFormat::Rgba32F, TexelFormat::Rgba16F,
                                   TexelFormat::Rgba8Unorm, TexelFormat::Rgba8Srgb}) {
    TexelFormat parsed = TexelFormat::Rgba32F;
    ASSERT_TRUE(parseFormat(formatName(format), parsed));
    EXPECT_EQ(parsed, format);
  }
  EXPECT_EQ(bytesPerTexel(TexelFormat::Rgba32F), 16);
  EXPECT_EQ(bytesPerTexel(TexelFormat::Rgba16F), 8);
  EXPECT_EQ(bytesPerTexel(TexelFormat::Rgba8Unorm), 4);
  EXPECT_EQ(bytesPerTexel(TexelFormat::Rgba8Srgb), 4);
  EXPECT_STREQ(formatName(TexelFormat::Rgba8Srgb), "rgba8srgb");
  TexelFormat unused;
  EXPECT_FALSE(parseFormat("rgba4", unused));
}

}  // namespace
}  // namespace quadra
