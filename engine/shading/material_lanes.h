// The lit shading of a group of lanes (Shading::Pbr, ../shared/LIGHTING.md
// "The material"): a draw's material read at each lane's interpolated
// attributes (every texture through the sampler and its LOD, each with its
// own coordinate set and transform), the normal map applied, and the light
// that leaves the surface toward the eye (shading/shade_lanes.h).
// Written once over lanes; the tile kernels of each ISA include it.
#pragma once

#include "shading/material_shading.h"
#include "shading/shade_lanes.h"
#include "texture/sample_lanes.h"

namespace quadra {

// What the tile kernel knows at each lane: every attribute's
// perspective-correct value (indexed as AttributeLayout numbers them), and
// the screen-space footprint of TEXCOORD_0 and TEXCOORD_1 (as the unlit
// shading's lookups take theirs).
template <class L>
struct MaterialLaneInputs {
  const typename L::F* attribute;
  UvDerivatives<L> footprint[2];
};

namespace material_reads {

template <class L>
QUADRA_LANE_INLINE Rgba<L> lookup(const MaterialTextureLookup& t, const MaterialShading& m,
                                  const MaterialLaneInputs<L>& in) {
  using F = typename L::F;
  const int set = t.texcoord;
  const F& u = in.attribute[m.texcoordAttribute[set]];
  const F& v = in.attribute[m.texcoordAttribute[set] + 1];
  const UvDerivatives<L>& d = in.footprint[set];
  if (!t.transformed) return sampleTexture<L>(t.view, u, v, d);
  // KHR_texture_transform is affine: the coordinates move by all of it, the
  // footprint by its linear part.
  const glm::mat3x2& k = t.transform;
  const F tu = F(k[0][0]) * u + F(k[1][0]) * v + F(k[2][0]);
  const F tv = F(k[0][1]) * u + F(k[1][1]) * v + F(k[2][1]);
  const UvDerivatives<L> td{
      F(k[0][0]) * d.dudx + F(k[1][0]) * d.dvdx, F(k[0][1]) * d.dudx + F(k[1][1]) * d.dvdx,
      F(k[0][0]) * d.dudy + F(k[1][0]) * d.dvdy, F(k[0][1]) * d.dudy + F(k[1][1]) * d.dvdy};
  return sampleTexture<L>(t.view, tu, tv, td);
}

template <class L>
QUADRA_LANE_INLINE Vec3Lanes<L> attributeVector(const MaterialLaneInputs<L>& in, int first) {
  return {in.attribute[first], in.attribute[first + 1], in.attribute[first + 2]};
}

template <class L>
QUADRA_LANE_INLINE Vec3Lanes<L> normalized(const Vec3Lanes<L>& v) {
  using F = typename L::F;
  const F inverse = F(1.0f) / simd::sqrt(simd::max(shading::dot<L>(v, v), F(1e-30f)));
  return {v.x * inverse, v.y * inverse, v.z * inverse};
}

template <class L>
QUADRA_LANE_INLINE Vec3Lanes<L> cross(const Vec3Lanes<L>& a, const Vec3Lanes<L>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// v in view space turned into world space.
template <class L>
QUADRA_LANE_INLINE Vec3Lanes<L> toWorld(const glm::mat3& m, const Vec3Lanes<L>& v) {
  using F = typename L::F;
  return {F(m[0][0]) * v.x + F(m[1][0]) * v.y + F(m[2][0]) * v.z,
          F(m[0][1]) * v.x + F(m[1][1]) * v.y + F(m[2][1]) * v.z,
          F(m[0][2]) * v.x + F(m[1][2]) * v.y + F(m[2][2]) * v.z};
}

}  // namespace material_reads

// The base colour's alpha alone: factor x texture x COLOR_0 (what a masked
// draw's visibility pass tests).
template <class L>
QUADRA_LANE_INLINE typename L::F materialAlpha(const MaterialShading& m,
                                               const MaterialLaneInputs<L>& in) {
  using F = typename L::F;
  F a(m.baseColorFactor.a);
  if (m.baseColor.present()) {
    Rgba<L> texel = material_reads::lookup<L>(m.baseColor, m, in);
    a = a * texel.a;
  }
  if (m.color >= 0) a = a * in.attribute[m.color + 3];
  return a;
}

// The material at the lanes as the light sees it (LIGHTING.md "The
// material"), into s; returns the alpha, as the unlit shading makes it.
template <class L>
QUADRA_LANE_INLINE typename L::F materialSurface(const MaterialShading& m,
                                                 const MaterialLaneInputs<L>& in,
                                                 SurfaceLanes<L>& s) {
  using F = typename L::F;
  using namespace material_reads;
  // Base colour: factor x texture (sRGB-decoded when loaded) x COLOR_0.
  F r(m.baseColorFactor.r), g(m.baseColorFactor.g), b(m.baseColorFactor.b), a(m.baseColorFactor.a);
  if (m.baseColor.present()) {
    Rgba<L> texel = lookup<L>(m.baseColor, m, in);
    if (m.baseColor.view.premultiplied) texel = unpremultiplied<L>(texel);
    r = r * texel.r, g = g * texel.g, b = b * texel.b, a = a * texel.a;
  }
  if (m.color >= 0) {
    r = r * in.attribute[m.color], g = g * in.attribute[m.color + 1];
    b = b * in.attribute[m.color + 2], a = a * in.attribute[m.color + 3];
  }
  s.baseColor = {r, g, b};
  // Metallic and roughness: factors x texture B and G.
  s.metallic = F(m.metallic);
  s.roughness = F(m.roughness);
  if (m.metallicRoughness.present()) {
    const Rgba<L> texel = lookup<L>(m.metallicRoughness, m, in);
    s.metallic = s.metallic * texel.b;
    s.roughness = s.roughness * texel.g;
  }
  // The shading frame in view space: the interpolated normal and tangent
  // normalized, B = w N x T; a normal map's n = normalize(T x + B y + N z).
  Vec3Lanes<L> n = normalized<L>(attributeVector(in, m.normalAttribute));
  if (m.normal.present()) {
    const Rgba<L> texel = lookup<L>(m.normal, m, in);
    const F scale(m.normalScale);
    const F tx = (texel.r * F(2.0f) - F(1.0f)) * scale;
    const F ty = (texel.g * F(2.0f) - F(1.0f)) * scale;
    const F tz = texel.b * F(2.0f) - F(1.0f);
    // A minified normal map's filtered normal is shorter the more its
    // texels' normals spread: that spread widens the lobe.
    s.roughness = toksvigRoughness<L>(s.roughness, simd::sqrt(tx * tx + ty * ty + tz * tz));
    const Vec3Lanes<L> t = normalized<L>(attributeVector(in, m.tangent));
    const F sign = simd::select(in.attribute[m.tangent + 3] < F(0.0f), F(-1.0f), F(1.0f));
    const Vec3Lanes<L> bt = cross<L>(n, t);
    n = normalized<L>({t.x * tx + bt.x * sign * ty + n.x * tz,
                       t.y * tx + bt.y * sign * ty + n.y * tz,
                       t.z * tx + bt.z * sign * ty + n.z * tz});
  }
  // Occlusion scales the environment's light only.
  s.occlusion = F(1.0f);
  if (m.occlusion.present()) {
    const Rgba<L> texel = lookup<L>(m.occlusion, m, in);
    s.occlusion = F(1.0f) + F(m.occlusionStrength) * (texel.r - F(1.0f));
  }
  F er(m.emission.r), eg(m.emission.g), eb(m.emission.b);
  if (m.emissive.present()) {
    const Rgba<L> texel = lookup<L>(m.emissive, m, in);
    er = er * texel.r, eg = eg * texel.g, eb = eb * texel.b;
  }
  s.emission = {er, eg, eb};
  // KHR_materials_ior and _specular: the dielectric's f0 and f90, from the
  // weight (the texture's A) and the colour (its RGB, sRGB).
  F specular(m.specularFactor);
  if (m.specular.present()) specular = specular * lookup<L>(m.specular, m, in).a;
  F sr(m.specularColorFactor.r), sg(m.specularColorFactor.g), sb(m.specularColorFactor.b);
  if (m.specularColor.present()) {
    const Rgba<L> texel = lookup<L>(m.specularColor, m, in);
    sr = sr * texel.r, sg = sg * texel.g, sb = sb * texel.b;
  }
  s.dielectricF0 = shading::dielectricF0<L>(F(m.ior), {sr, sg, sb}, specular);
  s.dielectricF90 = specular;
  // World space: the view direction is toward the eye at the origin.
  const Vec3Lanes<L> p = attributeVector(in, m.position);
  const Vec3Lanes<L> offset = toWorld<L>(m.worldFromView, p);
  s.position = {offset.x + F(m.eye.x), offset.y + F(m.eye.y), offset.z + F(m.eye.z)};
  s.normal = toWorld<L>(m.worldFromView, n);
  s.view =
      toWorld<L>(m.worldFromView, normalized<L>({F(0.0f) - p.x, F(0.0f) - p.y, F(0.0f) - p.z}));
  return a;
}

// The material at the lanes and the radiance it sends toward the eye
// (LIGHTING.md "The light"), alpha as the unlit shading makes it.
template <class L>
QUADRA_LANE_INLINE Rgba<L> materialRadiance(const MaterialShading& m,
                                            const MaterialLaneInputs<L>& in) {
  SurfaceLanes<L> s;
  const typename L::F a = materialSurface<L>(m, in, s);
  const RgbLanes<L> radiance = surfaceRadiance<L>(*m.lighting, s);
  return {radiance.r, radiance.g, radiance.b, a};
}

// The shading AOVs of the lanes (docs/cli.md "AOVs"): the material's terms
// as materialRadiance lights them (roughness after Toksvig, the lobe's), and
// the light of each lobe; emission + diffuse + specular is materialRadiance's
// colour up to rounding.
template <class L>
struct MaterialAovLanes {
  RgbLanes<L> albedo;
  typename L::F roughness, metallic;
  RgbLanes<L> emission, diffuse, specular;
};

template <class L>
QUADRA_LANE_INLINE MaterialAovLanes<L> materialAovs(const MaterialShading& m,
                                                    const MaterialLaneInputs<L>& in) {
  SurfaceLanes<L> s;
  materialSurface<L>(m, in, s);
  const shading::LobePair<L> light = surfaceLobes<L>(*m.lighting, s);
  return {s.baseColor, s.roughness, s.metallic, s.emission, light.diffuse, light.specular};
}

}  // namespace quadra
