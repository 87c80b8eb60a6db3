// KHR_texture_transform: the engine's matrix against a double evaluation and
// against the extension's own example; applied in the vertex stage it gives
// the frame that coordinates transformed beforehand give (so derivatives and
// LOD follow it); and the shared TextureTransform models against the
// reference tracer, which applies the transform on a path of its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "api/renderer.h"
#include "lab/image/image_difference.h"
#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"
#include "param_names.h"
#include "render_helpers.h"
#include "scene/gltf_loader.h"

namespace quadra {
namespace {

namespace fs = std::filesystem;

// The extension's definition in double: scale, then rotate (the vector (1, 0)
// goes to (cos r, -sin r)), then offset.
glm::dvec2 transformInDouble(const TextureTransform& t, const glm::dvec2& uv) {
  const double c = std::cos(double(t.rotation)), s = std::sin(double(t.rotation));
  const double x = uv.x * t.scale.x, y = uv.y * t.scale.y;
  return {c * x + s * y + t.offset.x, -s * x + c * y + t.offset.y};
}

glm::vec2 applyMatrix(const TextureTransform& t, const glm::vec2& uv) {
  return t.matrix() * glm::vec3(uv, 1.0f);
}

TEST(TextureTransform, MatrixMatchesADoubleEvaluation) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> offset(-3.0f, 3.0f), rotation(-7.0f, 7.0f),
      scale(-4.0f, 4.0f), coordinate(-2.0f, 3.0f);
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    TextureTransform t;
    t.offset = {offset(rng), offset(rng)};
    t.rotation = rotation(rng);
    t.scale = {scale(rng), scale(rng)};
    const glm::vec2 uv(coordinate(rng), coordinate(rng));
    const glm::dvec2 expected = transformInDouble(t, uv);
    const glm::vec2 got = applyMatrix(t, uv);
    // Float entries and a float dot product: a few ulps of the largest term
    // (|scale x uv| <= 12, |offset| <= 3).
    const double bound = 16.0 * 12.0 * 0x1p-24;
    for (int k = 0; k < 2; ++k) worst = std::max(worst, std::fabs(got[k] - expected[k]));
    EXPECT_LE(std::fabs(got.x - expected.x), bound) << i;
    EXPECT_LE(std::fabs(got.y - expected.y), bound) << i;
  }
  std::printf("[ texture transform ] largest error against double: %.3g\n", worst);
  EXPECT_EQ(TextureTransform{}.matrix(), glm::mat3x2(1.0f));
  EXPECT_TRUE(TextureTransform{}.isIdentity());
}

// The extension's example: offset (0, 1), rotation pi/2 and scale 0.5 read
// "the lower left quadrant of the source image, rotated clockwise 90°".
TEST(TextureTransform, TheExtensionsExampleReadsTheLowerLeftQuadrant) {
  TextureTransform t;
  t.offset = {0.0f, 1.0f};
  t.rotation = 1.57079632679f;
  t.scale = {0.5f, 0.5f};
  const glm::vec2 corners[4][2] = {{{0, 0}, {0.0f, 1.0f}},
                                   {{1, 0}, {0.0f, 0.5f}},
                                   {{0, 1}, {0.5f, 1.0f}},
                                   {{1, 1}, {0.5f, 0.5f}}};
  for (const auto& [from, to] : corners) {
    const glm::vec2 got = applyMatrix(t, from);
    EXPECT_NEAR(got.x, to.x, 1e-6) << from.x << "," << from.y;
    EXPECT_NEAR(got.y, to.y, 1e-6) << from.x << "," << from.y;
  }
}

Frame renderScene(const Scene& scene, const RenderSettings& settings) {
  return renderOnce(scene, firstCameraOrDefault(scene), settings);
}

// The ground plane to the horizon (every footprint from magnified to strongly
// anisotropic): a transform in the material must draw what the same transform
// applied to the mesh's coordinates draws. Axis-aligned scales are exact in
// float either way, so those frames are the same bits, with every filter's
// footprint; a rotation and offset round differently, so only nearly.
TEST(TextureTransform, InTheMaterialEqualsCoordinatesTransformedBeforehand) {
  const Scene plain = makeBuiltinScene("checker-plane");
  const auto compare = [&](const TextureTransform& t, Filter filter, double minPsnr) {
    Scene inMaterial = plain, inMesh = plain;
    for (Material& m : inMaterial.materials) m.baseColorTransform = t;
    for (Mesh& mesh : inMesh.meshes)
      for (glm::vec2& uv : mesh.texcoords[0]) uv = applyMatrix(t, uv);
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.filter = filter;
    const Frame a = renderScene(inMaterial, settings), b = renderScene(inMesh, settings);
    const Frame untransformed = renderScene(plain, settings);
    EXPECT_NE(a.rgba, untransformed.rgba) << filterName(filter);
    if (minPsnr == 0.0) {
      EXPECT_EQ(a.rgba, b.rgba) << filterName(filter);
    } else {
      const double psnr = imageDifference(frameImage(a), frameImage(b)).psnr;
      EXPECT_GT(psnr, minPsnr) << filterName(filter);
    }
  };
  TextureTransform scaled;
  scaled.scale = {2.0f, 3.0f};
  TextureTransform general;
  general.offset = {0.3f, -0.7f};
  general.rotation = 0.6f;
  general.scale = {1.5f, 0.75f};
  for (const Filter filter : {Filter::Trilinear, Filter::Anisotropic, Filter::NearestMip}) {
    compare(scaled, filter, 0.0);
    compare(general, filter, 60.0);
  }
}

// ---- the shared models against the reference tracer ---------------------------------

constexpr int kWidth = 320;
constexpr int kHeight = 240;
// 6 x 6 exact hits a pixel, box filtered.
constexpr int kReferenceSamplesPerAxis = 6;

std::string modelPath(const std::string& model) {
  return std::string(QUADRA_ASSETS_DIR) + "/" + model + "/glTF/" + model + ".gltf";
}

// The pixels whose centre the reference sees on a surface with a texture
// transform: where a wrong transform shows (the rest of a model, labels and
// backgrounds, would only dilute the figure).
std::vector<bool> transformedPixels(const Scene& scene, const ref::ReferenceTracer& tracer) {
  std::vector<bool> mask(std::size_t(kWidth) * kHeight, false);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::optional<ref::TracerHit> hit = tracer.nearestHit({x + 0.5, y + 0.5});
      if (!hit) continue;
      const int material =
          scene.meshes[std::size_t(scene.instances[std::size_t(hit->instance)].mesh)].material;
      mask[std::size_t(y) * kWidth + x] =
          material >= 0 && !scene.materials[std::size_t(material)].baseColorTransform.isIdentity();
    }
  return mask;
}

// PSNR (peak 1) over R, G and B of the masked pixels.
double maskedPsnr(const Image& a, const Image& b, const std::vector<bool>& mask) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t p = 0; p < mask.size(); ++p) {
    if (!mask[p]) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.rgba[p * 4 + c]) - double(b.rgba[p * 4 + c]);
      sum += d * d;
    }
    count += 3;
  }
  return -10.0 * std::log10(sum / double(count));
}

Image drawnFrame(const Scene& scene) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.samples = 16;  // edges as the reference's box filter sees them
  return frameImage(renderScene(scene, settings));
}

struct TransformModel {
  const char* name;
  double minPsnr;  // dB; the frame drawn without the transforms must fall below it
};

class TextureTransformModels : public ::testing::TestWithParam<TransformModel> {};

TEST_P(TextureTransformModels, MatchTheReferenceTracer) {
  const TransformModel model = GetParam();
  const std::string path = modelPath(model.name);
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
  const Scene scene = loadGltf(path);
  const ref::ReferenceTracer tracer(scene, firstCameraOrDefault(scene), kWidth, kHeight);
  const Image reference = tracer.render(kReferenceSamplesPerAxis);
  const std::vector<bool> mask = transformedPixels(scene, tracer);
  ASSERT_GT(std::count(mask.begin(), mask.end(), true), 400);
  const Image drawn = drawnFrame(scene);
  const double whole = imageDifference(drawn, reference).psnr;
  const double transformed = maskedPsnr(drawn, reference, mask);
  // The same frame with the transforms dropped (what quadra drew before it
  // read the extension): the threshold must tell the two apart.
  Scene untransformed = scene;
  for (Material& m : untransformed.materials) m.baseColorTransform = TextureTransform{};
  const double without = maskedPsnr(drawnFrame(untransformed), reference, mask);
  std::printf(
      "[ %s %dx%d ] PSNR against the reference: %.2f dB on the transformed surfaces (%.2f dB "
      "without the transforms), %.2f dB on the whole frame\n",
      model.name, kWidth, kHeight, transformed, without, whole);
  EXPECT_GT(transformed, model.minPsnr);
  EXPECT_LT(without, model.minPsnr);
}

std::string transformModelName(const ::testing::TestParamInfo<TransformModel>& info) {
  return asTestName(info.param.name);
}

INSTANTIATE_TEST_SUITE_P(SharedAssets, TextureTransformModels,
                         ::testing::Values(TransformModel{"TextureTransformTest", 20.0},
                                           TransformModel{"TextureTransformMultiTest", 20.0}),
                         transformModelName);

}  // namespace
}  // namespace quadra
