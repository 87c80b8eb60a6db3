// Texel pairs → channel lanes, for the sampler's bilinear rows. pair[k]
// points to lane k's left and right RGBA texels, contiguous in a padded level
// (texture/padded_level.h); left[c] and right[c] receive channel c of every
// lane's left and right texel, decoded to float. One helper per register
// width, templated on the storage encoding: each loads a pair whole, decodes
// it in registers (F16C and byte widening where the ISA has them) and
// transposes (or, for float pairs, gathers: the benchmarked alternative).
// The decodes are exact or round exactly as the scalar decode in
// texture/texel_format.cpp, so every path returns the same bits. Codes8 is
// the one encoding left undecoded: 8-bit codes as int32s in the registers'
// bits, for a decode after the transpose (sRGB8's table, lookupCodes).
//
// Include only from per-ISA kernel translation units; the 256- and 512-bit
// helpers exist only in files built with AVX2 / AVX-512 flags.
#pragma once

#include <cstdint>

#include <emmintrin.h>
#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "simd/transpose.h"

namespace quadra::simd {

// How a pair is stored: 2 x RGBA float (32 bytes), half (16), UNORM8 (8), or
// 8-bit codes (8) to be decoded after the transpose.
enum class PairEncoding { Float32, Half, Unorm8, Codes8 };

// UNORM8 codes decode as code * this (texture/texel_format.h kUnorm8Scale,
// the same float, so every path rounds alike).
constexpr float kUnorm8Scale = 1.0f / 255.0f;

// The gather alternative for float pairs: per-lane texel offsets from `base`,
// one hardware gather per channel and side. Defined for 256- and 512-bit
// registers only (SSE2 has no gathers); the sampler uses it from AVX2 on.
template <class Floats, class Ints>
void gatherTexelPairs(const float* base, Ints offset, Floats left[4], Floats right[4]);

// Exactly texel_format.cpp's halfToFloat, four lanes at a time: the
// magnitude's bits moved into float position are the value times 2^-112, one
// exact multiply rescales, infinity/NaN get the full exponent back.
QUADRA_TRANSPOSE_INLINE __m128 halfToFloat4(__m128i half32) {
  const __m128i magnitude = _mm_slli_epi32(_mm_and_si128(half32, _mm_set1_epi32(0x7FFF)), 13);
  __m128 value =
      _mm_mul_ps(_mm_castsi128_ps(magnitude), _mm_castsi128_ps(_mm_set1_epi32(239 << 23)));
  const __m128 infOrNan = _mm_cmpge_ps(value, _mm_set1_ps(65536.0f));
  value = _mm_or_ps(value, _mm_and_ps(infOrNan, _mm_castsi128_ps(_mm_set1_epi32(0x7F800000))));
  const __m128i sign = _mm_slli_epi32(_mm_and_si128(half32, _mm_set1_epi32(0x8000)), 16);
  return _mm_or_ps(value, _mm_castsi128_ps(sign));
}

// One lane's pair as its left and right texel, four channels each.
template <PairEncoding kEncoding>
QUADRA_TRANSPOSE_INLINE void loadPair(const std::uint8_t* pair, __m128& left, __m128& right) {
  const __m128i zero = _mm_setzero_si128();
  if constexpr (kEncoding == PairEncoding::Float32) {
    left = _mm_loadu_ps(reinterpret_cast<const float*>(pair));
    right = _mm_loadu_ps(reinterpret_cast<const float*>(pair) + 4);
  } else if constexpr (kEncoding == PairEncoding::Half) {
    const __m128i halves = _mm_loadu_si128(reinterpret_cast<const __m128i*>(pair));
    left = halfToFloat4(_mm_unpacklo_epi16(halves, zero));
    right = halfToFloat4(_mm_unpackhi_epi16(halves, zero));
  } else {
    const __m128i words =
        _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(pair)), zero);
    const __m128i l = _mm_unpacklo_epi16(words, zero), r = _mm_unpackhi_epi16(words, zero);
    if constexpr (kEncoding == PairEncoding::Codes8) {
      left = _mm_castsi128_ps(l);
      right = _mm_castsi128_ps(r);
    } else {
      const __m128 scale = _mm_set1_ps(kUnorm8Scale);
      left = _mm_mul_ps(_mm_cvtepi32_ps(l), scale);
      right = _mm_mul_ps(_mm_cvtepi32_ps(r), scale);
    }
  }
}

template <PairEncoding kEncoding>
QUADRA_TRANSPOSE_INLINE void transposeTexelPairs(const std::uint8_t* const pair[4], __m128 left[4],
                                                 __m128 right[4]) {
  __m128 l[4], r[4];
  for (int k = 0; k < 4; ++k) loadPair<kEncoding>(pair[k], l[k], r[k]);
  _MM_TRANSPOSE4_PS(l[0], l[1], l[2], l[3]);
  _MM_TRANSPOSE4_PS(r[0], r[1], r[2], r[3]);
  for (int c = 0; c < 4; ++c) left[c] = l[c], right[c] = r[c];
}

// table[code] per lane, the codes as int32 in the register's bits (a Codes8
// transpose's output) and in [0, 255]. Without gathers the lanes are looked
// up one by one.
QUADRA_TRANSPOSE_INLINE __m128 lookupCodes(const float* table, __m128 codes) {
  alignas(16) std::int32_t code[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(code), _mm_castps_si128(codes));
  return _mm_setr_ps(table[code[0]], table[code[1]], table[code[2]], table[code[3]]);
}

#if defined(__AVX2__)
// One lane's pair in a 256-bit register: left texel low, right texel high.
template <PairEncoding kEncoding>
QUADRA_TRANSPOSE_INLINE __m256 loadPair256(const std::uint8_t* pair) {
  if constexpr (kEncoding == PairEncoding::Float32) {
    return _mm256_loadu_ps(reinterpret_cast<const float*>(pair));
  } else if constexpr (kEncoding == PairEncoding::Half) {
    return _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(pair)));
  } else {
    const __m256i codes =
        _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(pair)));
    if constexpr (kEncoding == PairEncoding::Codes8) return _mm256_castsi256_ps(codes);
    return _mm256_mul_ps(_mm256_cvtepi32_ps(codes), _mm256_set1_ps(kUnorm8Scale));
  }
}

// The 4x4 transpose inside each 128-bit block of four registers: block b of
// out[c] holds channel c of block b of in[0..3] (unpack and shuffle never
// cross blocks).
QUADRA_TRANSPOSE_INLINE void transposeBlocks(const __m256 in[4], __m256 out[4]) {
  const __m256 lo01 = _mm256_unpacklo_ps(in[0], in[1]), hi01 = _mm256_unpackhi_ps(in[0], in[1]);
  const __m256 lo23 = _mm256_unpacklo_ps(in[2], in[3]), hi23 = _mm256_unpackhi_ps(in[2], in[3]);
  out[0] = _mm256_shuffle_ps(lo01, lo23, _MM_SHUFFLE(1, 0, 1, 0));
  out[1] = _mm256_shuffle_ps(lo01, lo23, _MM_SHUFFLE(3, 2, 3, 2));
  out[2] = _mm256_shuffle_ps(hi01, hi23, _MM_SHUFFLE(1, 0, 1, 0));
  out[3] = _mm256_shuffle_ps(hi01, hi23, _MM_SHUFFLE(3, 2, 3, 2));
}

// Eight lanes: a register per lane holds its pair; the block transposes of
// lanes 0-3 and 4-7 leave left channels in the low blocks and right ones in
// the high blocks, which one permute splits.
template <PairEncoding kEncoding>
QUADRA_TRANSPOSE_INLINE void transposeTexelPairs(const std::uint8_t* const pair[8], __m256 left[4],
                                                 __m256 right[4]) {
  __m256 in[2][4], out[2][4];
  for (int k = 0; k < 8; ++k) in[k / 4][k % 4] = loadPair256<kEncoding>(pair[k]);
  transposeBlocks(in[0], out[0]);
  transposeBlocks(in[1], out[1]);
  for (int c = 0; c < 4; ++c) {
    left[c] = _mm256_permute2f128_ps(out[0][c], out[1][c], 0x20);
    right[c] = _mm256_permute2f128_ps(out[0][c], out[1][c], 0x31);
  }
}

// Lane by lane as in SSE2: the AVX2 gather of the same lanes measured no
// faster on the AMD EPYC (Zen 5) VM when this was chosen (commit 03e5d0f),
// and gathers are microcode-mitigated on many Intel parts.
QUADRA_TRANSPOSE_INLINE __m256 lookupCodes(const float* table, __m256 codes) {
  alignas(32) std::int32_t code[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(code), _mm256_castps_si256(codes));
  return _mm256_setr_ps(table[code[0]], table[code[1]], table[code[2]], table[code[3]],
                        table[code[4]], table[code[5]], table[code[6]], table[code[7]]);
}

template <>
QUADRA_TRANSPOSE_INLINE void gatherTexelPairs(const float* base, __m256i offset, __m256 left[4],
                                              __m256 right[4]) {
  const __m256i index = _mm256_slli_epi32(offset, 2);  // 4 floats per texel
  for (int c = 0; c < 4; ++c) {
    left[c] = _mm256_i32gather_ps(base + c, index, 4);
    right[c] = _mm256_i32gather_ps(base + 4 + c, index, 4);
  }
}
#endif

#if defined(__AVX512F__)
// The pairs of two lanes in one 512-bit register: a's in the low half.
template <PairEncoding kEncoding>
QUADRA_TRANSPOSE_INLINE __m512 loadPairs512(const std::uint8_t* a, const std::uint8_t* b) {
  if constexpr (kEncoding == PairEncoding::Float32) {
    return _mm512_insertf32x8(
        _mm512_castps256_ps512(_mm256_loadu_ps(reinterpret_cast<const float*>(a))),
        _mm256_loadu_ps(reinterpret_cast<const float*>(b)), 1);
  } else if constexpr (kEncoding == PairEncoding::Half) {
    return _mm512_cvtph_ps(_mm256_loadu2_m128i(reinterpret_cast<const __m128i*>(b),
                                               reinterpret_cast<const __m128i*>(a)));
  } else {
    const __m128i codes = _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(a)),
                                             _mm_loadl_epi64(reinterpret_cast<const __m128i*>(b)));
    if constexpr (kEncoding == PairEncoding::Codes8)
      return _mm512_castsi512_ps(_mm512_cvtepu8_epi32(codes));
    return _mm512_mul_ps(_mm512_cvtepi32_ps(_mm512_cvtepu8_epi32(codes)),
                         _mm512_set1_ps(kUnorm8Scale));
  }
}

QUADRA_TRANSPOSE_INLINE void transposeBlocks(const __m512 in[4], __m512 out[4]) {
  const __m512 lo01 = _mm512_unpacklo_ps(in[0], in[1]), hi01 = _mm512_unpackhi_ps(in[0], in[1]);
  const __m512 lo23 = _mm512_unpacklo_ps(in[2], in[3]), hi23 = _mm512_unpackhi_ps(in[2], in[3]);
  out[0] = _mm512_shuffle_ps(lo01, lo23, _MM_SHUFFLE(1, 0, 1, 0));
  out[1] = _mm512_shuffle_ps(lo01, lo23, _MM_SHUFFLE(3, 2, 3, 2));
  out[2] = _mm512_shuffle_ps(hi01, hi23, _MM_SHUFFLE(1, 0, 1, 0));
  out[3] = _mm512_shuffle_ps(hi01, hi23, _MM_SHUFFLE(3, 2, 3, 2));
}

// Sixteen lanes: register j of group g holds the pairs of lanes 8g + j and
// 8g + j + 4, so after the block transposes group g's blocks are the left,
// right, left, right channels of lanes 8g..8g+3 and 8g+4..8g+7; one 128-bit
// shuffle per channel and side puts the four runs in lane order.
template <PairEncoding kEncoding>
QUADRA_TRANSPOSE_INLINE void transposeTexelPairs(const std::uint8_t* const pair[16], __m512 left[4],
                                                 __m512 right[4]) {
  __m512 in[2][4], out[2][4];
  for (int g = 0; g < 2; ++g)
    for (int j = 0; j < 4; ++j)
      in[g][j] = loadPairs512<kEncoding>(pair[8 * g + j], pair[8 * g + j + 4]);
  transposeBlocks(in[0], out[0]);
  transposeBlocks(in[1], out[1]);
  for (int c = 0; c < 4; ++c) {
    left[c] = _mm512_shuffle_f32x4(out[0][c], out[1][c], _MM_SHUFFLE(2, 0, 2, 0));
    right[c] = _mm512_shuffle_f32x4(out[0][c], out[1][c], _MM_SHUFFLE(3, 1, 3, 1));
  }
}

// In registers, no gather: each two-register permute looks up 32 entries by
// the code's low 5 bits, and three blends on bits 5, 6, 7 pick among the
// eight results. Measured faster than the gather and than lane-by-lane
// lookups on the AMD EPYC (Zen 5) VM when this was chosen (commit 03e5d0f);
// today's cost per lookup is in docs/texel-storage.md.
QUADRA_TRANSPOSE_INLINE __m512 lookupCodes(const float* table, __m512 codes) {
  const __m512i index = _mm512_castps_si512(codes);
  __m512 part[8];
  for (int j = 0; j < 8; ++j)
    part[j] = _mm512_permutex2var_ps(_mm512_loadu_ps(table + 32 * j), index,
                                     _mm512_loadu_ps(table + 32 * j + 16));
  for (int bit = 5, n = 8; bit < 8; ++bit, n /= 2) {
    const __mmask16 high = _mm512_test_epi32_mask(index, _mm512_set1_epi32(1 << bit));
    for (int j = 0; j < n / 2; ++j)
      part[j] = _mm512_mask_blend_ps(high, part[2 * j], part[2 * j + 1]);
  }
  return part[0];
}

template <>
QUADRA_TRANSPOSE_INLINE void gatherTexelPairs(const float* base, __m512i offset, __m512 left[4],
                                              __m512 right[4]) {
  const __m512i index = _mm512_slli_epi32(offset, 2);
  for (int c = 0; c < 4; ++c) {
    left[c] = _mm512_i32gather_ps(index, base + c, 4);
    right[c] = _mm512_i32gather_ps(index, base + 4 + c, 4);
  }
}
#endif

}  // namespace quadra::simd
