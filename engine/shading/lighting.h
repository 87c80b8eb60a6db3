// What the tile kernels read to light a surface: LightingView, plain data
// built once per frame by the renderer (the prepared environment's tables,
// the frame's punctual lights, flags), and the world-space light record the
// lane code evaluates. The lane code is shade_lanes.h; the environment's
// tables come from prepared_environment.h.
#pragma once

#include <cstdint>
#include <vector>

namespace quadra {

struct Light;
class PreparedEnvironment;

// One KHR_lights_punctual light in world space, with the spot cone's terms
// precomputed as the specification's implementation note does.
struct PunctualLight {
  enum class Type : std::int32_t { Directional = 0, Point = 1, Spot = 2 };
  Type type = Type::Point;
  float position[3] = {0.0f, 0.0f, 0.0f};
  // Unit direction the light travels (its node's -Z), directional and spot.
  float direction[3] = {0.0f, 0.0f, -1.0f};
  // colour x intensity: W/m^2 (lux) for directional, W/sr (candela) otherwise.
  float radiance[3] = {1.0f, 1.0f, 1.0f};
  // 1 / range^4 for the range window (0: unlimited).
  float inverseRange4 = 0.0f;
  // Spot: attenuation = clamp(cd x angleScale + angleOffset, 0, 1)^2, cd the
  // cosine between the light's direction and the ray to the surface.
  float angleScale = 0.0f, angleOffset = 1.0f;
};

// The world-space record of a scene light (its node's translation and -Z,
// colour x intensity, range, cone). Intensity must be finite and >= 0: the
// loader rejects others.
PunctualLight punctualLightOf(const Light& light);

// The prepared environment as the lane code reads it. Cube maps: face f of
// level l is a square of (n + 2)^2 RGBA float texels (A unused: a texel pair
// is one 32-byte load), n = size >> l, with a
// one-texel border that repeats the neighbouring faces, so a bilinear tap
// never crosses a face; faces +X, -X, +Y, -Y, +Z, -Z (cube_layout.h).
struct EnvironmentView {
  static constexpr int kTexelFloats = 4;
  const float* radiance = nullptr;            // every level, level 0 first
  const std::int64_t* levelOffset = nullptr;  // float index of each level's face 0
  // Each level's first texel, 16 entries 64-byte aligned (simd::laneAddresses),
  // and the irradiance level's the same way (entry 0).
  const std::uint8_t* const* levelTexels = nullptr;
  const std::uint8_t* const* irradianceTexels = nullptr;
  int size = 0;  // level 0's face size (a power of two)
  int levelCount = 0;
  const float* irradiance = nullptr;  // (1/pi) x cosine-weighted integral, one level
  int irradianceSize = 0;
  // The directional albedo table (brdf_table.h) and the filtered importance
  // samples: sets of kFisSetSize[i] samples {t1, t2, sqrt(1 - t1^2)}, one
  // after the other. A lane group takes the set for its roughest lane:
  // narrow lobes need few samples (shade_lanes.h has the measured error).
  static constexpr int kFisSets = 3;
  static constexpr int kFisSetSize[kFisSets] = {4, 8, 16};
  static constexpr float kFisSetRoughness[kFisSets - 1] = {0.2f, 0.45f};  // set i below this
  const float* brdfTable = nullptr;
  const float* fisSamples = nullptr;
};

struct LightingView {
  bool environment = false;  // false: the environment term is 0
  EnvironmentView env;
  const PunctualLight* lights = nullptr;
  int lightCount = 0;
};

// The view of `environment` (may be null) and `lights` (which must outlive it).
LightingView lightingViewOf(const PreparedEnvironment* environment,
                            const std::vector<PunctualLight>& lights);

}  // namespace quadra
