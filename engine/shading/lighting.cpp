// Building the lane code's plain records: scene lights to PunctualLight,
// and the frame's LightingView.
#include "shading/lighting.h"

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "shading/prepared_environment.h"

namespace quadra {

PunctualLight punctualLightOf(const Light& light) {
  PunctualLight p;
  p.type = light.type == Light::Type::Directional ? PunctualLight::Type::Directional
           : light.type == Light::Type::Spot      ? PunctualLight::Type::Spot
                                                  : PunctualLight::Type::Point;
  for (int k = 0; k < 3; ++k) {
    p.position[k] = light.world[3][k];
    p.radiance[k] = light.color[k] * light.intensity;
  }
  // The node's -Z axis; its scale is ignored (normalized).
  const double dx = -light.world[2][0], dy = -light.world[2][1], dz = -light.world[2][2];
  const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (len > 0.0) {
    p.direction[0] = float(dx / len), p.direction[1] = float(dy / len),
    p.direction[2] = float(dz / len);
  }
  if (light.range > 0.0f) {
    const double r2 = double(light.range) * light.range;
    p.inverseRange4 = float(1.0 / (r2 * r2));
  }
  if (p.type == PunctualLight::Type::Spot) {
    // KHR_lights_punctual's implementation note.
    const double cosOuter = std::cos(double(light.outerConeAngle));
    const double cosInner = std::cos(double(light.innerConeAngle));
    const double scale = 1.0 / std::max(0.001, cosInner - cosOuter);
    p.angleScale = float(scale);
    p.angleOffset = float(-cosOuter * scale);
  }
  return p;
}

LightingView lightingViewOf(const PreparedEnvironment* environment,
                            const std::vector<PunctualLight>& lights) {
  LightingView view;
  if (environment) {
    view.environment = true;
    view.env = environment->view();
  }
  view.lights = lights.data();
  view.lightCount = int(lights.size());
  return view;
}

}  // namespace quadra
