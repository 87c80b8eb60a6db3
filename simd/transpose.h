// 4x4 float transposes between interleaved RGBA and planar channels, in the
// SSE2 baseline every x86-64 has: resolve's planes → pixels (with streaming
// stores: the frame is not read again, so skipping the read-for-ownership
// halves its memory traffic) and the sampler's texels → channel lanes.
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

// Four RGBA texels (unaligned) → four channel runs of 4 floats each (aligned):
// out[c][k] = channel c of texel k.
inline void transposeToChannels(const float* const texel[4], float* const out[4]) {
  __m128 t0 = _mm_loadu_ps(texel[0]), t1 = _mm_loadu_ps(texel[1]), t2 = _mm_loadu_ps(texel[2]),
         t3 = _mm_loadu_ps(texel[3]);
  _MM_TRANSPOSE4_PS(t0, t1, t2, t3);
  _mm_store_ps(out[0], t0);
  _mm_store_ps(out[1], t1);
  _mm_store_ps(out[2], t2);
  _mm_store_ps(out[3], t3);
}

// Orders streaming stores before whatever the thread does next.
inline void streamFence() {
  _mm_sfence();
}

}  // namespace quadra::simd
