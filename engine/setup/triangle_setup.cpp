// Setup: the scalar, double-precision part of the front end. It runs once per
// triangle and is shared by every ISA path, so its results are the same bits
// whichever kernel rasterizes them.
#include "setup/triangle_setup.h"

#include <algorithm>
#include <cmath>

#include "clip/clip.h"
#include "setup/fixed_point.h"

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

// A vertex after the perspective divide, snapped.
struct WindowVertex {
  std::int64_t x, y;  // 1/256 pixel
  double z, invW;
  const double* clip;  // x, y, z, w, attributes
};

struct SetupContext {
  const DrawGeometry& geometry;
  const Viewport& viewport;
  std::uint32_t drawIndex;
  int attributeCount;
  SetupOutput& out;
};

WindowVertex toWindow(const double* clip, const Viewport& vp) {
  const double invW = 1.0 / clip[3];
  const double xw = (clip[0] * invW + 1.0) * 0.5 * vp.width;
  const double yw = (1.0 - clip[1] * invW) * 0.5 * vp.height;
  // nearbyint: round half to even under the default rounding mode.
  return {std::int64_t(std::nearbyint(xw * kSubpixelScale)),
          std::int64_t(std::nearbyint(yw * kSubpixelScale)), clip[2] * invW, invW, clip};
}

// Edge from p to q of a triangle with positive area (in y-down window space,
// i.e. clockwise on screen). Inside is E > 0; ties go to top and left edges
// (D3D): a top edge runs exactly horizontally to the right, a left edge upward.
EdgeFunction makeEdge(const WindowVertex& p, const WindowVertex& q) {
  const std::int64_t dx = q.x - p.x, dy = q.y - p.y;
  const bool topLeft = dy < 0 || (dy == 0 && dx > 0);
  const std::int64_t half = kSubpixelScale / 2;  // pixel centre offset
  EdgeFunction e;
  e.a = -dy * kSubpixelScale;
  e.b = dx * kSubpixelScale;
  e.c = dx * (half - p.y) - dy * (half - p.x) + (topLeft ? 1 : 0);
  return e;
}

// Plane through three (window position, value) pairs, stored relative to the
// centre of pixel (originX, originY).
Plane makePlane(const WindowVertex* v, const double* values, double det, int originX,
                int originY) {
  const double x0 = double(v[0].x) / kSubpixelScale, y0 = double(v[0].y) / kSubpixelScale;
  const double x1 = double(v[1].x) / kSubpixelScale - x0, y1 = double(v[1].y) / kSubpixelScale - y0;
  const double x2 = double(v[2].x) / kSubpixelScale - x0, y2 = double(v[2].y) / kSubpixelScale - y0;
  const double f1 = values[1] - values[0], f2 = values[2] - values[0];
  const double dx = (f1 * y2 - f2 * y1) / det;
  const double dy = (f2 * x1 - f1 * x2) / det;
  const double c = values[0] + dx * (originX + 0.5 - x0) + dy * (originY + 0.5 - y0);
  return {float(dx), float(dy), float(c)};
}

// Pixel centres px + 0.5 inside [lo, hi] (in 1/256 units), clamped to [0, limit).
void pixelSpan(std::int64_t lo, std::int64_t hi, int limit, std::int32_t& first,
               std::int32_t& last) {
  const std::int64_t half = kSubpixelScale / 2;
  // ceil((lo - half) / 256) and floor((hi - half) / 256) for signed values.
  const std::int64_t a = lo - half, b = hi - half;
  std::int64_t f = a >= 0 ? (a + kSubpixelScale - 1) / kSubpixelScale : -((-a) / kSubpixelScale);
  std::int64_t l = b >= 0 ? b / kSubpixelScale : -((-b + kSubpixelScale - 1) / kSubpixelScale);
  first = std::int32_t(std::max<std::int64_t>(f, 0));
  last = std::int32_t(std::min<std::int64_t>(l, limit - 1));
}

void emitTriangle(const SetupContext& ctx, WindowVertex v0, WindowVertex v1, WindowVertex v2) {
  SetupCounters& n = ctx.out.counters;
  const std::int64_t area = (v1.x - v0.x) * (v2.y - v0.y) - (v2.x - v0.x) * (v1.y - v0.y);
  if (area == 0) {
    ++n.degenerate;
    return;
  }
  // glTF front faces are counter-clockwise with y up, so negative area here.
  const bool front = (area < 0) != ctx.geometry.frontIsClockwise;
  if (!front && ctx.geometry.cullBackFaces) {
    ++n.backFace;
    return;
  }
  if (area < 0) std::swap(v1, v2);
  WindowVertex v[3] = {v0, v1, v2};

  TriangleRecord t;
  pixelSpan(std::min({v0.x, v1.x, v2.x}), std::max({v0.x, v1.x, v2.x}), ctx.viewport.width, t.minX,
            t.maxX);
  pixelSpan(std::min({v0.y, v1.y, v2.y}), std::max({v0.y, v1.y, v2.y}), ctx.viewport.height,
            t.minY, t.maxY);
  if (t.minX > t.maxX || t.minY > t.maxY) {
    ++n.outside;
    return;
  }
  t.edges[0] = makeEdge(v[1], v[2]);
  t.edges[1] = makeEdge(v[2], v[0]);
  t.edges[2] = makeEdge(v[0], v[1]);
  t.draw = ctx.drawIndex;
  t.firstPlane = std::uint32_t(ctx.out.planes.size());

  const double det = double(std::llabs(area)) / double(kSubpixelScale * kSubpixelScale);
  double values[3];
  for (int i = 0; i < 3; ++i) values[i] = v[i].z;
  ctx.out.planes.push_back(makePlane(v, values, det, t.minX, t.minY));
  for (int i = 0; i < 3; ++i) values[i] = v[i].invW;
  ctx.out.planes.push_back(makePlane(v, values, det, t.minX, t.minY));
  for (int k = 0; k < ctx.attributeCount; ++k) {
    for (int i = 0; i < 3; ++i) values[i] = v[i].clip[4 + k] * v[i].invW;
    ctx.out.planes.push_back(makePlane(v, values, det, t.minX, t.minY));
  }
  ctx.out.triangles.push_back(t);
  ++n.drawn;
}

bool finitePosition(const float* v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && std::isfinite(v[3]);
}

}  // namespace

void setupTriangles(const DrawGeometry& geometry, const TransformedVertices& vertices,
                    std::uint32_t drawIndex, std::size_t firstTriangle,
                    std::size_t lastTriangle, const Viewport& viewport, SetupOutput& out) {
  const SetupContext ctx{geometry, viewport, drawIndex, geometry.attributes.count, out};
  const int floats = vertices.stride;
  // Guard band in units of w: window x stays within kGuardBandPixels of the viewport.
  const double guardX = 1.0 + 2.0 * kGuardBandPixels / viewport.width;
  const double guardY = 1.0 + 2.0 * kGuardBandPixels / viewport.height;
  const std::uint32_t* indices = geometry.mesh->indices.data();
  ClipPolygon polygon;
  double direct[3][kMaxClipVertexFloats];
  for (std::size_t t = firstTriangle; t < lastTriangle; ++t) {
    ++out.counters.in;
    const float* tri[3];
    for (int i = 0; i < 3; ++i) tri[i] = vertices.vertex(indices[3 * t + i]);
    if (!finitePosition(tri[0]) || !finitePosition(tri[1]) || !finitePosition(tri[2])) {
      ++out.counters.invalid;
      continue;
    }
    const ClipResult clip = clipTriangle(tri, floats, guardX, guardY, polygon);
    if (clip == ClipResult::Outside) {
      ++out.counters.outside;
      continue;
    }
    if (clip == ClipResult::Inside) {
      WindowVertex w[3];
      for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < floats; ++k) direct[i][k] = tri[i][k];
        w[i] = toWindow(direct[i], viewport);
      }
      emitTriangle(ctx, w[0], w[1], w[2]);
      continue;
    }
    // The clipped polygon becomes a fan; its pieces count as drawn separately.
    ++out.counters.clipped;
    const WindowVertex first = toWindow(polygon.vertices[0].v, viewport);
    for (int i = 1; i + 1 < polygon.count; ++i)
      emitTriangle(ctx, first, toWindow(polygon.vertices[i].v, viewport),
                   toWindow(polygon.vertices[i + 1].v, viewport));
  }
}

}  // namespace quadra
