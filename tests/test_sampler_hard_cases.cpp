// The sampler on hard inputs, every filter, wrap mode and kernel path:
// textures 1x1, 1xN, Nx1 and 1000x3; NaN, infinite and zero derivatives;
// 1000:1 anisotropy; coordinates near 1e4 under repeat; lookups exactly on
// the edges under clamp; footprints beyond the last mip level; the border
// colour. Each case states what exact means and checks it against an
// independent expectation (a constant texture stays constant, the
// double-precision bilinear reference, the texture mean, the border colour).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "lab/texture/ground_truth.h"
#include "lab/texture/test_textures.h"
#include "render_helpers.h"
#include "sampler_helpers.h"

namespace quadra {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

const WrapMode kAllWraps[] = {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge,
                              WrapMode::ClampToBorder};

// Lookups no filter may turn into NaN, out-of-range values or a crash.
std::vector<Lookup> hostileLookups() {
  return {{kNan, 0.5f, 0.01f, 0, 0, 0.01f},
          {0.5f, kInf, 0.01f, 0, 0, 0.01f},
          {-kInf, 0.5f, 0.01f, 0, 0, 0.01f},
          {0.5f, 0.5f, kNan, kNan, kNan, kNan},
          {0.5f, 0.5f, kInf, 0, 0, kInf},
          {0.5f, 0.5f, kInf, kInf, -kInf, kInf},
          {0.5f, 0.5f, 0, 0, 0, 0},
          {0.25f, 0.75f, 1.0f, 0, 0, 1e-3f},          // 1000:1
          {0.25f, 0.75f, 0.7f, 0.7f, -7e-4f, 7e-4f},  // 1000:1, diagonal
          {1e4f, -1e4f, 1e3f, 0, 0, 1e-3f},
          {3e38f, -3e38f, 1e-3f, 0, 0, 1e-3f},
          {0.3f, 0.7f, 1e6f, 1e6f, -1e6f, 1e6f},
          {0.0f, 1.0f, 1e-30f, 0, 0, 1e-30f}};
}

// A constant texture is reproduced exactly (to float rounding) by every
// filter, wrap mode (border colour = the constant) and format, on every path,
// whatever the footprint: the sharpest property that still holds on hostile input.
TEST(SamplerHardCases, ConstantTexturesStayConstantOnHostileInput) {
  const float value[4] = {0.25f, 0.5f, 0.75f, 1.0f};
  for (const auto& [w, h] : {std::pair{1, 1}, {1, 7}, {7, 1}, {1000, 3}, {3, 1000}}) {
    auto image = std::make_shared<Image>(w, h);
    for (std::size_t i = 0; i < image->rgba.size(); ++i) image->rgba[i] = value[i % 4];
    std::vector<Lookup> lookups = hostileLookups();
    const std::vector<Lookup> random = randomLookups(64, 3);
    lookups.insert(lookups.end(), random.begin(), random.end());
    for (const WrapMode wrap : kAllWraps) {
      SamplerState state;
      state.wrapU = state.wrapV = wrap;
      std::copy(value, value + 4, state.borderColor);
      const Texture texture(image, state, TexelFormat::Rgba16F);
      for (const Filter filter : kEveryFilter) {
        for (const Isa isa : supportedIsas()) {
          const std::vector<float> got = sampleAll(texture, filter, isa, lookups);
          for (std::size_t i = 0; i < got.size(); ++i)
            ASSERT_NEAR(got[i], value[i % 4], 1e-6)
                << w << "x" << h << " " << filterName(filter) << " " << wrapName(wrap) << " "
                << isaName(isa) << " lookup " << i / 4;
        }
      }
    }
  }
}

// On a texture of varying texels every result stays finite and inside the
// texel range (filters average with non-negative weights), on every path.
TEST(SamplerHardCases, HostileInputGivesFiniteValuesInTheTexelRange) {
  for (const auto& [w, h] : {std::pair{1, 1}, {1, 9}, {9, 1}, {1000, 3}}) {
    const auto image = std::make_shared<Image>(makeValueNoiseTexture(w, h, 5));
    for (const WrapMode wrap : kAllWraps) {
      SamplerState state;
      state.wrapU = state.wrapV = wrap;
      state.borderColor[0] = 1.0f;
      const Texture texture(image, state);
      for (const Filter filter : kEveryFilter) {
        for (const Isa isa : supportedIsas()) {
          for (const float got : sampleAll(texture, filter, isa, hostileLookups())) {
            ASSERT_TRUE(std::isfinite(got)) << filterName(filter) << " " << wrapName(wrap);
            ASSERT_GE(got, -1e-6f);
            ASSERT_LE(got, 1.0f + 1e-6f);
          }
        }
      }
    }
  }
}

// Zero derivatives are magnification: exactly the bilinear lookup (or the
// nearest one for nearest filtering) at the point, for every mip filter.
TEST(SamplerHardCases, ZeroDerivativesAreTheBilinearLookup) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(37, 11, 4));
  const Texture texture(image, SamplerState{});
  std::vector<Lookup> lookups = randomLookups(200, 9);
  for (Lookup& l : lookups) l[2] = l[3] = l[4] = l[5] = 0.0f;
  for (const Isa isa : supportedIsas()) {
    const std::vector<float> bilinear = sampleAll(texture, Filter::Bilinear, isa, lookups);
    for (const Filter filter : {Filter::NearestMip, Filter::Trilinear}) {
      EXPECT_EQ(sampleAll(texture, filter, isa, lookups), bilinear)
          << filterName(filter) << " " << isaName(isa);
    }
  }
}

// Repeat is periodic in float as far as float can tell: u + 10000 is the same
// lookup as u whenever both are exact (multiples of 2^-10 near 1e4), so the
// results are identical bits, not merely close.
TEST(SamplerHardCases, RepeatNearTenThousandIsExactlyPeriodic) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(64, 64, 6));
  const Texture texture(image, SamplerState{});
  std::vector<Lookup> near, far;
  for (int k = 0; k < 1024; k += 7) {
    const float u = float(k) / 1024.0f, v = float((k * 37) % 1024) / 1024.0f;
    near.push_back({u, v, 1e-3f, 0, 0, 1e-3f});
    far.push_back({u + 10000.0f, v - 9000.0f, 1e-3f, 0, 0, 1e-3f});
  }
  for (const Isa isa : supportedIsas())
    for (const Filter filter : {Filter::Bilinear, Filter::Trilinear, Filter::Anisotropic})
      EXPECT_EQ(sampleAll(texture, filter, isa, far), sampleAll(texture, filter, isa, near))
          << filterName(filter) << " " << isaName(isa);
}

// Under clamp, a lookup exactly on an edge or corner of the texture (u, v in
// {0, 1}) reads the edge texel alone: bilinear weights put it at the clamped
// texel centre's side.
TEST(SamplerHardCases, LookupsExactlyOnTheEdgesUnderClampReadTheEdgeTexels) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(5, 4, 8));
  SamplerState state;
  state.wrapU = state.wrapV = WrapMode::ClampToEdge;
  const Texture texture(image, state);
  const std::vector<Lookup> corners = {
      {0, 0, 0, 0, 0, 0}, {1, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0}, {1, 1, 0, 0, 0, 0}};
  const int texel[4][2] = {{0, 0}, {4, 0}, {0, 3}, {4, 3}};
  for (const Isa isa : supportedIsas()) {
    const std::vector<float> got = sampleAll(texture, Filter::Bilinear, isa, corners);
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(got[std::size_t(4 * i + c)], image->texel(texel[i][0], texel[i][1])[c])
            << isaName(isa) << " corner " << i;
  }
}

// A footprint larger than the texture asks for a LOD beyond the last level:
// trilinear clamps to the 1x1 level, the area-weighted mean of the texture
// (mip_chain.h), whatever the position.
TEST(SamplerHardCases, LodBeyondTheLastLevelIsTheTextureMean) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(24, 40, 2));
  const Texture texture(image, SamplerState{});
  double mean[4] = {0, 0, 0, 0};
  for (int y = 0; y < image->height; ++y)
    for (int x = 0; x < image->width; ++x)
      for (int c = 0; c < 4; ++c) mean[c] += image->texel(x, y)[c];
  for (double& m : mean) m /= double(image->width * image->height);
  std::vector<Lookup> lookups;
  for (int k = 0; k < 20; ++k) lookups.push_back({0.05f * float(k), 0.3f, 64.0f, 0, 0, 64.0f});
  for (const Isa isa : supportedIsas()) {
    const std::vector<float> got = sampleAll(texture, Filter::Trilinear, isa, lookups);
    for (std::size_t i = 0; i < got.size(); ++i)
      EXPECT_NEAR(got[i], mean[i % 4], 1e-5) << isaName(isa) << " lookup " << i / 4;
  }
}

// Far outside the texture, clamp-to-border returns the border colour exactly;
// half a texel outside, the border and edge texels blend as the reference does.
TEST(SamplerHardCases, BorderColourOutsideAndBlendedAtTheEdge) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(6, 6, 1));
  SamplerState state;
  state.wrapU = state.wrapV = WrapMode::ClampToBorder;
  const float border[4] = {0.125f, 0.5f, 0.875f, 1.0f};
  std::copy(border, border + 4, state.borderColor);
  const Texture texture(image, state);
  const BilinearReference reference(*image, state);
  const std::vector<Lookup> outside = {{-0.5f, 0.5f, 0, 0, 0, 0},
                                       {1.5f, 0.5f, 0, 0, 0, 0},
                                       {0.5f, -3.0f, 0, 0, 0, 0},
                                       {7.0f, 9.0f, 0, 0, 0, 0}};
  std::vector<Lookup> edge;
  for (int k = 0; k <= 12; ++k) edge.push_back({-0.1f + 0.1f * float(k), 1.0f / 24.0f, 0, 0, 0, 0});
  for (const Isa isa : supportedIsas()) {
    const std::vector<float> far = sampleAll(texture, Filter::Bilinear, isa, outside);
    for (std::size_t i = 0; i < far.size(); ++i) EXPECT_EQ(far[i], border[i % 4]) << i;
    const std::vector<float> near = sampleAll(texture, Filter::Bilinear, isa, edge);
    for (std::size_t i = 0; i < edge.size(); ++i) {
      double want[4];
      reference.lookup(edge[i][0], edge[i][1], want);
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(near[4 * i + std::size_t(c)], want[c], 2e-6) << i;
    }
  }
}

}  // namespace
}  // namespace quadra
