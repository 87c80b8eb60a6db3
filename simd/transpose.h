// Transposes between interleaved RGBA and planar channels: resolve's planes →
// pixels (SSE2, with streaming stores: the frame is not read again, so skipping
// the read-for-ownership halves its memory traffic) and the sampler's texel
// pairs → channel lanes (one helper per register width; the wider ones only
// in files built with AVX / AVX-512, i.e. the per-ISA kernels).
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

// Texel pairs → channel lanes, for bilinear rows: pair[k] points to lane k's
// left and right RGBA texels, 8 contiguous floats (texture/padded_level.h);
// left[c] and right[c] receive channel c of every lane's left and right texel.
// One helper per register width; each loads a pair whole where the register
// allows and transposes in registers.
QUADRA_TRANSPOSE_INLINE void transposeTexelPairs(const float* const pair[4], __m128 left[4],
                                                 __m128 right[4]) {
  __m128 l0 = _mm_loadu_ps(pair[0]), l1 = _mm_loadu_ps(pair[1]), l2 = _mm_loadu_ps(pair[2]),
         l3 = _mm_loadu_ps(pair[3]);
  __m128 r0 = _mm_loadu_ps(pair[0] + 4), r1 = _mm_loadu_ps(pair[1] + 4),
         r2 = _mm_loadu_ps(pair[2] + 4), r3 = _mm_loadu_ps(pair[3] + 4);
  _MM_TRANSPOSE4_PS(l0, l1, l2, l3);
  _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
  left[0] = l0, left[1] = l1, left[2] = l2, left[3] = l3;
  right[0] = r0, right[1] = r1, right[2] = r2, right[3] = r3;
}

#if defined(__AVX__)
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

// Eight lanes: a register per lane holds its pair (left texel in the low
// block); the block transpose of lanes 0-3 and of 4-7 leaves left channels in
// the low blocks and right ones in the high blocks, which one permute splits.
QUADRA_TRANSPOSE_INLINE void transposeTexelPairs(const float* const pair[8], __m256 left[4],
                                                 __m256 right[4]) {
  __m256 in[2][4], out[2][4];
  for (int k = 0; k < 8; ++k) in[k / 4][k % 4] = _mm256_loadu_ps(pair[k]);
  transposeBlocks(in[0], out[0]);
  transposeBlocks(in[1], out[1]);
  for (int c = 0; c < 4; ++c) {
    left[c] = _mm256_permute2f128_ps(out[0][c], out[1][c], 0x20);
    right[c] = _mm256_permute2f128_ps(out[0][c], out[1][c], 0x31);
  }
}
#endif

#if defined(__AVX512F__)
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
QUADRA_TRANSPOSE_INLINE void transposeTexelPairs(const float* const pair[16], __m512 left[4],
                                                 __m512 right[4]) {
  __m512 in[2][4], out[2][4];
  for (int g = 0; g < 2; ++g)
    for (int j = 0; j < 4; ++j)
      in[g][j] = _mm512_insertf32x8(_mm512_castps256_ps512(_mm256_loadu_ps(pair[8 * g + j])),
                                    _mm256_loadu_ps(pair[8 * g + j + 4]), 1);
  transposeBlocks(in[0], out[0]);
  transposeBlocks(in[1], out[1]);
  for (int c = 0; c < 4; ++c) {
    left[c] = _mm512_shuffle_f32x4(out[0][c], out[1][c], _MM_SHUFFLE(2, 0, 2, 0));
    right[c] = _mm512_shuffle_f32x4(out[0][c], out[1][c], _MM_SHUFFLE(3, 1, 3, 1));
  }
}
#endif

// Orders streaming stores before whatever the thread does next.
QUADRA_TRANSPOSE_INLINE void streamFence() {
  _mm_sfence();
}

}  // namespace quadra::simd
