// Test helpers for the programs the build makes (the quadra CLI and its peer
// renderers), run as subprocesses: their exit status and output, scratch
// files, and the one-line error check.
#pragma once

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "render_options.h"

namespace quadra {

namespace fs = std::filesystem;

struct RunResult {
  int exitCode = -1;
  std::string out, err;
};

// One directory per test process: CTest runs the cases in parallel. It is
// removed when the process exits (a run left one behind per process before,
// ~1500 after a day of test runs).
inline fs::path testDir() {
  static const struct Scratch {
    fs::path dir = fs::temp_directory_path() / ("quadra_cli_test_" + std::to_string(getpid()));
    ~Scratch() {
      std::error_code ignored;
      fs::remove_all(dir, ignored);
    }
  } scratch;
  fs::create_directories(scratch.dir);
  return scratch.dir;
}

// `program arguments` through the shell, stdin from /dev/null.
inline RunResult runProgram(const std::string& program, const std::string& arguments) {
  const fs::path dir = testDir();
  const std::string outFile = (dir / "stdout.txt").string(),
                    errFile = (dir / "stderr.txt").string();
  const std::string command =
      program + " " + arguments + " >" + outFile + " 2>" + errFile + " </dev/null";
  const int status = std::system(command.c_str());
  RunResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream o(outFile), e(errFile);
  std::stringstream os, es;
  os << o.rdbuf();
  es << e.rdbuf();
  r.out = os.str();
  r.err = es.str();
  return r;
}

// The quadra CLI.
inline RunResult run(const std::string& arguments) {
  return runProgram(QUADRA_CLI_PATH, arguments);
}

inline fs::path tempPath(const std::string& name) {
  const fs::path dir = testDir();
  fs::remove(dir / name);
  return dir / name;
}

// A glTF sample model of the shared assets beside the checkout (tests skip
// when it is absent).
inline std::string modelPath(const std::string& model) {
  return std::string(QUADRA_ASSETS_DIR) + "/" + model + "/glTF/" + model + ".gltf";
}

// An empty scratch folder of its own for each test.
inline fs::path emptyFolder(const std::string& name) {
  const fs::path dir = testDir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The names of the files in `dir`, sorted.
inline std::vector<std::string> fileNames(const fs::path& dir) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

inline std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The commands `quadra help` lists ("render", "sample", "report textures",
// ...), without their arguments and without help and --version: each has its
// own --help.
inline std::vector<std::string> commandsInOverview(const std::string& overview) {
  std::vector<std::string> commands;
  std::istringstream lines(overview);
  bool listing = false;
  for (std::string line; std::getline(lines, line);) {
    if (line == "commands:") {
      listing = true;
      continue;
    }
    if (!listing || line.rfind("  ", 0) != 0) {
      listing = false;
      continue;
    }
    std::string name = line.substr(2, line.find("   ", 2) - 2);
    name = name.substr(0, name.find(" ["));  // "render [SCENE]"
    if (name != "help" && name != "--version") commands.push_back(name);
  }
  return commands;
}

inline void expectOneLineError(const RunResult& r, const std::string& mentions) {
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find(mentions), std::string::npos) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
}

// The render contract (DESIGN.md "Contracts"), whichever renderer ran
// `render builtin:checker-plane --width 96 --height 54 --frames 3 --threads 2
// --out EXR --out PNG`: a frame line after `prefix` with what it rendered,
// and both files at that size.
inline void expectCheckerPlaneFrame(const RunResult& r, const std::string& prefix,
                                    const fs::path& exr, const fs::path& png) {
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto line = lineKeyValues(r.out, prefix);
  for (const char* key : {"median", "min", "max", "triangles", "width", "height", "threads"})
    ASSERT_TRUE(line.count(key)) << key << " missing in: " << r.out;
  EXPECT_EQ(line.at("width"), "96");
  EXPECT_EQ(line.at("height"), "54");
  EXPECT_EQ(line.at("threads"), "2");
  EXPECT_EQ(line.at("triangles"), "2");
  EXPECT_LE(std::stod(line.at("min")), std::stod(line.at("median")));
  EXPECT_LE(std::stod(line.at("median")), std::stod(line.at("max")));
  const Image fromExr = readImage(exr.string()), fromPng = readImage(png.string());
  EXPECT_EQ(fromExr.width, 96);
  EXPECT_EQ(fromPng.height, 54);
}

// The llvmpipe peer (quadra-llvmpipe), where the build made it (it needs
// libosmesa6-dev): its tests skip elsewhere.
#if defined(QUADRA_LLVMPIPE_PATH)
inline constexpr bool kHavePeer = true;
inline RunResult runPeer(const std::string& arguments) {
  return runProgram(QUADRA_LLVMPIPE_PATH, arguments);
}
#else
inline constexpr bool kHavePeer = false;
inline RunResult runPeer(const std::string&) {
  return {};
}
#endif

#define SKIP_WITHOUT_PEER() \
  if (!kHavePeer) GTEST_SKIP() << "quadra-llvmpipe was not built (needs libosmesa6-dev)"

}  // namespace quadra
