// Resolve's transpose of planar channels into RGBA pixels, in the SSE2
// baseline, with streaming stores: the frame is not read again, so skipping
// the read-for-ownership halves its memory traffic. (The sampler's texel
// transposes are in simd/texel_pairs.h.)
#pragma once

#include <emmintrin.h>

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

// A whole 2x2 quad's planar channels (4 floats each, 16-byte aligned) → its
// two pixels in each of two frame rows (each 16-byte aligned).
QUADRA_TRANSPOSE_INLINE void transposeQuadToRowsStreaming(const float* r, const float* g,
                                                          const float* b, const float* a,
                                                          float* row0, float* row1) {
  __m128 p00 = _mm_load_ps(r), p10 = _mm_load_ps(g), p01 = _mm_load_ps(b), p11 = _mm_load_ps(a);
  _MM_TRANSPOSE4_PS(p00, p10, p01, p11);
  _mm_stream_ps(row0, p00);
  _mm_stream_ps(row0 + 4, p10);
  _mm_stream_ps(row1, p01);
  _mm_stream_ps(row1 + 4, p11);
}

// Orders streaming stores before whatever the thread does next.
QUADRA_TRANSPOSE_INLINE void streamFence() {
  _mm_sfence();
}

}  // namespace quadra::simd
