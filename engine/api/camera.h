// Camera conventions in one place: view and projection matrices (clip depth in
// [0, 1], Vulkan/D3D style), the default framing camera, and lookAt.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace quadra {

// World → view (the inverse of Camera::world, without its scale).
glm::mat4 viewMatrix(const Camera& camera);

// View → clip for a viewport of the given aspect (width / height). The camera's
// own aspect ratio is ignored, so pixels stay square. Perspective:
// x_c = f/aspect*x, y_c = f*y, w_c = -z with f = 1/tan(yfov/2); depth z_c/w_c is
// 0 at znear and 1 at zfar (zfar == 0: infinite, depth → 1 at infinity).
// Orthographic: half-height ymag, half-width ymag*aspect, w_c = 1.
//
// Reversed depth swaps the ends: 1 at znear, 0 at zfar (n / -z for an
// infinite perspective), tested with GREATER. Float depth then keeps its
// precision where perspective spends it (1/z crowds distant depths near one
// end, and floats are densest near 0), so far surfaces stay resolved.
enum class DepthMode : std::uint8_t { Standard, Reversed };
glm::mat4 projectionMatrix(const Camera& camera, double aspect,
                           DepthMode depth = DepthMode::Standard);

// Camera-to-world matrix of a camera at eye looking at target.
glm::mat4 lookAtWorld(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up);

}  // namespace quadra
