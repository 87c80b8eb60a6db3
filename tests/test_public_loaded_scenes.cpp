// What the public API offers for a loaded scene. LoadOptions: the sandbox
// widened only by allowedPaths, the memory budget and the scene index, each
// refusal a one-line error naming the file. The animation clock
// (Scene::setAnimationTime): frames posed through it are `quadra render
// --sequence`'s EXRs bit for bit (a node hierarchy framed once without a
// camera, a skin, morph targets), the rest pose is the scene as loaded, and
// bad animations and times are one-line errors.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.h"
#include "quadra/quadra.hpp"

namespace quadra {
namespace {

namespace api = quadra::api;

constexpr int kWidth = 64;
constexpr int kHeight = 48;

// R, G, B, A interleaved and Z, as the CLI wrote them.
struct ExrFrame {
  std::vector<float> rgba, depth;
};

ExrFrame readExrFrame(const fs::path& path) {
  Imf::InputFile file(path.string().c_str());
  const Imath::Box2i window = file.header().dataWindow();
  EXPECT_EQ(window.max.x - window.min.x + 1, kWidth);
  EXPECT_EQ(window.max.y - window.min.y + 1, kHeight);
  ExrFrame frame{std::vector<float>(std::size_t(kWidth) * kHeight * 4),
                 std::vector<float>(std::size_t(kWidth) * kHeight)};
  Imf::FrameBuffer buffer;
  const auto origin = [&](float* first, int channels) {
    return reinterpret_cast<char*>(first - (std::ptrdiff_t(window.min.y) * kWidth + window.min.x) *
                                               channels);
  };
  const char* names[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c)
    buffer.insert(names[c], Imf::Slice(Imf::FLOAT, origin(frame.rgba.data() + c, 4),
                                       4 * sizeof(float), std::size_t(kWidth) * 4 * sizeof(float)));
  buffer.insert("Z", Imf::Slice(Imf::FLOAT, origin(frame.depth.data(), 1), sizeof(float),
                                std::size_t(kWidth) * sizeof(float)));
  file.setFrameBuffer(buffer);
  file.readPixels(window.min.y, window.max.y);
  return frame;
}

ExrFrame renderThroughApi(const api::Scene& scene, api::Renderer& renderer) {
  ExrFrame frame{std::vector<float>(std::size_t(kWidth) * kHeight * 4),
                 std::vector<float>(std::size_t(kWidth) * kHeight)};
  const api::DepthTarget depth{.bytes = std::as_writable_bytes(std::span(frame.depth)),
                               .rowStride = kWidth * sizeof(float)};
  renderer.render(scene,
                  {.pixels = std::as_writable_bytes(std::span(frame.rgba)),
                   .width = kWidth,
                   .height = kHeight,
                   .rowStride = kWidth * 4 * sizeof(float),
                   .format = api::PixelFormat::Rgba32F},
                  &depth);
  return frame;
}

std::size_t differingFloats(const std::vector<float>& a, const std::vector<float>& b) {
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differing += std::memcmp(&a[i], &b[i], 4) != 0;
  return differing;
}

// One misuse, and its message (or a part of it).
template <typename Call>
void expectError(Call&& call, const std::string& message, bool whole = true) {
  try {
    call();
    ADD_FAILURE() << "no error, expected: " << message;
  } catch (const api::Error& error) {
    if (whole)
      EXPECT_EQ(std::string(error.what()), message);
    else
      EXPECT_NE(std::string(error.what()).find(message), std::string::npos) << error.what();
  }
}

std::size_t coveredPixels(const ExrFrame& frame) {
  std::size_t covered = 0;
  for (std::size_t i = 3; i < frame.rgba.size(); i += 4) covered += frame.rgba[i] > 0.0f;
  return covered;
}

TEST(PublicLoadOptions, SandboxBudgetAndSceneGuardTheLoad) {
  const std::string box = modelPath("Box");
  if (!fs::exists(box)) GTEST_SKIP() << "no " << box;
  // Box.gltf in a folder of its own, its buffer moved into a sibling folder.
  const fs::path root = emptyFolder("public_load_options");
  fs::create_directories(root / "scene");
  fs::create_directories(root / "outside");
  fs::copy_file(fs::path(box).parent_path() / "Box0.bin", root / "outside" / "Box0.bin");
  std::stringstream text;
  text << std::ifstream(box).rdbuf();
  std::string json = text.str();
  const std::string uri = "\"Box0.bin\"";
  ASSERT_NE(json.find(uri), std::string::npos);
  json.replace(json.find(uri), uri.size(), "\"../outside/Box0.bin\"");
  const std::string escaping = (root / "scene" / "box.gltf").string();
  std::ofstream(escaping) << json;

  expectError([&] { (void)api::load(escaping); }, "URI '../outside/Box0.bin'", false);
  expectError([&] { (void)api::load(escaping, {.allowedPaths = {(root / "scene").string()}}); },
              "URI '../outside/Box0.bin'", false);
  const api::Scene allowed = api::load(escaping, {.allowedPaths = {(root / "outside").string()}});
  api::Renderer renderer({.threads = 2});
  EXPECT_GT(coveredPixels(renderThroughApi(allowed, renderer)), std::size_t(kWidth * kHeight / 8));

  expectError([&] { (void)api::load(box, {.maxMemory = 1000}); },
              box +
                  ": the file (2898 bytes) needs 2.8 KiB, over the memory budget of 1000 bytes "
                  "(0 bytes already used; --max-memory raises it)");
  expectError([&] { (void)api::load(box, {.scene = 3}); },
              box + ": scene 3 does not exist (the file has 1)");
  expectError([&] { (void)api::load(box, {.scene = -2}); },
              box + ": scene -2 is not a scene index (or -1, the file's default)");
  EXPECT_EQ(api::LoadOptions{}.maxMemory, std::uint64_t(8) << 30);
}

TEST(PublicAnimation, PosedFramesAreTheCliSequencesFrames) {
  int models = 0;
  for (const char* name : {"BoxAnimated", "SimpleSkin", "AnimatedMorphCube"}) {
    const std::string model = modelPath(name);
    if (!fs::exists(model)) continue;
    ++models;
    const fs::path dir = emptyFolder(std::string("public_animation_") + name);
    constexpr int kFrames = 4;
    constexpr double kFps = 3.0;
    const RunResult r = run(
        "render " + model + " --shading unlit --width 64 --height 48 --threads 2 --sequence 0:" +
        std::to_string(kFrames - 1) + " --fps 3 --out " + (dir / "f_#.exr").string());
    ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;

    api::Scene scene = api::load(model);
    ASSERT_EQ(scene.animationCount(), 1) << name;
    api::Renderer renderer({.threads = 2});
    std::vector<ExrFrame> frames;
    for (int f = 0; f < kFrames; ++f) {
      scene.setAnimationTime(0, f / kFps);
      frames.push_back(renderThroughApi(scene, renderer));
      const ExrFrame cli = readExrFrame(dir / ("f_" + std::to_string(f) + ".exr"));
      EXPECT_EQ(differingFloats(frames.back().rgba, cli.rgba), 0u) << name << " frame " << f;
      EXPECT_EQ(differingFloats(frames.back().depth, cli.depth), 0u) << name << " frame " << f;
    }
    // The model moves: the comparison above is between posed frames.
    EXPECT_GT(differingFloats(frames.front().rgba, frames.back().rgba), 10u) << name;
  }
  if (models == 0) GTEST_SKIP() << "no animated models in " << QUADRA_ASSETS_DIR;
}

TEST(PublicAnimation, RestPoseIsTheSceneAsLoaded) {
  const std::string model = modelPath("SimpleSkin");
  if (!fs::exists(model)) GTEST_SKIP() << "no " << model;
  api::Renderer renderer({.threads = 2});
  const api::Scene loaded = api::load(model);
  const ExrFrame asLoaded = renderThroughApi(loaded, renderer);
  api::Scene posed = api::load(model);
  posed.setAnimationTime(0, 2.0);
  const ExrFrame moved = renderThroughApi(posed, renderer);
  posed.setAnimationTime(-1, 0.0);
  const ExrFrame rest = renderThroughApi(posed, renderer);
  EXPECT_GT(differingFloats(moved.rgba, asLoaded.rgba), 10u);
  EXPECT_EQ(differingFloats(rest.rgba, asLoaded.rgba), 0u);
  EXPECT_EQ(differingFloats(rest.depth, asLoaded.depth), 0u);
}

TEST(PublicAnimation, BadAnimationsAndTimesAreOneLineErrors) {
  const std::string model = modelPath("BoxAnimated");
  if (!fs::exists(model)) GTEST_SKIP() << "no " << model;
  api::Scene scene = api::load(model);
  expectError([&] { scene.setAnimationTime(1, 0.0); },
              "setAnimationTime: animation 1 is not one of the scene's 1 (or -1, the rest pose)");
  expectError([&] { scene.setAnimationTime(-2, 0.0); },
              "setAnimationTime: animation -2 is not one of the scene's 1 (or -1, the rest pose)");
  expectError([&] { scene.setAnimationTime(0, std::numeric_limits<double>::quiet_NaN()); },
              "setAnimationTime: seconds nan is not finite");
  expectError([&] { (void)scene.animationName(-1); },
              "animationName: animation -1 is not one of the scene's 1");
  expectError([&] { (void)api::Scene().animationDuration(0); },
              "animationDuration: animation 0 is not one of the scene's 0");
  EXPECT_EQ(scene.animationName(0), "");
  EXPECT_NEAR(scene.animationDuration(0), 3.708, 1e-3);  // BoxAnimated's last key
}

}  // namespace
}  // namespace quadra
