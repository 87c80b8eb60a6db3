// The environment's mapping and bilinear radiance in double (LIGHTING.md "The
// environment").
#include "lab/reference/environment_lookup.h"

#include <algorithm>
#include <cmath>

namespace quadra::ref {

namespace {
constexpr double kEnvPi = 3.14159265358979323846;
}  // namespace

glm::dvec2 equirectUv(const glm::dvec3& d) {
  return {0.5 + std::atan2(d.x, -d.z) / (2.0 * kEnvPi),
          std::acos(std::clamp(d.y, -1.0, 1.0)) / kEnvPi};
}

glm::dvec3 equirectDirection(const glm::dvec2& uv) {
  const double phi = 2.0 * kEnvPi * (uv.x - 0.5), theta = kEnvPi * uv.y;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

glm::dvec3 environmentRadianceAt(const EnvironmentImage& env, const glm::dvec2& uv) {
  const double x = uv.x * env.width - 0.5, y = uv.y * env.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  const auto column = [&](double i) {
    const double m = std::fmod(i, double(env.width));
    return int(m < 0 ? m + env.width : m);
  };
  const auto row = [&](double j) { return int(std::clamp(j, 0.0, double(env.height - 1))); };
  const auto texel = [&](double i, double j) {
    const float* t = env.texel(column(i), row(j));
    return glm::dvec3(t[0], t[1], t[2]);
  };
  return (1 - fy) * ((1 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0)) +
         fy * ((1 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1));
}

glm::dvec3 environmentRadiance(const EnvironmentImage& env, const glm::dvec3& d) {
  return environmentRadianceAt(env, equirectUv(d));
}

}  // namespace quadra::ref
