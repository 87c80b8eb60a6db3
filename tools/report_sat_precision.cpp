// `quadra report sat-precision`: the summed-area table's precision problem,
// measured. On an N x N noise texture (default 8192, where a float table's
// entries reach ~3e7 and a float step is 2 to 4) it sums random boxes of
// texels three ways - a float table, a float table of the values minus their
// mean (the usual mitigation), and quadra's fixed-point integer table
// (texture/summed_area.h) - and prints the error of each box's average
// against a direct double-precision sum of its texels, per box size.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "core/error.h"
#include "core/parallel.h"
#include "lab/texture/test_textures.h"
#include "texture/padded_level.h"
#include "texture/summed_area.h"

namespace quadra {
namespace {

constexpr const char* kSatPrecisionUsage =
    R"(usage: quadra report sat-precision [--size N] [--boxes N] [--seed S] [--threads N]
  --size N     the noise texture is N x N (default 8192; memory about 80 bytes per texel)
  --boxes N    random boxes per size bucket (default 2000)
  --seed S     texture and box seed (default 1)
  --threads N  threads for building the tables (default: all cores)
Error: max and RMS abs error of a box's average (channel R) against a direct
double sum of its texels; boxes lie anywhere in the texture.
)";

// A float table of channel 0 minus `offset`, summed in float row by row and
// then down the columns, as a float prefix-sum pass would.
std::vector<float> floatTable(const Image& image, double offset) {
  const std::size_t w = std::size_t(image.width), h = std::size_t(image.height);
  std::vector<float> table((w + 1) * (h + 1), 0.0f);
  for (std::size_t y = 0; y < h; ++y) {
    float* row = &table[(y + 1) * (w + 1)];
    for (std::size_t x = 0; x < w; ++x)
      row[x + 1] = row[x] + float(double(image.texel(int(x), int(y))[0]) - offset);
  }
  for (std::size_t y = 1; y <= h; ++y)
    for (std::size_t x = 0; x <= w; ++x) table[y * (w + 1) + x] += table[(y - 1) * (w + 1) + x];
  return table;
}

struct ErrorStats {
  double max = 0.0, sumSq = 0.0;
  std::size_t count = 0;
  void add(double error) {
    max = std::max(max, std::abs(error));
    sumSq += error * error;
    ++count;
  }
  double rms() const { return count ? std::sqrt(sumSq / double(count)) : 0.0; }
};

// One texture: the three tables, random boxes per size bucket, one table row each.
void measureTables(const char* name, const Image& image, int boxes, std::uint64_t seed,
                   const Executor& executor) {
  const int size = image.width;
  double mean = 0.0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) mean += image.rgba[i];
  mean /= double(size) * double(size);
  const std::vector<float> naive = floatTable(image, 0.0), offset = floatTable(image, mean);
  const PaddedLevel level(image, TexelFormat::Rgba32F);
  const SummedAreaTable table(level.view(), TexelFormat::Rgba32F, &executor);
  TextureView view;  // only the wrap modes matter for box sums inside the texture
  view.wrapU = view.wrapV = WrapMode::ClampToEdge;

  const std::size_t w1 = std::size_t(size) + 1;
  auto boxOf = [&](const std::vector<float>& t, int x0, int x1, int y0, int y1) {
    auto at = [&](int x, int y) { return double(t[std::size_t(y) * w1 + std::size_t(x)]); };
    return at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
  };

  std::mt19937_64 rng(seed);
  const int buckets[][2] = {{1, 2}, {3, 16}, {17, 128}};
  for (const auto& bucket : buckets) {
    if (bucket[0] > size) continue;  // no box of these sides fits the texture
    const int hi = std::min(bucket[1], size);
    std::uniform_int_distribution<int> side(bucket[0], hi), position(0, size - hi);
    ErrorStats naiveError, offsetError, fixedError;
    for (int b = 0; b < boxes; ++b) {
      const int x0 = position(rng), y0 = position(rng);
      const int x1 = x0 + side(rng), y1 = y0 + side(rng);
      double direct = 0.0;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) direct += image.texel(x, y)[0];
      const double area = double(x1 - x0) * double(y1 - y0);
      naiveError.add((boxOf(naive, x0, x1, y0, y1) - direct) / area);
      offsetError.add((boxOf(offset, x0, x1, y0, y1) + mean * area - direct) / area);
      double sum[4];
      table.texelSum(view, x0, x1, y0, y1, sum);
      fixedError.add((sum[0] - direct) / area);
    }
    const std::string sides = std::to_string(bucket[0]) + "-" + std::to_string(hi);
    const std::string fixed =
        "int64, fixed point 2^-" + std::to_string(table.fractionBits()) + " (quadra)";
    std::printf("| %s | %s | float | 4 | %.3g | %.3g |\n", name, sides.c_str(), naiveError.max,
                naiveError.rms());
    std::printf("| %s | %s | float, mean subtracted | 4 | %.3g | %.3g |\n", name, sides.c_str(),
                offsetError.max, offsetError.rms());
    std::printf("| %s | %s | %s | 8 | %.3g | %.3g |\n", name, sides.c_str(), fixed.c_str(),
                fixedError.max, fixedError.rms());
  }
}

}  // namespace

int runSatPrecisionReport(const std::vector<std::string>& args) {
  int size = 8192, boxes = 2000, threads = 0;
  std::uint64_t seed = 1;
  CommandOptions options("report sat-precision", kSatPrecisionUsage);
  options.integer("--size", size, 16, 16384);
  options.integer("--boxes", boxes, 1, 1 << 20);
  addSeedOption(options, seed);
  addThreadsOption(options, threads);
  if (options.parse(args) == Parsed::HelpShown) return 0;

  const Executor executor(threads);
  std::printf("sat-precision: %dx%d textures (seed %llu), %d boxes per bucket\n\n", size, size,
              (unsigned long long)seed, boxes);
  std::printf(
      "| texture | box side (texels) | table | bytes per channel | max error | RMS error |\n");
  std::printf("|---|---|---|---|---|---|\n");
  // Noise has no large-scale trend, so mean subtraction keeps its float sums
  // small; the smooth texture's slow variation defeats it.
  for (const char* name : {"noise", "smooth"}) {
    const Image image = std::string(name) == "noise" ? makeValueNoiseTexture(size, size, seed)
                                                     : makeSmoothNoiseTexture(size, size, seed);
    measureTables(name, image, boxes, seed, executor);
  }
  return 0;
}

}  // namespace quadra
