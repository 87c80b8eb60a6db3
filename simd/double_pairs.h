// Two doubles a register in the SSE2 baseline, for the per-sample plane
// arithmetic of baseline files that must round exactly as the scalar code
// does. Written out rather than left to the vectorizer: GCC 12 vectorized a
// loop's float narrowing followed by a widening (double -> float -> double)
// into nothing, dropping the rounding between them (tile_kernel.cpp's
// sampleDepthsInTile, half its results one ulp off).
#pragma once

#include <emmintrin.h>

// Always inlined, as simd/transpose.h says why.
#define QUADRA_DOUBLE_PAIR_INLINE inline __attribute__((always_inline))

namespace quadra::simd {

struct DoublePair {
  __m128d v;

  QUADRA_DOUBLE_PAIR_INLINE explicit DoublePair(double both) : v(_mm_set1_pd(both)) {}
  QUADRA_DOUBLE_PAIR_INLINE explicit DoublePair(__m128d value) : v(value) {}
  // Two doubles, from unaligned memory.
  QUADRA_DOUBLE_PAIR_INLINE static DoublePair load(const double* two) {
    return DoublePair(_mm_loadu_pd(two));
  }
  // Each rounded to float and back: exactly double(float(x)).
  QUADRA_DOUBLE_PAIR_INLINE DoublePair roundedToFloat() const {
    return DoublePair(_mm_cvtps_pd(_mm_cvtpd_ps(v)));
  }
  // Each rounded to float, into two floats of unaligned memory.
  QUADRA_DOUBLE_PAIR_INLINE void storeAsFloats(float* two) const {
    _mm_storel_pi(reinterpret_cast<__m64*>(two), _mm_cvtpd_ps(v));
  }
};

QUADRA_DOUBLE_PAIR_INLINE DoublePair operator+(DoublePair a, DoublePair b) {
  return DoublePair(_mm_add_pd(a.v, b.v));
}
QUADRA_DOUBLE_PAIR_INLINE DoublePair operator*(DoublePair a, DoublePair b) {
  return DoublePair(_mm_mul_pd(a.v, b.v));
}

}  // namespace quadra::simd
