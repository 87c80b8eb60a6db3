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

// The checker texture of builtin:checker-plane: `squares` x `squares` black and
// white squares of `texelsPerSquare` texels each (linear 0.0 / 1.0).
Image makeCheckerImage(int squares, int texelsPerSquare);

}  // namespace quadra
