// Setup: the scalar, double-precision part of the front end. It runs once per
// triangle and is shared by every ISA path, so its results are the same bits
// whichever kernel rasterizes them.
#include "setup/triangle_setup.h"

#include <algorithm>
#include <cmath>

#include "clip/clip.h"
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

constexpr int kMaxAttributes = kMaxClipVertexFloats - 4;

// A projected vertex with the attribute values its planes interpolate.
struct SetupVertex {
  std::int64_t x, y;        // snapped, 1/256 pixel: coverage
  double windowX, windowY;  // unsnapped, pixels: attribute planes
  double z, invW;
  double attr[kMaxAttributes];  // attribute / w
};

struct SetupContext {
  const DrawGeometry& geometry;
  const Viewport& viewport;
  std::uint32_t drawIndex;
  int attributeCount;
  SetupOutput& out;
};

// `snapped`: s's window position snapped (the vertex stage's, or snapped here
// for a clipped vertex).
template <class T>
SetupVertex makeSetupVertex(const ScreenVertex& s, SubpixelPosition snapped, const T* attributes,
                            int count) {
  SetupVertex v;  // attr[count..] stay unset: nothing reads them
  v.x = snapped.x, v.y = snapped.y;
  v.windowX = s.windowX, v.windowY = s.windowY, v.z = s.z, v.invW = s.invW;
  for (int k = 0; k < count; ++k) v.attr[k] = double(attributes[k]) * s.invW;
  return v;
}

// What the snapped positions alone decide about a triangle, in the order
// emitTriangle applies it: most triangles of a closed mesh face away or are
// off screen, and are dropped here before their attributes are touched.
enum class Cull : std::uint8_t { Keep, Degenerate, BackFace, Outside };

struct SnappedTriangle {
  std::int64_t x[3], y[3];
  std::int64_t area() const {
    return (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  }
};

// Pixel indices whose centres px + 0.5 lie in [lo, hi] (1/256 units), clamped to [0, limit).
void pixelSpan(std::int64_t lo, std::int64_t hi, int limit, std::int32_t& first,
               std::int32_t& last) {
  const std::int64_t half = kSubpixelScale / 2;
  // ceil((lo - half) / 256) and floor((hi - half) / 256), with arithmetic shifts.
  const std::int64_t f = -((half - lo) >> kSubpixelBits);
  const std::int64_t l = (hi - half) >> kSubpixelBits;
  first = std::int32_t(std::max<std::int64_t>(f, 0));
  last = std::int32_t(std::min<std::int64_t>(l, limit - 1));
}

// The pixels whose centres a kept triangle's bounding box holds, in the viewport.
struct PixelBox {
  std::int32_t minX, minY, maxX, maxY;
};

// Most triangles of a dense mesh end here, so it reads only the snapped
// positions and writes nothing but the small box (a TriangleRecord
// zero-filled per triangle cost a tenth of setup). Forced inline, as is
// kept(): a call per triangle cost dense-mesh 2% of its frame.
[[gnu::always_inline]] inline Cull cullSnapped(const SetupContext& ctx, const SnappedTriangle& t,
                                               PixelBox& box) {
  const std::int64_t area = t.area();
  if (area == 0) return Cull::Degenerate;
  // glTF front faces are counter-clockwise with y up, so negative area here.
  const bool front = (area < 0) != ctx.geometry.frontIsClockwise;
  if (!front && ctx.geometry.cullBackFaces) return Cull::BackFace;
  pixelSpan(std::min({t.x[0], t.x[1], t.x[2]}), std::max({t.x[0], t.x[1], t.x[2]}),
            ctx.viewport.width, box.minX, box.maxX);
  pixelSpan(std::min({t.y[0], t.y[1], t.y[2]}), std::max({t.y[0], t.y[1], t.y[2]}),
            ctx.viewport.height, box.minY, box.maxY);
  if (box.minX > box.maxX || box.minY > box.maxY) return Cull::Outside;
  return Cull::Keep;
}

// Counts a culled triangle; true when it is kept.
[[gnu::always_inline]] inline bool kept(Cull cull, SetupCounters& n) {
  switch (cull) {
    case Cull::Degenerate:
      ++n.degenerate;
      return false;
    case Cull::BackFace:
      ++n.backFace;
      return false;
    case Cull::Outside:
      ++n.outside;  // covers no pixel centre inside the viewport
      return false;
    case Cull::Keep:
      break;
  }
  return true;
}

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

// Whether a triangle whose bbox spans at most 2x2 pixel centres covers any
// of them; larger ones are assumed to. A dense mesh has many triangles
// between pixel centres (about a third of MetalRoughSpheresNoTextures' at
// 1080p); dropped here, they cost no planes, bins or tile work.
bool coversAPixelCentre(const TriangleRecord& t) {
  if (t.maxX - t.minX > 1 || t.maxY - t.minY > 1) return true;
  for (std::int32_t py = t.minY; py <= t.maxY; ++py)
    for (std::int32_t px = t.minX; px <= t.maxX; ++px)
      if (t.edges[0].at(px, py) > 0 && t.edges[1].at(px, py) > 0 && t.edges[2].at(px, py) > 0)
        return true;
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
  explicit PlaneSolver(const SetupVertex* const v[3]) {
    double x[3], y[3];
    for (int i = 0; i < 3; ++i) x[i] = v[i]->windowX, y[i] = v[i]->windowY;
    const double det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    constexpr double kGridCellArea = 1.0 / (double(kSubpixelScale) * kSubpixelScale);
    if (!(std::fabs(det) >= kGridCellArea))
      for (int i = 0; i < 3; ++i)
        x[i] = double(v[i]->x) / kSubpixelScale, y[i] = double(v[i]->y) / kSubpixelScale;
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

// Emits a triangle that passed cullSnapped (snapped holds its vertices'
// snapped positions, box what cullSnapped found). vertexOf(i) makes the setup
// vertex of corner i; it is called only once the snapped edges show the
// triangle covers a pixel centre, so the triangles dropped between pixel
// centres never touch their attributes.
template <class VertexOf>
void emitKept(const SetupContext& ctx, const SnappedTriangle& snapped, const PixelBox& box,
              const VertexOf& vertexOf) {
  TriangleRecord t;
  t.minX = std::int16_t(box.minX), t.minY = std::int16_t(box.minY);
  t.maxX = std::int16_t(box.maxX), t.maxY = std::int16_t(box.maxY);
  int corner[3] = {0, 1, 2};
  if (snapped.area() < 0) std::swap(corner[1], corner[2]);
  t.edges[0] = makeEdge(snapped, corner[1], corner[2]);
  t.edges[1] = makeEdge(snapped, corner[2], corner[0]);
  t.edges[2] = makeEdge(snapped, corner[0], corner[1]);
  if (!coversAPixelCentre(t)) {
    ++ctx.out.counters.outside;
    return;
  }
  t.draw = ctx.drawIndex;
  t.firstPlane = std::uint32_t(ctx.out.planes.size());

  const SetupVertex v0 = vertexOf(corner[0]), v1 = vertexOf(corner[1]), v2 = vertexOf(corner[2]);
  const SetupVertex* const v[3] = {&v0, &v1, &v2};
  const PlaneSolver solver(v);
  const auto plane = [&](double f0, double f1, double f2) {
    ctx.out.planes.push_back(solver.solve(f0, f1, f2, t.minX, t.minY));
  };
  plane(v0.z, v1.z, v2.z);
  plane(v0.invW, v1.invW, v2.invW);
  for (int k = 0; k < ctx.attributeCount; ++k) plane(v0.attr[k], v1.attr[k], v2.attr[k]);
  ctx.out.triangles.push_back(t);
  ++ctx.out.counters.drawn;
}

void emitTriangle(const SetupContext& ctx, const SetupVertex& v0, const SetupVertex& v1,
                  const SetupVertex& v2) {
  const SnappedTriangle snapped{{v0.x, v1.x, v2.x}, {v0.y, v1.y, v2.y}};
  PixelBox box;
  const SetupVertex* const v[3] = {&v0, &v1, &v2};
  if (kept(cullSnapped(ctx, snapped, box), ctx.out.counters))
    emitKept(ctx, snapped, box, [&](int i) { return *v[i]; });
}

// Clips a triangle that leaves near/far or the guard band and emits its fan.
void emitClipped(const SetupContext& ctx, const float* const tri[3], int floats) {
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
  SetupVertex fan[kMaxClipPolygon];
  for (int i = 0; i < polygon.count; ++i) {
    const double* c = polygon.vertices[i].v;
    const ScreenVertex projected = projectToWindow(c[0], c[1], c[2], c[3], ctx.viewport);
    fan[i] = makeSetupVertex(projected, snapToSubpixel(projected.windowX, projected.windowY), c + 4,
                             ctx.attributeCount);
  }
  // The fan's pieces count as drawn (or culled) separately.
  for (int i = 1; i + 1 < polygon.count; ++i) emitTriangle(ctx, fan[0], fan[i], fan[i + 1]);
}

}  // namespace

void setupTriangles(const DrawGeometry& geometry, const TransformedVertices& vertices,
                    std::uint32_t drawIndex, std::size_t firstTriangle, std::size_t lastTriangle,
                    const Viewport& viewport, SetupOutput& out) {
  const SetupContext ctx{geometry, viewport, drawIndex, geometry.attributes.count, out};
  const std::uint32_t* indices = geometry.mesh->indices.data();
  constexpr std::uint8_t kOutsideViewport =
      kOutsideNear | kOutsideFar | kOutsideLeft | kOutsideRight | kOutsideBottom | kOutsideTop;
  out.counters.in += lastTriangle - firstTriangle;
  for (std::size_t t = firstTriangle; t < lastTriangle; ++t) {
    const std::uint32_t i0 = indices[3 * t], i1 = indices[3 * t + 1], i2 = indices[3 * t + 2];
    const std::uint8_t c0 = vertices.outcode[i0], c1 = vertices.outcode[i1],
                       c2 = vertices.outcode[i2];
    if ((c0 | c1 | c2) & kNotFinite) {
      ++out.counters.invalid;
      continue;
    }
    if (c0 & c1 & c2 & kOutsideViewport) {
      ++out.counters.outside;  // all three beyond one plane
      continue;
    }
    if ((c0 | c1 | c2) & kNeedsClipping) {
      const float* tri[3] = {vertices.vertex(i0), vertices.vertex(i1), vertices.vertex(i2)};
      emitClipped(ctx, tri, vertices.stride);
      continue;
    }
    const SubpixelPosition p0 = vertices.subpixel[i0], p1 = vertices.subpixel[i1],
                           p2 = vertices.subpixel[i2];
    const SnappedTriangle snapped{{p0.x, p1.x, p2.x}, {p0.y, p1.y, p2.y}};
    PixelBox box;
    if (!kept(cullSnapped(ctx, snapped, box), out.counters)) continue;
    const std::uint32_t index[3] = {i0, i1, i2};
    const SubpixelPosition position[3] = {p0, p1, p2};
    emitKept(ctx, snapped, box, [&](int i) {
      return makeSetupVertex(vertices.screen[index[i]], position[i], vertices.vertex(index[i]) + 4,
                             ctx.attributeCount);
    });
  }
}

}  // namespace quadra
