// Texel formats: names, sizes and the scalar encode/decode that storage
// conversion and the scalar kernel path use (texel_format.h).
#include "texture/texel_format.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "texture/image.h"

namespace quadra {

namespace {

struct FormatSpelling {
  TexelFormat format;
  const char* name;
};

constexpr std::array<FormatSpelling, 4> kFormats = {{
    {TexelFormat::Rgba32F, "rgba32f"},
    {TexelFormat::Rgba16F, "rgba16f"},
    {TexelFormat::Rgba8Unorm, "rgba8"},
    {TexelFormat::Rgba8Srgb, "rgba8srgb"},
}};

const FormatSpelling& spelling(TexelFormat format) {
  for (const FormatSpelling& s : kFormats)
    if (s.format == format) return s;
  return kFormats[0];
}

std::uint32_t bitsOf(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

float floatOf(std::uint32_t bits) {
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// Nearest code of a value clamped to [0, 1]; the caller has replaced NaN.
std::uint8_t unorm8Code(float value) {
  return std::uint8_t(std::nearbyint(std::clamp(value, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

const char* formatName(TexelFormat format) {
  return spelling(format).name;
}

bool parseFormat(const std::string& name, TexelFormat& out) {
  for (const FormatSpelling& s : kFormats) {
    if (name == s.name) {
      out = s.format;
      return true;
    }
  }
  return false;
}

float halfToFloat(std::uint16_t half) {
  // The magnitude's bits shifted into a float's place are the value times
  // 2^-112 (denormal halves land on float denormals); one exact multiply
  // rescales. Infinity and NaN come out >= 2^16 and get the full exponent.
  const std::uint32_t magnitude = std::uint32_t(half & 0x7FFF) << 13;
  float value = floatOf(magnitude) * floatOf(std::uint32_t(254 - 15) << 23);
  if (value >= 65536.0f) value = floatOf(bitsOf(value) | 0x7F800000u);
  return floatOf(bitsOf(value) | (std::uint32_t(half & 0x8000) << 16));
}

namespace {

// Round to nearest even, in integers; inline so encodeTexels' loops carry
// no call per channel (texture preparation converts every texel of every
// level).
inline std::uint16_t halfOf(float value) {
  const std::uint32_t bits = bitsOf(value);
  const std::uint16_t sign = std::uint16_t((bits >> 16) & 0x8000);
  const float magnitude = std::fabs(value);
  if (std::isnan(value)) return 0x7E00;
  if (magnitude >= 65520.0f) return sign | 0x7C00;  // rounds to infinity
  if (magnitude < 6.103515625e-05f) {
    // Denormal half: a multiple of 2^-24; the scaling is exact and
    // nearbyint rounds to nearest even (the default rounding mode).
    return sign | std::uint16_t(std::nearbyint(magnitude * 16777216.0f));
  }
  // Normal: drop 13 mantissa bits with round-to-nearest-even.
  const std::uint32_t m = bitsOf(magnitude);
  const std::uint32_t rounded = m + 0x0FFFu + ((m >> 13) & 1u);
  return sign | std::uint16_t((rounded >> 13) - ((127u - 15u) << 10));
}

}  // namespace

std::uint16_t floatToHalf(float value) {
  return halfOf(value);
}

namespace {

// One texel in one format, NaN stored as 0; inlined into encodeTexels' loops.
template <TexelFormat kFormat>
inline void encodeOne(const float rgba[4], std::uint8_t* out) {
  float clean[4];
  for (int c = 0; c < 4; ++c) clean[c] = std::isnan(rgba[c]) ? 0.0f : rgba[c];
  if constexpr (kFormat == TexelFormat::Rgba32F) {
    std::memcpy(out, clean, 16);
  } else if constexpr (kFormat == TexelFormat::Rgba16F) {
    for (int c = 0; c < 4; ++c) {
      const std::uint16_t h = halfOf(clean[c]);
      std::memcpy(out + 2 * c, &h, 2);
    }
  } else if constexpr (kFormat == TexelFormat::Rgba8Unorm) {
    for (int c = 0; c < 4; ++c) out[c] = unorm8Code(clean[c]);
  } else {
    for (int c = 0; c < 3; ++c) out[c] = unorm8Code(linearToSrgb(clean[c]));
    out[3] = unorm8Code(clean[3]);
  }
}

// Halves for a run of floats (NaN stored as +0, as encodeOne does), written
// without branches so the compiler vectorizes it: the three cases of halfOf
// are all computed and the right one selected. Denormal halves come from one
// float addition whose rounding (to nearest even, the default mode) does the
// work: x + 0.5 puts the half denormal's units in the low mantissa bits.
void encodeHalves(const float* in, std::size_t count, std::uint8_t* out) {
  constexpr std::uint32_t kRoundsToInfinity = 0x477FF000;  // 65520
  constexpr std::uint32_t kSmallestNormal = 0x38800000;    // 2^-14
  constexpr std::uint32_t kInfinityBits = 0x7F800000;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t bits = bitsOf(in[i]);
    const std::uint32_t magnitude = bits & 0x7FFFFFFFu;
    const std::uint32_t sign = (bits >> 16) & 0x8000u;
    const std::uint32_t normal =
        (magnitude + 0x0FFFu + ((magnitude >> 13) & 1u) - ((127u - 15u) << 23)) >> 13;
    const std::uint32_t denormal = bitsOf(floatOf(magnitude) + 0.5f) - 0x3F000000u;
    std::uint32_t half = magnitude < kSmallestNormal ? denormal : normal;
    half = magnitude >= kRoundsToInfinity ? 0x7C00u : half;
    half |= sign;
    half = magnitude > kInfinityBits ? 0u : half;
    const std::uint16_t value = std::uint16_t(half);
    std::memcpy(out + 2 * i, &value, 2);
  }
}

template <TexelFormat kFormat>
void encodeRun(const float* rgba, std::size_t count, std::uint8_t* out) {
  if constexpr (kFormat == TexelFormat::Rgba16F) return encodeHalves(rgba, 4 * count, out);
  constexpr std::size_t kBytes = kFormat == TexelFormat::Rgba32F   ? 16
                                 : kFormat == TexelFormat::Rgba16F ? 8
                                                                   : 4;
  for (std::size_t i = 0; i < count; ++i) encodeOne<kFormat>(rgba + 4 * i, out + kBytes * i);
}

}  // namespace

void encodeTexels(TexelFormat format, const float* rgba, std::size_t count, std::uint8_t* out) {
  switch (format) {
    case TexelFormat::Rgba32F:
      return encodeRun<TexelFormat::Rgba32F>(rgba, count, out);
    case TexelFormat::Rgba16F:
      return encodeRun<TexelFormat::Rgba16F>(rgba, count, out);
    case TexelFormat::Rgba8Unorm:
      return encodeRun<TexelFormat::Rgba8Unorm>(rgba, count, out);
    case TexelFormat::Rgba8Srgb:
      return encodeRun<TexelFormat::Rgba8Srgb>(rgba, count, out);
  }
}

void encodeTexel(TexelFormat format, const float rgba[4], std::uint8_t* out) {
  encodeTexels(format, rgba, 1, out);
}

void decodeTexel(TexelFormat format, const std::uint8_t* in, float rgba[4]) {
  switch (format) {
    case TexelFormat::Rgba32F:
      std::memcpy(rgba, in, 16);
      return;
    case TexelFormat::Rgba16F:
      for (int c = 0; c < 4; ++c) {
        std::uint16_t h;
        std::memcpy(&h, in + 2 * c, 2);
        rgba[c] = halfToFloat(h);
      }
      return;
    case TexelFormat::Rgba8Unorm:
      for (int c = 0; c < 4; ++c) rgba[c] = float(in[c]) * kUnorm8Scale;
      return;
    case TexelFormat::Rgba8Srgb:
      for (int c = 0; c < 3; ++c) rgba[c] = srgb8ToLinear(in[c]);
      rgba[3] = float(in[3]) * kUnorm8Scale;
      return;
  }
}

}  // namespace quadra
