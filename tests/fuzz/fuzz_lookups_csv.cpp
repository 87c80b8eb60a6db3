// Fuzz target lookups_csv: the bytes as the LOOKUPS.csv of `quadra sample`
// through its reader, and the rows it accepts (any float strtof gives: NaN,
// Inf, denormals, 1e38) looked up in a small texture with every filter on
// every ISA path, as the command does.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <sstream>
#include <string>

#include "core/error.h"
#include "fuzz_support.h"
#include "lookups_csv.h"
#include "texture/texture.h"

namespace {

// An 8x8 texture with distinct texels, so that a wrong texel address shows
// up as a read outside it rather than a plausible colour.
std::shared_ptr<const quadra::Image> smallImage() {
  auto image = std::make_shared<quadra::Image>(8, 8);
  for (std::size_t i = 0; i < image->rgba.size(); ++i) image->rgba[i] = float(i % 29) / 28.0f;
  return image;
}

}  // namespace

void quadra::fuzz::runLookupsCsv(const std::uint8_t* data, std::size_t size) {
  Lookups lookups;
  try {
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    lookups = readLookups(in, "lookups.csv");
  } catch (const Error&) {
    return;  // the expected outcome for a malformed file
  }
  // The reader is what grows with the input; the kernels see a bounded batch.
  LookupBatch batch = lookups.batch();
  batch.count = std::min<std::size_t>(batch.count, 64);
  static const std::shared_ptr<const Image> image = smallImage();
  SamplerState state;
  state.wrapU = WrapMode(size % 4);
  state.wrapV = WrapMode(size / 4 % 4);
  const Texture texture(image, state);
  std::vector<float> rgba(batch.count * 4);
  for (Isa isa : supportedIsas())
    for (Filter filter : kEveryFilter) {
      const TextureSampler sampler(texture, FilterSettings(filter), isa);
      sampler.sample(batch, 0, batch.count, rgba.data());
    }
}
