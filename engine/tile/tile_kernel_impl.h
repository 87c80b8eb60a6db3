// The tile kernel source, compiled once per ISA. For one triangle and one
// tile, coarse 8x8 block accept/reject on exact integer edge functions, then
// 2x2 quads in SIMD lanes: coverage and the depth test, and then either the
// visibility pass's triangle id or, on the forward path, perspective-correct
// attributes, derivatives, LOD, texture sample, alpha and blend. The shading
// pass shades a draw's visible pixels, packed into lanes. One colour function
// (shadeColor) serves all three.
//
// Included only by the generated tile_kernel_<isa>.cpp files, each of which
// defines QUADRA_KERNEL_ISA_<isa>. Everything sits in an ISA-named namespace
// and an anonymous one, so no symbol compiled with one ISA's flags can be
// picked by the linker for another ISA's caller.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include "shading/background_lanes.h"
#include "shading/material_lanes.h"
#include "simd/kernel_isa.h"
#include "texture/sample_lanes.h"
#include "tile/tile_kernel.h"

namespace quadra {
namespace QUADRA_KERNEL_NAMESPACE {
namespace {

using L = simd::Lanes<QUADRA_KERNEL_ARCH>;
using F = L::F;
using I = L::I;
using M = L::M;

constexpr int kQuads = L::kQuads;
constexpr int kGroupWidth = 2 * kQuads;  // pixels per row in one lane group

// Lane k of a group is pixel (2*(k/4) + k%2, (k/2)%2) relative to the group.
struct LaneOffsets {
  F x, y;
  I xi, yi;
  LaneOffsets() {
    alignas(64) float xs[L::kWidth], ys[L::kWidth];
    alignas(64) std::int32_t xis[L::kWidth], yis[L::kWidth];
    for (int k = 0; k < L::kWidth; ++k) {
      xis[k] = 2 * (k / 4) + k % 2;
      yis[k] = (k / 2) % 2;
      xs[k] = float(xis[k]);
      ys[k] = float(yis[k]);
    }
    x = F::load_aligned(xs);
    y = F::load_aligned(ys);
    xi = I::load_aligned(xis);
    yi = I::load_aligned(yis);
  }
};

// A plane rebased to the tile: value at local pixel centre (x, y) is c + dx*x + dy*y.
struct TilePlane {
  F dx, dy, c;
  F at(const F& x, const F& y) const { return c + dx * x + dy * y; }
};

TilePlane rebase(const Plane& p, const TriangleRecord& t, const TileBuffers& tile) {
  const Plane q = planeInTile(p, t, tile);
  return {F(q.dx), F(q.dy), F(q.c)};
}

// The pixels of an 8x8 block inside both the tile's viewport part and the
// triangle's bbox: rows [rowBegin, rowEnd), columns [columnBegin, columnEnd).
// A small triangle's is a few pixels, and the coverage loop visits only those.
struct BlockRange {
  int rowBegin, rowEnd, columnBegin, columnEnd;
  BlockRange(int bx, int by, int xBegin, int xEnd, int yBegin, int yEnd)
      : rowBegin(std::max(yBegin - by, 0)),
        rowEnd(std::min(yEnd - by, kBlockSize)),
        columnBegin(std::max(xBegin - bx, 0)),
        columnEnd(std::min(xEnd - bx, kBlockSize)) {}
};

// A triangle's edge functions in 32-bit lanes, in the lanes' own pixel order:
// coverage without a bit per pixel to gather into lanes, for a triangle of
// any size. The lanes hold E / 256 rounded up, which is positive exactly
// where E is: a and b are multiples of kSubpixelScale (256; setup's
// makeEdge), so E = E(corner) + 256 L at a pixel with L integer, and E > 0
// exactly where L + ceil(E(corner) / 256) > 0. Over a block that an edge
// crosses that is at most 14 (|a| + |b|) / 256 + 1 < 2^28 in magnitude
// (a and b are int32), so it fits, and an edge positive over the whole
// block drops out of that block's test. (Unscaled, E fitted only for |a| +
// |b| < 2^27, and longer triangles, full-screen quads among them, took a
// scalar test per pixel: 6-7% of alpha-quads' multisampled frame.)
struct LaneEdges {
  std::int64_t low[3], high[3];  // min / max of E - E(corner) over a block
  std::int32_t a[3], b[3];       // the edges' a and b over kSubpixelScale
  I offset[3];                   // L at each lane's pixel from the group's corner

  // Whether the unscaled E fits 32-bit lanes over a crossing block (the
  // small-triangle paths, which take it unscaled).
  static bool fits(const TriangleRecord& t) {
    for (const EdgeFunction& f : t.edges)
      if (std::abs(std::int64_t(f.a)) + std::abs(std::int64_t(f.b)) >= (std::int64_t(1) << 27))
        return false;
    return true;
  }

  LaneEdges(const TriangleRecord& t, const LaneOffsets& lane) {
    const std::int64_t span = kBlockSize - 1;
    for (int e = 0; e < 3; ++e) {
      const std::int64_t fa = t.edges[e].a, fb = t.edges[e].b;
      low[e] = std::min<std::int64_t>(0, fa * span) + std::min<std::int64_t>(0, fb * span);
      high[e] = std::max<std::int64_t>(0, fa * span) + std::max<std::int64_t>(0, fb * span);
      a[e] = t.edges[e].a / kSubpixelScale, b[e] = t.edges[e].b / kSubpixelScale;
      offset[e] = I(a[e]) * lane.xi + I(b[e]) * lane.yi;
    }
  }
};

// One block's coverage from LaneEdges: the edges that cross the block, each
// with its values at the lanes of the block's first group.
class BlockLaneCoverage {
 public:
  // False when the block lies outside an edge. (px, py): the block's top-left
  // pixel in the window. Only the edges in `tested` (bit e: edge e) are
  // evaluated: the others hold over the whole tile.
  template <class Tested>
  QUADRA_LANE_INLINE bool start(const TriangleRecord& t, const LaneEdges& edges, Tested tested,
                                int px, int py) {
    crossing_ = 0;
    for (int e = 0; e < 3; ++e) {
      if (!(unsigned(tested) >> e & 1u)) continue;
      const std::int64_t corner = t.edges[e].at(px, py);
      if (corner + edges.high[e] <= 0) return false;
      if (corner + edges.low[e] > 0) continue;  // inside over the whole block
      const std::int64_t cornerOver256RoundedUp = -((-corner) >> kSubpixelBits);
      base_[crossing_] = I(std::int32_t(cornerOver256RoundedUp)) + edges.offset[e];
      a_[crossing_] = edges.a[e], b_[crossing_] = edges.b[e];
      ++crossing_;
    }
    return true;
  }

  // The lanes of the group at (gx, gy) in the block that the triangle covers.
  M group(int gx, int gy) const {
    if (crossing_ == 0) return F(0.0f) == F(0.0f);
    I value = base_[0] + I(a_[0] * gx + b_[0] * gy);
    for (int k = 1; k < crossing_; ++k)
      value = simd::min(value, base_[k] + I(a_[k] * gx + b_[k] * gy));
    return simd::toFloat(value) > F(0.0f);  // int to float keeps the sign and zero
  }

 private:
  int crossing_ = 0;
  I base_[3];
  std::int32_t a_[3], b_[3];
};

// A plane over lanes: the value at tile-local pixel centre (x, y) is
// c + dx*x + dy*y, with its coefficients broadcast (one triangle) or gathered
// per lane (the shading pass's pixels of several triangles).
using LanePlane = TilePlane;

// The exact derivatives of (u, v) at a pixel from the planes of u/w, v/w and
// 1/w (w = 1 / (1/w) there), by the quotient rule, times the draw's
// footprint scale: the footprint every analytic lookup takes.
QUADRA_LANE_INLINE UvDerivatives<L> analyticFootprint(const ShadeState& shade, const F& u,
                                                      const F& v, const F& w, const LanePlane& invW,
                                                      const LanePlane& pu, const LanePlane& pv) {
  const F scale(shade.footprintScale);
  return {(pu.dx - u * invW.dx) * w * scale, (pv.dx - v * invW.dx) * w * scale,
          (pu.dy - u * invW.dy) * w * scale, (pv.dy - v * invW.dy) * w * scale};
}

// The colour of a draw's pixels at (x, y) from their triangles' 1/w and
// attribute/w planes; the one shading function of the forward path, the
// masked draws' alpha test and the shading pass, so all three agree bit for
// bit. quadDerivatives takes the footprint from differences across each 2x2 quad
// (lanes in quad order, helper lanes included); otherwise the derivatives are
// the planes' own at each pixel centre: with U = u/w and W = 1/w, u = U/W and
// du/dx = (U_x - u W_x) / W.
// Whether shadeColor reads 1/w and the attribute planes: all but a draw of
// one colour (ShadeState::shadesOneColour, at run time).
constexpr bool readsPlanes(bool textured, bool vertexColor, bool lit, ShadeOutput output) {
  return textured || vertexColor || lit || output != ShadeOutput::Color;
}

// The footprint of (u, v) from differences across each 2x2 quad (lanes in
// quad order, helper lanes included): one per quad, from its top-left pixel.
QUADRA_LANE_INLINE UvDerivatives<L> quadFootprint(const ShadeState& shade, const F& u, const F& v) {
  const F u0 = simd::quadBroadcast<0>(u), v0 = simd::quadBroadcast<0>(v);
  UvDerivatives<L> d{simd::quadBroadcast<1>(u) - u0, simd::quadBroadcast<1>(v) - v0,
                     simd::quadBroadcast<2>(u) - u0, simd::quadBroadcast<2>(v) - v0};
  // Supersampled frames filter for the sample spacing (1 otherwise: exact).
  const F scale(shade.footprintScale);
  return {d.dudx * scale, d.dvdx * scale, d.dudy * scale, d.dvdy * scale};
}

// Lit shading (Shading::Pbr): every attribute the draw interpolates, each
// texture coordinate set's footprint as the unlit lookups take theirs, and
// then the shading stage's material and light (shading/material_lanes.h).
// value: the attributes' values, which the result points to.
QUADRA_LANE_INLINE MaterialLaneInputs<L> litMaterialInputs(const ShadeState& shade, const F& x,
                                                           const F& y, const LanePlane& invW,
                                                           const LanePlane* attr,
                                                           bool quadDerivatives, F* value) {
  const F w = F(1.0f) / invW.at(x, y);
  for (int k = 0; k < shade.attributes.count; ++k) value[k] = attr[k].at(x, y) * w;
  const MaterialShading& material = *shade.material;
  MaterialLaneInputs<L> in{value, {}};
  for (int set = 0; set < 2; ++set) {
    const int t = material.texcoordAttribute[set];
    if (t < 0) continue;
    in.footprint[set] = quadDerivatives ? quadFootprint(shade, value[t], value[t + 1])
                                        : analyticFootprint(shade, value[t], value[t + 1], w, invW,
                                                            attr[t], attr[t + 1]);
  }
  return in;
}

// Not inlined: one copy per ISA serves every specialization that may meet a
// lit draw.
[[gnu::noinline]] Rgba<L> litMaterialColor(const ShadeState& shade, const F& x, const F& y,
                                           const LanePlane& invW, const LanePlane* attr,
                                           bool quadDerivatives) {
  F value[kMaxShadedAttributes];
  const MaterialLaneInputs<L> in =
      litMaterialInputs(shade, x, y, invW, attr, quadDerivatives, value);
  return materialRadiance<L>(*shade.material, in);
}

// The shading AOVs' terms of a lit draw (materialAovs), at the same inputs
// as litMaterialColor; only the AOV pass calls it.
[[gnu::noinline]] MaterialAovLanes<L> litMaterialAovs(const ShadeState& shade, const F& x,
                                                      const F& y, const LanePlane& invW,
                                                      const LanePlane* attr) {
  F value[kMaxShadedAttributes];
  const MaterialLaneInputs<L> in = litMaterialInputs(shade, x, y, invW, attr, false, value);
  return materialAovs<L>(*shade.material, in);
}

// A lit draw's alpha alone, for the visibility pass's alpha test: the base
// colour's (materialAlpha), without the light.
[[gnu::noinline]] F litMaterialAlpha(const ShadeState& shade, const F& x, const F& y,
                                     const LanePlane& invW, const LanePlane* attr) {
  const F w = F(1.0f) / invW.at(x, y);
  F value[kMaxShadedAttributes];
  for (int k = 0; k < shade.attributes.count; ++k) value[k] = attr[k].at(x, y) * w;
  const MaterialShading& material = *shade.material;
  MaterialLaneInputs<L> in{value, {}};
  const int t =
      material.baseColor.present() ? material.texcoordAttribute[material.baseColor.texcoord] : -1;
  if (t >= 0)
    in.footprint[material.baseColor.texcoord] =
        analyticFootprint(shade, value[t], value[t + 1], w, invW, attr[t], attr[t + 1]);
  return materialAlpha<L>(material, in);
}

template <bool kTextured, bool kVertexColor, bool kLit, ShadeOutput kOutput>
QUADRA_LANE_INLINE Rgba<L> shadeColor(const ShadeState& shade, const F& x, const F& y,
                                      const LanePlane& invW, const LanePlane* attr,
                                      bool quadDerivatives) {
  if constexpr (kLit) {
    if (shade.material != nullptr)
      return litMaterialColor(shade, x, y, invW, attr, quadDerivatives);
  }
  // Perspective-correct: a = (a/w) / (1/w), with one exact division. A
  // colour that reads no plane reads no 1/w either (RunShader gathers none).
  F w(1.0f);
  if constexpr (readsPlanes(kTextured, kVertexColor, kLit, kOutput)) w = F(1.0f) / invW.at(x, y);
  const auto attribute = [&](int index) { return attr[index].at(x, y) * w; };
  const AttributeLayout& layout = shade.attributes;
  F r = F(shade.baseColor.r), g = F(shade.baseColor.g), b = F(shade.baseColor.b),
    a = F(shade.baseColor.a);
  if constexpr (kTextured || kOutput != ShadeOutput::Color) {
    const F u = attribute(layout.texcoord), v = attribute(layout.texcoord + 1);
    if constexpr (kOutput == ShadeOutput::TexCoord) {
      r = u, g = v, b = F(0.0f), a = F(1.0f);
    } else {
      const UvDerivatives<L> d =
          quadDerivatives ? quadFootprint(shade, u, v)
                          : analyticFootprint(shade, u, v, w, invW, attr[layout.texcoord],
                                              attr[layout.texcoord + 1]);
      if constexpr (kOutput == ShadeOutput::Derivatives) {
        r = d.dudx, g = d.dvdx, b = d.dudy, a = d.dvdy;
      } else {
        Rgba<L> texel = sampleTexture<L>(shade.texture, u, v, d);
        // Textures whose alpha is read filter premultiplied; shading is straight.
        if (shade.texture.premultiplied) texel = unpremultiplied<L>(texel);
        r = r * texel.r, g = g * texel.g, b = b * texel.b, a = a * texel.a;
      }
    }
  }
  if constexpr (kVertexColor) {
    r = r * attribute(layout.color);
    g = g * attribute(layout.color + 1);
    b = b * attribute(layout.color + 2);
    a = a * attribute(layout.color + 3);
  }
  if constexpr (kLit) {
    // Head light along the view direction: Lambert on the view-space normal.
    const F nx = attribute(layout.normal), ny = attribute(layout.normal + 1),
            nz = attribute(layout.normal + 2);
    const F length = simd::sqrt(nx * nx + ny * ny + nz * nz);
    const F facing = simd::abs(nz) / simd::max(length, F(1e-20f));
    const F light = F(0.15f) + F(0.85f) * simd::min(facing, F(1.0f));
    r = r * light, g = g * light, b = b * light;
  }
  return {r, g, b, a};
}

// The state a draw's kernels are specialized on (template parameters), so
// the inner loops carry no per-pixel branches for features a draw lacks.
template <bool kTextured_, bool kVertexColor_, bool kLit_, AlphaMode kAlpha_,
          ShadeOutput kOutput_ = ShadeOutput::Color>
struct Features {
  static constexpr bool kTextured = kTextured_, kVertexColor = kVertexColor_, kLit = kLit_;
  static constexpr AlphaMode kAlpha = kAlpha_;
  static constexpr ShadeOutput kOutput = kOutput_;
  // RunShader gathers the planes of a draw whose colour reads them, and the
  // tile stage rebases them (rebaseShadePlanes) for those draws alone.
  static constexpr bool kReadsPlanes = readsPlanes(kTextured, kVertexColor, kLit, kOutput);
  // quadDerivatives: the forward shader's lanes hold whole 2x2 quads, so it
  // can take a texture's footprint from their differences (a branch, not a
  // template parameter: another copy of every forward shader cost build time).
  static Rgba<L> color(const ShadeState& s, const F& x, const F& y, const LanePlane& invW,
                       const LanePlane* attr, bool quadDerivatives = false) {
    return shadeColor<kTextured, kVertexColor, kLit, kOutput>(s, x, y, invW, attr, quadDerivatives);
  }
  // The alpha a masked draw's visibility pass tests (the two-pass draws take
  // analytic footprints).
  static F alpha(const ShadeState& s, const F& x, const F& y, const LanePlane& invW,
                 const LanePlane* attr) {
    if constexpr (kLit)
      if (s.material != nullptr) return litMaterialAlpha(s, x, y, invW, attr);
    return color(s, x, y, invW, attr).a;
  }
};

// One triangle's planes rebased to the tile: depth, and unless only depth is
// needed, 1/w and the attributes.
struct TrianglePlanes {
  Plane depth;  // z rebased to the tile, as scalars
  TilePlane z, invW;
  TilePlane attr[kMaxShadedAttributes];
  TrianglePlanes(const ShadeState& s, const TriangleRecord& t, const Plane* planes,
                 const TileBuffers& tile, bool depthOnly = false) {
    depth = planeInTile(planes[0], t, tile);
    z = {F(depth.dx), F(depth.dy), F(depth.c)};
    if (depthOnly) return;
    invW = rebase(planes[1], t, tile);
    for (int k = 0; k < s.attributes.count; ++k) attr[k] = rebase(planes[2 + k], t, tile);
  }
};

// The lanes where a fragment at depth z passes `compare` against the stored
// depth. Uniform per draw, so the switch is one predicted branch per group.
QUADRA_LANE_INLINE M depthPasses(CompareFunction compare, const F& z, const F& stored) {
  switch (compare) {
    case CompareFunction::Never:
      return ~(F(0.0f) == F(0.0f));
    case CompareFunction::Less:
      return z < stored;
    case CompareFunction::Equal:
      return z == stored;
    case CompareFunction::LessEqual:
      return z <= stored;
    case CompareFunction::Greater:
      return z > stored;
    case CompareFunction::NotEqual:
      return z != stored;
    case CompareFunction::GreaterEqual:
      return z >= stored;
    case CompareFunction::Always:
      break;
  }
  return F(0.0f) == F(0.0f);
}

// A blend factor for channel `channel` (3: alpha) of premultiplied src and
// dst (scene/scene.h BlendFactor).
QUADRA_LANE_INLINE F blendFactor(BlendFactor factor, const F* src, const F* dst, int channel) {
  switch (factor) {
    case BlendFactor::Zero:
      return F(0.0f);
    case BlendFactor::One:
      return F(1.0f);
    case BlendFactor::SrcColor:
      return src[channel];
    case BlendFactor::OneMinusSrcColor:
      return F(1.0f) - src[channel];
    case BlendFactor::DstColor:
      return dst[channel];
    case BlendFactor::OneMinusDstColor:
      return F(1.0f) - dst[channel];
    case BlendFactor::SrcAlpha:
      return src[3];
    case BlendFactor::OneMinusSrcAlpha:
      return F(1.0f) - src[3];
    case BlendFactor::DstAlpha:
      return dst[3];
    case BlendFactor::OneMinusDstAlpha:
      break;
  }
  return F(1.0f) - dst[3];
}

// One channel of the blend: equation(s * sf, d * df); min and max take the
// unscaled values. Premultiplied "over" (One, OneMinusSrcAlpha) rounds as
// src + dst * (1 - a) did before blend state existed: s * 1 is exact.
QUADRA_LANE_INLINE F blendChannel(BlendEquation equation, const F& s, const F& sf, const F& d,
                                  const F& df) {
  switch (equation) {
    case BlendEquation::Add:
      return s * sf + d * df;
    case BlendEquation::Subtract:
      return s * sf - d * df;
    case BlendEquation::ReverseSubtract:
      return d * df - s * sf;
    case BlendEquation::Min:
      return simd::min(s, d);
    case BlendEquation::Max:
      break;
  }
  return simd::max(s, d);
}

// A premultiplied "over" step of straight colour c onto the covered lanes of
// `color`: c * a + dst * (1 - a), alpha included (blendChannel's Add of
// src * 1 and dst * (1 - a), bit for bit: s * 1 is exact).
QUADRA_LANE_INLINE void blendOver(const M& cover, const Rgba<L>& c, float* const color[4]) {
  const F src[4] = {c.r * c.a, c.g * c.a, c.b * c.a, c.a};
  const F keep = F(1.0f) - c.a;
  for (int k = 0; k < 4; ++k) {
    const F dst = F::load_aligned(color[k]);
    simd::select(cover, src[k] + dst * keep, dst).store_aligned(color[k]);
  }
}

// The covered lanes' fragments of straight colour c into sample plane
// `plane` of the fragment store, as "over" steps: premultiplied colour and
// alpha, and 1 - alpha of what lies behind (the products blendOver forms).
QUADRA_LANE_INLINE void deferOver(BlendedFragments& fragments, int plane, const M& cover,
                                  const F& zValue, const Rgba<L>& c, int index) {
  // Mostly the covered samples hold as many fragments as each other (a
  // triangle's neighbours arrived together): then the group's fragments go
  // into that one layer as a register a field. Otherwise, or at the budget,
  // lane by lane (BlendedFragments::add), as a field by field store per
  // lane was a sixth of overlapping-glass's frame.
  const std::uint32_t lanes = simd::bits(cover);
  const std::size_t first = std::size_t(plane) * TileBuffers::kPixels + std::size_t(index);
  std::uint8_t* const counts = fragments.counts() + first;
  const int layer = counts[std::countr_zero(lanes)];
  bool oneLayer = layer < BlendedFragments::kMaxPerSample;
  for (std::uint32_t rest = lanes; rest != 0 && oneLayer; rest &= rest - 1)
    oneLayer = counts[std::countr_zero(rest)] == layer;
  if (oneLayer) {
    const F fields[BlendedFragments::kFields] = {zValue,    c.r * c.a, c.g * c.a,
                                                 c.b * c.a, c.a,       F(1.0f) - c.a};
    for (int f = 0; f < BlendedFragments::kFields; ++f) {
      float* const to = fragments.field(layer, f) + first;
      simd::select(cover, fields[f], F::load_aligned(to)).store_aligned(to);
    }
    for (std::uint32_t rest = lanes; rest != 0; rest &= rest - 1)
      counts[std::countr_zero(rest)] = std::uint8_t(layer + 1);
    fragments.markTouched(first);
    return;
  }
  alignas(64) float z[L::kWidth], rgba[4][L::kWidth], keep[L::kWidth];
  zValue.store_aligned(z);
  (c.r * c.a).store_aligned(rgba[0]);
  (c.g * c.a).store_aligned(rgba[1]);
  (c.b * c.a).store_aligned(rgba[2]);
  c.a.store_aligned(rgba[3]);
  (F(1.0f) - c.a).store_aligned(keep);
  const float* const color[4] = {rgba[0], rgba[1], rgba[2], rgba[3]};
  fragments.add(plane, index, simd::bits(cover), z, color, keep);
}

// Forward path: one group of quads, coverage in; depth test, shading, alpha,
// blend and depth write as it goes.
template <class Feat>
struct ForwardShader {
  const ShadeState& shade;
  TileBuffers& tile;
  const TrianglePlanes planes;
  BlendedFragments* deferred;  // where a blended draw's fragments wait, or null
  int plane;                   // the tile's sample plane, for `deferred`
  // The premultiplied "over" preset (every glTF BLEND draw), blended without
  // the general state's per-channel switches: through them, alpha-quads'
  // frame took ~15% longer (quadra_bench, 1 thread).
  bool over;

  ForwardShader(const ShadeState& s, const TriangleRecord& t, const Plane* p, TileBuffers& tb,
                BlendedFragments* d = nullptr, int samplePlane = 0)
      : shade(s),
        tile(tb),
        planes(s, t, p, tb),
        deferred(d),
        plane(samplePlane),
        over(s.blend == BlendState::premultipliedOver()) {}

  bool depthWritten() const { return shade.depthWrite; }

  // Returns the group's depths after it (when the draw writes depth). Forced
  // inline: called, with the depth compare and blend state switches grown
  // into it, alpha-quads' blended raster ran 19% more instructions
  // (callgrind, AVX2).
  QUADRA_LANE_INLINE F shadeGroup(const F& x, const F& y, M cover, int index) const {
    float* const depth = tile.depth + index;
    const F zValue = planes.z.at(x, y);
    const F zOld = F::load_aligned(depth);
    if (shade.depthCompare != CompareFunction::Always)
      cover = cover & depthPasses(shade.depthCompare, zValue, zOld);
    if (!simd::any(cover)) return zOld;
    Rgba<L> c = Feat::color(shade, x, y, planes.invW, planes.attr,
                            shade.derivatives == DerivativeMode::Quad);
    if (Feat::kAlpha == AlphaMode::Mask) cover = cover & (c.a >= F(shade.alphaCutoff));
    if (Feat::kAlpha != AlphaMode::Blend && Feat::kOutput != ShadeOutput::Derivatives)
      c.a = F(1.0f);  // A = dv/dy there
    if (!simd::any(cover)) return zOld;
    if (deferred != nullptr) {
      // The late samples' fragments wait for the depth-order composite.
      const M late = F::load_unaligned(deferred->late(plane) + index) != F(0.0f);
      if (simd::any(cover & late)) deferOver(*deferred, plane, cover & late, zValue, c, index);
      cover = cover & ~late;
      if (!simd::any(cover)) return zOld;
    }
    float* const color[4] = {tile.color[0] + index, tile.color[1] + index, tile.color[2] + index,
                             tile.color[3] + index};
    write(cover, zValue, zOld, c, depth, color);
    return simd::select(cover, zValue, zOld);
  }

  // Any other blend state: out of line, so the raster loop that inlines
  // shadeGroup stays small for the common states.
  [[gnu::noinline]] static void blendWith(const BlendState& blend, const M& cover, const F* src,
                                          float* const color[4]) {
    const F dst[4] = {F::load_aligned(color[0]), F::load_aligned(color[1]),
                      F::load_aligned(color[2]), F::load_aligned(color[3])};
    for (int k = 0; k < 4; ++k) {
      const bool alpha = k == 3;
      const F sf = blendFactor(alpha ? blend.srcAlpha : blend.srcColor, src, dst, k);
      const F df = blendFactor(alpha ? blend.dstAlpha : blend.dstColor, src, dst, k);
      const F out =
          blendChannel(alpha ? blend.alphaEquation : blend.colorEquation, src[k], sf, dst[k], df);
      simd::select(cover, out, dst[k]).store_aligned(color[k]);
    }
  }

  void write(const M& cover, const F& zValue, const F& zOld, const Rgba<L>& c, float* depth,
             float* const color[4]) const {
    // The tile holds premultiplied colour; shading gives straight colour, and
    // only a blended draw's alpha is not 1 (the test views' A is no alpha).
    F src[4] = {c.r, c.g, c.b, c.a};
    if constexpr (Feat::kAlpha == AlphaMode::Blend)
      for (int k = 0; k < 3; ++k) src[k] = src[k] * c.a;
    const BlendState& blend = shade.blend;
    if (!blend.enabled) {
      for (int k = 0; k < 4; ++k)
        simd::select(cover, src[k], F::load_aligned(color[k])).store_aligned(color[k]);
    } else if (over) {
      blendOver(cover, c, color);
    } else {
      blendWith(blend, cover, src, color);
    }
    if (shade.depthWrite) simd::select(cover, zValue, zOld).store_aligned(depth);
  }
};

// Order pass for blended draws (tile/blended_fragments.h): one group of
// quads, coverage in; where a fragment passes the depth test strictly behind
// the sample's latest blended fragment, the sample is marked late.
struct BlendOrderShader {
  const ShadeState& shade;
  TileBuffers& tile;
  const TrianglePlanes planes;
  BlendedFragments& fragments;
  int plane;

  BlendOrderShader(const ShadeState& s, const TriangleRecord& t, const Plane* p, TileBuffers& tb,
                   BlendedFragments& f, int samplePlane)
      : shade(s), tile(tb), planes(s, t, p, tb, true), fragments(f), plane(samplePlane) {}

  bool depthWritten() const { return false; }

  F shadeGroup(const F& x, const F& y, M cover, int index) const {
    const F zValue = planes.z.at(x, y);
    const F zOld = F::load_aligned(tile.depth + index);
    // Only glTF BLEND draws come here, and they test "nearer".
    cover = cover & (shade.depthGreater ? zValue > zOld : zValue < zOld);
    if (!simd::any(cover)) return zOld;
    float* const latest = fragments.latest(plane) + index;
    float* const late = fragments.late(plane) + index;
    const F before = F::load_unaligned(latest);
    const M behind = shade.depthGreater ? zValue < before : zValue > before;
    simd::select(cover & behind, F(1.0f), F::load_unaligned(late)).store_unaligned(late);
    simd::select(cover, zValue, before).store_unaligned(latest);
    return zOld;
  }
};

// A blended draw shaded per pixel (shadeBlendedPixels), its first pass at one
// sample plane: one group of quads, coverage in; the samples the triangle
// covers and that pass the depth test get bit `plane` of
// BlendedFragments::covered.
struct BlendCoverageShader {
  const ShadeState& shade;
  TileBuffers& tile;
  const TrianglePlanes planes;
  std::int32_t* covered;
  I bit;

  BlendCoverageShader(const ShadeState& s, const TriangleRecord& t, const Plane* p, TileBuffers& tb,
                      BlendedFragments& f, int samplePlane)
      : shade(s),
        tile(tb),
        planes(s, t, p, tb, true),
        covered(reinterpret_cast<std::int32_t*>(f.covered())),
        bit(std::int32_t(1) << samplePlane) {}

  bool depthWritten() const { return false; }

  F shadeGroup(const F& x, const F& y, M cover, int index) const {
    const F zValue = planes.z.at(x, y);
    const F zOld = F::load_aligned(tile.depth + index);
    cover = cover & depthPasses(shade.depthCompare, zValue, zOld);
    if (!simd::any(cover)) return zOld;
    const I was = I::load_unaligned(covered + index);
    simd::asInt(simd::select(cover, simd::asFloat(was | bit), simd::asFloat(was)))
        .store_unaligned(covered + index);
    return zOld;
  }
};

// Visibility pass: one group of quads, coverage in; the depth test (and a
// masked draw's alpha test, with the same colour function as the shading
// pass), then depth and triangle id where the triangle wins.
template <class Feat>
struct VisibilityShader {
  const ShadeState& shade;
  TileBuffers& tile;
  const TrianglePlanes planes;
  const F id;  // the triangle's tile-local index, as float bits
  mutable bool won = false;

  VisibilityShader(const ShadeState& s, const TriangleRecord& t, const Plane* p, TileBuffers& tb,
                   std::uint32_t triangleId)
      : shade(s),
        tile(tb),
        planes(s, t, p, tb, Feat::kAlpha != AlphaMode::Mask),
        id(simd::asFloat(I(std::int32_t(triangleId)))) {}

  bool depthWritten() const { return true; }

  // Returns the group's depths after it.
  F shadeGroup(const F& x, const F& y, M cover, int index) const {
    float* const depth = tile.depth + index;
    const F zValue = planes.z.at(x, y);
    const F zOld = F::load_aligned(depth);
    cover = cover & (shade.depthGreater ? zValue > zOld : zValue < zOld);
    if (!simd::any(cover)) return zOld;
    if constexpr (Feat::kAlpha == AlphaMode::Mask) {
      cover = cover & (Feat::alpha(shade, x, y, planes.invW, planes.attr) >= F(shade.alphaCutoff));
      if (!simd::any(cover)) return zOld;
    }
    won = true;
    const F zNew = simd::select(cover, zValue, zOld);
    zNew.store_aligned(depth);
    float* const ids = reinterpret_cast<float*>(tile.visible + index);
    simd::select(cover, id, F::load_aligned(ids)).store_aligned(ids);
    return zNew;
  }
};

// Hierarchical depth for one triangle: the range of its depth plane over an
// 8x8 block against the block's bounds (TileBuffers::blockDepthMin/Max). The
// range is widened by 2^-20 of the plane's largest term, well past the
// rounding of the lanes' float evaluation (three roundings of 2^-24), so a
// block is skipped only where every sample's depth test would fail: the
// output does not change, only the work. The ordering compares skip blocks
// (the ...Equal ones only strictly beyond the bounds, where a depth equal to
// the bound would pass); Never skips every block; Equal, NotEqual and Always
// none.
class BlockDepthTest {
 public:
  BlockDepthTest() = default;  // for arrays filled before use
  BlockDepthTest(const Plane& z, const ShadeState& shade)
      : compare_(shade.depthCompare), z_{z.dx, z.dy, z.c} {
    const double span = kBlockSize - 1;
    low_ = std::min(0.0, z_.dx * span) + std::min(0.0, z_.dy * span);
    high_ = std::max(0.0, z_.dx * span) + std::max(0.0, z_.dy * span);
    // Coplanar layers at one depth hide each other's blocks: no margin there.
    margin_ = depthPlaneMargin(z_.c, z_.dx, z_.dy, kTileSize);
  }

  // Whether the triangle fails the depth test at every sample of the block
  // whose top-left pixel is (bx, by), tile-local. NaN ranges never fail.
  bool hidden(int bx, int by, int block, const TileBuffers& tile) const {
    return hiddenAt(slopeAt(bx, by), block, tile);
  }

  // hidden() in two parts, for planes that differ only in c (one triangle's
  // samples): the slopes' part at the block, shared, then each plane's test.
  double slopeAt(int bx, int by) const { return z_.dx * bx + z_.dy * by; }
  bool hiddenAt(double slope, int block, const TileBuffers& tile) const {
    return hiddenBehind(slope, tile.blockDepthMin[block], tile.blockDepthMax[block]);
  }
  // The test against bounds given: a block's own, or the widest of several
  // sample planes' bounds on it.
  bool hiddenBehind(double slope, float boundMin, float boundMax) const {
    const double base = z_.c + slope;
    switch (compare_) {
      case CompareFunction::Less:
        return base + low_ - margin_ >= boundMax;
      case CompareFunction::LessEqual:
        return base + low_ - margin_ > boundMax;
      case CompareFunction::Greater:
        return base + high_ + margin_ <= boundMin;
      case CompareFunction::GreaterEqual:
        return base + high_ + margin_ < boundMin;
      case CompareFunction::Never:
        return true;
      default:
        return false;
    }
  }

 private:
  CompareFunction compare_;
  struct {
    double dx, dy, c;
  } z_;
  double low_ = 0, high_ = 0, margin_ = 0;
};

// The block's depth bounds after a triangle wrote it: `low` and `high` are
// the lane-wise extremes of the depths of the groups it visited; exact when
// it visited all of the block's groups, else added to the old bounds.
QUADRA_LANE_INLINE void updateBlockDepth(TileBuffers& tile, int block, const F& low, const F& high,
                                         bool wholeBlock) {
  float lo, hi;
  simd::reduceMinMax<L>(low, high, lo, hi);
  if (!wholeBlock) {
    lo = std::min(lo, tile.blockDepthMin[block]);
    hi = std::max(hi, tile.blockDepthMax[block]);
  }
  tile.blockDepthMin[block] = lo;
  tile.blockDepthMax[block] = hi;
}

// The small-triangle path: a triangle whose part of the tile lies in one 8x8
// block (most of a dense mesh's) tests all three edges in lanes straight from
// the block's corner: no block walk, no per-block edge classification, none
// of LaneEdges' extremes (the walk ran ~750 instructions a call on
// dense-mesh). Exact, unscaled, when the edges fit (LaneEdges::fits) and
// each corner value is below 2^30 in magnitude: a lane's value is at most
// 7 (|a| + |b|) < 2^30 further. Returns false, having done nothing, for the rare triangles beyond
// that (a huge one the viewport clips to one block), which walk. Coverage is
// the walk's: an edge the walk drops over the block is positive at every lane
// here. Extending it to triangles over 2 x 2 blocks ran more instructions, as
// did any loop over blocks here (callgrind, dense-mesh, AVX2 path).
template <class ShadeBlock>
QUADRA_LANE_INLINE bool rasterizeInOneBlock(const TriangleRecord& t, const TileBuffers& tile,
                                            const LaneOffsets& lane,
                                            const BlockDepthTest& depthTest,
                                            const ShadeBlock& shadeBlock, int bx, int by,
                                            const BlockRange& range) {
  std::int64_t corner[3];
  for (int e = 0; e < 3; ++e) {
    corner[e] = t.edges[e].at(tile.originX + bx, tile.originY + by);
    if (std::uint64_t(corner[e] + (std::int64_t(1) << 30)) >= (std::uint64_t(1) << 31))
      return false;
  }
  const int block = TileBuffers::blockAt(bx, by);
  if (depthTest.hidden(bx, by, block, tile)) return true;
  I base[3];
  std::int32_t a[3], b[3];
  for (int e = 0; e < 3; ++e) {
    a[e] = t.edges[e].a, b[e] = t.edges[e].b;
    base[e] = I(std::int32_t(corner[e])) + I(a[e]) * lane.xi + I(b[e]) * lane.yi;
  }
  shadeBlock(bx, by, block, range, [&](int gx, int gy) {
    I value = base[0] + I(a[0] * gx + b[0] * gy);
    value = simd::min(value, base[1] + I(a[1] * gx + b[1] * gy));
    value = simd::min(value, base[2] + I(a[2] * gx + b[2] * gy));
    return simd::toFloat(value) > F(0.0f);  // int to float keeps the sign and zero
  });
  return true;
}

// The pixels of a triangle's box inside the tile, tile-local, half-open.
struct BoxInTile {
  int xBegin, yBegin, xEnd, yEnd;
  BoxInTile(const TriangleRecord& t, const TileBuffers& tile)
      : xBegin(std::max(t.minX - tile.originX, 0)),
        yBegin(std::max(t.minY - tile.originY, 0)),
        xEnd(std::min(t.maxX - tile.originX + 1, tile.width)),
        yEnd(std::min(t.maxY - tile.originY + 1, tile.height)) {}
  bool empty() const { return xBegin >= xEnd || yBegin >= yEnd; }
};

// Walks the triangle's 8x8 blocks inside the tile, skips those its depth
// leaves hidden, and hands each group of quads with coverage to the shader
// (forward or visibility), keeping the blocks' depth bounds.
template <class ShaderT>
void rasterizeWith(const TriangleRecord& t, const ShaderT& shader, TileBuffers& tile) {
  const BoxInTile box(t, tile);
  if (box.empty()) return;
  const int xBegin = box.xBegin, yBegin = box.yBegin, xEnd = box.xEnd, yEnd = box.yEnd;

  static const LaneOffsets lane;  // const after construction; per ISA namespace
  const BlockDepthTest depthTest(shader.planes.depth, shader.shade);
  const bool depthWritten = shader.depthWritten();
  constexpr int kGroupsPerBlock = kBlockSize * kBlockSize / L::kWidth;

  // The groups of one block inside `range` that coverOf(gx, gy, x, y) finds
  // covered go to the shader; the block's depth bounds follow what it wrote.
  const auto shadeBlock = [&](int bx, int by, int block, const BlockRange& range,
                              const auto& coverOf) {
    // Only a block the viewport's edge crosses has lanes to mask beyond it:
    // elsewhere the triangle's own edges keep it inside its bbox.
    const bool clipped = bx + kBlockSize > tile.width || by + kBlockSize > tile.height;
    F low(std::numeric_limits<float>::infinity()), high(-std::numeric_limits<float>::infinity());
    int visited = 0;
    for (int gy = range.rowBegin & ~1; gy < range.rowEnd; gy += 2) {
      for (int gx = range.columnBegin / kGroupWidth * kGroupWidth; gx < range.columnEnd;
           gx += kGroupWidth) {
        const F x = lane.x + F(float(bx + gx)), y = lane.y + F(float(by + gy));
        M cover = coverOf(gx, gy);
        if (clipped) cover = cover & (x < F(float(tile.width))) & (y < F(float(tile.height)));
        if (!simd::any(cover)) continue;
        const F depth = shader.shadeGroup(x, y, cover, TileBuffers::index(bx + gx, by + gy));
        if (!depthWritten) continue;  // the block's bounds stay as they are
        low = simd::min(low, depth), high = simd::max(high, depth);
        ++visited;
      }
    }
    if (visited > 0) updateBlockDepth(tile, block, low, high, visited == kGroupsPerBlock);
  };

  const int byFirst = yBegin & ~(kBlockSize - 1), bxFirst = xBegin & ~(kBlockSize - 1);
  if (((xBegin ^ (xEnd - 1)) | (yBegin ^ (yEnd - 1))) < kBlockSize && LaneEdges::fits(t) &&
      rasterizeInOneBlock(t, tile, lane, depthTest, shadeBlock, bxFirst, byFirst,
                          BlockRange(bxFirst, byFirst, xBegin, xEnd, yBegin, yEnd)))
    return;
  const LaneEdges edges(t, lane);
  BlockLaneCoverage coverage;
  // tested: a std::integral_constant for small triangles, so their block
  // test compiles to the plain three-edge one.
  const auto walk = [&](auto tested) {
    for (int by = byFirst; by < yEnd; by += kBlockSize) {
      for (int bx = bxFirst; bx < xEnd; bx += kBlockSize) {
        const int block = TileBuffers::blockAt(bx, by);
        if (depthTest.hidden(bx, by, block, tile)) continue;
        if (!coverage.start(t, edges, tested, tile.originX + bx, tile.originY + by)) continue;
        shadeBlock(bx, by, block, BlockRange(bx, by, xBegin, xEnd, yBegin, yEnd),
                   [&](int gx, int gy) { return coverage.group(gx, gy); });
      }
    }
  };
  // Small parts (a few blocks at most: nearly all of a dense mesh's) test
  // every edge in each block; a per-tile check would cost more than it
  // saves (dense-mesh's frame took 6% longer with one for every part).
  constexpr int kWholeTileCheckPixels = 4 * kBlockSize * kBlockSize;
  if ((xEnd - xBegin) * (yEnd - yBegin) < kWholeTileCheckPixels)
    return walk(std::integral_constant<unsigned, 0b111>());
  // Larger ones: an edge positive at the four corners of the lanes the walk
  // can visit (the triangle's part of the tile, widened to whole groups) is
  // positive at every one of them (E is linear), so the blocks skip it, and
  // a triangle that covers the tile there tests no edge at all.
  const int x0 = tile.originX + xBegin / kGroupWidth * kGroupWidth;
  const int x1 = tile.originX + (xEnd + kGroupWidth - 1) / kGroupWidth * kGroupWidth - 1;
  const int y0 = tile.originY + (yBegin & ~1), y1 = tile.originY + ((yEnd + 1) & ~1) - 1;
  unsigned tested = 0;
  for (int e = 0; e < 3; ++e) {
    const EdgeFunction& f = t.edges[e];
    const std::int64_t low = std::min({f.at(x0, y0), f.at(x1, y0), f.at(x0, y1), f.at(x1, y1)});
    tested |= unsigned(low <= 0) << e;
  }
  walk(tested);
}

// The planes of each lane's triangle (tile triangle ids per lane), broadcast
// when the lanes share one.
QUADRA_LANE_INLINE void lanePlanes(const float* table, const std::uint32_t* ids, int planeCount,
                                   LanePlane* out) {
  bool oneTriangle = true;
  for (int k = 1; k < L::kWidth; ++k) oneTriangle = oneTriangle && ids[k] == ids[0];
  if (oneTriangle) {
    const float* planes = table + std::size_t(ids[0]) * kShadePlaneStride;
    for (int j = 0; j < planeCount; ++j)
      out[j] = {F(planes[3 * j]), F(planes[3 * j + 1]), F(planes[3 * j + 2])};
    return;
  }
  const float* plane[L::kWidth];  // each lane's plane j; the table has a float past its end
  for (int k = 0; k < L::kWidth; ++k) plane[k] = table + std::size_t(ids[k]) * kShadePlaneStride;
  for (int j = 0; j < planeCount; ++j) {
    F coefficients[3];
    simd::loadTriples<L>(plane, coefficients);
    out[j] = {coefficients[0], coefficients[1], coefficients[2]};
    for (int k = 0; k < L::kWidth; ++k) plane[k] += 3;
  }
}

// Shading pass for one draw: its whole lane groups in place (the lanes in
// the tile's quad order, as the forward path has them), then its other
// pixels packed kWidth at a time, each lane with its own triangle's planes.
template <class Feat>
class RunShader {
 public:
  RunShader(const ShadeState& s, const ShadeRun& r, TileBuffers& t)
      : shade_(s), run_(r), tile_(t), planeCount_(1 + s.attributes.count) {}

  void group(int first) const {
    static const LaneOffsets lane;  // const after construction; per ISA namespace
    LanePlane p[1 + kMaxShadedAttributes];
    if constexpr (Feat::kReadsPlanes)
      lanePlanes(run_.planes, tile_.visible + first, planeCount_, p);
    const F x = lane.x + F(float(TileBuffers::xAt(first)));
    const F y = lane.y + F(float(TileBuffers::yAt(first)));
    const Rgba<L> c = Feat::color(shade_, x, y, p[0], p + 1);
    c.r.store_aligned(tile_.color[0] + first);
    c.g.store_aligned(tile_.color[1] + first);
    c.b.store_aligned(tile_.color[2] + first);
    F(1.0f).store_aligned(tile_.color[3] + first);  // opaque and masked draws: alpha 1
  }

  // R, G, B of the lanes' positions, each with its own triangle's planes.
  void shadeLanes(const F& x, const F& y, const std::uint32_t* ids, float (*out)[L::kWidth]) const {
    LanePlane p[1 + kMaxShadedAttributes];
    if constexpr (Feat::kReadsPlanes) lanePlanes(run_.planes, ids, planeCount_, p);
    const Rgba<L> c = Feat::color(shade_, x, y, p[0], p + 1);
    c.r.store_aligned(out[0]);
    c.g.store_aligned(out[1]);
    c.b.store_aligned(out[2]);
  }

  // `count` pixels (1..kWidth); lanes past them repeat the last and are not written.
  void packed(const std::uint16_t* pixels, int count) const {
    alignas(64) float xs[L::kWidth], ys[L::kWidth];
    alignas(64) float out[3][L::kWidth];
    alignas(64) std::uint32_t ids[L::kWidth];
    int pixel[L::kWidth];
    for (int k = 0; k < L::kWidth; ++k) {
      pixel[k] = pixels[std::min(k, count - 1)];
      xs[k] = float(TileBuffers::xAt(pixel[k]));
      ys[k] = float(TileBuffers::yAt(pixel[k]));
      ids[k] = tile_.visible[pixel[k]];
    }
    shadeLanes(F::load_aligned(xs), F::load_aligned(ys), ids, out);
    for (int k = 0; k < count; ++k) {
      for (int ch = 0; ch < 3; ++ch) tile_.color[ch][pixel[k]] = out[ch][k];
      tile_.color[3][pixel[k]] = 1.0f;
    }
  }

  // run_.jobs[first .. first+count) (count 1..kWidth), each at its own
  // position with its own triangle; colours to run_.jobColor.
  void jobs(int first, int count) const {
    alignas(64) float out[3][L::kWidth];
    alignas(64) std::uint32_t ids[L::kWidth];
    const float* job[L::kWidth];  // x, y and the triangle's bits: simd::loadTriples' records
    static_assert(offsetof(ShadeJob, x) == 0 && offsetof(ShadeJob, y) == 4 &&
                  sizeof(ShadeJob) >= 4 * sizeof(float));
    for (int k = 0; k < L::kWidth; ++k) {
      const ShadeJob& lane = run_.jobs[first + std::min(k, count - 1)];
      job[k] = reinterpret_cast<const float*>(&lane);
      ids[k] = lane.triangle;
    }
    F position[3];
    simd::loadTriples<L>(job, position);
    shadeLanes(position[0], position[1], ids, out);
    for (int k = 0; k < count; ++k)
      for (int ch = 0; ch < 3; ++ch) run_.jobColor[3 * (first + k) + ch] = out[ch][k];
  }

  void listed() const {
    for (int first = 0; first < run_.jobCount; first += L::kWidth)
      jobs(first, std::min(L::kWidth, run_.jobCount - first));
    for (int g = 0; g < run_.groupCount; ++g) group(run_.groups[g]);
    for (int first = 0; first < run_.pixelCount; first += L::kWidth)
      packed(run_.pixels + first, std::min(L::kWidth, run_.pixelCount - first));
  }

  // The whole tile: the lanes whose triangle is in the run's range, found by
  // two compares per group. Ids as int32 converted to float: kNoTriangle is
  // -1, below any id, and ids stay exact (the tile stage scans only below
  // kMaxScannedTriangles).
  void scanned() const {
    const F first(float(run_.firstTriangle)), end(float(run_.endTriangle));
    std::uint16_t pending[2 * L::kWidth];
    int pendingCount = 0;
    for (int index = 0; index < TileBuffers::kPixels; index += L::kWidth) {
      const F ids = simd::toFloat(
          I::load_aligned(reinterpret_cast<const std::int32_t*>(tile_.visible + index)));
      const std::uint32_t mine = simd::bits((ids >= first) & (ids < end));
      if (mine == 0) continue;
      if (mine == (1u << L::kWidth) - 1) {
        group(index);
        continue;
      }
      for (int k = 0; k < L::kWidth; ++k)
        if (mine >> k & 1u) pending[pendingCount++] = std::uint16_t(index + k);
      if (pendingCount >= L::kWidth) {
        packed(pending, L::kWidth);
        pendingCount -= L::kWidth;
        std::copy(pending + L::kWidth, pending + L::kWidth + pendingCount, pending);
      }
    }
    if (pendingCount > 0) packed(pending, pendingCount);
  }

 private:
  const ShadeState& shade_;
  const ShadeRun& run_;
  TileBuffers& tile_;
  int planeCount_;
};

// Calls visit.template operator()<Features<...>>() with the features the draw
// has: the one place a ShadeState becomes template parameters.
template <class Visit>
auto withFeatures(const ShadeState& s, Visit&& visit) {
  const auto alpha = [&]<bool kTex, bool kColor, bool kLit>() {
    switch (s.alphaMode) {
      case AlphaMode::Mask:
        return visit.template operator()<Features<kTex, kColor, kLit, AlphaMode::Mask>>();
      case AlphaMode::Blend:
        return visit.template operator()<Features<kTex, kColor, kLit, AlphaMode::Blend>>();
      case AlphaMode::Opaque:
        break;
    }
    return visit.template operator()<Features<kTex, kColor, kLit, AlphaMode::Opaque>>();
  };
  const auto lit = [&]<bool kTex, bool kColor>() {
    if (s.lit) return alpha.template operator()<kTex, kColor, true>();
    return alpha.template operator()<kTex, kColor, false>();
  };
  if (s.textured) {
    if (s.vertexColor) return lit.template operator()<true, true>();
    return lit.template operator()<true, false>();
  }
  if (s.vertexColor) return lit.template operator()<false, true>();
  return lit.template operator()<false, false>();
}

void rasterize(const TriangleRecord& t, const Plane* p, const ShadeState& s, TileBuffers& tile,
               BlendedFragments* deferred, int plane) {
  // Test views are opaque, untextured and unlit (api/renderer.cpp makeDraw).
  constexpr AlphaMode kOpaque = AlphaMode::Opaque;
  if (s.output == ShadeOutput::TexCoord) {
    using Feat = Features<false, false, false, kOpaque, ShadeOutput::TexCoord>;
    return rasterizeWith(t, ForwardShader<Feat>(s, t, p, tile), tile);
  }
  if (s.output == ShadeOutput::Derivatives) {
    using Feat = Features<false, false, false, kOpaque, ShadeOutput::Derivatives>;
    return rasterizeWith(t, ForwardShader<Feat>(s, t, p, tile), tile);
  }
  withFeatures(s, [&]<class Feat>() {
    rasterizeWith(t, ForwardShader<Feat>(s, t, p, tile, deferred, plane), tile);
  });
}

void orderBlended(const TriangleRecord& t, const Plane* p, const ShadeState& s, TileBuffers& tile,
                  BlendedFragments& fragments, int plane) {
  rasterizeWith(t, BlendOrderShader(s, t, p, tile, fragments, plane), tile);
}

void coverBlended(const TriangleRecord& t, const Plane* p, const ShadeState& s, TileBuffers& tile,
                  BlendedFragments& fragments, int plane) {
  rasterizeWith(t, BlendCoverageShader(s, t, p, tile, fragments, plane), tile);
}

// A blended draw's triangle shaded per pixel, after coverBlended at every
// sample plane: each pixel some sample of which it covers is shaded once, at
// the centre where it covers them all, else at the mean of their positions
// (meanSampleOffset's arithmetic, as the opaque draws' mixed pixels), and
// that colour is blended into, or deferred at, each covered sample with the
// sample's own depth. Clears the coverage words it reads.
template <class Feat>
void shadeBlendedPixelsWith(const TriangleRecord& t, const Plane* p, const ShadeState& s,
                            const SamplePattern& pattern, TileBuffers* samplePlanes,
                            BlendedFragments& fragments) {
  const TileBuffers& tile = samplePlanes[0];  // every plane has the tile's origin and size
  const BoxInTile box(t, tile);
  if (box.empty()) return;
  static const LaneOffsets lane;  // const after construction; per ISA namespace
  const TrianglePlanes planes(s, t, p, tile);
  const int samples = pattern.count;
  // Each sample's depth plane rebased to the tile, as the planes at that
  // sample's own pass rebase it (SampleDepths: the same bits).
  float depthC[kMaxSamples];
  sampleDepthsInTile(p[0], pattern, t, tile, samples, depthC);
  std::int32_t* const covered = reinterpret_cast<std::int32_t*>(fragments.covered());
  const bool orderPassRan = fragments.orderPassRan();
  const F allSamples(float((1 << samples) - 1));
  for (int gy = box.yBegin & ~1; gy < box.yEnd; gy += 2) {
    for (int gx = box.xBegin / kGroupWidth * kGroupWidth; gx < box.xEnd; gx += kGroupWidth) {
      const int index = TileBuffers::index(gx, gy);
      const I held = I::load_unaligned(covered + index);
      const F heldValue = simd::toFloat(held);  // at most 16 bits: exact
      const M any = heldValue != F(0.0f);
      if (!simd::any(any)) continue;
      I(0).store_unaligned(covered + index);
      const F x = lane.x + F(float(gx)), y = lane.y + F(float(gy));
      F shadeX = x, shadeY = y;
      const M partial = any & (heldValue != allSamples);
      if (simd::any(partial)) {
        F sumX(0.0f), sumY(0.0f), count(0.0f);  // whole numbers: exact
        for (int k = 0; k < samples; ++k) {
          const M in = simd::toFloat(held & I(std::int32_t(1) << k)) != F(0.0f);
          sumX = sumX + simd::select(in, F(float(pattern.offsets[k].x)), F(0.0f));
          sumY = sumY + simd::select(in, F(float(pattern.offsets[k].y)), F(0.0f));
          count = count + simd::select(in, F(1.0f), F(0.0f));
        }
        const F scale = F(1.0f) / (simd::max(count, F(1.0f)) * F(float(kSampleUnitsPerPixel)));
        shadeX = x + simd::select(partial, sumX * scale, F(0.0f));
        shadeY = y + simd::select(partial, sumY * scale, F(0.0f));
      }
      const Rgba<L> c = Feat::color(s, shadeX, shadeY, planes.invW, planes.attr);
      for (int k = 0; k < samples; ++k) {
        M cover = simd::toFloat(held & I(std::int32_t(1) << k)) != F(0.0f);
        if (!simd::any(cover)) continue;
        if (orderPassRan) {  // else no sample is late
          const M late = F::load_unaligned(fragments.late(k) + index) != F(0.0f);
          if (simd::any(cover & late)) {
            const TilePlane z{F(planes.depth.dx), F(planes.depth.dy), F(depthC[k])};
            deferOver(fragments, k, cover & late, z.at(x, y), c, index);
            cover = cover & ~late;
            if (!simd::any(cover)) continue;
          }
        }
        TileBuffers& plane = samplePlanes[k];
        float* const color[4] = {plane.color[0] + index, plane.color[1] + index,
                                 plane.color[2] + index, plane.color[3] + index};
        blendOver(cover, c, color);
      }
    }
  }
}

void shadeBlendedPixels(const TriangleRecord& t, const Plane* p, const ShadeState& s,
                        const SamplePattern& pattern, TileBuffers* samplePlanes,
                        BlendedFragments& fragments) {
  withFeatures(s, [&]<class Feat>() {
    if constexpr (Feat::kAlpha == AlphaMode::Blend)
      shadeBlendedPixelsWith<Feat>(t, p, s, pattern, samplePlanes, fragments);
  });
}

bool visibility(const TriangleRecord& t, const Plane* p, const ShadeState& s, std::uint32_t id,
                TileBuffers& tile) {
  const auto visit = [&]<class Feat>() {
    if constexpr (Feat::kAlpha == AlphaMode::Blend) {
      return false;  // blended draws take the forward path
    } else {
      const VisibilityShader<Feat> shader(s, t, p, tile, id);
      rasterizeWith(t, shader, tile);
      return shader.won;
    }
  };
  // Only a masked draw's alpha test shades here: the others need no features.
  if (s.alphaMode == AlphaMode::Mask) return withFeatures(s, visit);
  return visit.template operator()<Features<false, false, false, AlphaMode::Opaque>>();
}

// visibilityAtSamples for a small triangle (nearly all of a dense mesh's):
// its blocks, the edges' steps and the group walk once, and in each group
// every sample's coverage and depth test. The same bits as `visibility` on
// each plane with the triangle moved to its sample: the moved edges differ by
// whole integers (EdgeFunction::atSample), and each sample tests its moved
// depth plane. Returns -1, having done nothing, for larger triangles, which
// walk each plane with the tile-wide edge tests.
template <int kSamples>
int visibilitySmallAtSamples(const TriangleRecord& t, const Plane* p, const ShadeState& s,
                             std::uint32_t id, const SamplePattern& pattern, TileBuffers* planes) {
  const TileBuffers& tile = planes[0];  // every plane has the tile's origin and size
  const BoxInTile box(t, tile);
  if (box.empty()) return 0;
  const int xBegin = box.xBegin, yBegin = box.yBegin, xEnd = box.xEnd, yEnd = box.yEnd;
  constexpr int kSmallPixels = 4 * kBlockSize * kBlockSize;  // rasterizeWith's small parts
  if ((xEnd - xBegin) * (yEnd - yBegin) >= kSmallPixels || !LaneEdges::fits(t)) return -1;

  static const LaneOffsets lane;  // const after construction; per ISA namespace
  constexpr int samples = kSamples;
  std::int32_t a[3], b[3];
  std::int64_t high[3];  // max of E - E(corner) over a block
  I laneOffset[3];       // E - E(group corner) at each lane's pixel
  for (int e = 0; e < 3; ++e) {
    a[e] = t.edges[e].a, b[e] = t.edges[e].b;
    high[e] = std::max<std::int64_t>(0, std::int64_t(a[e]) * (kBlockSize - 1)) +
              std::max<std::int64_t>(0, std::int64_t(b[e]) * (kBlockSize - 1));
    laneOffset[e] = I(a[e]) * lane.xi + I(b[e]) * lane.yi;
  }
  // Arrays of the pattern's size, not kMaxSamples: this runs once per small
  // triangle, and zeroing 16 optional depth tests was 6% of its time (perf,
  // dense-mesh at 4 samples).
  std::int64_t shift[kSamples][3];  // each sample's edges minus the centre's
  TilePlane z[kSamples];
  BlockDepthTest depthTest[kSamples];
  float depthC[kSamples];
  sampleDepthsInTile(p[0], pattern, t, tile, kSamples, depthC);
  for (int k = 0; k < samples; ++k) {
    const SampleOffset o = pattern.offsets[k];
    for (int e = 0; e < 3; ++e) shift[k][e] = t.edges[e].sampleShift(o);
    const Plane depth{p[0].dx, p[0].dy, depthC[k]};
    z[k] = {F(depth.dx), F(depth.dy), F(depth.c)};
    depthTest[k] = BlockDepthTest(depth, s);
  }

  const F triangleId = simd::asFloat(I(std::int32_t(id)));
  constexpr int kGroupsPerBlock = kBlockSize * kBlockSize / L::kWidth;
  // A lane's edge value is within 7 (|a| + |b|) < 0.875 * 2^30 of its block
  // corner's (LaneEdges::fits), so a corner clamped to +-2^30 keeps every
  // lane's sign and stays inside 32 bits.
  constexpr std::int64_t kClamp = std::int64_t(1) << 30;
  I base[kSamples][3];  // per sample, the edges at the lanes of the block's first group
  F low[kSamples], highDepth[kSamples];
  int visited[kSamples];
  bool won = false;
  for (int by = yBegin & ~(kBlockSize - 1); by < yEnd; by += kBlockSize) {
    for (int bx = xBegin & ~(kBlockSize - 1); bx < xEnd; bx += kBlockSize) {
      const int block = TileBuffers::blockAt(bx, by);
      std::int64_t corner[3];
      for (int e = 0; e < 3; ++e) corner[e] = t.edges[e].at(tile.originX + bx, tile.originY + by);
      const double slope = depthTest[0].slopeAt(bx, by);  // the samples' planes share it
      std::uint32_t tested = 0;  // bit k: sample k may have coverage in the block
      for (int k = 0; k < samples; ++k) {
        if (depthTest[k].hiddenAt(slope, block, planes[k])) continue;
        const std::int64_t at[3] = {corner[0] + shift[k][0], corner[1] + shift[k][1],
                                    corner[2] + shift[k][2]};
        if (at[0] + high[0] <= 0 || at[1] + high[1] <= 0 || at[2] + high[2] <= 0) continue;
        for (int e = 0; e < 3; ++e)
          base[k][e] = I(std::int32_t(std::clamp(at[e], -kClamp, kClamp))) + laneOffset[e];
        tested |= 1u << k;
        low[k] = F(std::numeric_limits<float>::infinity());
        highDepth[k] = F(-std::numeric_limits<float>::infinity());
        visited[k] = 0;
      }
      if (tested == 0) continue;
      const bool clipped = bx + kBlockSize > tile.width || by + kBlockSize > tile.height;
      const BlockRange range(bx, by, xBegin, xEnd, yBegin, yEnd);
      for (int gy = range.rowBegin & ~1; gy < range.rowEnd; gy += 2) {
        for (int gx = range.columnBegin / kGroupWidth * kGroupWidth; gx < range.columnEnd;
             gx += kGroupWidth) {
          const F x = lane.x + F(float(bx + gx)), y = lane.y + F(float(by + gy));
          const M inTile = clipped ? (x < F(float(tile.width))) & (y < F(float(tile.height)))
                                   : F(0.0f) == F(0.0f);
          const I step[3] = {I(a[0] * gx + b[0] * gy), I(a[1] * gx + b[1] * gy),
                             I(a[2] * gx + b[2] * gy)};
          const int index = TileBuffers::index(bx + gx, by + gy);
          for (std::uint32_t left = tested; left != 0; left &= left - 1) {
            const int k = __builtin_ctz(left);
            I value = base[k][0] + step[0];
            value = simd::min(value, base[k][1] + step[1]);
            value = simd::min(value, base[k][2] + step[2]);
            M cover = (simd::toFloat(value) > F(0.0f)) & inTile;
            if (!simd::any(cover)) continue;
            // VisibilityShader::shadeGroup at sample k.
            float* const depth = planes[k].depth + index;
            const F zValue = z[k].at(x, y);
            const F zOld = F::load_aligned(depth);
            cover = cover & (s.depthGreater ? zValue > zOld : zValue < zOld);
            F zNow = zOld;
            if (simd::any(cover)) {
              won = true;
              zNow = simd::select(cover, zValue, zOld);
              zNow.store_aligned(depth);
              float* const ids = reinterpret_cast<float*>(planes[k].visible + index);
              simd::select(cover, triangleId, F::load_aligned(ids)).store_aligned(ids);
            }
            low[k] = simd::min(low[k], zNow), highDepth[k] = simd::max(highDepth[k], zNow);
            ++visited[k];
          }
        }
      }
      for (std::uint32_t left = tested; left != 0; left &= left - 1) {
        const int k = __builtin_ctz(left);
        if (visited[k] > 0)
          updateBlockDepth(planes[k], block, low[k], highDepth[k], visited[k] == kGroupsPerBlock);
      }
    }
  }
  return won ? 1 : 0;
}

// The quad-samples path's box of at most 2x2 pixels that is off the quad
// grid (an odd first column or row): ~45% of the calls on
// MetalRoughSpheresNoTextures at 4 samples, where walking the 2 or 4 grid
// quads it touches (callgrind: ~2.3 quads a call) tested mostly lanes
// outside it. Here one quad at the box's own corner holds its samples: its
// coverage and depths are the grid quads' lanes' (the same edge values and
// the same plane at the same pixels), and each covered sample is then
// tested and written alone, its pixels lying in different grid quads.
// Boxes that one or two own quads cover, taken the same way, ran more
// instructions there (docs/samples.md, the fourteenth session). `edge` and
// `z` are at the box's first pixel (xBegin, yBegin). Returns whether the
// triangle won a sample.
template <int kRegisters>
QUADRA_LANE_INLINE bool visibilityOffGridQuad(const I (&edge)[kRegisters][3],
                                              const TilePlane (&z)[kRegisters], const F& quadX,
                                              const F& quadY, const BoxInTile& box,
                                              bool depthGreater, std::uint32_t id,
                                              TileBuffers* planes) {
  static_assert(kRegisters * L::kWidth <= 64);
  const F x = quadX + F(float(box.xBegin)), y = quadY + F(float(box.yBegin));
  const M inBox = (x < F(float(box.xEnd))) & (y < F(float(box.yEnd)));
  alignas(64) float depths[kRegisters * L::kWidth];
  std::uint64_t covered = 0;  // bit r * kWidth + lane
  for (int r = 0; r < kRegisters; ++r) {
    I value = simd::min(simd::min(edge[r][0], edge[r][1]), edge[r][2]);
    const M cover = (simd::toFloat(value) > F(0.0f)) & inBox;
    z[r].at(x, y).store_aligned(depths + r * L::kWidth);
    covered |= std::uint64_t(simd::bits(cover)) << (r * L::kWidth);
  }
  if (covered == 0) return false;
  int index[4], block[4];  // per pixel j of the quad
  for (int j = 0; j < 4; ++j) {
    const int px = box.xBegin + (j & 1), py = box.yBegin + (j >> 1);
    index[j] = TileBuffers::index(px, py);
    block[j] = TileBuffers::blockAt(px, py);
  }
  bool won = false;
  for (; covered != 0; covered &= covered - 1) {
    // Lane 4k + j of the registers taken in turn is pixel j at sample k.
    const int lane = __builtin_ctzll(covered);
    TileBuffers& plane = planes[lane >> 2];
    const int pixel = index[lane & 3];
    const float depth = depths[lane];
    const float stored = plane.depth[pixel];
    if (!(depthGreater ? depth > stored : depth < stored)) continue;
    won = true;
    plane.depth[pixel] = depth;
    plane.visible[pixel] = id;
    // Widened by what was written: the bounds stay conservative.
    const int b = block[lane & 3];
    plane.blockDepthMin[b] = std::min(plane.blockDepthMin[b], depth);
    plane.blockDepthMax[b] = std::max(plane.blockDepthMax[b], depth);
  }
  return won;
}

// visibilityAtSamples for a tiny triangle (a box of at most 8x8 pixels:
// most of a dense mesh's) where kRegisters registers hold one quad's samples
// (TileKernelSelection::quadSampleRegisters: AVX-512 one at 4 samples, AVX2
// two). Lane 4k + j of register r is pixel j of the quad at sample
// r * kWidth / 4 + k, loaded from and stored to that sample's plane a quad
// (4 floats) at a time, so a quad's samples take one coverage and depth
// test per register, where visibilitySmallAtSamples tests each sample's
// lane group in turn, mostly empty for such a triangle (callgrind,
// dense-mesh at 4 samples: ~900 instructions a triangle there). The same
// bits: a lane's edge value is the moved edge's (the sample's shift
// (a/16) ox + (b/16) oy is exact, a and b being multiples of 256) and its
// depth the moved plane's, rounded as there. Exact in 32 bits without
// clamping: every lane lies within 10 px of the triangle's vertices on both
// axes, so |E| < 10 (|a| + |b|) < 2^31 (LaneEdges::fits). Returns -1,
// having done nothing, for other triangles.
template <int kSamples>
int visibilityQuadSamples(const TriangleRecord& t, const Plane* p, const ShadeState& s,
                          std::uint32_t id, const SamplePattern& pattern, TileBuffers* planes) {
  constexpr int kRegisters =
      TileKernelSelection::quadSampleRegisters(QUADRA_KERNEL_ISA_ENUM, L::kWidth, kSamples);
  if constexpr (kRegisters == 0) {
    return -1;
  } else {
    constexpr int kBox = TileKernelSelection::kQuadSamplesBox;
    constexpr int kSamplesPerRegister = L::kWidth / 4;
    if (t.maxX - t.minX >= kBox || t.maxY - t.minY >= kBox || !LaneEdges::fits(t)) return -1;
    const TileBuffers& tile = planes[0];  // every plane has the tile's origin and size
    const BoxInTile box(t, tile);
    if (box.empty()) return 0;
    const int xBegin = box.xBegin, yBegin = box.yBegin, xEnd = box.xEnd, yEnd = box.yEnd;
    // A box of at most 2x2 pixels off the quad grid takes one quad at its
    // own corner (visibilityOffGridQuad); others the grid's quads.
    const bool offGrid = xEnd - xBegin <= 2 && yEnd - yBegin <= 2 && ((xBegin | yBegin) & 1) != 0;
    // The first quad's top-left pixel.
    const int x0 = offGrid ? xBegin : xBegin & ~1, y0 = offGrid ? yBegin : yBegin & ~1;

    // Per lane: its pixel in the quad and its sample's offset.
    static const LaneOffsets lane;  // lanes 0-3 are one quad's pixels on every path
    // Each sample's depth plane, four samples a register of floats, and
    // each lane's sample's (repeated over the quad's pixels).
    constexpr int kFours = (kSamples + 3) / 4;
    const SampleDepths depths(p[0], t, tile);
    __m128 depthFour[kFours];
    for (int q = 0; q < kFours; ++q) depthFour[q] = depths.four(pattern, 4 * q);
    TilePlane z[kRegisters];
    for (int r = 0; r < kRegisters; ++r) {
      const int sample = r * kSamplesPerRegister;
      z[r] = {F(p[0].dx), F(p[0].dy), simd::repeatPerQuad<L>(depthFour[sample / 4], sample % 4)};
    }
    const I quadX = lane.xi & I(1), quadY = lane.yi;  // lane pixel within its quad
    const F quadXf = simd::toFloat(quadX), quadYf = lane.y;
    std::int32_t a[3], b[3];
    I edge[kRegisters][3];  // at each lane, at the first quad
    for (int e = 0; e < 3; ++e) {
      a[e] = t.edges[e].a, b[e] = t.edges[e].b;
      const std::int64_t corner = t.edges[e].at(tile.originX + x0, tile.originY + y0);
      const I atQuad = I(std::int32_t(corner)) + I(a[e]) * quadX + I(b[e]) * quadY;
      for (int r = 0; r < kRegisters; ++r)
        edge[r][e] =
            atQuad +
            I(a[e] / kSampleUnitsPerPixel) * I::load_aligned(pattern.quadLaneX + r * L::kWidth) +
            I(b[e] / kSampleUnitsPerPixel) * I::load_aligned(pattern.quadLaneY + r * L::kWidth);
    }
    if (offGrid)
      return visibilityOffGridQuad<kRegisters>(edge, z, quadXf, quadYf, box, s.depthGreater, id,
                                               planes)
                 ? 1
                 : 0;

    // Hierarchical depth over the (up to 2x2) blocks the quads touch: a block
    // is skipped where the sample plane nearest the viewer fails against the
    // widest of the planes' bounds there, so every sample fails (its plane is
    // behind that one, and BlockDepthTest's margin grows with |c| no faster
    // than c moves). Only past kHiddenTestQuads quads: for fewer, the test
    // (doubles, every plane's bounds) cost more than the quads' own depth
    // tests it spares, nearly all of them passing on a visible mesh
    // (1080p, 4 samples, 1 thread: raster 52 -> 48.5 ms on
    // MetalRoughSpheresNoTextures, 33 -> 30.5 on dense-mesh).
    constexpr int kHiddenTestQuads = 4;
    // The box in quads (every value here is non-negative: unsigned, the
    // divisions are shifts).
    const unsigned quadColumns = unsigned(xEnd - x0 + 1) / 2,
                   quadRows = unsigned(yEnd - y0 + 1) / 2;
    const int bx0 = int(unsigned(x0) / kBlockSize), by0 = int(unsigned(y0) / kBlockSize);
    std::uint32_t hiddenBlocks = 0;  // bit 2 * (by - by0) + (bx - bx0)
    if (quadColumns * quadRows > unsigned(kHiddenTestQuads)) {
      const bool farthestFirst = s.depthCompare == CompareFunction::Greater ||
                                 s.depthCompare == CompareFunction::GreaterEqual;
      alignas(16) float depthC[4 * kFours];
      for (int q = 0; q < kFours; ++q) _mm_store_ps(depthC + 4 * q, depthFour[q]);
      const float nearestC = farthestFirst ? *std::max_element(depthC, depthC + kSamples)
                                           : *std::min_element(depthC, depthC + kSamples);
      const BlockDepthTest depthTest(Plane{p[0].dx, p[0].dy, nearestC}, s);
      const int bx1 = (xEnd - 1) / kBlockSize, by1 = (yEnd - 1) / kBlockSize;
      for (int by = by0; by <= by1; ++by)
        for (int bx = bx0; bx <= bx1; ++bx) {
          const int block = by * TileBuffers::kBlocksPerRow + bx;
          float boundMin = planes[0].blockDepthMin[block],
                boundMax = planes[0].blockDepthMax[block];
          for (int k = 1; k < kSamples; ++k) {
            boundMin = std::min(boundMin, planes[k].blockDepthMin[block]);
            boundMax = std::max(boundMax, planes[k].blockDepthMax[block]);
          }
          const double slope = depthTest.slopeAt(bx * kBlockSize, by * kBlockSize);
          if (depthTest.hiddenBehind(slope, boundMin, boundMax))
            hiddenBlocks |= 1u << (2 * (by - by0) + (bx - bx0));
        }
    }

    const F triangleId = simd::asFloat(I(std::int32_t(id)));
    constexpr std::ptrdiff_t kPlaneFloats = sizeof(TileBuffers) / sizeof(float);
    F written[2] = {F(std::numeric_limits<float>::infinity()),
                    F(-std::numeric_limits<float>::infinity())};  // the depths written
    std::uint32_t writtenBlocks = 0;
    // A quad reaches past the tile only in an odd last column or row of it.
    const bool mayClip = ((tile.width & 1) != 0 && xEnd == tile.width) ||
                         ((tile.height & 1) != 0 && yEnd == tile.height);
    // Quad (column, row) of the box: its index, block and offset from the
    // first quad follow by shifts and additions, where computing them from
    // pixel positions per quad ran 1.3% more of this function's
    // instructions (callgrind, MetalRoughSpheresNoTextures at 4 samples).
    const int firstIndex = TileBuffers::index(x0, y0);
    constexpr int kQuadsPerBlock = kBlockSize / 2;
    for (unsigned row = 0; row < quadRows; ++row) {
      const int qy = y0 + 2 * int(row);
      const unsigned rowBits = 2 * (unsigned(qy) / kBlockSize - unsigned(by0));
      const int rowIndex = firstIndex + int(row) * 2 * kTileSize;
      for (unsigned column = 0; column < quadColumns; ++column) {
        const int qx = x0 + 2 * int(column);
        const unsigned blockBit =
            rowBits + (unsigned(x0 / 2) + column) / kQuadsPerBlock - unsigned(bx0);
        if (hiddenBlocks >> blockBit & 1u) continue;
        const std::int32_t dx = 2 * std::int32_t(column), dy = 2 * std::int32_t(row);
        const I step[3] = {I(a[0] * dx + b[0] * dy), I(a[1] * dx + b[1] * dy),
                           I(a[2] * dx + b[2] * dy)};
        const F x = quadXf + F(float(qx)), y = quadYf + F(float(qy));
        const bool clipped = mayClip && (qx + 2 > tile.width || qy + 2 > tile.height);
        const int index = rowIndex + 4 * int(column);
        // Without a branch on coverage or the depth test: a tiny triangle's
        // are at random, and mispredicted they cost more than the loads and
        // stores (of unchanged values where nothing passes) they would skip.
        std::uint32_t passed = 0;
        for (int r = 0; r < kRegisters; ++r) {
          I value = edge[r][0] + step[0];
          value = simd::min(value, edge[r][1] + step[1]);
          value = simd::min(value, edge[r][2] + step[2]);
          M cover = simd::toFloat(value) > F(0.0f);  // int to float keeps the sign and zero
          if (clipped) cover = cover & (x < F(float(tile.width))) & (y < F(float(tile.height)));
          TileBuffers& first = planes[r * kSamplesPerRegister];  // the register's first sample
          float* const depth = first.depth + index;
          const F zValue = z[r].at(x, y);
          const F zOld = simd::loadQuadsStrided<L>(depth, kPlaneFloats);
          cover = cover & (s.depthGreater ? zValue > zOld : zValue < zOld);
          simd::storeQuadsStrided<L>(simd::select(cover, zValue, zOld), depth, kPlaneFloats);
          float* const ids = reinterpret_cast<float*>(first.visible + index);
          simd::storeQuadsStrided<L>(
              simd::select(cover, triangleId, simd::loadQuadsStrided<L>(ids, kPlaneFloats)), ids,
              kPlaneFloats);
          written[0] = simd::min(written[0], simd::select(cover, zValue, written[0]));
          written[1] = simd::max(written[1], simd::select(cover, zValue, written[1]));
          passed |= simd::bits(cover);
        }
        writtenBlocks |= std::uint32_t(passed != 0) << blockBit;
      }
    }
    if (writtenBlocks == 0) return 0;
    // Every written block's bounds on every plane widened by what was written
    // (conservative: a plane's bounds need only contain its depths).
    float low, high;
    simd::reduceMinMax<L>(written[0], written[1], low, high);
    for (std::uint32_t left = writtenBlocks; left != 0; left &= left - 1) {
      const int bit = __builtin_ctz(left);
      const int block = (by0 + bit / 2) * TileBuffers::kBlocksPerRow + bx0 + bit % 2;
      for (int k = 0; k < kSamples; ++k) {
        planes[k].blockDepthMin[block] = std::min(planes[k].blockDepthMin[block], low);
        planes[k].blockDepthMax[block] = std::max(planes[k].blockDepthMax[block], high);
      }
    }
    return 1;
  }
}

bool visibilityAtSamples(const TriangleRecord& t, const Plane* p, const ShadeState& s,
                         std::uint32_t id, const SamplePattern& pattern, TileBuffers* planes) {
  const int small = withSampleCount(pattern.count, [&](auto samples) {
    constexpr int kSamples = decltype(samples)::value;
    const int tiny = visibilityQuadSamples<kSamples>(t, p, s, id, pattern, planes);
    return tiny >= 0 ? tiny : visibilitySmallAtSamples<kSamples>(t, p, s, id, pattern, planes);
  });
  if (small >= 0) return small == 1;
  // Larger triangles: each plane as a frame of its own, the triangle moved to its sample.
  bool won = false;
  for (int k = 0; k < pattern.count; ++k) {
    const Plane depth = p[0].atSample(pattern.offsets[k]);
    won |= visibility(atSample(t, pattern.offsets[k]), &depth, s, id, planes[k]);
  }
  return won;
}

// One lane group's jobs from jobs[first ..]: their positions and triangles,
// the last job repeated past count.
void gatherJobs(const ShadeJob* jobs, int first, int count, float* xs, float* ys,
                std::uint32_t* ids) {
  for (int k = 0; k < L::kWidth; ++k) {
    const ShadeJob& job = jobs[first + std::min(k, count - first - 1)];
    xs[k] = job.x, ys[k] = job.y, ids[k] = job.triangle;
  }
}

// The lod and anisotropy AOVs of a textured draw's pixels: the footprint
// shadeColor takes at each job's position and the level its filter reads there.
void footprintLevels(const ShadeState& s, const float* planes, const ShadeJob* jobs, int count,
                     float* lod, float* anisotropy) {
  const int planeCount = 1 + s.attributes.count;
  const int texcoord = s.attributes.texcoord;
  for (int first = 0; first < count; first += L::kWidth) {
    alignas(64) float xs[L::kWidth], ys[L::kWidth];
    alignas(64) std::uint32_t ids[L::kWidth];
    gatherJobs(jobs, first, count, xs, ys, ids);
    LanePlane p[1 + kMaxShadedAttributes];
    lanePlanes(planes, ids, planeCount, p);
    const F x = F::load_aligned(xs), y = F::load_aligned(ys);
    const F w = F(1.0f) / p[0].at(x, y);
    const F u = p[1 + texcoord].at(x, y) * w, v = p[2 + texcoord].at(x, y) * w;
    const UvDerivatives<L> d =
        analyticFootprint(s, u, v, w, p[0], p[1 + texcoord], p[2 + texcoord]);
    const FootprintLevel<L> level = footprintLevel<L>(s.texture, u, v, d);
    alignas(64) float levels[L::kWidth], probes[L::kWidth];
    level.lod.store_aligned(levels);
    level.anisotropy.store_aligned(probes);
    for (int k = 0; k < std::min(L::kWidth, count - first); ++k)
      lod[first + k] = levels[k], anisotropy[first + k] = probes[k];
  }
}

// The base colour an unlit draw shows (the albedo AOV of Shading::Unlit,
// Shading::Lit and KHR_materials_unlit draws): shadeColor without the light.
Rgba<L> unlitBaseColor(const ShadeState& s, const F& x, const F& y, const LanePlane& invW,
                       const LanePlane* attr) {
  constexpr ShadeOutput kColor = ShadeOutput::Color;
  if (s.textured)
    return s.vertexColor ? shadeColor<true, true, false, kColor>(s, x, y, invW, attr, false)
                         : shadeColor<true, false, false, kColor>(s, x, y, invW, attr, false);
  return s.vertexColor ? shadeColor<false, true, false, kColor>(s, x, y, invW, attr, false)
                       : shadeColor<false, false, false, kColor>(s, x, y, invW, attr, false);
}

// The shading AOVs of a draw's jobs (TileKernels::shadingAovs).
void shadingAovs(const ShadeState& s, const float* planes, const ShadeJob* jobs, int count,
                 float* out) {
  const int planeCount = 1 + s.attributes.count;
  // A draw of one colour reads no plane, and the tile stage rebased none.
  const bool readsPlanes = !s.shadesOneColour();
  for (int first = 0; first < count; first += L::kWidth) {
    alignas(64) float xs[L::kWidth], ys[L::kWidth];
    alignas(64) std::uint32_t ids[L::kWidth];
    gatherJobs(jobs, first, count, xs, ys, ids);
    LanePlane p[1 + kMaxShadedAttributes];
    if (readsPlanes) lanePlanes(planes, ids, planeCount, p);
    const F x = F::load_aligned(xs), y = F::load_aligned(ys);
    const F zero(0.0f);
    MaterialAovLanes<L> a{{zero, zero, zero}, zero, zero, {zero, zero, zero}, {zero, zero, zero},
                          {zero, zero, zero}};
    if (s.material != nullptr) {
      a = litMaterialAovs(s, x, y, p[0], p + 1);
    } else {
      const Rgba<L> c = unlitBaseColor(s, x, y, p[0], p + 1);
      a.albedo = {c.r, c.g, c.b};
    }
    const F* channels[kShadingAovFloats] = {
        &a.albedo.r,   &a.albedo.g,   &a.albedo.b,   &a.roughness, &a.metallic,
        &a.emission.r, &a.emission.g, &a.emission.b, &a.diffuse.r, &a.diffuse.g,
        &a.diffuse.b,  &a.specular.r, &a.specular.g, &a.specular.b};
    const int lanes = std::min(L::kWidth, count - first);
    for (int c = 0; c < kShadingAovFloats; ++c) {
      alignas(64) float values[L::kWidth];
      channels[c]->store_aligned(values);
      for (int k = 0; k < lanes; ++k)
        out[std::size_t(c) * std::size_t(count) + std::size_t(first + k)] = values[k];
    }
  }
}

void copyAgreeingSamples(TileBuffers* planes, int samples, const std::uint32_t* differs) {
  for (int k = 1; k < samples; ++k)
    for (int c = 0; c < 4; ++c) {
      const float* __restrict from = planes[0].color[c];
      float* __restrict to = planes[k].color[c];
      // A select on the bits, not a conditional store or a float select, so
      // it vectorizes (a branch per pixel made alpha-quads' 16-sample frame
      // 1.8x slower than shading every sample; the float select ran scalar,
      // 2.4 instructions a pixel).
      for (int p = 0; p < TileBuffers::kPixels; ++p) {
        const std::uint32_t fromPlane0 = differs[p] == 0 ? ~0u : 0u;
        to[p] = std::bit_cast<float>((std::bit_cast<std::uint32_t>(from[p]) & fromPlane0) |
                                     (std::bit_cast<std::uint32_t>(to[p]) & ~fromPlane0));
      }
    }
}

void averageSamples(TileBuffers* planes, int samples) {
  const float weight = 1.0f / float(samples);  // a power of two: exact
  for (int width = 1; width < samples; width *= 2)
    for (int k = 0; k + width < samples; k += 2 * width)
      for (int c = 0; c < 4; ++c) {
        float* __restrict sum = planes[k].color[c];
        const float* __restrict add = planes[k + width].color[c];
        for (int p = 0; p < TileBuffers::kPixels; ++p) sum[p] += add[p];
      }
  for (int c = 0; c < 4; ++c)
    for (int p = 0; p < TileBuffers::kPixels; ++p) planes[0].color[c][p] *= weight;
}

void nearestSampleDepth(TileBuffers* planes, int samples, bool depthGreater) {
  float* __restrict nearest = planes[0].depth;
  for (int k = 1; k < samples; ++k) {
    const float* __restrict depth = planes[k].depth;
    if (depthGreater)
      for (int p = 0; p < TileBuffers::kPixels; ++p) nearest[p] = std::max(nearest[p], depth[p]);
    else
      for (int p = 0; p < TileBuffers::kPixels; ++p) nearest[p] = std::min(nearest[p], depth[p]);
  }
}

// One lane group's kept fragments (layers [0, N), N the most any of its
// samples holds) sorted far to near per lane and composited over the group's
// colour. Ascending keys: standard depth negated (its far fragments hold the
// larger depths), equal depths by arrival (the layer). Layers a lane does
// not hold sort first, at -inf, and are skipped.
template <int N>
void compositeLayers(const BlendedFragments& fragments, std::size_t slot, const F& count,
                     float* const color[4]) {
  using Field = BlendedFragments::Field;
  F key[N], arrival[N], rgba[N][4], keep[N];
  for (int k = 0; k < N; ++k) {
    const F depth = F::load_aligned(fragments.field(k, Field::kDepth) + slot);
    arrival[k] = F(float(k));
    key[k] = simd::select(arrival[k] < count, fragments.depthGreater() ? depth : -depth,
                          F(-std::numeric_limits<float>::infinity()));
    for (int c = 0; c < 4; ++c)
      rgba[k][c] = F::load_aligned(fragments.field(k, Field::kRed + c) + slot);
    keep[k] = F::load_aligned(fragments.field(k, Field::kKeep) + slot);
  }
  const auto exchange = [](const M& where, F& a, F& b) {
    const F low = simd::select(where, b, a);
    b = simd::select(where, a, b);
    a = low;
  };
  // Odd-even transposition: N rounds of neighbour exchanges sort N keys.
  for (int round = 0; round < N; ++round)
    for (int k = round % 2; k + 1 < N; k += 2) {
      const M later =
          (key[k] > key[k + 1]) | ((key[k] == key[k + 1]) & (arrival[k] > arrival[k + 1]));
      if (!simd::any(later)) continue;
      exchange(later, key[k], key[k + 1]);
      exchange(later, arrival[k], arrival[k + 1]);
      for (int c = 0; c < 4; ++c) exchange(later, rgba[k][c], rgba[k + 1][c]);
      exchange(later, keep[k], keep[k + 1]);
    }
  F dst[4];
  for (int c = 0; c < 4; ++c) dst[c] = F::load_aligned(color[c]);
  for (int k = 0; k < N; ++k) {
    const M held = arrival[k] < count;
    for (int c = 0; c < 4; ++c) dst[c] = simd::select(held, rgba[k][c] + dst[c] * keep[k], dst[c]);
  }
  for (int c = 0; c < 4; ++c) dst[c].store_aligned(color[c]);
}

// compositeLayers<most>, most from 1 to the budget: compared in turn, so
// each call inlines (a table of pointers cost overlapping-glass 2-3%).
template <std::size_t... kIndex>
QUADRA_LANE_INLINE void compositeLayersFor(int most, std::index_sequence<kIndex...>,
                                           const BlendedFragments& fragments, std::size_t slot,
                                           const F& count, float* const color[4]) {
  ((most == int(kIndex) + 1 &&
    (compositeLayers<int(kIndex) + 1>(fragments, slot, count, color), true)) ||
   ...);
}

void compositeBlended(BlendedFragments& fragments, TileBuffers* planes) {
  constexpr int kGroupSlots = BlendedFragments::kGroupSlots;
  static_assert(kGroupSlots % L::kWidth == 0);
  const std::uint8_t* const counts = fragments.counts();
  const std::vector<std::uint64_t>& touched = fragments.touchedGroups();
  for (std::size_t w = 0; w < touched.size(); ++w)
    for (std::uint64_t bits = touched[w]; bits != 0; bits &= bits - 1) {
      const std::size_t group = w * 64 + std::size_t(std::countr_zero(bits));
      for (std::size_t slot = group * kGroupSlots; slot < (group + 1) * kGroupSlots;
           slot += L::kWidth) {
        alignas(64) float held[L::kWidth];
        int most = 0;
        for (int k = 0; k < L::kWidth; ++k) {
          held[k] = float(counts[slot + std::size_t(k)]);
          most = std::max(most, int(counts[slot + std::size_t(k)]));
        }
        if (most == 0) continue;
        TileBuffers& plane = planes[slot / TileBuffers::kPixels];
        const std::size_t pixel = slot % TileBuffers::kPixels;
        float* const color[4] = {plane.color[0] + pixel, plane.color[1] + pixel,
                                 plane.color[2] + pixel, plane.color[3] + pixel};
        const F count = F::load_aligned(held);
        compositeLayersFor(most,
                           std::make_index_sequence<std::size_t(BlendedFragments::kMaxPerSample)>(),
                           fragments, slot, count, color);
      }
    }
  fragments.clear();
}

void compositeBackground(const BackgroundView& view, TileBuffers& tile) {
  static const LaneOffsets lane;  // const after construction; per ISA namespace
  for (int first = 0; first < TileBuffers::kPixels; first += L::kWidth) {
    const F a = F::load_aligned(tile.color[3] + first);
    if (!simd::any(a < F(1.0f))) continue;
    const F x = lane.x + F(float(tile.originX + TileBuffers::xAt(first)) + 0.5f);
    const F y = lane.y + F(float(tile.originY + TileBuffers::yAt(first)) + 0.5f);
    const RgbLanes<L> behind = backgroundThroughPixels<L>(view, x, y);
    const F keep = F(1.0f) - a;
    float* const c[3] = {tile.color[0] + first, tile.color[1] + first, tile.color[2] + first};
    (F::load_aligned(c[0]) + keep * behind.r).store_aligned(c[0]);
    (F::load_aligned(c[1]) + keep * behind.g).store_aligned(c[1]);
    (F::load_aligned(c[2]) + keep * behind.b).store_aligned(c[2]);
    F(1.0f).store_aligned(tile.color[3] + first);
  }
}

void shade(const ShadeState& s, const ShadeRun& run, TileBuffers& tile) {
  withFeatures(s, [&]<class Feat>() {
    if constexpr (Feat::kAlpha != AlphaMode::Blend) {
      const RunShader<Feat> shader(s, run, tile);
      if (run.scanTile) return shader.scanned();
      shader.listed();
    }
  });
}

}  // namespace
}  // namespace QUADRA_KERNEL_NAMESPACE

// The filters for this ISA, compiled here once: the batch lookups of the same
// ISA (texture/sample_kernel_impl.h) call this copy rather than compiling
// their own, which took a fifth of the kernels' build time.
template Rgba<simd::Lanes<QUADRA_KERNEL_ARCH>> sampleTexture(
    const TextureView& view, const simd::Lanes<QUADRA_KERNEL_ARCH>::F& u,
    const simd::Lanes<QUADRA_KERNEL_ARCH>::F& v,
    const UvDerivatives<simd::Lanes<QUADRA_KERNEL_ARCH>>& d);

const TileKernels& QUADRA_KERNEL_ENTRY(tileKernels)() {
  static const TileKernels kernels{QUADRA_KERNEL_ISA_ENUM,
                                   QUADRA_KERNEL_NAMESPACE::L::kWidth,
                                   &QUADRA_KERNEL_NAMESPACE::rasterize,
                                   &QUADRA_KERNEL_NAMESPACE::orderBlended,
                                   &QUADRA_KERNEL_NAMESPACE::coverBlended,
                                   &QUADRA_KERNEL_NAMESPACE::shadeBlendedPixels,
                                   &QUADRA_KERNEL_NAMESPACE::compositeBlended,
                                   &QUADRA_KERNEL_NAMESPACE::visibility,
                                   &QUADRA_KERNEL_NAMESPACE::visibilityAtSamples,
                                   &QUADRA_KERNEL_NAMESPACE::shade,
                                   &QUADRA_KERNEL_NAMESPACE::copyAgreeingSamples,
                                   &QUADRA_KERNEL_NAMESPACE::averageSamples,
                                   &QUADRA_KERNEL_NAMESPACE::nearestSampleDepth,
                                   &QUADRA_KERNEL_NAMESPACE::footprintLevels,
                                   &QUADRA_KERNEL_NAMESPACE::shadingAovs,
                                   &QUADRA_KERNEL_NAMESPACE::compositeBackground};
  return kernels;
}

}  // namespace quadra
