// Setup: triangles are culled a SIMD group at a time (setup/cull_kernel.h),
// and the survivors built here, one at a time in double precision. Every
// step is exact or the same scalar code on every ISA path, so the records are
// the same bits whichever kernels cull and rasterize them.
#include "setup/triangle_setup.h"

#include <algorithm>
#include <cmath>

#include "clip/clip.h"
#include "setup/cull_kernel.h"
#include "window/window_space.h"

namespace quadra {

void SetupCounters::add(const SetupCounters& o) {
  in += o.in;
  drawn += o.drawn;
  backFace += o.backFace;
  outside += o.outside;
  degenerate += o.degenerate;
  invalid += o.invalid;
  clipped += o.clipped;
}

namespace {

// A triangle corner as setup reads it, where the vertex stage (or the clip)
// left it: nothing is copied for it, and each attribute is divided by w as
// its plane is solved.
template <class T>
struct Corner {
  const ScreenVertex& screen;  // unsnapped window position, depth, 1/w: the planes
  SubpixelPosition snapped;    // coverage
  const T* attributes;         // not yet divided by w
};

struct SetupContext {
  const DrawGeometry& geometry;
  const Viewport& viewport;
  const SamplePattern& samples;
  const CullKernel& cullKernel;
  std::uint32_t drawIndex;
  int attributeCount;
  SetupOutput& out;
};

struct SnappedTriangle {
  std::int64_t x[3], y[3];
};

// The pixels whose centres a kept triangle's bounding box holds, in the viewport.
struct PixelBox {
  std::int32_t minX, minY, maxX, maxY;
};

// Edge from vertex p to vertex q of a triangle with positive area (in y-down
// window space, i.e. clockwise on screen). Inside is E > 0; ties go to top and
// left edges (D3D): a top edge runs exactly horizontally to the right, a left
// edge upward.
EdgeFunction makeEdge(const SnappedTriangle& s, int p, int q) {
  const std::int64_t dx = s.x[q] - s.x[p], dy = s.y[q] - s.y[p];
  const bool topLeft = dy < 0 || (dy == 0 && dx > 0);
  const std::int64_t half = kSubpixelScale / 2;  // pixel centre offset
  EdgeFunction e;
  e.a = std::int32_t(-dy * kSubpixelScale);
  e.b = std::int32_t(dx * kSubpixelScale);
  e.c = dx * (half - s.y[p]) - dy * (half - s.x[p]) + (topLeft ? 1 : 0);
  return e;
}

// Whether a triangle whose box spans at most kCoverageBox pixels a side
// covers one of their samples (larger ones are assumed to): the small
// triangles the cull kernel left untested (cull_kernel.h CullGroup::covers).
bool coversASample(const TriangleRecord& t, const SamplePattern& samples) {
  constexpr int span = kCoverageBox - 1;
  if (t.maxX - t.minX > span || t.maxY - t.minY > span) return true;
  // The edges stepped pixel by pixel from the box's corner, each sample's
  // shift added once: additions only, where evaluating each edge at each
  // pixel and sample was 5% of a 4-sample dense-mesh frame (perf).
  std::int64_t corner[3];
  for (int e = 0; e < 3; ++e) corner[e] = t.edges[e].at(t.minX, t.minY);
  for (int s = 0; s < samples.count; ++s) {
    std::int64_t row[3];
    for (int e = 0; e < 3; ++e) row[e] = corner[e] + t.edges[e].sampleShift(samples.offsets[s]);
    for (std::int32_t py = t.minY; py <= t.maxY; ++py) {
      std::int64_t edge[3] = {row[0], row[1], row[2]};
      for (std::int32_t px = t.minX; px <= t.maxX; ++px) {
        if ((edge[0] > 0) & (edge[1] > 0) & (edge[2] > 0)) return true;
        for (int e = 0; e < 3; ++e) edge[e] += t.edges[e].a;
      }
      for (int e = 0; e < 3; ++e) row[e] += t.edges[e].b;
    }
  }
  return false;
}

// Solves value = v0 + dx*(x - x0) + dy*(y - y0) through the three vertices and
// stores it relative to the centre of the record's first bbox pixel.
//
// The planes go through the unsnapped window positions: snapping moves a
// vertex up to 1/512 px while its attributes stay, which tilts the plane of a
// thin triangle (a clipped polygon's fan has many) by that over the
// triangle's width: 0.27 px of texture shift on the grazing hard case, 1e-5
// px this way. Only when the unsnapped area is below one grid cell (its sign
// and size are then rounding, not geometry) do the snapped positions serve.
struct PlaneSolver {
  double x0, y0, x1, y1, x2, y2, invDet;
  template <class T>
  explicit PlaneSolver(const Corner<T>* const v[3]) {
    double x[3], y[3];
    for (int i = 0; i < 3; ++i) x[i] = v[i]->screen.windowX, y[i] = v[i]->screen.windowY;
    const double det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    constexpr double kGridCellArea = 1.0 / (double(kSubpixelScale) * kSubpixelScale);
    if (!(std::fabs(det) >= kGridCellArea))
      for (int i = 0; i < 3; ++i)
        x[i] = double(v[i]->snapped.x) / kSubpixelScale,
        y[i] = double(v[i]->snapped.y) / kSubpixelScale;
    x0 = x[0], y0 = y[0];
    x1 = x[1] - x0, y1 = y[1] - y0, x2 = x[2] - x0, y2 = y[2] - y0;
    invDet = 1.0 / (x1 * y2 - x2 * y1);
  }
  Plane solve(double f0, double f1, double f2, int originX, int originY) const {
    f1 -= f0;
    f2 -= f0;
    const double dx = (f1 * y2 - f2 * y1) * invDet;
    const double dy = (f2 * x1 - f1 * x2) * invDet;
    const double c = f0 + dx * (originX + 0.5 - x0) + dy * (originY + 0.5 - y0);
    return {float(dx), float(dy), float(c)};
  }
};

// The unit normal of a triangle's plane in view space, from its corners'
// view-space positions (the vertex stage's position attribute), on the side
// its front faces: a mesh without NORMAL is shaded flat (glTF 2.0 §3.7.2.1).
template <class T>
void faceNormalOf(const DrawGeometry& g, const Corner<T>* const v[3], double out[3]) {
  const int p = g.attributes.position;
  double e1[3], e2[3];
  for (int k = 0; k < 3; ++k) {
    e1[k] = double(v[1]->attributes[p + k]) - double(v[0]->attributes[p + k]);
    e2[k] = double(v[2]->attributes[p + k]) - double(v[0]->attributes[p + k]);
  }
  double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                 e1[0] * e2[1] - e1[1] * e2[0]};
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  // The corners arrive in window order (emitKept swaps a negative-area
  // triangle's), which is clockwise on screen, so this normal points away
  // from the viewer for every triangle: turned, it faces the viewer, as a
  // front face's does and a double-sided back face's shading normal must.
  const double scale = length > 0.0 ? -1.0 / length : 0.0;
  for (int k = 0; k < 3; ++k) out[k] = n[k] * scale;
}

// Emits a triangle that passed culling (snapped holds its vertices' snapped
// positions, box, the area's sign and whether it covers a sample what
// culling found). cornerOf(i) is corner i (a Corner); it is called only once
// the triangle is known to cover a sample, so the triangles dropped between
// samples never touch their attributes.
template <class CornerOf>
void emitKept(const SetupContext& ctx, const SnappedTriangle& snapped, const PixelBox& box,
              bool negativeArea, bool coversSample, std::uint32_t source,
              const CornerOf& cornerOf) {
  TriangleRecord t;
  t.minX = std::int16_t(box.minX), t.minY = std::int16_t(box.minY);
  t.maxX = std::int16_t(box.maxX), t.maxY = std::int16_t(box.maxY);
  int corner[3] = {0, 1, 2};
  if (negativeArea) std::swap(corner[1], corner[2]);
  t.edges[0] = makeEdge(snapped, corner[1], corner[2]);
  t.edges[1] = makeEdge(snapped, corner[2], corner[0]);
  t.edges[2] = makeEdge(snapped, corner[0], corner[1]);
  if (!coversSample && !coversASample(t, ctx.samples)) {
    ++ctx.out.counters.outside;
    return;
  }
  t.draw = ctx.drawIndex;
  t.firstPlane = std::uint32_t(ctx.out.planes.size());

  const auto v0 = cornerOf(corner[0]), v1 = cornerOf(corner[1]), v2 = cornerOf(corner[2]);
  const decltype(v0)* const v[3] = {&v0, &v1, &v2};
  const PlaneSolver solver(v);
  const ScreenVertex &s0 = v0.screen, &s1 = v1.screen, &s2 = v2.screen;
  const auto plane = [&](double f0, double f1, double f2) {
    ctx.out.planes.push_back(solver.solve(f0, f1, f2, t.minX, t.minY));
  };
  plane(s0.z, s1.z, s2.z);
  plane(s0.invW, s1.invW, s2.invW);
  // A back face of a double-sided lit draw (its front is counter-clockwise
  // with y up: negative area here, unless mirrored) shades with its normal
  // and tangent frame turned to the viewer.
  const bool backFace = ctx.geometry.mirrored ? negativeArea : !negativeArea;
  const std::uint32_t negated = backFace ? ctx.geometry.negatedOnBackFaces : 0u;
  const int faceNormal = ctx.geometry.faceNormal;
  double face[3] = {0.0, 0.0, 0.0};
  if (faceNormal >= 0) faceNormalOf(ctx.geometry, v, face);
  for (int k = 0; k < ctx.attributeCount; ++k) {
    const double sign = negated >> k & 1u ? -1.0 : 1.0;
    if (faceNormal >= 0 && k >= faceNormal && k < faceNormal + 3) {
      const double n = face[k - faceNormal];
      plane(n * s0.invW, n * s1.invW, n * s2.invW);
      continue;
    }
    plane(sign * v0.attributes[k] * s0.invW, sign * v1.attributes[k] * s1.invW,
          sign * v2.attributes[k] * s2.invW);
  }
  ctx.out.triangles.push_back(t);
  if (ctx.out.recordSources) ctx.out.sourceTriangles.push_back(source);
  ++ctx.out.counters.drawn;
}

// Culls `triangles` triangles, corners[3t .. 3t+2] indexing subpixel and
// outcode, a group of cullKernel.lanes at a time, and emits what is left in
// submission order: clipOf(its corners) for a triangle that needs clipping,
// emitKept with cornerOf(vertex index) for a kept one; sourceOf(its
// corners) is the mesh triangle it came from.
template <class ClipOf, class SourceOf, class CornerOf>
void cullAndEmit(const SetupContext& ctx, const std::uint32_t* corners, std::size_t triangles,
                 const SubpixelPosition* subpixel, const std::uint8_t* outcode,
                 const ClipOf& clipOf, const SourceOf& sourceOf, const CornerOf& cornerOf) {
  const CullKernel& kernel = ctx.cullKernel;
  const FaceCulling faces{ctx.geometry.cullBackFaces, ctx.geometry.frontIsClockwise};
  const int reach = ctx.samples.reachSubpixels();
  SetupCounters& n = ctx.out.counters;
  CullGroup group;
  for (std::size_t first = 0; first < triangles; first += std::size_t(kernel.lanes)) {
    const int count = int(std::min<std::size_t>(std::size_t(kernel.lanes), triangles - first));
    const std::uint32_t* groupCorners = corners + 3 * first;
    kernel.cull(groupCorners, count, subpixel, outcode, ctx.viewport, ctx.samples, reach, faces,
                group);
    n.invalid += std::size_t(group.notFinite);
    n.outside += std::size_t(group.outside);
    n.degenerate += std::size_t(group.degenerate);
    n.backFace += std::size_t(group.backFace);
    for (std::uint32_t todo = group.keep | group.clip; todo; todo &= todo - 1) {
      const int t = __builtin_ctz(todo);
      const std::uint32_t* index = groupCorners + 3 * t;
      if (group.clip >> t & 1) {
        clipOf(index);
        continue;
      }
      const SnappedTriangle snapped{
          {subpixel[index[0]].x, subpixel[index[1]].x, subpixel[index[2]].x},
          {subpixel[index[0]].y, subpixel[index[1]].y, subpixel[index[2]].y}};
      const PixelBox box{group.minX[t], group.minY[t], group.maxX[t], group.maxY[t]};
      emitKept(ctx, snapped, box, group.negative >> t & 1, group.covers >> t & 1, sourceOf(index),
               [&](int corner) { return cornerOf(index[corner]); });
    }
  }
}

// Clips a triangle that leaves near/far or the guard band and emits its fan.
void emitClipped(const SetupContext& ctx, const float* const tri[3], int floats,
                 std::uint32_t source) {
  double guardX, guardY;
  guardBand(ctx.viewport, guardX, guardY);
  ClipPolygon polygon;
  if (clipTriangle(tri, floats, guardX, guardY, polygon) == ClipResult::Outside) {
    ++ctx.out.counters.outside;
    return;
  }
  // The clip leaves every vertex at w >= near > 0 up to rounding; a w that is
  // not positive anyway (NaN, or a polygon rounded onto the eye) cannot be
  // projected, so the polygon is dropped as degenerate instead of divided by.
  for (int i = 0; i < polygon.count; ++i)
    if (!(polygon.vertices[i].v[3] > 0.0)) {
      ++ctx.out.counters.degenerate;
      return;
    }
  ++ctx.out.counters.clipped;
  ScreenVertex projected[kMaxClipPolygon];
  SubpixelPosition snapped[kMaxClipPolygon];
  const std::uint8_t inside[kMaxClipPolygon] = {};  // the clip put every vertex inside
  std::uint32_t corners[3 * (kMaxClipPolygon - 2)];
  for (int i = 0; i < polygon.count; ++i) {
    const double* c = polygon.vertices[i].v;
    projected[i] = projectToWindow(c[0], c[1], c[2], c[3], ctx.viewport);
    snapped[i] = snapToSubpixel(projected[i].windowX, projected[i].windowY);
  }
  // The fan's pieces count as drawn (or culled) separately.
  const int pieces = polygon.count - 2;
  for (int i = 0; i < pieces; ++i) {
    corners[3 * i] = 0;
    corners[3 * i + 1] = std::uint32_t(i + 1);
    corners[3 * i + 2] = std::uint32_t(i + 2);
  }
  cullAndEmit(
      ctx, corners, std::size_t(pieces), snapped, inside, [](const std::uint32_t*) {},
      [source](const std::uint32_t*) { return source; },
      [&](std::uint32_t i) {
        return Corner<double>{projected[i], snapped[i], polygon.vertices[i].v + 4};
      });
}

}  // namespace

const CullKernel& cullKernel(Isa isa) {
  switch (isa) {
    case Isa::Avx512:
      // The 16-lane kernel builds its lanes from scalars more slowly than
      // two 8-lane groups (dense-mesh setup 11.5 ms against 9.2, alternating
      // runs); the verdicts are the same bits.
    case Isa::Avx2:
      return cullKernelAvx2();
    case Isa::Sse2:
      return cullKernelSse2();
    case Isa::Scalar:
      break;
  }
  return cullKernelScalar();
}

void setupTriangles(const DrawGeometry& geometry, const TransformedVertices& vertices,
                    std::uint32_t drawIndex, std::size_t firstTriangle, std::size_t lastTriangle,
                    const Viewport& viewport, const SamplePattern& samples,
                    const CullKernel& cullKernel, SetupOutput& out) {
  const SetupContext ctx{
      geometry, viewport, samples, cullKernel, drawIndex, geometry.attributes.count, out};
  out.counters.in += lastTriangle - firstTriangle;
  const std::uint32_t* const meshIndices = geometry.mesh->indices.data();
  const auto sourceOf = [meshIndices](const std::uint32_t* index) {
    return std::uint32_t((index - meshIndices) / 3);
  };
  cullAndEmit(
      ctx, geometry.mesh->indices.data() + 3 * firstTriangle, lastTriangle - firstTriangle,
      vertices.subpixel.data(), vertices.outcode.data(),
      [&](const std::uint32_t* index) {
        const float* tri[3] = {vertices.vertex(index[0]), vertices.vertex(index[1]),
                               vertices.vertex(index[2])};
        emitClipped(ctx, tri, vertices.stride, sourceOf(index));
      },
      sourceOf,
      [&](std::uint32_t i) {
        return Corner<float>{vertices.screen[i], vertices.subpixel[i], vertices.vertex(i) + 4};
      });
}

}  // namespace quadra
