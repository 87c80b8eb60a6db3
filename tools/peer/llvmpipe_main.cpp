// quadra-llvmpipe: the peer renderer quadra is measured against (`quadra
// report frames`, `quadra report lighting`). `quadra-llvmpipe render SCENE …`
// mirrors `quadra render` for what it supports: it loads the scene (and for
// pbr the environment) with quadra's loaders, takes the same camera, draws
// the same frame with Mesa's llvmpipe (gl_scene_renderer.h: unlit as quadra
// shades it, pbr as the Khronos glTF Sample Viewer lights it), times it the
// way quadra times its own (one warm-up frame, then K timed frames, each
// until its colour is in memory), writes the last frame with quadra's
// writers and prints `llvmpipe frame_ms …`. A separate program, so that
// quadra never links Mesa.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "api/renderer.h"
#include "cli_options.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "core/parallel.h"
#include "gl_scene_renderer.h"
#include "io/image_io.h"
#include "lab/scene/builtin_scenes.h"
#include "osmesa_context.h"
#include "render_options.h"

namespace quadra {
namespace {

constexpr const char* kProgram = "quadra-llvmpipe";

constexpr const char* kUsage = R"(usage: quadra-llvmpipe render [SCENE] [options]
Draws quadra's frame of SCENE with Mesa's llvmpipe (OpenGL 4.5 through OSMesa)
for comparison with `quadra render`: the same loader, camera and draw order;
unlit, the same shading; pbr, glTF's material lit as the Khronos glTF Sample
Viewer lights it (split-sum image-based lighting, docs/lighting.md).
  SCENE                  file.gltf | file.glb | builtin:NAME (default builtin:showcase)
  --scene N              which glTF scene to render (default: the file's default scene)
  --allow-path DIR       a folder the glTF file's URIs may read besides its own (repeatable,
                         as for quadra render)
  --max-memory SIZE      what loading the scene may allocate, as for quadra render (default 8G)
  --width W --height H   image size, default 1920x1080
  --eye x,y,z --target x,y,z --up x,y,z --fovy DEG --near N --far F
                         override the scene's first camera (far 0 = infinite)
  --filter nearest|bilinear|nearest-mip|trilinear|aniso
                         texture filter for every texture (default: each glTF sampler's)
  --aniso N              max anisotropy, default 16
  --lod-bias B           added to every texture lookup's LOD (default 0)
  --texture-format auto|rgba32f|rgba16f|rgba8|rgba8srgb
                         texel format of the GL textures (default auto: as quadra stores them)
  --framebuffer rgba32f|srgba8
                         colour buffer: rgba32f (default) holds what quadra's frame holds;
                         srgba8 is llvmpipe's cheapest target (8-bit sRGB, blended in linear;
                         pbr frames tone mapped by the shader)
  --shading unlit|pbr    unlit (default) = baseColorFactor x baseColorTexture x vertex colour;
                         pbr = glTF's metallic-roughness material under the environment
                         (prefiltered once, timed as prepare_ms) and the scene's
                         KHR_lights_punctual lights; KHR_materials_unlit materials stay unlit
  --env FILE.hdr|FILE.exr|builtin:NAME
                         pbr's environment, as for quadra render (default builtin:studio)
  --env-rotation DEG     turn the environment about +Y, counter-clockwise seen from above
  --env-intensity S      scale the environment's radiance (default 1)
  --background env|color|transparent
                         what pbr shows where no surface is: the environment seen through
                         the pixel (default), --background-color, or alpha 0
  --background-color R,G,B
                         linear radiance of --background color (default 0,0,0)
  --lights on|off        the scene's KHR_lights_punctual lights (default on)
  --exposure EV          outputs hold radiance x 2^EV (default 0)
  --tonemap pbr-neutral|aces|none
                         how pbr's PNG outputs (and its srgba8 framebuffer) map radiance to
                         [0, 1] before sRGB encoding (default pbr-neutral); EXR stays linear
  --ibl-size N           pbr: the prefiltered cubes' face size, a power of two from 16 to 1024
                         (default 256, the Sample Viewer's; 5 roughness levels at any size)
  --lut-size N           pbr: the GGX table's side, 16 to 4096 (default 1024, the Sample
                         Viewer's)
  --samples N            multisampling (MSAA): 1 (default), 2, 4, 8 or 16 samples per pixel,
                         as far as llvmpipe has them (GL_MAX_SAMPLES), resolved by
                         glBlitFramebuffer (the samples' mean) within the frame's time
  --threads N            llvmpipe's rasterizer threads (LP_NUM_THREADS; default: all cores)
  --frames K             K timed frames after one warm-up (default 1)
  --out FILE.exr|FILE.png
                         write the last frame (may be given more than once)
Prints "llvmpipe frame_ms median=... min=... max=... triangles=... width=... height=...
threads=... frames=... mesa=... vector_bits=... samples=... prepare_ms=..." after
rendering; a frame's time ends when its colour has been read back; prepare_ms is the
pbr environment's preparation (0 for unlit), done once before the first frame.
)";

struct PeerCommand {
  std::string scenePath = "builtin:showcase";
  LoadOptions load;
  PeerSettings settings;
  int threads = 0;
  int frames = 1;
  std::vector<std::string> outputs;
  CameraOverrides camera;
  RenderSettings lit;  // the lighting options, as quadra render reads them
  LightingOptions lighting;
};

std::optional<PeerCommand> parseRender(const std::vector<std::string>& args) {
  PeerCommand cmd;
  CommandOptions options("render", kUsage, kProgram);
  addSceneOptions(options, cmd.scenePath, cmd.load);
  addSizeOptions(options, cmd.settings.width, cmd.settings.height);
  addCameraOptions(options, cmd.camera);
  addFilterOptions(options, cmd.settings.filter, cmd.settings.maxAniso, cmd.settings.lodBias);
  addTexelFormatOrAutoOption(options, "--texture-format", cmd.settings.textureFormat);
  options.choice("--framebuffer", "framebuffer",
                 {{"rgba32f", PeerFramebuffer::Rgba32F}, {"srgba8", PeerFramebuffer::Srgba8}},
                 cmd.settings.framebuffer);
  addSamplesOption(options, cmd.settings.samples);
  options.choice("--shading", "shading", {{"unlit", Shading::Unlit}, {"pbr", Shading::Pbr}},
                 cmd.settings.shading);
  addLightingOptions(options, cmd.lit, cmd.lighting);
  options.integer("--ibl-size", cmd.settings.iblSize, 16, 1024);
  options.integer("--lut-size", cmd.settings.lutSize, 16, 4096);
  addThreadsOption(options, cmd.threads);
  options.integer("--frames", cmd.frames, 1, 100000);
  addOutputOption(options, cmd.outputs);
  if (options.parse(args) == Parsed::HelpShown) return std::nullopt;
  cmd.settings.frameDepth = outputsNeedDepth(cmd.outputs);
  if ((cmd.settings.iblSize & (cmd.settings.iblSize - 1)) != 0)
    throw UsageError("--ibl-size: '" + std::to_string(cmd.settings.iblSize) +
                     "' must be a power of two (16, 32, ... 1024)");
  cmd.settings.environmentRotation = cmd.lit.environmentRotation;
  cmd.settings.environmentIntensity = cmd.lit.environmentIntensity;
  cmd.settings.background = cmd.lit.background;
  cmd.settings.clearColor = cmd.lit.clearColor;
  cmd.settings.punctualLights = cmd.lit.punctualLights;
  cmd.settings.exposure = cmd.lit.exposure;
  // As quadra render: pbr frames tone map with PBR Neutral unless told.
  const bool pbr = cmd.settings.shading == Shading::Pbr;
  cmd.settings.toneMap = cmd.lighting.toneMap.value_or(pbr ? ToneMap::PbrNeutral : ToneMap::None);
  if (cmd.settings.filter && !peerSupportsFilter(*cmd.settings.filter))
    throw UsageError(
        std::string("--filter ") + filterName(*cmd.settings.filter) +
        ": llvmpipe has no such filter (nearest, bilinear, nearest-mip, trilinear, aniso)");
  return cmd;
}

// The word after `marker` ("4.5 (Core Profile) Mesa 22.3.6", "Mesa " -> "22.3.6").
std::string wordAfter(const std::string& text, const std::string& marker) {
  const std::size_t at = text.find(marker);
  if (at == std::string::npos) return "unknown";
  const std::size_t start = at + marker.size();
  return text.substr(start, text.find_first_of(" ,)", start) - start);
}

// The word before `marker` ("llvmpipe (LLVM 15.0.6, 256 bits)", " bits" -> "256").
std::string wordBefore(const std::string& text, const std::string& marker) {
  const std::size_t at = text.find(marker);
  if (at == std::string::npos || at == 0) return "unknown";
  const std::size_t space = text.rfind(' ', at - 1);
  const std::size_t start = space == std::string::npos ? 0 : space + 1;
  return text.substr(start, at - start);
}

int renderCommand(const std::vector<std::string>& args) {
  const std::optional<PeerCommand> parsed = parseRender(args);
  if (!parsed) return 0;
  const PeerCommand& cmd = *parsed;
  const int threads =
      cmd.threads > 0 ? cmd.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  const Scene scene = loadSceneArgument(cmd.scenePath, cmd.load, kProgram);
  PeerSettings settings = cmd.settings;
  std::optional<EnvironmentImage> environment;
  if (settings.shading == Shading::Pbr) {
    MemoryBudget budget(cmd.load.maxMemory, "--env");
    environment = loadEnvironmentArgument(cmd.lighting.environment, budget);
    settings.environment = &*environment;
  }
  const Camera camera = chooseCamera(scene, cmd.camera);
  const OsMesaContext context(threads);
  GlSceneRenderer renderer(context, scene, settings);

  renderer.render(camera);  // warm-up: llvmpipe compiles its shaders here
  std::vector<double> times;
  for (int i = 0; i < cmd.frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    renderer.render(camera);
    times.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  Frame frame;
  renderer.lastFrame(frame);
  // quadra's writer, on as many threads as llvmpipe had, as quadra's CLI does.
  const Executor writer(threads);
  // An 8-bit pbr frame was tone mapped by its shader already.
  const ToneMap pngToneMap =
      settings.framebuffer == PeerFramebuffer::Srgba8 && settings.shading == Shading::Pbr
          ? ToneMap::None
          : settings.toneMap;
  for (const std::string& path : cmd.outputs) {
    writeFrame(frame, path, &writer, {}, pngToneMap);
    std::cout << "llvmpipe wrote " << path << "\n";
  }
  const FrameTimeSummary summary = summarizeFrameTimes(times);
  std::printf(
      "llvmpipe frame_ms median=%.3f min=%.3f max=%.3f triangles=%zu width=%d height=%d "
      "threads=%d frames=%d mesa=%s vector_bits=%s samples=%d prepare_ms=%.3f\n",
      summary.median, summary.min, summary.max, scene.triangleCount(), cmd.settings.width,
      cmd.settings.height, threads, cmd.frames, wordAfter(context.version(), "Mesa ").c_str(),
      wordBefore(context.renderer(), " bits").c_str(), cmd.settings.samples, renderer.prepareMs());
  return 0;
}

// Its one command's usage is its overview: `help`, `help render` and
// `render --help` print the same.
int run(const std::vector<std::string>& args) {
  if (args.empty() || args[0] == "--help" || args[0] == "-h" ||
      (args[0] == "help" && (args.size() == 1 || args[1] == "render"))) {
    std::cout << kUsage;
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "render") return renderCommand({args.begin() + 1, args.end()});
  const std::string& command = args[0] == "help" ? args[1] : args[0];
  const std::string suggestion = didYouMean(command, std::vector<std::string>{"render", "help"});
  throw UsageError("unknown command '" + command + "' " +
                   (suggestion.empty() ? "(commands: render, help)" : suggestion.substr(1)));
}

}  // namespace
}  // namespace quadra

int main(int argc, char** argv) {
  return quadra::runMain("quadra-llvmpipe", argc, argv, quadra::run);
}
