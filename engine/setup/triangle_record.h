// TriangleRecord: the setup stage's output and the tile stage's input: a
// triangle ready to rasterize, with exact edge functions and attribute planes.
#pragma once

#include <cstdint>
#include <vector>

namespace quadra {

// Edge i covers pixel (px, py) exactly when a*px + b*py + c > 0 (integer pixel
// indices; the pixel centre offset and the top-left tie rule are folded into c).
struct EdgeFunction {
  std::int64_t a = 0;
  std::int64_t b = 0;
  std::int64_t c = 0;
  std::int64_t at(std::int64_t px, std::int64_t py) const { return a * px + b * py + c; }
};

// A value interpolated linearly in screen space: at the centre of pixel
// (px, py) it is c + dx*(px - originX) + dy*(py - originY), where the origin is
// the triangle's first covered-bbox pixel.
struct Plane {
  float dx = 0.0f;
  float dy = 0.0f;
  float c = 0.0f;
};

struct TriangleRecord {
  EdgeFunction edges[3];
  std::int32_t minX = 0, minY = 0, maxX = -1, maxY = -1;  // inclusive pixel bbox in the viewport
  std::uint32_t firstPlane = 0;  // z, 1/w, then attribute/w planes, in the chunk's plane list
  std::uint32_t draw = 0;
};

}  // namespace quadra
