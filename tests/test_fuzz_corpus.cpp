// Every fuzz target's seed corpus and every input a fuzzing run found
// (tests/fuzz/corpus/TARGET, tests/fuzz/regressions/TARGET) replayed through
// the target's own code in every test build, so that the Release and
// sanitizer suites keep each fixed finding fixed without libFuzzer. One ctest
// per target; a crash or a sanitizer report fails it, and an exception other
// than quadra::Error escapes the entry point and fails it too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_support.h"

namespace quadra {
namespace {

namespace fs = std::filesystem;

struct FuzzTarget {
  const char* name;
  void (*run)(const std::uint8_t*, std::size_t);
};

const FuzzTarget kTargets[] = {{"gltf_json", fuzz::runGltfJson},
                               {"glb", fuzz::runGlb},
                               {"image", fuzz::runImage},
                               {"environment", fuzz::runEnvironment},
                               {"lookups_csv", fuzz::runLookupsCsv},
                               {"render", fuzz::runRender}};

std::vector<fs::path> inputsOf(const std::string& target) {
  std::vector<fs::path> files;
  for (const char* folder : {"corpus", "regressions"}) {
    const fs::path dir = fs::path(QUADRA_FUZZ_DIR) / folder / target;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec))
      if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class FuzzCorpus : public ::testing::TestWithParam<FuzzTarget> {};

TEST_P(FuzzCorpus, EveryInputRunsWithoutAFinding) {
  const FuzzTarget& target = GetParam();
  const std::vector<fs::path> files = inputsOf(target.name);
  ASSERT_FALSE(files.empty()) << "no seeds for " << target.name;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    std::ifstream in(file, std::ios::binary);
    const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
    target.run(bytes.data(), bytes.size());
  }
}

INSTANTIATE_TEST_SUITE_P(Fuzz, FuzzCorpus, ::testing::ValuesIn(kTargets),
                         [](const ::testing::TestParamInfo<FuzzTarget>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace quadra
