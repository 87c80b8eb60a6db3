// Fuzz targets gltf_json and glb: the bytes as a .gltf or .glb file through
// loadGltf, as `quadra render FILE` reads it, and whatever loads is drawn at
// 32x24 (one thread, the best ISA) so that the loader's output reaches the
// pipeline too. Two targets, as the loader chooses the parser by the
// extension and each form wants its own corpus. Both load and frame run under
// a 1 GiB memory budget (--max-memory), as a render farm would set one: an
// input whose sizes ask for more is the expected one-line error, not a
// finding of libFuzzer's 2 GB resident limit (scripts/fuzz.sh).
#include <cstddef>
#include <cstdint>

#include "api/renderer.h"
#include "core/error.h"
#include "fuzz_support.h"
#include "scene/gltf_loader.h"

namespace quadra::fuzz {
namespace {

constexpr std::uint64_t kFuzzMemoryBudget = std::uint64_t(1) << 30;

void runGltf(const std::uint8_t* data, std::size_t size, const char* name) {
  const std::string path = writeInput(data, size, name);
  try {
    std::vector<std::string> notes;
    LoadOptions options;
    options.maxMemory = kFuzzMemoryBudget;
    const Scene scene = loadGltf(path, options, &notes);
    static Renderer renderer({.threads = 1, .isa = std::nullopt});
    Frame frame;
    RenderSettings settings;
    settings.width = 32;
    settings.height = 24;
    settings.maxMemory = kFuzzMemoryBudget;
    renderer.render(scene, firstCameraOrDefault(scene), settings, frame);
  } catch (const Error&) {
    // A one-line user error is the expected outcome for malformed input.
  }
}

}  // namespace

void runGltfJson(const std::uint8_t* data, std::size_t size) {
  runGltf(data, size, "in.gltf");
}
void runGlb(const std::uint8_t* data, std::size_t size) {
  runGltf(data, size, "in.glb");
}

}  // namespace quadra::fuzz
