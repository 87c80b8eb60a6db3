// quadra's public C++ API, the one header an embedder includes:
//
//   #include <quadra/quadra.hpp>
//   quadra::api::Scene scene;
//   auto mesh = scene.addMesh({.positions = positions, .indices32 = indices});
//   auto material = scene.addMaterial({.baseColor = {1, 0.5f, 0, 1}});
//   scene.addInstance(mesh, material);
//   quadra::api::Renderer renderer({.threads = 2});
//   renderer.render(scene, {.pixels = bytes, .width = 640, .height = 360,
//                           .rowStride = 640 * 4, .format = quadra::api::PixelFormat::Rgba8Srgb});
//
// Thread safety, ownership and errors: see scene.hpp and renderer.hpp; in
// short, every failure is a quadra::api::Error with a one-line message, scenes
// copy what they are given, and one Renderer renders one frame at a time.
// Design notes: docs/api.md.
#pragma once

#include "quadra/environment.hpp"
#include "quadra/error.hpp"
#include "quadra/export.h"
#include "quadra/renderer.hpp"
#include "quadra/scene.hpp"
#include "quadra/version.h"

namespace quadra {

// The library's version, "MAJOR.MINOR.PATCH"; equals QUADRA_VERSION_STRING
// when the headers and the library come from one install.
QUADRA_API const char* version();

}  // namespace quadra
