// Image: a linear-float RGBA raster, the one pixel container quadra moves
// between loading, the texture stage and output. Row 0 is the top row, which
// is where glTF's v = 0 lies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace quadra {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // width * height * 4, row-major, linear (not sRGB)

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(std::size_t(w) * std::size_t(h) * 4, 0.0f) {}

  float* texel(int x, int y) { return &rgba[(std::size_t(y) * std::size_t(width) + x) * 4]; }
  const float* texel(int x, int y) const {
    return &rgba[(std::size_t(y) * std::size_t(width) + x) * 4];
  }
};

// The sRGB transfer function (IEC 61966-2-1), exact in float.
float srgbToLinear(float encoded);
float linearToSrgb(float linear);
// Decode of an 8-bit sRGB code through a 256-entry table built once.
float srgb8ToLinear(std::uint8_t code);

}  // namespace quadra
