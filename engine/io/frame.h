// Frame: a rendered image in memory, what the tile stage resolves its tiles
// into and the writers (io/image_io.h) read: premultiplied linear RGBA float,
// window-space depth in [0,1] and, when asked for, coverage.
#pragma once

#include <vector>

namespace quadra {

struct Frame {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // width * height * 4, row 0 at the top, premultiplied
  // width * height, or empty when the render was asked for none
  // (RenderSettings::frameDepth); 1 = far plane / nothing drawn.
  std::vector<float> depth;
  // width * height, or empty when the render was asked for none
  // (RenderSettings::frameCoverage): the fraction of the pixel's samples that
  // a depth-writing (opaque or masked) triangle holds, filtered as the colour is.
  std::vector<float> coverage;
};

}  // namespace quadra
