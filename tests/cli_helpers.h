// Test helpers for the programs the build makes (the quadra CLI and its peer
// renderers), run as subprocesses: their exit status and output, scratch
// files, and the one-line error check.
#pragma once

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace quadra {

namespace fs = std::filesystem;

struct RunResult {
  int exitCode = -1;
  std::string out, err;
};

// One directory per test process: CTest runs the cases in parallel.
inline fs::path testDir() {
  const fs::path dir = fs::temp_directory_path() / ("quadra_cli_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
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

inline void expectOneLineError(const RunResult& r, const std::string& mentions) {
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find(mentions), std::string::npos) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
}

}  // namespace quadra
