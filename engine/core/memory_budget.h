// MemoryBudget: the bytes one load or one render may allocate for the big
// things a scene file controls (decoded buffers and images, texture levels,
// the frame and tile memory), charged before each allocation so that a hostile
// or careless file ends in a one-line error instead of an out-of-memory kill.
// It travels with the call (LoadOptions::maxMemory, RenderSettings::maxMemory):
// no global state. The rules and defaults: docs/cli.md, "Memory budget".
#pragma once

#include <cstdint>
#include <string>

namespace quadra {

// The default budget of a load and of a render: 8 GiB. The largest image a
// scene may hold (2^28 texels, decoded to 4 GiB of linear float RGBA) fits
// once, a second one does not, and every shipped scene and test stays far
// below it; a fixed figure keeps the outcome the same on every machine.
constexpr std::uint64_t kDefaultMaxMemory = std::uint64_t(8) << 30;

// "512M", "4G", "1.5G", "65536": a number of bytes, optionally with a suffix
// K, M, G or T (1024-based; "KiB", "MB" and the like mean the same), at least
// 1 byte and at most 1024T (2^50); `option` names the flag in the one-line Error.
std::uint64_t parseMemorySize(const std::string& option, const std::string& text);

// A size for messages: "3.0 GiB", "512.0 MiB", "700 bytes", "1 byte".
std::string formatBytes(std::uint64_t bytes);

class MemoryBudget {
 public:
  // owner: what messages start with (the scene file, or "render").
  MemoryBudget(std::uint64_t limit, std::string owner);

  // Counts `bytes` for `what` ("image 0 ('big.png') decoded to 16384x16384")
  // or throws Error("<owner>: <what> needs <n>, over the memory budget of
  // <limit> (<used> already used; --max-memory raises it)"), leaving the
  // count as it was. Not thread-safe: charge from one thread, in a fixed
  // order, so that which charge fails does not depend on scheduling.
  void charge(const std::string& what, std::uint64_t bytes);

  std::uint64_t used() const { return used_; }
  std::uint64_t limit() const { return limit_; }

 private:
  std::uint64_t limit_;
  std::uint64_t used_ = 0;
  std::string owner_;
};

}  // namespace quadra
