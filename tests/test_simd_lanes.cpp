// The lane layer's own contract: log2 accuracy against libm in double, and
// bit-identical results between the scalar reference lanes and SSE2 lanes
// (SSE2 is the x86-64 baseline, so this file needs no ISA flags).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "simd/lanes.h"

namespace quadra {
namespace {

using Scalar = simd::Lanes<simd::ScalarArch>;
using Sse2 = simd::Lanes<xsimd::sse2>;

template <class L>
void log2Of(const float in[4], float out[4]) {
  simd::log2<L>(L::F::load_unaligned(in)).store_unaligned(out);
}

TEST(SimdLanes, Log2IsAccurateAndIdenticalAcrossPaths) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> exponent(-120.0f, 120.0f);
  double worst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    float in[4], scalar[4], sse2[4];
    for (float& x : in) x = std::exp2(exponent(rng));
    log2Of<Scalar>(in, scalar);
    log2Of<Sse2>(in, sse2);
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(std::memcmp(&scalar[k], &sse2[k], sizeof(float)), 0) << in[k];
      worst = std::max(worst, std::fabs(double(scalar[k]) - std::log2(double(in[k]))));
    }
  }
  // The LOD needs 8 fractional bits (2^-8 = 0.0039); the polynomial gives ~1e-6.
  EXPECT_LT(worst, 4e-6);
  std::printf("log2 worst absolute error %.3g\n", worst);
}

TEST(SimdLanes, Log2OfZeroNegativeAndNanIsFiniteAndSmall) {
  const float in[4] = {0.0f, -1.0f, NAN, 1e-45f};
  float out[4];
  log2Of<Scalar>(in, out);
  for (float v : out) {
    EXPECT_TRUE(std::isfinite(v));
    EXPECT_LE(v, -126.0f + 1e-4f);
  }
}

TEST(SimdLanes, QuadBroadcastAndMaskBitsAgree) {
  const float in[4] = {1.0f, 2.0f, 3.0f, 4.0f};
  float scalar[4], sse2[4];
  simd::quadBroadcast<2>(Scalar::F::load_unaligned(in)).store_unaligned(scalar);
  simd::quadBroadcast<2>(Sse2::F::load_unaligned(in)).store_unaligned(sse2);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(scalar[k], 3.0f);
    EXPECT_EQ(sse2[k], 3.0f);
  }
  for (std::uint32_t bits = 0; bits < 16; ++bits) {
    EXPECT_EQ(simd::bits(simd::maskFromBits<Scalar>(bits)), bits);
    EXPECT_EQ(simd::bits(simd::maskFromBits<Sse2>(bits)), bits);
  }
}

// The double lanes the summed-area kernel uses: int64 loads convert as the
// scalar conversion does over the whole int64 range, NaN is named on every
// path, and per-lane values repeat over a lane's channels.
TEST(SimdLanes, DoubleLanesConvertNameNanAndRepeatLikeScalar) {
  std::mt19937_64 rng(9);
  for (int i = 0; i < 20000; ++i) {
    alignas(64) std::int64_t values[4];
    for (std::int64_t& v : values) v = std::int64_t(rng() >> (rng() % 64));  // every magnitude
    if (i % 2) values[1] = -values[1];
    alignas(64) double scalar[4], sse2[4];
    simd::loadAsDouble<Scalar>(values).store_aligned(scalar);
    simd::loadAsDouble<Sse2>(values).store_aligned(sse2);
    simd::loadAsDouble<Sse2>(values + 2).store_aligned(sse2 + 2);
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(scalar[k], double(values[k])) << values[k];
      EXPECT_EQ(sse2[k], double(values[k])) << values[k];
    }
  }
  const double nan = std::nan("");
  EXPECT_EQ(simd::bits(simd::isNan(Scalar::D(nan, 1.0, -INFINITY, nan))), 0b1001u);
  alignas(16) double lanes[2] = {nan, 0.0}, repeated[2];
  const auto sse2Nan = simd::isNan(Sse2::D::load_aligned(lanes));
  EXPECT_TRUE(sse2Nan.get(0));
  EXPECT_FALSE(sse2Nan.get(1));
  simd::repeatPerChannel<Sse2>(lanes + 1).store_aligned(repeated);
  EXPECT_EQ(repeated[0], 0.0);
  EXPECT_EQ(repeated[1], 0.0);
}

}  // namespace
}  // namespace quadra
