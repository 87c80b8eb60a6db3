// Running another program: to completion, for reports that time whole
// processes (`quadra report frames` runs quadra and its peer renderers), with
// its exit status, what it printed, and its wall time from spawn to exit; or
// in this process's place (`quadra report` becomes quadra-report).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace quadra {

struct ProcessResult {
  int exitCode = -1;  // -1: killed by a signal
  std::string out, err;
  double seconds = 0.0;  // from just before the spawn to the reaped exit
};

// Runs `program` with `arguments` (no shell, so no quoting), stdin from
// /dev/null; stdout and stderr go through files in `scratchDir`, which
// unlike pipes cannot stall the child, and are read back after it exits.
// Throws Error when the program cannot be started.
ProcessResult runProcess(const std::filesystem::path& program,
                         const std::vector<std::string>& arguments,
                         const std::filesystem::path& scratchDir);

// Replaces this process with `program` and `arguments` (execv: the same
// stdin, stdout, stderr and environment; its exit status is this process's).
// Returns only by throwing Error, when the program cannot be started.
[[noreturn]] void replaceProcess(const std::filesystem::path& program,
                                 const std::vector<std::string>& arguments);

// The running executable (/proc/self/exe); the programs built with it are in
// the same folder.
std::filesystem::path executablePath();

}  // namespace quadra
