// Fuzz target image: the bytes as an image file through readImage (PNG, JPEG
// or EXR by their magic number, as `quadra sample --texture` and glTF images
// read them), the in-memory PNG and JPEG decoders that glTF's embedded images
// use, and, for a small image, the texture built from it (mip chain and all)
// sampled once with every filter.
#include <cstddef>
#include <cstdint>
#include <memory>

#include "core/error.h"
#include "fuzz_support.h"
#include "io/image_io.h"
#include "texture/texture.h"
#include "texture/texture_sampler.h"

namespace {

void sampleEveryFilter(quadra::Image image) {
  using namespace quadra;
  const auto shared = std::make_shared<const Image>(std::move(image));
  const Texture texture(shared, SamplerState{});
  const float u = 0.3f, v = 0.7f, dudx = 0.9f, dvdx = 0.1f, dudy = -0.2f, dvdy = 0.4f;
  const LookupBatch batch{&u, &v, &dudx, &dvdx, &dudy, &dvdy, 1};
  float rgba[4];
  for (Filter filter : kEveryFilter) {
    const TextureSampler sampler(texture, FilterSettings(filter), Isa::Scalar);
    sampler.sample(batch, 0, 1, rgba);
  }
}

}  // namespace

void quadra::fuzz::runImage(const std::uint8_t* data, std::size_t size) {
  try {
    if (isPng(data, size)) (void)decodePng(data, size, "memory.png");
    if (isJpeg(data, size)) (void)decodeJpeg(data, size, "memory.jpg");
  } catch (const Error&) {
  }
  try {
    Image image = readImage(writeInput(data, size, "input.img"));
    // Large images only cost time here: their decoding is what was fuzzed.
    if (std::size_t(image.width) * std::size_t(image.height) <= 64 * 64)
      sampleEveryFilter(std::move(image));
  } catch (const Error&) {
    // A one-line user error is the expected outcome for malformed input.
  }
}
