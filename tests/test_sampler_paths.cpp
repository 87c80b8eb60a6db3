// The sampler's kernel paths against each other and against the padded
// storage they read: every SIMD path returns the scalar path's bits for every
// filter and wrap mode (non-power-of-two sizes, seams, magnification through
// strong minification), and a padded level repeats each row's first texel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "lab/texture/ground_truth.h"
#include "lab/texture/test_textures.h"
#include "sampler_helpers.h"
#include "texture/image.h"
#include "texture/padded_level.h"

namespace quadra {
namespace {

constexpr TexelFormat kAllFormats[] = {TexelFormat::Rgba32F, TexelFormat::Rgba16F,
                                       TexelFormat::Rgba8Unorm, TexelFormat::Rgba8Srgb};

TEST(PaddedLevel, EachRowEndsWithACopyOfItsFirstTexelInEveryFormat) {
  const Image image = makeValueNoiseTexture(5, 3, 2);
  for (const TexelFormat format : kAllFormats) {
    const PaddedLevel padded(image, format);
    const std::size_t texelBytes = std::size_t(bytesPerTexel(format));
    ASSERT_EQ(padded.stride, 6);
    ASSERT_EQ(padded.texels.size(), 6 * 3 * texelBytes);
    for (int y = 0; y < 3; ++y) {
      for (int x = 0; x <= 5; ++x) {
        float stored[4], expected[4];
        decodeTexel(format,
                    padded.texels.data() + (std::size_t(y) * 6 + std::size_t(x)) * texelBytes,
                    stored);
        std::uint8_t encoded[16];
        encodeTexel(format, image.texel(x % 5, y), encoded);
        decodeTexel(format, encoded, expected);
        for (int c = 0; c < 4; ++c) EXPECT_EQ(stored[c], expected[c]) << formatName(format) << x;
      }
    }
  }
}

TEST(SamplerPaths, EveryIsaMatchesScalarForEveryFilterWrapModeAndFormat) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(37, 23, 5));
  const std::vector<Lookup> lookups = randomLookups(400, 17);
  int compared = 0;
  for (const TexelFormat format : kAllFormats) {
    for (const WrapMode wrap : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge,
                                WrapMode::ClampToBorder}) {
      SamplerState state;
      state.wrapU = state.wrapV = wrap;
      state.borderColor[0] = 0.25f, state.borderColor[3] = 1.0f;
      const Texture texture(image, state, format);
      for (const Filter filter : kEveryFilter) {
        const std::vector<float> scalar = sampleAll(texture, filter, Isa::Scalar, lookups);
        for (const Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
          if (!isaSupported(isa)) continue;
          EXPECT_EQ(sampleAll(texture, filter, isa, lookups), scalar)
              << isaName(isa) << " " << filterName(filter) << " " << wrapName(wrap) << " "
              << formatName(format);
          ++compared;
        }
      }
    }
  }
  if (compared == 0) GTEST_SKIP() << "this CPU has no SIMD path to compare";
}

// The gather variant of the float fetch (the benchmarked alternative) reads
// the same texels: identical bits on the paths that have gathers.
TEST(SamplerPaths, GatheredTexelsEqualPairLoads) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(37, 23, 5));
  const std::vector<Lookup> lookups = randomLookups(300, 29);
  int compared = 0;
  for (const WrapMode wrap : {WrapMode::Repeat, WrapMode::ClampToBorder}) {
    SamplerState state;
    state.wrapU = state.wrapV = wrap;
    const Texture texture(image, state);
    for (const Filter filter : {Filter::Bilinear, Filter::Trilinear, Filter::Anisotropic}) {
      for (const Isa isa : {Isa::Avx2, Isa::Avx512}) {
        if (!isaSupported(isa)) continue;
        EXPECT_EQ(sampleAll(texture, filter, isa, lookups, true),
                  sampleAll(texture, filter, isa, lookups))
            << isaName(isa) << " " << filterName(filter) << " " << wrapName(wrap);
        ++compared;
      }
    }
  }
  if (compared == 0) GTEST_SKIP() << "this CPU has no gather path";
}

// Each narrow format against float storage, bilinear on every path: within
// the format's stated rounding (texel_format.h) of values in [0, 1]; for
// sRGB8 that is half the widest step of the decoded codes (254 → 255).
TEST(SamplerPaths, NarrowFormatsStayWithinTheirRoundingOfFloat) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(64, 48, 3));
  const std::vector<Lookup> lookups = randomLookups(500, 23);
  const Texture exact(image, SamplerState{}, TexelFormat::Rgba32F);
  const struct {
    TexelFormat format;
    double bound;
  } cases[] = {{TexelFormat::Rgba16F, std::ldexp(1.0, -11) + 1e-7},
               {TexelFormat::Rgba8Unorm, 1.0 / 510.0 + 1e-7},
               {TexelFormat::Rgba8Srgb, 0.5 * (1.0 - double(srgb8ToLinear(254))) + 1e-7}};
  for (const auto& c : cases) {
    const Texture narrow(image, SamplerState{}, c.format);
    for (const Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
      if (!isaSupported(isa)) continue;
      const std::vector<float> want = sampleAll(exact, Filter::Bilinear, isa, lookups);
      const std::vector<float> got = sampleAll(narrow, Filter::Bilinear, isa, lookups);
      double worst = 0.0;
      for (std::size_t i = 0; i < got.size(); ++i)
        worst = std::max(worst, std::fabs(double(got[i]) - double(want[i])));
      EXPECT_LE(worst, c.bound) << formatName(c.format) << " " << isaName(isa);
      EXPECT_GT(worst, 0.0) << formatName(c.format) << " is not narrower than float";
    }
  }
}

// The pair reads of the last column (repeat: the padding copy of column 0;
// clamp and mirror: weight 0 on the padding) against the double-precision
// bilinear reference, on a texture one texel wide and one 1000 wide, at
// positions on and around every column edge.
TEST(SamplerPaths, BilinearAtTheLastColumnMatchesTheReferenceOnEveryPath) {
  for (const int width : {1, 2, 1000}) {
    const auto image = std::make_shared<Image>(makeValueNoiseTexture(width, 3, 8));
    std::vector<Lookup> lookups;
    for (int i = -3; i <= 3; ++i)
      for (const float offset : {-0.75f, -0.5f, -0.25f, 0.0f, 0.25f, 0.5f})
        lookups.push_back({(float(width * i) + offset) / float(width), 0.4f, 1e-4f, 0, 0, 1e-4f});
    for (const WrapMode wrap : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge,
                                WrapMode::ClampToBorder}) {
      SamplerState state;
      state.wrapU = state.wrapV = wrap;
      state.borderColor[1] = 0.5f;
      const Texture texture(image, state);
      const BilinearReference reference(*image, state);
      // Float rounding of u * width moves the position by up to width * 2^-24
      // texels; a wrong texel pair is off by the texel contrast (~0.1 to 1).
      const double tolerance = 1e-6 + double(width) * 1.2e-7;
      for (const Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaSupported(isa)) continue;
        const std::vector<float> got = sampleAll(texture, Filter::Bilinear, isa, lookups);
        for (std::size_t i = 0; i < lookups.size(); ++i) {
          double want[4];
          reference.lookup(lookups[i][0], lookups[i][1], want);
          for (int c = 0; c < 4; ++c)
            ASSERT_NEAR(got[i * 4 + std::size_t(c)], want[c], tolerance)
                << isaName(isa) << " " << wrapName(wrap) << " width " << width << " u "
                << lookups[i][0] << " channel " << c;
        }
      }
    }
  }
}

// A texture whose texels are exact decodes of 8-bit sRGB colour and UNORM8
// alpha codes loses nothing in rgba8srgb: nearest lookups at texel centres
// return its texels bit for bit, and bilinear lookups match the
// double-precision reconstruction of those texels, on every path.
TEST(SamplerPaths, Srgb8StorageOfEightBitTexelsIsLossless) {
  constexpr int kWidth = 19, kHeight = 11;
  const auto image = std::make_shared<Image>(kWidth, kHeight);
  for (std::size_t i = 0; i < image->rgba.size(); ++i) {
    const std::uint8_t code = std::uint8_t(i * 97 % 256);  // every code, neighbours far apart
    image->rgba[i] = i % 4 == 3 ? float(code) * kUnorm8Scale : srgb8ToLinear(code);
  }
  SamplerState state;
  state.wrapU = WrapMode::Repeat, state.wrapV = WrapMode::ClampToEdge;
  const Texture texture(image, state, TexelFormat::Rgba8Srgb);
  const BilinearReference reference(*image, state);
  std::vector<Lookup> centres;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      centres.push_back(
          {(float(x) + 0.5f) / kWidth, (float(y) + 0.5f) / kHeight, 1e-4f, 0, 0, 1e-4f});
  std::vector<Lookup> between = randomLookups(300, 41);
  for (Lookup& l : between) l[2] = l[3] = l[4] = l[5] = 1e-4f;  // magnified: level 0
  for (const Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
    if (!isaSupported(isa)) continue;
    const std::vector<float> nearest = sampleAll(texture, Filter::Nearest, isa, centres);
    for (std::size_t i = 0; i < nearest.size(); ++i)
      ASSERT_EQ(nearest[i], image->rgba[i]) << isaName(isa) << " texel " << i / 4;
    const std::vector<float> bilinear = sampleAll(texture, Filter::Bilinear, isa, between);
    for (std::size_t i = 0; i < between.size(); ++i) {
      double want[4];
      reference.lookup(between[i][0], between[i][1], want);
      // Float lerps of values in [0, 1]: a few ulps; a wrong texel is off by ~0.1.
      for (int c = 0; c < 4; ++c)
        ASSERT_NEAR(bilinear[i * 4 + std::size_t(c)], want[c], 1e-6)
            << isaName(isa) << " lookup " << i << " channel " << c;
    }
  }
}

}  // namespace
}  // namespace quadra
