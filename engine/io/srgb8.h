// The 8-bit sRGB codes image output writes: a linear value's code, the
// definition (srgb8Code) and a fast encoder that returns the same code for
// every float (Srgb8Encoder), so writing a frame costs no pow per channel.
#pragma once

#include <cstdint>

namespace quadra {

// Nearest 8-bit code of a value in [0, 1], ties up.
inline std::uint8_t roundToUnorm8(float unit) {
  return std::uint8_t(unit * 255.0f + 0.5f);
}

// The definition: roundToUnorm8(linearToSrgb(linear)); NaN and values at or
// below 0 are 0, values at or above 1 are 255.
std::uint8_t srgb8Code(float linear);

// srgb8Code without the pow: the 255 values where the code steps up, found
// once by bisection over the floats through srgb8Code itself, and a binary
// search among them per value (8 compares). The code is monotone in the
// value, so both agree on every float (tests/test_image_io.cpp checks every
// step's neighbours and a sweep of the range).
class Srgb8Encoder {
 public:
  Srgb8Encoder();
  std::uint8_t operator()(float linear) const {
    if (!(linear > 0.0f)) return 0;  // NaN too
    int code = 0;
    for (int step = 128; step > 0; step >>= 1)
      if (linear >= steps_[code + step]) code += step;
    return std::uint8_t(code);
  }
  // The smallest float whose code is `code` (1..255).
  float step(int code) const { return steps_[code]; }

 private:
  float steps_[256];
};

// Premultiplied linear RGBA floats -> straight (alpha divided out) 8-bit
// sRGB r, g, b and UNORM8 a, `width` pixels: what PNG output and the public
// API's Rgba8Srgb targets hold.
void encodeSrgb8Row(const float* rgba, int width, std::uint8_t* out);

}  // namespace quadra
