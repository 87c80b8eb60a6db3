// Whole files read into memory (file_bytes.h), through a POSIX descriptor so
// that what is checked (type, size, where it really is) is the file read.
#include "core/file_bytes.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <system_error>

#include "core/error.h"

namespace quadra {

namespace {

class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

// O_NONBLOCK: opening a FIFO must not wait for a writer; it is then refused
// as not a regular file. Regular files ignore the flag.
int openForReading(const std::string& path, int extraFlags) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | extraFlags);
  if (fd < 0) {
    if (errno == ELOOP && (extraFlags & O_NOFOLLOW)) {
      throw makeError(path, "is now a symbolic link (replaced after the sandbox checked it)");
    }
    throw makeError(path, "cannot open file");
  }
  return fd;
}

std::vector<std::uint8_t> readOpened(const Descriptor& file, const std::string& path) {
  struct stat status {};
  if (::fstat(file.get(), &status) != 0) throw makeError(path, "cannot read file");
  if (S_ISDIR(status.st_mode)) throw makeError(path, "is a directory");
  if (!S_ISREG(status.st_mode)) throw makeError(path, "is not a regular file");
  if (status.st_size == 0) throw makeError(path, "file is empty");
  if (std::uint64_t(status.st_size) > kMaxFileSize) {
    throw makeError(path, "file is larger than 4 GiB");
  }
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(status.st_size));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t got = ::read(file.get(), bytes.data() + done, bytes.size() - done);
    if (got < 0 && errno == EINTR) continue;
    // 0 before the end: the file shrank while being read.
    if (got <= 0) throw makeError(path, "cannot read file");
    done += std::size_t(got);
  }
  return bytes;
}

}  // namespace

std::vector<std::uint8_t> readWholeFile(const std::string& path) {
  const Descriptor file(openForReading(path, 0));
  return readOpened(file, path);
}

std::vector<std::uint8_t> readCanonicalFile(const std::string& path) {
  const Descriptor file(openForReading(path, O_NOFOLLOW));
  // O_NOFOLLOW guards the last component only; the kernel's name for the
  // open file says whether a folder on the way became a link. Without /proc
  // (not Linux, or not mounted) that second check is not possible and the
  // last-component guard is what remains.
  std::array<char, 4096> target{};
  const std::string self = "/proc/self/fd/" + std::to_string(file.get());
  const ssize_t length = ::readlink(self.c_str(), target.data(), target.size() - 1);
  if (length > 0) {
    const std::string opened(target.data(), std::size_t(length));
    if (opened != path) {
      throw makeError(path, "now resolves to " + opened +
                                " (a link replaced a folder after the sandbox checked it)");
    }
  }
  return readOpened(file, path);
}

}  // namespace quadra
