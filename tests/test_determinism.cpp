// The determinism contract (DESIGN.md "Threading and determinism"): a frame is
// bit-identical for any thread count and any run, down to the EXR file's
// bytes, and every SIMD kernel path renders exactly what the scalar path does.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "api/renderer.h"
#include "core/error.h"
#include "io/image_io.h"
#include "lab/scene/builtin_scenes.h"
#include "lab/scene/lit_scenes.h"
#include "param_names.h"
#include "render_helpers.h"
#include "scene/gltf_loader.h"

namespace quadra {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;

Frame renderWith(const Scene& scene, int threads, std::optional<Isa> isa,
                 std::optional<Filter> filter = std::nullopt) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.filter = filter;
  return renderOnce(scene, firstCameraOrDefault(scene), settings, threads, isa);
}

// Bitwise equality (so -0 vs +0 or NaN payloads count as differences), with the
// first differing element named on failure.
::testing::AssertionResult sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size())
    return ::testing::AssertionFailure() << "sizes " << a.size() << " vs " << b.size();
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(float)) != 0)
      return ::testing::AssertionFailure() << "element " << i << ": " << a[i] << " vs " << b[i];
  return ::testing::AssertionSuccess();
}
::testing::AssertionResult sameBits(const std::vector<std::uint32_t>& a,
                                    const std::vector<std::uint32_t>& b) {
  if (a != b) return ::testing::AssertionFailure() << "the uint planes differ";
  return ::testing::AssertionSuccess();
}

void expectSameFrame(const Frame& got, const Frame& expected) {
  EXPECT_EQ(got.width, expected.width);
  EXPECT_EQ(got.height, expected.height);
  EXPECT_TRUE(sameBits(got.rgba, expected.rgba)) << "colour";
  EXPECT_TRUE(sameBits(got.depth, expected.depth)) << "depth";
  EXPECT_TRUE(sameBits(got.coverage, expected.coverage)) << "coverage";
  EXPECT_TRUE(sameBits(got.normal, expected.normal)) << "normal";
  EXPECT_TRUE(sameBits(got.position, expected.position)) << "position";
  EXPECT_TRUE(sameBits(got.uv, expected.uv)) << "uv";
  EXPECT_TRUE(sameBits(got.motion, expected.motion)) << "motion";
  EXPECT_TRUE(sameBits(got.primitiveId, expected.primitiveId)) << "id.primitive";
  EXPECT_TRUE(sameBits(got.nodeId, expected.nodeId)) << "id.node";
  EXPECT_TRUE(sameBits(got.materialId, expected.materialId)) << "id.material";
  EXPECT_TRUE(sameBits(got.lod, expected.lod)) << "lod";
  EXPECT_TRUE(sameBits(got.anisotropy, expected.anisotropy)) << "anisotropy";
  EXPECT_TRUE(sameBits(got.albedo, expected.albedo)) << "albedo";
  EXPECT_TRUE(sameBits(got.roughness, expected.roughness)) << "roughness";
  EXPECT_TRUE(sameBits(got.metallic, expected.metallic)) << "metallic";
  EXPECT_TRUE(sameBits(got.emission, expected.emission)) << "emission";
  EXPECT_TRUE(sameBits(got.diffuse, expected.diffuse)) << "diffuse";
  EXPECT_TRUE(sameBits(got.specular, expected.specular)) << "specular";
}

std::string fileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A fresh directory for this test's files, removed when the test ends.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

bool hasVisiblePixels(const Frame& frame) {
  for (std::size_t i = 3; i < frame.rgba.size(); i += 4)
    if (frame.rgba[i] > 0.0f) return true;
  return false;
}

TEST(Determinism, ThreadCountsGiveIdenticalFramesAndFiles) {
  const Scene scene = makeBuiltinScene("showcase");
  const ScratchDir dir("quadra_determinism");
  const Frame reference = renderWith(scene, 1, std::nullopt);
  ASSERT_TRUE(hasVisiblePixels(reference));  // an empty frame would prove nothing
  writeFrame(reference, (dir.path() / "threads1.exr").string());
  const std::string referenceBytes = fileBytes(dir.path() / "threads1.exr");
  ASSERT_FALSE(referenceBytes.empty());
  for (int threads : {1, 2, 3, 4, 8}) {  // more threads than cores included
    SCOPED_TRACE("threads " + std::to_string(threads));
    const Frame frame = renderWith(scene, threads, std::nullopt);
    expectSameFrame(frame, reference);
    const std::filesystem::path file = dir.path() / ("run_" + std::to_string(threads) + ".exr");
    writeFrame(frame, file.string());
    EXPECT_TRUE(fileBytes(file) == referenceBytes) << "EXR bytes differ";
  }
}

TEST(Determinism, RepeatedFramesFromOneRendererAreIdentical) {
  const Scene scene = makeBuiltinScene("showcase");
  RendererConfig config;
  config.threads = 4;
  Renderer renderer(config);
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  Frame first, again;
  renderer.render(scene, firstCameraOrDefault(scene), settings, first);
  for (int run = 0; run < 3; ++run) {
    renderer.render(scene, firstCameraOrDefault(scene), settings, again);
    expectSameFrame(again, first);
  }
}

// A Renderer keeps its front-end buffers between frames; whatever the frame
// before left in them (more draws, more triangles, clipped polygons, another
// size) must not reach the next one: each frame equals a fresh Renderer's,
// counters included.
TEST(Determinism, OneRendererAcrossScenesMatchesFreshRenderers) {
  Renderer renderer(RendererConfig{});
  const auto expectFresh = [&](const std::string& name, int width, int height) {
    SCOPED_TRACE(name);
    const Scene scene = makeBuiltinScene(name);
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    Frame reused;
    const FrameStats got = renderer.render(scene, firstCameraOrDefault(scene), settings, reused);
    FrameStats fresh;
    const Frame expected = renderOnce(scene, firstCameraOrDefault(scene), settings,
                                      renderer.threadCount(), std::nullopt, &fresh);
    expectSameFrame(reused, expected);
    EXPECT_EQ(got.trianglesIn, fresh.trianglesIn);
    EXPECT_EQ(got.trianglesDrawn, fresh.trianglesDrawn);
    EXPECT_EQ(got.culledBackFace, fresh.culledBackFace);
    EXPECT_EQ(got.culledOutside, fresh.culledOutside);
    EXPECT_EQ(got.droppedDegenerate, fresh.droppedDegenerate);
    EXPECT_EQ(got.droppedInvalid, fresh.droppedInvalid);
    EXPECT_EQ(got.clipped, fresh.clipped);
  };
  expectFresh("random-triangles", kWidth, kHeight);  // 20000 triangles, 3 chunks
  expectFresh("near-plane", kWidth / 2, kHeight);    // clipped polygons, fewer of everything
  expectFresh("showcase", kWidth, kHeight * 2);      // several draws
  expectFresh("invalid-input", kWidth, kHeight);     // dropped triangles
  expectFresh("near-plane", kWidth, kHeight);
}

// A Renderer keeps the tile stage's per-worker scratch between frames too
// (TileWorkspace): frames whose settings size it alike reuse it, others
// make it afresh. Whatever a frame leaves there (kept blended fragments,
// alpha-to-coverage's per-sample states of its draw indices, lists and
// planes of another sample count) must not reach the next: each frame of a
// run that changes samples, rate, filter, AOVs and scene equals a fresh
// Renderer's.
TEST(Determinism, OneRendererAcrossSampleSettingsMatchesFreshRenderers) {
  RendererConfig config;
  config.threads = 2;
  Renderer renderer(config);
  const Scene showcase = makeBuiltinScene("showcase");         // textures, alpha mask, blending
  const Scene glass = makeBuiltinScene("intersecting-glass");  // kept fragments
  const Scene plane = makeBuiltinScene("checker-plane");       // opaque only
  struct Step {
    const Scene* scene;
    int samples;
    bool sampleRate = false, alphaToCoverage = false, wideFilter = false, aovs = false;
    std::optional<Filter> filter = std::nullopt;
  };
  const Step steps[] = {
      {&glass, 4},
      // The same draw masked with another texture filter: a state kept
      // from the frame before would draw it with the old one.
      {&showcase, 4, false, true, false, false, Filter::Nearest},
      {&showcase, 4, false, true},
      {&showcase, 4},
      {&glass, 4, true},
      {&plane, 4},
      {&showcase, 16, false, true, true},
      {&glass, 1},
      {&showcase, 4, false, true, false, true},
      {&glass, 4},
  };
  int index = 0;
  for (const Step& step : steps) {
    SCOPED_TRACE("step " + std::to_string(index++));
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.samples = step.samples;
    settings.shadingRate = step.sampleRate ? ShadingRate::Sample : ShadingRate::Pixel;
    settings.alphaToCoverage = step.alphaToCoverage;
    settings.pixelFilter = step.wideFilter ? PixelFilter::BlackmanHarris : PixelFilter::Box;
    settings.filter = step.filter;
    settings.frameCoverage = true;
    if (step.aovs) settings.aovs = AovSet(Aov::Normal) | AovSet(Aov::Ids);
    const Camera camera = firstCameraOrDefault(*step.scene);
    Frame reused;
    renderer.render(*step.scene, camera, settings, reused);
    ASSERT_TRUE(hasVisiblePixels(reused));
    expectSameFrame(reused, renderOnce(*step.scene, camera, settings, 2, std::nullopt));
  }
}

// A tile no triangle reaches takes a path of its own (tile_stage.cpp
// renderTile: one sample plane standing for all). Into an embedder's frame
// that still holds the last frame, it must write every pixel's colour,
// depth and coverage as the general path would: at the bottom-left corner
// the checker plane covered, and dense-mesh's sphere, centred, bins nothing
// there.
TEST(Determinism, EmptyTilesOverwriteTheFrameBefore) {
  const Scene plane = makeBuiltinScene("checker-plane");
  const Scene sphere = makeBuiltinScene("dense-mesh:2000");
  for (const int samples : {1, 4, 16}) {
    SCOPED_TRACE(samples);
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.samples = samples;
    settings.frameCoverage = true;
    Renderer renderer(RendererConfig{});
    Frame reused;
    renderer.render(plane, firstCameraOrDefault(plane), settings, reused);
    const std::size_t corner = std::size_t(kHeight - 1) * kWidth;  // bottom left
    ASSERT_GT(reused.coverage.at(corner), 0.0f);                   // held a surface
    renderer.render(sphere, firstCameraOrDefault(sphere), settings, reused);
    const Frame expected =
        renderOnce(sphere, firstCameraOrDefault(sphere), settings, renderer.threadCount());
    ASSERT_EQ(expected.coverage.at(corner), 0.0f);  // and now holds none
    expectSameFrame(reused, expected);
  }
}

// Every filter, on scenes with textures, blending and dense geometry, so each
// kernel specialization meets its scalar twin. One test per scene, so ctest
// spreads them over the cores.
class EveryIsa : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryIsa, MatchesScalar) {
  const std::vector<std::optional<Filter>> filters = {
      std::nullopt,      Filter::Nearest,     Filter::Bilinear, Filter::NearestMip,
      Filter::Trilinear, Filter::Anisotropic, Filter::Ewa,      Filter::SummedArea};
  int compared = 0;
  const Scene scene = makeBuiltinScene(GetParam());
  for (const std::optional<Filter>& filter : filters) {
    SCOPED_TRACE(std::string("filter ") + (filter ? filterName(*filter) : "from sampler"));
    const Frame scalar = renderWith(scene, 2, Isa::Scalar, filter);
    ASSERT_TRUE(hasVisiblePixels(scalar));
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
      if (!isaSupported(isa)) continue;
      SCOPED_TRACE(isaName(isa));
      expectSameFrame(renderWith(scene, 2, isa, filter), scalar);
      ++compared;
    }
  }
  if (compared == 0) GTEST_SKIP() << "this CPU has no SIMD path to compare";
}

INSTANTIATE_TEST_SUITE_P(Determinism, EveryIsa,
                         ::testing::Values("showcase", "checker-plane", "alpha-quads"),
                         sceneTestName);
// The frame of `settings` at 1 thread (with something drawn), reproduced bit
// for bit at 3 threads and on every kernel path.
void expectSameAcrossThreadsAndIsas(const Scene& scene, const RenderSettings& settings) {
  const Camera camera = firstCameraOrDefault(scene);
  const Frame reference = renderOnce(scene, camera, settings, 1, std::nullopt);
  ASSERT_TRUE(hasVisiblePixels(reference));
  expectSameFrame(renderOnce(scene, camera, settings, 3, std::nullopt), reference);
  for (Isa isa : supportedIsas()) {
    SCOPED_TRACE(isaName(isa));
    expectSameFrame(renderOnce(scene, camera, settings, 2, isa), reference);
  }
}

// The surface AOVs keep the contract too (scalar code after the visibility
// pass, whose winners are the same bits on every path), at one sample and
// several, with a moved previous pose so that motion is not all zero; lod
// and anisotropy come from the per-ISA kernels, under the scenes' own
// filters and the anisotropic one, and so do the shading AOVs (unlit here:
// the base colour; lit below).
TEST(Determinism, AovsAreIdenticalAcrossThreadsAndIsas) {
  for (const std::string name : {"showcase", "alpha-quads"}) {
    SCOPED_TRACE(name);
    const Scene scene = makeBuiltinScene(name);
    PreviousPose previous;
    previous.camera = firstCameraOrDefault(scene);
    previous.camera.world[3] += glm::vec4(0.25f, 0.1f, 0.0f, 0.0f);
    for (const Instance& instance : scene.instances)
      previous.instanceWorlds.push_back(instance.world);
    for (const int samples : {1, 4}) {
      SCOPED_TRACE(std::to_string(samples) + " samples");
      RenderSettings settings;
      settings.width = kWidth / 2;
      settings.height = kHeight / 2;
      settings.samples = samples;
      settings.aovs = AovSet(Aov::Normal) | AovSet(Aov::Position) | AovSet(Aov::Uv) |
                      AovSet(Aov::Motion) | AovSet(Aov::Ids) | kFootprintAovs | kShadingAovs;
      settings.previousPose = &previous;
      expectSameAcrossThreadsAndIsas(scene, settings);
      if (samples > 1) continue;
      SCOPED_TRACE("aniso");
      settings.filter = Filter::Anisotropic;
      expectSameAcrossThreadsAndIsas(scene, settings);
    }
  }
}

// The lit shading's AOVs (material terms and each lobe's light) keep the
// contract: the per-ISA material and light code, each lane's sample count
// its own, at one sample and several.
TEST(Determinism, ShadingAovsAreIdenticalAcrossThreadsAndIsas) {
  Scene scene = metalRoughSpheresScene(3, 3, glm::vec3(0.8f, 0.5f, 0.3f));
  Light light;
  light.intensity = 30.0f;
  light.world[3] = glm::vec4(-3.0f, 4.0f, 5.0f, 1.0f);
  scene.lights.push_back(light);
  for (const int samples : {1, 4}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    RenderSettings settings;
    settings.width = kWidth / 4;
    settings.height = kHeight / 4;
    settings.samples = samples;
    settings.shading = Shading::Pbr;
    settings.environment = std::make_shared<EnvironmentImage>(sunnySkyEnvironment(64, 32));
    settings.aovs = kShadingAovs;
    expectSameAcrossThreadsAndIsas(scene, settings);
  }
}

// Samples per pixel keep the contract: at every count and shading rate the
// frame is the same bits for any thread count and kernel path (samples are
// planes the kernels render one by one, and the resolve sums them in order).
// One test per scene and sample count, so ctest spreads them over the cores;
// half the other tests' size still leaves partial tiles on both edges and
// more tiles than threads, which is all the contract depends on (96 s under
// ASan at full size in one test, the whole cross product kept).
struct SampleCase {
  std::string scene;
  int samples;
};

// What GoogleTest prints for a failing instance (its bytes otherwise).
void PrintTo(const SampleCase& sampleCase, std::ostream* out) {
  *out << sampleCase.scene << ", " << sampleCase.samples << " samples";
}

class EverySampleCount : public ::testing::TestWithParam<SampleCase> {};

TEST_P(EverySampleCount, IsIdenticalAcrossThreadsAndIsas) {
  const Scene scene = makeBuiltinScene(GetParam().scene);
  for (const ShadingRate rate : {ShadingRate::Pixel, ShadingRate::Sample}) {
    SCOPED_TRACE(rate == ShadingRate::Sample ? "per sample" : "per pixel");
    RenderSettings settings;
    settings.width = kWidth / 2;
    settings.height = kHeight / 2;
    settings.samples = GetParam().samples;
    settings.shadingRate = rate;
    expectSameAcrossThreadsAndIsas(scene, settings);
  }
}

std::vector<SampleCase> everySceneAndSampleCount() {
  std::vector<SampleCase> cases;
  for (const std::string scene : {"showcase", "alpha-quads"})
    for (const int samples : {2, 4, 8, 16}) cases.push_back({scene, samples});
  return cases;
}

std::string sampleCaseName(const ::testing::TestParamInfo<SampleCase>& info) {
  return asTestName(info.param.scene + "_" + std::to_string(info.param.samples) + "_samples");
}

INSTANTIATE_TEST_SUITE_P(Determinism, EverySampleCount,
                         ::testing::ValuesIn(everySceneAndSampleCount()), sampleCaseName);

// Tiny triangles take the kernel path whose registers hold one quad's
// samples where an ISA has one (TileKernelSelection::quadSampleRegisters:
// one to four registers, SSE2 at 2 and 4 samples, AVX2 at 2-8, AVX-512 at
// 4-16), and each sample's lane groups in turn elsewhere (always on the
// scalar path): the same bits, with partial quads at the frame's odd right
// and bottom edges, boxes of 2x2 pixels or less off the quad grid (one quad
// at the box's corner, its covered samples written one by one), triangles
// across tile borders, and the hierarchical depth of both depth directions.
TEST(Determinism, TinyTrianglesAtSamplesAreIdenticalAcrossIsas) {
  for (const std::string name : {"slivers", "subpixel-plane"}) {
    const Scene scene = makeBuiltinScene(name);
    for (const int samples : {2, 4, 8})
      for (const DepthMode depth : {DepthMode::Standard, DepthMode::Reversed}) {
        SCOPED_TRACE(name + ", " + std::to_string(samples) + " samples" +
                     (depth == DepthMode::Reversed ? ", reversed depth" : ""));
        RenderSettings settings;
        settings.width = 203;
        settings.height = 117;
        settings.samples = samples;
        settings.depth = depth;
        expectSameAcrossThreadsAndIsas(scene, settings);
      }
  }
}

// The wide pixel filter finishes the pixels near tile borders in a second
// pass from the neighbours' sums, added in a fixed order: the same bits for
// any thread count and kernel path, coverage included. 200x120 leaves
// partial tiles at the right and bottom.
TEST(Determinism, WidePixelFilterIsIdenticalAcrossThreadsAndIsas) {
  const Scene scene = makeBuiltinScene("showcase");
  for (const auto& [samples, rate] : {std::pair{1, ShadingRate::Pixel},
                                      {4, ShadingRate::Pixel},
                                      {16, ShadingRate::Pixel},
                                      {4, ShadingRate::Sample}}) {
    SCOPED_TRACE("samples " + std::to_string(samples) +
                 (rate == ShadingRate::Sample ? " per sample" : " per pixel"));
    RenderSettings settings;
    settings.width = 200;
    settings.height = 120;
    settings.samples = samples;
    settings.shadingRate = rate;
    settings.pixelFilter = PixelFilter::BlackmanHarris;
    settings.frameCoverage = true;
    expectSameAcrossThreadsAndIsas(scene, settings);
  }
}

// Depth is resolved only when asked; the colour does not depend on it, and
// an EXR (whose Z channel needs it) refuses a depthless frame by name.
TEST(Determinism, FrameWithoutDepthHasTheSameColour) {
  const Scene scene = makeBuiltinScene("showcase");
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  const Frame withDepth = renderOnce(scene, firstCameraOrDefault(scene), settings);
  settings.frameDepth = false;
  const Frame colourOnly = renderOnce(scene, firstCameraOrDefault(scene), settings);
  EXPECT_TRUE(colourOnly.depth.empty());
  ASSERT_EQ(withDepth.depth.size(), std::size_t(kWidth) * kHeight);
  EXPECT_TRUE(sameBits(colourOnly.rgba, withDepth.rgba));
  const ScratchDir dir("quadra_no_depth");
  const std::string exr = (dir.path() / "no_depth.exr").string();
  try {
    writeFrame(colourOnly, exr);
    ADD_FAILURE() << "a frame without depth was written as EXR";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no depth"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(exr));
  writeFrame(colourOnly, (dir.path() / "no_depth.png").string());  // PNG needs none
}

// Opaque and masked draws shade in two passes (visibility, then the visible
// pixels packed into lanes) or forward; both run one colour function on the
// same planes, so every pixel must come out the same bits, on every path,
// however the pixels were packed.
class TwoPassShading : public ::testing::TestWithParam<std::string> {};

// Real models: many draws per tile, masked and blended materials.
const std::vector<std::string> kTwoPassModels = {"MetalRoughSpheresNoTextures", "GlassVaseFlowers",
                                                 "AlphaBlendModeTest"};

TEST_P(TwoPassShading, WritesWhatForwardShadingWrites) {
  const std::string& name = GetParam();
  Scene scene;
  if (std::find(kTwoPassModels.begin(), kTwoPassModels.end(), name) == kTwoPassModels.end()) {
    scene = makeBuiltinScene(name);
  } else {
    const std::filesystem::path path =
        std::filesystem::path(QUADRA_ASSETS_DIR) / name / "glTF" / (name + ".gltf");
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "sample model absent: " << path;
    scene = loadGltf(path.string());
  }
  for (const Shading shading : {Shading::Unlit, Shading::Lit}) {
    for (const Isa isa : supportedIsas()) {
      SCOPED_TRACE(std::string(shading == Shading::Lit ? "lit " : "unlit ") + isaName(isa));
      RenderSettings settings;
      settings.width = kWidth;
      settings.height = kHeight;
      settings.shading = shading;
      settings.filter = Filter::Anisotropic;
      FrameStats twoPassStats;
      const Frame twoPass =
          renderOnce(scene, firstCameraOrDefault(scene), settings, 2, isa, &twoPassStats);
      ASSERT_TRUE(hasVisiblePixels(twoPass));
      EXPECT_GT(twoPassStats.stages.shade, 0.0);  // the shading pass ran
      settings.opaqueShading = OpaqueShading::Forward;
      expectSameFrame(renderOnce(scene, firstCameraOrDefault(scene), settings, 2, isa), twoPass);
    }
  }
}

std::vector<std::string> twoPassScenes() {
  std::vector<std::string> names = {"showcase",         "checker-plane", "alpha-quads",
                                    "random-triangles", "near-plane",    "subpixel-plane"};
  names.insert(names.end(), kTwoPassModels.begin(), kTwoPassModels.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(Determinism, TwoPassShading, ::testing::ValuesIn(twoPassScenes()),
                         sceneTestName);

}  // namespace
}  // namespace quadra
