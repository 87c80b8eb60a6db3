// Projection conventions (see camera.h) and the framing of scenes with no camera.
#include "api/camera.h"

#include <algorithm>
#include <cmath>

#include "api/renderer.h"

namespace quadra {

glm::mat4 viewMatrix(const Camera& camera) {
  glm::mat4 world = camera.world;
  for (int c = 0; c < 3; ++c) {  // drop scale: glTF says camera nodes must not scale
    const float length = glm::length(glm::vec3(world[c]));
    if (length > 0.0f) world[c] /= length;
  }
  return glm::inverse(world);
}

glm::mat4 projectionMatrix(const Camera& camera, double aspect, DepthMode depth) {
  glm::dmat4 p(0.0);
  const double n = camera.znear, f = camera.zfar;
  if (camera.type == Camera::Type::Perspective) {
    const double focal = 1.0 / std::tan(0.5 * double(camera.yfov));
    p[0][0] = focal / aspect;
    p[1][1] = focal;
    p[2][3] = -1.0;  // w_c = -z
    if (f > 0.0) {
      p[2][2] = f / (n - f);
      p[3][2] = n * f / (n - f);
    } else {
      p[2][2] = -1.0;
      p[3][2] = -n;
    }
  } else {
    const double halfHeight = camera.ymag, halfWidth = camera.ymag * aspect;
    p[0][0] = 1.0 / halfWidth;
    p[1][1] = 1.0 / halfHeight;
    p[2][2] = 1.0 / (n - f);
    p[3][2] = n / (n - f);
    p[3][3] = 1.0;
  }
  if (depth == DepthMode::Reversed) {
    // depth' = 1 - depth: z_c' = w_c - z_c, exact in double before the float cast.
    for (int column = 0; column < 4; ++column) p[column][2] = p[column][3] - p[column][2];
  }
  return glm::mat4(p);
}

glm::mat4 lookAtWorld(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up) {
  const glm::vec3 back = glm::normalize(eye - target);
  glm::vec3 right = glm::cross(up, back);
  if (glm::length(right) < 1e-12f) right = glm::cross(glm::vec3(0, 0, 1), back);
  right = glm::normalize(right);
  const glm::vec3 trueUp = glm::cross(back, right);
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(right, 0.0f);
  m[1] = glm::vec4(trueUp, 0.0f);
  m[2] = glm::vec4(back, 0.0f);
  m[3] = glm::vec4(eye, 1.0f);
  return m;
}

namespace {

// Looks at the scene's bounds from `direction` (unit length), far enough that
// the bounding sphere fits a 45-degree view with 10% to spare.
Camera framingCamera(const Scene& scene, const glm::vec3& direction) {
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  if (!(lo.x <= hi.x)) lo = glm::vec3(-1.0f), hi = glm::vec3(1.0f);
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
  Camera camera;
  camera.yfov = 0.7854f;  // 45 degrees
  const float distance = radius / std::sin(0.5f * camera.yfov) * 1.1f;
  camera.world = lookAtWorld(centre + direction * distance, centre, glm::vec3(0, 1, 0));
  camera.znear = std::max(distance - radius, distance * 0.01f) * 0.5f;
  camera.zfar = distance + 2.0f * radius;
  return camera;
}

const glm::vec3 kDefaultDirection = glm::normalize(glm::vec3(0.35f, 0.4f, 1.0f));

}  // namespace

Camera defaultCamera(const Scene& scene) {
  return framingCamera(scene, kDefaultDirection);
}

Camera orbitCamera(const Scene& scene, int view, int views) {
  // The angle in double from the view's index, so that view k of N is the
  // same camera however many views came before; view 0 turns by exactly 0.
  const double angle = 2.0 * 3.14159265358979323846 * double(view) / double(views);
  const float c = float(std::cos(angle)), s = float(std::sin(angle));
  const glm::vec3 d = kDefaultDirection;
  return framingCamera(scene, glm::vec3(c * d.x + s * d.z, d.y, c * d.z - s * d.x));
}

Camera firstCameraOrDefault(const Scene& scene) {
  return scene.cameras.empty() ? defaultCamera(scene) : scene.cameras.front();
}

}  // namespace quadra
