// Lane types for the kernels: a thin layer over xsimd plus a plain-C++ scalar
// path with the same interface, so each kernel is one source compiled per ISA.
//
// Lanes<Arch>::F (float lanes), ::I (int32 lanes), ::M (float lane mask);
// for the filters whose sums need double (the summed-area table), ::D (double
// lanes, kDoubleWidth of them: half of F's, four on the scalar path), ::DM
// (their mask) and ::I64 (int64 lanes beside them).
// Lanes are grouped in 2x2 pixel quads: lane 4q + 2*ly + lx is pixel (lx, ly) of
// quad q. SSE2 and scalar carry 1 quad, AVX2 2 quads, AVX-512 4 quads.
//
// Precision contract (SwiftShader style): every operation here is exactly
// rounded IEEE (add, sub, mul, div, sqrt, floor, min/max with SSE semantics
// "a < b ? a : b"), no approximate reciprocals, no fused multiply-add, so the
// scalar path and every SIMD path produce bit-identical results.
//
// Include only from per-ISA kernel translation units (see cmake/QuadraIsa.cmake).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include <xsimd/xsimd.hpp>

// For the small lane helpers the kernels call per lane group: GCC otherwise
// leaves some out of line, and passing lanes through memory to a call sits on
// the kernels' critical path.
#define QUADRA_LANE_INLINE inline __attribute__((always_inline))

namespace quadra::simd {

// ---------------------------------------------------------------- scalar path
// Four lanes in plain C++: the readable reference the SIMD paths are tested against.
struct ScalarArch {};

template <class T>
struct ScalarBatch;

struct ScalarMask {
  static constexpr int size = 4;
  bool v[4];
  friend ScalarMask operator&(const ScalarMask& a, const ScalarMask& b) {
    return {{a.v[0] && b.v[0], a.v[1] && b.v[1], a.v[2] && b.v[2], a.v[3] && b.v[3]}};
  }
  friend ScalarMask operator|(const ScalarMask& a, const ScalarMask& b) {
    return {{a.v[0] || b.v[0], a.v[1] || b.v[1], a.v[2] || b.v[2], a.v[3] || b.v[3]}};
  }
  friend ScalarMask operator~(const ScalarMask& a) {
    return {{!a.v[0], !a.v[1], !a.v[2], !a.v[3]}};
  }
};

template <class T>
struct ScalarBatch {
  static constexpr int size = 4;
  T v[4];
  ScalarBatch() = default;
  ScalarBatch(T x) : v{x, x, x, x} {}  // NOLINT: broadcast, like xsimd
  ScalarBatch(T a, T b, T c, T d) : v{a, b, c, d} {}

  static ScalarBatch load_aligned(const T* p) { return {p[0], p[1], p[2], p[3]}; }
  static ScalarBatch load_unaligned(const T* p) { return load_aligned(p); }
  void store_aligned(T* p) const { std::memcpy(p, v, sizeof(v)); }
  void store_unaligned(T* p) const { store_aligned(p); }
  T get(int i) const { return v[i]; }

  template <class Op>
  static ScalarBatch map(const ScalarBatch& a, const ScalarBatch& b, Op op) {
    return {op(a.v[0], b.v[0]), op(a.v[1], b.v[1]), op(a.v[2], b.v[2]), op(a.v[3], b.v[3])};
  }
  template <class Op>
  static ScalarMask test(const ScalarBatch& a, const ScalarBatch& b, Op op) {
    return {{op(a.v[0], b.v[0]), op(a.v[1], b.v[1]), op(a.v[2], b.v[2]), op(a.v[3], b.v[3])}};
  }
  friend ScalarBatch operator+(const ScalarBatch& a, const ScalarBatch& b) {
    return map(a, b, [](T x, T y) -> T { return x + y; });
  }
  friend ScalarBatch operator-(const ScalarBatch& a, const ScalarBatch& b) {
    return map(a, b, [](T x, T y) -> T { return x - y; });
  }
  friend ScalarBatch operator*(const ScalarBatch& a, const ScalarBatch& b) {
    return map(a, b, [](T x, T y) -> T { return x * y; });
  }
  friend ScalarBatch operator/(const ScalarBatch& a, const ScalarBatch& b) {
    return map(a, b, [](T x, T y) -> T { return x / y; });
  }
  friend ScalarBatch operator&(const ScalarBatch& a, const ScalarBatch& b) {
    return map(a, b, [](T x, T y) -> T { return x & y; });
  }
  friend ScalarBatch operator|(const ScalarBatch& a, const ScalarBatch& b) {
    return map(a, b, [](T x, T y) -> T { return x | y; });
  }
  friend ScalarBatch operator-(const ScalarBatch& a) { return ScalarBatch(T(0)) - a; }
  friend ScalarBatch operator>>(const ScalarBatch& a, int s) {
    return {T(a.v[0] >> s), T(a.v[1] >> s), T(a.v[2] >> s), T(a.v[3] >> s)};
  }
  friend ScalarBatch operator<<(const ScalarBatch& a, int s) {
    return {T(a.v[0] << s), T(a.v[1] << s), T(a.v[2] << s), T(a.v[3] << s)};
  }
  friend ScalarMask operator<(const ScalarBatch& a, const ScalarBatch& b) {
    return test(a, b, [](T x, T y) { return x < y; });
  }
  friend ScalarMask operator<=(const ScalarBatch& a, const ScalarBatch& b) {
    return test(a, b, [](T x, T y) { return x <= y; });
  }
  friend ScalarMask operator>(const ScalarBatch& a, const ScalarBatch& b) {
    return test(a, b, [](T x, T y) { return x > y; });
  }
  friend ScalarMask operator>=(const ScalarBatch& a, const ScalarBatch& b) {
    return test(a, b, [](T x, T y) { return x >= y; });
  }
  friend ScalarMask operator==(const ScalarBatch& a, const ScalarBatch& b) {
    return test(a, b, [](T x, T y) { return x == y; });
  }
  friend ScalarMask operator!=(const ScalarBatch& a, const ScalarBatch& b) {
    return test(a, b, [](T x, T y) { return x != y; });
  }
};

template <class Arch>
struct Lanes {
  using F = xsimd::batch<float, Arch>;
  using I = xsimd::batch<std::int32_t, Arch>;
  using M = xsimd::batch_bool<float, Arch>;
  using D = xsimd::batch<double, Arch>;
  using DM = xsimd::batch_bool<double, Arch>;
  using I64 = xsimd::batch<std::int64_t, Arch>;
  static constexpr int kWidth = int(F::size);
  static constexpr int kQuads = kWidth / 4;
  static constexpr int kDoubleWidth = int(D::size);
};

template <>
struct Lanes<ScalarArch> {
  using F = ScalarBatch<float>;
  using I = ScalarBatch<std::int32_t>;
  using M = ScalarMask;
  using D = ScalarBatch<double>;
  using DM = ScalarMask;
  using I64 = ScalarBatch<std::int64_t>;
  static constexpr int kWidth = 4;
  static constexpr int kQuads = 1;
  static constexpr int kDoubleWidth = 4;
};

// ------------------------------------------------------------ scalar functions
inline ScalarBatch<float> select(const ScalarMask& m, const ScalarBatch<float>& a,
                                 const ScalarBatch<float>& b) {
  return {m.v[0] ? a.v[0] : b.v[0], m.v[1] ? a.v[1] : b.v[1], m.v[2] ? a.v[2] : b.v[2],
          m.v[3] ? a.v[3] : b.v[3]};
}
inline ScalarBatch<float> min(const ScalarBatch<float>& a, const ScalarBatch<float>& b) {
  return ScalarBatch<float>::map(a, b, [](float x, float y) { return x < y ? x : y; });
}
inline ScalarBatch<float> max(const ScalarBatch<float>& a, const ScalarBatch<float>& b) {
  return ScalarBatch<float>::map(a, b, [](float x, float y) { return x > y ? x : y; });
}
inline ScalarBatch<float> abs(const ScalarBatch<float>& a) {
  return ScalarBatch<float>::map(a, a, [](float x, float) { return __builtin_fabsf(x); });
}
inline ScalarBatch<float> floor(const ScalarBatch<float>& a) {
  return ScalarBatch<float>::map(a, a, [](float x, float) { return __builtin_floorf(x); });
}
inline ScalarBatch<float> sqrt(const ScalarBatch<float>& a) {
  return ScalarBatch<float>::map(a, a, [](float x, float) { return __builtin_sqrtf(x); });
}
inline ScalarBatch<double> select(const ScalarMask& m, const ScalarBatch<double>& a,
                                  const ScalarBatch<double>& b) {
  return {m.v[0] ? a.v[0] : b.v[0], m.v[1] ? a.v[1] : b.v[1], m.v[2] ? a.v[2] : b.v[2],
          m.v[3] ? a.v[3] : b.v[3]};
}
inline ScalarBatch<double> abs(const ScalarBatch<double>& a) {
  return ScalarBatch<double>::map(a, a, [](double x, double) { return __builtin_fabs(x); });
}
inline ScalarBatch<double> floor(const ScalarBatch<double>& a) {
  return ScalarBatch<double>::map(a, a, [](double x, double) { return __builtin_floor(x); });
}
inline ScalarMask isNan(const ScalarBatch<double>& a) {
  return ScalarBatch<double>::test(a, a, [](double x, double) { return x != x; });
}
inline ScalarBatch<std::int32_t> min(const ScalarBatch<std::int32_t>& a,
                                     const ScalarBatch<std::int32_t>& b) {
  return ScalarBatch<std::int32_t>::map(
      a, b, [](std::int32_t x, std::int32_t y) { return x < y ? x : y; });
}
inline ScalarBatch<std::int32_t> max(const ScalarBatch<std::int32_t>& a,
                                     const ScalarBatch<std::int32_t>& b) {
  return ScalarBatch<std::int32_t>::map(
      a, b, [](std::int32_t x, std::int32_t y) { return x > y ? x : y; });
}
// Truncation toward zero (cvttps); callers keep values inside int32 range.
inline ScalarBatch<std::int32_t> toInt(const ScalarBatch<float>& a) {
  return {std::int32_t(a.v[0]), std::int32_t(a.v[1]), std::int32_t(a.v[2]), std::int32_t(a.v[3])};
}
inline ScalarBatch<float> toFloat(const ScalarBatch<std::int32_t>& a) {
  return {float(a.v[0]), float(a.v[1]), float(a.v[2]), float(a.v[3])};
}
inline ScalarBatch<std::int32_t> asInt(const ScalarBatch<float>& a) {
  ScalarBatch<std::int32_t> r;
  std::memcpy(r.v, a.v, sizeof(r.v));
  return r;
}
inline ScalarBatch<float> asFloat(const ScalarBatch<std::int32_t>& a) {
  ScalarBatch<float> r;
  std::memcpy(r.v, a.v, sizeof(r.v));
  return r;
}
inline bool any(const ScalarMask& m) {
  return m.v[0] || m.v[1] || m.v[2] || m.v[3];
}
inline bool all(const ScalarMask& m) {
  return m.v[0] && m.v[1] && m.v[2] && m.v[3];
}
inline std::uint32_t bits(const ScalarMask& m) {
  return std::uint32_t(m.v[0]) | std::uint32_t(m.v[1]) << 1 | std::uint32_t(m.v[2]) << 2 |
         std::uint32_t(m.v[3]) << 3;
}
// Broadcasts lane k of every quad to all four lanes of that quad.
template <int k>
inline ScalarBatch<float> quadBroadcast(const ScalarBatch<float>& a) {
  return ScalarBatch<float>(a.v[k]);
}
// Lane j of the result is lane index[j] of a (index in [0, width)): a
// variable permute, for spreading per-lookup values over lanes that work on
// other lookups' taps.
template <class T>
inline ScalarBatch<T> permute(const ScalarBatch<T>& a, const ScalarBatch<std::int32_t>& index) {
  return {a.v[index.v[0]], a.v[index.v[1]], a.v[index.v[2]], a.v[index.v[3]]};
}
// The same from two registers, a then b: index in [0, 2 width).
inline ScalarBatch<float> permute2(const ScalarBatch<float>& a, const ScalarBatch<float>& b,
                                   const ScalarBatch<std::int32_t>& index) {
  ScalarBatch<float> r;
  for (int k = 0; k < 4; ++k) r.v[k] = index.v[k] < 4 ? a.v[index.v[k]] : b.v[index.v[k] - 4];
  return r;
}

// ------------------------------------------------------------- xsimd functions
template <class A>
inline xsimd::batch<float, A> select(const xsimd::batch_bool<float, A>& m,
                                     const xsimd::batch<float, A>& a,
                                     const xsimd::batch<float, A>& b) {
  return xsimd::select(m, a, b);
}
template <class A>
inline xsimd::batch<double, A> select(const xsimd::batch_bool<double, A>& m,
                                      const xsimd::batch<double, A>& a,
                                      const xsimd::batch<double, A>& b) {
  return xsimd::select(m, a, b);
}
template <class T, class A>
inline xsimd::batch<T, A> min(const xsimd::batch<T, A>& a, const xsimd::batch<T, A>& b) {
  return xsimd::min(a, b);
}
template <class T, class A>
inline xsimd::batch<T, A> max(const xsimd::batch<T, A>& a, const xsimd::batch<T, A>& b) {
  return xsimd::max(a, b);
}
template <class T, class A>
inline xsimd::batch<T, A> abs(const xsimd::batch<T, A>& a) {
  return xsimd::abs(a);
}
// On SSE2 (no roundps/roundpd) xsimd 8.1 floors through a conversion to
// integer lanes on every lane and keeps the input where |a| is at least
// 2^(mantissa bits); converting such a lane (1e30, Inf, NaN) is undefined
// behaviour (UBSan float-cast-overflow, found by the lookups_csv fuzz
// target). Those lanes are already integers or NaN, so they are swapped for
// 0 before the conversion and put back after: the same values, no UB. The
// other ISAs round natively and skip the two selects.
template <class T, class A>
inline xsimd::batch<T, A> floor(const xsimd::batch<T, A>& a) {
  if constexpr (std::is_same_v<A, xsimd::sse2>) {
    using B = xsimd::batch<T, A>;
    const auto small =
        xsimd::abs(a) < B(T(std::uint64_t(1) << (std::numeric_limits<T>::digits - 1)));
    return xsimd::select(small, xsimd::floor(xsimd::select(small, a, B(T(0)))), a);
  } else {
    return xsimd::floor(a);
  }
}
// Not `a != a`: xsimd's != is the ordered compare on AVX (false for NaN) and
// the unordered one on SSE2 (true), so only this names NaN on every path.
template <class A>
inline xsimd::batch_bool<double, A> isNan(const xsimd::batch<double, A>& a) {
  return xsimd::isnan(a);
}
template <class A>
inline xsimd::batch<float, A> sqrt(const xsimd::batch<float, A>& a) {
  return xsimd::sqrt(a);
}
template <class A>
inline xsimd::batch<std::int32_t, A> toInt(const xsimd::batch<float, A>& a) {
  return xsimd::to_int(a);
}
template <class A>
inline xsimd::batch<float, A> toFloat(const xsimd::batch<std::int32_t, A>& a) {
  return xsimd::to_float(a);
}
template <class A>
inline xsimd::batch<std::int32_t, A> asInt(const xsimd::batch<float, A>& a) {
  return xsimd::bitwise_cast<xsimd::batch<std::int32_t, A>>(a);
}
template <class A>
inline xsimd::batch<float, A> asFloat(const xsimd::batch<std::int32_t, A>& a) {
  return xsimd::bitwise_cast<xsimd::batch<float, A>>(a);
}
template <class A>
inline bool any(const xsimd::batch_bool<float, A>& m) {
  return xsimd::any(m);
}
template <class A>
inline bool all(const xsimd::batch_bool<float, A>& m) {
  return xsimd::all(m);
}

#if defined(__SSE2__)
inline std::uint32_t bits(const xsimd::batch_bool<float, xsimd::sse2>& m) {
  return std::uint32_t(_mm_movemask_ps(m));
}
template <int k>
inline xsimd::batch<float, xsimd::sse2> quadBroadcast(const xsimd::batch<float, xsimd::sse2>& a) {
  return _mm_shuffle_ps(a, a, _MM_SHUFFLE(k, k, k, k));
}
// SSE2 has no variable permute (pshufb is SSSE3): four lanes through memory.
template <class T>
inline xsimd::batch<T, xsimd::sse2> permute(const xsimd::batch<T, xsimd::sse2>& a,
                                            const xsimd::batch<std::int32_t, xsimd::sse2>& index) {
  alignas(16) T value[4], out[4];
  alignas(16) std::int32_t lane[4];
  a.store_aligned(value);
  index.store_aligned(lane);
  for (int k = 0; k < 4; ++k) out[k] = value[lane[k]];
  return xsimd::batch<T, xsimd::sse2>::load_aligned(out);
}
inline xsimd::batch<float, xsimd::sse2> permute2(
    const xsimd::batch<float, xsimd::sse2>& a, const xsimd::batch<float, xsimd::sse2>& b,
    const xsimd::batch<std::int32_t, xsimd::sse2>& index) {
  alignas(16) float value[8], out[4];
  alignas(16) std::int32_t lane[4];
  a.store_aligned(value);
  b.store_aligned(value + 4);
  index.store_aligned(lane);
  for (int k = 0; k < 4; ++k) out[k] = value[lane[k]];
  return xsimd::batch<float, xsimd::sse2>::load_aligned(out);
}
#endif
#if defined(__AVX2__)
inline std::uint32_t bits(const xsimd::batch_bool<float, xsimd::avx2>& m) {
  return std::uint32_t(_mm256_movemask_ps(m));
}
// vpermilps permutes within each 128-bit half, which is exactly one quad.
template <int k>
inline xsimd::batch<float, xsimd::avx2> quadBroadcast(const xsimd::batch<float, xsimd::avx2>& a) {
  return _mm256_permute_ps(a, _MM_SHUFFLE(k, k, k, k));
}
inline xsimd::batch<float, xsimd::avx2> permute(
    const xsimd::batch<float, xsimd::avx2>& a,
    const xsimd::batch<std::int32_t, xsimd::avx2>& index) {
  return _mm256_permutevar8x32_ps(a, index);
}
inline xsimd::batch<std::int32_t, xsimd::avx2> permute(
    const xsimd::batch<std::int32_t, xsimd::avx2>& a,
    const xsimd::batch<std::int32_t, xsimd::avx2>& index) {
  return _mm256_permutevar8x32_epi32(a, index);
}
inline xsimd::batch<float, xsimd::avx2> permute2(
    const xsimd::batch<float, xsimd::avx2>& a, const xsimd::batch<float, xsimd::avx2>& b,
    const xsimd::batch<std::int32_t, xsimd::avx2>& index) {
  const __m256 fromB = _mm256_castsi256_ps(_mm256_cmpgt_epi32(index, _mm256_set1_epi32(7)));
  return _mm256_blendv_ps(_mm256_permutevar8x32_ps(a, index), _mm256_permutevar8x32_ps(b, index),
                          fromB);
}
#endif
#if defined(__AVX512F__) && defined(__AVX512BW__)
inline std::uint32_t bits(const xsimd::batch_bool<float, xsimd::avx512bw>& m) {
  return std::uint32_t(m.data);
}
template <int k>
inline xsimd::batch<float, xsimd::avx512bw> quadBroadcast(
    const xsimd::batch<float, xsimd::avx512bw>& a) {
  return _mm512_permute_ps(a, _MM_SHUFFLE(k, k, k, k));
}
inline xsimd::batch<float, xsimd::avx512bw> permute(
    const xsimd::batch<float, xsimd::avx512bw>& a,
    const xsimd::batch<std::int32_t, xsimd::avx512bw>& index) {
  return _mm512_permutexvar_ps(index, a);
}
inline xsimd::batch<std::int32_t, xsimd::avx512bw> permute(
    const xsimd::batch<std::int32_t, xsimd::avx512bw>& a,
    const xsimd::batch<std::int32_t, xsimd::avx512bw>& index) {
  return _mm512_permutexvar_epi32(index, a);
}
inline xsimd::batch<float, xsimd::avx512bw> permute2(
    const xsimd::batch<float, xsimd::avx512bw>& a, const xsimd::batch<float, xsimd::avx512bw>& b,
    const xsimd::batch<std::int32_t, xsimd::avx512bw>& index) {
  return _mm512_permutex2var_ps(a, index, b);
}
#endif

// ------------------------------------------------------- shared lane helpers
// Lane constants given per lane (width W entries).
template <class V, class T>
inline V fromArray(const T* values) {
  return V::load_unaligned(values);
}

// Mask of the lanes whose bit is set in `laneBits` (bit k = lane k).
template <class L>
inline typename L::M maskFromBits(std::uint32_t laneBits) {
  alignas(64) std::int32_t pattern[L::kWidth];
  for (int k = 0; k < L::kWidth; ++k) pattern[k] = std::int32_t(1) << k;
  const typename L::I lane = L::I::load_aligned(pattern);
  return toFloat(typename L::I(std::int32_t(laneBits)) & lane) != typename L::F(0.0f);
}

#if defined(__AVX2__)
// For eight lanes, per 8-bit lane mask: the set lanes' indices in lane order
// (`list`), and each lane's rank among the set lanes (`rank`), as 3-bit fields.
struct LaneMaskTables {
  std::uint32_t list[256], rank[256];
};
constexpr LaneMaskTables makeLaneMaskTables() {
  LaneMaskTables t{};
  for (std::uint32_t mask = 0; mask < 256; ++mask) {
    std::uint32_t set = 0;
    for (std::uint32_t k = 0; k < 8; ++k) {
      t.rank[mask] |= (set & 7) << (3 * k);
      if (mask >> k & 1) t.list[mask] |= k << (3 * set++);
    }
  }
  return t;
}
static constexpr LaneMaskTables kLaneMaskTables = makeLaneMaskTables();
#endif

// offset + the index of each lane set in laneBits, in lane order, to
// out[0, popcount): a compress. out has room for a whole register, which may
// be written in full.
template <class L>
QUADRA_LANE_INLINE void compressLaneIndices(std::uint32_t laneBits, std::int32_t offset,
                                            std::int32_t* out) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
  if constexpr (L::kWidth == 16) {  // the register form: compress-to-memory is slow on Zen 4
    const __m512i lane =
        _mm512_add_epi32(_mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
                         _mm512_set1_epi32(offset));
    _mm512_storeu_si512(out, _mm512_maskz_compress_epi32(__mmask16(laneBits), lane));
    return;
  }
#endif
#if defined(__AVX2__)
  if constexpr (L::kWidth == 8) {
    const __m256i fields = _mm256_srlv_epi32(_mm256_set1_epi32(int(kLaneMaskTables.list[laneBits])),
                                             _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out),
                        _mm256_add_epi32(_mm256_and_si256(fields, _mm256_set1_epi32(7)),
                                         _mm256_set1_epi32(offset)));
    return;
  }
#endif
  int n = 0;
  for (std::uint32_t rest = laneBits; rest; rest &= rest - 1)
    out[n++] = offset + __builtin_ctz(rest);
}

// Lane k of the result: where bit k of laneBits is set, the next of
// values[offset], values[offset + 1], ... in lane order; elsewhere 0: an
// expand. values is register-aligned and offset < width: the SIMD paths read
// the two whole registers values[0, 2 width) as they were stored (a load
// straddling two earlier stores cannot be forwarded from them and waits
// for both to reach the cache, ~20 cycles here) and pick the lanes by permute.
template <class L>
QUADRA_LANE_INLINE typename L::F expandLoad(std::uint32_t laneBits, const float* values,
                                            int offset) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
  if constexpr (L::kWidth == 16) {
    const __mmask16 set = __mmask16(laneBits);
    const __m512i rank = _mm512_maskz_expand_epi32(
        set, _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
    return _mm512_maskz_permutex2var_ps(set, _mm512_load_ps(values),
                                        _mm512_add_epi32(rank, _mm512_set1_epi32(offset)),
                                        _mm512_load_ps(values + 16));
  }
#endif
#if defined(__AVX2__)
  if constexpr (L::kWidth == 8) {
    const __m256i shifts = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
    const __m256i index = _mm256_add_epi32(
        _mm256_and_si256(
            _mm256_srlv_epi32(_mm256_set1_epi32(int(kLaneMaskTables.rank[laneBits])), shifts),
            _mm256_set1_epi32(7)),
        _mm256_set1_epi32(offset));
    const __m256 low = _mm256_permutevar8x32_ps(_mm256_load_ps(values), index);
    const __m256 high = _mm256_permutevar8x32_ps(_mm256_load_ps(values + 8), index);
    const __m256 fromHigh = _mm256_castsi256_ps(_mm256_cmpgt_epi32(index, _mm256_set1_epi32(7)));
    const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const __m256i set =
        _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(laneBits)), bit), bit);
    return _mm256_and_ps(_mm256_blendv_ps(low, high, fromHigh), _mm256_castsi256_ps(set));
  }
#endif
  alignas(64) float out[L::kWidth] = {};
  for (int k = 0, n = offset; k < L::kWidth; ++k)
    if (laneBits >> k & 1) out[k] = values[n++];
  return L::F::load_aligned(out);
}

// The smallest and the largest lane of `low` and `high`, by halving the
// register: log2(width) steps where a store and a scalar loop took width.
// Lanes are compared with min/max's semantics, so for finite lanes the value
// is the same on every path (a -0 / +0 tie may come out either way).
template <class L>
QUADRA_LANE_INLINE void reduceMinMax(const typename L::F& low, const typename L::F& high,
                                     float& lowest, float& highest) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
  if constexpr (L::kWidth == 16) {
    lowest = _mm512_reduce_min_ps(low);
    highest = _mm512_reduce_max_ps(high);
    return;
  }
#endif
#if defined(__AVX2__)
  if constexpr (L::kWidth == 8) {
    auto halve = [](__m256 x, auto op) {
      __m128 v = op(_mm256_castps256_ps128(x), _mm256_extractf128_ps(x, 1));
      v = op(v, _mm_movehl_ps(v, v));
      return _mm_cvtss_f32(op(v, _mm_shuffle_ps(v, v, 1)));
    };
    lowest = halve(low, [](__m128 a, __m128 b) { return _mm_min_ps(a, b); });
    highest = halve(high, [](__m128 a, __m128 b) { return _mm_max_ps(a, b); });
    return;
  }
#endif
  alignas(64) float lows[L::kWidth], highs[L::kWidth];
  low.store_aligned(lows);
  high.store_aligned(highs);
  lowest = lows[0], highest = highs[0];
  for (int k = 1; k < L::kWidth; ++k)
    lowest = std::min(lowest, lows[k]), highest = std::max(highest, highs[k]);
}

// Int lanes whose lane k is value(k), built in registers from the scalars:
// storing them one by one and loading the register back cannot be forwarded
// from the stores and waits for them to reach the cache (setup's culling
// gathered its vertices that way about 12% slower on AVX2: 10.4 against 9.2
// ms on dense-mesh).
template <class L, class Value>
QUADRA_LANE_INLINE typename L::I laneInts(const Value& value) {
  if constexpr (std::is_same_v<L, Lanes<ScalarArch>>) {
    return {value(0), value(1), value(2), value(3)};
#if defined(__AVX512F__) && defined(__AVX512BW__)
  } else if constexpr (L::kWidth == 16) {
    // Two halves: GCC builds a 16-value set through the stack, which is the
    // stall this avoids.
    const __m256i low = _mm256_setr_epi32(value(0), value(1), value(2), value(3), value(4),
                                          value(5), value(6), value(7));
    const __m256i high = _mm256_setr_epi32(value(8), value(9), value(10), value(11), value(12),
                                           value(13), value(14), value(15));
    return _mm512_inserti64x4(_mm512_castsi256_si512(low), high, 1);
#endif
#if defined(__AVX2__)
  } else if constexpr (L::kWidth == 8) {
    return _mm256_setr_epi32(value(0), value(1), value(2), value(3), value(4), value(5), value(6),
                             value(7));
#endif
  } else {
    static_assert(L::kWidth == 4, "SSE2: four lanes");
    return _mm_setr_epi32(value(0), value(1), value(2), value(3));
  }
}

// Lane k's address base[index[k]] + offset[k] * kBytes (kBytes a power of
// two), to out[k]; base holds 16 entries, 64-byte aligned (entries no index
// names may hold anything). On AVX-512 the base pointers are looked up by a
// two-register permute and the addresses formed in 64-bit lanes: the scalar
// loop's two loads and three operations per lane were a sixth of the
// anisotropic filter's time, whose lanes read several levels at once.
template <class L, int kBytes>
QUADRA_LANE_INLINE void laneAddresses(const std::uint8_t* const* base, const typename L::I& index,
                                      const typename L::I& offset,
                                      const std::uint8_t* out[L::kWidth]) {
  static_assert(kBytes > 0 && (kBytes & (kBytes - 1)) == 0);
#if defined(__AVX512F__) && defined(__AVX512BW__)
  if constexpr (L::kWidth == 16) {
    constexpr int kShift = __builtin_ctz(kBytes);
    const __m512i low = _mm512_load_si512(base), high = _mm512_load_si512(base + 8);
    const __m256i lanes[2] = {_mm512_castsi512_si256(index),
                              _mm512_extracti64x4_epi64(__m512i(index), 1)};
    const __m256i offsets[2] = {_mm512_castsi512_si256(offset),
                                _mm512_extracti64x4_epi64(__m512i(offset), 1)};
    for (int h = 0; h < 2; ++h) {
      const __m512i start = _mm512_permutex2var_epi64(low, _mm512_cvtepi32_epi64(lanes[h]), high);
      const __m512i bytes = _mm512_slli_epi64(_mm512_cvtepi32_epi64(offsets[h]), kShift);
      _mm512_storeu_si512(out + 8 * h, _mm512_add_epi64(start, bytes));
    }
    return;
  }
#endif
  alignas(64) std::int32_t lane[L::kWidth], off[L::kWidth];
  index.store_aligned(lane);
  offset.store_aligned(off);
  for (int k = 0; k < L::kWidth; ++k) out[k] = base[lane[k]] + std::ptrdiff_t(off[k]) * kBytes;
}

// One register from a quad (4 floats, 16-byte aligned) in each of width / 4
// places `stride` floats apart: lanes 4k .. 4k + 3 from base + k * stride.
// The multisample kernels' view of a quad's samples, one quad per sample plane.
template <class L>
QUADRA_LANE_INLINE typename L::F loadQuadsStrided(const float* base, std::ptrdiff_t stride) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
  if constexpr (L::kWidth == 16) {
    const __m512 low = _mm512_insertf32x4(_mm512_castps128_ps512(_mm_load_ps(base)),
                                          _mm_load_ps(base + stride), 1);
    return _mm512_insertf32x4(_mm512_insertf32x4(low, _mm_load_ps(base + 2 * stride), 2),
                              _mm_load_ps(base + 3 * stride), 3);
  }
#endif
#if defined(__AVX2__)
  if constexpr (L::kWidth == 8)
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(base)),
                                _mm_load_ps(base + stride), 1);
#endif
  alignas(64) float lanes[L::kWidth];
  for (int k = 0; k < L::kWidth; ++k) lanes[k] = base[(k / 4) * stride + k % 4];
  return L::F::load_aligned(lanes);
}

// The inverse of loadQuadsStrided: lanes 4k .. 4k + 3 to base + k * stride.
template <class L>
QUADRA_LANE_INLINE void storeQuadsStrided(const typename L::F& value, float* base,
                                          std::ptrdiff_t stride) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
  if constexpr (L::kWidth == 16) {
    _mm_store_ps(base, _mm512_castps512_ps128(value));
    _mm_store_ps(base + stride, _mm512_extractf32x4_ps(value, 1));
    _mm_store_ps(base + 2 * stride, _mm512_extractf32x4_ps(value, 2));
    _mm_store_ps(base + 3 * stride, _mm512_extractf32x4_ps(value, 3));
    return;
  }
#endif
#if defined(__AVX2__)
  if constexpr (L::kWidth == 8) {
    _mm_store_ps(base, _mm256_castps256_ps128(value));
    _mm_store_ps(base + stride, _mm256_extractf128_ps(value, 1));
    return;
  }
#endif
  alignas(64) float lanes[L::kWidth];
  value.store_aligned(lanes);
  for (int k = 0; k < L::kWidth; ++k) base[(k / 4) * stride + k % 4] = lanes[k];
}

// Lane k of out[j] holds the bits of records[k][j], j < 3: a triple per
// lane (a plane's dx, dy, c; a shading job's x, y) as three registers. Each
// record must be readable for 4 floats (the fourth is loaded and dropped). In registers, 4 lanes a
// 4x4 transpose: through memory, each register's load waited for its lanes' scalar stores.
template <class L>
QUADRA_LANE_INLINE void loadTriples(const float* const* records, typename L::F out[3]) {
#if defined(__SSE2__)
  if constexpr (!std::is_same_v<L, Lanes<ScalarArch>>) {
    __m128 quarter[L::kWidth / 4][3];
    for (int q = 0; q < L::kWidth / 4; ++q) {
      __m128 a = _mm_loadu_ps(records[4 * q]), b = _mm_loadu_ps(records[4 * q + 1]),
             c = _mm_loadu_ps(records[4 * q + 2]), d = _mm_loadu_ps(records[4 * q + 3]);
      _MM_TRANSPOSE4_PS(a, b, c, d);
      quarter[q][0] = a, quarter[q][1] = b, quarter[q][2] = c;
    }
    for (int j = 0; j < 3; ++j) {
      if constexpr (L::kWidth == 4) {
        out[j] = quarter[0][j];
#if defined(__AVX2__)
      } else if constexpr (L::kWidth == 8) {
        out[j] = _mm256_insertf128_ps(_mm256_castps128_ps256(quarter[0][j]), quarter[1][j], 1);
#endif
#if defined(__AVX512F__) && defined(__AVX512BW__)
      } else if constexpr (L::kWidth == 16) {
        const __m512 low =
            _mm512_insertf32x4(_mm512_castps128_ps512(quarter[0][j]), quarter[1][j], 1);
        out[j] = _mm512_insertf32x4(_mm512_insertf32x4(low, quarter[2][j], 2), quarter[3][j], 3);
#endif
      }
    }
    return;
  }
#endif
  alignas(64) float lanes[3][L::kWidth];
  for (int k = 0; k < L::kWidth; ++k)  // a record's floats may be another type's bits
    for (int j = 0; j < 3; ++j) std::memcpy(&lanes[j][k], records[k] + j, sizeof(float));
  for (int j = 0; j < 3; ++j) out[j] = L::F::load_aligned(lanes[j]);
}

// Lane i of the result is four[first + i / 4] (first + width / 4 <= 4): a
// value per quad of lanes, from a register (a load over the stores that
// built it in memory waits for them).
template <class L>
QUADRA_LANE_INLINE typename L::F repeatPerQuad(__m128 four, int first) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
  if constexpr (L::kWidth == 16)
    return _mm512_permutexvar_ps(
        _mm512_add_epi32(_mm512_set1_epi32(first),
                         _mm512_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3)),
        _mm512_castps128_ps512(four));
#endif
#if defined(__AVX2__)
  if constexpr (L::kWidth == 8)
    return _mm256_permutevar8x32_ps(
        _mm256_castps128_ps256(four),
        _mm256_add_epi32(_mm256_set1_epi32(first), _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1)));
#endif
  alignas(16) float values[4];
  _mm_store_ps(values, four);
  return typename L::F(values[first]);  // SSE2 and scalar: one quad
}

// kDoubleWidth int64 values from `values` (register-aligned) as doubles,
// rounded to nearest like the scalar conversion (cvtsi2sd). AVX-512DQ
// converts a register (xsimd 8.1's own conversion there does not compile: it
// names a parameter that does not exist); AVX2 has no such instruction, and
// xsimd splits each value into an exact high part and an exact low part that
// one correctly rounded addition joins (the full-range method of
// stackoverflow.com/questions/41144668); on SSE2 that takes ten operations
// for two values, where two scalar conversions from memory take five.
template <class L>
QUADRA_LANE_INLINE typename L::D loadAsDouble(const std::int64_t* values) {
  if constexpr (std::is_same_v<L, Lanes<ScalarArch>>) {
    return {double(values[0]), double(values[1]), double(values[2]), double(values[3])};
#if defined(__AVX512F__) && defined(__AVX512DQ__)
  } else if constexpr (L::kDoubleWidth == 8) {
    return _mm512_cvtepi64_pd(_mm512_load_si512(values));
#endif
#if defined(__AVX2__)
  } else if constexpr (L::kDoubleWidth == 4) {
    return xsimd::to_float(L::I64::load_aligned(values));
#endif
  } else {
    static_assert(L::kDoubleWidth == 2, "SSE2: two doubles");
    return _mm_setr_pd(double(values[0]), double(values[1]));
  }
}

// Element i of the result is perLane[i / 4] (for SSE2, whose two elements
// are two channels of one lane: perLane[0]): per-lane doubles repeated over
// the four channels of an RGBA lane group stored [lane][channel].
template <class L>
QUADRA_LANE_INLINE typename L::D repeatPerChannel(const double* perLane) {
  if constexpr (L::kDoubleWidth == 8) {
#if defined(__AVX512F__)
    return _mm512_permutexvar_pd(_mm512_setr_epi64(0, 0, 0, 0, 1, 1, 1, 1),
                                 _mm512_castpd128_pd512(_mm_loadu_pd(perLane)));
#endif
  } else {
    return typename L::D(perLane[0]);
  }
}

// log2(x) for x > 0 finite, absolute error below 1e-6 over the whole range:
// exponent from the bits, mantissa m in [sqrt(1/2), sqrt(2)), and log2(m) =
// t*q(t), t = m - 1, with q of degree 6 interpolating log2(1+t)/t at Chebyshev
// nodes (max error 6.3e-7 before float rounding). No division: an earlier
// atanh series needed one, and its latency was the hottest spot of the LOD.
// Only exactly rounded operations, so every path returns the same bits.
// Zero, negative and NaN inputs return -126 (the log2 of the smallest normal).
template <class L>
QUADRA_LANE_INLINE typename L::F log2(const typename L::F& x) {
  using F = typename L::F;
  using I = typename L::I;
  const F safe = select(x > F(1.17549435e-38f), x, F(1.17549435e-38f));  // NaN → min normal
  const I bitsOf = asInt(safe);
  const I exponent = (bitsOf >> 23) - I(127);
  F m = asFloat((bitsOf & I(0x007FFFFF)) | I(0x3F800000));
  const auto high = m > F(1.41421356f);
  m = select(high, m * F(0.5f), m);
  const F e = toFloat(exponent) + select(high, F(1.0f), F(0.0f));
  const F t = m - F(1.0f);
  // Estrin's scheme: the same polynomial with a dependency chain of 5
  // operations instead of Horner's 12 (this code is latency-bound).
  const F t2 = t * t;
  const F t4 = t2 * t2;
  const F low = F(1.44269652f) + t * F(-0.721360179f);
  const F mid = F(0.480613125f) + t * F(-0.359524455f);
  const F top = (F(0.296119557f) + t * F(-0.267963871f)) + t2 * F(0.168186591f);
  const F q = (low + t2 * mid) + t4 * top;
  return e + t * q;
}

}  // namespace quadra::simd
