// quadra command-line tool: the entry point (the command overview, `quadra
// help`), `quadra render` (DESIGN.md "Contracts") on glTF files and
// built-in scenes, and the hand-over of `quadra report` to quadra-report.
// Every failure is one line on stderr and a non-zero exit (cli_options.h
// runMain: 2 for usage, 1 otherwise); outputs are written only after a frame
// succeeded.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <OpenEXR/ImfThreading.h>

#include "api/camera.h"
#include "api/renderer.h"
#include "cli_options.h"
#include "commands.h"
#include "core/error.h"
#include "core/parallel.h"
#include "frame_batch.h"
#include "io/image_io.h"
#include "lab/scene/builtin_scenes.h"
#include "progress.h"
#include "render_options.h"
#include "report_subjects.h"
#include "scene/animation.h"
#include "sequence_options.h"
#include "sequence_writer.h"
#include "subprocess.h"
#include "window/sample_pattern.h"

namespace quadra {
namespace {

constexpr const char* kUsage = R"(usage: quadra render [SCENE] [options]
Renders a glTF file or a built-in scene, times the frames and writes the last to each --out.
  SCENE                  file.gltf | file.glb | builtin:NAME (default builtin:showcase)
  --scene N              which glTF scene to render (default: the file's default scene)
  --allow-path DIR       a folder besides the glTF file's own that its buffer and image URIs
                         may read (repeatable; default: its own folder only, by relative
                         URIs; absolute paths and file: URIs only inside a DIR given here)
  --max-memory SIZE      what the scene may allocate, for loading and again for each frame
                         (buffers, meshes, decoded images, texture levels, frame and tile
                         memory): bytes or K, M, G, T (1024-based), e.g. 512M (default 8G)
  --width W --height H   image size, default 1920x1080 (at most 8192 per side)
  --eye x,y,z --target x,y,z --up x,y,z --fovy DEG --near N --far F
                         override the scene's first camera (far 0 = infinite)
  --filter nearest|bilinear|nearest-mip|trilinear|aniso|ewa|area|sat|ripmap
                         texture filter for every texture (default: each glTF sampler's)
  --aniso N              max anisotropy, default 16
  --lod-bias B           added to every texture lookup's LOD (default 0)
  --lod box|gl           trilinear's level: nearer the pixel's box footprint (default,
                         0.2 below GL's; closer to the ideal image) or OpenGL's
                         log2 of the footprint, as GPUs choose it
  --texture-format auto|rgba32f|rgba16f|rgba8|rgba8srgb
                         texel storage (default auto: rgba16f for 8-bit images, else rgba32f)
  --depth standard|reversed
                         depth buffer: standard (0 near, LESS) or reversed (1 near, GREATER)
  --shading unlit|lit|pbr
                         pbr (default) = glTF's metallic-roughness material under the
                         environment and the scene's KHR_lights_punctual lights
                         (docs/lighting.md); KHR_materials_unlit materials stay unlit;
                         unlit = baseColorFactor x baseColorTexture x vertex colour;
                         lit = that x a Lambert head light
  --env FILE.hdr|FILE.exr|builtin:NAME
                         pbr's environment: an equirectangular panorama of linear radiance
                         (default builtin:studio; `quadra env --help` lists the built-ins)
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
                         how PNG outputs map radiance to [0, 1] before sRGB encoding:
                         Khronos PBR Neutral (default), ACES (Hill's fit) or a clamp;
                         EXR outputs stay linear
  --derivatives analytic|quad
                         texture footprints: the triangles' exact derivatives at each pixel
                         (default) or 2x2 quad differences, as GPUs take them
  --opaque-shading two-pass|forward
                         opaque draws: visibility pass then shading of the visible pixels
                         (default), or shaded as rasterized; the same image either way
  --samples N            coverage and depth samples per pixel: 1, 2, 4, 8 or 16 (default 1)
  --pixel-filter box|blackman-harris
                         how the samples become pixels: each pixel's own samples averaged
                         (default), or every sample within 2 px of the pixel's centre
                         weighted by a Blackman-Harris window (4 px wide; at 1 sample a
                         blur of the pixel centres)
  --aov LIST             more EXR channels, comma-separated (repeatable): N (N.X/Y/Z world
                         normal), P (P.X/Y/Z world position), uv (uv.U/V), motion (motion.X/Y,
                         pixels since the previous frame of a --sequence), id (id.primitive,
                         id.node, id.material, uint), mask (coverage, filtered as the colour),
                         lod and anisotropy (the base colour texture's mip level and probe
                         count as its filter chooses them), albedo, roughness, metallic and
                         emission (albedo.R/G/B, roughness, metallic, emission.R/G/B: the pbr
                         material's terms), diffuse and specular (diffuse.R/G/B,
                         specular.R/G/B: the light of each lobe; emission + diffuse +
                         specular = the colour), Z (always written); PNG outputs hold none
                         (docs/cli.md "AOVs")
  --shading-rate pixel|sample
                         with --samples: shade once per pixel and visible triangle
                         (default, multisampling) or every sample (supersampling)
  --alpha-to-coverage    MASK materials cover round(alpha x samples) of a pixel's samples
                         instead of testing alpha against their cutoff (at 1 sample: 0.5)
  --threads N            default: all cores (loading decodes on them too)
  --isa auto|scalar|sse2|avx2|avx512
                         kernel path (default auto: the best this CPU has)
  --frames K             K timed frames after one warm-up (default 1)
  --out FILE.exr|FILE.png
                         write the last frame (may be given more than once)
  --exr-compression none|rle|zips|zip|piz
                         how EXR outputs are compressed, all lossless (default zip, at
                         zlib's fastest level)
  --exr-colour float|half
                         EXR colour channels R, G, B, A as FLOAT (default) or HALF; Z,
                         mask and the AOVs stay FLOAT
  --sequence FIRST:LAST  render frames FIRST..LAST of an animation, frame f at time f/fps,
                         each frame timed once; every --out must hold a run of '#', which
                         each frame's file has its number in, zero-padded to the run's
                         length (--out 'out/walk_####.exr'); a scene without animations
                         renders the same frame each time
  --fps F                frames per second of --sequence (default 24)
  --animation NAME|INDEX the animation --sequence plays (default: the scene's first)
  --orbit N              a turntable: frames 0..N-1, frame k seen from the default framing
                         turned 360 x k / N degrees about the vertical through the scene's
                         centre (the scene at rest; its own cameras unused); --out as for
                         --sequence
  --shard I/N            render only shard I of N (0 <= I < N) of the sequence's (or orbit's) frames: the
                         frame at position p of the sequence (p = frame - FIRST) is shard
                         p mod N's, so N processes with I = 0..N-1 render each frame once
  --skip-existing        do not render a frame whose every output file exists (files are
                         written whole under a temporary name, then renamed: a file under
                         its final name is complete), so a stopped sequence resumes
  --progress bar|plain|none
                         sequence progress on stderr: a redrawn bar (default where stderr
                         is a terminal), one "quadra progress frame=... status=rendered|skipped
                         ms=... done=... total=... fps=... eta_s=... out=..." line per frame
                         (for logs), or nothing (default elsewhere)
  --stats                also print where the time went: "quadra stages_ms load=... first_frame=...
                         env=... draws=... vertex=... setup=... bin=... raster=... shade=...
                         resolve=... write=..." (env: the environment's preparation, within
                         first_frame)
Prints "quadra frame_ms median=... min=... max=... triangles=... width=... height=...
threads=..." after rendering.
built-in scenes: )";

std::string usage() {
  std::string list;
  for (const std::string& name : builtinSceneNames()) list += (list.empty() ? "" : ", ") + name;
  return kUsage + list + "\n";
}

// `quadra help`: one line a command; each command's own --help has its options.
std::string overview() {
  std::vector<std::pair<std::string, std::string>> rows = {
      {"render [SCENE]", "render a glTF file or a built-in scene to EXR or PNG, timed"},
      {"sample", "texture lookups from a CSV file through one filter, timed"},
      {"env [ENV]", "write an environment's texels, as quadra lights with them, to EXR"}};
  for (const auto& [subject, summary] : reportSubjects())
    rows.emplace_back("report " + subject, summary);
  rows.emplace_back("help [COMMAND]", "this overview, or COMMAND's help (as COMMAND --help)");
  rows.emplace_back("--version", "print quadra's version");
  return "usage: quadra COMMAND [options]\n"
         "commands:\n" +
         summaryLines(rows) +
         "'quadra help COMMAND' or 'quadra COMMAND --help' prints a command's options.\n"
         "Exit status: 0 done; 1 bad input (a file missing, malformed or unwritable, a memory\n"
         "budget exceeded, a failed run or check); 2 usage (an unknown command, subject or\n"
         "option, a missing or malformed value, options that do not combine).\n";
}

// `quadra render` lights with pbr unless --shading says otherwise
// (issue 46); the engine's RenderSettings keeps unlit, which every in-process
// caller (tests, reports, the public API) states or relies on.
RenderSettings pbrByDefault() {
  RenderSettings settings;
  settings.shading = Shading::Pbr;
  return settings;
}

struct RenderCommand {
  std::string scenePath = "builtin:showcase";
  LoadOptions load;
  RenderSettings settings = pbrByDefault();
  RendererConfig config;
  int frames = 1;
  bool framesGiven = false;
  std::optional<FrameRange> sequence;
  double fps = 24.0;
  bool fpsGiven = false;
  std::optional<std::string> animation;  // --animation as given
  std::optional<int> orbit;              // --orbit N: views around the scene, frames 0..N-1
  std::optional<Shard> shard;
  bool skipExisting = false;
  std::optional<ProgressMode> progress;  // unset: defaultProgressMode()
  bool stats = false;
  std::vector<std::string> outputs;
  ExrSettings exr;
  const char* exrOption = nullptr;  // the first EXR storage option given, for messages
  CameraOverrides camera;
  std::optional<TexelFormat> textureFormat;  // unset: as the loader chose
  LightingOptions lighting;
};

// The options that split a sequence among processes and report on it.
void addBatchOptions(CommandOptions& options, RenderCommand& cmd) {
  options.value("--shard", [&cmd](const std::string& option, const std::string& value) {
    cmd.shard = parseShard(option, value);
  });
  options.flag("--skip-existing", [&cmd] { cmd.skipExisting = true; });
  using Progress = std::optional<ProgressMode>;
  options.choice("--progress", "progress display",
                 {{"bar", Progress(ProgressMode::Bar)},
                  {"plain", Progress(ProgressMode::Plain)},
                  {"none", Progress(ProgressMode::None)}},
                 cmd.progress);
}

// nullopt: --help printed the usage.
std::optional<RenderCommand> parseRender(const std::vector<std::string>& args) {
  RenderCommand cmd;
  CommandOptions options("render", usage());
  addSceneOptions(options, cmd.scenePath, cmd.load);
  addSizeOptions(options, cmd.settings.width, cmd.settings.height);
  addCameraOptions(options, cmd.camera);
  addFilterOptions(options, cmd.settings.filter, cmd.settings.maxAniso, cmd.settings.lodBias);
  options.choice("--lod", "LOD rule", {{"box", LodRule::Box}, {"gl", LodRule::Gl}},
                 cmd.settings.lodRule);
  addTexelFormatOrAutoOption(options, "--texture-format", cmd.textureFormat);
  options.choice("--depth", "depth mode",
                 {{"standard", DepthMode::Standard}, {"reversed", DepthMode::Reversed}},
                 cmd.settings.depth);
  options.choice("--shading", "shading",
                 {{"unlit", Shading::Unlit}, {"lit", Shading::Lit}, {"pbr", Shading::Pbr}},
                 cmd.settings.shading);
  addLightingOptions(options, cmd.settings, cmd.lighting);
  options.choice("--derivatives", "derivative mode",
                 {{"analytic", DerivativeMode::Analytic}, {"quad", DerivativeMode::Quad}},
                 cmd.settings.derivatives);
  options.choice("--opaque-shading", "opaque shading",
                 {{"two-pass", OpaqueShading::TwoPass}, {"forward", OpaqueShading::Forward}},
                 cmd.settings.opaqueShading);
  addSamplesOption(options, cmd.settings.samples);
  options.choice("--shading-rate", "shading rate",
                 {{"pixel", ShadingRate::Pixel}, {"sample", ShadingRate::Sample}},
                 cmd.settings.shadingRate);
  options.choice("--pixel-filter", "pixel filter",
                 {{"box", PixelFilter::Box}, {"blackman-harris", PixelFilter::BlackmanHarris}},
                 cmd.settings.pixelFilter);
  addAovOption(options, cmd.settings);
  addThreadsOption(options, cmd.config.threads);
  addIsaOption(options, cmd.config.isa);
  options.value("--frames", [&cmd](const std::string& option, const std::string& value) {
    cmd.frames = parseInteger(option, value, 1, 100000);
    cmd.framesGiven = true;
  });
  options.flag("--stats", [&] { cmd.stats = true; });
  options.flag("--alpha-to-coverage", [&] { cmd.settings.alphaToCoverage = true; });
  addOutputOption(options, cmd.outputs);
  options.value("--exr-compression", [&cmd](const std::string& option, const std::string& value) {
    if (!parseExrCompression(value, cmd.exr.compression))
      throw UsageError(option + ": '" + value +
                       "' is not an EXR compression quadra writes (valid: " +
                       exrCompressionNames() + ")" + didYouMean(value, exrCompressionNames()));
    if (!cmd.exrOption) cmd.exrOption = "--exr-compression";
  });
  options.value("--exr-colour", [&cmd](const std::string& option, const std::string& value) {
    if (value != "float" && value != "half")
      throw UsageError(option + ": '" + value + "' is not an EXR colour type (valid: float, half)" +
                       didYouMean(value, "float, half"));
    cmd.exr.halfColour = value == "half";
    if (!cmd.exrOption) cmd.exrOption = "--exr-colour";
  });
  options.value("--sequence", [&cmd](const std::string& option, const std::string& value) {
    cmd.sequence = parseFrameRange(option, value);
  });
  options.value("--fps", [&cmd](const std::string& option, const std::string& value) {
    cmd.fps = parseNumber(option, value);
    if (!(cmd.fps > 0.0)) throw UsageError(option + ": '" + value + "' must be positive");
    cmd.fpsGiven = true;
  });
  options.value("--animation",
                [&cmd](const std::string&, const std::string& value) { cmd.animation = value; });
  options.value("--orbit", [&cmd](const std::string& option, const std::string& value) {
    cmd.orbit = parseInteger(option, value, 1, 1000000);
  });
  addBatchOptions(options, cmd);
  if (options.parse(args) == Parsed::HelpShown) return std::nullopt;
  if (cmd.orbit) {
    if (cmd.sequence) throw UsageError("--orbit: not with --sequence (a turntable poses nothing)");
    if (cmd.fpsGiven || cmd.animation)
      throw UsageError("--orbit: not with --fps or --animation (the scene stays at rest)");
    if (cmd.camera.eye || cmd.camera.target || cmd.camera.up)
      throw UsageError("--orbit: not with --eye, --target or --up (the orbit places the camera)");
    if (cmd.framesGiven)
      throw UsageError("--frames: not with --orbit (each frame of a turntable is timed once)");
    cmd.sequence = FrameRange{0, *cmd.orbit - 1};
  }
  const char* const sequenceOption = cmd.orbit ? "--orbit" : "--sequence";
  if (!cmd.sequence) {
    if (cmd.fpsGiven) throw UsageError("--fps: only with --sequence");
    if (cmd.animation) throw UsageError("--animation: only with --sequence");
    if (cmd.shard) throw UsageError("--shard: only with --sequence or --orbit");
    if (cmd.skipExisting) throw UsageError("--skip-existing: only with --sequence or --orbit");
    if (cmd.progress) throw UsageError("--progress: only with --sequence or --orbit");
  } else {
    if (cmd.framesGiven)
      throw UsageError("--frames: not with --sequence (each frame of a sequence is timed once)");
    if (cmd.skipExisting && cmd.outputs.empty())
      throw UsageError("--skip-existing: needs an --out (it skips the frames whose files exist)");
    for (const std::string& path : cmd.outputs) {
      if (!hasFrameField(path))
        throw UsageError("--out: '" + path +
                         "' has no run of '#' for the frame number (needed with " + sequenceOption +
                         ")");
    }
  }
  // --background color is opaque: black unless --background-color says.
  if (cmd.settings.background == Background::Color) cmd.settings.clearColor.a = 1.0f;
  cmd.settings.frameDepth = outputsNeedDepth(cmd.outputs);
  if (cmd.exrOption && !cmd.settings.frameDepth)
    throw UsageError(std::string(cmd.exrOption) + ": no --out is an .exr file");
  cmd.settings.maxMemory = cmd.load.maxMemory;
  cmd.load.threads = cmd.config.threads;  // decoding the scene's meshes and images too
  if (cmd.settings.aovs != 0 && !cmd.outputs.empty() && !cmd.settings.frameDepth)
    std::cerr << "quadra: note: --aov: only .exr outputs hold AOVs; the PNG files will not\n";
  return cmd;
}

// --tonemap, or by default what the shading asks for: pbr's radiance
// through Khronos PBR Neutral, the unlit shadings' colours clamped.
ToneMap pngToneMap(const RenderCommand& cmd) {
  if (cmd.lighting.toneMap) return *cmd.lighting.toneMap;
  return cmd.settings.shading == Shading::Pbr ? ToneMap::PbrNeutral : ToneMap::None;
}

// The scene, and for pbr shading the environment into cmd.settings: loaded
// once, before the first frame.
Scene loadScene(RenderCommand& cmd) {
  Scene scene = loadSceneArgument(cmd.scenePath, cmd.load, "quadra");
  if (cmd.textureFormat) setTextureStorage(scene, *cmd.textureFormat);
  if (cmd.settings.shading == Shading::Pbr) {
    MemoryBudget budget(cmd.load.maxMemory, "--env");
    cmd.settings.environment = std::make_shared<const EnvironmentImage>(
        loadEnvironmentArgument(cmd.lighting.environment, budget));
  }
  return scene;
}

// One line of key=value pairs: loading, the warm-up frame (which also builds
// the texture levels its filters read and prepares a lit frame's environment,
// env, part of it) and writing once each, and each frame stage's median over
// the timed frames (api/renderer.h StageTimes says how a parallel pass is
// split among its stages).
void printStages(double loadMs, double firstFrameMs, double envMs,
                 const std::vector<StageTimes>& frames, double writeMs) {
  const auto stage = [&](double StageTimes::*field) {
    std::vector<double> values;
    for (const StageTimes& t : frames) values.push_back(t.*field);
    return summarizeFrameTimes(values).median;
  };
  std::printf(
      "quadra stages_ms load=%.3f first_frame=%.3f env=%.3f draws=%.3f vertex=%.3f setup=%.3f "
      "bin=%.3f raster=%.3f shade=%.3f resolve=%.3f write=%.3f\n",
      loadMs, firstFrameMs, envMs, stage(&StageTimes::draws), stage(&StageTimes::vertex),
      stage(&StageTimes::setup), stage(&StageTimes::bin), stage(&StageTimes::raster),
      stage(&StageTimes::shade), stage(&StageTimes::resolve), writeMs);
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// The frame_ms line (DESIGN.md "Contracts") over the timed frames; the
// triangle counts are the last frame's.
void printFrameLine(const RenderCommand& cmd, const Renderer& renderer,
                    const std::vector<double>& times, const FrameStats& stats,
                    std::size_t frameCount) {
  const FrameTimeSummary summary = summarizeFrameTimes(times);
  std::printf(
      "quadra frame_ms median=%.3f min=%.3f max=%.3f triangles=%zu width=%d height=%d threads=%d "
      "isa=%s frames=%zu drawn=%zu culled=%zu clipped=%zu\n",
      summary.median, summary.min, summary.max, stats.trianglesIn, cmd.settings.width,
      cmd.settings.height, renderer.threadCount(), isaName(renderer.isa()), frameCount,
      stats.trianglesDrawn,
      stats.culledBackFace + stats.culledOutside + stats.droppedDegenerate + stats.droppedInvalid,
      stats.clipped);
}

// "quadra sequence frames=N seconds=S fps=F steady_fps=G": the whole run
// from the first frame's start to the last file written, and the rate after
// the first frame (which also builds the texture levels its filters read).
void printSequenceLine(std::size_t frames, std::chrono::steady_clock::time_point start,
                       std::chrono::steady_clock::time_point firstDone) {
  const double seconds = millisecondsSince(start) / 1000.0;
  const double afterFirst = millisecondsSince(firstDone) / 1000.0;
  const double steady =
      frames > 1 && afterFirst > 0.0 ? double(frames - 1) / afterFirst : double(frames) / seconds;
  std::printf("quadra sequence frames=%zu seconds=%.3f fps=%.3f steady_fps=%.3f\n", frames, seconds,
              double(frames) / seconds, steady);
}

// --sequence: frame f of the range posed at time f / fps, rendered once and
// written to each --out with its number in the name. The scene is loaded
// once and only its instances and cameras move; the renderer keeps its
// buffers from frame to frame, and the files of one frame are written
// (tools/sequence_writer.h) while the next renders. --orbit is a sequence of
// views of the scene at rest. Each file is written whole under a temporary
// name and renamed (io/image_io.h), so a stopped sequence leaves only
// complete frames, which --skip-existing then leaves alone. --shard keeps
// this process's share of the frames (frame_batch.h).
int renderSequence(const RenderCommand& cmd, Renderer& renderer, Scene& scene, double loadMs) {
  // Chosen before anything is rendered, so a wrong name writes nothing.
  const int animation = cmd.animation ? findAnimation(scene, "--animation", *cmd.animation)
                        : (scene.animations.empty() || cmd.orbit) ? -1
                                                                  : 0;
  // A scene without a camera is framed once, at its rest pose: a camera that
  // re-framed the animated bounds every frame would move with them.
  const std::optional<Camera> fixedCamera =
      scene.cameras.empty() ? std::optional<Camera>(chooseCamera(scene, cmd.camera)) : std::nullopt;
  std::vector<int> frames;
  for (int f = cmd.sequence->first; f <= cmd.sequence->last; ++f) frames.push_back(f);
  if (cmd.shard) frames = shardFrames(frames, *cmd.shard);
  SequenceProgress progress(cmd.progress.value_or(defaultProgressMode()), int(frames.size()));
  // The writer's thread reports the frames it wrote, this loop the ones it
  // skips: one report at a time.
  std::mutex reporting;
  // Frame k is written on the writer's thread while frame k + 1 renders; two
  // frames may wait, so a slow disk holds the loop back by at most that.
  SequenceWriter writer(renderer.threadCount(), 2, cmd.exr, pngToneMap(cmd));
  NodePose pose;
  std::vector<double> times;
  std::vector<StageTimes> stages;
  FrameStats stats;
  Frame frame;
  const auto sequenceStart = std::chrono::steady_clock::now();
  std::optional<std::chrono::steady_clock::time_point> firstDone;
  RenderSettings settings = cmd.settings;
  PreviousPose previous;  // the motion AOV's pose one frame earlier
  const auto cameraAt = [&](int f) {
    return cmd.orbit     ? applyCameraOverrides(orbitCamera(scene, f, *cmd.orbit), cmd.camera)
           : fixedCamera ? *fixedCamera
                         : chooseCamera(scene, cmd.camera);
  };
  for (const int f : frames) {
    std::vector<std::string> paths = framePaths(cmd.outputs, f);
    if (cmd.skipExisting && allFilesExist(paths)) {
      const std::lock_guard<std::mutex> lock(reporting);
      progress.skipped(f, paths);
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    if (hasAov(settings.aovs, Aov::Motion)) {
      poseNodes(scene, animation, double(f - 1) / cmd.fps, pose);
      placeOnNodes(scene, pose);
      previous.camera = cameraAt(f - 1);
      previous.instanceWorlds.clear();
      previous.instanceJoints.clear();
      previous.instanceMorphWeights.clear();
      for (const Instance& instance : scene.instances) {
        previous.instanceWorlds.push_back(instance.world);
        previous.instanceJoints.push_back(instance.jointMatrices);
        previous.instanceMorphWeights.push_back(instance.morphWeights);
      }
      settings.previousPose = &previous;
    }
    poseNodes(scene, animation, double(f) / cmd.fps, pose);
    placeOnNodes(scene, pose);
    const Camera camera = cameraAt(f);
    describeRender(settings, frame.metadata);  // frame may be a spare the writer handed back
    stats = renderer.render(scene, camera, settings, frame);
    times.push_back(millisecondsSince(start));
    stages.push_back(stats.stages);
    if (!firstDone) firstDone = std::chrono::steady_clock::now();
    writer.submit(frame, std::move(paths),
                  [&progress, &reporting, f, start](const std::vector<std::string>& written) {
                    const std::lock_guard<std::mutex> lock(reporting);
                    progress.clearBar();
                    for (const std::string& path : written)
                      std::cout << "quadra wrote " << path << "\n";
                    progress.rendered(f, written, millisecondsSince(start));
                  });
  }
  const double writeMs = writer.finish();
  progress.finish();
  // Nothing rendered (every frame skipped, or a shard past the sequence's
  // end): the frame line still comes, with frames=0 and zero times.
  printFrameLine(cmd, renderer, times.empty() ? std::vector<double>{0.0} : times, stats,
                 times.size());
  if (firstDone) printSequenceLine(times.size(), sequenceStart, *firstDone);
  if (cmd.stats && !times.empty())
    printStages(loadMs, times.front(), stages.front().environment, stages, writeMs);
  return 0;
}

int renderCommand(const std::vector<std::string>& args) {
  std::optional<RenderCommand> parsed = parseRender(args);
  if (!parsed) return 0;
  RenderCommand& cmd = *parsed;
  Renderer renderer(cmd.config);  // checks --isa before any slow loading
  // OpenEXR compresses scanline blocks on its own process-wide pool, off by
  // default; the tool (not the library, which keeps no global state) sizes it
  // to the render's threads. Only when an output is EXR (the outputs that
  // need depth): a PNG-only render has no use for the pool's threads.
  if (outputsNeedDepth(cmd.outputs)) Imf::setGlobalThreadCount(renderer.threadCount());
  const auto loadStart = std::chrono::steady_clock::now();
  Scene scene = loadScene(cmd);
  const double loadMs = millisecondsSince(loadStart);
  if (cmd.sequence) return renderSequence(cmd, renderer, scene, loadMs);
  const Camera camera = chooseCamera(scene, cmd.camera);

  Frame frame;
  describeRender(cmd.settings, frame.metadata);
  const auto firstStart = std::chrono::steady_clock::now();
  FrameStats stats = renderer.render(scene, camera, cmd.settings, frame);  // warm-up
  const double firstFrameMs = millisecondsSince(firstStart);
  const double firstEnvMs = stats.stages.environment;
  std::vector<double> times;
  std::vector<StageTimes> stages;
  for (int i = 0; i < cmd.frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    stats = renderer.render(scene, camera, cmd.settings, frame);
    times.push_back(millisecondsSince(start));
    stages.push_back(stats.stages);
  }
  const auto writeStart = std::chrono::steady_clock::now();
  const Executor writer(renderer.threadCount());
  for (const std::string& path : cmd.outputs) {
    writeFrame(frame, path, &writer, cmd.exr, pngToneMap(cmd));
    std::cout << "quadra wrote " << path << "\n";
  }
  const double writeMs = millisecondsSince(writeStart);
  printFrameLine(cmd, renderer, times, stats, times.size());
  if (cmd.stats) printStages(loadMs, firstFrameMs, firstEnvMs, stages, writeMs);
  return 0;
}

// `quadra report ...`: the reports and the lab code only they use are a
// program of their own, quadra-report beside this one (tools/CMakeLists.txt
// says why), which takes this process's place with the same arguments, so
// its output and exit status are the command's.
int runReportProgram(const std::vector<std::string>& args) {
  const std::filesystem::path program = executablePath().parent_path() / "quadra-report";
  if (::access(program.c_str(), X_OK) != 0)
    throw Error(
        "report: quadra-report is not beside this quadra (it is built by `cmake --build "
        "build --target quadra-report`)");
  replaceProcess(program, args);
}

int run(const std::vector<std::string>& args) {
  if (args.empty() || args == std::vector<std::string>{"help"} || args[0] == "--help" ||
      args[0] == "-h") {
    std::cout << overview();
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "help") {
    // "help report frames" is "report frames --help", to the byte.
    std::vector<std::string> command(args.begin() + 1, args.end());
    command.emplace_back("--help");
    return run(command);
  }
  if (args[0] == "--version") {
    std::cout << "quadra " QUADRA_VERSION_STRING "\n";
    return 0;
  }
  const std::vector<std::string> commandArgs(args.begin() + 1, args.end());
  if (args[0] == "render") return renderCommand(commandArgs);
  if (args[0] == "sample") return runSample(commandArgs);
  if (args[0] == "env") return runEnv(commandArgs);
  if (args[0] == "report") return runReportProgram(commandArgs);
  const std::vector<std::string> commands = {"render", "sample", "env",
                                             "report", "help",   "--version"};
  const std::string suggestion = didYouMean(args[0], commands);
  throw UsageError("unknown command '" + args[0] + "' " +
                   (suggestion.empty() ? "(commands: render, sample, env, report, help)"
                                       : suggestion.substr(1)));
}

}  // namespace
}  // namespace quadra

int main(int argc, char** argv) {
  return quadra::runMain("quadra", argc, argv, quadra::run);
}
