// The lit shading stage over lanes, what the tile kernels call per lane
// group: surfaceRadiance = occlusion x environment term + punctual lights +
// emission (LIGHTING.md "The light"), the background's filtered lookup, and
// the normal map's Toksvig roughness.
//
// The environment term, per lane (docs/shading.md has the derivation and the
// measured error against the exact integral and against split sum):
//  - specular: filtered importance sampling (Křivánek & Colbert 2008) of the
//    GGX lobe for the lane's real view (Heitz 2018's visible-normal samples,
//    weight G2 / G1(v)), each sample a lookup of the radiance cube averaged
//    over the sample's share of the lobe's solid angle, 1 / (K pdf). The
//    samples give the lobe's weighted average radiance for the Fresnel
//    split's two parts, (1 - w) and w; the albedo table (brdf_table.h) gives
//    their exact integrals under uniform light, so a uniform environment is
//    reproduced exactly and the lobe's shape at grazing angles is the real one.
//  - diffuse: the irradiance cube at n, x the table's Fresnel share S(n.v).
//
// Include only from per-ISA kernel translation units.
#pragma once

#include <algorithm>

#include "shading/brdf_lanes.h"
#include "shading/environment_lanes.h"
#include "shading/lighting.h"
#include "simd/lanes.h"

namespace quadra {

// One lane group's surface, in world space. normal: unit, already normal
// mapped and facing the viewer; view: unit, toward the eye.
template <class L>
struct SurfaceLanes {
  Vec3Lanes<L> position, normal, view;
  RgbLanes<L> baseColor;              // linear
  typename L::F metallic, roughness;  // roughness perceptual, alpha = roughness^2
  typename L::F occlusion;            // 1 + strength (ao - 1)
  // The dielectric's Fresnel (brdf_lanes.h dielectricF0 from ior, specular
  // colour and specular; 0.04 and 1 without KHR_materials_ior / _specular).
  RgbLanes<L> dielectricF0;
  typename L::F dielectricF90;
  RgbLanes<L> emission;  // linear, x emissive strength
};

namespace shading {

// An orthonormal frame (t, b, n) around unit n, branch-free (Duff et al. 2017,
// "Building an Orthonormal Basis, Revisited").
template <class L>
QUADRA_LANE_INLINE void tangentFrame(const Vec3Lanes<L>& n, Vec3Lanes<L>& t, Vec3Lanes<L>& b) {
  using F = typename L::F;
  const F sign = simd::select(n.z >= F(0.0f), F(1.0f), F(-1.0f));
  const F a = F(-1.0f) / (sign + n.z);
  const F c = n.x * n.y * a;
  t = {F(1.0f) + sign * n.x * n.x * a, sign * c, F(0.0f) - sign * n.x};
  b = {c, sign + n.y * n.y * a, F(0.0f) - n.y};
}

template <class L>
QUADRA_LANE_INLINE BrdfMaterial<L> brdfMaterialOf(const SurfaceLanes<L>& s) {
  return {s.baseColor, s.metallic, s.roughness * s.roughness, s.dielectricF0, s.dielectricF90};
}

// The GGX lobe's average radiance for the two parts of the Fresnel split:
// weighted by (1 - w) and by w (w Schlick's weight at the sample's h.v).
template <class L>
struct LobeRadiance {
  RgbLanes<L> outer, grazing;
};

template <class L>
QUADRA_LANE_INLINE LobeRadiance<L> specularLobeRadiance(const EnvironmentView& env,
                                                        const Vec3Lanes<L>& n,
                                                        const Vec3Lanes<L>& v,
                                                        const typename L::F& roughness) {
  using F = typename L::F;
  const F alpha = roughness * roughness;
  // Each lane's sample set by its own roughness (so that a lane's result
  // does not depend on its neighbours, nor on the ISA's lane count); the
  // group runs as many samples as its largest set, and a lane's samples past
  // its set's size weigh exactly 0.
  static_assert(EnvironmentView::kFisSets == 3, "three sample sets");
  const auto inSet1 = roughness >= F(EnvironmentView::kFisSetRoughness[0]);
  const auto inSet2 = roughness >= F(EnvironmentView::kFisSetRoughness[1]);
  const int count = simd::any(inSet2)   ? EnvironmentView::kFisSetSize[2]
                    : simd::any(inSet1) ? EnvironmentView::kFisSetSize[1]
                                        : EnvironmentView::kFisSetSize[0];
  const float* set0 = env.fisSamples;
  const float* set1 = set0 + 3 * EnvironmentView::kFisSetSize[0];
  const float* set2 = set1 + 3 * EnvironmentView::kFisSetSize[1];
  const F laneCount = simd::select(inSet2, F(float(EnvironmentView::kFisSetSize[2])),
                                   simd::select(inSet1, F(float(EnvironmentView::kFisSetSize[1])),
                                                F(float(EnvironmentView::kFisSetSize[0]))));
  Vec3Lanes<L> t, b;
  tangentFrame<L>(n, t, b);
  // The view in the frame, and Heitz's stretched view Vh with its frame (T1, T2).
  const F vx = dot<L>(v, t), vy = dot<L>(v, b);
  const F vz = simd::max(dot<L>(v, n), F(1e-4f));
  const F alpha2 = alpha * alpha;
  const F gv = simd::sqrt(vz * vz * (F(1.0f) - alpha2) + alpha2);
  F hx = alpha * vx, hy = alpha * vy, hz = vz;
  const F hlen = F(1.0f) / simd::sqrt(hx * hx + hy * hy + hz * hz);
  hx = hx * hlen, hy = hy * hlen, hz = hz * hlen;
  const F lensq = hx * hx + hy * hy;
  const auto tilted = lensq > F(1e-20f);
  const F inv = F(1.0f) / simd::sqrt(simd::max(lensq, F(1e-20f)));
  const F t1x = simd::select(tilted, F(0.0f) - hy * inv, F(1.0f));
  const F t1y = simd::select(tilted, hx * inv, F(0.0f));
  // T2 = Vh x T1 (T1.z = 0).
  const F t2x = F(0.0f) - hz * t1y, t2y = hz * t1x, t2z = hx * t1y - hy * t1x;
  const F blend = F(0.5f) * (F(1.0f) + hz);
  // Each sample's share of the lobe: 1 / (K pdf(l)), pdf(l) = D(h) / (2 (n.v + gv)).
  const F k = laneCount;
  const F alpha2c = simd::max(alpha2, F(1e-8f));
  const F omegaScale = F(2.0f * kPi) * (vz + gv) / (k * alpha2c);
  RgbLanes<L> sum0{F(0.0f), F(0.0f), F(0.0f)}, sum1 = sum0;
  F weight0(0.0f), weight1(0.0f);
  for (int i = 0; i < count; ++i) {
    // Sample i of each lane's set (an index past a set's end reads its
    // last sample, weighted 0 below).
    const float* s0 = set0 + 3 * std::min(i, EnvironmentView::kFisSetSize[0] - 1);
    const float* s1 = set1 + 3 * std::min(i, EnvironmentView::kFisSetSize[1] - 1);
    const float* s2 = set2 + 3 * i;
    F sample[3];
    for (int j = 0; j < 3; ++j)
      sample[j] = simd::select(inSet2, F(s2[j]), simd::select(inSet1, F(s1[j]), F(s0[j])));
    const auto active = F(float(i)) < laneCount;
    const F p1 = sample[0];
    const F p2 = (F(1.0f) - blend) * sample[2] + blend * sample[1];
    const F p3 = simd::sqrt(simd::max(F(1.0f) - p1 * p1 - p2 * p2, F(0.0f)));
    // The visible normal, unstretched: h (frame coordinates).
    F mx = alpha * (p1 * t1x + p2 * t2x + p3 * hx);
    F my = alpha * (p1 * t1y + p2 * t2y + p3 * hy);
    F mz = simd::max(p2 * t2z + p3 * hz, F(0.0f));
    const F mlen = F(1.0f) / simd::sqrt(simd::max(mx * mx + my * my + mz * mz, F(1e-30f)));
    mx = mx * mlen, my = my * mlen, mz = mz * mlen;
    const F vh = vx * mx + vy * my + vz * mz;
    const F nl = F(2.0f) * vh * mz - vz;
    const F nlc = simd::max(nl, F(1e-8f));
    const F gl = simd::sqrt(nlc * nlc * (F(1.0f) - alpha2) + alpha2);
    const F weight =
        simd::select((nl > F(0.0f)) & active, nlc * (vz + gv) / (nlc * gv + vz * gl), F(0.0f));
    const F w = schlickWeight<L>(vh);
    // l = 2 (v.h) h - v in world space.
    const F twoVh = F(2.0f) * vh;
    const Vec3Lanes<L> l{twoVh * (mx * t.x + my * b.x + mz * n.x) - v.x,
                         twoVh * (mx * t.y + my * b.y + mz * n.y) - v.y,
                         twoVh * (mx * t.z + my * b.z + mz * n.z) - v.z};
    const F d = mz * mz * (alpha2c - F(1.0f)) + F(1.0f);
    const RgbLanes<L> radiance = filteredRadiance<L>(env, l, omegaScale * d * d, -0.5f, false);
    const F w0 = weight * (F(1.0f) - w), w1 = weight * w;
    sum0 = {sum0.r + radiance.r * w0, sum0.g + radiance.g * w0, sum0.b + radiance.b * w0};
    sum1 = {sum1.r + radiance.r * w1, sum1.g + radiance.g * w1, sum1.b + radiance.b * w1};
    weight0 = weight0 + w0, weight1 = weight1 + w1;
  }
  const F inv0 = F(1.0f) / simd::max(weight0, F(1e-30f));
  const F inv1 = F(1.0f) / simd::max(weight1, F(1e-30f));
  return {{sum0.r * inv0, sum0.g * inv0, sum0.b * inv0},
          {sum1.r * inv1, sum1.g * inv1, sum1.b * inv1}};
}

// The environment term's two lobes: the integral of Lenv(l) f(v, l) max(0, n.l) dl
// for f's diffuse and its specular part.
template <class L>
QUADRA_LANE_INLINE LobePair<L> environmentLobes(const EnvironmentView& env,
                                                const SurfaceLanes<L>& s) {
  using F = typename L::F;
  const BrdfMaterial<L> m = brdfMaterialOf<L>(s);
  const FresnelSplit<L> f = fresnelSplit<L>(m);
  const F nv = clamp01<L>(dot<L>(s.normal, s.view));
  const AlbedoLanes<L> albedo = albedoLookup<L>(env.brdfTable, nv, s.roughness);
  const LobeRadiance<L> lobe = specularLobeRadiance<L>(env, s.normal, s.view, s.roughness);
  const RgbLanes<L> e = irradiance<L>(env, s.normal);
  // Diffuse: baseColor x E x (diffuseF0 (1 - S) + diffuseF90 S).
  const F diffuse = f.diffuseF0 * (F(1.0f) - albedo.s) + f.diffuseF90 * albedo.s;
  const F grazing = f.specF90 * albedo.b;
  return {
      {diffuse * s.baseColor.r * e.r, diffuse * s.baseColor.g * e.g, diffuse * s.baseColor.b * e.b},
      {f.specF0.r * albedo.a * lobe.outer.r + grazing * lobe.grazing.r,
       f.specF0.g * albedo.a * lobe.outer.g + grazing * lobe.grazing.g,
       f.specF0.b * albedo.a * lobe.outer.b + grazing * lobe.grazing.b}};
}

// The environment term: integral of Lenv(l) f(v, l) max(0, n.l) dl, the
// lobes summed (specular + diffuse: the order the sum always had).
template <class L>
QUADRA_LANE_INLINE RgbLanes<L> environmentRadiance(const EnvironmentView& env,
                                                   const SurfaceLanes<L>& s) {
  const LobePair<L> lobes = environmentLobes<L>(env, s);
  return {lobes.specular.r + lobes.diffuse.r, lobes.specular.g + lobes.diffuse.g,
          lobes.specular.b + lobes.diffuse.b};
}

// KHR_lights_punctual: E_l f(v, l) (n.l) summed over the lights. Point and
// spot: intensity / d^2 x the range window clamp(1 - (d / range)^4, 0, 1)
// (the specification's recommended implementation); spot: x clamp(cd scale +
// offset, 0, 1)^2 (its implementation note). No shadows (LIGHTING.md).
// arrive(light, l, attenuation) is called per light.
template <class L, class Arrive>
QUADRA_LANE_INLINE void forEachPunctualLight(const LightingView& view, const SurfaceLanes<L>& s,
                                             Arrive&& arrive) {
  using F = typename L::F;
  for (int i = 0; i < view.lightCount; ++i) {
    const PunctualLight& light = view.lights[i];
    Vec3Lanes<L> l;
    F attenuation(1.0f);
    if (light.type == PunctualLight::Type::Directional) {
      l = {F(-light.direction[0]), F(-light.direction[1]), F(-light.direction[2])};
    } else {
      l = {F(light.position[0]) - s.position.x, F(light.position[1]) - s.position.y,
           F(light.position[2]) - s.position.z};
      const F d2 = simd::max(dot<L>(l, l), F(1e-20f));
      const F invD = F(1.0f) / simd::sqrt(d2);
      l = {l.x * invD, l.y * invD, l.z * invD};
      const F ratio4 = d2 * d2 * F(light.inverseRange4);
      const F window = clamp01<L>(F(1.0f) - ratio4);
      attenuation = window / d2;
      if (light.type == PunctualLight::Type::Spot) {
        const F cd = F(0.0f) - (l.x * F(light.direction[0]) + l.y * F(light.direction[1]) +
                                l.z * F(light.direction[2]));
        const F cone = clamp01<L>(cd * F(light.angleScale) + F(light.angleOffset));
        attenuation = attenuation * cone * cone;
      }
    }
    arrive(light, l, attenuation);
  }
}

template <class L>
QUADRA_LANE_INLINE RgbLanes<L> punctualRadiance(const LightingView& view,
                                                const SurfaceLanes<L>& s) {
  using F = typename L::F;
  const BrdfMaterial<L> m = brdfMaterialOf<L>(s);
  RgbLanes<L> sum{F(0.0f), F(0.0f), F(0.0f)};
  forEachPunctualLight<L>(
      view, s, [&](const PunctualLight& light, const Vec3Lanes<L>& l, const F& attenuation) {
        const RgbLanes<L> f = brdfCosine<L>(m, s.normal, s.view, l);
        sum = {sum.r + f.r * attenuation * F(light.radiance[0]),
               sum.g + f.g * attenuation * F(light.radiance[1]),
               sum.b + f.b * attenuation * F(light.radiance[2])};
      });
  return sum;
}

// punctualRadiance's two lobes apart.
template <class L>
QUADRA_LANE_INLINE LobePair<L> punctualLobes(const LightingView& view, const SurfaceLanes<L>& s) {
  using F = typename L::F;
  const BrdfMaterial<L> m = brdfMaterialOf<L>(s);
  LobePair<L> sum{{F(0.0f), F(0.0f), F(0.0f)}, {F(0.0f), F(0.0f), F(0.0f)}};
  forEachPunctualLight<L>(
      view, s, [&](const PunctualLight& light, const Vec3Lanes<L>& l, const F& attenuation) {
        const LobePair<L> f = brdfCosineLobes<L>(m, s.normal, s.view, l);
        const F r = attenuation * F(light.radiance[0]), g = attenuation * F(light.radiance[1]),
                b = attenuation * F(light.radiance[2]);
        sum.diffuse = {sum.diffuse.r + f.diffuse.r * r, sum.diffuse.g + f.diffuse.g * g,
                       sum.diffuse.b + f.diffuse.b * b};
        sum.specular = {sum.specular.r + f.specular.r * r, sum.specular.g + f.specular.g * g,
                        sum.specular.b + f.specular.b * b};
      });
  return sum;
}

}  // namespace shading

// The outgoing radiance toward the viewer: occlusion x environment term +
// punctual lights + emission (LIGHTING.md "The light").
template <class L>
QUADRA_LANE_INLINE RgbLanes<L> surfaceRadiance(const LightingView& view, const SurfaceLanes<L>& s) {
  RgbLanes<L> out = s.emission;
  if (view.environment) {
    const RgbLanes<L> e = shading::environmentRadiance<L>(view.env, s);
    out = {out.r + s.occlusion * e.r, out.g + s.occlusion * e.g, out.b + s.occlusion * e.b};
  }
  if (view.lightCount > 0) {
    const RgbLanes<L> p = shading::punctualRadiance<L>(view, s);
    out = {out.r + p.r, out.g + p.g, out.b + p.b};
  }
  return out;
}

// The light each lobe sends toward the viewer (the diffuse and specular
// AOVs): occlusion x the environment's lobe + the punctual lights' lobe.
// emission + diffuse + specular is surfaceRadiance up to rounding.
template <class L>
QUADRA_LANE_INLINE shading::LobePair<L> surfaceLobes(const LightingView& view,
                                                     const SurfaceLanes<L>& s) {
  using F = typename L::F;
  shading::LobePair<L> out{{F(0.0f), F(0.0f), F(0.0f)}, {F(0.0f), F(0.0f), F(0.0f)}};
  if (view.environment) {
    const shading::LobePair<L> e = shading::environmentLobes<L>(view.env, s);
    out.diffuse = {s.occlusion * e.diffuse.r, s.occlusion * e.diffuse.g, s.occlusion * e.diffuse.b};
    out.specular = {s.occlusion * e.specular.r, s.occlusion * e.specular.g,
                    s.occlusion * e.specular.b};
  }
  if (view.lightCount > 0) {
    const shading::LobePair<L> p = shading::punctualLobes<L>(view, s);
    out.diffuse = {out.diffuse.r + p.diffuse.r, out.diffuse.g + p.diffuse.g,
                   out.diffuse.b + p.diffuse.b};
    out.specular = {out.specular.r + p.specular.r, out.specular.g + p.specular.g,
                    out.specular.b + p.specular.b};
  }
  return out;
}

// The background: the environment's radiance through a pixel, averaged over
// the pixel's footprint (`omega` steradians around direction d, any length).
template <class L>
QUADRA_LANE_INLINE RgbLanes<L> backgroundRadiance(const LightingView& view, const Vec3Lanes<L>& d,
                                                  const typename L::F& omega) {
  return shading::filteredRadiance<L>(view.env, d, omega);
}

// Toksvig-style roughness for a mip-filtered normal map (Toksvig 2005,
// "Mipmapping normal maps", with the von Mises-Fisher fit of Han et al. 2007,
// "Frequency domain normal map filtering"): the filtered normal's length r < 1
// measures the spread of the normals it averages, a vMF lobe of concentration
// kappa = (3r - r^3) / (1 - r^2); its angular variance 1 / kappa per axis adds
// to GGX's slope variance alpha^2 / 2, so alpha'^2 = alpha^2 + 2 / kappa.
// Returns the perceptual roughness sqrt(alpha'), at most 1.
template <class L>
QUADRA_LANE_INLINE typename L::F toksvigRoughness(const typename L::F& roughness,
                                                  const typename L::F& normalLength) {
  using F = typename L::F;
  const F r = simd::min(simd::max(normalLength, F(1e-4f)), F(1.0f));
  const F spread = F(2.0f) * (F(1.0f) - r * r) / (F(3.0f) * r - r * r * r);
  const F alpha = roughness * roughness;
  const F alpha2 = simd::min(alpha * alpha + spread, F(1.0f));
  return simd::sqrt(simd::sqrt(alpha2));
}

}  // namespace quadra
