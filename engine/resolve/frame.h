// Frame: the resolved output of a render, what resolve hands to the writers:
// premultiplied linear RGBA float and window-space depth in [0,1].
#pragma once

#include <vector>

namespace quadra {

struct Frame {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;   // width * height * 4, row 0 at the top, premultiplied
  std::vector<float> depth;  // width * height; 1 = far plane / nothing drawn
};

}  // namespace quadra
