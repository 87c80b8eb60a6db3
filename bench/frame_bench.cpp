// Whole-frame cost at 1920x1080, trilinear: built-in scenes and shared sample
// models at 1 and 2 threads, in ms/frame with triangles/s and pixels/s, next
// to a do-nothing baseline that shows the harness's own overhead.
#include <benchmark/benchmark.h>

#include <exception>
#include <filesystem>
#include <string>

#include "api/renderer.h"
#include "lab/scene/builtin_scenes.h"
#include "scene/gltf_loader.h"

namespace quadra {
namespace {

constexpr int kWidth = 1920;
constexpr int kHeight = 1080;
constexpr const char* kBuiltinPrefix = "builtin:";

// builtin:NAME, or a model folder name under QUADRA_ASSETS_DIR.
Scene loadBenchScene(const std::string& source) {
  if (source.rfind(kBuiltinPrefix, 0) == 0)
    return makeBuiltinScene(source.substr(std::string(kBuiltinPrefix).size()));
  const std::filesystem::path path =
      std::filesystem::path(QUADRA_ASSETS_DIR) / source / "glTF" / (source + ".gltf");
  if (!std::filesystem::exists(path)) throw std::runtime_error(path.string() + ": not found");
  return loadGltf(path.string());
}

// state.range(0) is the thread count. Loading, renderer construction and one
// warm-up frame (which also builds the mip chains) stay outside the timing.
void frameTime(benchmark::State& state, const std::string& source) {
  Scene scene;
  try {
    scene = loadBenchScene(source);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const Camera camera = firstCameraOrDefault(scene);
  RendererConfig config;
  config.threads = int(state.range(0));
  Renderer renderer(config);
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.filter = Filter::Trilinear;
  Frame frame;
  renderer.render(scene, camera, settings, frame);
  for (auto _ : state) {
    renderer.render(scene, camera, settings, frame);
    benchmark::DoNotOptimize(frame.rgba.data());
    benchmark::ClobberMemory();
  }
  const double frames = double(state.iterations());
  state.counters["triangles/s"] =
      benchmark::Counter(frames * double(scene.triangleCount()), benchmark::Counter::kIsRate);
  state.counters["pixels/s"] =
      benchmark::Counter(frames * kWidth * kHeight, benchmark::Counter::kIsRate);
  state.SetLabel(source + " isa=" + isaName(renderer.isa()));
}

// The harness alone: what an empty timed loop costs.
void baseline(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(state.iterations());
}

#define QUADRA_FRAME_BENCHMARK(id, source)              \
  BENCHMARK_CAPTURE(frameTime, id, std::string(source)) \
      ->ArgName("threads")                              \
      ->Arg(1)                                          \
      ->Arg(2)                                          \
      ->UseRealTime()                                   \
      ->Unit(benchmark::kMillisecond)

BENCHMARK(baseline)->UseRealTime()->Unit(benchmark::kMillisecond);
QUADRA_FRAME_BENCHMARK(checker_plane, "builtin:checker-plane");
QUADRA_FRAME_BENCHMARK(alpha_quads, "builtin:alpha-quads");
QUADRA_FRAME_BENCHMARK(dense_mesh, "builtin:dense-mesh");
QUADRA_FRAME_BENCHMARK(water_bottle, "WaterBottle");
QUADRA_FRAME_BENCHMARK(glass_vase_flowers, "GlassVaseFlowers");
QUADRA_FRAME_BENCHMARK(metal_rough_spheres, "MetalRoughSpheresNoTextures");

}  // namespace
}  // namespace quadra

BENCHMARK_MAIN();
