// Setup's first step in SIMD lanes: what a group of triangles' outcodes and
// snapped positions alone decide, one lane per triangle. Most triangles of a
// dense mesh stop here (back-facing, off screen, between pixel centres' rows
// and columns, small and between samples), so they cost a few lane
// operations and no branch each; setup (triangle_setup.cpp) applies the
// verdicts in the scalar order and builds only the triangles left. Compiled
// once per ISA (cull_kernel_isa.cpp.in); every decision is exact, so every
// path culls the same triangles.
#pragma once

#include <cstdint>

#include "simd/isa.h"
#include "vertex/vertex_stage.h"
#include "window/sample_pattern.h"

namespace quadra {

constexpr int kMaxCullLanes = 16;

// What became of a group of triangles: bit t of a mask is triangle t.
struct CullGroup {
  std::uint32_t keep = 0;  // to set up
  std::uint32_t clip = 0;  // to clip first: a vertex lies beyond near, far or the guard band
  // The others, counted by the first reason that drops them (setup's order:
  // not finite, beyond one viewport plane, zero area, back-facing, no pixel
  // centre in their bounding box).
  int notFinite = 0, outside = 0, degenerate = 0, backFace = 0;
  // A kept triangle's box of the pixels whose centres lie within `reach`
  // of its bounding box, clamped to the viewport.
  alignas(64) std::int32_t minX[kMaxCullLanes], minY[kMaxCullLanes], maxX[kMaxCullLanes],
      maxY[kMaxCullLanes];
  // A kept triangle's area is negative (counter-clockwise with y up).
  std::uint32_t negative = 0;
  // Kept triangles found to cover a sample. Those of a box up to
  // kCoverageBox pixels a side and vertices within kMaxCoverageExtent of
  // each other are tested here (the ones covering none are dropped, counted
  // outside); setup tests the other small ones.
  std::uint32_t covers = 0;
};

// The largest box the kernel tests for sample coverage, in pixels a side: a
// dense mesh's triangles between samples, which would otherwise cost planes,
// bins and tile work for nothing, fit in it at every sample count (the
// pattern's reach widens a box by at most one pixel).
constexpr int kCoverageBox = 3;
// ... and the largest extent of its vertices, in 1/256 pixel, so that the
// test's arithmetic is exact in float (cull_kernel_impl.h).
constexpr int kMaxCoverageExtent = 4 * 256;

// Which faces a draw drops (a back face is one whose winding is not the
// front's).
struct FaceCulling {
  bool cullBackFaces = true;
  bool frontIsClockwise = false;
};

struct CullKernel {
  int lanes;  // triangles per group
  // Triangles t = 0 .. count-1 (count <= lanes) whose corners
  // indices[3t .. 3t+2] index the vertices' snapped positions and outcodes
  // (TransformedVertices'), each pixel sampled at `samples`; reach is
  // samples.reachSubpixels(), computed once by the caller.
  void (*cull)(const std::uint32_t* indices, int count, const SubpixelPosition* subpixel,
               const std::uint8_t* outcode, const Viewport& viewport, const SamplePattern& samples,
               int reach, FaceCulling faces, CullGroup& out);
};

const CullKernel& cullKernel(Isa isa);
const CullKernel& cullKernelScalar();
const CullKernel& cullKernelSse2();
const CullKernel& cullKernelAvx2();
const CullKernel& cullKernelAvx512();

}  // namespace quadra
