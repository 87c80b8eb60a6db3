// What a lit frame shows where no surface covers a pixel
// (Background::Environment): the environment seen along the pixel's ray,
// filtered over the pixel's footprint on the sphere. Built once per frame by
// the renderer from the camera; read per lane group by backgroundRadiance
// (shading/background_lanes.h), which the tile kernels call after a tile's
// last draw.
#pragma once

#include <glm/glm.hpp>

namespace quadra {

struct LightingView;

struct BackgroundView {
  const LightingView* lighting = nullptr;
  glm::mat3 worldFromView{1.0f};
  // A perspective camera's ray through window point (x, y) (y down) runs
  // along view-space (scaleX (x - centreX), scaleY (centreY - y), -1); an
  // orthographic camera's every ray along (0, 0, -1), whose footprint on the
  // sphere is a point.
  bool perspective = true;
  float scaleX = 1.0f, scaleY = 1.0f, centreX = 0.0f, centreY = 0.0f;
};

}  // namespace quadra
