// The environment behind a lit frame's uncovered pixels (BackgroundView),
// over lanes: each lane's ray and the solid angle its pixel spans, looked up
// in the prepared environment at that footprint, so a bright sun neither
// aliases nor leaves a seam where u wraps or a pinch at the poles.
#pragma once

#include "shading/background_view.h"
#include "shading/shade_lanes.h"

namespace quadra {

// Radiance seen through the pixels centred at window (x, y).
template <class L>
QUADRA_LANE_INLINE RgbLanes<L> backgroundThroughPixels(const BackgroundView& view,
                                                       const typename L::F& x,
                                                       const typename L::F& y) {
  using F = typename L::F;
  if (!view.perspective) {
    const glm::vec3 d = view.worldFromView * glm::vec3(0.0f, 0.0f, -1.0f);
    return backgroundRadiance<L>(*view.lighting, {F(d.x), F(d.y), F(d.z)}, F(0.0f));
  }
  const F dx = F(view.scaleX) * (x - F(view.centreX));
  const F dy = F(view.scaleY) * (F(view.centreY) - y);
  // The pixel spans scaleX x scaleY on the plane at distance 1, which is
  // |d|^-3 of that in solid angle along d = (dx, dy, -1).
  const F lengthSq = dx * dx + dy * dy + F(1.0f);
  const F inverseLength = F(1.0f) / simd::sqrt(lengthSq);
  const F solidAngle = F(view.scaleX * view.scaleY) * inverseLength * inverseLength * inverseLength;
  const glm::mat3& m = view.worldFromView;
  const F vx = dx * inverseLength, vy = dy * inverseLength, vz = F(0.0f) - inverseLength;
  const Vec3Lanes<L> d{F(m[0][0]) * vx + F(m[1][0]) * vy + F(m[2][0]) * vz,
                       F(m[0][1]) * vx + F(m[1][1]) * vy + F(m[2][1]) * vz,
                       F(m[0][2]) * vx + F(m[1][2]) * vy + F(m[2][2]) * vz};
  return backgroundRadiance<L>(*view.lighting, d, solidAngle);
}

}  // namespace quadra
