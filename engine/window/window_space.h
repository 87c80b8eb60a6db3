// Window space, written down once for every stage that uses it: the viewport,
// the projection of a clip-space point to the window (y down, pixel centres at
// +0.5), the 16.8 fixed point and the guard band with the range proof that
// keeps every edge function exact in 64-bit integers, and the tile and block
// sizes that divide the window into work. The vertex stage and setup project
// through it, the bin and tile stages cut the window with it.
//
// Window coordinates are snapped to 1/256 pixel (8 sub-pixel bits, as D3D11).
// The clip stage keeps every vertex within kGuardBandPixels outside the
// viewport, and viewports are at most kMaxViewport pixels, so |window| <
// 2^14 px and a snapped coordinate fits in 2^22 units. Then:
//   edge deltas dx, dy        < 2^23
//   step per pixel a = 256*dy < 2^31
//   constant c = dx*y - dy*x  < 2^46
//   E(px, py) = a*px + b*py + c over pixels |p| < 2^14:  < 2^47
// comfortably inside int64, so coverage is decided exactly.
#pragma once

#include <algorithm>
#include <cstdint>

namespace quadra {

constexpr int kSubpixelBits = 8;
constexpr int kSubpixelScale = 1 << kSubpixelBits;  // 256
constexpr int kMaxViewport = 8192;
constexpr int kGuardBandPixels = 8192;

// Tiles are the unit of parallel work; blocks the unit of coarse accept/reject.
// 64x64 RGBA32F + D32 is 80 KiB (L2-resident); 32x32 is 20 KiB (fits L1).
// Measured at 1080p, 2 threads, paired runs: 32 vs 64 gave alpha-quads 39.5
// vs 40.2 ms, checker-plane 11.7 vs 11.7 ms, dense-mesh 117.3 vs 114.5 ms —
// a wash, so 64 (a quarter of the per-triangle tile setups).
constexpr int kTileSize = 64;
constexpr int kBlockSize = 8;

// A window coordinate (pixels, within the guard band) in 1/256 pixel, rounded
// half to even without a libm call: adding 1.5 * 2^52 leaves no fraction
// bits, so the FPU's default rounding does the work (exact for |v| < 2^51).
inline std::int64_t snapToSubpixel(double window) {
  constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52
  return std::int64_t((window * kSubpixelScale + kShift) - kShift);
}

// A window position snapped to the 1/256-pixel grid; within the guard band
// it needs 23 bits, so setup's culling reads 8 bytes a vertex.
struct SubpixelPosition {
  std::int32_t x = 0, y = 0;
};

// A window position within the guard band, both coordinates snapped.
inline SubpixelPosition snapToSubpixel(double windowX, double windowY) {
  return {std::int32_t(snapToSubpixel(windowX)), std::int32_t(snapToSubpixel(windowY))};
}

struct Viewport {
  int width = 0;
  int height = 0;
};

// A vertex after the perspective divide. Setup snaps the position for coverage
// (snapToSubpixel) and solves the attribute planes through it unsnapped.
struct ScreenVertex {
  double windowX = 0.0, windowY = 0.0;  // window position in pixels
  double z = 0.0;                       // depth z/w
  double invW = 0.0;                    // 1/w
};

// The guard band as a multiple of w per axis: |x| <= guardX * w keeps window
// x within kGuardBandPixels of the viewport.
void guardBand(const Viewport& viewport, double& guardX, double& guardY);

// Window position of a clip-space point (w > 0); the one projection the vertex
// stage and setup (for clipped vertices) share. Inline: out of line, each
// vertex waited on the division through a call and a returned struct (a
// sixth of the vertex stage).
inline ScreenVertex projectToWindow(double x, double y, double z, double w,
                                    const Viewport& viewport) {
  const double invW = 1.0 / w;
  // A vertex the clip put on a guard plane may round a hair beyond it; the
  // clamp (to the guard band plus a pixel, far outside any pixel centre)
  // keeps the fixed-point range proof and the integer snap valid for any w.
  const auto window = [](double ndc, int size) {
    const double limit = kGuardBandPixels + 1.0;
    return std::clamp((ndc + 1.0) * 0.5 * size, -limit, size + limit);
  };
  const double xw = window(x * invW, viewport.width);
  const double yw = window(-y * invW, viewport.height);
  return {xw, yw, z * invW, invW};
}

}  // namespace quadra
