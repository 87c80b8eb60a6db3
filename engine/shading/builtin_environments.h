// The built-in environments (builtin:NAME): analytic radiance functions
// realized as texels at a fixed size, each texel the function's value at its
// centre's direction. The texels are the environment (LIGHTING.md); the
// functions, sizes and why are docs/lighting.md "Built-in environments".
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "shading/environment_image.h"

namespace quadra {

// What quadra lights with when no environment is named.
constexpr const char* kDefaultEnvironment = "builtin:studio";

// The names builtinEnvironment takes ("studio", "sky", "white"), in the order
// help texts list them.
const std::vector<std::string>& builtinEnvironmentNames();

// NAME without "builtin:"; the image's name is "builtin:NAME". Throws
// Error("builtin:NAME: unknown built-in environment (studio, sky, white)").
EnvironmentImage builtinEnvironment(std::string_view name);

}  // namespace quadra
