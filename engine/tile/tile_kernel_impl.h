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

#include <cstdint>

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
  LaneOffsets() {
    alignas(64) float xs[L::kWidth], ys[L::kWidth];
    for (int k = 0; k < L::kWidth; ++k) {
      xs[k] = float(2 * (k / 4) + k % 2);
      ys[k] = float((k / 2) % 2);
    }
    x = F::load_aligned(xs);
    y = F::load_aligned(ys);
  }
};

// Bit b of a group's packed coverage: row (b / kGroupWidth), column
// (b % kGroupWidth); the lane with that pixel gets it.
M groupMask(std::uint32_t packed) {
  std::uint32_t laneBits = 0;
  for (int k = 0; k < L::kWidth; ++k) {
    const int column = 2 * (k / 4) + k % 2, row = (k / 2) % 2;
    laneBits |= ((packed >> (row * kGroupWidth + column)) & 1u) << k;
  }
  return simd::maskFromBits<L>(laneBits);
}

// A plane rebased to the tile: value at local pixel centre (x, y) is c + dx*x + dy*y.
struct TilePlane {
  F dx, dy, c;
  F at(const F& x, const F& y) const { return c + dx * x + dy * y; }
};

TilePlane rebase(const Plane& p, const TriangleRecord& t, const TileBuffers& tile) {
  const Plane q = planeInTile(p, t, tile);
  return {F(q.dx), F(q.dy), F(q.c)};
}

// A triangle's edge functions prepared for 8x8 blocks: per edge, the offsets
// of the eight columns of a row, and the extremes over a block, so the
// per-block work is additions only (AVX2 has no 64-bit multiply).
struct BlockEdges {
  std::int64_t column[3][kBlockSize];
  std::int64_t rowStep[3];
  std::int64_t lowOffset[3], highOffset[3];  // min / max of E - E(corner) over the block

  explicit BlockEdges(const TriangleRecord& t) {
    const std::int64_t span = kBlockSize - 1;
    for (int e = 0; e < 3; ++e) {
      const EdgeFunction& f = t.edges[e];
      for (int c = 0; c < kBlockSize; ++c) column[e][c] = f.a * c;
      rowStep[e] = f.b;
      lowOffset[e] = std::min<std::int64_t>(0, f.a * span) + std::min<std::int64_t>(0, f.b * span);
      highOffset[e] = std::max<std::int64_t>(0, f.a * span) + std::max<std::int64_t>(0, f.b * span);
    }
  }
};

// The pixels of an 8x8 block inside both the tile's viewport part and the
// triangle's bbox: rows [rowBegin, rowEnd), columns [columnBegin, columnEnd),
// and as a mask, bit (row*8 + column). A small triangle's is a few bits, and
// the coverage loop visits only those.
struct BlockRange {
  int rowBegin, rowEnd, columnBegin, columnEnd;
  std::uint64_t mask;
  BlockRange(int bx, int by, int xBegin, int xEnd, int yBegin, int yEnd)
      : rowBegin(std::max(yBegin - by, 0)),
        rowEnd(std::min(yEnd - by, kBlockSize)),
        columnBegin(std::max(xBegin - bx, 0)),
        columnEnd(std::min(xEnd - bx, kBlockSize)) {
    const std::uint64_t rowBits = ((1u << columnEnd) - 1u) & ~((1u << columnBegin) - 1u);
    constexpr std::uint64_t kFirstColumn = 0x0101010101010101u;  // bit 0 of every row
    const std::uint64_t rows = kFirstColumn * rowBits;           // rowBits in every row
    const std::uint64_t below = rowEnd == kBlockSize ? ~0ull : (1ull << (rowEnd * kBlockSize)) - 1;
    mask = rows & below & ~((1ull << (rowBegin * kBlockSize)) - 1);
  }
};

// Coverage of the 8x8 block whose top-left pixel is (px, py) in the window,
// within `range`: bit (row*8 + column). Exact: integer edge functions
// (window/window_space.h).
std::uint64_t blockCoverage(const TriangleRecord& t, const BlockEdges& edges, int px, int py,
                            const BlockRange& range) {
  std::int64_t corner[3];
  bool full = true;
  for (int e = 0; e < 3; ++e) {
    corner[e] = t.edges[e].at(px, py);
    if (corner[e] + edges.highOffset[e] <= 0) return 0;
    full = full && corner[e] + edges.lowOffset[e] > 0;
  }
  if (full) return range.mask;
  std::uint64_t mask = 0;
  for (int row = range.rowBegin; row < range.rowEnd; ++row) {
    std::int64_t start[3];
    for (int e = 0; e < 3; ++e) start[e] = corner[e] + edges.rowStep[e] * row;
    std::uint64_t bits = 0;
    for (int c = range.columnBegin; c < range.columnEnd; ++c) {
      const bool inside = (start[0] + edges.column[0][c] > 0) &
                          (start[1] + edges.column[1][c] > 0) & (start[2] + edges.column[2][c] > 0);
      bits |= std::uint64_t(inside) << c;
    }
    mask |= bits << (row * kBlockSize);
  }
  return mask;
}

// A plane over lanes: the value at tile-local pixel centre (x, y) is
// c + dx*x + dy*y, with its coefficients broadcast (one triangle) or gathered
// per lane (the shading pass's pixels of several triangles).
using LanePlane = TilePlane;

// The colour of a draw's pixels at (x, y) from their triangles' 1/w and
// attribute/w planes; the one shading function of the forward path, the
// masked draws' alpha test and the shading pass, so all three agree bit for
// bit. kQuad takes the footprint from differences across each 2x2 quad
// (lanes in quad order, helper lanes included); otherwise the derivatives are
// the planes' own at each pixel centre: with U = u/w and W = 1/w, u = U/W and
// du/dx = (U_x - u W_x) / W.
template <bool kTextured, bool kVertexColor, bool kLit, bool kQuad, ShadeOutput kOutput>
QUADRA_LANE_INLINE Rgba<L> shadeColor(const ShadeState& shade, const F& x, const F& y,
                                      const LanePlane& invW, const LanePlane* attr) {
  // Perspective-correct: a = (a/w) / (1/w), with one exact division.
  const F w = F(1.0f) / invW.at(x, y);
  const auto attribute = [&](int index) { return attr[index].at(x, y) * w; };
  const AttributeLayout& layout = shade.attributes;
  F r = F(shade.baseColor.r), g = F(shade.baseColor.g), b = F(shade.baseColor.b),
    a = F(shade.baseColor.a);
  if constexpr (kTextured || kOutput != ShadeOutput::Color) {
    const F u = attribute(layout.texcoord), v = attribute(layout.texcoord + 1);
    if constexpr (kOutput == ShadeOutput::TexCoord) {
      r = u, g = v, b = F(0.0f), a = F(1.0f);
    } else {
      UvDerivatives<L> d;
      if constexpr (kQuad) {
        // Coarse derivatives: one footprint per quad, from its top-left pixel.
        const F u0 = simd::quadBroadcast<0>(u), v0 = simd::quadBroadcast<0>(v);
        d = {simd::quadBroadcast<1>(u) - u0, simd::quadBroadcast<1>(v) - v0,
             simd::quadBroadcast<2>(u) - u0, simd::quadBroadcast<2>(v) - v0};
      } else {
        const LanePlane& pu = attr[layout.texcoord];
        const LanePlane& pv = attr[layout.texcoord + 1];
        d = {(pu.dx - u * invW.dx) * w, (pv.dx - v * invW.dx) * w, (pu.dy - u * invW.dy) * w,
             (pv.dy - v * invW.dy) * w};
      }
      if constexpr (kOutput == ShadeOutput::Derivatives) {
        r = d.dudx, g = d.dvdx, b = d.dudy, a = d.dvdy;
      } else {
        const Rgba<L> texel = sampleTexture<L>(shade.texture, u, v, d);
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
          ShadeOutput kOutput_ = ShadeOutput::Color, bool kQuad_ = false>
struct Features {
  static constexpr bool kTextured = kTextured_, kVertexColor = kVertexColor_, kLit = kLit_,
                        kQuad = kQuad_;
  static constexpr AlphaMode kAlpha = kAlpha_;
  static constexpr ShadeOutput kOutput = kOutput_;
  static Rgba<L> color(const ShadeState& s, const F& x, const F& y, const LanePlane& invW,
                       const LanePlane* attr) {
    return shadeColor<kTextured, kVertexColor, kLit, kQuad, kOutput>(s, x, y, invW, attr);
  }
};

// One triangle's planes rebased to the tile: depth, and unless only depth is
// needed, 1/w and the attributes.
struct TrianglePlanes {
  TilePlane z, invW;
  TilePlane attr[kMaxShadedAttributes];
  TrianglePlanes(const ShadeState& s, const TriangleRecord& t, const Plane* planes,
                 const TileBuffers& tile, bool depthOnly = false) {
    z = rebase(planes[0], t, tile);
    if (depthOnly) return;
    invW = rebase(planes[1], t, tile);
    for (int k = 0; k < s.attributes.count; ++k) attr[k] = rebase(planes[2 + k], t, tile);
  }
};

// Forward path: one group of quads, coverage in; depth test, shading, alpha,
// blend and depth write as it goes.
template <class Feat>
struct ForwardShader {
  const ShadeState& shade;
  TileBuffers& tile;
  const TrianglePlanes planes;

  ForwardShader(const ShadeState& s, const TriangleRecord& t, const Plane* p, TileBuffers& tb)
      : shade(s), tile(tb), planes(s, t, p, tb) {}

  void shadeGroup(const F& x, const F& y, M cover, int index) const {
    float* const depth = tile.depth + index;
    const F zValue = planes.z.at(x, y);
    const F zOld = F::load_aligned(depth);
    if (shade.depthTest) cover = cover & (shade.depthGreater ? zValue > zOld : zValue < zOld);
    if (!simd::any(cover)) return;
    Rgba<L> c = Feat::color(shade, x, y, planes.invW, planes.attr);
    if (Feat::kAlpha == AlphaMode::Mask) cover = cover & (c.a >= F(shade.alphaCutoff));
    if (Feat::kAlpha != AlphaMode::Blend && Feat::kOutput != ShadeOutput::Derivatives)
      c.a = F(1.0f);  // A = dv/dy there
    if (!simd::any(cover)) return;
    float* const color[4] = {tile.color[0] + index, tile.color[1] + index, tile.color[2] + index,
                             tile.color[3] + index};
    write(cover, zValue, zOld, c, depth, color);
  }

  void write(const M& cover, const F& zValue, const F& zOld, const Rgba<L>& c, float* depth,
             float* const color[4]) const {
    const F src[4] = {c.r, c.g, c.b, c.a};
    if (shade.blend == BlendMode::Replace) {
      for (int k = 0; k < 4; ++k)
        simd::select(cover, src[k], F::load_aligned(color[k])).store_aligned(color[k]);
    } else if (shade.blend == BlendMode::Over) {
      // Premultiplied "over": dst = src*a + dst*(1 - a).
      const F keep = F(1.0f) - c.a;
      for (int k = 0; k < 3; ++k) {
        const F dst = F::load_aligned(color[k]);
        simd::select(cover, src[k] * c.a + dst * keep, dst).store_aligned(color[k]);
      }
      const F dstA = F::load_aligned(color[3]);
      simd::select(cover, c.a + dstA * keep, dstA).store_aligned(color[3]);
    } else {
      for (int k = 0; k < 4; ++k) {
        const F dst = F::load_aligned(color[k]);
        simd::select(cover, dst + src[k], dst).store_aligned(color[k]);
      }
    }
    if (shade.depthWrite) simd::select(cover, zValue, zOld).store_aligned(depth);
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

  void shadeGroup(const F& x, const F& y, M cover, int index) const {
    float* const depth = tile.depth + index;
    const F zValue = planes.z.at(x, y);
    const F zOld = F::load_aligned(depth);
    cover = cover & (shade.depthGreater ? zValue > zOld : zValue < zOld);
    if (!simd::any(cover)) return;
    if constexpr (Feat::kAlpha == AlphaMode::Mask) {
      const Rgba<L> c = Feat::color(shade, x, y, planes.invW, planes.attr);
      cover = cover & (c.a >= F(shade.alphaCutoff));
      if (!simd::any(cover)) return;
    }
    won = true;
    simd::select(cover, zValue, zOld).store_aligned(depth);
    float* const ids = reinterpret_cast<float*>(tile.visible + index);
    simd::select(cover, id, F::load_aligned(ids)).store_aligned(ids);
  }
};

// Walks the triangle's 8x8 blocks inside the tile and hands each group of
// quads with coverage to the shader (forward or visibility).
template <class ShaderT>
void rasterizeWith(const TriangleRecord& t, const ShaderT& shader, const TileBuffers& tile) {
  // Pixel range of the triangle inside this tile, tile-local, half-open.
  const int xBegin = std::max(t.minX - tile.originX, 0);
  const int yBegin = std::max(t.minY - tile.originY, 0);
  const int xEnd = std::min(t.maxX - tile.originX + 1, tile.width);
  const int yEnd = std::min(t.maxY - tile.originY + 1, tile.height);
  if (xBegin >= xEnd || yBegin >= yEnd) return;

  const BlockEdges edges(t);
  static const LaneOffsets lane;  // const after construction; per ISA namespace
  constexpr std::uint32_t kRowBits = (1u << kGroupWidth) - 1;

  for (int by = yBegin & ~(kBlockSize - 1); by < yEnd; by += kBlockSize) {
    for (int bx = xBegin & ~(kBlockSize - 1); bx < xEnd; bx += kBlockSize) {
      const BlockRange range(bx, by, xBegin, xEnd, yBegin, yEnd);
      const std::uint64_t coverage =
          blockCoverage(t, edges, tile.originX + bx, tile.originY + by, range);
      if (coverage == 0) continue;
      for (int gy = range.rowBegin & ~1; gy < range.rowEnd; gy += 2) {
        for (int gx = range.columnBegin / kGroupWidth * kGroupWidth; gx < range.columnEnd;
             gx += kGroupWidth) {
          const int shift = gy * kBlockSize + gx;
          const std::uint32_t packed = std::uint32_t((coverage >> shift) & kRowBits) |
                                       std::uint32_t((coverage >> (shift + kBlockSize)) & kRowBits)
                                           << kGroupWidth;
          if (packed == 0) continue;
          shader.shadeGroup(lane.x + F(float(bx + gx)), lane.y + F(float(by + gy)),
                            groupMask(packed), TileBuffers::index(bx + gx, by + gy));
        }
      }
    }
  }
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
  alignas(64) float lane[3][L::kWidth];
  for (int j = 0; j < planeCount; ++j) {
    for (int k = 0; k < L::kWidth; ++k) {
      const float* planes = table + std::size_t(ids[k]) * kShadePlaneStride + 3 * j;
      lane[0][k] = planes[0], lane[1][k] = planes[1], lane[2][k] = planes[2];
    }
    out[j] = {F::load_aligned(lane[0]), F::load_aligned(lane[1]), F::load_aligned(lane[2])};
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
    lanePlanes(run_.planes, tile_.visible + first, planeCount_, p);
    const F x = lane.x + F(float(TileBuffers::xAt(first)));
    const F y = lane.y + F(float(TileBuffers::yAt(first)));
    const Rgba<L> c = Feat::color(shade_, x, y, p[0], p + 1);
    c.r.store_aligned(tile_.color[0] + first);
    c.g.store_aligned(tile_.color[1] + first);
    c.b.store_aligned(tile_.color[2] + first);
    F(1.0f).store_aligned(tile_.color[3] + first);  // opaque and masked draws: alpha 1
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
    LanePlane p[1 + kMaxShadedAttributes];
    lanePlanes(run_.planes, ids, planeCount_, p);
    const Rgba<L> c = Feat::color(shade_, F::load_aligned(xs), F::load_aligned(ys), p[0], p + 1);
    c.r.store_aligned(out[0]);
    c.g.store_aligned(out[1]);
    c.b.store_aligned(out[2]);
    for (int k = 0; k < count; ++k) {
      for (int ch = 0; ch < 3; ++ch) tile_.color[ch][pixel[k]] = out[ch][k];
      tile_.color[3][pixel[k]] = 1.0f;
    }
  }

  void listed() const {
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

template <class Feat>
using QuadFeatures = Features<Feat::kTextured, Feat::kVertexColor, Feat::kLit, Feat::kAlpha,
                              ShadeOutput::Color, true>;

void rasterize(const TriangleRecord& t, const Plane* p, const ShadeState& s, TileBuffers& tile) {
  // Test views are opaque, untextured and unlit (api/renderer.cpp makeDraw).
  constexpr AlphaMode kOpaque = AlphaMode::Opaque;
  const bool quad = s.derivatives == DerivativeMode::Quad;
  if (s.output == ShadeOutput::TexCoord) {
    using Feat = Features<false, false, false, kOpaque, ShadeOutput::TexCoord>;
    return rasterizeWith(t, ForwardShader<Feat>(s, t, p, tile), tile);
  }
  if (s.output == ShadeOutput::Derivatives) {
    if (quad) {
      using Feat = Features<false, false, false, kOpaque, ShadeOutput::Derivatives, true>;
      return rasterizeWith(t, ForwardShader<Feat>(s, t, p, tile), tile);
    }
    using Feat = Features<false, false, false, kOpaque, ShadeOutput::Derivatives>;
    return rasterizeWith(t, ForwardShader<Feat>(s, t, p, tile), tile);
  }
  withFeatures(s, [&]<class Feat>() {
    if (quad) return rasterizeWith(t, ForwardShader<QuadFeatures<Feat>>(s, t, p, tile), tile);
    rasterizeWith(t, ForwardShader<Feat>(s, t, p, tile), tile);
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

const TileKernels& QUADRA_KERNEL_ENTRY(tileKernels)() {
  static const TileKernels kernels{QUADRA_KERNEL_ISA_ENUM, QUADRA_KERNEL_NAMESPACE::L::kWidth,
                                   &QUADRA_KERNEL_NAMESPACE::rasterize,
                                   &QUADRA_KERNEL_NAMESPACE::visibility,
                                   &QUADRA_KERNEL_NAMESPACE::shade};
  return kernels;
}

}  // namespace quadra
