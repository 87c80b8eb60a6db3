// How a texture's texels are stored for sampling. Every format decodes to
// linear float RGBA before filtering; the narrower ones trade precision for
// memory and bandwidth:
//   rgba32f    16 bytes, exact
//   rgba16f     8 bytes, IEEE half: relative error <= 2^-11 (|x| < 65504)
//   rgba8       4 bytes, UNORM: absolute error <= 1/510, for data in [0, 1]
//   rgba8srgb   4 bytes, R, G, B as 8-bit sRGB codes (nearest on the sRGB
//               scale), A as UNORM8: exact for the texels of an 8-bit sRGB
//               image (it stores that image's own codes); other colours in
//               [0, 1] within half a code step, 1.5e-4 near 0 to 0.0045
//               near 1 in linear units
// sRGB sources are decoded to linear when loaded, and mip levels are built
// from the decoded image in linear float, then stored in the texture's format.
//
// `auto` stores 8-bit sRGB colour images as rgba16f, not rgba8srgb: decoding
// sRGB codes is a 256-entry table lookup per colour channel, and without fast
// gathers the kernels pay more for it than the half bandwidth saves, even from
// DRAM (AVX-512, one thread, ns per trilinear lookup, L1 / DRAM texture:
// rgba16f 8.8 / 12.9, rgba8srgb 14.3 / 18.8; frames of builtin:alpha-quads
// 32.5 against 49.6 ms, docs/texel-storage.md). rgba16f keeps an 8-bit
// source's steps too (its coarsest half step, 2^-11 near 1, is 18x finer than
// the source's 0.0089 there); rgba8srgb is the choice when memory counts:
// half of rgba16f, and lossless for 8-bit sources.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace quadra {

enum class TexelFormat : std::uint8_t { Rgba32F, Rgba16F, Rgba8Unorm, Rgba8Srgb };

constexpr int bytesPerTexel(TexelFormat format) {
  return format == TexelFormat::Rgba32F ? 16 : format == TexelFormat::Rgba16F ? 8 : 4;
}
const char* formatName(TexelFormat format);
// Parses rgba32f|rgba16f|rgba8|rgba8srgb; false when unknown.
bool parseFormat(const std::string& name, TexelFormat& out);

// One texel in and out of storage. Encoding rounds to nearest (ties to even
// for halves) and maps NaN to 0, so stored texels are always numbers;
// decoding is what every kernel path computes, bit for bit.
void encodeTexel(TexelFormat format, const float rgba[4], std::uint8_t* out);
// `count` texels of linear RGBA float, one format branch for the whole run.
void encodeTexels(TexelFormat format, const float* rgba, std::size_t count, std::uint8_t* out);
void decodeTexel(TexelFormat format, const std::uint8_t* in, float rgba[4]);

// The UNORM8 decode factor: code * kUnorm8Scale (the kernels multiply by
// the same float, so every path rounds alike).
constexpr float kUnorm8Scale = 1.0f / 255.0f;

// IEEE half <-> float. halfToFloat is exact; floatToHalf rounds to nearest
// even, overflows to infinity, and flushes nothing (halves keep denormals).
float halfToFloat(std::uint16_t half);
std::uint16_t floatToHalf(float value);

}  // namespace quadra
