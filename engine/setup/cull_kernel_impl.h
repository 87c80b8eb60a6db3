// The cull kernel for one ISA (included by the generated per-ISA file; see
// cull_kernel.h for what it decides).
#pragma once

#include "setup/cull_kernel.h"
#include "simd/kernel_isa.h"

namespace quadra {
namespace QUADRA_KERNEL_NAMESPACE {
namespace {

using L = simd::Lanes<QUADRA_KERNEL_ARCH>;
using F = L::F;
using I = L::I;
using M = L::M;
constexpr int kLanes = L::kWidth;
static_assert(kLanes <= kMaxCullLanes);

// Lanes holding a non-zero value. Every value tested here is below 2^24, so
// the float conversion is exact and the float mask's bits serve.
std::uint32_t nonZero(const I& v) {
  return simd::bits(simd::toFloat(v) != F(0.0f));
}

// First and last pixel index whose centre px + 0.5 lies in [lo, hi] (1/256
// units), clamped to [0, limit): setup's pixel span, per lane.
void pixelSpan(const I& lo, const I& hi, int limit, I& first, I& last) {
  const I half(kSubpixelScale / 2);
  first = simd::max(I(0) - ((half - lo) >> kSubpixelBits), I(0));
  last = simd::min((hi - half) >> kSubpixelBits, I(limit - 1));
}

int lanesSet(std::uint32_t bits) {
  return __builtin_popcount(bits);
}

// Which of the `tested` triangles (boxes of at most kCoverageBox pixels a
// side) cover a sample of a pixel of their box. Per edge p->q the edge
// function of window/window_space.h's grid, dx (Y - yp) - dy (X - xp) plus
// one on top and left edges, at each sample position (X, Y) of each pixel:
// the deltas are below 2^11 and the positions within 2^11 of the vertices,
// so every product and sum is an integer below 2^24, exact in float. A
// triangle of negative area has its edges reversed: deltas of the other
// sign, the same line.
std::uint32_t coveringSamples(const I (&x)[3], const I (&y)[3], const M& negative, const I& minX,
                              const I& minY, const I& maxX, const I& maxY,
                              const SamplePattern& samples, std::uint32_t tested) {
  const F sign = simd::select(negative, F(-1.0f), F(1.0f));
  const F centreX = simd::toFloat((minX << kSubpixelBits) + I(kSubpixelScale / 2));
  const F centreY = simd::toFloat((minY << kSubpixelBits) + I(kSubpixelScale / 2));
  F edge[3], stepX[3], stepY[3], dxUnit[3], dyUnit[3];  // at the box's first pixel centre
  for (int e = 0; e < 3; ++e) {
    const int p = (e + 1) % 3, q = (e + 2) % 3;  // setup's edge e runs from corner e+1 to e+2
    const F dx = simd::toFloat(x[q] - x[p]) * sign, dy = simd::toFloat(y[q] - y[p]) * sign;
    const M topLeft = (dy < F(0.0f)) | ((dy == F(0.0f)) & (dx > F(0.0f)));
    edge[e] = dx * (centreY - simd::toFloat(y[p])) - dy * (centreX - simd::toFloat(x[p])) +
              simd::select(topLeft, F(1.0f), F(0.0f));
    stepX[e] = dy * F(-float(kSubpixelScale)), stepY[e] = dx * F(float(kSubpixelScale));
    constexpr float kSampleUnit = float(kSubpixelScale / kSampleUnitsPerPixel);
    dxUnit[e] = dx * F(kSampleUnit), dyUnit[e] = dy * F(kSampleUnit);
  }
  const F width = simd::toFloat(maxX - minX), height = simd::toFloat(maxY - minY);
  M inBox[kCoverageBox][kCoverageBox];
  for (int j = 0; j < kCoverageBox; ++j)
    for (int i = 0; i < kCoverageBox; ++i)
      inBox[j][i] = (F(float(i)) <= width) & (F(float(j)) <= height);
  M covered = F(0.0f) != F(0.0f);
  for (int s = 0; s < samples.count; ++s) {
    const F ox(float(samples.offsets[s].x)), oy(float(samples.offsets[s].y));
    F row[3];
    for (int e = 0; e < 3; ++e) row[e] = edge[e] + dxUnit[e] * oy - dyUnit[e] * ox;
    for (int j = 0; j < kCoverageBox; ++j) {
      F at[3] = {row[0], row[1], row[2]};
      for (int i = 0; i < kCoverageBox; ++i) {
        covered = covered | ((simd::min(simd::min(at[0], at[1]), at[2]) > F(0.0f)) & inBox[j][i]);
        for (int e = 0; e < 3; ++e) at[e] = at[e] + stepX[e];
      }
      for (int e = 0; e < 3; ++e) row[e] = row[e] + stepY[e];
    }
    // Most triangles are found at their first sample.
    if ((tested & ~simd::bits(covered)) == 0) break;
  }
  return tested & simd::bits(covered);
}

void cull(const std::uint32_t* indices, int count, const SubpixelPosition* subpixel,
          const std::uint8_t* outcode, const Viewport& viewport, const SamplePattern& samples,
          int reach, FaceCulling faces, CullGroup& out) {
  // A short group repeats its first triangle, so the gather below has no
  // per-lane test.
  alignas(64) std::uint32_t padded[3 * kLanes];
  if (count < kLanes) {
    for (int k = 0; k < 3 * kLanes; ++k) padded[k] = indices[k < 3 * count ? k : k % 3];
    indices = padded;
  }
  // The vertices are scattered: loaded one by one into lanes (the hardware
  // gathers are slower on this project's machines).
  I x[3], y[3], code[3];
  for (int k = 0; k < 3; ++k) {  // a corner at a time, each index loaded once
    const auto vertex = [&](int t) { return indices[3 * t + k]; };
    x[k] = simd::laneInts<L>([&](int t) { return subpixel[vertex(t)].x; });
    y[k] = simd::laneInts<L>([&](int t) { return subpixel[vertex(t)].y; });
    code[k] = simd::laneInts<L>([&](int t) { return std::int32_t(outcode[vertex(t)]); });
  }
  const I x0 = x[0], x1 = x[1], x2 = x[2], y0 = y[0], y1 = y[1], y2 = y[2];
  const I c0 = code[0], c1 = code[1], c2 = code[2];
  std::uint32_t rest = (1u << count) - 1;  // count <= kLanes <= 16

  constexpr std::int32_t kOutsideViewport =
      kOutsideNear | kOutsideFar | kOutsideLeft | kOutsideRight | kOutsideBottom | kOutsideTop;
  const I some = c0 | c1 | c2;
  const std::uint32_t notFinite = nonZero(some & I(kNotFinite)) & rest;
  rest &= ~notFinite;
  const std::uint32_t outside = nonZero(c0 & c1 & c2 & I(kOutsideViewport)) & rest;
  rest &= ~outside;
  out.clip = nonZero(some & I(kNeedsClipping)) & rest;
  rest &= ~out.clip;

  // The area's cross product dx1*dy2 - dx2*dy1: the deltas (below 2^23) are
  // exact floats and each product is rounded once, and rounding is
  // monotonic, so products that differ as floats differ the same way
  // exactly. Equal ones (area 0, or a difference below their rounding) are
  // decided in int64.
  const F p = simd::toFloat(x1 - x0) * simd::toFloat(y2 - y0);
  const F q = simd::toFloat(x2 - x0) * simd::toFloat(y1 - y0);
  std::uint32_t negative = simd::bits(p < q);
  std::uint32_t degenerate = 0;
  for (std::uint32_t tie = rest & ~(negative | simd::bits(p > q)); tie; tie &= tie - 1) {
    const int t = __builtin_ctz(tie);
    const SubpixelPosition v0 = subpixel[indices[3 * t]], v1 = subpixel[indices[3 * t + 1]],
                           v2 = subpixel[indices[3 * t + 2]];
    const std::int64_t area = (std::int64_t(v1.x) - v0.x) * (std::int64_t(v2.y) - v0.y) -
                              (std::int64_t(v2.x) - v0.x) * (std::int64_t(v1.y) - v0.y);
    if (area < 0) negative |= 1u << t;
    if (area == 0) degenerate |= 1u << t;
  }
  rest &= ~degenerate;
  std::uint32_t backFace = 0;
  if (faces.cullBackFaces) {
    // glTF front faces are counter-clockwise with y up: negative area here.
    backFace = rest & (faces.frontIsClockwise ? negative : ~negative);
    rest &= ~backFace;
  }

  I minX, maxX, minY, maxY;
  const I widen(reach);
  const I lowX = simd::min(simd::min(x0, x1), x2), highX = simd::max(simd::max(x0, x1), x2);
  const I lowY = simd::min(simd::min(y0, y1), y2), highY = simd::max(simd::max(y0, y1), y2);
  pixelSpan(lowX - widen, highX + widen, viewport.width, minX, maxX);
  pixelSpan(lowY - widen, highY + widen, viewport.height, minY, maxY);
  const std::uint32_t noPixel = simd::bits((simd::toFloat(minX) > simd::toFloat(maxX)) |
                                           (simd::toFloat(minY) > simd::toFloat(maxY))) &
                                rest;
  out.keep = rest & ~noPixel;

  // Small triangles: whether one covers a sample, without a branch a pixel
  // (setup tested them one by one, and the mispredicted exits were a sixth
  // of a 4-sample MetalRoughSpheresNoTextures frame; perf). Those whose
  // winding took the exact tie break are left to setup.
  const F boxSide = F(float(kCoverageBox - 1)), extent = F(float(kMaxCoverageExtent));
  const std::uint32_t small =
      simd::bits((simd::toFloat(maxX - minX) <= boxSide) & (simd::toFloat(maxY - minY) <= boxSide) &
                 (simd::toFloat(highX - lowX) <= extent) &
                 (simd::toFloat(highY - lowY) <= extent)) &
      out.keep & (simd::bits(p < q) | simd::bits(p > q));
  out.covers = 0;
  if (small != 0) out.covers = coveringSamples(x, y, p < q, minX, minY, maxX, maxY, samples, small);
  const std::uint32_t noSample = small & ~out.covers;
  out.keep &= ~noSample;
  out.negative = negative & out.keep;
  out.notFinite = lanesSet(notFinite);
  out.outside = lanesSet(outside) + lanesSet(noPixel) + lanesSet(noSample);
  out.degenerate = lanesSet(degenerate);
  out.backFace = lanesSet(backFace);
  minX.store_aligned(out.minX);
  minY.store_aligned(out.minY);
  maxX.store_aligned(out.maxX);
  maxY.store_aligned(out.maxY);
}

}  // namespace
}  // namespace QUADRA_KERNEL_NAMESPACE

const CullKernel& QUADRA_KERNEL_ENTRY(cullKernel)() {
  static constexpr CullKernel kernel{QUADRA_KERNEL_NAMESPACE::kLanes,
                                     QUADRA_KERNEL_NAMESPACE::cull};
  return kernel;
}

}  // namespace quadra
