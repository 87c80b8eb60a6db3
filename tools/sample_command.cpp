// `quadra sample`: batch texture lookups from a CSV for scoring the sampler
// from outside (DESIGN.md "Contracts"). Reads everything first, times only the
// lookups, writes the values once (temporary file + rename).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "core/error.h"
#include "core/parallel.h"
#include "io/image_io.h"
#include "lookups_csv.h"
#include "texture/texture_sampler.h"

namespace quadra {
namespace {

constexpr const char* kSampleUsage =
    R"(usage: quadra sample --texture FILE.png|FILE.jpg|FILE.exr --filter F --in LOOKUPS.csv --out VALUES.csv
                     [--aniso N] [--wrap repeat|mirror|clamp|border] [--threads N] [--isa ISA]
                     [--lod-bias B] [--min-lod L] [--max-lod L] [--format F]
  --filter nearest|bilinear|nearest-mip|trilinear|aniso|ewa|area|sat|ripmap
  --format rgba32f|rgba16f|rgba8|rgba8srgb
                                   texel storage the sampler reads (default rgba32f)
  LOOKUPS.csv: header u,v,dudx,dvdx,dudy,dvdy (normalized units, per-pixel derivatives)
  VALUES.csv:  header r,g,b,a, one row per lookup, linear float
A PNG is decoded from sRGB to linear; an EXR is read as linear. Prints
"quadra sample_ns per_lookup=... lookups=... threads=... isa=..." (lookup time only).
)";

struct SampleCommand {
  std::string texturePath, inPath, outPath;
  FilterSettings filtering;
  WrapMode wrap = WrapMode::Repeat;
  TexelFormat format = TexelFormat::Rgba32F;
  int threads = 0;
  std::optional<Isa> isa;
};

// nullopt: --help printed the usage.
std::optional<SampleCommand> parseSample(const std::vector<std::string>& args) {
  SampleCommand cmd;
  CommandOptions options("sample", kSampleUsage);
  options.text("--texture", cmd.texturePath);
  options.text("--in", cmd.inPath);
  options.text("--out", cmd.outPath);
  addFilterOptions(options, cmd.filtering.filter, cmd.filtering.maxAniso, cmd.filtering.lodBias);
  addLodRangeOptions(options, cmd.filtering.minLod, cmd.filtering.maxLod);
  options.value("--wrap", [&](const std::string& option, const std::string& value) {
    if (!parseWrap(value, cmd.wrap))
      throw UsageError(option + ": unknown wrap mode '" + value +
                       "' (repeat, mirror, clamp, border)" +
                       didYouMean(value, "repeat, mirror, clamp, border"));
  });
  addTexelFormatOption(options, "--format", cmd.format);
  addThreadsOption(options, cmd.threads);
  addIsaOption(options, cmd.isa);
  if (options.parse(args) == Parsed::HelpShown) return std::nullopt;
  if (cmd.texturePath.empty()) throw UsageError("sample: --texture is required");
  if (!cmd.filtering.filter) throw UsageError("sample: --filter is required");
  if (cmd.filtering.minLod < 0.0f || cmd.filtering.minLod > cmd.filtering.maxLod)
    throw UsageError("--min-lod/--max-lod: need 0 <= min <= max");
  if (cmd.inPath.empty()) throw UsageError("sample: --in is required");
  if (cmd.outPath.empty()) throw UsageError("sample: --out is required");
  if (!endsWithIgnoringCase(cmd.outPath, ".csv"))
    throw UsageError(cmd.outPath + ": output must be a .csv file");
  return cmd;
}

void writeValues(const std::string& path, const std::vector<float>& rgba) {
  const std::string temporary = path + ".tmp-quadra";
  {
    std::FILE* file = std::fopen(temporary.c_str(), "w");
    if (!file) throw Error(path + ": cannot open for writing");
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> guard(file, &std::fclose);
    bool ok = std::fputs("r,g,b,a\n", file) >= 0;
    for (std::size_t i = 0; ok && i < rgba.size(); i += 4)
      ok = std::fprintf(file, "%.9g,%.9g,%.9g,%.9g\n", rgba[i], rgba[i + 1], rgba[i + 2],
                        rgba[i + 3]) > 0;
    ok = ok && std::fflush(file) == 0;
    if (!ok) {
      guard.reset();
      std::remove(temporary.c_str());
      throw Error(path + ": write failed");
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw Error(path + ": cannot rename the finished file into place");
  }
}

}  // namespace

int runSample(const std::vector<std::string>& args) {
  const std::optional<SampleCommand> parsed = parseSample(args);
  if (!parsed) return 0;
  const SampleCommand& cmd = *parsed;
  const Isa isa = supportedIsa(cmd.isa);
  SamplerState state;
  state.wrapU = state.wrapV = cmd.wrap;
  auto image = std::make_shared<Image>(readImage(cmd.texturePath));
  const Texture texture(image, state, cmd.format);
  const TextureSampler sampler(texture, cmd.filtering, isa);
  const Lookups lookups = readLookups(cmd.inPath);
  const LookupBatch batch = lookups.batch();
  std::vector<float> rgba(batch.count * 4);
  const Executor executor(cmd.threads);

  // Repeat the whole batch until 0.2 s have passed; only lookups are timed.
  const auto start = std::chrono::steady_clock::now();
  std::size_t done = 0;
  double seconds = 0.0;
  do {
    executor.parallelFor(batch.count, 4096, [&](std::size_t begin, std::size_t end) {
      sampler.sample(batch, begin, end, rgba.data());
    });
    done += batch.count;
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } while (seconds < 0.2 && batch.count > 0);

  writeValues(cmd.outPath, rgba);
  std::printf("quadra sample_ns per_lookup=%.3f lookups=%zu threads=%d isa=%s\n",
              done ? seconds * 1e9 / double(done) : 0.0, batch.count, executor.threadCount(),
              isaName(isa));
  return 0;
}

}  // namespace quadra
