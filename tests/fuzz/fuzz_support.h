// What every fuzz target shares: its entry point (one function per target,
// which libFuzzer's LLVMFuzzerTestOneInput calls in the fuzz build and
// tests/test_fuzz_corpus.cpp calls on the seeds and the regression inputs in
// every test build), the bytes as a file (the loaders and readImage take a
// path, as the CLI gives them one), the ISA paths this CPU runs, and a reader
// that turns bytes into choices. quadra::Error is an expected outcome: the
// entry points catch it; anything else that escapes, or any crash, is a finding.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "simd/isa.h"

namespace quadra::fuzz {

// The targets, by the names scripts/fuzz.sh lists (fuzz_gltf.cpp runs both
// glTF forms).
void runGltfJson(const std::uint8_t* data, std::size_t size);
void runGlb(const std::uint8_t* data, std::size_t size);
void runImage(const std::uint8_t* data, std::size_t size);
void runEnvironment(const std::uint8_t* data, std::size_t size);
void runLookupsCsv(const std::uint8_t* data, std::size_t size);
void runRender(const std::uint8_t* data, std::size_t size);

// Choices taken from the front of the input; zeros once it is used up, so
// that every input, however short, makes a complete scene.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint32_t u32() {
    std::uint8_t bytes[4] = {0, 0, 0, 0};
    const std::size_t n = size_ < 4 ? size_ : 4;
    if (n) std::memcpy(bytes, data_, n);
    data_ += n;
    size_ -= n;
    return std::uint32_t(bytes[0]) | std::uint32_t(bytes[1]) << 8 | std::uint32_t(bytes[2]) << 16 |
           std::uint32_t(bytes[3]) << 24;
  }
  std::uint8_t byte() {
    if (!size_) return 0;
    --size_;
    return *data_++;
  }
  // In [lo, hi]; the range is small everywhere it is used.
  int in(int lo, int hi) { return lo + int(byte() % unsigned(hi - lo + 1)); }
  bool flag() { return byte() & 1; }
  // An ordinary value in [-range, range) from 16 bits.
  float unit(float range) {
    const unsigned bits = unsigned(byte()) | unsigned(byte()) << 8;
    return (float(bits) / 32768.0f - 1.0f) * range;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
};

// A folder of this process's own under TMPDIR (libFuzzer's -jobs/-fork
// workers each get one), made once and removed at a normal exit; the
// targets write their input there.
inline const std::string& scratchFolder() {
  static const std::string folder = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string base = (tmp && *tmp ? tmp : "/tmp");
    base += "/quadra-fuzz-" + std::to_string(::getpid());
    const std::string command = "mkdir -p '" + base + "'";
    if (std::system(command.c_str()) != 0) std::abort();
    return base;
  }();
  // Registered after `folder` is made, so it runs before `folder` is destroyed.
  static const bool removedAtExit = std::atexit([] {
                                      std::error_code ignored;
                                      std::filesystem::remove_all(scratchFolder(), ignored);
                                    }) == 0;
  (void)removedAtExit;
  return folder;
}

// Writes the input to scratchFolder()/name and returns that path.
inline std::string writeInput(const std::uint8_t* data, std::size_t size, const char* name) {
  const std::string path = scratchFolder() + "/" + name;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) std::abort();
  if (size && std::fwrite(data, 1, size, file) != size) std::abort();
  if (std::fclose(file) != 0) std::abort();
  return path;
}

// Every kernel path this CPU can run, scalar reference first.
inline std::vector<Isa> supportedIsas() {
  std::vector<Isa> isas;
  for (Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512})
    if (isaSupported(isa)) isas.push_back(isa);
  return isas;
}

}  // namespace quadra::fuzz
