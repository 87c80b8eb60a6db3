// Setup stage: clip-space triangles of one draw → TriangleRecords. Culls
// (outside, back-facing, zero-area, NaN/Inf), clips where needed, divides by w,
// snaps to 16.8 fixed point, and builds edge functions and attribute planes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "setup/cull_kernel.h"
#include "setup/triangle_record.h"
#include "vertex/draw.h"
#include "vertex/vertex_stage.h"
#include "window/sample_pattern.h"

namespace quadra {

struct SetupCounters {
  std::size_t in = 0, drawn = 0, backFace = 0, outside = 0, degenerate = 0, invalid = 0,
              clipped = 0;
  void add(const SetupCounters& o);
};

// Output of one front-end chunk, in submission order.
struct SetupOutput {
  std::vector<TriangleRecord> triangles;
  std::vector<Plane> planes;
  // With recordSources (the renderer sets it when AOVs read ids or the
  // surface), per record the index of the mesh triangle it came from (a
  // clipped triangle's pieces share it); else empty.
  bool recordSources = false;
  std::vector<std::uint32_t> sourceTriangles;
  SetupCounters counters;
  void clear() {  // keeps the capacity for the next frame
    triangles.clear();
    planes.clear();
    sourceTriangles.clear();
    counters = {};
  }
};

// Sets up triangles [firstTriangle, lastTriangle) of a draw into out
// (appending), culling them first with cullKernel (setup/cull_kernel.h). A
// record's box holds every pixel one of whose `samples` it may cover, and
// only triangles that cover a sample are kept.
void setupTriangles(const DrawGeometry& geometry, const TransformedVertices& vertices,
                    std::uint32_t drawIndex, std::size_t firstTriangle, std::size_t lastTriangle,
                    const Viewport& viewport, const SamplePattern& samples,
                    const CullKernel& cullKernel, SetupOutput& out);

}  // namespace quadra
