// Whole-frame cost at 1920x1080, trilinear: built-in scenes and shared sample
// models at 1 and 2 threads, in ms/frame with triangles/s, pixels/s and the
// stages of api/renderer.h StageTimes (ms per frame), next to a do-nothing
// baseline that shows the harness's own overhead.
#include <benchmark/benchmark.h>

#include <array>
#include <exception>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "api/renderer.h"
#include "lab/scene/builtin_scenes.h"
#include "scene/animation.h"
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

// Each stage of `total` paired with the same stage of `part`, in StageTimes' order.
std::array<std::pair<double*, double>, 7> stageFields(StageTimes& total, const StageTimes& part) {
  return {{{&total.draws, part.draws},
           {&total.vertex, part.vertex},
           {&total.setup, part.setup},
           {&total.bin, part.bin},
           {&total.raster, part.raster},
           {&total.shade, part.shade},
           {&total.resolve, part.resolve}}};
}

// A renderer on `threads` threads and the trilinear settings every frame
// benchmark draws with, after one warm-up frame (which also builds the mip
// chains), so loading and first use stay outside the timing.
struct WarmRenderer {
  Renderer renderer;
  RenderSettings settings;
  Frame frame;
  WarmRenderer(const Scene& scene, const Camera& camera, int threads, int width, int height)
      : renderer(RendererConfig{.threads = threads, .isa = std::nullopt}) {
    settings.width = width;
    settings.height = height;
    settings.filter = Filter::Trilinear;
    renderer.render(scene, camera, settings, frame);
  }
};

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
  WarmRenderer warm(scene, camera, int(state.range(0)), kWidth, kHeight);
  StageTimes sum;
  for (auto _ : state) {
    const StageTimes t = warm.renderer.render(scene, camera, warm.settings, warm.frame).stages;
    benchmark::DoNotOptimize(warm.frame.rgba.data());
    benchmark::ClobberMemory();
    for (auto [total, part] : stageFields(sum, t)) *total += part;
  }
  const double frames = double(state.iterations());
  // The same stages `quadra render --stats` prints, as the mean ms per frame.
  const char* const names[] = {"draws_ms",  "vertex_ms", "setup_ms",  "bin_ms",
                               "raster_ms", "shade_ms",  "resolve_ms"};
  int i = 0;
  for (auto [total, part] : stageFields(sum, sum))
    state.counters[names[i++]] = benchmark::Counter(*total / frames);
  state.counters["triangles/s"] =
      benchmark::Counter(frames * double(scene.triangleCount()), benchmark::Counter::kIsRate);
  state.counters["pixels/s"] =
      benchmark::Counter(frames * kWidth * kHeight, benchmark::Counter::kIsRate);
  state.SetLabel(source + " isa=" + isaName(warm.renderer.isa()));
}

// How a frame scales: builtin:dense-mesh:N against its triangle count at
// 1080p, and builtin:dense-mesh against the pixel count, 2 threads. Google
// Benchmark fits the complexity (BigO) over the runs of each.
void scalingRun(benchmark::State& state, const std::string& source, int width, int height,
                std::int64_t complexityN) {
  const Scene scene = loadBenchScene(source);
  const Camera camera = firstCameraOrDefault(scene);
  WarmRenderer warm(scene, camera, 2, width, height);
  for (auto _ : state) {
    warm.renderer.render(scene, camera, warm.settings, warm.frame);
    benchmark::DoNotOptimize(warm.frame.rgba.data());
  }
  state.SetComplexityN(complexityN);
  state.counters["triangles"] = double(scene.triangleCount());
  state.counters["pixels"] = double(width) * height;
  state.SetLabel(source + " " + std::to_string(width) + "x" + std::to_string(height));
}

void scalingTriangles(benchmark::State& state) {
  scalingRun(state, "builtin:dense-mesh:" + std::to_string(state.range(0)), kWidth, kHeight,
             state.range(0));
}

void scalingPixels(benchmark::State& state) {
  const int height = int(state.range(0)), width = height * 16 / 9;
  scalingRun(state, "builtin:dense-mesh", width, height, std::int64_t(width) * height);
}

// A sequence's frames: builtin:flyover posed at each next frame time (24 fps,
// round its 4 s) and rendered, 2 threads, so posing and the moving camera
// are in the time; beside frameTime on a still, it shows what a frame of a
// sequence costs more (quadra render --sequence prints the same as
// steady_fps, with the files written on their own thread).
void sequenceFrames(benchmark::State& state) {
  Scene scene = loadBenchScene("builtin:flyover");
  WarmRenderer warm(scene, firstCameraOrDefault(scene), 2, kWidth, kHeight);
  NodePose pose;
  int frame = 0;
  for (auto _ : state) {
    poseNodes(scene, 0, double(frame++ % 96) / 24.0, pose);
    placeOnNodes(scene, pose);
    warm.renderer.render(scene, scene.cameras.front(), warm.settings, warm.frame);
    benchmark::DoNotOptimize(warm.frame.rgba.data());
  }
  state.counters["frames/s"] =
      benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
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
BENCHMARK(scalingTriangles)
    ->ArgName("triangles")
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Arg(10000000)
    ->Complexity()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(scalingPixels)
    ->ArgName("height")
    ->Arg(720)
    ->Arg(1080)
    ->Arg(2160)
    ->Arg(4320)
    ->Complexity()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(sequenceFrames)->UseRealTime()->Unit(benchmark::kMillisecond);
QUADRA_FRAME_BENCHMARK(flyover_still, "builtin:flyover");
QUADRA_FRAME_BENCHMARK(checker_plane, "builtin:checker-plane");
QUADRA_FRAME_BENCHMARK(alpha_quads, "builtin:alpha-quads");
QUADRA_FRAME_BENCHMARK(dense_mesh, "builtin:dense-mesh");
QUADRA_FRAME_BENCHMARK(water_bottle, "WaterBottle");
QUADRA_FRAME_BENCHMARK(glass_vase_flowers, "GlassVaseFlowers");
QUADRA_FRAME_BENCHMARK(metal_rough_spheres, "MetalRoughSpheresNoTextures");

}  // namespace
}  // namespace quadra

BENCHMARK_MAIN();
