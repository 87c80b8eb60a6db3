// Tests for the mip chain against a double-precision reference that integrates
// the piecewise-constant source over each destination footprint as a 2D
// rectangle intersection (not the code's separable integer-tap formulation).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "texture/mip_chain.h"

namespace quadra {
namespace {

struct RefImage {
  int width = 0;
  int height = 0;
  std::vector<double> rgba;
  const double* texel(int x, int y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
};

RefImage toRef(const Image& image) {
  return {image.width, image.height, std::vector<double>(image.rgba.begin(), image.rgba.end())};
}

double overlap(double lo, double hi, double cellLo) {
  return std::max(0.0, std::min(hi, cellLo + 1.0) - std::max(lo, cellLo));
}

// Destination texel (x, y) covers the source rectangle
// [x*sw/dw, (x+1)*sw/dw) x [y*sh/dh, (y+1)*sh/dh); its value is the integral of
// the source over that rectangle divided by the rectangle's area. The scan
// deliberately covers one extra texel on each side, clipped to zero area.
RefImage referenceDownsample(const RefImage& src, int dw, int dh) {
  RefImage dst{dw, dh, std::vector<double>(std::size_t(dw) * dh * 4, 0.0)};
  const double sx = double(src.width) / dw;
  const double sy = double(src.height) / dh;
  for (int y = 0; y < dh; ++y) {
    const double y0 = y * sy, y1 = (y + 1) * sy;
    for (int x = 0; x < dw; ++x) {
      const double x0 = x * sx, x1 = (x + 1) * sx;
      double sum[4] = {0, 0, 0, 0};
      double area = 0.0;
      for (int j = std::max(0, int(y0) - 1); j <= std::min(src.height - 1, int(y1) + 1); ++j) {
        for (int i = std::max(0, int(x0) - 1); i <= std::min(src.width - 1, int(x1) + 1); ++i) {
          const double a = overlap(x0, x1, i) * overlap(y0, y1, j);
          for (int c = 0; c < 4; ++c) sum[c] += a * src.texel(i, j)[c];
          area += a;
        }
      }
      EXPECT_NEAR(area, sx * sy, 1e-9 * sx * sy);
      for (int c = 0; c < 4; ++c) dst.rgba[(std::size_t(y) * dw + x) * 4 + c] = sum[c] / area;
    }
  }
  return dst;
}

Image randomImage(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-1.0f, 2.0f);
  Image image(w, h);
  for (float& v : image.rgba) v = value(rng);
  return image;
}

// Values lie in [-1, 2]; each level adds at most half a float ulp of 2 (1.2e-7)
// to the error of the level it was built from, so 1e-6 covers ~8 levels.
constexpr double kTolerance = 1e-6;

void expectNear(const Image& actual, const RefImage& expected, const char* what) {
  ASSERT_EQ(actual.width, expected.width) << what;
  ASSERT_EQ(actual.height, expected.height) << what;
  for (std::size_t i = 0; i < actual.rgba.size(); ++i) {
    ASSERT_NEAR(actual.rgba[i], expected.rgba[i], kTolerance)
        << what << " texel " << i / 4 << " of " << actual.width << "x" << actual.height;
  }
}

double mean(const Image& image) {
  double sum = 0.0;
  for (float v : image.rgba) sum += v;
  return sum / double(image.rgba.size());
}

TEST(MipChain, LevelCountAndSizes) {
  const struct {
    int w, h, levels;
  } cases[] = {{1, 1, 1},     {2, 2, 2},   {3, 1, 2},     {1, 3, 2},     {5, 7, 3},
               {256, 256, 9}, {256, 4, 9}, {211, 211, 8}, {1000, 3, 10}, {1024, 1025, 11}};
  for (const auto& c : cases) {
    const Image level0(c.w, c.h);
    const MipChain chain(level0, nullptr);
    ASSERT_EQ(chain.levelCount(), c.levels) << c.w << "x" << c.h;
    EXPECT_EQ(&chain.level(0), &level0);  // level 0 is used in place
    for (int l = 0; l < chain.levelCount(); ++l) {
      const double scale = std::ldexp(1.0, l);
      EXPECT_EQ(chain.level(l).width, std::max(1, int(std::floor(c.w / scale))));
      EXPECT_EQ(chain.level(l).height, std::max(1, int(std::floor(c.h / scale))));
      EXPECT_EQ(chain.level(l).rgba.size(),
                std::size_t(chain.level(l).width) * chain.level(l).height * 4);
    }
    const Image& last = chain.level(chain.levelCount() - 1);
    EXPECT_EQ(last.width * last.height, 1);
  }
}

TEST(MipChain, EveryLevelMatchesAreaIntegralReference) {
  const int sizes[][2] = {{211, 211}, {1000, 3}, {3, 1}, {1, 1}, {5, 7}, {64, 32}, {17, 40}};
  unsigned seed = 1;
  for (const auto& size : sizes) {
    const Image level0 = randomImage(size[0], size[1], seed++);
    const MipChain chain(level0, nullptr);
    RefImage reference = toRef(level0);
    for (int l = 1; l < chain.levelCount(); ++l) {
      const Image& level = chain.level(l);
      reference = referenceDownsample(reference, level.width, level.height);
      expectNear(level, reference, "mip level");
    }
  }
}

// A level built straight from float data with double accumulation is the exact
// area mean rounded once: within half a float ulp (plus double rounding noise).
// Float accumulation would miss this bound by several ulps.
TEST(MipChain, OneReductionIsRoundedOnceToFloat) {
  const int cases[][4] = {{211, 211, 105, 105}, {1000, 3, 500, 1}, {5, 7, 2, 3}, {10, 7, 3, 4}};
  unsigned seed = 50;
  for (const auto& c : cases) {
    const Image src = randomImage(c[0], c[1], seed++);
    const Image dst = downsampleBox(src, c[2], c[3], nullptr);
    const RefImage reference = referenceDownsample(toRef(src), c[2], c[3]);
    for (std::size_t i = 0; i < dst.rgba.size(); ++i) {
      const float a = std::abs(dst.rgba[i]);
      const double halfUlp = 0.5 * double(std::nextafter(a, 1e30f) - a);
      ASSERT_NEAR(dst.rgba[i], reference.rgba[i], halfUlp + 1e-14)
          << c[0] << "x" << c[1] << " texel " << i / 4;
    }
  }
}

// For power-of-two sizes each level-l texel is exactly the mean of a 2^l square
// block of level 0, a second oracle that needs no chain at all.
TEST(MipChain, PowerOfTwoLevelsAreBlockMeansOfLevelZero) {
  const Image level0 = randomImage(64, 16, 7);
  const MipChain chain(level0, nullptr);
  ASSERT_EQ(chain.levelCount(), 7);
  for (int l = 1; l < chain.levelCount(); ++l) {
    const Image& level = chain.level(l);
    const int bw = 64 / level.width, bh = 16 / level.height;
    for (int y = 0; y < level.height; ++y) {
      for (int x = 0; x < level.width; ++x) {
        for (int c = 0; c < 4; ++c) {
          double sum = 0.0;
          for (int j = 0; j < bh; ++j) {
            for (int i = 0; i < bw; ++i) sum += level0.texel(x * bw + i, y * bh + j)[c];
          }
          ASSERT_NEAR(level.texel(x, y)[c], sum / (bw * bh), kTolerance) << l;
        }
      }
    }
  }
}

// Box reduction preserves the mean exactly; a filter that drops the odd row or
// column of an NPOT level shifts it by far more than the tolerance.
TEST(MipChain, NpotLevelsPreserveTheMean) {
  const int sizes[][2] = {{211, 211}, {1000, 3}, {3, 1}, {5, 7}, {333, 97}};
  unsigned seed = 20;
  for (const auto& size : sizes) {
    Image level0 = randomImage(size[0], size[1], seed++);
    // A ramp along both axes so edge rows and columns differ from the mean.
    for (int y = 0; y < level0.height; ++y) {
      for (int x = 0; x < level0.width; ++x) level0.texel(x, y)[0] += 3.0f * float(x + y);
    }
    const MipChain chain(level0, nullptr);
    const double mean0 = mean(level0);
    for (int l = 1; l < chain.levelCount(); ++l) {
      EXPECT_NEAR(mean(chain.level(l)), mean0, 1e-6 * std::abs(mean0) + 1e-7)
          << size[0] << "x" << size[1] << " level " << l;
    }
  }
}

TEST(MipChain, DownsampleToArbitrarySizeMatchesReference) {
  const Image src = randomImage(10, 7, 30);
  const int targets[][2] = {{3, 4}, {7, 7}, {1, 1}, {10, 2}, {4, 14}};
  for (const auto& t : targets) {
    expectNear(downsampleBox(src, t[0], t[1], nullptr), referenceDownsample(toRef(src), t[0], t[1]),
               "downsampleBox");
  }
}

TEST(MipChain, ParallelBuildIsBitIdenticalToSerial) {
  const Image level0 = randomImage(1023, 517, 40);
  const MipChain serial(level0, nullptr);
  for (int threads : {1, 2, 5}) {
    const Executor executor(threads);
    const MipChain parallel(level0, &executor);
    ASSERT_EQ(parallel.levelCount(), serial.levelCount());
    for (int l = 1; l < serial.levelCount(); ++l) {
      const std::vector<float>& a = serial.level(l).rgba;
      const std::vector<float>& b = parallel.level(l).rgba;
      ASSERT_EQ(a.size(), b.size());
      EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0)
          << "level " << l << " threads " << threads;
    }
  }
}

}  // namespace
}  // namespace quadra

// Internal checks (core/error.h) end in an exception an embedding
// application can catch, not in abort(): an empty source is such a bug.
TEST(InternalCheck, AFailedCheckThrowsALogicErrorNamingItInsteadOfAborting) {
  try {
    (void)quadra::downsampleBox(quadra::Image{}, 1, 1, nullptr);
    ADD_FAILURE() << "the empty source passed the check";
  } catch (const std::logic_error& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("internal check failed at "), std::string::npos) << what;
    EXPECT_NE(what.find("mip_chain.cpp:"), std::string::npos) << what;
    EXPECT_NE(what.find(": src.width > 0 && src.height > 0"), std::string::npos) << what;
  }
}
