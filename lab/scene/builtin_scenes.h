// Scenes that need no files, by name: `builtin:checker-plane` (the classic
// aliasing/anisotropy ground plane) and `builtin:showcase` (the default).
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace quadra {

std::vector<std::string> builtinSceneNames();
// name without the "builtin:" prefix; throws Error for an unknown name.
// "dense-mesh:N" is builtin:dense-mesh with about N triangles (8..1e8), for
// measuring how a frame scales with its triangle count.
Scene makeBuiltinScene(const std::string& name);

// Unit sphere with `stacks` rings from the +Y pole and `slices` segments, with
// normals and TEXCOORD_0 (u around, v from the top pole, 0, to the bottom, 1).
Mesh makeSphere(int stacks, int slices, int material);

}  // namespace quadra
