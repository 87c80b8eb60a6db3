// What `quadra render` and the peer renderers that mirror it (tools/peer/)
// share, so that both read a command line the same way and see the same
// frame: the SCENE argument (a glTF file or builtin:NAME), the camera
// overrides applied to the scene's first camera, and the statistics of the
// `… frame_ms median=… min=… max=…` line.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "api/renderer.h"
#include "cli_options.h"
#include "io/frame.h"
#include "io/tone_map.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "shading/builtin_environments.h"
#include "shading/environment_source.h"

namespace quadra {

constexpr const char* kBuiltinScenePrefix = "builtin:";

// builtin:NAME from the lab, anything else a glTF file; the loader's notes go
// to stderr, one line each, after `program` ("quadra: note: …"). An unknown
// NAME is a UsageError with the names closest to it.
Scene loadSceneArgument(const std::string& scene, const LoadOptions& load,
                        const std::string& program);

// SCENE, the one positional argument, --scene N (which glTF scene),
// --allow-path and --max-memory.
void addSceneOptions(CommandOptions& options, std::string& scene, LoadOptions& load);
// --allow-path DIR, repeatable: a folder besides the scene's own that its URIs
// may read (LoadOptions::allowedPaths); one that does not exist is an input
// error (exit 1, as a missing scene file is), even for a built-in scene.
void addAllowPathOption(CommandOptions& options, LoadOptions& load);
// An environment argument (--env, `quadra env`): builtin:NAME or a panorama
// file (shading/environment_source.h loadEnvironment). An unknown NAME is a
// UsageError with the names closest to it; a file's problems stay Errors.
EnvironmentImage loadEnvironmentArgument(const std::string& source, MemoryBudget& budget,
                                         TexelRepairs* repairs = nullptr);

// --max-memory SIZE (core/memory_budget.h parseMemorySize: 512M, 4G, bytes):
// the budget of the load (LoadOptions::maxMemory), which a command that
// renders in-process also gives its RenderSettings::maxMemory.
void addMaxMemoryOption(CommandOptions& options, LoadOptions& load);
// --width and --height, each 1..kMaxViewportSize.
void addSizeOptions(CommandOptions& options, int& width, int& height);
// --out FILE.exr|FILE.png, repeatable: the files the last frame is written to.
void addOutputOption(CommandOptions& options, std::vector<std::string>& outputs);

// Whether a frame must carry depth for these outputs: an EXR's Z channel
// does, a PNG does not. Depth is produced only for what reads it.
bool outputsNeedDepth(const std::vector<std::string>& outputs);

// --aov LIST, repeatable: comma-separated AOV names (docs/cli.md "AOVs"): Z, N,
// P, uv, motion, id, mask, lod, anisotropy, albedo, roughness, metallic, emission, diffuse,
// specular. mask sets frameCoverage, Z is always in an EXR,
// the others are RenderSettings::aovs bits; any other name is an Error
// listing the valid ones.
void addAovOption(CommandOptions& options, RenderSettings& settings);
// The AOV names --aov accepts, for messages: "Z, N, P, uv, motion, id, mask, lod, anisotropy,
// albedo, roughness, metallic, emission, diffuse, specular".
std::string aovNames();

// Pbr shading's light and output (LIGHTING.md, docs/lighting.md), as
// `quadra render` and its lit peer read them: --env FILE|builtin:NAME (kept
// here, for loadEnvironmentArgument), --env-rotation DEG,
// --env-intensity S, --background env|color|transparent, --background-color
// R,G,B, --lights on|off, --exposure EV, --tonemap pbr-neutral|aces|none.
struct LightingOptions {
  std::string environment = kDefaultEnvironment;  // shading/builtin_environments.h
  std::optional<ToneMap> toneMap;                 // unset: the shading's default
};
void addLightingOptions(CommandOptions& options, RenderSettings& settings,
                        LightingOptions& lighting);

// The settings that decide a frame's pixels, as "key=value" words for the
// EXR header (FrameMetadata::strings); nothing that differs between runs
// of the same frame (threads, kernel path, file names) is in it.
std::string describeRenderSettings(const RenderSettings& settings);
// quadra's version and describeRenderSettings, as the EXR header's string
// attributes quadraVersion and quadraRenderSettings.
void describeRender(const RenderSettings& settings, FrameMetadata& metadata);

// --eye, --target, --up, --fovy, --near, --far: each set one overrides that
// part of the scene's first camera.
struct CameraOverrides {
  std::optional<glm::vec3> eye, target, up;
  std::optional<float> fovyDegrees, znear, zfar;
};
void addCameraOptions(CommandOptions& options, CameraOverrides& overrides);
// The scene's first camera (or the default framing) with the overrides
// applied; an Error when they contradict each other.
Camera chooseCamera(const Scene& scene, const CameraOverrides& overrides);
// `camera` with the overrides applied (chooseCamera's second half).
Camera applyCameraOverrides(Camera camera, const CameraOverrides& overrides);

// The key=value pairs of the line of `output` that starts with `prefix`
// ("quadra frame_ms "), for a caller that reads a render's report back.
std::map<std::string, std::string> lineKeyValues(const std::string& output,
                                                 const std::string& prefix);

// Frame times (ms) as the frame_ms line reports them.
struct FrameTimeSummary {
  double median = 0.0, min = 0.0, max = 0.0;
};
// `times` must not be empty; the median of an even count is the mean of the middle two.
FrameTimeSummary summarizeFrameTimes(std::vector<double> times);

}  // namespace quadra
