// Image storage, premultiplication, the sRGB transfer function (IEC
// 61966-2-1) in both directions, and the 8-bit decode table that PNG and glTF
// sRGB textures go through.
#include "texture/image.h"

#include <array>
#include <cmath>

#include "core/large_buffer.h"
#include "core/parallel.h"

namespace quadra {

Image::Image(int w, int h, const Executor* executor) : width(w), height(h) {
  resizeLarge(rgba, std::size_t(w) * std::size_t(h) * 4, 0.0f, executor);
}

Image premultiplied(const Image& straight, const Executor* executor) {
  Image out(straight.width, straight.height, executor);
  const std::size_t rowFloats = std::size_t(straight.width) * 4;
  const auto rows = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin * rowFloats; i < end * rowFloats; i += 4) {
      const float alpha = straight.rgba[i + 3];
      for (int c = 0; c < 3; ++c) out.rgba[i + c] = straight.rgba[i + c] * alpha;
      out.rgba[i + 3] = alpha;
    }
  };
  if (executor == nullptr) {
    rows(0, std::size_t(straight.height));
  } else {
    executor->parallelFor(std::size_t(straight.height), 64, rows);
  }
  return out;
}

bool isOpaque(const Image& image) {
  for (std::size_t i = 3; i < image.rgba.size(); i += 4)
    if (image.rgba[i] != 1.0f) return false;
  return true;
}

namespace {

// The standard's breakpoints: below them the curve is the linear toe segment.
constexpr float kEncodedToe = 0.04045f;
constexpr float kLinearToe = 0.0031308f;

}  // namespace

float srgbToLinear(float encoded) {
  if (std::isnan(encoded)) return 0.0f;
  if (encoded <= kEncodedToe) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float linear) {
  // NaN fails both comparisons, so it must be caught before clamping.
  if (!(linear > 0.0f)) return 0.0f;
  if (linear >= 1.0f) return 1.0f;
  if (linear <= kLinearToe) return 12.92f * linear;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

const float* srgb8ToLinearTable() {
  // Built in double so every entry is the correctly rounded float of the
  // exact curve, not the float curve's own rounding error.
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double e = i / 255.0;
      const double l = e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
      t[std::size_t(i)] = float(l);
    }
    return t;
  }();
  return table.data();
}

float srgb8ToLinear(std::uint8_t code) {
  return srgb8ToLinearTable()[code];
}

}  // namespace quadra
