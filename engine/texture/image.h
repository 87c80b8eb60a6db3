// Image: a linear-float RGBA raster, the one pixel container quadra moves
// between loading, the texture stage and output. Row 0 is the top row, which
// is where glTF's v = 0 lies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace quadra {

class Executor;

// The largest image quadra reads or samples: 2^28 texels, a 16384^2 texture.
// Memory at that size: 4 GiB as the float Image, and as sampled storage with
// its mip chain (4/3 of level 0, padding aside) 5.3 GiB in rgba32f, 2.7 GiB in
// rgba16f, 1.3 GiB in rgba8. Larger files are refused by size before any
// pixel is decoded: more likely hostile than a texture, and a clear error
// beats dying in the allocator.
constexpr std::int64_t kMaxImagePixels = std::int64_t(1) << 28;

struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // width * height * 4, row-major, linear (not sRGB)

  Image() = default;
  // Zero-filled; the memory is mapped on `executor`'s threads when one is
  // given (core/large_buffer.h).
  Image(int w, int h, const Executor* executor = nullptr);

  float* texel(int x, int y) { return &rgba[(std::size_t(y) * std::size_t(width) + x) * 4]; }
  const float* texel(int x, int y) const {
    return &rgba[(std::size_t(y) * std::size_t(width) + x) * 4];
  }
};

// rgb times alpha per texel (one float rounding each), alpha kept: the form
// textures whose alpha is read are filtered in (texture/texture.h). Rows in
// parallel on `executor` when given.
Image premultiplied(const Image& straight, const Executor* executor = nullptr);
// Whether every texel's alpha is 1, so premultiplying would change nothing.
bool isOpaque(const Image& image);

// The sRGB transfer function (IEC 61966-2-1), exact in float.
float srgbToLinear(float encoded);
float linearToSrgb(float linear);
// Decode of an 8-bit sRGB code through a 256-entry table built once. The
// sampling kernels index the table itself (srgb8ToLinearTable()[code]), so
// texels stored as sRGB codes decode to the same bits on every path.
float srgb8ToLinear(std::uint8_t code);
const float* srgb8ToLinearTable();

}  // namespace quadra
