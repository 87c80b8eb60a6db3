// Row padding of texture levels (see padded_level.h).
#include "texture/padded_level.h"

#include <algorithm>
#include <cstddef>

#include "core/large_buffer.h"
#include "core/parallel.h"

namespace quadra {

PaddedLevel::PaddedLevel(const Image& image, TexelFormat format, const Executor* executor)
    : width(image.width), height(image.height), stride(image.width + 1) {
  resizeLarge(texels,
              std::size_t(stride) * std::size_t(height) * std::size_t(bytesPerTexel(format)),
              std::uint8_t(0), executor);
  const std::size_t texelBytes = std::size_t(bytesPerTexel(format));
  const auto encodeRows = [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y) {
      std::uint8_t* row = texels.data() + y * std::size_t(stride) * texelBytes;
      encodeTexels(format, image.texel(0, int(y)), std::size_t(width), row);
      std::copy(row, row + texelBytes, row + std::size_t(width) * texelBytes);
    }
  };
  // Each row is independent, so any split writes the same bytes.
  if (executor)
    executor->parallelFor(std::size_t(height), 16, encodeRows);
  else
    encodeRows(0, std::size_t(height));
}

}  // namespace quadra
