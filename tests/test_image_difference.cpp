// lab/image/image_difference.h: PSNR and max difference, and that a NaN
// pixel is never taken for a match.
#include <gtest/gtest.h>

#include <cmath>

#include "lab/image/image_difference.h"

namespace quadra {
namespace {

TEST(ImageDifference, PsnrAndMaxOverColourOnly) {
  Image a(2, 1), b(2, 1);
  EXPECT_TRUE(std::isinf(imageDifference(a, b).psnr));
  b.rgba[0] = 0.1f;  // one of six colour values off by 0.1: MSE 0.01 / 6
  b.rgba[3] = 1.0f;  // alpha is left out
  const ImageDifference d = imageDifference(a, b);
  EXPECT_NEAR(d.psnr, -10.0 * std::log10(0.01 / 6.0), 1e-5);
  EXPECT_FLOAT_EQ(float(d.maxAbs), 0.1f);
}

TEST(ImageDifference, NanIsNoMatch) {
  Image a(2, 1), b(2, 1);
  b.rgba[5] = NAN;
  const ImageDifference d = imageDifference(a, b);
  EXPECT_TRUE(std::isnan(d.psnr)) << d.psnr;
  EXPECT_TRUE(std::isnan(d.maxAbs)) << d.maxAbs;
}

}  // namespace
}  // namespace quadra
