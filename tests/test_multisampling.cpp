// Samples per pixel against the ideal image (the reference tracer's box-
// filtered frame of exact hits): more samples must converge on it, along
// silhouettes at either shading rate, inside textured surfaces when every
// sample is shaded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "api/renderer.h"
#include "lab/image/image_difference.h"
#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"
#include "lab/scene/hard_case_scenes.h"
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

// At 4 and 16 samples a sample is shaded at the centre of its own cell of
// the pixel's 2x2 or 4x4 grid, so the samples' footprints tile the pixel:
// one sample per cell, each cell the one its position lies in or borders.
TEST(Multisampling, ShadingOffsetsTakeOneCellEach) {
  for (const int count : {4, 16}) {
    const SamplePattern& pattern = samplePattern(count);
    const int side = count == 4 ? 2 : 4, cell = kSampleUnitsPerPixel / side;
    std::vector<int> taken(std::size_t(count), 0);
    for (int k = 0; k < count; ++k) {
      const SampleOffset at = pattern.offsets[k], centre = shadingOffset(pattern, k);
      const int cx = (centre.x + kSampleUnitsPerPixel / 2) / cell;
      const int cy = (centre.y + kSampleUnitsPerPixel / 2) / cell;
      ASSERT_EQ(centre.x, -kSampleUnitsPerPixel / 2 + cx * cell + cell / 2) << count << " " << k;
      ASSERT_EQ(centre.y, -kSampleUnitsPerPixel / 2 + cy * cell + cell / 2) << count << " " << k;
      ++taken[std::size_t(cy * side + cx)];
      // Within 1/16 pixel of its cell (the closed square), in each axis.
      EXPECT_LE(std::abs(at.x - centre.x), cell / 2 + 1) << count << " " << k;
      EXPECT_LE(std::abs(at.y - centre.y), cell / 2 + 1) << count << " " << k;
    }
    for (const int n : taken) EXPECT_EQ(n, 1) << count;
  }
  for (const int count : {1, 2, 8})
    for (int k = 0; k < count; ++k) {
      EXPECT_EQ(shadingOffset(samplePattern(count), k).x, samplePattern(count).offsets[k].x);
      EXPECT_EQ(shadingOffset(samplePattern(count), k).y, samplePattern(count).offsets[k].y);
    }
}

// Inside a plane, 16 samples shaded per sample are the frame at 4x4 the
// resolution box-downsampled: the same lookups (each cell's centre, a
// quarter of the pixel's footprint), summed in another order. Shaded at the
// standard positions instead, each lookup would read the plane up to 3/16
// pixel away from its cell's centre.
TEST(Multisampling, SixteenSamplesShadedPerSampleAreTheFrameAtFourTimesTheResolution) {
  const Scene scene = makeBuiltinScene("checker-plane");
  const Camera camera = firstCameraOrDefault(scene);
  const int width = 64, height = 36;
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.filter = Filter::Anisotropic;
  settings.samples = 16;
  settings.shadingRate = ShadingRate::Sample;
  const Frame sixteen = renderOnce(scene, camera, settings);
  settings.width = 4 * width;
  settings.height = 4 * height;
  settings.samples = 1;
  const Frame large = renderOnce(scene, camera, settings);
  // Rows below the plane's far edge (the horizon lies at y ~ 14.9), where
  // every sample of a pixel sees the plane.
  double worst = 0.0;
  for (int y = 17; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (int j = 0; j < 4; ++j)
          for (int i = 0; i < 4; ++i)
            sum +=
                large.rgba[(std::size_t(4 * y + j) * std::size_t(4 * width) + 4 * x + i) * 4 + c];
        const double got = sixteen.rgba[(std::size_t(y) * width + x) * 4 + c];
        worst = std::max(worst, std::fabs(got - sum / 16.0));
      }
  EXPECT_LT(worst, 1e-4);
}

// Draws of one colour each (untextured, unlit, without vertex colours)
// shade every sample alike, so shading once per pixel must give the frame
// that shading each sample gives, to the bit: a pixel whose samples the
// triangles of one such draw hold, every one, is shaded once in plane 0
// (tile_stage.cpp wholePixelsOfOneColour), one it shares with another
// draw or with the clear colour once per triangle. Taking the wrong pixels
// out (one with a clear sample, or another draw's) moves an edge pixel to
// one colour. Random triangles, a third of them tiny, in two draws of two
// colours, and in one draw alone, whose tiles' mixed pixels are found by
// coverage and written from one shaded colour (tile_stage.cpp
// writeCoverageColors); with the box filter (mixed pixels resolved as they
// are shaded) and Blackman-Harris (every sample's colour kept).
TEST(Multisampling, OneColourDrawsAreTheFrameShadedPerSample) {
  Scene scene = randomTrianglesScene(4000, 7);
  ASSERT_EQ(scene.meshes.size(), 1u);
  Mesh& first = scene.meshes[0];
  first.texcoords[0].clear();
  Mesh second;
  const std::size_t half = first.indices.size() / 6 * 3;
  second.positions.assign(first.positions.begin() + std::ptrdiff_t(half), first.positions.end());
  first.positions.resize(half);
  for (Mesh* mesh : {&first, &second}) {
    mesh->indices.resize(mesh->positions.size());
    for (std::size_t i = 0; i < mesh->indices.size(); ++i) mesh->indices[i] = std::uint32_t(i);
  }
  scene.materials.resize(2);
  for (Material& material : scene.materials) {
    material.baseColorTexture = -1;
    material.doubleSided = true;
  }
  scene.materials[0].baseColorFactor = {0.8f, 0.3f, 0.1f, 1.0f};
  scene.materials[1].baseColorFactor = {0.1f, 0.45f, 0.9f, 1.0f};
  second.material = 1;
  const Scene oneDraw = scene;
  scene.meshes.push_back(std::move(second));
  scene.instances.push_back({1, scene.instances[0].world});
  for (const Scene* draws : {static_cast<const Scene*>(&scene), &oneDraw})
    for (const PixelFilter filter : {PixelFilter::Box, PixelFilter::BlackmanHarris})
      for (const int samples : {2, 4, 8, 16}) {
        SCOPED_TRACE(std::to_string(draws->meshes.size()) + " draws, " +
                     (filter == PixelFilter::Box ? "box, " : "Blackman-Harris, ") +
                     std::to_string(samples) + " samples");
        RenderSettings settings;
        settings.width = 203;
        settings.height = 117;
        settings.samples = samples;
        settings.pixelFilter = filter;
        const Frame perPixel = renderOnce(*draws, firstCameraOrDefault(*draws), settings);
        settings.shadingRate = ShadingRate::Sample;
        const Frame perSample = renderOnce(*draws, firstCameraOrDefault(*draws), settings);
        ASSERT_EQ(perPixel.rgba.size(), perSample.rgba.size());
        std::size_t differing = 0, edge = 0;
        for (std::size_t i = 0; i < perPixel.rgba.size(); ++i) {
          differing += std::memcmp(&perPixel.rgba[i], &perSample.rgba[i], sizeof(float)) != 0;
          const float value = perPixel.rgba[i];
          edge += i % 4 == 0 && value != 0.8f && value != 0.1f && value != 0.0f;
        }
        EXPECT_EQ(differing, 0u);
        EXPECT_GT(edge, 100u);  // pixels that mix the colours: the case is there
      }
}

// Blended draws shaded once per pixel (tile_kernel.h shadeBlendedPixels): a
// pixel every sample of which a blended triangle covers is shaded at its
// centre, so inside builtin:alpha-quads' textured, half-transparent quads
// (and its opaque background, shaded at the centre too) every sample holds
// the one-sample frame's colour and their mean is that colour to the bit.
// Only pixels along an edge (the quads' outlines, the background's
// diagonal: 12.5% of the frame at 4 samples, 14.6% at 16) may differ. Shaded per sample, each
// sample reads the gradient texture at its own position, and nearly every
// pixel differs.
TEST(Multisampling, BlendedDrawsAreShadedOncePerPixel) {
  const Scene scene = makeBuiltinScene("alpha-quads");
  const Camera camera = firstCameraOrDefault(scene);
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  const Frame one = renderOnce(scene, camera, settings);
  const auto sameAsOneSample = [&](const Frame& frame) {
    std::size_t same = 0;
    for (std::size_t p = 0; p < one.rgba.size(); p += 4)
      same += std::memcmp(&frame.rgba[p], &one.rgba[p], 4 * sizeof(float)) == 0;
    return double(same) / double(one.rgba.size() / 4);
  };
  for (const int samples : {4, 16}) {
    settings.samples = samples;
    settings.shadingRate = ShadingRate::Pixel;
    const double perPixel = sameAsOneSample(renderOnce(scene, camera, settings));
    settings.shadingRate = ShadingRate::Sample;
    const double perSample = sameAsOneSample(renderOnce(scene, camera, settings));
    std::printf(
        "[ alpha-quads, %d samples ] pixels equal to the 1-sample frame's: %.3f shaded "
        "per pixel, %.3f per sample\n",
        samples, perPixel, perSample);
    EXPECT_GT(perPixel, 0.8) << samples << " samples";
    EXPECT_LT(perSample, 0.2) << samples << " samples";
  }
}

// A blended pixel whose samples its triangle covers only in part is shaded
// at the mean of those samples, inside the triangle, never at the pixel
// centre outside it. Small blended triangles of opaque red, green and blue
// corners (a colour gradient of up to 0.2 a pixel) over a transparent
// clear: each pixel's resolved colour over its resolved alpha is the colour
// shaded there, which interpolation inside the triangle keeps within
// [0, 1] in every channel; shaded half a pixel outside, an edge pixel's
// colour would leave it by up to 0.1.
TEST(Multisampling, BlendedEdgePixelsAreShadedInsideTheirTriangles) {
  Scene scene;
  scene.name = "blended-gradients";
  Material material;
  material.alphaMode = AlphaMode::Blend;
  material.doubleSided = true;
  scene.materials = {material};
  Mesh mesh;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> at(8.0, 248.0), size(5.0, 12.0);
  for (int n = 0; n < 60; ++n) {
    const double x = at(rng), y = at(rng), w = size(rng), h = size(rng);
    const auto base = std::uint32_t(mesh.positions.size());
    mesh.positions.push_back(worldFromWindow(x, y));
    mesh.positions.push_back(worldFromWindow(x + w, y + 0.3 * h));
    mesh.positions.push_back(worldFromWindow(x + 0.4 * w, y + h));
    mesh.colors.insert(mesh.colors.end(), {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
  }
  mesh.material = 0;
  scene.meshes.push_back(std::move(mesh));
  scene.instances.push_back({0, glm::mat4(1.0f)});
  scene.cameras.push_back(pixelExactCamera());
  for (const int samples : {4, 16}) {
    RenderSettings settings;
    settings.width = settings.height = kPixelExactSize;
    settings.samples = samples;
    const Frame frame = renderOnce(scene, scene.cameras[0], settings);
    std::size_t edge = 0;
    float worst = 0.0f;  // how far outside [0, 1] a shaded channel lies
    for (std::size_t p = 0; p < frame.rgba.size(); p += 4) {
      const float alpha = frame.rgba[p + 3];
      if (alpha <= 0.0f) continue;
      edge += alpha < 1.0f;
      for (int c = 0; c < 3; ++c) {
        const float shaded = frame.rgba[p + std::size_t(c)] / alpha;
        worst = std::max({worst, -shaded, shaded - 1.0f});
      }
    }
    EXPECT_GT(edge, 1000u) << samples << " samples: the case is there";
    EXPECT_LT(worst, 1e-5f) << samples << " samples";
  }
}

}  // namespace
}  // namespace quadra
