// `quadra report lighting` (issue 46): quadra's lit frames, and the llvmpipe
// peer's where it draws pbr, against the lab's lit ideal and against each
// other's time. Run on one small sample model at tiny sizes: the tables and
// the CSV carry a row per scene and environment, quadra's PSNR figures are
// real scores against the ideal, the ideal is cached, and bad options fail
// before anything is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.h"

namespace quadra {
namespace {

// The cells of the first table row that starts with "| label | environment |".
std::vector<std::string> tableRow(const std::string& out, const std::string& label,
                                  std::size_t skip = 0) {
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("| " + label + " |", 0) != 0 || skip-- > 0) continue;
    std::vector<std::string> cells;
    std::istringstream parts(line.substr(1));
    for (std::string cell; std::getline(parts, cell, '|');)
      cells.push_back(cell.substr(1, cell.size() - 2));
    return cells;
  }
  return {};
}

TEST(ReportLighting, ScoresQuadrasLitFramesAgainstTheIdealAndTimesThem) {
  if (!fs::exists(modelPath("Suzanne"))) GTEST_SKIP() << "the shared sample models are absent";
  const fs::path dir = testDir() / "report_lighting";
  fs::remove_all(dir);
  const std::string command =
      "report lighting --scenes Suzanne --envs builtin:studio --accuracy-size 48x27 "
      "--speed-size 64x36 --ideal-spp 4 --rounds 1 --frames 1 --threads 2 "
      "--llvmpipe-ibl-size 32 --llvmpipe-lut-size 64 --out-dir " +
      dir.string();
  const RunResult r = run(command);
  ASSERT_EQ(r.exitCode, 0) << r.err;

  // scene, environment, ideal s, quadra 1 spp all, interior, 16 spp all,
  // interior, llvmpipe all, interior, gain dB
  const std::vector<std::string> accuracy = tableRow(r.out, "Suzanne");
  ASSERT_EQ(accuracy.size(), 10u) << r.out;
  EXPECT_EQ(accuracy[1], "studio");
  const std::regex number("-?[0-9]+(\\.[0-9]+)?");
  for (std::size_t i = 2; i < 7; ++i)
    EXPECT_TRUE(std::regex_match(accuracy[i], number)) << i << ": '" << accuracy[i] << "'";
  // Real scores: 16 supersampled samples near the ideal, the single sample
  // not far behind, each well above what a wrong frame scores.
  EXPECT_GT(std::stod(accuracy[5]), 30.0) << r.out;
  EXPECT_GT(std::stod(accuracy[3]), 20.0) << r.out;
  EXPECT_LT(std::stod(accuracy[3]), std::stod(accuracy[5]) + 3.0) << r.out;

  // scene, environment, triangles, quadra ms, 16 spp ms, llvmpipe ms, ratio,
  // 8-bit quadra, llvmpipe, ratio, e2e quadra, llvmpipe, ratio
  const std::vector<std::string> speed = tableRow(r.out, "Suzanne", 1);
  ASSERT_EQ(speed.size(), 13u) << r.out;
  EXPECT_EQ(speed[2], "3,936");
  for (const std::size_t i : {3u, 4u, 7u, 10u})
    EXPECT_TRUE(std::regex_match(speed[i], number)) << i << ": '" << speed[i] << "'";
  const bool peerMeasured = r.out.find("llvmpipe: not measured") == std::string::npos;
  if (peerMeasured) {
    for (const std::size_t i : {7u, 8u, 9u})
      EXPECT_TRUE(std::regex_match(accuracy[i], number)) << i << ": '" << accuracy[i] << "'";
    for (const std::size_t i : {5u, 6u, 8u, 9u, 11u, 12u})
      EXPECT_TRUE(std::regex_match(speed[i], number)) << i << ": '" << speed[i] << "'";
  } else {
    EXPECT_EQ(accuracy[7], "-");
    EXPECT_EQ(speed[5], "-");
  }
  EXPECT_NE(r.out.find("quadra 16 spp at least 40 dB (all pixels): "), std::string::npos);

  std::ifstream csv(dir / "lighting.csv");
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("scene,environment,triangles,ideal_s,", 0), 0u) << header;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line.rfind("Suzanne,studio,3936,", 0), 0u) << line;
  EXPECT_FALSE(std::getline(csv, line)) << "one row";
  std::ifstream svg(dir / "lighting.svg");
  std::stringstream plot;
  plot << svg.rdbuf();
  EXPECT_NE(plot.str().find("<circle"), std::string::npos);
  for (const char* file : {"Suzanne.studio.quadra-1spp.exr", "Suzanne.studio.quadra-16spp.exr"})
    EXPECT_TRUE(fs::exists(dir / "lighting" / file)) << file;

  // The second run reads the ideal back, to the same scores.
  const RunResult again = run(command);
  ASSERT_EQ(again.exitCode, 0) << again.err;
  const std::vector<std::string> cached = tableRow(again.out, "Suzanne");
  ASSERT_EQ(cached.size(), 10u) << again.out;
  EXPECT_EQ(cached[2], "cached");
  EXPECT_EQ(cached[3], accuracy[3]);
  EXPECT_EQ(cached[5], accuracy[5]);
}

TEST(ReportLighting, BadOptionsAreOneLineErrorsAndWriteNothing) {
  const fs::path dir = testDir() / "report_lighting_never";
  fs::remove_all(dir);
  const std::string outDir = " --out-dir " + dir.string();
  expectOneLineError(run("report lighting --bogus" + outDir),
                     "report lighting: unknown option '--bogus'");
  expectOneLineError(run("report lighting --accuracy-size 320" + outDir),
                     "--accuracy-size: expected WxH");
  expectOneLineError(run("report lighting --speed-size 0x10" + outDir), "--speed-size");
  expectOneLineError(run("report lighting --scenes NoSuchModel" + outDir),
                     "--scenes: 'NoSuchModel' is neither");
  expectOneLineError(
      run("report lighting --scenes builtin:showcase --envs /nonexistent.hdr" + outDir),
      "/nonexistent.hdr");
  expectOneLineError(run("report lighting --scenes builtin:showcase --envs builtin:nope" + outDir),
                     "builtin:nope");
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
}  // namespace quadra
