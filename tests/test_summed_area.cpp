// The summed-area-table filter against independent double references: the
// converged ground truth of axis-aligned footprints (where the filter's box is
// the footprint itself) under every wrap mode, direct texel sums for the
// table's integer sums, and the precision case a float table fails.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "lab/texture/ground_truth.h"
#include "lab/texture/test_textures.h"
#include "render_helpers.h"
#include "sampler_helpers.h"
#include "texture/summed_area.h"

namespace quadra {
namespace {

// Blue in the border too, so each channel's border term is checked.
constexpr std::array<float, 4> kBorder = {0.25f, 0.0f, 0.75f, 1.0f};

// Axis-aligned footprints: sub-texel to several texture periods wide, centred
// anywhere in [-2, 3)^2 so boxes cross seams, edges and whole periods.
std::vector<Lookup> axisAlignedLookups(int count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> position(-2.0f, 3.0f), logSize(-7.0f, 1.0f);
  std::vector<Lookup> lookups;
  for (int i = 0; i < count; ++i) {
    const float u = position(rng), v = position(rng);
    const float du = std::exp2(logSize(rng)), dv = std::exp2(logSize(rng));
    // Alternate the derivative that carries each axis: the box is the bounding box either way.
    lookups.push_back(i % 2 ? Lookup{u, v, du, 0.0f, 0.0f, dv} : Lookup{u, v, 0.0f, dv, du, 0.0f});
  }
  return lookups;
}

// The integral of the bilinear reconstruction over a texel-space box, cell by
// cell: between four texel centres the reconstruction is bilinear, so each
// cell's part is its corner texels times the integrals of the linear weights.
void exactBoxAverage(const BilinearReference& reference, double x0, double x1, double y0, double y1,
                     double rgba[4]) {
  struct CellPart {
    long cell;
    double left, right;  // integrals of the weights of texels cell and cell + 1
  };
  auto parts = [](double a, double b) {
    std::vector<CellPart> out;
    for (long i = long(std::floor(a - 0.5)); double(i) + 0.5 < b; ++i) {
      const double s0 = std::max(a, double(i) + 0.5) - (double(i) + 0.5);
      const double s1 = std::min(b, double(i) + 1.5) - (double(i) + 0.5);
      const double right = 0.5 * (s1 * s1 - s0 * s0);
      out.push_back({i, (s1 - s0) - right, right});
    }
    return out;
  };
  double sum[4] = {0, 0, 0, 0};
  for (const CellPart& px : parts(x0, x1)) {
    for (const CellPart& py : parts(y0, y1)) {
      const double weights[4] = {px.left * py.left, px.right * py.left, px.left * py.right,
                                 px.right * py.right};
      for (int corner = 0; corner < 4; ++corner) {
        double texel[4];  // a lookup exactly at a texel centre reads that texel
        reference.lookupTexel(double(px.cell + corner % 2), double(py.cell + corner / 2), texel);
        for (int c = 0; c < 4; ++c) sum[c] += weights[corner] * texel[c];
      }
    }
  }
  for (int c = 0; c < 4; ++c) rgba[c] = sum[c] / ((x1 - x0) * (y1 - y0));
}

TEST(SummedArea, AxisAlignedFootprintsEqualTheExactBoxIntegralInEveryWrapMode) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(13, 9, 4));
  const std::vector<Lookup> lookups = axisAlignedLookups(200, 7);
  for (const WrapMode wrap : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge,
                              WrapMode::ClampToBorder}) {
    const Texture texture(image, samplerWith(wrap, kBorder));
    const BilinearReference reference(*image, samplerWith(wrap, kBorder));
    const std::vector<float> got = sampleAll(texture, Filter::SummedArea, Isa::Scalar, lookups);
    for (std::size_t i = 0; i < lookups.size(); ++i) {
      const Lookup& l = lookups[i];
      const double hx = 0.5 * (double(l[2]) + double(l[4])) * 13.0;
      const double hy = 0.5 * (double(l[3]) + double(l[5])) * 9.0;
      const double cx = double(l[0]) * 13.0, cy = double(l[1]) * 9.0;
      double truth[4];
      exactBoxAverage(reference, cx - hx, cx + hx, cy - hy, cy + hy, truth);
      for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(got[i * 4 + c], truth[c], 2e-6)
            << wrapName(wrap) << " lookup " << i << " channel " << c;
    }
  }
}

// The cell-by-cell integral itself against the converged ground truth (an
// independent midpoint quadrature), so the reference above is not taken on trust.
TEST(SummedArea, TheExactBoxIntegralAgreesWithTheGroundTruth) {
  const Image image = makeValueNoiseTexture(13, 9, 4);
  // Fine from the start: a coarse midpoint grid can step over the kinks at
  // texel centres and still look converged.
  GroundTruthOptions options;
  options.samplesPerTexel = 16.0;
  options.minSamplesPerAxis = 64;
  options.maxSamples = std::size_t(1) << 22;
  for (const WrapMode wrap : {WrapMode::Repeat, WrapMode::ClampToBorder}) {
    const BilinearReference reference(image, samplerWith(wrap, kBorder));
    for (const Lookup& l : axisAlignedLookups(20, 8)) {
      const GroundTruthValue truth =
          groundTruth(reference, {l[0], l[1], l[2], l[3], l[4], l[5]}, options);
      const double hx = 0.5 * (double(l[2]) + double(l[4])) * 13.0;
      const double hy = 0.5 * (double(l[3]) + double(l[5])) * 9.0;
      double exact[4];
      exactBoxAverage(reference, double(l[0]) * 13.0 - hx, double(l[0]) * 13.0 + hx,
                      double(l[1]) * 9.0 - hy, double(l[1]) * 9.0 + hy, exact);
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(exact[c], truth.rgba[c], 2e-4) << wrapName(wrap);
    }
  }
}

// Whole periods: a box of k periods under repeat averages to the texture's
// mean whatever its position; under clamp, a box far outside reads the edge.
TEST(SummedArea, WholePeriodsAverageToTheMeanAndFarBoxesReadTheEdge) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(11, 6, 2));
  double mean[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < image->rgba.size(); ++i) mean[i % 4] += image->rgba[i];
  for (double& m : mean) m /= 66.0;
  const Texture repeat(image, samplerWith(WrapMode::Repeat, kBorder));
  // u in the middle of a texel column, 3 periods wide: exactly 3 periods.
  const std::vector<Lookup> periods = {{0.37f, -5.2f, 3.0f, 0.0f, 0.0f, 2.0f},
                                       {1e4f + 0.25f, 0.5f, 0.0f, 1.0f, 5.0f, 0.0f}};
  const std::vector<float> got = sampleAll(repeat, Filter::SummedArea, Isa::Scalar, periods);
  for (std::size_t i = 0; i < periods.size(); ++i)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[i * 4 + c], mean[c], 1e-6) << i;

  const Texture clamp(image, samplerWith(WrapMode::ClampToEdge, kBorder));
  const BilinearReference reference(*image, samplerWith(WrapMode::ClampToEdge, kBorder));
  // Far right of the texture, one texel tall at row 2's centre: the last column's texel.
  const std::vector<Lookup> far = {{1e6f, 2.5f / 6.0f, 0.5f, 0.0f, 0.0f, 1e-6f}};
  const std::vector<float> edge = sampleAll(clamp, Filter::SummedArea, Isa::Scalar, far);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(edge[c], image->texel(10, 2)[c], 1e-5);
}

// The table's integer sums against direct double sums, on a texture large
// enough that a float table's entries (up to ~2e6) have lost every digit of a
// small box: its error, measured here, is what the fixed point removes.
TEST(SummedArea, BoxSumsAreExactWhereAFloatTableFails) {
  constexpr int kSide = 2048;
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(kSide, kSide, 9));
  const Texture texture(image, samplerWith(WrapMode::Repeat, kBorder));
  const Executor executor(2);
  const SummedAreaTable& table = texture.summedAreaTable(&executor);
  EXPECT_GE(table.fractionBits(), 24);
  const TextureView view = makeTextureView(texture, FilterSettings(Filter::SummedArea));

  // The naive table, channel 0, in float.
  std::vector<float> naive(std::size_t(kSide + 1) * (kSide + 1), 0.0f);
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      naive[std::size_t(y + 1) * (kSide + 1) + x + 1] =
          image->texel(x, y)[0] + naive[std::size_t(y) * (kSide + 1) + x + 1] +
          naive[std::size_t(y + 1) * (kSide + 1) + x] - naive[std::size_t(y) * (kSide + 1) + x];
  auto at = [&](int x, int y) { return double(naive[std::size_t(y) * (kSide + 1) + x]); };

  std::mt19937 rng(3);
  std::uniform_int_distribution<int> corner(kSide / 2, kSide - 9), size(1, 8);
  double worstNaive = 0.0, worstTable = 0.0;
  for (int i = 0; i < 500; ++i) {
    const int x0 = corner(rng), y0 = corner(rng), x1 = x0 + size(rng), y1 = y0 + size(rng);
    double direct[4] = {0, 0, 0, 0};
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 4; ++c) direct[c] += image->texel(x, y)[c];
    const double area = double(x1 - x0) * double(y1 - y0);
    double sum[4];
    table.texelSum(view, x0, x1, y0, y1, sum);
    for (int c = 0; c < 4; ++c)
      worstTable = std::max(worstTable, std::abs(sum[c] - direct[c]) / area);
    const double naiveSum = at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
    worstNaive = std::max(worstNaive, std::abs(naiveSum - direct[0]) / area);
  }
  // Fixed-point rounding only: half a step per texel.
  EXPECT_LE(worstTable, std::ldexp(1.0, -table.fractionBits() - 1));
  EXPECT_GT(worstNaive, 0.01) << "the float table was expected to fail here";
}

TEST(SummedArea, EveryIsaAndThreadCountGivesTheSameBits) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(37, 23, 5));
  const Texture texture(image, samplerWith(WrapMode::MirroredRepeat, kBorder),
                        TexelFormat::Rgba16F);
  const std::vector<Lookup> lookups = randomLookups(300, 12);
  const std::vector<float> scalar = sampleAll(texture, Filter::SummedArea, Isa::Scalar, lookups);
  for (const Isa isa : supportedIsas())
    EXPECT_EQ(sampleAll(texture, Filter::SummedArea, isa, lookups), scalar) << isaName(isa);
  // A table built on 3 threads holds the sums of the serial one (texture's,
  // built by the lookups above).
  const Texture parallel(image, samplerWith(WrapMode::MirroredRepeat, kBorder),
                         TexelFormat::Rgba16F);
  const Executor executor(3);
  const TextureView parallelView =
      makeTextureView(parallel, FilterSettings(Filter::SummedArea), &executor);
  const TextureView serialView = makeTextureView(texture, FilterSettings(Filter::SummedArea));
  double a[4], b[4];
  parallelView.summedArea->texelSum(parallelView, -40, 77, -3, 51, a);
  serialView.summedArea->texelSum(serialView, -40, 77, -3, 51, b);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(a[c], b[c]);
}

// The lane kernels against the scalar reference, SummedAreaTable::lookup, bit
// for bit on every ISA and wrap mode, over footprints from sub-texel to past
// the 64-period limit and the inputs that take special paths (NaN, Inf, zero
// derivatives, far positions); and the reference itself against a hash of its
// output before the kernels were vectorized (commit d828d93: lookup called lane
// by lane), so the lane code is checked against that code, not only against
// what the reference has become.
TEST(SummedArea, LaneKernelsGiveTheScalarReferenceBitsInEveryWrapMode) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(37, 23, 5));
  std::vector<Lookup> lookups = randomLookups(997, 21);  // not a whole number of lane groups
  for (const Lookup& l : randomLookups(64, 22))          // boxes beyond 64 periods, clamped
    lookups.push_back({l[0] * 100.0f, l[1], l[2] * 200.0f, l[3] * 200.0f, l[4], l[5]});
  const float inf = INFINITY, nan = NAN;
  const std::vector<Lookup> special = {
      {0.3f, 0.7f, 0.0f, 0.0f, 0.0f, 0.0f},     {nan, 0.5f, 0.01f, 0.0f, 0.0f, 0.01f},
      {0.5f, inf, 0.01f, 0.0f, 0.0f, 0.01f},    {0.5f, 0.5f, nan, 0.0f, 0.0f, 0.01f},
      {0.5f, 0.5f, inf, 0.0f, 0.0f, -inf},      {-1e30f, 1e30f, 0.02f, 0.0f, 0.0f, 0.02f},
      {-7.25f, 40.5f, 3.0f, -1.0f, 2.0f, 5.0f}, {0.0f, 1.0f, 1e-9f, 0.0f, 0.0f, 1e-9f}};
  lookups.insert(lookups.end(), special.begin(), special.end());
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a over every mode's reference bits
  for (const WrapMode wrap : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge,
                              WrapMode::ClampToBorder}) {
    const Texture texture(image, samplerWith(wrap, kBorder), TexelFormat::Rgba32F);
    const TextureView view = makeTextureView(texture, FilterSettings(Filter::SummedArea));
    std::vector<std::uint32_t> reference(lookups.size() * 4);
    for (std::size_t i = 0; i < lookups.size(); ++i) {
      const Lookup& l = lookups[i];
      float rgba[4];
      view.summedArea->lookup(view, l[0], l[1], l[2], l[3], l[4], l[5], rgba);
      std::memcpy(&reference[i * 4], rgba, sizeof(rgba));
    }
    for (const std::uint32_t bits : reference)
      for (int byte = 0; byte < 4; ++byte)
        hash = (hash ^ ((bits >> (8 * byte)) & 0xFF)) * 1099511628211ull;
    for (const Isa isa : supportedIsas()) {
      const std::vector<float> got = sampleAll(texture, Filter::SummedArea, isa, lookups);
      std::vector<std::uint32_t> gotBits(got.size());
      std::memcpy(gotBits.data(), got.data(), got.size() * sizeof(float));
      for (std::size_t i = 0; i < gotBits.size(); ++i)
        ASSERT_EQ(gotBits[i], reference[i])
            << wrapName(wrap) << " " << isaName(isa) << " lookup " << i / 4 << " channel " << i % 4;
    }
  }
  EXPECT_EQ(hash, 12025791041729856473ull) << "the reference's bits changed";
}

// `quadra report sat-precision` prints, per texture and box size, a float
// table's error far above the fixed-point table's, which stays within its
// rounding bound.
TEST(SummedArea, PrecisionReportShowsTheFloatTableFailingAndTheFixedPointHolding) {
  const std::string out = (std::filesystem::temp_directory_path() /
                           ("quadra_sat_report_" + std::to_string(getpid()) + ".txt"))
                              .string();
  const std::string command = std::string(QUADRA_CLI_PATH) +
                              " report sat-precision --size 512 --boxes 200 --threads 2 >" + out;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(out);
  std::string line;
  int fixedRows = 0;
  double floatMax = 0.0;
  while (std::getline(in, line)) {
    // | texture | sides | table | bytes | max | rms |
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, '|');) cells.push_back(cell);
    if (cells.size() != 7 || cells[5].find_first_of("0123456789") == std::string::npos) continue;
    const double maxError = std::stod(cells[5]);
    if (cells[3] == " float ") floatMax = std::max(floatMax, maxError);
    if (cells[3].find("int64") != std::string::npos) {
      ++fixedRows;
      EXPECT_LE(maxError, 1e-9) << line;  // 512^2 leaves 2^-31 steps
    }
  }
  std::filesystem::remove(out);
  EXPECT_EQ(fixedRows, 6);  // 2 textures x 3 box-size buckets
  EXPECT_GT(floatMax, 1e-5);
}

// The smallest texture the report takes (16 x 16) holds no box of the
// largest bucket's sides (17-128): that bucket is left out, not sampled
// from an empty range (which crashed).
TEST(SummedArea, PrecisionReportOnTheSmallestTextureLeavesOutBoxesThatDoNotFit) {
  const std::string out = (std::filesystem::temp_directory_path() /
                           ("quadra_sat_small_" + std::to_string(getpid()) + ".txt"))
                              .string();
  const std::string command = std::string(QUADRA_CLI_PATH) +
                              " report sat-precision --size 16 --boxes 20 --threads 1 >" + out;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(out);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove(out);
  EXPECT_NE(text.find("| 3-16 |"), std::string::npos) << text;
  EXPECT_EQ(text.find("| 17-"), std::string::npos) << text;
}

}  // namespace
}  // namespace quadra
