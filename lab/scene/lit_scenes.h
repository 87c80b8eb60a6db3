// Scenes and environments for lit shading's tests, built in code: a grid of
// spheres over metallic x roughness (as glTF's MetalRoughSpheres), a plane
// under a given material, and synthetic panoramas (uniform, split at the
// horizon, a sky with a small bright sun).
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "shading/environment_image.h"

namespace quadra {

// columns x rows unit spheres 2.5 apart in the z = 0 plane, seen by the
// scene's one perspective camera on +Z looking down -Z (at the panorama's
// centre): roughness rises from 0 (left) to 1 (right), metallic from 0
// (bottom row) to 1 (top row); base colour `baseColor`.
Scene metalRoughSpheresScene(int columns, int rows, const glm::vec3& baseColor);

// The square |x|, |z| <= halfSize in the plane y = 0, facing +Y, with normals
// and TEXCOORD_0 = (x, z) / (2 halfSize) + 0.5, in `material`; no camera.
Scene litPlaneScene(const Material& material, float halfSize);

// Every texel `radiance`.
EnvironmentImage uniformEnvironment(const glm::vec3& radiance, int width = 8, int height = 4);
// Rows above the horizon (the top height / 2) `sky`, the others `ground`.
EnvironmentImage splitEnvironment(const glm::vec3& sky, const glm::vec3& ground, int width,
                                  int height);
// A sky brightening toward the horizon over a dim ground, and a sun of 3 x 3
// texels of radiance 2000 at u = 0.3, v = 0.25 (45 degrees up, left of -Z).
EnvironmentImage sunnySkyEnvironment(int width, int height);

}  // namespace quadra
