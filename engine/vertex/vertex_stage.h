// Vertex stage: a draw's mesh → clip-space positions plus exactly the
// attributes the draw's material reads (one flat float array), and for each
// vertex its clip outcode and, when it lies inside the guard band, its
// window position, unsnapped and snapped, so setup projects and snaps each
// shared vertex once.
#pragma once

#include <cstdint>
#include <vector>

#include "vertex/draw.h"
#include "window/window_space.h"

namespace quadra {

class Executor;

// Outcode bits: planes a vertex is outside of.
enum OutcodeBit : std::uint8_t {
  kOutsideNear = 1 << 0,   // z < 0
  kOutsideFar = 1 << 1,    // z > w
  kOutsideGuard = 1 << 2,  // beyond the guard band on some side (needs side clipping)
  kOutsideLeft = 1 << 3,   // viewport sides, for trivial rejection only
  kOutsideRight = 1 << 4,
  kOutsideBottom = 1 << 5,
  kOutsideTop = 1 << 6,
  kNotFinite = 1 << 7,  // NaN or Inf in the position or an attribute the draw reads
};
constexpr std::uint8_t kNeedsClipping = kOutsideNear | kOutsideFar | kOutsideGuard;

// Vertex i occupies data[i*stride .. i*stride+stride): x, y, z, w (clip space),
// then the attributes at the offsets of geometry.attributes (plus 4).
struct TransformedVertices {
  std::vector<float> data;
  // screen and subpixel are valid where outcode has none of kNeedsClipping | kNotFinite.
  std::vector<ScreenVertex> screen;
  std::vector<SubpixelPosition> subpixel;  // screen's window position, snapped
  std::vector<std::uint8_t> outcode;
  int stride = 4;
  const float* vertex(std::uint32_t i) const { return &data[std::size_t(i) * std::size_t(stride)]; }
};

void transformVertices(const DrawGeometry& geometry, const Viewport& viewport,
                       const Executor& executor, TransformedVertices& out);

}  // namespace quadra
