// The SCENE argument, the camera overrides and the frame-time statistics
// shared by `quadra render` and its peers.
#include "render_options.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include "api/camera.h"
#include "api/renderer.h"
#include "core/error.h"
#include "core/file_sandbox.h"
#include "core/memory_budget.h"
#include "io/image_io.h"
#include "lab/scene/builtin_scenes.h"
#include "shading/builtin_environments.h"
#include "shading/environment_source.h"

namespace quadra {

Scene loadSceneArgument(const std::string& scene, const LoadOptions& load,
                        const std::string& program) {
  const std::string prefix = kBuiltinScenePrefix;
  if (scene.rfind(prefix, 0) == 0) {
    const std::string name = scene.substr(prefix.size());
    try {
      return makeBuiltinScene(name);
    } catch (const Error& e) {
      // A built-in scene reads no file: only its name (or dense-mesh's
      // count) can be wrong, and that is the command line's fault.
      const std::vector<std::string> known = builtinSceneNames();
      const std::string base = name.substr(0, name.find(':'));
      const bool knownBase = std::find(known.begin(), known.end(), base) != known.end();
      throw UsageError(e.what() + (knownBase ? "" : didYouMean(name, known)));
    }
  }
  std::vector<std::string> notes;
  Scene loaded = loadGltf(scene, load, &notes);
  for (const std::string& note : notes) std::cerr << program << ": note: " << note << "\n";
  return loaded;
}

EnvironmentImage loadEnvironmentArgument(const std::string& source, MemoryBudget& budget,
                                         TexelRepairs* repairs) {
  try {
    return loadEnvironment(source, budget, repairs);
  } catch (const Error& e) {
    // A built-in reads no file: an unknown name is the command line's fault.
    const std::string prefix = "builtin:";
    if (source.rfind(prefix, 0) != 0) throw;
    const std::string name = source.substr(prefix.size());
    const std::vector<std::string>& known = builtinEnvironmentNames();
    if (std::find(known.begin(), known.end(), name) != known.end()) throw;
    throw UsageError(e.what() + didYouMean(name, known));
  }
}

namespace {

glm::vec3 parseVector(const std::string& option, const std::string& text) {
  glm::vec3 v;
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string::npos))
      throw Error(option + ": '" + text + "' must be three numbers x,y,z");
    v[i] = float(parseNumber(option, text.substr(start, comma - start)));
    start = comma + 1;
  }
  return v;
}

}  // namespace

void addSceneOptions(CommandOptions& options, std::string& scene, LoadOptions& load) {
  const auto given = std::make_shared<bool>(false);
  options.positional([&scene, given](const std::string& argument) {
    if (*given) throw Error("render: more than one scene given ('" + argument + "')");
    scene = argument;
    *given = true;
  });
  options.integer("--scene", load.sceneIndex, 0, 1 << 20);
  addAllowPathOption(options, load);
  addMaxMemoryOption(options, load);
}

void addAllowPathOption(CommandOptions& options, LoadOptions& load) {
  options.pathValue("--allow-path", [&load](const std::string&, const std::string& folder) {
    canonicalAllowedFolder(folder);  // a missing folder is an error even for builtin scenes
    load.allowedPaths.push_back(folder);
  });
}

void addMaxMemoryOption(CommandOptions& options, LoadOptions& load) {
  options.value("--max-memory", [&load](const std::string& option, const std::string& size) {
    load.maxMemory = parseMemorySize(option, size);
  });
}

void addSizeOptions(CommandOptions& options, int& width, int& height) {
  options.integer("--width", width, 1, kMaxViewportSize);
  options.integer("--height", height, 1, kMaxViewportSize);
}

void addOutputOption(CommandOptions& options, std::vector<std::string>& outputs) {
  options.value("--out", [&outputs](const std::string&, const std::string& value) {
    if (!endsWithIgnoringCase(value, ".exr") && !endsWithIgnoringCase(value, ".png"))
      throw Error(value + ": unsupported output format (use .exr or .png)");
    outputs.push_back(value);
  });
}

bool outputsNeedDepth(const std::vector<std::string>& outputs) {
  return std::any_of(outputs.begin(), outputs.end(),
                     [](const std::string& path) { return endsWithIgnoringCase(path, ".exr"); });
}

namespace {

// --aov's names: the surface AOVs' layer names (io/frame.h Aov), Z and mask.
struct AovName {
  const char* name;
  AovSet bits;  // 0: Z or mask, handled apart
};
constexpr AovName kAovNames[] = {{"Z", 0},
                                 {"N", AovSet(Aov::Normal)},
                                 {"P", AovSet(Aov::Position)},
                                 {"uv", AovSet(Aov::Uv)},
                                 {"motion", AovSet(Aov::Motion)},
                                 {"id", AovSet(Aov::Ids)},
                                 {kCoverageChannel, 0},
                                 {"lod", AovSet(Aov::Lod)},
                                 {"anisotropy", AovSet(Aov::Anisotropy)},
                                 {"albedo", AovSet(Aov::Albedo)},
                                 {"roughness", AovSet(Aov::Roughness)},
                                 {"metallic", AovSet(Aov::Metallic)},
                                 {"emission", AovSet(Aov::Emission)},
                                 {"diffuse", AovSet(Aov::Diffuse)},
                                 {"specular", AovSet(Aov::Specular)}};

}  // namespace

std::string aovNames() {
  std::string list;
  for (const AovName& aov : kAovNames) list += (list.empty() ? "" : ", ") + std::string(aov.name);
  return list;
}

void addAovOption(CommandOptions& options, RenderSettings& settings) {
  options.value("--aov", [&settings](const std::string& option, const std::string& value) {
    for (const std::string& name : splitList(option, value)) {
      const AovName* found = std::find_if(std::begin(kAovNames), std::end(kAovNames),
                                          [&](const AovName& aov) { return name == aov.name; });
      if (found == std::end(kAovNames))
        throw UsageError(option + ": '" + name + "' is not an AOV quadra writes (valid: " +
                         aovNames() + ")" + didYouMean(name, aovNames()));
      settings.aovs |= found->bits;
      if (name == kCoverageChannel) settings.frameCoverage = true;
    }
  });
}

std::string describeRenderSettings(const RenderSettings& s) {
  std::ostringstream out;
  out << "width=" << s.width << " height=" << s.height
      << " filter=" << (s.filter ? filterName(*s.filter) : "per-sampler") << " aniso=" << s.maxAniso
      << " lod-bias=" << s.lodBias << " lod=" << (s.lodRule == LodRule::Box ? "box" : "gl")
      << " shading="
      << (s.shading == Shading::Pbr   ? "pbr"
          : s.shading == Shading::Lit ? "lit"
                                      : "unlit")
      << " depth=" << (s.depth == DepthMode::Reversed ? "reversed" : "standard")
      << " samples=" << s.samples
      << " shading-rate=" << (s.shadingRate == ShadingRate::Sample ? "sample" : "pixel")
      << " pixel-filter="
      << (s.pixelFilter == PixelFilter::BlackmanHarris ? "blackman-harris" : "box")
      << " alpha-to-coverage=" << (s.alphaToCoverage ? "on" : "off");
  if (s.shading == Shading::Pbr)
    out << " env-rotation=" << s.environmentRotation << " env-intensity=" << s.environmentIntensity
        << " lights=" << (s.punctualLights ? "on" : "off") << " background="
        << (s.background == Background::Environment ? "env"
            : s.background == Background::Color     ? "color"
                                                    : "transparent");
  if (s.exposure != 0.0f) out << " exposure=" << s.exposure;
  out << " aov=Z";
  for (const AovName& aov : kAovNames)
    if ((aov.bits != 0 && (s.aovs & aov.bits) != 0) ||
        (aov.name == std::string(kCoverageChannel) && s.frameCoverage))
      out << "," << aov.name;
  return out.str();
}

void addLightingOptions(CommandOptions& options, RenderSettings& settings,
                        LightingOptions& lighting) {
  options.value("--env", [&lighting](const std::string&, const std::string& value) {
    lighting.environment = value;
  });
  options.value("--env-rotation", [&settings](const std::string& option, const std::string& value) {
    const double degrees = parseNumber(option, value);
    if (!(std::fabs(degrees) <= kMaxEnvironmentRotation))
      throw UsageError(option + ": '" + value + "' is out of range (-36000..36000 degrees)");
    settings.environmentRotation = float(degrees);
  });
  options.value("--env-intensity",
                [&settings](const std::string& option, const std::string& value) {
                  const double scale = parseNumber(option, value);
                  if (!(scale >= 0.0 && scale <= kMaxEnvironmentIntensity))
                    throw UsageError(option + ": '" + value + "' must be in 0..1e9");
                  settings.environmentIntensity = float(scale);
                });
  options.choice("--background", "background",
                 {{"env", Background::Environment},
                  {"color", Background::Color},
                  {"transparent", Background::Transparent}},
                 settings.background);
  options.value("--background-color",
                [&settings](const std::string& option, const std::string& value) {
                  const glm::vec3 c = parseVector(option, value);
                  if (!(c.r >= 0.0f && c.g >= 0.0f && c.b >= 0.0f))
                    throw UsageError(option + ": '" + value + "' must not be negative");
                  settings.clearColor = glm::vec4(c, 1.0f);
                });
  options.choice("--lights", "punctual lights", {{"on", true}, {"off", false}},
                 settings.punctualLights);
  options.value("--exposure", [&settings](const std::string& option, const std::string& value) {
    const double ev = parseNumber(option, value);
    if (!(std::fabs(ev) <= kMaxExposure))
      throw UsageError(option + ": '" + value + "' is out of range (-64..64 EV)");
    settings.exposure = float(ev);
  });
  using OptionalToneMap = std::optional<ToneMap>;
  options.choice("--tonemap", "tone map",
                 {{"pbr-neutral", OptionalToneMap(ToneMap::PbrNeutral)},
                  {"aces", OptionalToneMap(ToneMap::Aces)},
                  {"none", OptionalToneMap(ToneMap::None)}},
                 lighting.toneMap);
}

void describeRender(const RenderSettings& settings, FrameMetadata& metadata) {
  metadata.strings = {{"quadraVersion", QUADRA_VERSION_STRING},
                      {"quadraRenderSettings", describeRenderSettings(settings)}};
}

void addCameraOptions(CommandOptions& options, CameraOverrides& overrides) {
  // A named pointer, not a structured binding: clang 14, which builds the
  // ASan suite, cannot capture a binding.
  for (const auto& bound :
       {std::pair{"--eye", &overrides.eye}, std::pair{"--target", &overrides.target},
        std::pair{"--up", &overrides.up}}) {
    auto* target = bound.second;
    options.value(bound.first, [target](const std::string& option, const std::string& value) {
      *target = parseVector(option, value);
    });
  }
  options.value("--fovy", [&overrides](const std::string& option, const std::string& value) {
    overrides.fovyDegrees = float(parseNumber(option, value));
    if (!(*overrides.fovyDegrees > 0.0f && *overrides.fovyDegrees < 180.0f))
      throw Error(option + ": '" + value + "' must be between 0 and 180 degrees");
  });
  options.value("--near", [&overrides](const std::string& option, const std::string& value) {
    overrides.znear = float(parseNumber(option, value));
    if (!(*overrides.znear > 0.0f)) throw Error(option + ": '" + value + "' must be positive");
  });
  options.value("--far", [&overrides](const std::string& option, const std::string& value) {
    overrides.zfar = float(parseNumber(option, value));
    if (*overrides.zfar < 0.0f)
      throw Error(option + ": '" + value + "' must be 0 (infinite) or positive");
  });
}

Camera chooseCamera(const Scene& scene, const CameraOverrides& overrides) {
  return applyCameraOverrides(firstCameraOrDefault(scene), overrides);
}

Camera applyCameraOverrides(Camera camera, const CameraOverrides& overrides) {
  if (overrides.eye || overrides.target || overrides.up) {
    const glm::vec3 position(camera.world[3]);
    const glm::vec3 forward = -glm::normalize(glm::vec3(camera.world[2]));
    const glm::vec3 eye = overrides.eye.value_or(position);
    const glm::vec3 target = overrides.target.value_or(eye + forward);
    const glm::vec3 up = overrides.up.value_or(glm::normalize(glm::vec3(camera.world[1])));
    if (glm::length(target - eye) == 0.0f) throw Error("--target: must differ from --eye");
    camera.world = lookAtWorld(eye, target, up);
  }
  if (overrides.fovyDegrees) {
    camera.type = Camera::Type::Perspective;
    camera.yfov = *overrides.fovyDegrees * 3.14159265358979f / 180.0f;
  }
  if (overrides.znear) camera.znear = *overrides.znear;
  if (overrides.zfar) camera.zfar = *overrides.zfar;
  if (camera.zfar > 0.0f && camera.zfar <= camera.znear)
    throw Error("--far: the far plane must lie beyond the near plane");
  return camera;
}

std::map<std::string, std::string> lineKeyValues(const std::string& output,
                                                 const std::string& prefix) {
  std::map<std::string, std::string> pairs;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(prefix, 0) != 0) continue;
    std::istringstream words(line.substr(prefix.size()));
    for (std::string word; words >> word;) {
      const std::size_t eq = word.find('=');
      if (eq != std::string::npos) pairs[word.substr(0, eq)] = word.substr(eq + 1);
    }
  }
  return pairs;
}

FrameTimeSummary summarizeFrameTimes(std::vector<double> times) {
  QUADRA_CHECK(!times.empty());
  std::sort(times.begin(), times.end());
  const std::size_t n = times.size();
  const double median = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
  return {median, times.front(), times.back()};
}

}  // namespace quadra
