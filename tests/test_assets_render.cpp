// Every shared sample model (QUADRA_ASSETS_DIR/<Model>/glTF/*.gltf) loads and
// renders at 160x120 through its first camera (or the default framing)
// without throwing, and shows something when it has triangles.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "api/renderer.h"
#include "param_names.h"
#include "scene/gltf_loader.h"

namespace quadra {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> sampleModels() {
  std::vector<std::string> files;
  std::error_code error;
  if (!fs::is_directory(QUADRA_ASSETS_DIR, error)) return files;
  for (const fs::directory_entry& model : fs::directory_iterator(QUADRA_ASSETS_DIR, error)) {
    const fs::path gltfDir = model.path() / "glTF";
    if (!fs::is_directory(gltfDir, error)) continue;
    for (const fs::directory_entry& file : fs::directory_iterator(gltfDir, error))
      if (file.path().extension() == ".gltf") files.push_back(file.path().string());
  }
  std::sort(files.begin(), files.end());
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
