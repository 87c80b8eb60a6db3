// libFuzzer's entry point for one target, the one QUADRA_FUZZ_ENTRY names
// (tests/fuzz/CMakeLists.txt builds one executable per target).
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  quadra::fuzz::QUADRA_FUZZ_ENTRY(data, size);
  return 0;
}
