// Homogeneous clipping (Sutherland–Hodgman in clip space, before the divide).
// Attributes are linear in clip space, so interpolating them there is exact.
#include "clip/clip.h"

#include <cmath>

namespace quadra {

namespace {

// Signed distance of a clip-space point to plane p; inside when >= 0.
// Planes: near z >= 0, far z <= w, then the guard band sides.
constexpr int kPlaneCount = 6;

double planeDistance(int plane, const double* v, double guardX, double guardY) {
  switch (plane) {
    case 0:
      return v[2];
    case 1:
      return v[3] - v[2];
    case 2:
      return guardX * v[3] + v[0];
    case 3:
      return guardX * v[3] - v[0];
    case 4:
      return guardY * v[3] + v[1];
    default:
      return guardY * v[3] - v[1];
  }
}

// The crossing is interpolated from the vertex nearer the plane (ties: the
// inside one), so the step is short: from a vertex 1e30 away, the near
// plane's w = near would be the difference of two values ~1e30, anything from
// -1e14 to 1e14. The two triangles sharing an edge see the same two vertices
// and distances, so they produce the same point.
void intersect(const ClipVertex& in, double dIn, const ClipVertex& out, double dOut, int floats,
               ClipVertex& result) {
  const bool fromIn = std::fabs(dIn) <= std::fabs(dOut);
  const ClipVertex& base = fromIn ? in : out;
  const ClipVertex& other = fromIn ? out : in;
  const double dBase = fromIn ? dIn : dOut, dOther = fromIn ? dOut : dIn;
  const double t = dBase / (dBase - dOther);
  for (int k = 0; k < floats; ++k) result.v[k] = base.v[k] + t * (other.v[k] - base.v[k]);
}

void clipAgainst(int plane, int floats, double guardX, double guardY, ClipPolygon& poly) {
  ClipPolygon result;
  double distance[kMaxClipPolygon];
  for (int i = 0; i < poly.count; ++i)
    distance[i] = planeDistance(plane, poly.vertices[i].v, guardX, guardY);
  for (int i = 0; i < poly.count; ++i) {
    const int j = (i + 1) % poly.count;
    const bool inI = distance[i] >= 0.0, inJ = distance[j] >= 0.0;
    if (inI) result.vertices[result.count++] = poly.vertices[i];
    if (inI != inJ) {
      if (inI)
        intersect(poly.vertices[i], distance[i], poly.vertices[j], distance[j], floats,
                  result.vertices[result.count++]);
      else
        intersect(poly.vertices[j], distance[j], poly.vertices[i], distance[i], floats,
                  result.vertices[result.count++]);
    }
  }
  poly = result;
}

}  // namespace

ClipResult clipTriangle(const float* const vertices[3], int floats, double guardX, double guardY,
                        ClipPolygon& out) {
  unsigned outsideAny = 0;
  for (int plane = 0; plane < kPlaneCount; ++plane) {
    int outside = 0;
    for (int i = 0; i < 3; ++i) {
      const double p[4] = {vertices[i][0], vertices[i][1], vertices[i][2], vertices[i][3]};
      if (planeDistance(plane, p, guardX, guardY) < 0.0) ++outside;
    }
    if (outside == 3) return ClipResult::Outside;
    if (outside > 0) outsideAny |= 1u << plane;
  }
  if (outsideAny == 0) return ClipResult::Inside;

  out.count = 3;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < floats; ++k) out.vertices[i].v[k] = vertices[i][k];
  for (int plane = 0; plane < kPlaneCount && out.count >= 3; ++plane)
    if (outsideAny & (1u << plane)) clipAgainst(plane, floats, guardX, guardY, out);
  return out.count >= 3 ? ClipResult::Clipped : ClipResult::Outside;
}

}  // namespace quadra
