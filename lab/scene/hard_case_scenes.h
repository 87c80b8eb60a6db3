// The hard-case scenes of numerical stability (builtin:near-plane,
// builtin:huge-1e30, ...): geometry that breaks naive rasterizers, each with
// its camera, so `quadra render` can draw them and `quadra report stability`
// can hold the engine against the double-precision references on them.
// Parameterized builders are exposed for the report's sweeps.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace quadra {

// Names without the "builtin:" prefix, in the order the report runs them.
std::vector<std::string> hardCaseSceneNames();
// The scene of one of those names; false for a name that is not a hard case.
bool makeHardCaseScene(const std::string& name, Scene& out);

// Orthographic scenes are drawn on a kPixelExactSize^2 viewport, where their
// camera maps world (x, y) to window (x + size/2, size/2 - y) with power-of-two
// scales only, so every float vertex lands exactly where it was placed.
constexpr int kPixelExactSize = 256;
Camera pixelExactCamera();
glm::vec3 worldFromWindow(double windowX, double windowY);

// Two parallel view-filling quads at view distance `distance` and
// `distance + separation`, near 1e-3, far 1e6; the nearer (red) one is drawn
// second, so a pixel is right only if the depth buffer separates them.
Scene zFightingScene(double distance, double separation);

// `count` seeded random double-sided triangles on the 1/256 grid of the
// pixel-exact viewport: a third on the half-pixel lattice, a third anywhere,
// a third tiny; some reach outside the viewport, some are degenerate.
Scene randomTrianglesScene(int count, std::uint32_t seed);

// The ground plane y = -1 seen from the origin at 45 degrees down, with
// TEXCOORD_0 = (x, z) / 4: one quad split along its diagonal when cellsPerSide
// is 1, else a grid of cellsPerSide^2 quads over the same rectangle (about
// half a pixel wide on screen at 200 cells and a 256 x 160 viewport).
Scene groundPlaneScene(int cellsPerSide);
// The rectangle groundPlaneScene tessellates: x in [-kGroundHalfWidth,
// kGroundHalfWidth], z in [kGroundFarZ, kGroundNearZ], at y = kGroundY.
constexpr float kGroundHalfWidth = 1.0f, kGroundNearZ = -1.2f, kGroundFarZ = -3.2f,
                kGroundY = -1.0f;

}  // namespace quadra
