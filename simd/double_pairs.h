// Two doubles a register in the SSE2 baseline, for the per-sample plane
// arithmetic that must round the same in every ISA's files and the tests.
// Written out rather than left to the vectorizer: GCC 12 vectorized a loop's
// float narrowing followed by a widening (double -> float -> double) into
// nothing, dropping the rounding between them (tile/tile_kernel.h's
// SampleDepths, half its results one ulp off).
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
  // Each rounded to float, in the low two floats (the high two zero).
  QUADRA_DOUBLE_PAIR_INLINE __m128 asFloats() const { return _mm_cvtpd_ps(v); }
};

QUADRA_DOUBLE_PAIR_INLINE DoublePair operator+(DoublePair a, DoublePair b) {
  return DoublePair(_mm_add_pd(a.v, b.v));
}
QUADRA_DOUBLE_PAIR_INLINE DoublePair operator*(DoublePair a, DoublePair b) {
  return DoublePair(_mm_mul_pd(a.v, b.v));
}

}  // namespace quadra::simd
