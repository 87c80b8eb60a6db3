// Every shared sample model (QUADRA_ASSETS_DIR/<Model>/glTF/*.gltf) loads and
// renders at 160x120 through its first camera (or the default framing)
// without throwing, and matches the double-precision reference tracer
// (lab/reference) at its first frame (an animated model posed at time 0 of
// its first animation, as `render --sequence 0:N` draws it): PSNR over the whole frame at 16
// samples per pixel against 6 x 6 exact hits a pixel, box filtered. The
// floor is low enough for what filtering legitimately changes (a texture
// minified to a few pixels a texel row, which the reference point-samples)
// and high enough that a wrong winding, wrap mode or texture transform falls
// under it: the last test breaks each on purpose and checks that it does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "api/renderer.h"
#include "lab/image/image_difference.h"
#include "lab/reference/reference_tracer.h"
#include "param_names.h"
#include "render_helpers.h"
#include "sample_models.h"
#include "scene/animation.h"
#include "scene/gltf_loader.h"

namespace quadra {
namespace {

namespace fs = std::filesystem;

// The models quadra loads (those requiring an extension it lacks are
// GltfSampleModels.EveryModelLoadsOrIsRefusedForItsRequiredExtension's).
std::vector<std::string> sampleModels() {
  std::vector<std::string> files;
  for (const fs::path& model : loadableSampleModels()) files.push_back(model.string());
  return files;
}

class AssetsRender : public ::testing::TestWithParam<std::string> {};

TEST_P(AssetsRender, LoadsAndRendersSomething) {
  const std::string path = GetParam();
  Scene scene;
  ASSERT_NO_THROW(scene = loadGltf(path)) << path;
  const Camera camera = firstCameraOrDefault(scene);
  RendererConfig config;
  config.threads = 2;
  Renderer renderer(config);
  RenderSettings settings;
  settings.width = 160;
  settings.height = 120;
  Frame frame;
  ASSERT_NO_THROW(renderer.render(scene, camera, settings, frame)) << path;
  ASSERT_EQ(frame.rgba.size(), std::size_t(160) * 120 * 4);
  if (scene.triangleCount() == 0) return;
  int visible = 0;
  for (std::size_t i = 3; i < frame.rgba.size(); i += 4) visible += frame.rgba[i] > 0.0f;
  EXPECT_GT(visible, 0) << path << ": " << scene.triangleCount() << " triangles, empty frame";
}

constexpr int kWidth = 160;
constexpr int kHeight = 120;

// PSNR of the engine's frame of `drawn` (16 samples, the models' own
// samplers) against the reference tracer's frame of `reference`, both
// through the first camera.
double psnrAgainstReference(const Scene& drawn, const Scene& reference) {
  const Camera camera = firstCameraOrDefault(reference);
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.samples = 16;
  return imageDifference(frameImage(renderOnce(drawn, camera, settings)),
                         ref::ReferenceTracer(reference, camera, kWidth, kHeight).render(6))
      .psnr;
}

// dB; measured 31.1-52.5 on every model but the two below (2026-11-27), and
// 17.2, 25.7 and 14.4 with the breakages of the last test. Models with a
// floor of their own, and why (a negative floor would leave one out):
// BoxTextured and BoxTexturedNonPowerOfTwo minify with NEAREST_MIPMAP_LINEAR,
// the nearest texel of a level, where the reference box-filters level 0
// bilinearly: 29.4 and 30.0 dB.
constexpr double kFloor = 29.0;
const std::map<std::string, double> kExceptions = {{"BoxTextured", 27.0},
                                                   {"BoxTexturedNonPowerOfTwo", 27.0}};

TEST_P(AssetsRender, MatchesTheReferenceTracerAtItsFirstFrame) {
  const std::string path = GetParam();
  const std::string model = fs::path(path).stem().string();
  const auto exception = kExceptions.find(model);
  const double floor = exception == kExceptions.end() ? kFloor : exception->second;
  if (floor < 0.0) GTEST_SKIP() << model << " is left out (see kExceptions)";
  Scene scene = loadGltf(path);
  if (scene.triangleCount() == 0) GTEST_SKIP() << model << " draws no triangles";
  if (!scene.animations.empty()) {  // the first frame of `render --sequence 0:...`
    NodePose pose;
    poseNodes(scene, 0, 0.0, pose);
    placeOnNodes(scene, pose);
  }
  const double psnr = psnrAgainstReference(scene, scene);
  std::printf("[ %s %dx%d ] PSNR against the reference tracer: %.2f dB (floor %.1f)\n",
              model.c_str(), kWidth, kHeight, psnr, floor);
  EXPECT_GT(psnr, floor) << path;
}

std::string assetPath(const std::string& model) {
  return std::string(QUADRA_ASSETS_DIR) + "/" + model + "/glTF/" + model + ".gltf";
}

// What the floor is for: the models drawn with one thing broken on purpose
// (in the engine's copy of the scene only) fall under it.
TEST(AssetsReference, AWrongWindingWrapModeOrTextureTransformFallsUnderTheFloor) {
  for (const char* model : {"NegativeScaleTest", "TextureSettingsTest", "TextureTransformTest"})
    if (!fs::exists(assetPath(model))) GTEST_SKIP() << "no " << assetPath(model);
  {  // every triangle wound the other way: culling keeps the wrong side
    const Scene reference = loadGltf(assetPath("NegativeScaleTest"));
    Scene scene = reference;
    for (Mesh& mesh : scene.meshes)
      for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
        std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
    const double psnr = psnrAgainstReference(scene, reference);
    std::printf("[ NegativeScaleTest, winding reversed ] %.2f dB\n", psnr);
    EXPECT_LT(psnr, kFloor);
  }
  {  // every texture repeating, whatever its sampler says
    const Scene reference = loadGltf(assetPath("TextureSettingsTest"));
    Scene scene = reference;
    for (auto& texture : scene.textures) {
      SamplerState sampler = texture->sampler();
      sampler.wrapU = sampler.wrapV = WrapMode::Repeat;
      texture = std::make_shared<const Texture>(texture->sharedImage(), sampler, texture->storage(),
                                                texture->alpha());
    }
    const double psnr = psnrAgainstReference(scene, reference);
    std::printf("[ TextureSettingsTest, every wrap repeat ] %.2f dB\n", psnr);
    EXPECT_LT(psnr, kFloor);
  }
  {  // KHR_texture_transform ignored, as quadra once did
    const Scene reference = loadGltf(assetPath("TextureTransformTest"));
    Scene scene = reference;
    for (Material& material : scene.materials) material.baseColorTransform = TextureTransform{};
    const double psnr = psnrAgainstReference(scene, reference);
    std::printf("[ TextureTransformTest, transforms dropped ] %.2f dB\n", psnr);
    EXPECT_LT(psnr, kFloor);
  }
}

std::string modelName(const ::testing::TestParamInfo<std::string>& info) {
  return asTestName(fs::path(info.param).stem().string());
}

INSTANTIATE_TEST_SUITE_P(SampleModels, AssetsRender, ::testing::ValuesIn(sampleModels()),
                         modelName);
// Without the assets folder the suite has no instances; that is a skip, not an error.
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(AssetsRender);

// Reports the skip when the folder is absent; when present, checks that the
// models bench/frame_bench.cpp measures are among them.
TEST(AssetsRenderFolder, HoldsTheBenchmarkedModels) {
  const std::vector<std::string> models = sampleModels();
  if (models.empty()) GTEST_SKIP() << "no sample models under " << QUADRA_ASSETS_DIR;
  for (const char* name : {"WaterBottle", "GlassVaseFlowers", "MetalRoughSpheresNoTextures"}) {
    const bool found = std::any_of(models.begin(), models.end(), [&](const std::string& path) {
      return fs::path(path).stem() == name;
    });
    EXPECT_TRUE(found) << name;
  }
}

}  // namespace
}  // namespace quadra
