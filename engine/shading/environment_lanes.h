// Lookups of the prepared environment over lanes: the cube map's projection
// (cube_layout.h's mapping, here in lanes), the footprint-filtered radiance
// (trilinear over the mip levels at the level whose texels match a solid
// angle: the background's lookup and each filtered importance sample's), the
// irradiance, and the BRDF albedo table.
//
// Include only from per-ISA kernel translation units (templates on the lane
// type; only + - * / sqrt floor and simd::log2, so every path gives the same bits).
#pragma once

#include <cstdint>
#include <type_traits>

#include "shading/brdf_lanes.h"
#include "shading/brdf_table.h"
#include "shading/lighting.h"
#include "simd/lanes.h"
#include "simd/texel_pairs.h"

namespace quadra::shading {

// Face (0..5, cube_layout.h order) and face coordinates (s, t) of directions.
template <class L>
struct CubeCoords {
  typename L::I face;
  typename L::F s, t;
};

template <class L>
QUADRA_LANE_INLINE CubeCoords<L> cubeProject(const Vec3Lanes<L>& d) {
  using F = typename L::F;
  const F ax = simd::abs(d.x), ay = simd::abs(d.y), az = simd::abs(d.z);
  const auto isX = (ax >= ay) & (ax >= az);
  const auto isY = ~isX & (ay >= az);
  const auto px = d.x > F(0.0f), py = d.y > F(0.0f), pz = d.z > F(0.0f);
  const F zero(0.0f);
  // Major axis magnitude and the numerators of s and t (cube_layout.h's table).
  const F ma = simd::select(isX, ax, simd::select(isY, ay, az));
  const F sn = simd::select(isX, simd::select(px, zero - d.z, d.z),
                            simd::select(isY, d.x, simd::select(pz, d.x, zero - d.x)));
  const F tn = simd::select(isY, simd::select(py, d.z, zero - d.z), zero - d.y);
  const F faceF = simd::select(
      isX, simd::select(px, F(0.0f), F(1.0f)),
      simd::select(isY, simd::select(py, F(2.0f), F(3.0f)), simd::select(pz, F(4.0f), F(5.0f))));
  const F inv = F(1.0f) / simd::max(ma, F(1e-30f));
  return {simd::toInt(faceF), sn * inv, tn * inv};
}

// Each lane's pair of adjacent RGBA float texels (pair[k] -> lane k's left
// and right texel) as channel lanes: the sampler's pair transposes
// (simd/texel_pairs.h: one load per lane, moves only, so every path has the
// same bits), or lane by lane on the scalar path.
template <class L>
QUADRA_LANE_INLINE void texelPairs(const std::uint8_t* const pair[L::kWidth], typename L::F left[3],
                                   typename L::F right[3]) {
  using F = typename L::F;
  if constexpr (std::is_same_v<L, simd::Lanes<simd::ScalarArch>>) {
    const float* p[4];
    for (int k = 0; k < 4; ++k) p[k] = reinterpret_cast<const float*>(pair[k]);
    for (int c = 0; c < 3; ++c) {
      left[c] = F(p[0][c], p[1][c], p[2][c], p[3][c]);
      right[c] = F(p[0][4 + c], p[1][4 + c], p[2][4 + c], p[3][4 + c]);
    }
  } else {
    typename F::register_type l[4], r[4];
    simd::transposeTexelPairs<simd::PairEncoding::Float32>(pair, l, r);
    for (int c = 0; c < 3; ++c) left[c] = l[c], right[c] = r[c];
  }
}

// Bilinear lookups, one cube level per lane: `level` the lane's level, whose
// faces have size size >> level and whose first texel is levelTexels[level].
template <class L>
QUADRA_LANE_INLINE RgbLanes<L> cubeBilinear(const std::uint8_t* const* levelTexels, int size,
                                            const CubeCoords<L>& c, const typename L::I& level) {
  using F = typename L::F;
  using I = typename L::I;
  constexpr int W = L::kWidth;
  constexpr int kTexelBytes = EnvironmentView::kTexelFloats * int(sizeof(float));
  // Face size n = size x 2^-level, exactly, from the exponent bits.
  const F scale = simd::asFloat((I(127) - level) << 23);
  const F n = F(float(size)) * scale;
  // Padded texel coordinates: texel i's centre sits at i + 1 (cube_layout.h).
  const F half(0.5f);
  const F x = simd::min(simd::max((c.s + F(1.0f)) * half * n + half, F(0.0f)), n + half);
  const F y = simd::min(simd::max((c.t + F(1.0f)) * half * n + half, F(0.0f)), n + half);
  const F x0 = simd::floor(x), y0 = simd::floor(y);
  const F ax = x - x0, ay = y - y0;
  // The texel index in the level, (face m + y0) m + x0 with m = n + 2: exact
  // in float (at most 6 x 1026^2 < 2^24).
  const F m = n + F(2.0f);
  const I offset = simd::toInt((simd::toFloat(c.face) * m + y0) * m + x0);
  const std::uint8_t* top[W];
  const std::uint8_t* bottom[W];
  simd::laneAddresses<L, kTexelBytes>(levelTexels, level, offset, top);
  simd::laneAddresses<L, kTexelBytes>(levelTexels, level, offset + simd::toInt(m), bottom);
  F t00[3], t10[3], t01[3], t11[3];
  texelPairs<L>(top, t00, t10);
  texelPairs<L>(bottom, t01, t11);
  F out[3];
  for (int ch = 0; ch < 3; ++ch) {
    const F upper = t00[ch] + (t10[ch] - t00[ch]) * ax;
    const F lower = t01[ch] + (t11[ch] - t01[ch]) * ax;
    out[ch] = upper + (lower - upper) * ay;
  }
  return {out[0], out[1], out[2]};
}

// The radiance arriving from direction d (any length), averaged over a
// footprint of solid angle `omega` steradians around it: trilinear between
// the two mip levels whose texels' solid angle there brackets omega (a
// texel of level 0 at face coordinates (s, t) spans (2 / size)^2 (1 + s^2 +
// t^2)^(-3/2) sr). omega <= the texel's reads level 0 bilinearly. lodBias
// shifts the level: the filtered importance samples read half a level
// sharper than their share of the lobe (measured: RMS error 0.041 at 0,
// 0.033 at -0.5, 0.043 at -1 on the test panoramas), since a level's
// bilinear tap already spreads over about two of its texels.
template <class L>
QUADRA_LANE_INLINE RgbLanes<L> filteredRadiance(const EnvironmentView& env, const Vec3Lanes<L>& d,
                                                const typename L::F& omega, float lodBias = 0.0f,
                                                bool blendLevels = true) {
  using F = typename L::F;
  using I = typename L::I;
  const CubeCoords<L> c = cubeProject<L>(d);
  const F q = F(1.0f) + c.s * c.s + c.t * c.t;
  const float texel0 = 4.0f / (float(env.size) * float(env.size));
  const F ratio = omega * q * simd::sqrt(q) * F(1.0f / texel0);
  const F maxLevel(float(env.levelCount - 1));
  const F lod =
      simd::min(simd::max(F(0.5f) * simd::log2<L>(ratio) + F(lodBias), F(0.0f)), maxLevel);
  const F l0 = simd::floor(blendLevels ? lod : lod + F(0.5f));
  const F frac = blendLevels ? lod - l0 : F(0.0f);
  const I level0 = simd::toInt(l0);
  const I level1 = simd::toInt(simd::min(l0 + F(1.0f), maxLevel));
  const RgbLanes<L> a = cubeBilinear<L>(env.levelTexels, env.size, c, level0);
  if (!simd::any(frac > F(0.0f))) return a;
  const RgbLanes<L> b = cubeBilinear<L>(env.levelTexels, env.size, c, level1);
  return {a.r + (b.r - a.r) * frac, a.g + (b.g - a.g) * frac, a.b + (b.b - a.b) * frac};
}

// (1/pi) x the cosine-weighted integral of the radiance around unit n.
template <class L>
QUADRA_LANE_INLINE RgbLanes<L> irradiance(const EnvironmentView& env, const Vec3Lanes<L>& n) {
  using I = typename L::I;
  return cubeBilinear<L>(env.irradianceTexels, env.irradianceSize, cubeProject<L>(n), I(0));
}

// The albedo table (brdf_table.h) at (n.v, roughness), bilinear: A, B, S.
template <class L>
struct AlbedoLanes {
  typename L::F a, b, s;
};

template <class L>
QUADRA_LANE_INLINE AlbedoLanes<L> albedoLookup(const float* table, const typename L::F& nv,
                                               const typename L::F& roughness) {
  using F = typename L::F;
  using namespace brdf_table;
  constexpr int W = L::kWidth;
  const F x =
      simd::min(simd::max(nv * F(float(kNvCount)) - F(0.5f), F(0.0f)), F(float(kNvCount - 1)));
  const F y = simd::min(simd::max(roughness * F(float(kRoughnessCount - 1)), F(0.0f)),
                        F(float(kRoughnessCount - 1)));
  // The last column and row interpolate with themselves (weight 0 on a copy).
  const F x0 = simd::min(simd::floor(x), F(float(kNvCount - 2)));
  const F y0 = simd::min(simd::floor(y), F(float(kRoughnessCount - 2)));
  const F ax = x - x0, ay = y - y0;
  alignas(64) std::int32_t ix[W], iy[W];
  simd::toInt(x0).store_aligned(ix);
  simd::toInt(y0).store_aligned(iy);
  alignas(64) float e[12][W];
  for (int k = 0; k < W; ++k) {
    const float* t0 = table + (std::size_t(iy[k]) * kNvCount + ix[k]) * kEntryFloats;
    const float* t1 = t0 + kNvCount * kEntryFloats;
    for (int ch = 0; ch < 3; ++ch) {
      e[ch][k] = t0[ch];
      e[3 + ch][k] = t0[kEntryFloats + ch];
      e[6 + ch][k] = t1[ch];
      e[9 + ch][k] = t1[kEntryFloats + ch];
    }
  }
  F out[3];
  for (int ch = 0; ch < 3; ++ch) {
    const F t00 = F::load_aligned(e[ch]), t10 = F::load_aligned(e[3 + ch]);
    const F t01 = F::load_aligned(e[6 + ch]), t11 = F::load_aligned(e[9 + ch]);
    const F top = t00 + (t10 - t00) * ax, bottom = t01 + (t11 - t01) * ax;
    out[ch] = top + (bottom - top) * ay;
  }
  return {out[0], out[1], out[2]};
}

}  // namespace quadra::shading
