// Row padding of texture levels (see padded_level.h).
#include "texture/padded_level.h"

#include <algorithm>
#include <cstddef>

namespace quadra {

PaddedLevel::PaddedLevel(const Image& image, TexelFormat format)
    : texels(std::size_t(image.width + 1) * std::size_t(image.height) *
             std::size_t(bytesPerTexel(format))),
      width(image.width),
      height(image.height),
      stride(image.width + 1) {
  const std::size_t texelBytes = std::size_t(bytesPerTexel(format));
  for (int y = 0; y < height; ++y) {
    std::uint8_t* row = texels.data() + std::size_t(y) * std::size_t(stride) * texelBytes;
    for (int x = 0; x < width; ++x) encodeTexel(format, image.texel(x, y), row + x * texelBytes);
    std::copy(row, row + texelBytes, row + std::size_t(width) * texelBytes);
  }
}

}  // namespace quadra
