// The sampler's kernel paths against each other and against the padded
// storage they read: every SIMD path returns the scalar path's bits for every
// filter and wrap mode (non-power-of-two sizes, seams, magnification through
// strong minification), and a padded level repeats each row's first texel.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "sampler_helpers.h"
#include "texture/ground_truth.h"
#include "texture/padded_level.h"
#include "texture/test_textures.h"

namespace quadra {
namespace {

TEST(PaddedLevel, EachRowEndsWithACopyOfItsFirstTexel) {
  const Image image = makeValueNoiseTexture(5, 3, 2);
  const PaddedLevel padded(image);
  ASSERT_EQ(padded.stride, 6);
  ASSERT_EQ(padded.texels.size(), std::size_t(6 * 3 * 4));
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x <= 5; ++x)
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(padded.texels[(std::size_t(y) * 6 + std::size_t(x)) * 4 + std::size_t(c)],
                  image.texel(x % 5, y)[c])
            << x << "," << y;
}

TEST(SamplerPaths, EveryIsaMatchesScalarForEveryFilterAndWrapMode) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(37, 23, 5));
  const std::vector<Lookup> lookups = randomLookups(400, 17);
  int compared = 0;
  for (const WrapMode wrap : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge,
                              WrapMode::ClampToBorder}) {
    SamplerState state;
    state.wrapU = state.wrapV = wrap;
    state.borderColor[0] = 0.25f, state.borderColor[3] = 1.0f;
    const Texture texture(image, state);
    for (const Filter filter : {Filter::Nearest, Filter::Bilinear, Filter::NearestMip,
                                Filter::Trilinear, Filter::Anisotropic}) {
      const std::vector<float> scalar = sampleAll(texture, filter, Isa::Scalar, lookups);
      for (const Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaSupported(isa)) continue;
        EXPECT_EQ(sampleAll(texture, filter, isa, lookups), scalar)
            << isaName(isa) << " " << filterName(filter) << " " << wrapName(wrap);
        ++compared;
      }
    }
  }
  if (compared == 0) GTEST_SKIP() << "this CPU has no SIMD path to compare";
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

}  // namespace
}  // namespace quadra
