// Google Benchmark of the shading stage: preparing a 2048 x 1024 panorama
// (the target: at most 0.5 s on 2 threads), and surfaceRadiance per lane
// group on each ISA path (environment only, and with three punctual lights),
// against a do-nothing baseline that only loads and stores the records.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/parallel.h"
#include "shading/environment_image.h"
#include "shading/prepared_environment.h"
#include "shading/shade_batch.h"

namespace quadra {
namespace {

// A sky gradient with a small bright sun: smooth and sharp content.
EnvironmentImage benchPanorama(int width, int height) {
  EnvironmentImage image;
  image.name = "bench";
  image.width = width, image.height = height;
  image.rgb.resize(std::size_t(width) * height * 3);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const float v = (j + 0.5f) / height, u = (i + 0.5f) / width;
      const bool sun = std::hypot(u - 0.3f, v - 0.25f) < 0.01f;
      float* t = image.rgb.data() + (std::size_t(j) * width + i) * 3;
      t[0] = sun ? 500.0f : 0.4f + 0.3f * v;
      t[1] = sun ? 480.0f : 0.5f + 0.2f * v;
      t[2] = sun ? 450.0f : 0.9f - 0.5f * v;
    }
  return image;
}

void prepareEnvironment(benchmark::State& state) {
  const EnvironmentImage image = benchPanorama(2048, 1024);
  const Executor executor(int(state.range(0)));
  { const PreparedEnvironment warm(image, {}, executor); }  // the albedo table, once per process
  for (auto _ : state) {
    const PreparedEnvironment env(image, {30.0f, 1.0f}, executor);
    benchmark::DoNotOptimize(env.view().radiance);
  }
}

std::vector<SurfaceRecord> benchSurfaces(std::size_t count) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<SurfaceRecord> surfaces(count);
  for (SurfaceRecord& s : surfaces) {
    const float nx = u(rng), ny = u(rng), nz = u(rng);
    const float len = std::sqrt(nx * nx + ny * ny + nz * nz) + 1e-6f;
    s.normal[0] = nx / len, s.normal[1] = ny / len, s.normal[2] = nz / len;
    // A view within 80 degrees of the normal.
    const float c = 0.2f + 0.8f * std::fabs(u(rng));
    s.view[0] = s.normal[0] * c + (1 - c) * 0.5f, s.view[1] = s.normal[1] * c + (1 - c) * 0.5f,
    s.view[2] = s.normal[2] * c;
    const float vl =
        std::sqrt(s.view[0] * s.view[0] + s.view[1] * s.view[1] + s.view[2] * s.view[2]);
    for (float& x : s.view) x /= vl;
    s.metallic = std::fabs(u(rng)), s.roughness = std::fabs(u(rng));
    s.baseColor[0] = 0.8f, s.baseColor[1] = 0.5f, s.baseColor[2] = 0.3f;
  }
  return surfaces;
}

void surfaceRadiance(benchmark::State& state) {
  static const PreparedEnvironment env(benchPanorama(2048, 1024), {}, Executor(2));
  const Isa isa = Isa(state.range(0));
  if (!isaSupported(isa)) {
    state.SkipWithError("ISA not supported here");
    return;
  }
  std::vector<PunctualLight> lights;
  if (state.range(1)) {
    lights.resize(3);
    lights[0].type = PunctualLight::Type::Directional;
    lights[1].position[1] = 2.0f;
    lights[2].type = PunctualLight::Type::Spot;
    lights[2].position[1] = 3.0f, lights[2].angleScale = 4.0f, lights[2].angleOffset = -2.5f;
  }
  const LightingView view = lightingViewOf(&env, lights);
  const std::vector<SurfaceRecord> surfaces = benchSurfaces(4096);
  std::vector<float> rgb(surfaces.size() * 3);
  const ShadeBatchKernel kernel = shadeBatchKernel(isa);
  for (auto _ : state) {
    kernel(view, surfaces.data(), surfaces.size(), rgb.data());
    benchmark::DoNotOptimize(rgb.data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(surfaces.size()));
}

// The same records through the kernel with no environment and no light:
// the loads, stores and emission alone.
void baseline(benchmark::State& state) {
  const LightingView view = lightingViewOf(nullptr, {});
  const std::vector<SurfaceRecord> surfaces = benchSurfaces(4096);
  std::vector<float> rgb(surfaces.size() * 3);
  const ShadeBatchKernel kernel = shadeBatchKernel(Isa(state.range(0)));
  for (auto _ : state) {
    kernel(view, surfaces.data(), surfaces.size(), rgb.data());
    benchmark::DoNotOptimize(rgb.data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(surfaces.size()));
}

void isaArguments(benchmark::internal::Benchmark* b) {
  b->ArgNames({"isa", "lights"});
  for (const Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512})
    for (int lights : {0, 1}) b->Args({int(isa), lights});
}

}  // namespace

BENCHMARK(prepareEnvironment)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(baseline)->ArgName("isa")->Arg(int(Isa::Avx2));
BENCHMARK(surfaceRadiance)->Apply(isaArguments);

}  // namespace quadra

BENCHMARK_MAIN();
