// The glTF 2.0 metallic-roughness BRDF over lanes (the specification's
// Appendix B, with KHR_materials_ior and KHR_materials_specular), one named
// function per term: D (GGX), V (height-correlated Smith-GGX), F (Schlick),
// and the metal/dielectric mix. LIGHTING.md is the contract; docs/shading.md
// has each formula with its source.
//
// Include only from per-ISA kernel translation units: everything here is a
// template on the lane type (simd/lanes.h), so no inline function is shared
// between ISAs. Only exactly rounded operations (+ - * / sqrt), so every path
// gives the same bits.
#pragma once

#include "simd/lanes.h"

namespace quadra {

template <class L>
struct RgbLanes {
  typename L::F r, g, b;
};

template <class L>
struct Vec3Lanes {
  typename L::F x, y, z;
};

namespace shading {

constexpr float kPi = 3.14159265358979f;
constexpr float kInvPi = 0.318309886183791f;

template <class L>
QUADRA_LANE_INLINE typename L::F dot(const Vec3Lanes<L>& a, const Vec3Lanes<L>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <class L>
QUADRA_LANE_INLINE typename L::F clamp01(const typename L::F& x) {
  using F = typename L::F;
  return simd::min(simd::max(x, F(0.0f)), F(1.0f));
}

// GGX (Trowbridge-Reitz) normal distribution, Walter et al. 2007 eq. 33:
// D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2), normalized so that
// the integral of D(h) (n.h) over the hemisphere is 1.
template <class L>
QUADRA_LANE_INLINE typename L::F ggxD(const typename L::F& nh, const typename L::F& alpha2) {
  using F = typename L::F;
  const F d = nh * nh * (alpha2 - F(1.0f)) + F(1.0f);
  return alpha2 / (F(kPi) * d * d);
}

// Height-correlated Smith-GGX visibility V = G2 / (4 |n.l| |n.v|) (Heitz 2014,
// "Understanding the masking-shadowing function", eq. 99; glTF Appendix B):
// V = 0.5 / (n.l sqrt((n.v)^2 (1 - alpha^2) + alpha^2) + n.v sqrt((n.l)^2 (1 - alpha^2) +
// alpha^2)). Callers keep n.l and n.v positive (the lanes where either is not are zeroed).
template <class L>
QUADRA_LANE_INLINE typename L::F smithGgxCorrelatedV(const typename L::F& nv,
                                                     const typename L::F& nl,
                                                     const typename L::F& alpha2) {
  using F = typename L::F;
  const F oneMinus = F(1.0f) - alpha2;
  const F gv = simd::sqrt(nv * nv * oneMinus + alpha2);
  const F gl = simd::sqrt(nl * nl * oneMinus + alpha2);
  return F(0.5f) / (nl * gv + nv * gl);
}

// Schlick's weight (1 - h.v)^5 (Schlick 1994); F = f0 + (f90 - f0) weight.
template <class L>
QUADRA_LANE_INLINE typename L::F schlickWeight(const typename L::F& vh) {
  using F = typename L::F;
  const F m = F(1.0f) - clamp01<L>(vh);
  const F m2 = m * m;
  return m2 * m2 * m;
}

template <class L>
QUADRA_LANE_INLINE typename L::F fresnelSchlick(const typename L::F& f0, const typename L::F& f90,
                                                const typename L::F& weight) {
  return f0 + (f90 - f0) * weight;
}

// KHR_materials_ior: f0 = ((ior - 1) / (ior + 1))^2 (outside ior 1; ior 1.5
// gives glTF's 0.04; ior 0 gives 1, as the extension allows).
template <class L>
QUADRA_LANE_INLINE typename L::F iorToF0(const typename L::F& ior) {
  const typename L::F r = (ior - typename L::F(1.0f)) / (ior + typename L::F(1.0f));
  return r * r;
}

// The material as the BRDF sees it, per lane. The dielectric's Fresnel comes
// from KHR_materials_specular (its "Implementation" section):
// dielectric_f0 = min(f0(ior) x specularColor, 1) x specular, dielectric_f90 =
// specular; without the extension specular = specularColor = 1 and ior = 1.5,
// so f0 = 0.04 and f90 = 1, LIGHTING.md's plain dielectric.
template <class L>
struct BrdfMaterial {
  RgbLanes<L> baseColor;  // linear
  typename L::F metallic;
  typename L::F alpha;  // roughness^2
  RgbLanes<L> dielectricF0;
  typename L::F dielectricF90;
};

template <class L>
QUADRA_LANE_INLINE RgbLanes<L> dielectricF0(const typename L::F& ior,
                                            const RgbLanes<L>& specularColor,
                                            const typename L::F& specular) {
  using F = typename L::F;
  const F f0 = iorToF0<L>(ior);
  return {simd::min(f0 * specularColor.r, F(1.0f)) * specular,
          simd::min(f0 * specularColor.g, F(1.0f)) * specular,
          simd::min(f0 * specularColor.b, F(1.0f)) * specular};
}

// The mixed material's Fresnel at Schlick weight w, split as
// F = specF0 (1 - w) + specF90 w for every lobe, with
// specF0 = mix(dielectric_f0, baseColor, metallic), specF90 = mix(dielectric_f90, 1, metallic),
// and the diffuse lobe's weight (1 - metallic)(1 - max(dielectric Fresnel)) =
// diffuseF0 (1 - w) + diffuseF90 w. Linear in w, so an integral over the lobe
// splits into the integrals of (1 - w) and w (the environment term uses that).
template <class L>
struct FresnelSplit {
  RgbLanes<L> specF0;
  typename L::F specF90;
  typename L::F diffuseF0, diffuseF90;  // already x (1 - metallic)
};

template <class L>
QUADRA_LANE_INLINE FresnelSplit<L> fresnelSplit(const BrdfMaterial<L>& m) {
  using F = typename L::F;
  const F dielectric = F(1.0f) - m.metallic;
  const RgbLanes<L>& d0 = m.dielectricF0;
  const F maxF0 = simd::max(simd::max(d0.r, d0.g), d0.b);
  return {{d0.r * dielectric + m.baseColor.r * m.metallic,
           d0.g * dielectric + m.baseColor.g * m.metallic,
           d0.b * dielectric + m.baseColor.b * m.metallic},
          m.dielectricF90 * dielectric + m.metallic,
          dielectric * (F(1.0f) - maxF0),
          dielectric * (F(1.0f) - m.dielectricF90)};
}

// The parts of f(v, l) (n.l) for unit n, v, l: mix(f_dielectric, f_metal, metallic) with
// f_metal = F_Schlick(baseColor, 1) D V and
// f_dielectric = (1 - max(F_d)) baseColor / pi + F_d D V, F_d = F_Schlick(dielectric_f0,
// dielectric_f90). Zero where n.l <= 0 or n.v <= 0. alpha is clamped to 2^-10 (alpha^2 ~ 1e-6) so
// that a punctual light on a mirror is the narrow lobe's finite value, not 0/0; the environment
// term handles alpha = 0 itself. brdfCosine sums the lobes, brdfCosineLobes keeps them apart.
template <class L>
struct BrdfCosineTerms {
  typename L::M lit;      // n.l > 0 and n.v > 0
  typename L::F nl, dv;   // n.l, D V
  typename L::F diffuse;  // the diffuse lobe's weight / pi, x baseColor gives its BRDF
  typename L::F oneMinusW, specF90w;
  FresnelSplit<L> split;
};

template <class L>
QUADRA_LANE_INLINE BrdfCosineTerms<L> brdfCosineTerms(const BrdfMaterial<L>& m,
                                                      const Vec3Lanes<L>& n, const Vec3Lanes<L>& v,
                                                      const Vec3Lanes<L>& l) {
  using F = typename L::F;
  const F nl = dot<L>(n, l), nv = dot<L>(n, v);
  const auto lit = (nl > F(0.0f)) & (nv > F(0.0f));
  Vec3Lanes<L> h{v.x + l.x, v.y + l.y, v.z + l.z};
  const F len2 = dot<L>(h, h);
  const F inv = F(1.0f) / simd::sqrt(simd::max(len2, F(1e-30f)));
  h = {h.x * inv, h.y * inv, h.z * inv};
  const F nh = clamp01<L>(dot<L>(n, h)), vh = dot<L>(v, h);
  const F alpha = simd::max(m.alpha, F(1.0f / 1024.0f));
  const F alpha2 = alpha * alpha;
  const F nlc = simd::max(nl, F(1e-8f)), nvc = simd::max(nv, F(1e-8f));
  const F dv = ggxD<L>(nh, alpha2) * smithGgxCorrelatedV<L>(nvc, nlc, alpha2);
  const F w = schlickWeight<L>(vh);
  const FresnelSplit<L> s = fresnelSplit<L>(m);
  const F oneMinusW = F(1.0f) - w;
  const F diffuse = (s.diffuseF0 * oneMinusW + s.diffuseF90 * w) * F(kInvPi);
  return {lit, nl, dv, diffuse, oneMinusW, s.specF90 * w, s};
}

template <class L>
QUADRA_LANE_INLINE RgbLanes<L> brdfCosine(const BrdfMaterial<L>& m, const Vec3Lanes<L>& n,
                                          const Vec3Lanes<L>& v, const Vec3Lanes<L>& l) {
  using F = typename L::F;
  const BrdfCosineTerms<L> t = brdfCosineTerms<L>(m, n, v, l);
  const RgbLanes<L>& f0 = t.split.specF0;
  const F zero(0.0f);
  return {simd::select(
              t.lit, ((f0.r * t.oneMinusW + t.specF90w) * t.dv + t.diffuse * m.baseColor.r) * t.nl,
              zero),
          simd::select(
              t.lit, ((f0.g * t.oneMinusW + t.specF90w) * t.dv + t.diffuse * m.baseColor.g) * t.nl,
              zero),
          simd::select(
              t.lit, ((f0.b * t.oneMinusW + t.specF90w) * t.dv + t.diffuse * m.baseColor.b) * t.nl,
              zero)};
}

// The two lobes of brdfCosine apart (the diffuse and specular AOVs); their
// sum is brdfCosine's up to rounding.
template <class L>
struct LobePair {
  RgbLanes<L> diffuse, specular;
};

template <class L>
QUADRA_LANE_INLINE LobePair<L> brdfCosineLobes(const BrdfMaterial<L>& m, const Vec3Lanes<L>& n,
                                               const Vec3Lanes<L>& v, const Vec3Lanes<L>& l) {
  using F = typename L::F;
  const BrdfCosineTerms<L> t = brdfCosineTerms<L>(m, n, v, l);
  const RgbLanes<L>& f0 = t.split.specF0;
  const F zero(0.0f);
  const F diffuse = t.diffuse * t.nl, specular = t.dv * t.nl;
  return {{simd::select(t.lit, diffuse * m.baseColor.r, zero),
           simd::select(t.lit, diffuse * m.baseColor.g, zero),
           simd::select(t.lit, diffuse * m.baseColor.b, zero)},
          {simd::select(t.lit, (f0.r * t.oneMinusW + t.specF90w) * specular, zero),
           simd::select(t.lit, (f0.g * t.oneMinusW + t.specF90w) * specular, zero),
           simd::select(t.lit, (f0.b * t.oneMinusW + t.specF90w) * specular, zero)}};
}

}  // namespace shading
}  // namespace quadra
