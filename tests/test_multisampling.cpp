// Samples per pixel against the ideal image (the reference tracer's box-
// filtered frame of exact hits): more samples must converge on it, along
// silhouettes at either shading rate, inside textured surfaces when every
// sample is shaded.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "api/renderer.h"
#include "lab/image/image_difference.h"
#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"
#include "render_helpers.h"

namespace quadra {
namespace {

constexpr int kWidth = 128;
constexpr int kHeight = 72;

double psnrAgainst(const Image& ideal, const Scene& scene, int samples, ShadingRate rate) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.samples = samples;
  settings.shadingRate = rate;
  return imageDifference(frameImage(renderOnce(scene, firstCameraOrDefault(scene), settings)),
                         ideal)
      .psnr;
}

Image idealImage(const Scene& scene) {
  // 16 x 16 exact hits a pixel: the reference's own error is far below the
  // differences compared here.
  return ref::ReferenceTracer(scene, firstCameraOrDefault(scene), kWidth, kHeight).render(16);
}

// Silhouettes: closed meshes against the clear colour, untextured, so the
// error is coverage along their outlines (and where they overlap).
TEST(Multisampling, SilhouettesConvergeOnTheIdealImage) {
  for (const std::string name : {"watertight", "closed-mesh"}) {
    SCOPED_TRACE(name);
    const Scene scene = makeBuiltinScene(name);
    const Image ideal = idealImage(scene);
    const double one = psnrAgainst(ideal, scene, 1, ShadingRate::Pixel);
    const double four = psnrAgainst(ideal, scene, 4, ShadingRate::Pixel);
    const double sixteen = psnrAgainst(ideal, scene, 16, ShadingRate::Pixel);
    const double sixteenPerSample = psnrAgainst(ideal, scene, 16, ShadingRate::Sample);
    std::printf("[ %s %dx%d ] PSNR dB: 1 sample %.2f, 4 %.2f, 16 %.2f, 16 per sample %.2f\n",
                name.c_str(), kWidth, kHeight, one, four, sixteen, sixteenPerSample);
    EXPECT_GT(four, one + 6.0);
    EXPECT_GT(sixteen, four + 4.0);
    EXPECT_GT(sixteen, 45.0);
    // Untextured and unlit: shading per sample has nothing more to find.
    EXPECT_NEAR(sixteenPerSample, sixteen, 0.5);
  }
}

// Texture detail inside the triangles (showcase: minified textures on its
// objects) is aliasing that only shading per sample removes: shading once
// per pixel filters each texture over the whole pixel, as one sample does.
TEST(Multisampling, ShadingPerSampleResolvesTextureDetail) {
  const Scene scene = makeBuiltinScene("showcase");
  const Image ideal = idealImage(scene);
  const double one = psnrAgainst(ideal, scene, 1, ShadingRate::Pixel);
  const double sixteen = psnrAgainst(ideal, scene, 16, ShadingRate::Pixel);
  const double sixteenPerSample = psnrAgainst(ideal, scene, 16, ShadingRate::Sample);
  std::printf("[ showcase %dx%d ] PSNR dB: 1 sample %.2f, 16 %.2f, 16 per sample %.2f\n", kWidth,
              kHeight, one, sixteen, sixteenPerSample);
  EXPECT_GT(sixteen, one);
  EXPECT_GT(sixteenPerSample, sixteen + 6.0);
}

}  // namespace
}  // namespace quadra
