// posix_spawn with stdout and stderr redirected to scratch files; execv.
#include "subprocess.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.h"

extern char** environ;

namespace quadra {
namespace {

std::string readWhole(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// argv for posix_spawn and execv: the program, its arguments, a null.
class ArgumentVector {
 public:
  ArgumentVector(const std::filesystem::path& program, const std::vector<std::string>& arguments)
      : text_{program.string()} {
    text_.insert(text_.end(), arguments.begin(), arguments.end());
    for (std::string& argument : text_) pointers_.push_back(argument.data());
    pointers_.push_back(nullptr);
  }
  ArgumentVector(const ArgumentVector&) = delete;  // the pointers point into text_
  ArgumentVector& operator=(const ArgumentVector&) = delete;
  char* const* data() const { return pointers_.data(); }
  const char* program() const { return pointers_[0]; }

 private:
  std::vector<std::string> text_;
  std::vector<char*> pointers_;
};

}  // namespace

ProcessResult runProcess(const std::filesystem::path& program,
                         const std::vector<std::string>& arguments,
                         const std::filesystem::path& scratchDir) {
  const std::string tag = std::to_string(::getpid());
  const std::filesystem::path outPath = scratchDir / ("stdout-" + tag + ".txt"),
                              errPath = scratchDir / ("stderr-" + tag + ".txt");
  ArgumentVector argv(program, arguments);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, outPath.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, errPath.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ProcessResult result;
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv.program(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0)
    throw Error(program.string() + ": cannot start (" + std::strerror(spawned) + ")");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw Error(program.string() + ": lost track of the process");
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = readWhole(outPath);
  result.err = readWhole(errPath);
  std::filesystem::remove(outPath);
  std::filesystem::remove(errPath);
  return result;
}

void replaceProcess(const std::filesystem::path& program,
                    const std::vector<std::string>& arguments) {
  ArgumentVector argv(program, arguments);
  std::fflush(nullptr);  // what this process printed comes before the program's
  ::execv(argv.program(), argv.data());
  throw Error(program.string() + ": cannot start (" + std::strerror(errno) + ")");
}

std::filesystem::path executablePath() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("/proc/self/exe: cannot find this program's own file");
  return self;
}

}  // namespace quadra
