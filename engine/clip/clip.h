// Clip stage: one clip-space triangle → a convex polygon inside the near and
// far planes and inside the guard band (sides are clipped only when a vertex
// leaves the guard band, never merely the viewport).
#pragma once

#include <cstdint>

namespace quadra {

constexpr int kMaxClipVertexFloats = 4 + 12;  // position + attributes
constexpr int kMaxClipPolygon = 3 + 6;        // each plane adds at most one vertex

struct ClipVertex {
  double v[kMaxClipVertexFloats];  // x, y, z, w, attributes
};

struct ClipPolygon {
  ClipVertex vertices[kMaxClipPolygon];
  int count = 0;
};

enum class ClipResult : std::uint8_t { Inside, Clipped, Outside };

// guardX/guardY: the guard band as a multiple of w (|x| <= guardX * w).
// floats: floats per vertex (4 + attributes). On Clipped, out holds the polygon.
ClipResult clipTriangle(const float* const vertices[3], int floats, double guardX, double guardY,
                        ClipPolygon& out);

}  // namespace quadra
