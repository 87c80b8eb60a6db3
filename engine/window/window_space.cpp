// Window space: the guard band and the projection of clip-space points.
#include "window/window_space.h"

#include <algorithm>

namespace quadra {

void guardBand(const Viewport& viewport, double& guardX, double& guardY) {
  guardX = 1.0 + 2.0 * kGuardBandPixels / viewport.width;
  guardY = 1.0 + 2.0 * kGuardBandPixels / viewport.height;
}

ScreenVertex projectToWindow(double x, double y, double z, double w, const Viewport& viewport) {
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
