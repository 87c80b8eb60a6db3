// Scenes that need no files, by name: `builtin:checker-plane` (the classic
// aliasing/anisotropy ground plane) and `builtin:showcase` (the default).
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace quadra {

std::vector<std::string> builtinSceneNames();
// name without the "builtin:" prefix; throws Error for an unknown name.
Scene makeBuiltinScene(const std::string& name);

}  // namespace quadra
