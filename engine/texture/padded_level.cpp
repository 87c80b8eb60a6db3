// Row padding of texture levels (see padded_level.h).
#include "texture/padded_level.h"

#include <algorithm>
#include <cstddef>

namespace quadra {

PaddedLevel::PaddedLevel(const Image& image)
    : texels(std::size_t(image.width + 1) * std::size_t(image.height) * 4),
      width(image.width),
      height(image.height),
      stride(image.width + 1) {
  for (int y = 0; y < height; ++y) {
    const float* source = image.texel(0, y);
    float* row = texels.data() + std::size_t(y) * std::size_t(stride) * 4;
    std::copy(source, source + std::size_t(width) * 4, row);
    std::copy(source, source + 4, row + std::size_t(width) * 4);
  }
}

}  // namespace quadra
