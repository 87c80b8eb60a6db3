// `quadra sample`: batch texture lookups from a CSV for scoring the sampler
// from outside (DESIGN.md "Contracts"). Reads everything first, times only the
// lookups, writes the values once (temporary file + rename).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "core/error.h"
#include "core/parallel.h"
#include "io/image_io.h"
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
      throw Error(option + ": unknown wrap mode '" + value + "' (repeat, mirror, clamp, border)");
  });
  addTexelFormatOption(options, "--format", cmd.format);
  addThreadsOption(options, cmd.threads);
  addIsaOption(options, cmd.isa);
  if (options.parse(args) == Parsed::HelpShown) return std::nullopt;
  if (cmd.texturePath.empty()) throw Error("sample: --texture is required");
  if (!cmd.filtering.filter) throw Error("sample: --filter is required");
  if (cmd.filtering.minLod < 0.0f || cmd.filtering.minLod > cmd.filtering.maxLod)
    throw Error("--min-lod/--max-lod: need 0 <= min <= max");
  if (cmd.inPath.empty()) throw Error("sample: --in is required");
  if (cmd.outPath.empty()) throw Error("sample: --out is required");
  if (!endsWithIgnoringCase(cmd.outPath, ".csv"))
    throw Error(cmd.outPath + ": output must be a .csv file");
  return cmd;
}

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// Structure-of-arrays lookups read from the CSV.
struct Lookups {
  std::vector<float> column[6];
  LookupBatch batch() const {
    return {column[0].data(), column[1].data(), column[2].data(), column[3].data(),
            column[4].data(), column[5].data(), column[0].size()};
  }
};

Lookups readLookups(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw Error(path + ": cannot open for reading");
  std::string line;
  if (!std::getline(file, line))
    throw Error(path + ": empty file (expected header u,v,dudx,dvdx,dudy,dvdy)");
  std::string header = trim(line);
  if (!header.empty() && static_cast<unsigned char>(header[0]) == 0xEF && header.size() >= 3)
    header = header.substr(3);  // UTF-8 byte order mark
  header.erase(std::remove(header.begin(), header.end(), ' '), header.end());
  if (header != "u,v,dudx,dvdx,dudy,dvdy")
    throw Error(path + ": line 1: header must be u,v,dudx,dvdx,dudy,dvdy");
  Lookups lookups;
  for (std::size_t lineNumber = 2; std::getline(file, line); ++lineNumber) {
    const std::string row = trim(line);
    if (row.empty()) continue;
    std::stringstream fields(row);
    std::string field;
    int n = 0;
    while (std::getline(fields, field, ',')) {
      if (n == 6)
        throw Error(path + ": line " + std::to_string(lineNumber) + ": more than 6 fields");
      char* end = nullptr;
      const std::string text = trim(field);
      const float value = std::strtof(text.c_str(), &end);
      if (text.empty() || *end != '\0')
        throw Error(path + ": line " + std::to_string(lineNumber) + ": '" + text +
                    "' is not a number");
      lookups.column[n++].push_back(value);
    }
    if (n != 6)
      throw Error(path + ": line " + std::to_string(lineNumber) + ": expected 6 fields, found " +
                  std::to_string(n));
  }
  return lookups;
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
