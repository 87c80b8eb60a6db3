// Ripmap levels against an independent construction: each level (i, j) is the
// exact box-area reduction of level 0 to its size in one step, although the
// ripmap builds it through a chain of halvings (non-power-of-two sizes
// included, where the chain's fractional weights must compose exactly).
#include <gtest/gtest.h>

#include <memory>

#include "core/parallel.h"
#include "lab/texture/test_textures.h"
#include "sampler_helpers.h"
#include "texture/mip_chain.h"
#include "texture/ripmap.h"

namespace quadra {
namespace {

TEST(Ripmap, EveryLevelIsTheOneStepBoxReductionOfLevel0) {
  const Executor executor(2);
  for (const auto& size :
       {std::pair{13, 9}, std::pair{16, 1}, std::pair{1, 7}, std::pair{64, 48}}) {
    const Image level0 = makeValueNoiseTexture(size.first, size.second, 11);
    const Ripmap ripmap(level0, TexelFormat::Rgba32F, &executor);
    int expectedX = 1, expectedY = 1;
    for (int w = size.first; w > 1; w /= 2) ++expectedX;
    for (int h = size.second; h > 1; h /= 2) ++expectedY;
    ASSERT_EQ(ripmap.countX, expectedX);
    ASSERT_EQ(ripmap.countY, expectedY);
    ASSERT_EQ(ripmap.levels.size(), std::size_t(expectedX * expectedY));
    for (int j = 0; j < ripmap.countY; ++j) {
      for (int i = 0; i < ripmap.countX; ++i) {
        const TextureLevel& level = ripmap.levels[std::size_t(j * ripmap.countX + i)];
        const int w = std::max(1, size.first >> i), h = std::max(1, size.second >> j);
        ASSERT_EQ(level.width, w);
        ASSERT_EQ(level.height, h);
        const Image direct = downsampleBox(level0, w, h, nullptr);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            float stored[4];
            decodeTexel(TexelFormat::Rgba32F,
                        level.texels + (std::size_t(y) * std::size_t(level.stride) + x) * 16,
                        stored);
            for (int c = 0; c < 4; ++c)
              EXPECT_NEAR(stored[c], direct.texel(x, y)[c], 2e-6)
                  << size.first << "x" << size.second << " level " << i << "," << j;
          }
      }
    }
  }
}

// A footprint exactly one level-(i, j) texel wide along each axis reads that
// level alone: the ripmap lookup is the bilinear lookup of it.
TEST(Ripmap, AnAxisAlignedFootprintOfOneLevelTexelReadsThatLevel) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(64, 32, 4));
  const Texture texture(image, SamplerState{});
  const Ripmap& ripmap = texture.ripmap();
  const std::vector<Lookup> lookups = {{0.3f, 0.6f, 4.0f / 64.0f, 0.0f, 0.0f, 1.0f / 32.0f},
                                       {0.71f, 0.2f, 1.0f / 64.0f, 0.0f, 0.0f, 8.0f / 32.0f}};
  const int levels[2][2] = {{2, 0}, {0, 3}};
  for (const Isa isa : {Isa::Scalar}) {
    const std::vector<float> got = sampleAll(texture, Filter::Ripmap, isa, lookups);
    for (std::size_t k = 0; k < lookups.size(); ++k) {
      const TextureLevel& level =
          ripmap.levels[std::size_t(levels[k][1] * ripmap.countX + levels[k][0])];
      // Bilinear by hand on that level (repeat wrap, texel centres at i + 0.5).
      const double x = lookups[k][0] * level.width - 0.5, y = lookups[k][1] * level.height - 0.5;
      const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
      const double fx = x - x0, fy = y - y0;
      auto texel = [&](int tx, int ty, int c) {
        tx = (tx % level.width + level.width) % level.width;
        ty = (ty % level.height + level.height) % level.height;
        float rgba[4];
        decodeTexel(TexelFormat::Rgba32F,
                    level.texels + (std::size_t(ty) * std::size_t(level.stride) + tx) * 16, rgba);
        return double(rgba[c]);
      };
      for (int c = 0; c < 4; ++c) {
        const double top = texel(x0, y0, c) * (1 - fx) + texel(x0 + 1, y0, c) * fx;
        const double bottom = texel(x0, y0 + 1, c) * (1 - fx) + texel(x0 + 1, y0 + 1, c) * fx;
        EXPECT_NEAR(got[k * 4 + c], top * (1 - fy) + bottom * fy, 1e-6) << k;
      }
    }
  }
}

}  // namespace
}  // namespace quadra
