// 4x4 float transposes between interleaved RGBA and planar channels, in the
// SSE2 baseline every x86-64 has: resolve's planes → pixels (with streaming
// stores: the frame is not read again, so skipping the read-for-ownership
// halves its memory traffic) and the sampler's texels → channel lanes.
#pragma once

#include <emmintrin.h>
#if defined(__AVX__)
#include <immintrin.h>
#endif

// Always inlined: these are compiled into baseline files and into every
// per-ISA kernel file. An out-of-line copy would be a weak symbol shared
// between them (GCC leaves one at -O1, e.g. in the sanitizer builds), and the
// linker could hand the AVX-encoded copy to an SSE2-only caller.
#define QUADRA_TRANSPOSE_INLINE inline __attribute__((always_inline))

namespace quadra::simd {

// in[c] points to 4 floats of channel c (16-byte aligned); out[p] (16-byte
// aligned) receives pixel p's 4 channels; null out[p] are skipped.
QUADRA_TRANSPOSE_INLINE void transposeToPixelsStreaming(const float* const in[4],
                                                        float* const out[4]) {
  __m128 r = _mm_load_ps(in[0]), g = _mm_load_ps(in[1]), b = _mm_load_ps(in[2]),
         a = _mm_load_ps(in[3]);
  _MM_TRANSPOSE4_PS(r, g, b, a);
  if (out[0]) _mm_stream_ps(out[0], r);
  if (out[1]) _mm_stream_ps(out[1], g);
  if (out[2]) _mm_stream_ps(out[2], b);
  if (out[3]) _mm_stream_ps(out[3], a);
}

// Four RGBA texels (unaligned) → four channel runs of 4 floats each (aligned):
// out[c][k] = channel c of texel k.
QUADRA_TRANSPOSE_INLINE void transposeToChannels(const float* const texel[4], float* const out[4]) {
  __m128 t0 = _mm_loadu_ps(texel[0]), t1 = _mm_loadu_ps(texel[1]), t2 = _mm_loadu_ps(texel[2]),
         t3 = _mm_loadu_ps(texel[3]);
  _MM_TRANSPOSE4_PS(t0, t1, t2, t3);
  _mm_store_ps(out[0], t0);
  _mm_store_ps(out[1], t1);
  _mm_store_ps(out[2], t2);
  _mm_store_ps(out[3], t3);
}

#if defined(__AVX__)
// Two texels per lane for four lanes in one 8-wide transpose: left[k] and
// right[k] are lane k's texels; out[c] receives channel c of the left texels
// (4 floats) and out[4 + c] of the right ones. One shuffle per texel where two
// 4-wide transposes take two. Only in files built with AVX (the per-ISA kernels).
QUADRA_TRANSPOSE_INLINE void transposeTexelPairs(const float* const left[4],
                                                 const float* const right[4], __m256 channel[4]) {
  __m256 t0 = _mm256_loadu2_m128(right[0], left[0]), t1 = _mm256_loadu2_m128(right[1], left[1]),
         t2 = _mm256_loadu2_m128(right[2], left[2]), t3 = _mm256_loadu2_m128(right[3], left[3]);
  const __m256 lo01 = _mm256_unpacklo_ps(t0, t1), hi01 = _mm256_unpackhi_ps(t0, t1);
  const __m256 lo23 = _mm256_unpacklo_ps(t2, t3), hi23 = _mm256_unpackhi_ps(t2, t3);
  channel[0] = _mm256_shuffle_ps(lo01, lo23, _MM_SHUFFLE(1, 0, 1, 0));
  channel[1] = _mm256_shuffle_ps(lo01, lo23, _MM_SHUFFLE(3, 2, 3, 2));
  channel[2] = _mm256_shuffle_ps(hi01, hi23, _MM_SHUFFLE(1, 0, 1, 0));
  channel[3] = _mm256_shuffle_ps(hi01, hi23, _MM_SHUFFLE(3, 2, 3, 2));
}

// As above, stored: out[c] receives channel c of the left texels, out[4 + c]
// of the right ones (4 floats each).
QUADRA_TRANSPOSE_INLINE void transposeTexelPairs(const float* const left[4],
                                                 const float* const right[4], float* const out[8]) {
  __m256 t0 = _mm256_loadu2_m128(right[0], left[0]), t1 = _mm256_loadu2_m128(right[1], left[1]),
         t2 = _mm256_loadu2_m128(right[2], left[2]), t3 = _mm256_loadu2_m128(right[3], left[3]);
  const __m256 lo01 = _mm256_unpacklo_ps(t0, t1), hi01 = _mm256_unpackhi_ps(t0, t1);
  const __m256 lo23 = _mm256_unpacklo_ps(t2, t3), hi23 = _mm256_unpackhi_ps(t2, t3);
  const __m256 r = _mm256_shuffle_ps(lo01, lo23, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 g = _mm256_shuffle_ps(lo01, lo23, _MM_SHUFFLE(3, 2, 3, 2));
  const __m256 b = _mm256_shuffle_ps(hi01, hi23, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 a = _mm256_shuffle_ps(hi01, hi23, _MM_SHUFFLE(3, 2, 3, 2));
  _mm256_storeu2_m128(out[4], out[0], r);
  _mm256_storeu2_m128(out[5], out[1], g);
  _mm256_storeu2_m128(out[6], out[2], b);
  _mm256_storeu2_m128(out[7], out[3], a);
}
#endif

#if defined(__AVX512F__)
// Sixteen lanes of left and right texel channels straight from four pair
// transposes (lanes 4g..4g+3 in pair[g]), kept in registers: assembling them
// through 128-bit stores and a 512-bit load defeats store forwarding.
QUADRA_TRANSPOSE_INLINE void assemblePairs16(const __m256 pair[4][4], __m512 left[4],
                                             __m512 right[4]) {
  for (int c = 0; c < 4; ++c) {
    const __m512 ab = _mm512_insertf32x8(_mm512_castps256_ps512(pair[0][c]), pair[1][c], 1);
    const __m512 cd = _mm512_insertf32x8(_mm512_castps256_ps512(pair[2][c]), pair[3][c], 1);
    left[c] = _mm512_shuffle_f32x4(ab, cd, _MM_SHUFFLE(2, 0, 2, 0));
    right[c] = _mm512_shuffle_f32x4(ab, cd, _MM_SHUFFLE(3, 1, 3, 1));
  }
}
#endif

// Orders streaming stores before whatever the thread does next.
QUADRA_TRANSPOSE_INLINE void streamFence() {
  _mm_sfence();
}

}  // namespace quadra::simd
