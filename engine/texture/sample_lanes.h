// Texture filtering over SIMD lanes, one source for every ISA (templated on
// the lane types of simd/lanes.h). Conventions (DESIGN.md): texel i covers
// [i, i+1) with its centre at i + 0.5, so a lookup at u reads x = u*W - 0.5;
// LOD λ = log2 of the footprint's longest axis in level-0 texels.
//
// Include only from per-ISA kernel translation units. Everything here is a
// template on the lane type, so no inline function is shared between ISAs.
#pragma once

#include <algorithm>
#include <cmath>

#include <type_traits>

#include "simd/lanes.h"
#include "simd/texel_pairs.h"

#include "texture/anisotropic.h"
#include "texture/area_filter.h"
#include "texture/ewa.h"
#include "texture/summed_area.h"
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

// How a kernel reads texels: the storage format, and for RGBA32F whether the
// bilinear rows come from hardware gathers instead of pair loads (kept as a
// benchmarked alternative: the gather:1 runs of quadra_sample_bench).
template <TexelFormat kStoredAs, bool kUseGathers = false>
struct TexelRead {
  static constexpr TexelFormat kFormat = kStoredAs;
  static constexpr bool kGather = kUseGathers;
  static_assert(!kUseGathers || kStoredAs == TexelFormat::Rgba32F, "gathers read float texels");
};

static_assert(simd::kUnorm8Scale == kUnorm8Scale, "one UNORM8 decode on every path");

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

// The size of the level each lane reads. Usually every lane of a group sits on
// one level: then `uniform` names it and the sizes are broadcast (assembling
// lanes from narrow stores defeats store forwarding); otherwise uniform is -1.
template <class L>
struct LevelGeometry {
  typename L::F width, height;
  typename L::I stride;  // texels per row (padded_level.h)
  int uniform;
  const TextureLevel* table;  // the levels the lanes' level indices refer to
  // When set (and not uniform): the table's first texels, 16 entries 64-byte
  // aligned (simd::laneAddresses), for lanes on several levels.
  const std::uint8_t* const* levelTexels;
};

template <class L>
QUADRA_LANE_INLINE LevelGeometry<L> levelGeometry(const LevelTable& table,
                                                  const typename L::I& level) {
  using F = typename L::F;
  using I = typename L::I;
  const int first = table.count == 1 ? 0 : int(level.get(0));
  if (table.count == 1 || simd::all(simd::toFloat(level) == F(float(first)))) {
    const TextureLevel& lev = table.levels[first];
    return {F(float(lev.width)), F(float(lev.height)), I(lev.stride), first, table.levels, nullptr};
  }
  alignas(64) std::int32_t lv[L::kWidth], stride[L::kWidth];
  alignas(64) float w[L::kWidth], h[L::kWidth];
  level.store_aligned(lv);
  for (int k = 0; k < L::kWidth; ++k) {
    w[k] = float(table.levels[lv[k]].width);
    h[k] = float(table.levels[lv[k]].height);
    stride[k] = table.levels[lv[k]].stride;
  }
  return {
      F::load_aligned(w), F::load_aligned(h), I::load_aligned(stride), -1, table.levels, nullptr};
}

// Texel offset (row * stride + column) of integer-valued coordinates, in
// int32: the loader caps textures at 2^28 texels and padding adds one per
// row, far below 2^31.
template <class L>
QUADRA_LANE_INLINE typename L::I texelOffset(const LevelGeometry<L>& g, const typename L::F& x,
                                             const typename L::F& y) {
  return simd::toInt(y) * g.stride + simd::toInt(x);
}

// Per-lane pointers to the texels at the given offsets.
template <class L, class R>
QUADRA_LANE_INLINE void texelPointers(const LevelGeometry<L>& g, const typename L::I& level,
                                      const typename L::I& offset,
                                      const std::uint8_t* out[L::kWidth]) {
  constexpr int texelBytes = bytesPerTexel(R::kFormat);
  if (g.levelTexels && g.uniform < 0) {
    simd::laneAddresses<L, texelBytes>(g.levelTexels, level, offset, out);
    return;
  }
  alignas(64) std::int32_t off[L::kWidth], lv[L::kWidth];
  offset.store_aligned(off);
  if (g.uniform >= 0) {
    const std::uint8_t* const base = g.table[g.uniform].texels;
    for (int k = 0; k < L::kWidth; ++k) out[k] = base + std::ptrdiff_t(off[k]) * texelBytes;
    return;
  }
  level.store_aligned(lv);
  for (int k = 0; k < L::kWidth; ++k)
    out[k] = g.table[lv[k]].texels + std::ptrdiff_t(off[k]) * texelBytes;
}

// One texel per lane (nearest filtering), decoded lane by lane.
template <class L, class R>
Rgba<L> fetch(const TextureView& view, const LevelGeometry<L>& g, const typename L::I& level,
              const typename L::F& x, const typename L::F& y) {
  const std::uint8_t* texel[L::kWidth];
  texelPointers<L, R>(g, level, texelOffset<L>(g, x, y), texel);
  alignas(64) float channel[4][L::kWidth];
  for (int k = 0; k < L::kWidth; ++k) {
    float rgba[4];
    decodeTexel(view.format, texel[k], rgba);
    for (int c = 0; c < 4; ++c) channel[c][k] = rgba[c];
  }
  using F = typename L::F;
  return {F::load_aligned(channel[0]), F::load_aligned(channel[1]), F::load_aligned(channel[2]),
          F::load_aligned(channel[3])};
}

// Four channel registers as lanes.
template <class L>
QUADRA_LANE_INLINE Rgba<L> fromRegisters(const typename L::F::register_type channel[4]) {
  return {channel[0], channel[1], channel[2], channel[3]};
}

template <class L, simd::PairEncoding kEncoding>
QUADRA_LANE_INLINE void transposeRowPairs(const std::uint8_t* const pair[L::kWidth], Rgba<L>& left,
                                          Rgba<L>& right) {
  typename L::F::register_type l[4], r[4];
  simd::transposeTexelPairs<kEncoding>(pair, l, r);
  left = fromRegisters<L>(l);
  right = fromRegisters<L>(r);
}

// rgba8srgb channel registers of codes (a Codes8 transpose) → values, as
// decodeTexel computes them: colour through the sRGB decode table, alpha
// code * kUnorm8Scale as in rgba8.
template <class L>
QUADRA_LANE_INLINE Rgba<L> decodeSrgb8(const TextureView& view,
                                       const typename L::F::register_type code[4]) {
  using F = typename L::F;
  const float* table = view.srgbTable;
  return {simd::lookupCodes(table, code[0]), simd::lookupCodes(table, code[1]),
          simd::lookupCodes(table, code[2]),
          simd::toFloat(simd::asInt(F(code[3]))) * F(kUnorm8Scale)};
}

// The left and right texels of one bilinear row per lane, as channel lanes:
// each lane reads its pair (texels x and x + 1, contiguous in a padded level)
// whole, decoded and transposed in registers (simd/texel_pairs.h). The
// gather variant (TexelRead<Rgba32F, true>) is the alternative the sampler
// benchmark measures per ISA; the pair loads won on both AVX2 and AVX-512 on
// an Intel Xeon and an AMD EPYC (Zen 5) VM (docs/texel-storage.md), and
// gathers are microcode-mitigated on many Intel parts, so they are the default.
template <class L, class R>
QUADRA_LANE_INLINE void fetchRowPairs(const TextureView& view, const LevelGeometry<L>& g,
                                      const typename L::I& level, const typename L::I& offset,
                                      Rgba<L>& left, Rgba<L>& right) {
  constexpr int W = L::kWidth;
  if constexpr (R::kGather && !kIsScalarLanes<L>) {
    if (g.uniform >= 0) {  // one base pointer for every lane
      typename L::F::register_type l[4], r[4];
      simd::gatherTexelPairs(reinterpret_cast<const float*>(g.table[g.uniform].texels),
                             typename L::I::register_type(offset), l, r);
      left = fromRegisters<L>(l);
      right = fromRegisters<L>(r);
      return;
    }
  }
  const std::uint8_t* pair[W];
  texelPointers<L, R>(g, level, offset, pair);
  if constexpr (kIsScalarLanes<L>) {
    for (int k = 0; k < W; ++k) {
      float l[4], r[4];
      decodeTexel(view.format, pair[k], l);
      decodeTexel(view.format, pair[k] + bytesPerTexel(R::kFormat), r);
      left.r.v[k] = l[0], left.g.v[k] = l[1], left.b.v[k] = l[2], left.a.v[k] = l[3];
      right.r.v[k] = r[0], right.g.v[k] = r[1], right.b.v[k] = r[2], right.a.v[k] = r[3];
    }
  } else if constexpr (R::kFormat == TexelFormat::Rgba32F) {
    transposeRowPairs<L, simd::PairEncoding::Float32>(pair, left, right);
  } else if constexpr (R::kFormat == TexelFormat::Rgba16F) {
    transposeRowPairs<L, simd::PairEncoding::Half>(pair, left, right);
  } else if constexpr (R::kFormat == TexelFormat::Rgba8Unorm) {
    transposeRowPairs<L, simd::PairEncoding::Unorm8>(pair, left, right);
  } else {
    typename L::F::register_type l[4], r[4];
    simd::transposeTexelPairs<simd::PairEncoding::Codes8>(pair, l, r);
    left = decodeSrgb8<L>(view, l);
    right = decodeSrgb8<L>(view, r);
  }
}

// Per lane: a where the mask is set, else b.
template <class L>
QUADRA_LANE_INLINE Rgba<L> selectRgba(const typename L::M& mask, const Rgba<L>& a,
                                      const Rgba<L>& b) {
  return {simd::select(mask, a.r, b.r), simd::select(mask, a.g, b.g), simd::select(mask, a.b, b.b),
          simd::select(mask, a.a, b.a)};
}

template <class L>
QUADRA_LANE_INLINE Rgba<L> withBorder(const TextureView& view, const Rgba<L>& c,
                                      const typename L::M& inside) {
  using F = typename L::F;
  const Rgba<L> border{F(view.border[0]), F(view.border[1]), F(view.border[2]), F(view.border[3])};
  return selectRgba<L>(inside, c, border);
}

template <class L>
QUADRA_LANE_INLINE Rgba<L> lerp(const Rgba<L>& p, const Rgba<L>& q, const typename L::F& t) {
  return {p.r + (q.r - p.r) * t, p.g + (q.g - p.g) * t, p.b + (q.b - p.b) * t,
          p.a + (q.a - p.a) * t};
}

}  // namespace sampling

// Nearest texel of the given level(s).
template <class L, class R>
Rgba<L> sampleNearest(const TextureView& view, typename L::F u, typename L::F v,
                      const typename L::I& level) {
  using namespace sampling;
  using F = typename L::F;
  const LevelGeometry<L> g = levelGeometry<L>(view.mipTable(), level);
  u = reduceCoordinate<L>(u, view.wrapU);
  v = reduceCoordinate<L>(v, view.wrapV);
  typename L::M inside = F(0.0f) == F(0.0f);
  const F x = wrapTexel<L>(simd::floor(u * g.width), g.width, view.wrapU, inside);
  const F y = wrapTexel<L>(simd::floor(v * g.height), g.height, view.wrapV, inside);
  return withBorder<L>(view, fetch<L, R>(view, g, level, x, y), inside);
}

// Bilinear reconstruction on the given level(s). Columns are read as pairs
// (x0, x0 + 1) of a padded level, so x0 is brought into [0, width - 1]:
// repeat wraps it (x0 + 1 = width reads the padding copy of column 0); clamp
// clamps the coordinate to [0, width - 1] (at the edge the right texel gets
// weight 0, which equals reading the edge texel twice); mirrored repeat is
// clamp on the folded coordinate (the bilinear reconstruction of a mirrored
// row is symmetric about each fold); border reads the pair at the clamped
// column and substitutes the border colour where a texel lies outside.
// `level` indexes g.table: the mip levels, or a ripmap's; g holds their sizes.
// The four texels around (u, v) and the fractions between them.
template <class L>
struct BilinearCorners {
  Rgba<L> c00, c10, c01, c11;
  typename L::F fx, fy;
};

template <class L, class R>
QUADRA_LANE_INLINE BilinearCorners<L> bilinearCorners(const TextureView& view,
                                                      const sampling::LevelGeometry<L>& g,
                                                      const typename L::I& level, typename L::F u,
                                                      typename L::F v) {
  using namespace sampling;
  using F = typename L::F;
  using M = typename L::M;
  u = reduceCoordinate<L>(u, view.wrapU);
  v = reduceCoordinate<L>(v, view.wrapV);
  if (view.wrapU == WrapMode::MirroredRepeat) u = simd::select(u > F(1.0f), F(2.0f) - u, u);
  F tx = u * g.width - F(0.5f);
  const F lastColumn = g.width - F(1.0f);
  if (view.wrapU == WrapMode::ClampToEdge || view.wrapU == WrapMode::MirroredRepeat)
    tx = simd::max(simd::min(tx, lastColumn), F(0.0f));
  const F ty = v * g.height - F(0.5f);
  const F fx0 = simd::floor(tx), fy0 = simd::floor(ty);
  const F fx = tx - fx0, fy = ty - fy0;

  F x0 = fx0;
  if (view.wrapU == WrapMode::Repeat) x0 = simd::select(fx0 < F(0.0f), fx0 + g.width, fx0);
  if (view.wrapU == WrapMode::ClampToBorder) x0 = simd::max(simd::min(fx0, lastColumn), F(0.0f));
  const M all = F(0.0f) == F(0.0f);
  M inY0 = all, inY1 = all;
  const F y0 = wrapTexel<L>(fy0, g.height, view.wrapV, inY0);
  const F y1 = wrapTexel<L>(fy0 + F(1.0f), g.height, view.wrapV, inY1);
  Rgba<L> c00, c10, c01, c11;
  fetchRowPairs<L, R>(view, g, level, texelOffset<L>(g, x0, y0), c00, c10);
  fetchRowPairs<L, R>(view, g, level, texelOffset<L>(g, x0, y1), c01, c11);

  if (view.wrapU == WrapMode::ClampToBorder || view.wrapV == WrapMode::ClampToBorder) {
    M inX0 = all, inX1 = all;
    if (view.wrapU == WrapMode::ClampToBorder) {
      inX0 = (fx0 >= F(0.0f)) & (fx0 <= lastColumn);
      inX1 = (fx0 >= F(-1.0f)) & (fx0 < lastColumn);
      // fx0 = -1 read the pair at column 0: its right texel is that left one.
      const M beforeFirst = fx0 < F(0.0f);
      c10 = selectRgba<L>(beforeFirst, c00, c10);
      c11 = selectRgba<L>(beforeFirst, c01, c11);
    }
    c00 = withBorder<L>(view, c00, inX0 & inY0);
    c10 = withBorder<L>(view, c10, inX1 & inY0);
    c01 = withBorder<L>(view, c01, inX0 & inY1);
    c11 = withBorder<L>(view, c11, inX1 & inY1);
  }
  return {c00, c10, c01, c11, fx, fy};
}

template <class L, class R>
QUADRA_LANE_INLINE Rgba<L> sampleBilinearOn(const TextureView& view,
                                            const sampling::LevelGeometry<L>& g,
                                            const typename L::I& level, const typename L::F& u,
                                            const typename L::F& v) {
  using sampling::lerp;
  const BilinearCorners<L> b = bilinearCorners<L, R>(view, g, level, u, v);
  return lerp<L>(lerp<L>(b.c00, b.c10, b.fx), lerp<L>(b.c01, b.c11, b.fx), b.fy);
}

template <class L, class R>
QUADRA_LANE_INLINE Rgba<L> sampleBilinearIn(const TextureView& view, const LevelTable& table,
                                            const typename L::F& u, const typename L::F& v,
                                            const typename L::I& level) {
  return sampleBilinearOn<L, R>(view, sampling::levelGeometry<L>(table, level), level, u, v);
}

template <class L, class R>
QUADRA_LANE_INLINE Rgba<L> sampleBilinear(const TextureView& view, const typename L::F& u,
                                          const typename L::F& v, const typename L::I& level) {
  return sampleBilinearIn<L, R>(view, view.mipTable(), u, v, level);
}

// Squared length of the footprint's longer side in level-0 texels: the LOD
// of the isotropic filters is half its log2.
template <class L>
QUADRA_LANE_INLINE typename L::F isotropicLengthSq(const TextureView& view,
                                                   const UvDerivatives<L>& d) {
  using F = typename L::F;
  const F w = F(float(view.levels[0].width)), h = F(float(view.levels[0].height));
  const F xu = d.dudx * w, xv = d.dvdx * h, yu = d.dudy * w, yv = d.dvdy * h;
  return simd::max(xu * xu + xv * xv, yu * yu + yv * yv);
}

// The view's LOD controls: clamp(λ + bias, minLod, maxLod); NaN becomes minLod.
template <class L>
QUADRA_LANE_INLINE typename L::F controlledLod(const TextureView& view, const typename L::F& lod) {
  using F = typename L::F;
  return simd::min(simd::max(lod + F(view.lodBias), F(view.minLod)), F(view.maxLod));
}

// The isotropic filters' λ' from the squared footprint length: the LOD
// controls applied to half its log2, and at most 0 where the length alone
// shows the lookup magnified (so rounding in the log2 cannot move that decision).
template <class L>
QUADRA_LANE_INLINE typename L::F isotropicLod(const TextureView& view,
                                              const typename L::F& lengthSq) {
  using F = typename L::F;
  const F lod = controlledLod<L>(view, F(0.5f) * simd::log2<L>(lengthSq));
  return simd::select(lengthSq <= F(view.magnifiedLengthSq), simd::min(lod, F(0.0f)), lod);
}

// The level a mip filter reads at λ': λ' within the chain [0, last level].
template <class L>
QUADRA_LANE_INLINE typename L::F levelRead(const TextureView& view, const typename L::F& lod) {
  using F = typename L::F;
  return simd::min(simd::max(lod, F(0.0f)), F(float(view.levelCount - 1)));  // max(NaN, 0) is 0
}

// One mip level per lane, filtered within the level as view.minLinear says:
// bilinear, or the nearest texel.
template <class L, class R>
QUADRA_LANE_INLINE Rgba<L> sampleWithinLevel(const TextureView& view, const typename L::F& u,
                                             const typename L::F& v, const typename L::I& level) {
  return view.minLinear ? sampleBilinear<L, R>(view, u, v, level)
                        : sampleNearest<L, R>(view, u, v, level);
}

// Trilinear (or nearest-mip) at LOD λ; λ <= 0 is magnification.
template <class L, class R>
QUADRA_LANE_INLINE Rgba<L> sampleMipmapped(const TextureView& view, const typename L::F& u,
                                           const typename L::F& v, typename L::F lod,
                                           bool linearBetweenLevels) {
  using F = typename L::F;
  using I = typename L::I;
  lod = levelRead<L>(view, lod);
  if (!linearBetweenLevels) {
    const I level = simd::toInt(simd::floor(lod + F(0.5f)));
    return sampleWithinLevel<L, R>(view, u, v, simd::min(level, I(view.levelCount - 1)));
  }
  const F levelFloor = simd::floor(lod);
  const F t = lod - levelFloor;
  const I level0 = simd::toInt(levelFloor);
  const I level1 = simd::min(level0 + I(1), I(view.levelCount - 1));
  const Rgba<L> fine = sampleWithinLevel<L, R>(view, u, v, level0);
  if (!simd::any(t > F(0.0f))) return fine;
  const Rgba<L> coarse = sampleWithinLevel<L, R>(view, u, v, level1);
  return sampling::lerp<L>(fine, coarse, t);
}

namespace aniso {

// One level's share of a lookup: its taps, their count, the level and its size.
template <class L>
struct Run {
  typename L::F taps, invTaps;
  // Tap j's weight is scale * clamp((1/2 - |o_j|) * invRamp, 0, 1): scale is
  // the run's share of the blend over the sum of its ramp weights, so the
  // weights of a lookup's taps add up to 1 and no division is left for the end.
  typename L::F scale;
  typename L::F level, width, height, stride;  // float: exact below 2^24, and selectable
};

template <class L>
struct Plan {
  typename L::F u, v;
  // Tap j of n sits at (u, v) + line * o_j, o_j = (j + 1/2) / n - 1/2.
  typename L::F lineU, lineV, invRamp;
  typename L::F blend;  // run 1's share (the coarser level); 0 where there is one run
  Run<L> run[2];
};

// Level l of the chain is max(1, floor(w / 2^l)) texels wide (texture/mip_chain.h)
// and padded to width + 1 (texture/padded_level.h): computed, not looked up
// lane by lane.
template <class L>
QUADRA_LANE_INLINE Run<L> levelRun(const TextureView& view, const typename L::F& level,
                                   const typename L::F& taps) {
  using F = typename L::F;
  using I = typename L::I;
  const F shrink = simd::asFloat((I(127) - simd::toInt(level)) << 23);  // 2^-level, exact
  const F width = simd::max(simd::floor(F(float(view.levels[0].width)) * shrink), F(1.0f));
  const F height = simd::max(simd::floor(F(float(view.levels[0].height)) * shrink), F(1.0f));
  return {taps, F(1.0f) / taps, F(0.0f), level, width, height, width + F(1.0f)};
}

// The sum of the ramp weights min(max((1/2 - |o_j|) * invRamp, 0), 1) of a
// run's n taps, in closed form: with d_j = min(j + 1/2, n - j - 1/2) the
// weights are min(d_j invRamp / n, 1), symmetric about the centre (whose
// weight is 1, as invRamp >= 2); the J smallest d_j of each half, those
// below n ramp, ramp up (they sum to invRamp J^2 / (2 n)), the rest weigh 1.
template <class L>
QUADRA_LANE_INLINE typename L::F rampWeightSum(const Run<L>& run, const typename L::F& ramp,
                                               const typename L::F& invRamp) {
  using F = typename L::F;
  const F half = simd::floor(run.taps * F(0.5f));
  const F x = run.taps * ramp - F(0.5f);
  F below = simd::floor(x);
  below = simd::select(x > below, below + F(1.0f), below);  // ceil
  below = simd::min(simd::max(below, F(0.0f)), half);
  return below * below * invRamp * run.invTaps + F(2.0f) * (half - below) +
         (run.taps - half - half);
}

// 2^-k for integer-valued k in [0, 126], exactly, from the exponent bits.
template <class L>
QUADRA_LANE_INLINE typename L::F exp2Negative(const typename L::F& k) {
  using I = typename L::I;
  return simd::asFloat((I(127) - simd::toInt(k)) << 23);
}

// The footprint's axes, its probe count N and its level: the first steps of
// the plan, and what the lod and anisotropy AOVs report.
template <class L>
struct Footprint {
  typename L::M finite;        // else the Jacobian reads as a point
  typename L::F ex, ey;        // the major axis' unit screen-space direction
  typename L::F major, minor;  // the singular values, level-0 texels
  typename L::F probes;        // N in [1, maxAniso]
  typename L::F lod;           // λ = log2(major / N), before the LOD controls
  typename L::F read;          // λ' within the chain: the level the runs are placed by
  typename L::F maxAniso, lastLevel;
};

template <class L>
QUADRA_LANE_INLINE Footprint<L> footprint(const TextureView& view, const UvDerivatives<L>& d) {
  using F = typename L::F;
  // The footprint's axes: J^T J = [[p, q], [q, r]] has the squared singular
  // values as eigenvalues. A non-finite Jacobian (NaN, infinite, or too large
  // to square) reads as a point.
  const F w = F(float(view.levels[0].width)), h = F(float(view.levels[0].height));
  F xu = d.dudx * w, xv = d.dvdx * h, yu = d.dudy * w, yv = d.dvdy * h;
  const auto finite = (xu * xu + xv * xv) + (yu * yu + yv * yv) < F(3.0e38f);
  xu = simd::select(finite, xu, F(0.0f)), xv = simd::select(finite, xv, F(0.0f));
  yu = simd::select(finite, yu, F(0.0f)), yv = simd::select(finite, yv, F(0.0f));
  const F p = xu * xu + xv * xv, q = xu * yu + xv * yv, r = yu * yu + yv * yv;
  const F halfSum = F(0.5f) * (p + r), halfDiff = F(0.5f) * (p - r);
  const F root = simd::sqrt(halfDiff * halfDiff + q * q);
  const F majorSq = halfSum + root;
  const F minorSq = simd::max(halfSum - root, F(0.0f));
  // The major eigenvector (ex, ey), in screen space; the stabler form of two.
  const auto pBigger = p >= r;
  F ex = simd::select(pBigger, majorSq - r, q);
  F ey = simd::select(pBigger, q, majorSq - p);
  const F eLen = simd::sqrt(ex * ex + ey * ey);
  const auto degenerate = ~(eLen > F(0.0f));
  const F invLen = F(1.0f) / eLen;
  ex = simd::select(degenerate, F(1.0f), ex * invLen);
  ey = simd::select(degenerate, F(0.0f), ey * invLen);
  const F major = simd::sqrt(majorSq), minor = simd::sqrt(minorSq);

  // N in [1, maxAniso] (minor == 0 gives the cap, major == 0 one probe) and
  // λ = log2(major / N), as a difference of logs: off the ratio's division,
  // whose latency the whole plan would wait on.
  const F maxAniso = F(float(std::clamp(view.maxAniso, 1, 64)));
  const F ratio = major / simd::max(minor, F(1e-30f));
  F probes = simd::floor(ratio);
  probes = simd::select(ratio > probes, probes + F(1.0f), probes);
  probes = simd::max(simd::min(probes, maxAniso), F(1.0f));
  const F lod = F(0.5f) * simd::log2<L>(majorSq) - simd::log2<L>(probes);  // -63 for a point
  const F read = levelRead<L>(view, controlledLod<L>(view, lod));
  const F lastLevel = F(float(view.levelCount - 1));
  return {finite, ex, ey, major, minor, probes, lod, read, maxAniso, lastLevel};
}

// The plan of every lane's lookup: texture/anisotropic.h, step by step.
template <class L>
QUADRA_LANE_INLINE Plan<L> planAnisotropic(const TextureView& view, const typename L::F& u,
                                           const typename L::F& v, const UvDerivatives<L>& d) {
  using F = typename L::F;
  const Footprint<L> f = footprint<L>(view, d);
  const auto finite = f.finite;
  const F ex = f.ex, ey = f.ey, major = f.major, minor = f.minor, probes = f.probes, lod = f.lod;
  const F read = f.read, maxAniso = f.maxAniso, lastLevel = f.lastLevel;

  // The levels read: both around λ below kBlendBelowRatio (and always where
  // maxAniso is below it), else the nearest.
  const auto blend = (major < F(kBlendBelowRatio) * minor) | (maxAniso < F(kBlendBelowRatio));
  const F fine = simd::floor(read);
  const F nearest = simd::min(simd::floor(read + F(0.5f)), lastLevel);
  Plan<L> plan;
  plan.blend = simd::select(blend, read - fine, F(0.0f));
  const F level0 = simd::select(blend, fine, nearest);
  const F level1 = simd::min(fine + F(1.0f), lastLevel);

  // The line the taps lie on, as a multiple of major: the shadow (a + b) or,
  // blended, major itself.
  const F shadow = simd::select(blend, F(1.0f), simd::abs(ex) + simd::abs(ey));
  // Spans of the tap spacing along that line (the coarser level has half as
  // many). While magnified the spacing is major / kMagnifiedTaps, clamped to
  // [major / N, 1]: shadow / spacing = shadow min(N, max(kMagnifiedTaps,
  // major)). Else a texel of level floor(λ) (blended) or round(λ).
  const auto magnified = lod < F(0.0f);
  const F naturalLevel = simd::select(blend, simd::floor(lod), simd::floor(lod + F(0.5f)));
  const F spans0 =
      simd::select(magnified, shadow * simd::min(probes, simd::max(F(kMagnifiedTaps), major)),
                   major * shadow *
                       exp2Negative<L>(simd::min(simd::max(naturalLevel, F(0.0f)), F(126.0f)))) *
      simd::select(blend, F(1.0f / kBlendedTapSpacing), F(1.0f / kTapSpacing));
  const F spans1 = simd::select(magnified, spans0, spans0 * F(0.5f));
  // Taps per run: ceil(spans), rounded up to whole chunks beyond a single tap
  // (a lane runs kChunk taps either way: the extra one is free accuracy).
  auto ceil = [](const F& x) {
    const F n = simd::floor(x);
    return simd::select(x > n, n + F(1.0f), n);
  };
  auto tapsFor = [&](const F& spans) {
    const F n = ceil(spans);
    const F chunks = ceil(n * F(1.0f / float(kChunk))) * F(float(kChunk));
    return simd::max(simd::min(simd::select(n > F(1.0f), chunks, n), F(kMaxTapsPerRun)), F(1.0f));
  };
  plan.run[0] = levelRun<L>(view, level0, tapsFor(spans0));
  plan.run[1] =
      levelRun<L>(view, level1, simd::select(plan.blend > F(0.0f), tapsFor(spans1), F(0.0f)));

  // The centre brought within a period for the periodic wraps (exactly: u
  // and floor(u) are close), so the taps' small offsets keep their bits far
  // from the origin and u + 10000 samples as u does; the clamp modes keep it
  // where it is (a clamped centre would move the taps back over the texture).
  auto periodic = [](const F& x, WrapMode mode) {
    if (mode == WrapMode::Repeat) return x - simd::floor(x);
    if (mode == WrapMode::MirroredRepeat) return x - F(2.0f) * simd::floor(x * F(0.5f));
    return x;
  };
  plan.u = periodic(u, view.wrapU), plan.v = periodic(v, view.wrapV);
  // The line in uv (normalized texture units): the major axis J (ex, ey) times it.
  plan.lineU = simd::select(finite, (d.dudx * ex + d.dudy * ey) * shadow, F(0.0f));
  plan.lineV = simd::select(finite, (d.dvdx * ex + d.dvdy * ey) * shadow, F(0.0f));
  // The trapezoid's ramps over the line: min(|ex|, |ey|) / (|ex| + |ey|) <= 1/2,
  // so a lone centre tap always weighs exactly 1; blended, no ramps (a box).
  const F rampWidth = simd::max(simd::min(simd::abs(ex), simd::abs(ey)), F(1e-6f));
  const F ramp = simd::select(blend, F(1e-6f), rampWidth / shadow);
  plan.invRamp = simd::select(blend, F(1e6f), shadow / rampWidth);
  plan.run[0].scale = (F(1.0f) - plan.blend) / rampWeightSum<L>(plan.run[0], ramp, plan.invRamp);
  plan.run[1].scale =
      simd::select(plan.run[1].taps > F(0.0f),
                   plan.blend / rampWeightSum<L>(plan.run[1], ramp, plan.invRamp), F(0.0f));
  return plan;
}

}  // namespace aniso

namespace aniso {

// One tap, weighted: the bilinear weights times the tap's own, four products
// per channel instead of three lerps and a product.
template <class L, class R>
QUADRA_LANE_INLINE Rgba<L> weightedTap(const TextureView& view, const sampling::LevelGeometry<L>& g,
                                       const typename L::I& level, const typename L::F& u,
                                       const typename L::F& v, const typename L::F& weight) {
  using F = typename L::F;
  const BilinearCorners<L> b = bilinearCorners<L, R>(view, g, level, u, v);
  const F right = weight * b.fx, left = weight - right;
  const F w11 = right * b.fy, w01 = left * b.fy, w10 = right - w11, w00 = left - w01;
  return {b.c00.r * w00 + b.c10.r * w10 + (b.c01.r * w01 + b.c11.r * w11),
          b.c00.g * w00 + b.c10.g * w10 + (b.c01.g * w01 + b.c11.g * w11),
          b.c00.b * w00 + b.c10.b * w10 + (b.c01.b * w01 + b.c11.b * w11),
          b.c00.a * w00 + b.c10.a * w10 + (b.c01.a * w01 + b.c11.a * w11)};
}

}  // namespace aniso

// Anisotropic filtering: weighted bilinear taps along the footprint's major
// axis on the level that fits its minor axis (texture/anisotropic.h), each
// lookup paying for its own taps only.
template <class L, class R>
Rgba<L> sampleAnisotropic(const TextureView& view, const typename L::F& u, const typename L::F& v,
                          const UvDerivatives<L>& d) {
  using F = typename L::F;
  using I = typename L::I;
  constexpr int W = L::kWidth;
  const aniso::Plan<L> plan = aniso::planAnisotropic<L>(view, u, v, d);
  const aniso::Run<L>& run0 = plan.run[0];
  // A group of single taps without blending (deep magnification): each the
  // one tap at the centre, weight 1, as the packed path below computes it.
  if (simd::all((run0.taps == F(1.0f)) & (plan.blend == F(0.0f)))) {
    const I level = simd::toInt(run0.level);
    return aniso::weightedTap<L, R>(view, sampling::levelGeometry<L>(view.mipTable(), level), level,
                                    u, v, F(1.0f));
  }

  // The taps, packed densely: job j is kChunk consecutive taps of one run of one
  // lookup, and W jobs run side by side whatever lookups they belong to, so no
  // lane idles while another lookup finishes (on the report's stream the most
  // taps of 16 lookups average 20.0, the taps 8.8). Jobs come in segments, one
  // per chunk start `first` and run: the lookups with taps left there.
  constexpr int kMaxSegments =
      2 * ((int(aniso::kMaxTapsPerRun) + aniso::kChunk - 1) / aniso::kChunk);
  constexpr int kMaxJobs = kMaxSegments * W + W;  // + a padding batch
  std::uint32_t segmentLanes[kMaxSegments];
  // Job j: lookup jobRun[j] % W, run jobRun[j] / W, taps from jobFirst[j] on.
  alignas(64) std::int32_t jobRun[kMaxJobs + W];
  alignas(64) float jobFirst[kMaxJobs + W];
  // Run 0's segments, then run 1's: the order jobs run in does not change any
  // bits, only the order each lookup's partial sums are added in does.
  int segments = 0, jobs = 0;
  for (int r = 0; r < 2; ++r) {
    for (float first = 0.0f;; first += float(aniso::kChunk)) {
      const std::uint32_t lanes = simd::bits(plan.run[r].taps > F(first));
      if (lanes == 0) break;
      segmentLanes[segments++] = lanes;
      simd::compressLaneIndices<L>(lanes, r * W, jobRun + jobs);
      F(first).store_unaligned(jobFirst + jobs);
      jobs += __builtin_popcount(lanes);
    }
  }
  // Idle lanes of the last batch run a tap of lookup 0 whose sums are never read.
  I(0).store_unaligned(jobRun + jobs);
  F(0.0f).store_unaligned(jobFirst + jobs);

  // Each job's weighted sums (r, g, b, a), in job order.
  alignas(64) float partial[4][kMaxJobs + W];
  static_assert(TextureView::kMaxLevels == 16, "simd::laneAddresses looks up 16 levels");
  alignas(64) const std::uint8_t* levelTexels[TextureView::kMaxLevels];
  for (int l = 0; l < TextureView::kMaxLevels; ++l)
    levelTexels[l] = view.levels[std::min(l, view.levelCount - 1)].texels;
  for (int batch = 0; batch < jobs; batch += W) {
    const I run = I::load_aligned(jobRun + batch);
    const I lookup = run & I(W - 1);
    const F first = F::load_aligned(jobFirst + batch);
    auto pick = [&](const F& a, const F& b) { return simd::permute2(a, b, run); };
    const F taps = pick(plan.run[0].taps, plan.run[1].taps);
    const F invTaps = pick(plan.run[0].invTaps, plan.run[1].invTaps);
    const F scale = pick(plan.run[0].scale, plan.run[1].scale);
    const F levelF = pick(plan.run[0].level, plan.run[1].level);
    const I level = simd::toInt(levelF);
    // Every batch looks its lanes' level pointers up (simd::laneAddresses),
    // even when they share one level: here that beat testing for one level
    // and its scalar loop (128² stream: AVX-512 47.2 -> 46.4 ns a lookup,
    // AVX2 64.1 -> 61.4; trilinear keeps the loop, which is faster there).
    const sampling::LevelGeometry<L> g{pick(plan.run[0].width, plan.run[1].width),
                                       pick(plan.run[0].height, plan.run[1].height),
                                       simd::toInt(pick(plan.run[0].stride, plan.run[1].stride)),
                                       -1,
                                       view.levels,
                                       levelTexels};
    const F cu = simd::permute(plan.u, lookup), cv = simd::permute(plan.v, lookup);
    const F lineU = simd::permute(plan.lineU, lookup), lineV = simd::permute(plan.lineV, lookup);
    const F invRamp = simd::permute(plan.invRamp, lookup);
    Rgba<L> acc{F(0.0f), F(0.0f), F(0.0f), F(0.0f)};
    for (int i = 0; i < aniso::kChunk; ++i) {
      const F tap = first + F(float(i));
      const F o = (tap + F(0.5f)) * invTaps - F(0.5f);
      const F ramp = simd::min(simd::max((F(0.5f) - simd::abs(o)) * invRamp, F(0.0f)), F(1.0f));
      const F weight = simd::select(tap < taps, ramp * scale, F(0.0f));
      const Rgba<L> c =
          aniso::weightedTap<L, R>(view, g, level, cu + lineU * o, cv + lineV * o, weight);
      acc.r = acc.r + c.r;
      acc.g = acc.g + c.g;
      acc.b = acc.b + c.b;
      acc.a = acc.a + c.a;
    }
    acc.r.store_aligned(partial[0] + batch);
    acc.g.store_aligned(partial[1] + batch);
    acc.b.store_aligned(partial[2] + batch);
    acc.a.store_aligned(partial[3] + batch);
  }
  const int computed = (jobs + W - 1) / W * W;  // the block after the last is read too
  for (int c = 0; c < 4; ++c) F(0.0f).store_aligned(partial[c] + computed);

  // The partial sums back to their lookups, segment by segment (run 0's, then
  // run 1's): each lookup's in the order of its taps on every path.
  Rgba<L> sum{F(0.0f), F(0.0f), F(0.0f), F(0.0f)};
  for (int s = 0, at = 0; s < segments; ++s) {
    const std::uint32_t lanes = segmentLanes[s];
    const int block = at / W * W, offset = at - block;
    sum.r = sum.r + simd::expandLoad<L>(lanes, partial[0] + block, offset);
    sum.g = sum.g + simd::expandLoad<L>(lanes, partial[1] + block, offset);
    sum.b = sum.b + simd::expandLoad<L>(lanes, partial[2] + block, offset);
    sum.a = sum.a + simd::expandLoad<L>(lanes, partial[3] + block, offset);
    at += __builtin_popcount(lanes);
  }
  return sum;
}

// Ripmap (texture/ripmap.h): a level per axis from the footprint's extent
// along it (λu = log2 of the length of the Jacobian's u row in texels, λv of
// its v row: for an axis-aligned footprint its side lengths), under the view's
// LOD controls; the four levels around (λu, λv) blended bilinearly.
template <class L>
struct RipmapLevels {
  typename L::F lodU, lodV;  // within [0, ripCountX - 1] and [0, ripCountY - 1]
};

template <class L>
QUADRA_LANE_INLINE RipmapLevels<L> ripmapLevels(const TextureView& view,
                                                const UvDerivatives<L>& d) {
  using F = typename L::F;
  const F w = F(float(view.levels[0].width)), h = F(float(view.levels[0].height));
  const F xu = d.dudx * w, yu = d.dudy * w, xv = d.dvdx * h, yv = d.dvdy * h;
  auto axisLod = [&](const F& lengthSq, int count) {  // simd::max(NaN, 0) is 0: level 0
    const F lod = controlledLod<L>(view, F(0.5f) * simd::log2<L>(lengthSq));
    return simd::min(simd::max(lod, F(0.0f)), F(float(count - 1)));
  };
  return {axisLod(xu * xu + yu * yu, view.ripCountX), axisLod(xv * xv + yv * yv, view.ripCountY)};
}

template <class L, class R>
Rgba<L> sampleRipmap(const TextureView& view, const typename L::F& u, const typename L::F& v,
                     const UvDerivatives<L>& d) {
  using F = typename L::F;
  using I = typename L::I;
  const RipmapLevels<L> levels = ripmapLevels<L>(view, d);
  const F lodU = levels.lodU, lodV = levels.lodV;
  const F floorU = simd::floor(lodU), floorV = simd::floor(lodV);
  const F tu = lodU - floorU, tv = lodV - floorV;
  const I i0 = simd::toInt(floorU), j0 = simd::toInt(floorV);
  const I i1 = simd::min(i0 + I(1), I(view.ripCountX - 1));
  const I j1 = simd::min(j0 + I(1), I(view.ripCountY - 1));
  const LevelTable table = view.ripTable();
  const I countX(view.ripCountX);
  // One row of the blend: levels (i0, j) and (i1, j), the second only when a lane needs it.
  auto row = [&](const I& j) {
    const Rgba<L> left = sampleBilinearIn<L, R>(view, table, u, v, j * countX + i0);
    if (!simd::any(tu > F(0.0f))) return left;
    return sampling::lerp<L>(left, sampleBilinearIn<L, R>(view, table, u, v, j * countX + i1), tu);
  };
  const Rgba<L> first = row(j0);
  if (!simd::any(tv > F(0.0f))) return first;
  return sampling::lerp<L>(first, row(j1), tv);
}

// A lane group's lookups in memory, for the filters that work lookup by
// lookup (EWA, area).
template <class L>
struct LaneLookups {
  alignas(64) float u[L::kWidth], v[L::kWidth], dudx[L::kWidth], dvdx[L::kWidth], dudy[L::kWidth],
      dvdy[L::kWidth];

  LaneLookups(const typename L::F& us, const typename L::F& vs, const UvDerivatives<L>& d) {
    us.store_aligned(u);
    vs.store_aligned(v);
    d.dudx.store_aligned(dudx);
    d.dvdx.store_aligned(dvdx);
    d.dudy.store_aligned(dudy);
    d.dvdy.store_aligned(dvdy);
  }
};

// A filter that works lookup by lookup in scalar code compiled once (EWA's
// plan): `lookup(k, rgba)` fills lane k. Their per-lookup
// work varies with the footprint, so lanes would mostly wait on each other;
// and one compiled copy gives every ISA path the same bits.
template <class L, class LaneLookup>
Rgba<L> sampleEachLane(const LaneLookup& lookup) {
  constexpr int W = L::kWidth;
  alignas(64) float out[4][W];
  for (int k = 0; k < W; ++k) {
    float rgba[4];
    lookup(k, rgba);
    for (int c = 0; c < 4; ++c) out[c][k] = rgba[c];
  }
  using F = typename L::F;
  return {F::load_aligned(out[0]), F::load_aligned(out[1]), F::load_aligned(out[2]),
          F::load_aligned(out[3])};
}

namespace ewa {

// exp(-2 x) - exp(-2) for x in [0, 1), else 0: kEwaShape's weight (ewa.h) of
// r^2 = x. A polynomial of degree 7 fitted at Chebyshev nodes (error below
// 8e-8 before float rounding), evaluated by Estrin's scheme: exactly rounded
// operations only, the same bits on every path, where std::exp per sample
// was the scalar loop's largest cost; a weight table would need a gather
// per lane (slow on this Zen, docs/texel-storage.md) or a per-ISA permute.
static_assert(kEwaShape.alpha == 2.0 && kEwaShape.zeroAtRim, "the polynomial is this shape's");
template <class L>
QUADRA_LANE_INLINE typename L::F weight(const typename L::F& x) {
  using F = typename L::F;
  const F x2 = x * x, x4 = x2 * x2;
  const F p01 = F(0.999999922f) + x * F(-1.99998992f);
  const F p23 = F(1.99978404f) + x * F(-1.33155871f);
  const F p45 = F(0.659425989f) + x * F(-0.25031036f);
  const F p67 = F(0.067623278f) + x * F(-0.00963902684f);
  const F e = (p01 + x2 * p23) + x4 * (p45 + x2 * p67);
  return simd::select(x < F(1.0f), e - F(0.135335283f), F(0.0f));
}

// Sums of weighted samples in a fixed order whatever the lane width: sample
// j goes to virtual lane j mod 16 (a register of 16 lanes, two of 8, or four
// of 4, in turn), and the 16 virtual sums are added by one fixed tree.
template <class L>
struct FixedOrderSum {
  using F = typename L::F;
  static constexpr int kTurns = 16 / L::kWidth;
  static_assert(kTurns * L::kWidth == 16, "lane widths divide 16");
  F sum[kTurns][5];
  int turn = 0;

  FixedOrderSum() {
    for (auto& t : sum)
      for (F& s : t) s = F(0.0f);
  }
  void add(const Rgba<L>& c, const F& w) {
    F* s = sum[turn];
    s[0] = s[0] + c.r * w, s[1] = s[1] + c.g * w, s[2] = s[2] + c.b * w, s[3] = s[3] + c.a * w;
    s[4] = s[4] + w;
    turn = turn + 1 == kTurns ? 0 : turn + 1;
  }
  // The weighted mean (0 where no sample weighed anything).
  void mean(float rgba[4]) const {
    alignas(64) float lane[5][16];
    for (int t = 0; t < kTurns; ++t)
      for (int c = 0; c < 5; ++c) sum[t][c].store_aligned(&lane[c][t * L::kWidth]);
    for (int half = 8; half >= 1; half /= 2)
      for (int c = 0; c < 5; ++c)
        for (int k = 0; k < half; ++k) lane[c][k] = lane[c][k] + lane[c][k + half];
    for (int c = 0; c < 4; ++c) rgba[c] = lane[4][0] > 0.0f ? lane[c][0] / lane[4][0] : 0.0f;
  }
};

// Integer-valued texel coordinates anywhere → inside [0, n) per the wrap
// mode; `inside` is cleared where the border colour applies.
template <class L>
QUADRA_LANE_INLINE typename L::F wrapAnywhere(typename L::F x, const typename L::F& n,
                                              WrapMode mode, typename L::M& inside) {
  using F = typename L::F;
  if (mode == WrapMode::Repeat || mode == WrapMode::MirroredRepeat) {
    const F period = mode == WrapMode::Repeat ? n : n + n;
    x = x - period * simd::floor(x / period);
    x = simd::select(x < F(0.0f), x + period, x);  // float division's last-bit slips
    x = simd::select(x >= period, x - period, x);
    if (mode == WrapMode::MirroredRepeat) x = simd::select(x >= n, period - F(1.0f) - x, x);
    return x;
  }
  if (mode == WrapMode::ClampToBorder) inside = inside & (x >= F(0.0f)) & (x <= n - F(1.0f));
  return simd::max(simd::min(x, n - F(1.0f)), F(0.0f));
}

}  // namespace ewa

// EWA (texture/ewa.h): each lane's lookup planned in scalar code compiled
// once, its samples summed W at a time in a fixed order.
template <class L, class R>
Rgba<L> sampleEwa(const TextureView& view, const typename L::F& u, const typename L::F& v,
                  const UvDerivatives<L>& d) {
  using F = typename L::F;
  using I = typename L::I;
  constexpr int W = L::kWidth;
  const LaneLookups<L> in(u, v, d);
  alignas(64) float laneIndex[W];
  for (int k = 0; k < W; ++k) laneIndex[k] = float(k);
  const F lanes = F::load_aligned(laneIndex);
  return sampleEachLane<L>([&](int k, float rgba[4]) {
    const EwaPlan plan =
        planEwa(view, in.u[k], in.v[k], in.dudx[k], in.dvdx[k], in.dudy[k], in.dvdy[k]);
    ewa::FixedOrderSum<L> sum;
    if (plan.grid) {
      // Sample n of the grid: column n mod columns, row n div columns.
      const int samples = plan.columns * plan.rows;
      const F columns = F(float(plan.columns)), rows = F(float(plan.rows));
      const I level0(0);
      for (int first = 0; first < samples; first += W) {
        const F n = lanes + F(float(first));
        const F row = simd::floor((n + F(0.5f)) / columns);
        const F column = n - row * columns;
        const F a = ((column + F(0.5f)) / columns - F(0.5f)) * F(2.0f);
        const F b = ((row + F(0.5f)) / rows - F(0.5f)) * F(2.0f);
        const F w = simd::select(n < F(float(samples)), ewa::weight<L>(a * a + b * b), F(0.0f));
        sum.add(sampleBilinear<L, R>(view, F(plan.u) + a * F(plan.axisAu) + b * F(plan.axisBu),
                                     F(plan.v) + a * F(plan.axisAv) + b * F(plan.axisBv), level0),
                w);
      }
      sum.mean(rgba);
      return;
    }
    // Texel centres, row by row inside the ellipse, W at a time.
    const I level(plan.level);
    const sampling::LevelGeometry<L> g = sampling::levelGeometry<L>(view.mipTable(), level);
    alignas(64) float xs[W], ys[W];
    int count = 0;
    auto flush = [&]() {
      for (int j = count; j < W; ++j) xs[j] = xs[0], ys[j] = ys[0];
      const F x = F::load_aligned(xs), y = F::load_aligned(ys);
      const F dx = x - F(plan.cx), dy = y - F(plan.cy);
      const F r2 = F(plan.qa) * dx * dx + F(plan.qb) * dx * dy + F(plan.qc) * dy * dy;
      const F w = simd::select(lanes < F(float(count)), ewa::weight<L>(r2), F(0.0f));
      typename L::M inside = F(0.0f) == F(0.0f);
      const F wx = ewa::wrapAnywhere<L>(x, g.width, view.wrapU, inside);
      const F wy = ewa::wrapAnywhere<L>(y, g.height, view.wrapV, inside);
      sum.add(sampling::withBorder<L>(view, sampling::fetch<L, R>(view, g, level, wx, wy), inside),
              w);
      count = 0;
    };
    for (int y = plan.y0; y <= plan.y1; ++y) {
      int x0, x1;
      ewaRowSpan(plan, y, x0, x1);
      for (int x = x0; x <= x1; ++x) {
        xs[count] = float(x), ys[count] = float(y);
        if (++count == W) flush();
      }
    }
    if (count > 0) flush();
    sum.mean(rgba);
  });
}

namespace sat {

// SummedAreaTable::lookup's steps (summed_area.cpp) on double lanes: the same
// exactly rounded operations in the same order (the kernels are compiled
// without FP contraction), so every lane gets lookup()'s bits.

// A lane group's floats, kDoubleWidth of them from `values`, as doubles.
template <class L>
QUADRA_LANE_INLINE typename L::D widen(const float* values) {
  alignas(64) double wide[L::kDoubleWidth];
  for (int k = 0; k < L::kDoubleWidth; ++k) wide[k] = double(values[k]);
  return L::D::load_aligned(wide);
}

// std::clamp(t, lo, hi): its comparisons, so NaN passes through as there.
template <class L>
QUADRA_LANE_INLINE typename L::D clamp(const typename L::D& t, double lo, double hi) {
  using D = typename L::D;
  return simd::select(t < D(lo), D(lo), simd::select(D(hi) < t, D(hi), t));
}

// Half a side of the footprint's bounding box in texels (boxOf's halfSide).
template <class L>
QUADRA_LANE_INLINE typename L::D halfSide(const typename L::D& a, const typename L::D& b,
                                          double size) {
  using D = typename L::D;
  const D side = D(0.5) * (simd::abs(a) + simd::abs(b)) * D(size);
  const D clamped =
      clamp<L>(side, SummedAreaTable::kMinHalfSide, 0.5 * SummedAreaTable::kMaxBoxPeriods * size);
  return simd::select(simd::isNan(side), D(SummedAreaTable::kMinHalfSide), clamped);
}

// The box centre brought near the texture (boxOf's centre), from a
// coordinate whose NaN and Inf count as 0.
template <class L>
QUADRA_LANE_INLINE typename L::D centre(const typename L::D& coordinate, WrapMode mode) {
  using D = typename L::D;
  const D t = simd::select(simd::abs(coordinate) < D(INFINITY), coordinate, D(0.0));
  if (mode == WrapMode::Repeat) return t - simd::floor(t);
  if (mode == WrapMode::MirroredRepeat) return t - D(2.0) * simd::floor(D(0.5) * t);
  return clamp<L>(t, -1.0 - 0.5 * SummedAreaTable::kMaxBoxPeriods,
                  2.0 + 0.5 * SummedAreaTable::kMaxBoxPeriods);
}

// A box corner's three prefix indices (first, first + 1, first + 2) and
// their weights along one axis (summed_area.cpp's cornerTerms).
template <class L>
struct CornerTerms {
  typename L::D first, weight[3];
};

template <class L>
QUADRA_LANE_INLINE CornerTerms<L> cornerTerms(const typename L::D& x, double sign) {
  using D = typename L::D;
  const D j = simd::floor(x - D(0.5)), s = x - D(0.5) - j;
  return {j,
          {D(sign * 0.5) * (D(1.0) - s) * (D(1.0) - s), D(sign) * (D(0.5) + s - s * s),
           D(sign * 0.5) * s * s}};
}

}  // namespace sat

// The summed-area table (texture/summed_area.h) across lanes: the boxes,
// their corner terms and the weighted box sums in double lanes, in lookup()'s
// operations and order (the same bits on every path; lookup() stays the
// scalar reference the tests compare with). Only the table reads and their
// exact integer sums go lane by lane, in SummedAreaTable::boxSums (no fast
// gathers here, and the wrap extension branches per lane), after every
// lane's entries are prefetched: on a table beyond the caches the lookups
// wait on memory (12 scattered cache lines each, 32 bytes a texel). The box
// sums pass through memory as [box][lane][channel], the layout the scalar
// code writes fastest. Against the lane-by-lane lookup() this replaced
// (docs/performance.md): 262 -> 157 ns a lookup at 128², 280 -> 190 at 2048²
// on AVX-512; 267 -> 169 / 278 -> 201 on AVX2; SSE2 and scalar lanes gain
// 13-27%.
template <class L>
Rgba<L> sampleSummedArea(const TextureView& view, const typename L::F& u, const typename L::F& v,
                         const UvDerivatives<L>& d) {
  using D = typename L::D;
  constexpr int W = L::kWidth, DW = L::kDoubleWidth;
  const SummedAreaTable& table = *view.summedArea;
  const LaneLookups<L> in(u, v, d);
  const double width = table.width(), height = table.height();
  const double fixedPointScale = std::ldexp(1.0, table.fractionBits());

  // The boxes and their corner terms (lookup's boxOf and boxAverage).
  alignas(64) double firstX[2][W], firstY[2][W], weightX[6][W], weightY[6][W], norm[W];
  for (int k = 0; k < W; k += DW) {
    using sat::widen;
    const D hx = sat::halfSide<L>(widen<L>(in.dudx + k), widen<L>(in.dudy + k), width);
    const D hy = sat::halfSide<L>(widen<L>(in.dvdx + k), widen<L>(in.dvdy + k), height);
    const D cx = sat::centre<L>(widen<L>(in.u + k), view.wrapU) * D(width);
    const D cy = sat::centre<L>(widen<L>(in.v + k), view.wrapV) * D(height);
    const D x0 = cx - hx, x1 = cx + hx, y0 = cy - hy, y1 = cy + hy;
    const sat::CornerTerms<L> xs[2] = {sat::cornerTerms<L>(x0, -1.0), sat::cornerTerms<L>(x1, 1.0)};
    const sat::CornerTerms<L> ys[2] = {sat::cornerTerms<L>(y0, -1.0), sat::cornerTerms<L>(y1, 1.0)};
    for (int corner = 0; corner < 2; ++corner) {
      xs[corner].first.store_aligned(&firstX[corner][k]);
      ys[corner].first.store_aligned(&firstY[corner][k]);
      for (int i = 0; i < 3; ++i) {
        xs[corner].weight[i].store_aligned(&weightX[corner * 3 + i][k]);
        ys[corner].weight[i].store_aligned(&weightY[corner * 3 + i][k]);
      }
    }
    (D(1.0) / (D(fixedPointScale) * (x1 - x0) * (y1 - y0))).store_aligned(&norm[k]);
  }

  // The table reads, lane by lane.
  SummedAreaTable::CornerIndices corners[W];
  for (int k = 0; k < W; ++k) {
    corners[k] = {{long(firstX[0][k]), long(firstX[1][k])},
                  {long(firstY[0][k]), long(firstY[1][k])}};
    table.prefetch(view, corners[k]);
  }
  alignas(64) std::int64_t boxSum[25][W][4];
  for (int k = 0; k < W; ++k) table.boxSums(view, corners[k], &boxSum[0][k][0], 4 * W);

  // The weighted sums, in boxAverage's order, over DW of the W x 4 (lane,
  // channel) sums at a time: the layout the table reads wrote (a lane's
  // channels side by side), with each lane's weights repeated over its channels.
  alignas(64) double average[W * 4];
  for (int e = 0; e < W * 4; e += DW) {
    const int lane = e / 4;
    D sum(0.0);
    for (int a = 1; a < 6; ++a) {
      const D wx = simd::repeatPerChannel<L>(&weightX[a][lane]);
      for (int b = 1; b < 6; ++b) {
        const D weight = wx * simd::repeatPerChannel<L>(&weightY[b][lane]);
        sum = sum + weight * simd::loadAsDouble<L>(&boxSum[(a - 1) * 5 + b - 1][0][0] + e);
      }
    }
    (sum * simd::repeatPerChannel<L>(&norm[lane])).store_aligned(&average[e]);
  }
  alignas(64) float out[4][W];
  for (int k = 0; k < W; ++k)
    for (int c = 0; c < 4; ++c) out[c][k] = float(average[k * 4 + c]);
  using F = typename L::F;
  return {F::load_aligned(out[0]), F::load_aligned(out[1]), F::load_aligned(out[2]),
          F::load_aligned(out[3])};
}

// The area filter (texture/area_filter.h), lookup by lane: each lane's grid
// is spread over the SIMD lanes, W samples per bilinear call on the level the
// plan chose. Sums run in double in sample order, so every ISA path adds the
// same values in the same order and returns the same bits.
template <class L, class R>
Rgba<L> sampleArea(const TextureView& view, const typename L::F& u, const typename L::F& v,
                   const UvDerivatives<L>& d) {
  using F = typename L::F;
  using I = typename L::I;
  constexpr int W = L::kWidth;
  const LaneLookups<L> in(u, v, d);
  alignas(64) float out[4][W], laneIndex[W];
  for (int k = 0; k < W; ++k) laneIndex[k] = float(k);
  const F lanes = F::load_aligned(laneIndex);
  for (int k = 0; k < W; ++k) {
    const AreaGrid grid = planAreaGrid(view, in.dudx[k], in.dvdx[k], in.dudy[k], in.dvdy[k]);
    const int samples = grid.columns * grid.rows;
    const F columns = F(float(grid.columns)), rows = F(float(grid.rows));
    const F dudx(in.dudx[k]), dvdx(in.dvdx[k]), dudy(in.dudy[k]), dvdy(in.dvdy[k]);
    double sum[4] = {0.0, 0.0, 0.0, 0.0};
    for (int first = 0; first < samples; first += W) {
      // Sample n of the grid: column n mod columns, row n div columns, at the
      // cell midpoints of the parallelogram's screen square [-1/2, 1/2]^2.
      const F n = lanes + F(float(first));
      const F row = simd::floor((n + F(0.5f)) / columns);
      const F column = n - row * columns;
      const F s = (column + F(0.5f)) / columns - F(0.5f);
      const F t = (row + F(0.5f)) / rows - F(0.5f);
      const Rgba<L> c = sampleBilinear<L, R>(view, F(in.u[k]) + dudx * s + dudy * t,
                                             F(in.v[k]) + dvdx * s + dvdy * t, I(grid.level));
      alignas(64) float value[4][W];
      c.r.store_aligned(value[0]);
      c.g.store_aligned(value[1]);
      c.b.store_aligned(value[2]);
      c.a.store_aligned(value[3]);
      const int count = std::min(W, samples - first);
      for (int j = 0; j < count; ++j)
        for (int ch = 0; ch < 4; ++ch) sum[ch] += double(value[ch][j]);
    }
    for (int ch = 0; ch < 4; ++ch) out[ch][k] = float(sum[ch] / double(samples));
  }
  return {F::load_aligned(out[0]), F::load_aligned(out[1]), F::load_aligned(out[2]),
          F::load_aligned(out[3])};
}

// The view's filter at the footprint given by the derivatives, for texels
// stored in R::kFormat (the view's format).
template <class L, class R>
Rgba<L> sampleTextureAs(const TextureView& view, const typename L::F& u, const typename L::F& v,
                        const UvDerivatives<L>& d) {
  using F = typename L::F;
  using I = typename L::I;
  const I level0(0);
  const Filter filter = view.minFilter;
  if (filter == Filter::Nearest) return sampleNearest<L, R>(view, u, v, level0);
  if (filter == Filter::Bilinear) return sampleBilinear<L, R>(view, u, v, level0);
  if (filter == Filter::Ewa) return sampleEwa<L, R>(view, u, v, d);
  if (filter == Filter::Area) return sampleArea<L, R>(view, u, v, d);
  if (filter == Filter::SummedArea) return sampleSummedArea<L>(view, u, v, d);
  if (filter == Filter::Ripmap) return sampleRipmap<L, R>(view, u, v, d);
  // Magnified lanes only change the anisotropic filter under nearest magnification.
  if (filter == Filter::Anisotropic && view.magLinear)
    return sampleAnisotropic<L, R>(view, u, v, d);
  // Magnification decided exactly on the squared footprint length: a group
  // that is magnified throughout (the common case up close) skips the log2
  // and the level selection, and reads level 0 as trilinear would there.
  const F lengthSq = isotropicLengthSq<L>(view, d);
  if (filter != Filter::Anisotropic && simd::all(lengthSq <= F(view.magnifiedLengthSq)))
    return view.magLinear ? sampleBilinear<L, R>(view, u, v, level0)
                          : sampleNearest<L, R>(view, u, v, level0);
  const F lod = isotropicLod<L>(view, lengthSq);
  // OpenGL's switch-over point c (4.6 §8.14.2): 0.5 for linear magnification
  // over nearest-texel mipmaps, so λ <= 0.5 reads bilinear level 0 rather than
  // level 0's nearest texel; else 0.
  const float switchOver = view.magLinear && !view.minLinear ? 0.5f : 0.0f;
  const auto magnified = ~(lod > F(switchOver));
  if (!view.magLinear && simd::all(magnified)) return sampleNearest<L, R>(view, u, v, level0);
  Rgba<L> c = filter == Filter::Anisotropic
                  ? sampleAnisotropic<L, R>(view, u, v, d)
                  : sampleMipmapped<L, R>(view, u, v, lod, filter == Filter::Trilinear);
  // Magnified lanes take the magnification filter where it differs from the
  // filter within a level (the anisotropic filter's taps are bilinear).
  const bool minLinear = view.minLinear || filter == Filter::Anisotropic;
  if (view.magLinear != minLinear && simd::any(magnified)) {
    const Rgba<L> m = view.magLinear ? sampleBilinear<L, R>(view, u, v, level0)
                                     : sampleNearest<L, R>(view, u, v, level0);
    c = sampling::selectRgba<L>(magnified, m, c);
  }
  return c;
}

// The view's filter at the footprint given by the derivatives: one branch on
// the storage format, so everything below is compiled for that format.
template <class L>
Rgba<L> sampleTexture(const TextureView& view, const typename L::F& u, const typename L::F& v,
                      const UvDerivatives<L>& d) {
  switch (view.format) {
    case TexelFormat::Rgba16F:
      return sampleTextureAs<L, TexelRead<TexelFormat::Rgba16F>>(view, u, v, d);
    case TexelFormat::Rgba8Unorm:
      return sampleTextureAs<L, TexelRead<TexelFormat::Rgba8Unorm>>(view, u, v, d);
    case TexelFormat::Rgba8Srgb:
      // The scalar path decodes every texel through decodeTexel(view.format),
      // so rgba8's instantiation is already rgba8srgb's: one fewer copy of
      // every filter in the largest kernel files.
      if constexpr (sampling::kIsScalarLanes<L>)
        return sampleTextureAs<L, TexelRead<TexelFormat::Rgba8Unorm>>(view, u, v, d);
      else
        return sampleTextureAs<L, TexelRead<TexelFormat::Rgba8Srgb>>(view, u, v, d);
    case TexelFormat::Rgba32F:
      break;
  }
  if constexpr (L::kWidth > 4) {  // gathers exist from AVX2 on
    if (view.gatherTexels)
      return sampleTextureAs<L, TexelRead<TexelFormat::Rgba32F, true>>(view, u, v, d);
  }
  return sampleTextureAs<L, TexelRead<TexelFormat::Rgba32F>>(view, u, v, d);
}

// What the lod and anisotropy AOVs report (docs/cli.md "AOVs"): the level the
// view's filter reads for this footprint and its probe count, from the
// functions that filter itself calls, so the AOV is the kernel's choice and
// not a second formula of it. lod is within the chain [0, levelCount - 1]:
// trilinear and nearest-mip λ' (the controls applied; magnified: 0), the
// anisotropic filter's λ' = log2(major / N) with N its probes, the ripmap's
// coarser axis level, EWA's and the area filter's planned level; 0 for the
// filters that read level 0 only. anisotropy is N for the anisotropic filter, else 1.
template <class L>
struct FootprintLevel {
  typename L::F lod, anisotropy;
};

template <class L>
FootprintLevel<L> footprintLevel(const TextureView& view, const typename L::F& u,
                                 const typename L::F& v, const UvDerivatives<L>& d) {
  using F = typename L::F;
  switch (view.minFilter) {
    case Filter::Nearest:
    case Filter::Bilinear:
    case Filter::SummedArea:
      break;
    case Filter::NearestMip:
    case Filter::Trilinear:
      return {levelRead<L>(view, isotropicLod<L>(view, isotropicLengthSq<L>(view, d))), F(1.0f)};
    case Filter::Anisotropic: {
      const aniso::Footprint<L> f = aniso::footprint<L>(view, d);
      return {f.read, f.probes};
    }
    case Filter::Ripmap: {
      const RipmapLevels<L> levels = ripmapLevels<L>(view, d);
      return {simd::max(levels.lodU, levels.lodV), F(1.0f)};
    }
    case Filter::Ewa:
    case Filter::Area: {
      const LaneLookups<L> in(u, v, d);
      alignas(64) float level[L::kWidth];
      for (int k = 0; k < L::kWidth; ++k) {
        if (view.minFilter == Filter::Area) {
          level[k] =
              float(planAreaGrid(view, in.dudx[k], in.dvdx[k], in.dudy[k], in.dvdy[k]).level);
        } else {
          const EwaPlan plan =
              planEwa(view, in.u[k], in.v[k], in.dudx[k], in.dvdx[k], in.dudy[k], in.dvdy[k]);
          level[k] = plan.grid ? 0.0f : float(plan.level);
        }
      }
      return {F::load_aligned(level), F(1.0f)};
    }
  }
  return {F(0.0f), F(1.0f)};
}

// The straight colour of a premultiplied lookup (TextureView::premultiplied):
// rgb / a, one IEEE division, so every path gives the same bits. Where a is 0
// there is no colour to recover and nothing of it shows: (0, 0, 0, 0).
template <class L>
QUADRA_LANE_INLINE Rgba<L> unpremultiplied(const Rgba<L>& c) {
  using F = typename L::F;
  const auto covered = c.a > F(0.0f);
  const F divisor = simd::select(covered, c.a, F(1.0f));
  return {simd::select(covered, c.r / divisor, F(0.0f)),
          simd::select(covered, c.g / divisor, F(0.0f)),
          simd::select(covered, c.b / divisor, F(0.0f)), c.a};
}

}  // namespace quadra
