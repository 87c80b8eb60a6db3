// The 8-bit sRGB code of a linear value, and its pow-free encoder.
#include "io/srgb8.h"

#include <algorithm>
#include <bit>

#include "texture/image.h"

namespace quadra {

std::uint8_t srgb8Code(float linear) {
  return roundToUnorm8(linearToSrgb(linear));
}

Srgb8Encoder::Srgb8Encoder() {
  // Each step is a bisection over the float bit patterns between 0 (code 0)
  // and 1 (code 255); positive floats order as their bits do.
  steps_[0] = 0.0f;
  for (int code = 1; code < 256; ++code) {
    std::uint32_t below = std::bit_cast<std::uint32_t>(0.0f);
    std::uint32_t at = std::bit_cast<std::uint32_t>(1.0f);  // srgb8Code(below) < code <= ...(at)
    while (at - below > 1) {
      const std::uint32_t middle = below + (at - below) / 2;
      (srgb8Code(std::bit_cast<float>(middle)) >= code ? at : below) = middle;
    }
    steps_[code] = std::bit_cast<float>(at);
  }
}

void encodeSrgb8Row(const float* rgba, int width, std::uint8_t* out) {
  static const Srgb8Encoder srgb8;
  for (int x = 0; x < width; ++x, rgba += 4, out += 4) {
    const float alpha = rgba[3];
    for (int c = 0; c < 3; ++c) {
      const float straight = alpha > 0.0f ? rgba[c] / alpha : rgba[c];
      out[c] = srgb8(straight);
    }
    const float clamped = alpha > 0.0f ? std::min(alpha, 1.0f) : 0.0f;  // NaN -> 0
    out[3] = roundToUnorm8(clamped);
  }
}

}  // namespace quadra
