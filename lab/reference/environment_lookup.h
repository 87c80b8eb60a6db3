// LIGHTING.md's environment in double precision, for the references and the
// tests: the direction <-> (u, v) mapping of the equirectangular panorama and
// the radiance of a direction (the bilinear interpolation of the texels at
// (u, v), wrapping in u and clamping in v). Written from LIGHTING.md alone,
// independently of the engine's lookups, so it can check them.
#pragma once

#include <glm/glm.hpp>

#include "shading/environment_image.h"

namespace quadra::ref {

// u = 0.5 + atan2(x, -z) / 2 pi, v = acos(clamp(y, -1, 1)) / pi for a unit
// direction d (glTF world space, +Y up): -Z is u = 0.5, +X u = 0.75, +Y v = 0.
glm::dvec2 equirectUv(const glm::dvec3& d);
// The unit direction of (u, v), the inverse of equirectUv.
glm::dvec3 equirectDirection(const glm::dvec2& uv);

// The bilinear radiance of the environment at (u, v): texel (i, j) centred
// at ((i + 0.5) / W, (j + 0.5) / H), wrapping in u, clamping in v.
glm::dvec3 environmentRadianceAt(const EnvironmentImage& env, const glm::dvec2& uv);
// The same in direction d.
glm::dvec3 environmentRadiance(const EnvironmentImage& env, const glm::dvec3& d);

}  // namespace quadra::ref
