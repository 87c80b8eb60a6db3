// Texel format conversions against independent double-precision references:
// every one of the 65536 halves decodes to its exact value; float → half
// rounds to the nearest half (ties to even) and overflows to infinity;
// UNORM8 decodes code/255 within one float rounding; names round-trip.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

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

TEST(TexelFormat, EncodeMapsNanToZeroAndUnorm8RoundsAndClamps) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float in[4] = {nan, 0.5f, -0.25f, 1.75f};
  for (const TexelFormat format :
       {TexelFormat::Rgba32F, TexelFormat::Rgba16F, TexelFormat::Rgba8Unorm}) {
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

TEST(TexelFormat, NamesAndSizesRoundTrip) {
  for (const TexelFormat format :
       {TexelFormat::Rgba32F, TexelFormat::Rgba16F, TexelFormat::Rgba8Unorm}) {
    TexelFormat parsed = TexelFormat::Rgba32F;
    ASSERT_TRUE(parseFormat(formatName(format), parsed));
    EXPECT_EQ(parsed, format);
  }
  EXPECT_EQ(bytesPerTexel(TexelFormat::Rgba32F), 16);
  EXPECT_EQ(bytesPerTexel(TexelFormat::Rgba16F), 8);
  EXPECT_EQ(bytesPerTexel(TexelFormat::Rgba8Unorm), 4);
  TexelFormat unused;
  EXPECT_FALSE(parseFormat("rgba4", unused));
}

}  // namespace
}  // namespace quadra
