// Texture lookups per filter x storage format x ISA, on textures sized for
// L1, L2 and DRAM, at 1 and 2 threads: ns per lookup and lookups/s over the
// report's seeded random footprint stream (magnification to 512:1
// minification, anisotropy 1..64, cache-unfriendly order). A do-nothing
// baseline runs the same batch loop writing each lookup's (u, v) instead of
// sampling, so its cost is what the harness and the output stream take.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "lab/texture/footprints.h"
#include "lab/texture/test_textures.h"
#include "texture/texture_sampler.h"

namespace quadra {
namespace {

constexpr std::size_t kLookups = 4096;
constexpr std::size_t kChunk = 512;  // lookups per task: the 2-thread split

// Square texture sides: RGBA32F with mips fits L1 (48 KiB), L2 (1 MiB) and
// only DRAM (64 MiB) on the project's machine; the narrow formats halve and
// quarter that.
constexpr int kSideL1 = 32, kSideL2 = 128, kSideDram = 2048;

const char* sizeName(int side) {
  return side == kSideL1 ? "L1" : side == kSideL2 ? "L2" : "DRAM";
}

// Textures and footprint sets are built once per size and shared.
struct Workload {
  std::shared_ptr<const Image> image;
  FootprintSet footprints;
};

const Workload& workload(int side) {
  static std::map<int, Workload> cache;
  auto it = cache.find(side);
  if (it == cache.end()) {
    Workload w{std::make_shared<const Image>(makeValueNoiseTexture(side, side, 7)),
               makeFootprintSet(
                   {.count = kLookups, .seed = 1, .textureWidth = side, .textureHeight = side})};
    it = cache.emplace(side, std::move(w)).first;
  }
  return it->second;
}

void runBatches(benchmark::State& state, const Executor& executor,
                const std::function<void(std::size_t, std::size_t)>& batch) {
  for (auto _ : state) {
    executor.parallelFor(kLookups / kChunk, 1, [&](std::size_t first, std::size_t last) {
      batch(first * kChunk, last * kChunk);
    });
    benchmark::ClobberMemory();
  }
  // Seconds per lookup: printed with an SI prefix, e.g. "9.6n" is 9.6 ns.
  state.counters["time/lookup"] =
      benchmark::Counter(double(kLookups), benchmark::Counter::kIsIterationInvariantRate |
                                               benchmark::Counter::kInvert);
  state.counters["lookups/s"] =
      benchmark::Counter(double(kLookups), benchmark::Counter::kIsIterationInvariantRate);
}

// args: filter, format, isa, texture side, threads[, gather].
void lookups(benchmark::State& state) {
  const Filter filter = Filter(state.range(0));
  const TexelFormat format = TexelFormat(state.range(1));
  const Isa isa = Isa(state.range(2));
  const int side = int(state.range(3));
  const bool gather = state.range(5) != 0;
  if (!isaSupported(isa)) {
    state.SkipWithError("ISA not supported by this CPU");
    return;
  }
  const Workload& w = workload(side);
  const Texture texture(w.image, SamplerState{}, format);
  FilterSettings settings(filter, 16);
  settings.gatherTexels = gather;
  const TextureSampler sampler(texture, settings, isa);
  const LookupBatch batch = w.footprints.batch();
  std::vector<float> rgba(kLookups * 4);
  const Executor executor(int(state.range(4)));
  runBatches(state, executor, [&](std::size_t begin, std::size_t end) {
    sampler.sample(batch, begin, end, rgba.data());
  });
  state.SetLabel(std::string(filterName(filter)) + " " + formatName(format) + " " + isaName(isa) +
                 " " + sizeName(side));
}

void baseline(benchmark::State& state) {
  const FootprintSet& footprints = workload(kSideL1).footprints;
  std::vector<float> rgba(kLookups * 4);
  const Executor executor(int(state.range(0)));
  runBatches(state, executor, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      rgba[4 * i] = footprints.u[i];
      rgba[4 * i + 1] = footprints.v[i];
    }
    benchmark::DoNotOptimize(rgba.data());
  });
}

void lookupArguments(benchmark::internal::Benchmark* b) {
  b->ArgNames({"filter", "format", "isa", "side", "threads", "gather"});
  for (const Filter filter : {Filter::Nearest, Filter::Bilinear, Filter::NearestMip,
                              Filter::Trilinear, Filter::Anisotropic, Filter::Ripmap})
    for (const TexelFormat format : {TexelFormat::Rgba32F, TexelFormat::Rgba16F,
                                     TexelFormat::Rgba8Unorm, TexelFormat::Rgba8Srgb})
      for (const Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512})
        for (const int side : {kSideL1, kSideL2, kSideDram})
          for (const int threads : {1, 2})
            b->Args({int(filter), int(format), int(isa), side, threads, 0});
  // The offline filters (lookup by lookup: one format tells their cost; every
  // ISA, as their lane code is compiled per ISA).
  for (const Filter filter : {Filter::Ewa, Filter::Area, Filter::SummedArea})
    for (const Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512})
      for (const int side : {kSideL1, kSideL2, kSideDram})
        b->Args({int(filter), int(TexelFormat::Rgba32F), int(isa), side, 1, 0});
  // The gather alternative of the float fetch, where the ISA has gathers
  // (compare with the gather:0 runs of the same filter, ISA and size above).
  for (const Filter filter : {Filter::Bilinear, Filter::Trilinear, Filter::Anisotropic})
    for (const Isa isa : {Isa::Avx2, Isa::Avx512})
      for (const int side : {kSideL1, kSideL2, kSideDram})
        b->Args({int(filter), int(TexelFormat::Rgba32F), int(isa), side, 1, 1});
}

BENCHMARK(baseline)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK(lookups)->Apply(lookupArguments)->UseRealTime();

}  // namespace
}  // namespace quadra

BENCHMARK_MAIN();
