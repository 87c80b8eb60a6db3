// The area filter's level and grid choice (area_filter.h).
#include "texture/area_filter.h"

#include <algorithm>
#include <cmath>

namespace quadra {

AreaGrid planAreaGrid(const TextureView& view, float dudx, float dvdx, float dudy, float dvdy) {
  const double w = view.levels[0].width, h = view.levels[0].height;
  // Edge lengths of the parallelogram in level-0 texels.
  const double edgeX = std::hypot(double(dudx) * w, double(dvdx) * h);
  const double edgeY = std::hypot(double(dudy) * w, double(dvdy) * h);
  AreaGrid grid;
  grid.level = view.levelCount - 1;
  if (!std::isfinite(edgeX) || !std::isfinite(edgeY)) return grid;
  for (int level = 0; level < view.levelCount; ++level) {
    const double scale = kAreaSamplesPerTexel / std::ldexp(1.0, level);
    const double columns = std::max(double(kAreaMinSamples), std::ceil(edgeX * scale));
    const double rows = std::max(double(kAreaMinSamples), std::ceil(edgeY * scale));
    if (columns * rows <= kAreaSampleBudget || level == view.levelCount - 1) {
      grid.level = level;
      grid.columns = int(std::min(columns, double(kAreaSampleBudget)));
      grid.rows = int(std::min(rows, double(kAreaSampleBudget / grid.columns)));
      return grid;
    }
  }
  return grid;
}

}  // namespace quadra
