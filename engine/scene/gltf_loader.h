// glTF 2.0 (.gltf and .glb) → Scene, through tinygltf, with every length,
// offset, index and size checked before it is trusted.
#pragma once

#include <string>

#include "scene/scene.h"

namespace quadra {

struct LoadOptions {
  int sceneIndex = -1;  // -1: the file's default scene (or scene 0)
};

// Throws Error("<path>: <problem>") for anything malformed or unsupported that
// cannot be ignored. Things it can ignore (points, lines) go to notes, one
// line each.
Scene loadGltf(const std::string& path, const LoadOptions& options = {},
               std::vector<std::string>* notes = nullptr);

}  // namespace quadra
