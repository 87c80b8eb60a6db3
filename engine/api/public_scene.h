// The public Scene's insides (include/quadra/scene.hpp): the engine Scene it
// builds, and which engine meshes each public mesh became. Shared by the
// facade's sources and by in-tree tests that check what an update touched;
// never installed.
#pragma once

#include <optional>
#include <vector>

#include "api/camera.h"
#include "quadra/scene.hpp"
#include "scene/animation.h"
#include "scene/scene.h"

namespace quadra::api {

struct Scene::Impl {
  quadra::Scene scene;
  // Engine meshes carry their material, public instances pick one per draw:
  // public mesh i is engine mesh derived[i][k], one per material drawn with
  // it (the first made at addMesh, material unset until its first instance).
  std::vector<std::vector<int>> derived;
  std::vector<bool> drawn;               // per public mesh: derived[i][0] has its material
  std::optional<quadra::Camera> camera;  // setCamera's; unset: the scene's or a default
  NodePose pose;                         // setAnimationTime's, its buffers reused
};

namespace detail {
struct SceneAccess {
  static const Scene::Impl& of(const Scene& scene) { return *scene.impl_; }
  static Scene::Impl& mutableOf(Scene& scene) { return *scene.impl_; }
};
}  // namespace detail

}  // namespace quadra::api
