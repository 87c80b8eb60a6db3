// Fuzz target environment: the bytes as a panorama file through
// loadEnvironment (Radiance .hdr or OpenEXR by their first bytes, the size
// rule, the memory budget and the texel rule, as `quadra env` and --env read
// them), and the .hdr decoder straight from memory. The budget is 16 MiB, so
// a header's claimed size is refused before allocation rather than decoded
// into libFuzzer's 2 GB limit; a loaded panorama is checked against the
// rule's promise (finite, non-negative, at most kMaxEnvironmentRadiance).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/error.h"
#include "core/memory_budget.h"
#include "fuzz_support.h"
#include "io/radiance_hdr.h"
#include "shading/environment_source.h"

namespace {

constexpr std::uint64_t kFuzzEnvironmentBudget = std::uint64_t(16) << 20;

}  // namespace

void quadra::fuzz::runEnvironment(const std::uint8_t* data, std::size_t size) {
  try {
    MemoryBudget budget(kFuzzEnvironmentBudget, "fuzz");
    const RgbImage image =
        decodeRadianceHdr(data, size, "memory.hdr", [&](std::int64_t width, std::int64_t height) {
          checkEnvironmentSize("memory.hdr", width, height);
          budget.charge("texels", std::uint64_t(width) * std::uint64_t(height) * 12);
        });
    if (image.rgb.size() != std::size_t(image.width) * std::size_t(image.height) * 3) std::abort();
  } catch (const Error&) {
  }
  try {
    MemoryBudget budget(kFuzzEnvironmentBudget, "fuzz");
    const EnvironmentImage env = loadEnvironment(writeInput(data, size, "input.env"), budget);
    if (env.width < 1 || env.height < 1 || env.texelCount() < 2 ||
        env.rgb.size() != env.texelCount() * 3)
      std::abort();
    for (float v : env.rgb)
      if (!(v >= 0.0f && v <= kMaxEnvironmentRadiance)) std::abort();
  } catch (const Error&) {
    // A one-line user error is the expected outcome for malformed input.
  }
}
