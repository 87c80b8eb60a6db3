// Window space: the guard band.
#include "window/window_space.h"

namespace quadra {

void guardBand(const Viewport& viewport, double& guardX, double& guardY) {
  guardX = 1.0 + 2.0 * kGuardBandPixels / viewport.width;
  guardY = 1.0 + 2.0 * kGuardBandPixels / viewport.height;
}

}  // namespace quadra
