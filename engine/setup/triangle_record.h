// TriangleRecord: the setup stage's output and the tile stage's input: a
// triangle ready to rasterize, with exact edge functions and attribute planes.
#pragma once

#include <cstdint>
#include <vector>

#include "window/sample_pattern.h"

namespace quadra {

// Edge i covers pixel (px, py) exactly when a*px + b*py + c > 0 (integer pixel
// indices; the pixel centre offset and the top-left tie rule are folded into c).
// a and b are 256 times a snapped edge delta, below 2^31 (window/window_space.h);
// c needs 64 bits. Products go through at(), in 64 bits.
struct EdgeFunction {
  std::int32_t a = 0;
  std::int32_t b = 0;
  std::int64_t c = 0;
  std::int64_t at(std::int64_t px, std::int64_t py) const {
    return std::int64_t(a) * px + std::int64_t(b) * py + c;
  }
  // The same edge with each pixel's sample at offset o standing in for its
  // centre. Exact: a and b are multiples of 256, o is in 1/16 pixel.
  EdgeFunction atSample(SampleOffset o) const { return {a, b, c + sampleShift(o)}; }
  std::int64_t sampleShift(SampleOffset o) const {
    return (std::int64_t(a) * o.x + std::int64_t(b) * o.y) / kSampleUnitsPerPixel;
  }
};

// A value interpolated linearly in screen space: at the centre of pixel
// (px, py) it is c + dx*(px - originX) + dy*(py - originY), where the origin is
// the triangle's first covered-bbox pixel.
struct Plane {
  float dx = 0.0f;
  float dy = 0.0f;
  float c = 0.0f;
  // The plane with each pixel's sample at offset o standing in for its centre.
  Plane atSample(SampleOffset o) const {
    const double shift = (double(dx) * o.x + double(dy) * o.y) / kSampleUnitsPerPixel;
    return {dx, dy, float(double(c) + shift)};
  }
};

// One cache line, so a record the tile stage reads (a tile's records lie
// scattered over their chunk) is one line to fetch, and a frame of a dense
// mesh holds a third less of them (96 bytes with 64-bit edge steps and a
// 32-bit box; frame times did not move, the memory did).
struct alignas(64) TriangleRecord {
  EdgeFunction edges[3];
  // Inclusive pixel bbox in the viewport (at most kMaxViewport = 8192 a side).
  std::int16_t minX = 0, minY = 0, maxX = -1, maxY = -1;
  std::uint32_t firstPlane = 0;  // z, 1/w, then attribute/w planes, in the chunk's plane list
  std::uint32_t draw = 0;
};
static_assert(sizeof(TriangleRecord) == 64);

// The record whose coverage at pixel (px, py) is the original's at that
// pixel's sample o (its box already reaches every pixel a sample can: setup
// widens it by the pattern's reach).
inline TriangleRecord atSample(const TriangleRecord& t, SampleOffset o) {
  TriangleRecord shifted = t;
  for (EdgeFunction& e : shifted.edges) e = e.atSample(o);
  return shifted;
}

}  // namespace quadra
