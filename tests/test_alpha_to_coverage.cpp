// Alpha to coverage (RenderSettings::alphaToCoverage): a masked surface
// whose alpha ramps across the view resolves, at N samples, to the fraction
// of samples round(alpha * N), within half a sample of the alpha itself;
// the cutoff test resolves it to 0 or 1.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "lab/scene/hard_case_scenes.h"
#include "render_helpers.h"
#include "texture/texture.h"

namespace quadra {
namespace {

constexpr int kSize = kPixelExactSize;

// A white MASK quad over the whole pixel-exact viewport whose texture's
// alpha at window x is x / kSize (one texel a pixel, magnified bilinear, so
// at pixel centres exactly (x + 0.5) / kSize).
Scene alphaRampScene() {
  Scene scene;
  scene.name = "alpha-ramp";
  Image ramp(kSize, 1);
  for (int x = 0; x < kSize; ++x) {
    float* texel = ramp.texel(x, 0);
    texel[0] = texel[1] = texel[2] = 1.0f;
    texel[3] = (float(x) + 0.5f) / float(kSize);
  }
  SamplerState sampler;
  sampler.wrapU = sampler.wrapV = WrapMode::ClampToEdge;
  scene.textures.push_back(
      std::make_shared<const Texture>(std::make_shared<const Image>(std::move(ramp)), sampler));
  Material mask;
  mask.baseColorTexture = 0;
  mask.alphaMode = AlphaMode::Mask;
  mask.doubleSided = true;
  scene.materials.push_back(mask);
  Mesh quad;
  for (const auto& [x, y] : {std::pair{0, 0}, {kSize, 0}, {kSize, kSize}, {0, kSize}}) {
    quad.positions.push_back(worldFromWindow(x, y));
    quad.texcoords[0].push_back({float(x) / float(kSize), 0.5f});
  }
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = 0;
  scene.meshes.push_back(quad);
  scene.instances.push_back({0, glm::mat4(1.0f)});
  scene.cameras.push_back(pixelExactCamera());
  return scene;
}

Frame renderRamp(int samples, bool alphaToCoverage, Isa isa = Isa::Scalar) {
  RenderSettings settings;
  settings.width = settings.height = kSize;
  settings.samples = samples;
  settings.alphaToCoverage = alphaToCoverage;
  const Scene scene = alphaRampScene();
  return renderOnce(scene, scene.cameras[0], settings, 2, isa);
}

TEST(AlphaToCoverage, CoversTheFractionOfSamplesTheAlphaSays) {
  for (const int samples : {4, 16}) {
    for (const Isa isa : supportedIsas()) {
      SCOPED_TRACE(std::to_string(samples) + " samples, " + isaName(isa));
      const Frame frame = renderRamp(samples, true, isa);
      double largest = 0.0;
      for (int y = 0; y < kSize; y += 37)
        for (int x = 0; x < kSize; ++x) {
          const float* pixel = &frame.rgba[(std::size_t(y) * kSize + std::size_t(x)) * 4];
          const double alpha = (x + 0.5) / kSize, covered = pixel[3];
          // The covered fraction is a whole number of samples, white where covered.
          ASSERT_EQ(covered * samples, std::round(covered * samples)) << x << ", " << y;
          ASSERT_EQ(pixel[0], pixel[3]);
          largest = std::max(largest, std::abs(covered - alpha));
        }
      // Half a sample, and each sample's own alpha is up to half a pixel's
      // ramp (1 / (2 kSize)) from the centre's.
      EXPECT_LE(largest, 0.5 / samples + 0.5 / kSize);
      EXPECT_GE(largest, 0.25 / samples);  // a real ramp of steps, not the alpha itself
    }
  }
}

TEST(AlphaToCoverage, TheCutoffTestCoversAllOrNothing) {
  const Frame cutoff = renderRamp(16, false);
  for (int x = 0; x < kSize; ++x) {
    const float covered = cutoff.rgba[std::size_t(x) * 4 + 3];
    EXPECT_EQ(covered, (x + 0.5) / kSize >= 0.5 ? 1.0f : 0.0f) << x;
  }
  // One sample: alpha to coverage is the cutoff at 0.5.
  const Frame one = renderRamp(1, true), oneCutoff = renderRamp(1, false);
  EXPECT_EQ(one.rgba, oneCutoff.rgba);
}

}  // namespace
}  // namespace quadra
