// The largest texture quadra accepts, sampled for real: 16384 x 16384
// (kMaxImagePixels, 2^28 texels). Texel offsets near the far corner pass
// 2^28, where an overflow or a float-precision index would show. Memory: the
// float image 4 GiB, its rgba8 storage 1 GiB, the float mip chain 1.3 GiB and
// its storage 0.3 GiB; the test needs 12 GiB of RAM and skips below that
// (and under sanitizers, whose shadow memory and slowdown it would multiply).
// It takes about 40 s on the 2-core VM, most of it encoding level 0.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/parallel.h"
#include "render_helpers.h"
#include "sampler_helpers.h"
#include "sanitizer_build.h"

namespace quadra {
namespace {

constexpr int kSide = 16384;

// 8-bit codes as rgba8 decodes them (texel_format.h): stored and read back exactly.
float codeAt(int x, int y) {
  return float((7 * x + 13 * y) % 256) * kUnorm8Scale;
}

double physicalMemoryGiB() {
  return double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE)) / double(1 << 30);
}

TEST(HugeTexture, SixteenThousandSquaredSamplesExactlyAtTheFarCorner) {
  if (kSanitizedBuild) GTEST_SKIP() << "16384^2 needs ~7 GiB; not under sanitizers";
  if (physicalMemoryGiB() < 12.0)
    GTEST_SKIP() << "16384^2 needs ~7 GiB; this machine has " << physicalMemoryGiB() << " GiB";
  static_assert(std::int64_t(kSide) * kSide == kMaxImagePixels, "the largest accepted texture");
  const Executor executor(0);
  auto image = std::make_shared<Image>(kSide, kSide);
  executor.parallelFor(kSide, 64, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < kSide; ++x) {
        float* t = image->texel(x, y);
        t[0] = codeAt(x, y), t[1] = codeAt(y, x), t[2] = 0.0f, t[3] = 1.0f;
      }
  });
  const Texture texture(image, SamplerState{}, TexelFormat::Rgba8Unorm);

  // Texel centres at the corners and inside, read by nearest and bilinear:
  // both are the texel itself.
  const int spots[][2] = {{0, 0},         {kSide - 1, kSide - 1}, {kSide - 1, 0},
                          {0, kSide - 1}, {12345, 16000},         {16383, 8191}};
  std::vector<Lookup> lookups;
  for (const auto& s : spots)
    lookups.push_back(
        {(float(s[0]) + 0.5f) / kSide, (float(s[1]) + 0.5f) / kSide, 0.0f, 0.0f, 0.0f, 0.0f});
  for (const Filter filter : {Filter::Nearest, Filter::Bilinear}) {
    for (const Isa isa : supportedIsas()) {
      const std::vector<float> got = sampleAll(texture, filter, isa, lookups);
      for (std::size_t k = 0; k < lookups.size(); ++k) {
        EXPECT_EQ(got[k * 4], codeAt(spots[k][0], spots[k][1])) << filterName(filter) << k;
        EXPECT_EQ(got[k * 4 + 1], codeAt(spots[k][1], spots[k][0])) << filterName(filter) << k;
      }
    }
  }

  // A footprint the size of the texture reads the last mip level: the mean,
  // exactly 0.5 per row (7x and 13y step through all 256 codes), which rgba8
  // stores as 128/255.
  FilterSettings settings(Filter::Trilinear);
  const TextureView view = makeTextureView(texture, settings, &executor);
  EXPECT_EQ(view.levelCount, 15);
  const std::vector<float> mean =
      sampleAll(texture, Filter::Trilinear, Isa::Scalar, {{0.3f, 0.8f, 1.0f, 0.0f, 0.0f, 1.0f}});
  EXPECT_NEAR(mean[0], 0.5f, 0.5f / 255.0f + 1e-6f);
  EXPECT_NEAR(mean[1], 0.5f, 0.5f / 255.0f + 1e-6f);
}

}  // namespace
}  // namespace quadra
