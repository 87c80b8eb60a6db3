// Texture filtering over SIMD lanes, one source for every ISA (templated on
// the lane types of simd/lanes.h). Conventions (DESIGN.md): texel i covers
// [i, i+1) with its centre at i + 0.5, so a lookup at u reads x = u*W - 0.5;
// LOD λ = log2 of the footprint's longest axis in level-0 texels.
//
// Include only from per-ISA kernel translation units. Everything here is a
// template on the lane type, so no inline function is shared between ISAs.
#pragma once

#include <algorithm>

#include <type_traits>

#include "simd/lanes.h"
#include "simd/transpose.h"

#include "texture/ewa.h"
#include "texture/texture_view.h"

namespace quadra {

template <class L>
struct Rgba {
  typename L::F r, g, b, a;
};

// Screen-space derivatives of (u, v), per lane.
template <class L>
struct UvDerivatives {
  typename L::F dudx, dvdx, dudy, dvdy;
};

namespace sampling {

template <class L>
constexpr bool kIsScalarLanes = std::is_same_v<L, simd::Lanes<simd::ScalarArch>>;

// Brings u into a small range where the wrap mode gives the same answer, and
// replaces NaN/Inf by 0 so no lane ever forms an out-of-range index.
template <class L>
QUADRA_LANE_INLINE typename L::F reduceCoordinate(typename L::F u, WrapMode mode) {
  using F = typename L::F;
  if (mode == WrapMode::Repeat) {
    u = u - simd::floor(u);  // exact (Sterbenz): u and floor(u) are close; result in [0, 1]
  } else if (mode == WrapMode::MirroredRepeat) {
    u = u - F(2.0f) * simd::floor(u * F(0.5f));
  } else {
    u = simd::max(simd::min(u, F(2.0f)), F(-1.0f));
  }
  return simd::select(simd::abs(u) <= F(4.0f), u, F(0.0f));
}

// Integer-valued texel coordinate x → index in [0, n) per the wrap mode.
// `inside` is cleared for lanes that read the border colour. x comes from a
// coordinate reduced by reduceCoordinate, so x lies in [-1, n] (repeat) or
// [-1, 2n] (mirrored repeat): one compare-and-shift wraps it, no division.
template <class L>
QUADRA_LANE_INLINE typename L::F wrapTexel(typename L::F x, typename L::F n, WrapMode mode,
                                           typename L::M& inside) {
  using F = typename L::F;
  switch (mode) {
    case WrapMode::Repeat: {
      x = simd::select(x < F(0.0f), x + n, x);
      return simd::select(x >= n, x - n, x);
    }
    case WrapMode::MirroredRepeat: {
      const F period = n + n;
      x = simd::select(x < F(0.0f), x + period, x);
      x = simd::select(x >= period, x - period, x);
      return simd::select(x >= n, period - F(1.0f) - x, x);
    }
    case WrapMode::ClampToEdge:
      return simd::max(simd::min(x, n - F(1.0f)), F(0.0f));
    case WrapMode::ClampToBorder:
      inside = inside & (x >= F(0.0f)) & (x <= n - F(1.0f));
      return simd::max(simd::min(x, n - F(1.0f)), F(0.0f));
  }
  return x;
}

// Per-lane level sizes, looked up from the view (lanes may sit on different levels).
template <class L>
// Returns the level when all lanes share one, else -1.
QUADRA_LANE_INLINE int levelSizes(const TextureView& view, const typename L::I& level,
                                  typename L::F& width, typename L::F& height) {
  if (view.levelCount == 1) {
    width = typename L::F(float(view.levels[0].width));
    height = typename L::F(float(view.levels[0].height));
    return 0;
  }
  alignas(64) std::int32_t lv[L::kWidth];
  alignas(64) float w[L::kWidth], h[L::kWidth];
  level.store_aligned(lv);
  // Usually every lane of a group sits on one level: broadcast its size rather
  // than assemble lanes from scalar stores (a wide load of narrow stores
  // cannot be store-forwarded and stalls).
  bool uniform = true;
  for (int k = 1; k < L::kWidth; ++k) uniform = uniform && lv[k] == lv[0];
  if (uniform) {
    width = typename L::F(float(view.levels[lv[0]].width));
    height = typename L::F(float(view.levels[lv[0]].height));
    return lv[0];
  }
  for (int k = 0; k < L::kWidth; ++k) {
    w[k] = float(view.levels[lv[k]].width);
    h[k] = float(view.levels[lv[k]].height);
  }
  width = L::F::load_aligned(w);
  height = L::F::load_aligned(h);
  return -1;
}

// One texel per lane (nearest filtering), loaded channel by channel.
template <class L>
Rgba<L> fetch(const TextureView& view, const typename L::I& level, const typename L::F& x,
              const typename L::F& y) {
  alignas(64) std::int32_t lv[L::kWidth], xi[L::kWidth], yi[L::kWidth];
  alignas(64) float r[L::kWidth], g[L::kWidth], b[L::kWidth], a[L::kWidth];
  level.store_aligned(lv);
  simd::toInt(x).store_aligned(xi);
  simd::toInt(y).store_aligned(yi);
  for (int k = 0; k < L::kWidth; ++k) {
    const TextureLevel& lev = view.levels[lv[k]];
    const float* t = lev.texels + (std::size_t(yi[k]) * std::size_t(lev.width) + xi[k]) * 4;
    r[k] = t[0];
    g[k] = t[1];
    b[k] = t[2];
    a[k] = t[3];
  }
  using F = typename L::F;
  return {F::load_aligned(r), F::load_aligned(g), F::load_aligned(b), F::load_aligned(a)};
}

// The 2x2 texels of a bilinear lookup in one pass over the lanes: corners
// (x0,y0), (x1,y0), (x0,y1), (x1,y1). Gather-free: each lane loads its RGBA
// texels whole and lanes are transposed into channels. Hardware gathers
// measured slower here (checker plane trilinear 15.0 vs 13.0 ms), and they are
// slow on AMD Zen and microcode-mitigated on many Intel parts.
// uniformLevel >= 0: every lane reads that level (no per-lane level lookup).
template <class L>
QUADRA_LANE_INLINE void fetch2x2Scalar(const TextureView& view, int uniformLevel,
                                       const std::int32_t* lv, const std::int32_t* xs0,
                                       const std::int32_t* xs1, const std::int32_t* ys0,
                                       const std::int32_t* ys1, Rgba<L> out[4]) {
  constexpr int W = L::kWidth;
  alignas(64) float texel[4][4][W];  // [corner][channel][lane]
  const float* corner[4][W];
  for (int k = 0; k < W; ++k) {
    const TextureLevel& lev = view.levels[uniformLevel >= 0 ? uniformLevel : lv[k]];
    // y * width < 2^28 (the loader's texel limit): a 32-bit product, which
    // vectorizes without 64-bit multiplies.
    const std::size_t row0 = std::uint32_t(ys0[k]) * std::uint32_t(lev.width);
    const std::size_t row1 = std::uint32_t(ys1[k]) * std::uint32_t(lev.width);
    corner[0][k] = lev.texels + (row0 + xs0[k]) * 4;
    corner[1][k] = lev.texels + (row0 + xs1[k]) * 4;
    corner[2][k] = lev.texels + (row1 + xs0[k]) * 4;
    corner[3][k] = lev.texels + (row1 + xs1[k]) * 4;
  }
#if defined(__AVX512F__)
  if constexpr (W == 16) {
    for (int c = 0; c < 4; c += 2) {
      __m256 pair[4][4];
      for (int g = 0; g < 4; ++g)
        simd::transposeTexelPairs(&corner[c][4 * g], &corner[c + 1][4 * g], pair[g]);
      __m512 left[4], right[4];
      simd::assemblePairs16(pair, left, right);
      out[c] = {left[0], left[1], left[2], left[3]};
      out[c + 1] = {right[0], right[1], right[2], right[3]};
    }
    return;
  }
#endif
  if constexpr (kIsScalarLanes<L>) {
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < W; ++k)
        for (int ch = 0; ch < 4; ++ch) texel[c][ch][k] = corner[c][k][ch];
  } else {
    // Whole-texel loads, transposed four lanes at a time (a scalar load per
    // channel cost twice as much).
#if defined(__AVX__)
    // Corners 0/1 and 2/3 are the left/right texels of one row: transpose them in pairs.
    for (int c = 0; c < 4; c += 2)
      for (int k = 0; k < W; k += 4) {
        float* const channels[8] = {&texel[c][0][k],     &texel[c][1][k],     &texel[c][2][k],
                                    &texel[c][3][k],     &texel[c + 1][0][k], &texel[c + 1][1][k],
                                    &texel[c + 1][2][k], &texel[c + 1][3][k]};
        simd::transposeTexelPairs(&corner[c][k], &corner[c + 1][k], channels);
      }
#else
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < W; k += 4) {
        float* const channels[4] = {&texel[c][0][k], &texel[c][1][k], &texel[c][2][k],
                                    &texel[c][3][k]};
        simd::transposeToChannels(&corner[c][k], channels);
      }
#endif
  }
  using F = typename L::F;
  for (int c = 0; c < 4; ++c)
    out[c] = {F::load_aligned(texel[c][0]), F::load_aligned(texel[c][1]),
              F::load_aligned(texel[c][2]), F::load_aligned(texel[c][3])};
}

// The 2x2 texels of a bilinear lookup: corners (x0,y0), (x1,y0), (x0,y1), (x1,y1).
template <class L>
QUADRA_LANE_INLINE void fetch2x2(const TextureView& view, const typename L::I& level,
                                 int uniformLevel, const typename L::F& x0, const typename L::F& x1,
                                 const typename L::F& y0, const typename L::F& y1, Rgba<L> out[4]) {
  constexpr int W = L::kWidth;
  alignas(64) std::int32_t lv[W], xs[2][W], ys[2][W];
  if (uniformLevel < 0) level.store_aligned(lv);
  simd::toInt(x0).store_aligned(xs[0]);
  simd::toInt(x1).store_aligned(xs[1]);
  simd::toInt(y0).store_aligned(ys[0]);
  simd::toInt(y1).store_aligned(ys[1]);
  fetch2x2Scalar<L>(view, uniformLevel, lv, xs[0], xs[1], ys[0], ys[1], out);
}

template <class L>
QUADRA_LANE_INLINE Rgba<L> withBorder(const TextureView& view, const Rgba<L>& c,
                                      const typename L::M& inside) {
  using F = typename L::F;
  return {
      simd::select(inside, c.r, F(view.border[0])), simd::select(inside, c.g, F(view.border[1])),
      simd::select(inside, c.b, F(view.border[2])), simd::select(inside, c.a, F(view.border[3]))};
}

template <class L>
QUADRA_LANE_INLINE Rgba<L> lerp(const Rgba<L>& p, const Rgba<L>& q, const typename L::F& t) {
  return {p.r + (q.r - p.r) * t, p.g + (q.g - p.g) * t, p.b + (q.b - p.b) * t,
          p.a + (q.a - p.a) * t};
}

}  // namespace sampling

// Nearest texel of the given level(s).
template <class L>
Rgba<L> sampleNearest(const TextureView& view, typename L::F u, typename L::F v,
                      const typename L::I& level) {
  using namespace sampling;
  using F = typename L::F;
  F width, height;
  levelSizes<L>(view, level, width, height);
  u = reduceCoordinate<L>(u, view.wrapU);
  v = reduceCoordinate<L>(v, view.wrapV);
  typename L::M inside = F(0.0f) == F(0.0f);
  const F x = wrapTexel<L>(simd::floor(u * width), width, view.wrapU, inside);
  const F y = wrapTexel<L>(simd::floor(v * height), height, view.wrapV, inside);
  return withBorder<L>(view, fetch<L>(view, level, x, y), inside);
}

// Bilinear reconstruction on the given level(s).
template <class L>
QUADRA_LANE_INLINE Rgba<L> sampleBilinear(const TextureView& view, typename L::F u, typename L::F v,
                                          const typename L::I& level) {
  using namespace sampling;
  using F = typename L::F;
  using M = typename L::M;
  F width, height;
  const int uniformLevel = levelSizes<L>(view, level, width, height);
  u = reduceCoordinate<L>(u, view.wrapU);
  v = reduceCoordinate<L>(v, view.wrapV);
  const F tx = u * width - F(0.5f), ty = v * height - F(0.5f);
  const F fx0 = simd::floor(tx), fy0 = simd::floor(ty);
  const F fx = tx - fx0, fy = ty - fy0;
  const M all = F(0.0f) == F(0.0f);
  M inX0 = all, inX1 = all, inY0 = all, inY1 = all;
  const F x0 = wrapTexel<L>(fx0, width, view.wrapU, inX0);
  const F x1 = wrapTexel<L>(fx0 + F(1.0f), width, view.wrapU, inX1);
  const F y0 = wrapTexel<L>(fy0, height, view.wrapV, inY0);
  const F y1 = wrapTexel<L>(fy0 + F(1.0f), height, view.wrapV, inY1);
  Rgba<L> c[4];
  fetch2x2<L>(view, level, uniformLevel, x0, x1, y0, y1, c);
  if (view.wrapU == WrapMode::ClampToBorder || view.wrapV == WrapMode::ClampToBorder) {
    c[0] = withBorder<L>(view, c[0], inX0 & inY0);
    c[1] = withBorder<L>(view, c[1], inX1 & inY0);
    c[2] = withBorder<L>(view, c[2], inX0 & inY1);
    c[3] = withBorder<L>(view, c[3], inX1 & inY1);
  }
  const Rgba<L>&c00 = c[0], &c10 = c[1], &c01 = c[2], &c11 = c[3];
  return lerp<L>(lerp<L>(c00, c10, fx), lerp<L>(c01, c11, fx), fy);
}

// Footprint size in level-0 texels: the LOD λ of the isotropic filters.
template <class L>
QUADRA_LANE_INLINE typename L::F isotropicLod(const TextureView& view, const UvDerivatives<L>& d) {
  using F = typename L::F;
  const F w = F(float(view.levels[0].width)), h = F(float(view.levels[0].height));
  const F xu = d.dudx * w, xv = d.dvdx * h, yu = d.dudy * w, yv = d.dvdy * h;
  const F lengthSq = simd::max(xu * xu + xv * xv, yu * yu + yv * yv);
  return F(0.5f) * simd::log2<L>(lengthSq);
}

// The view's LOD controls: clamp(λ + bias, minLod, maxLod); NaN becomes minLod.
template <class L>
QUADRA_LANE_INLINE typename L::F controlledLod(const TextureView& view, const typename L::F& lod) {
  using F = typename L::F;
  return simd::min(simd::max(lod + F(view.lodBias), F(view.minLod)), F(view.maxLod));
}

// Trilinear (or nearest-mip) at LOD λ; λ <= 0 is magnification.
template <class L>
QUADRA_LANE_INLINE Rgba<L> sampleMipmapped(const TextureView& view, const typename L::F& u,
                                           const typename L::F& v, typename L::F lod,
                                           bool linearBetweenLevels) {
  using F = typename L::F;
  using I = typename L::I;
  const F lastLevel = F(float(view.levelCount - 1));
  lod = simd::min(simd::max(lod, F(0.0f)), lastLevel);  // simd::max(NaN, 0) is 0: level 0
  if (!linearBetweenLevels) {
    const I level = simd::toInt(simd::floor(lod + F(0.5f)));
    return sampleBilinear<L>(view, u, v, simd::min(level, I(view.levelCount - 1)));
  }
  const F levelFloor = simd::floor(lod);
  const F t = lod - levelFloor;
  const I level0 = simd::toInt(levelFloor);
  const I level1 = simd::min(level0 + I(1), I(view.levelCount - 1));
  const Rgba<L> fine = sampleBilinear<L>(view, u, v, level0);
  if (!simd::any(t > F(0.0f))) return fine;
  const Rgba<L> coarse = sampleBilinear<L>(view, u, v, level1);
  return sampling::lerp<L>(fine, coarse, t);
}

// Anisotropic: N = simd::min(ceil(major/minor), maxAniso) trilinear probes along the
// footprint's major axis at λ = log2(major/N). The axes are the singular
// values of the Jacobian (the footprint ellipse), not the lengths of the two
// derivative vectors, which can be equal for a strongly sheared footprint.
template <class L>
Rgba<L> sampleAnisotropic(const TextureView& view, const typename L::F& u, const typename L::F& v,
                          const UvDerivatives<L>& d) {
  using F = typename L::F;
  const F w = F(float(view.levels[0].width)), h = F(float(view.levels[0].height));
  const F xu = d.dudx * w, xv = d.dvdx * h, yu = d.dudy * w, yv = d.dvdy * h;
  // J^T J = [[p, q], [q, r]]; its eigenvalues are the squared singular values.
  const F p = xu * xu + xv * xv, q = xu * yu + xv * yv, r = yu * yu + yv * yv;
  const F halfSum = F(0.5f) * (p + r), halfDiff = F(0.5f) * (p - r);
  const F root = simd::sqrt(halfDiff * halfDiff + q * q);
  const F majorSq = halfSum + root;
  const F minorSq = simd::max(halfSum - root, F(0.0f));
  // Eigenvector for the major eigenvalue, in screen space; pick the stabler form.
  const auto pBigger = p >= r;
  F ex = simd::select(pBigger, majorSq - r, q);
  F ey = simd::select(pBigger, q, majorSq - p);
  const F eLen = simd::sqrt(ex * ex + ey * ey);
  const auto degenerate = ~(eLen > F(0.0f));
  ex = simd::select(degenerate, F(1.0f), ex / eLen);
  ey = simd::select(degenerate, F(0.0f), ey / eLen);
  // Major axis in uv (normalized texture units).
  const F axisU = d.dudx * ex + d.dudy * ey, axisV = d.dvdx * ex + d.dvdy * ey;

  const F major = simd::sqrt(majorSq), minor = simd::sqrt(minorSq);
  const F maxAniso = F(float(view.maxAniso));
  // ceil(major/minor) in [1, maxAniso]; minor == 0 gives the cap, major == 0 one probe.
  const F ratio = major / simd::max(minor, F(1e-30f));
  F probes = simd::floor(ratio);
  probes = simd::select(ratio > probes, probes + F(1.0f), probes);
  probes = simd::max(simd::min(probes, maxAniso), F(1.0f));
  const F lod = controlledLod<L>(view, simd::log2<L>(major / probes));

  alignas(64) float probeCount[L::kWidth];
  probes.store_aligned(probeCount);
  int maxProbes = 1;
  for (int k = 0; k < L::kWidth; ++k) maxProbes = std::max(maxProbes, int(probeCount[k]));

  Rgba<L> sum{F(0.0f), F(0.0f), F(0.0f), F(0.0f)};
  for (int i = 0; i < maxProbes; ++i) {
    const F offset = (F(float(i) + 0.5f) / probes - F(0.5f));
    const auto active = F(float(i)) < probes;
    const Rgba<L> c = sampleMipmapped<L>(view, u + axisU * offset, v + axisV * offset, lod, true);
    sum.r = sum.r + simd::select(active, c.r, F(0.0f));
    sum.g = sum.g + simd::select(active, c.g, F(0.0f));
    sum.b = sum.b + simd::select(active, c.b, F(0.0f));
    sum.a = sum.a + simd::select(active, c.a, F(0.0f));
  }
  return {sum.r / probes, sum.g / probes, sum.b / probes, sum.a / probes};
}

// EWA, lane by lane through the scalar ewaLookup (its per-lookup texel count
// varies with the footprint, so lanes would mostly wait on each other).
template <class L>
Rgba<L> sampleEwa(const TextureView& view, const typename L::F& u, const typename L::F& v,
                  const UvDerivatives<L>& d) {
  constexpr int W = L::kWidth;
  alignas(64) float in[6][W], out[4][W];
  u.store_aligned(in[0]);
  v.store_aligned(in[1]);
  d.dudx.store_aligned(in[2]);
  d.dvdx.store_aligned(in[3]);
  d.dudy.store_aligned(in[4]);
  d.dvdy.store_aligned(in[5]);
  for (int k = 0; k < W; ++k) {
    float rgba[4];
    ewaLookup(view, in[0][k], in[1][k], in[2][k], in[3][k], in[4][k], in[5][k], rgba);
    for (int c = 0; c < 4; ++c) out[c][k] = rgba[c];
  }
  using F = typename L::F;
  return {F::load_aligned(out[0]), F::load_aligned(out[1]), F::load_aligned(out[2]),
          F::load_aligned(out[3])};
}

// The view's filter at the footprint given by the derivatives.
template <class L>
Rgba<L> sampleTexture(const TextureView& view, const typename L::F& u, const typename L::F& v,
                      const UvDerivatives<L>& d) {
  using F = typename L::F;
  using I = typename L::I;
  const I level0(0);
  const Filter filter = view.minFilter;
  if (filter == Filter::Nearest) return sampleNearest<L>(view, u, v, level0);
  if (filter == Filter::Bilinear) return sampleBilinear<L>(view, u, v, level0);
  if (filter == Filter::Ewa) return sampleEwa<L>(view, u, v, d);
  const F lod = controlledLod<L>(view, isotropicLod<L>(view, d));
  const auto magnified = ~(lod > F(0.0f));
  if (!view.magLinear && simd::all(magnified)) return sampleNearest<L>(view, u, v, level0);
  Rgba<L> c = filter == Filter::Anisotropic
                  ? sampleAnisotropic<L>(view, u, v, d)
                  : sampleMipmapped<L>(view, u, v, lod, filter == Filter::Trilinear);
  if (!view.magLinear && simd::any(magnified)) {
    const Rgba<L> n = sampleNearest<L>(view, u, v, level0);
    c = {simd::select(magnified, n.r, c.r), simd::select(magnified, n.g, c.g),
         simd::select(magnified, n.b, c.b), simd::select(magnified, n.a, c.a)};
  }
  return c;
}

}  // namespace quadra
