// The tile kernel source, compiled once per ISA: for one triangle and one tile,
// coarse 8x8 block accept/reject on exact integer edge functions, then 2x2
// quads in SIMD lanes: coverage, depth test, perspective-correct attributes,
// quad derivatives, LOD, texture sample, alpha, blend.
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
  // In double, once per triangle and tile, so the per-pixel float evaluation
  // only ever spans one tile.
  const double c = double(p.c) + double(p.dx) * double(tile.originX - t.minX) +
                   double(p.dy) * double(tile.originY - t.minY);
  return {F(p.dx), F(p.dy), F(float(c))};
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

// Coverage of the 8x8 block whose top-left pixel is (px, py) in the window:
// bit (row*8 + column), limited to validMask, whose rows lie in
// [rowBegin, rowEnd). Exact: integer edge functions (window/window_space.h).
std::uint64_t blockCoverage(const TriangleRecord& t, const BlockEdges& edges, int px, int py,
                            std::uint64_t validMask, int rowBegin, int rowEnd) {
  std::int64_t corner[3];
  bool full = true;
  for (int e = 0; e < 3; ++e) {
    corner[e] = t.edges[e].at(px, py);
    if (corner[e] + edges.highOffset[e] <= 0) return 0;
    full = full && corner[e] + edges.lowOffset[e] > 0;
  }
  if (full) return validMask;
  std::uint64_t mask = 0;
  for (int row = rowBegin; row < rowEnd; ++row) {
    std::int64_t start[3];
    for (int e = 0; e < 3; ++e) start[e] = corner[e] + edges.rowStep[e] * row;
    std::uint64_t bits = 0;
    for (int c = 0; c < kBlockSize; ++c) {
      const bool inside = (start[0] + edges.column[0][c] > 0) &
                          (start[1] + edges.column[1][c] > 0) & (start[2] + edges.column[2][c] > 0);
      bits |= std::uint64_t(inside) << c;
    }
    mask |= bits << (row * kBlockSize);
  }
  return mask & validMask;
}

// Pixels of the block inside both the tile's viewport part and the triangle's bbox.
std::uint64_t blockValidMask(int bx, int by, int xBegin, int xEnd, int yBegin, int yEnd) {
  std::uint64_t rowBits = 0;
  for (int column = 0; column < kBlockSize; ++column)
    if (bx + column >= xBegin && bx + column < xEnd) rowBits |= 1u << column;
  std::uint64_t mask = 0;
  for (int row = 0; row < kBlockSize; ++row)
    if (by + row >= yBegin && by + row < yEnd) mask |= rowBits << (row * kBlockSize);
  return mask;
}

struct Attributes {
  F u, v;
  F r, g, b, a;
  F nx, ny, nz;
};

template <bool kTextured, bool kVertexColor, bool kLit, AlphaMode kAlpha,
          ShadeOutput kOutput = ShadeOutput::Color>
struct Shader {
  const ShadeState& shade;
  TilePlane z, invW;
  TilePlane attr[12];

  Shader(const ShadeState& s, const TriangleRecord& t, const Plane* planes, const TileBuffers& tile)
      : shade(s) {
    z = rebase(planes[0], t, tile);
    invW = rebase(planes[1], t, tile);
    for (int k = 0; k < s.attributes.count; ++k) attr[k] = rebase(planes[2 + k], t, tile);
  }

  F attribute(int index, const F& x, const F& y, const F& w) const {
    return attr[index].at(x, y) * w;
  }

  // One group of quads: coverage in, colour and depth out.
  void shadeGroup(const F& x, const F& y, M cover, float* depth, float* const color[4]) const {
    const F zValue = z.at(x, y);
    const F zOld = F::load_aligned(depth);
    if (shade.depthTest) cover = cover & (shade.depthGreater ? zValue > zOld : zValue < zOld);
    if (!simd::any(cover)) return;

    // Perspective-correct: a = (a/w) / (1/w), with one exact division.
    const F w = F(1.0f) / invW.at(x, y);
    const AttributeLayout& layout = shade.attributes;
    F r = F(shade.baseColor.r), g = F(shade.baseColor.g), b = F(shade.baseColor.b),
      a = F(shade.baseColor.a);
    if (kTextured || kOutput != ShadeOutput::Color) {
      const F u = attribute(layout.texcoord, x, y, w);
      const F v = attribute(layout.texcoord + 1, x, y, w);
      if constexpr (kOutput == ShadeOutput::TexCoord) {
        r = u, g = v, b = F(0.0f), a = F(1.0f);
      } else {
        // Coarse derivatives: one footprint per quad, from its top-left pixel.
        const F u0 = simd::quadBroadcast<0>(u), v0 = simd::quadBroadcast<0>(v);
        const UvDerivatives<L> d{simd::quadBroadcast<1>(u) - u0, simd::quadBroadcast<1>(v) - v0,
                                 simd::quadBroadcast<2>(u) - u0, simd::quadBroadcast<2>(v) - v0};
        if constexpr (kOutput == ShadeOutput::Derivatives) {
          r = d.dudx, g = d.dvdx, b = d.dudy, a = d.dvdy;
        } else {
          const Rgba<L> texel = sampleTexture<L>(shade.texture, u, v, d);
          r = r * texel.r, g = g * texel.g, b = b * texel.b, a = a * texel.a;
        }
      }
    }
    if (kVertexColor) {
      r = r * attribute(layout.color, x, y, w);
      g = g * attribute(layout.color + 1, x, y, w);
      b = b * attribute(layout.color + 2, x, y, w);
      a = a * attribute(layout.color + 3, x, y, w);
    }
    if (kLit) {
      // Head light along the view direction: Lambert on the view-space normal.
      const F nx = attribute(layout.normal, x, y, w), ny = attribute(layout.normal + 1, x, y, w),
              nz = attribute(layout.normal + 2, x, y, w);
      const F length = simd::sqrt(nx * nx + ny * ny + nz * nz);
      const F facing = simd::abs(nz) / simd::max(length, F(1e-20f));
      const F light = F(0.15f) + F(0.85f) * simd::min(facing, F(1.0f));
      r = r * light, g = g * light, b = b * light;
    }
    if (kAlpha == AlphaMode::Mask) cover = cover & (a >= F(shade.alphaCutoff));
    if (kAlpha != AlphaMode::Blend && kOutput != ShadeOutput::Derivatives) a = F(1.0f);
    if (!simd::any(cover)) return;
    write(cover, zValue, zOld, r, g, b, a, depth, color);
  }

  void write(const M& cover, const F& zValue, const F& zOld, const F& r, const F& g, const F& b,
             const F& a, float* depth, float* const color[4]) const {
    const F src[4] = {r, g, b, a};
    if (shade.blend == BlendMode::Replace) {
      for (int c = 0; c < 4; ++c)
        simd::select(cover, src[c], F::load_aligned(color[c])).store_aligned(color[c]);
    } else if (shade.blend == BlendMode::Over) {
      // Premultiplied "over": dst = src*a + dst*(1 - a).
      const F keep = F(1.0f) - a;
      for (int c = 0; c < 3; ++c) {
        const F dst = F::load_aligned(color[c]);
        simd::select(cover, src[c] * a + dst * keep, dst).store_aligned(color[c]);
      }
      const F dstA = F::load_aligned(color[3]);
      simd::select(cover, a + dstA * keep, dstA).store_aligned(color[3]);
    } else {
      for (int c = 0; c < 4; ++c) {
        const F dst = F::load_aligned(color[c]);
        simd::select(cover, dst + src[c], dst).store_aligned(color[c]);
      }
    }
    if (shade.depthWrite) simd::select(cover, zValue, zOld).store_aligned(depth);
  }
};

template <class ShaderT>
void rasterizeWith(const TriangleRecord& t, const Plane* planes, const ShadeState& shade,
                   TileBuffers& tile) {
  // Pixel range of the triangle inside this tile, tile-local, half-open.
  const int xBegin = std::max(t.minX - tile.originX, 0);
  const int yBegin = std::max(t.minY - tile.originY, 0);
  const int xEnd = std::min(t.maxX - tile.originX + 1, tile.width);
  const int yEnd = std::min(t.maxY - tile.originY + 1, tile.height);
  if (xBegin >= xEnd || yBegin >= yEnd) return;

  const ShaderT shader(shade, t, planes, tile);
  const BlockEdges edges(t);
  static const LaneOffsets lane;  // const after construction; per ISA namespace
  constexpr std::uint32_t kRowBits = (1u << kGroupWidth) - 1;

  for (int by = yBegin & ~(kBlockSize - 1); by < yEnd; by += kBlockSize) {
    for (int bx = xBegin & ~(kBlockSize - 1); bx < xEnd; bx += kBlockSize) {
      const std::uint64_t valid = blockValidMask(bx, by, xBegin, xEnd, yBegin, yEnd);
      const std::uint64_t coverage =
          blockCoverage(t, edges, tile.originX + bx, tile.originY + by, valid,
                        std::max(yBegin - by, 0), std::min(yEnd - by, kBlockSize));
      if (coverage == 0) continue;
      for (int gy = 0; gy < kBlockSize; gy += 2) {
        for (int gx = 0; gx < kBlockSize; gx += kGroupWidth) {
          const int shift = gy * kBlockSize + gx;
          const std::uint32_t packed = std::uint32_t((coverage >> shift) & kRowBits) |
                                       std::uint32_t((coverage >> (shift + kBlockSize)) & kRowBits)
                                           << kGroupWidth;
          if (packed == 0) continue;
          const int index = TileBuffers::index(bx + gx, by + gy);
          float* const color[4] = {tile.color[0] + index, tile.color[1] + index,
                                   tile.color[2] + index, tile.color[3] + index};
          shader.shadeGroup(lane.x + F(float(bx + gx)), lane.y + F(float(by + gy)),
                            groupMask(packed), tile.depth + index, color);
        }
      }
    }
  }
}

template <bool kTextured, bool kVertexColor, bool kLit>
void dispatchAlpha(const TriangleRecord& t, const Plane* p, const ShadeState& s,
                   TileBuffers& tile) {
  switch (s.alphaMode) {
    case AlphaMode::Opaque:
      return rasterizeWith<Shader<kTextured, kVertexColor, kLit, AlphaMode::Opaque>>(t, p, s, tile);
    case AlphaMode::Mask:
      return rasterizeWith<Shader<kTextured, kVertexColor, kLit, AlphaMode::Mask>>(t, p, s, tile);
    case AlphaMode::Blend:
      return rasterizeWith<Shader<kTextured, kVertexColor, kLit, AlphaMode::Blend>>(t, p, s, tile);
  }
}

template <bool kTextured, bool kVertexColor>
void dispatchLit(const TriangleRecord& t, const Plane* p, const ShadeState& s, TileBuffers& tile) {
  if (s.lit) return dispatchAlpha<kTextured, kVertexColor, true>(t, p, s, tile);
  dispatchAlpha<kTextured, kVertexColor, false>(t, p, s, tile);
}

// Specialize on the state the draw actually has (template parameters), so
// the inner loop carries no per-pixel branches for features it does not use.
// Test views are opaque, untextured and unlit (api/renderer.cpp makeDraw).
void rasterize(const TriangleRecord& t, const Plane* p, const ShadeState& s, TileBuffers& tile) {
  constexpr AlphaMode kOpaque = AlphaMode::Opaque;
  if (s.output == ShadeOutput::TexCoord)
    return rasterizeWith<Shader<false, false, false, kOpaque, ShadeOutput::TexCoord>>(t, p, s,
                                                                                      tile);
  if (s.output == ShadeOutput::Derivatives)
    return rasterizeWith<Shader<false, false, false, kOpaque, ShadeOutput::Derivatives>>(t, p, s,
                                                                                         tile);
  if (s.textured) {
    if (s.vertexColor) return dispatchLit<true, true>(t, p, s, tile);
    return dispatchLit<true, false>(t, p, s, tile);
  }
  if (s.vertexColor) return dispatchLit<false, true>(t, p, s, tile);
  dispatchLit<false, false>(t, p, s, tile);
}

}  // namespace
}  // namespace QUADRA_KERNEL_NAMESPACE

const TileKernels& QUADRA_KERNEL_ENTRY(tileKernels)() {
  static const TileKernels kernels{QUADRA_KERNEL_ISA_ENUM, QUADRA_KERNEL_NAMESPACE::L::kWidth,
                                   &QUADRA_KERNEL_NAMESPACE::rasterize};
  return kernels;
}

}  // namespace quadra
