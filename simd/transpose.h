// 4x4 float transpose for the baseline (SSE2) build: turns four planar
// channel vectors into four interleaved RGBA pixels, written with streaming
// stores (the frame is not read again, so skipping the read-for-ownership
// halves resolve's memory traffic). Used by resolve, not an ISA kernel.
#pragma once

#include <emmintrin.h>

namespace quadra::simd {

// in[c] points to 4 floats of channel c (16-byte aligned); out[p] (16-byte
// aligned) receives pixel p's 4 channels; null out[p] are skipped.
inline void transposeToPixelsStreaming(const float* const in[4], float* const out[4]) {
  __m128 r = _mm_load_ps(in[0]), g = _mm_load_ps(in[1]), b = _mm_load_ps(in[2]),
         a = _mm_load_ps(in[3]);
  _MM_TRANSPOSE4_PS(r, g, b, a);
  if (out[0]) _mm_stream_ps(out[0], r);
  if (out[1]) _mm_stream_ps(out[1], g);
  if (out[2]) _mm_stream_ps(out[2], b);
  if (out[3]) _mm_stream_ps(out[3], a);
}

// Orders streaming stores before whatever the thread does next.
inline void streamFence() {
  _mm_sfence();
}

}  // namespace quadra::simd
