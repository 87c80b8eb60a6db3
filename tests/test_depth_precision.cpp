// Depth precision, standard against reversed float depth (api/camera.h
// DepthMode): two parallel quads at view distance D, separated by s, near
// plane 1e-3 and far 1e6; the nearer (red) quad is drawn second, so a pixel is
// resolved correctly only if the depth buffer separates the two. Exact means:
// every pixel red. Reported: the fraction of red pixels per case. And the
// depth at each sample of a multisampled pixel, rounded as every path rounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "lab/scene/builtin_scenes.h"
#include "lab/scene/hard_case_scenes.h"
#include "render_helpers.h"
#include "tile/tile_kernel.h"

namespace quadra {
namespace {

constexpr int kSize = 48;

double redFraction(const Scene& scene, DepthMode depth) {
  RenderSettings settings;
  settings.width = settings.height = kSize;
  settings.depth = depth;
  const Frame frame = renderOnce(scene, scene.cameras[0], settings, 1);
  std::size_t red = 0;
  for (std::size_t i = 0; i < frame.rgba.size(); i += 4)
    red += frame.rgba[i] == 1.0f && frame.rgba[i + 1] == 0.0f;
  return double(red) / double(kSize * kSize);
}

TEST(DepthPrecision, ReversedDepthResolvesWhatStandardDepthCannot) {
  const double distances[] = {10.0, 100.0, 1000.0, 10000.0};
  const double relative[] = {1e-3, 1e-4, 1e-5};
  std::printf("[ depth precision: fraction of pixels resolved, near 1e-3, far 1e6 ]\n");
  std::printf("| distance | separation | standard | reversed |\n|---:|---:|---:|---:|\n");
  for (const double d : distances) {
    for (const double r : relative) {
      const Scene scene = zFightingScene(d, d * r);
      const double standard = redFraction(scene, DepthMode::Standard);
      const double reversed = redFraction(scene, DepthMode::Reversed);
      std::printf("| %g | %g | %.3f | %.3f |\n", d, d * r, standard, reversed);
      // Reversed float depth has relative precision everywhere: n/D is tiny
      // but exactly as finely represented as the separation needs.
      EXPECT_EQ(reversed, 1.0) << "D " << d << " s/D " << r;
      EXPECT_GE(reversed, standard);
    }
  }
  // And the test has teeth: standard depth, 1 - n/D, has float steps of
  // 2^-24 near 1, far coarser than the n*s/D^2 = 1e-10 this case needs.
  EXPECT_LT(redFraction(zFightingScene(1000.0, 0.1), DepthMode::Standard), 0.5);
}

// On an ordinary scene the depth mode changes the stored depth, not the
// picture: the showcase renders the same pixels to rounding, and its
// reversed depth is one minus the standard depth (to float rounding near 1).
TEST(DepthPrecision, ReversedDepthDrawsTheSamePicture) {
  const Scene scene = makeBuiltinScene("showcase");
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  const Frame standard = renderOnce(scene, firstCameraOrDefault(scene), settings, 2);
  settings.depth = DepthMode::Reversed;
  const Frame reversed = renderOnce(scene, firstCameraOrDefault(scene), settings, 2);
  // Not bit-identical: the near-plane clip of the ground plane measures its
  // plane distance from the other matrix row (w - z instead of z), so the
  // clipped vertices round differently (measured: 2.4e-5 at most).
  double worst = 0.0;
  for (std::size_t i = 0; i < standard.rgba.size(); ++i)
    worst = std::max(worst, double(std::fabs(reversed.rgba[i] - standard.rgba[i])));
  EXPECT_LT(worst, 1e-4);
  for (std::size_t i = 0; i < standard.depth.size(); ++i)
    ASSERT_NEAR(reversed.depth[i], 1.0f - standard.depth[i], 1e-6f) << "pixel " << i;
}

// The small triangles' kernels take each sample's depth from SampleDepths
// (sampleDepthsInTile), the larger ones move the plane (Plane::atSample)
// and rebase it to the tile (planeInTile) themselves: a triangle's depths
// must not change with the path it takes, so the two agree to the bit, over
// random planes (slopes up to 1 a pixel, depths in [0, 1]) and tile offsets.
TEST(DepthPrecision, EachSampleDepthRoundsAsThePlaneMovedThenRebased) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> slope(-1.0f, 1.0f), depth(0.0f, 1.0f);
  std::uniform_int_distribution<int> corner(0, 8191);
  const auto tile = std::make_unique<TileBuffers>();
  for (const int samples : {2, 4, 8, 16}) {
    const SamplePattern& pattern = samplePattern(samples);
    for (int trial = 0; trial < 20000; ++trial) {
      const float scale = std::ldexp(1.0f, -(trial % 24));  // slopes down to 2^-23 a pixel
      const Plane plane{slope(random) * scale, slope(random) * scale, depth(random)};
      TriangleRecord t;
      t.minX = std::int16_t(corner(random)), t.minY = std::int16_t(corner(random));
      tile->originX = (t.minX + trial % 64) / kTileSize * kTileSize;
      tile->originY = (t.minY + trial % 64) / kTileSize * kTileSize;
      float atSamples[kMaxSamples];
      withSampleCount(samples, [&](auto count) {
        sampleDepthsInTile(plane, pattern, t, *tile, decltype(count)::value, atSamples);
      });
      for (int k = 0; k < samples; ++k) {
        // volatile: the moved plane's depth is rounded to float before it
        // is rebased, whatever the compiler does with this loop.
        volatile float moved = plane.atSample(pattern.offsets[k]).c;
        const float expected = planeInTile(Plane{plane.dx, plane.dy, moved}, t, *tile).c;
        ASSERT_EQ(std::memcmp(&expected, &atSamples[k], sizeof(float)), 0)
            << samples << " samples, sample " << k << ": " << expected << " against "
            << atSamples[k];
      }
    }
  }
}

}  // namespace
}  // namespace quadra
