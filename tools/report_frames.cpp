// `quadra report frames`: quadra against Mesa's llvmpipe on the same frames,
// in the same run. For every built-in scene and every sample model (or the
// --scenes list) it runs `quadra render` and `quadra-llvmpipe render`
// (tools/peer/; both found beside quadra-report) as separate processes with the same
// arguments, over R rounds, the two taking turns at going first: a timing run
// (K timed frames after a warm-up; its median frame time; the frame written
// as EXR) and an end-to-end run (--frames 1 writing a PNG,
// timed from spawn to exit). It prints a markdown table of the medians over
// the rounds and of the two images' difference, then the geometric means of
// the ratios, and writes DIR/frames.csv. Both draw unlit (--shading unlit,
// the default) or lit (--shading pbr under --env).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "core/error.h"
#include "io/image_io.h"
#include "lab/image/image_difference.h"
#include "lab/scene/builtin_scenes.h"
#include "lab/scene/sample_models.h"
#include "render_options.h"
#include "report_output.h"
#include "report_runs.h"
#include "subprocess.h"

namespace quadra {
namespace {

namespace fs = std::filesystem;

constexpr const char* kFramesUsage =
    R"(usage: quadra report frames [--width W] [--height H] [--threads N] [--frames K]
                            [--rounds R] [--scenes LIST] [--assets DIR] [--out-dir DIR]
                            [--llvmpipe-framebuffer rgba32f|srgba8] [--allow-path DIR]
                            [--max-memory SIZE] [--samples N] [--shading unlit|pbr]
                            [--env FILE|builtin:NAME] [--llvmpipe-ibl-size N]
                            [--llvmpipe-lut-size N]
  --width W --height H  frame size (default 1920x1080)
  --threads N           threads of both renderers (default: all cores)
  --frames K            timed frames per timing run, after one warm-up (default 5)
  --rounds R            rounds of runs; each figure is the median over them (default 3)
  --scenes LIST         comma-separated builtin:NAME, sample model names (folders of
                        --assets) or .gltf/.glb files (default: every built-in scene
                        but flyover, the sequence scene, then every model in --assets)
  --assets DIR          the sample models, DIR/<Model>/glTF/<Model>.gltf
                        (default: ../shared/assets beside the source tree)
  --out-dir DIR         where frames.csv and the images (DIR/frames/) go (default out)
  --llvmpipe-framebuffer rgba32f|srgba8
                        llvmpipe's colour buffer: rgba32f (default) holds what quadra's
                        frame holds; srgba8 is llvmpipe's cheapest target
  --allow-path DIR      a folder the glTF files' URIs may read besides their own
                        (repeatable; passed to both renderers)
  --max-memory SIZE     the memory budget of each load and frame (default 8G; passed to
                        both renderers)
  --samples N           samples per pixel, 1 (default), 2, 4, 8 or 16, passed to both
                        renderers: quadra shades once per pixel and visible triangle,
                        llvmpipe draws N-sample MSAA (it has 4 at most)
  --shading unlit|pbr   both renderers' shading (default unlit); pbr: glTF's
                        metallic-roughness material lit by --env, the split-sum method
                        on llvmpipe's side (see quadra report lighting)
  --env FILE|builtin:NAME
                        pbr's environment, passed to both renderers (default
                        builtin:studio)
  --llvmpipe-ibl-size N pbr: llvmpipe's prefiltered cubes' face size (its --ibl-size;
                        default 256, the Sample Viewer's)
  --llvmpipe-lut-size N pbr: llvmpipe's GGX table's side (its --lut-size; default 1024,
                        the Sample Viewer's)
Each scene is rendered by `quadra render` and, where it was built beside this
quadra, by `quadra-llvmpipe render` (Mesa's llvmpipe, the same camera and
shading), as separate processes with the same options, taking turns at going first.
Frame time: the median of K timed frames per run. End to end: the wall time of
`render SCENE --frames 1 --out FILE.png`, from process start to exit. Ratios are
quadra / llvmpipe (below 1: quadra is faster). PSNR (peak 1) and max over R, G, B
of the two linear EXR images.
)";

struct FramesOptions {
  int width = 1920;
  int height = 1080;
  int threads = 0;
  int frames = 5;
  int rounds = 3;
  std::string scenes;
  std::string assets = QUADRA_ASSETS_DIR;
  std::string outDir = "out";
  std::string peerFramebuffer = "rgba32f";        // quadra-llvmpipe --framebuffer
  int peerIblSize = 256, peerLutSize = 1024;      // quadra-llvmpipe --ibl-size, --lut-size (pbr)
  LoadOptions load;                               // --allow-path and --max-memory, passed on
  int samples = 1;                                // --samples, passed on
  std::string shading = "unlit";                  // --shading, passed on
  std::string environment = kDefaultEnvironment;  // --env, passed on with pbr
};

std::optional<FramesOptions> parseFrames(const std::vector<std::string>& args) {
  FramesOptions options;
  CommandOptions parser("report frames", kFramesUsage);
  addSizeOptions(parser, options.width, options.height);
  addThreadsOption(parser, options.threads);
  parser.integer("--frames", options.frames, 1, 1000);
  parser.integer("--rounds", options.rounds, 1, 100);
  parser.text("--scenes", options.scenes);
  parser.text("--assets", options.assets);
  parser.text("--out-dir", options.outDir);
  parser.integer("--llvmpipe-ibl-size", options.peerIblSize, 16, 1024);
  parser.integer("--llvmpipe-lut-size", options.peerLutSize, 16, 4096);
  parser.choice("--llvmpipe-framebuffer", "framebuffer",
                {{"rgba32f", std::string("rgba32f")}, {"srgba8", std::string("srgba8")}},
                options.peerFramebuffer);
  addAllowPathOption(parser, options.load);
  addMaxMemoryOption(parser, options.load);
  addSamplesOption(parser, options.samples);
  parser.choice("--shading", "shading",
                {{"unlit", std::string("unlit")}, {"pbr", std::string("pbr")}}, options.shading);
  parser.text("--env", options.environment);
  if (parser.parse(args) == Parsed::HelpShown) return std::nullopt;
  if (options.threads == 0)
    options.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  return options;
}

// Every <Model>/glTF/<Model>.gltf under `assets` that quadra loads, by name;
// none when absent. The others (refused for an extension they require, so
// no frame of them can be timed) are named on stderr.
std::vector<SceneEntry> sampleModels(const fs::path& assets) {
  std::vector<SceneEntry> models;
  std::error_code ec;
  if (!fs::is_directory(assets, ec)) return models;
  for (const fs::directory_entry& folder : fs::directory_iterator(assets, ec)) {
    const std::string name = folder.path().filename().string();
    const fs::path file = modelFile(assets, name);
    if (!fs::is_regular_file(file, ec)) continue;
    if (const std::string lacked = lackedRequiredGltfExtension(file); !lacked.empty()) {
      std::cerr << "quadra: note: report frames: " << name << " left out: it requires " << lacked
                << "\n";
      continue;
    }
    models.push_back({name, file.string()});
  }
  std::sort(models.begin(), models.end(),
            [](const SceneEntry& a, const SceneEntry& b) { return a.label < b.label; });
  return models;
}

std::vector<SceneEntry> chooseFramesScenes(const FramesOptions& options) {
  const std::vector<std::string> builtins = builtinSceneNames();
  std::vector<SceneEntry> scenes;
  if (options.scenes.empty()) {
    for (const std::string& name : builtins) {
      // The sequence scene: its still is showcase's content, measured there.
      if (name == "flyover") continue;
      scenes.push_back({kBuiltinScenePrefix + name, kBuiltinScenePrefix + name});
    }
    for (const SceneEntry& model : sampleModels(options.assets)) scenes.push_back(model);
    return scenes;
  }
  for (const std::string& entry : splitList("--scenes", options.scenes))
    scenes.push_back(sceneEntryOf(entry, options.assets));
  return scenes;
}

struct Measurements {
  std::vector<double> frameMs, endToEndSeconds;  // one per round
  std::size_t triangles = 0;
  std::map<std::string, std::string> line;  // the last frame_ms line's key=value pairs
};

struct FramesSceneResult {
  SceneEntry scene;
  std::vector<Measurements> byContender;
  std::optional<ImageDifference> difference;
};

ImageDifference compareImages(const SceneEntry& scene, const fs::path& a, const fs::path& b) {
  try {
    return imageDifference(readImage(a.string()), readImage(b.string()));
  } catch (const Error& e) {
    throw Error(scene.label + ": " + e.what());
  }
}

}  // namespace

int runFramesReport(const std::vector<std::string>& args) {
  const std::optional<FramesOptions> parsed = parseFrames(args);
  if (!parsed) return 0;
  const FramesOptions& options = *parsed;
  if (options.shading == "pbr") {
    MemoryBudget budget(options.load.maxMemory, "--env");
    loadEnvironmentArgument(options.environment, budget);  // checked before any run
  }
  const std::vector<SceneEntry> scenes = chooseFramesScenes(options);
  if (scenes.empty()) throw Error("report frames: no scenes to render");
  const fs::path outDir(options.outDir), imageDir = outDir / "frames";
  std::error_code ec;
  std::vector<Contender> contenders = {
      {"quadra", executablePath().parent_path() / "quadra", {"--shading", options.shading}}};
  const std::optional<fs::path> peer = findLlvmpipePeer();
  std::string peerNote;  // why llvmpipe is not measured
  if (!peer)
    peerNote =
        "quadra-llvmpipe is not beside this quadra (it is built where libosmesa6-dev is "
        "installed, by scripts/test.sh or `cmake --build build --target quadra-llvmpipe`)";
  std::vector<std::string> peerOptions = {"--framebuffer", options.peerFramebuffer};
  if (peer && options.shading == "pbr") {
    peerNote = peerRefusal(*peer, {"--shading", "pbr"});
    if (!peerNote.empty()) peerNote = "quadra-llvmpipe refuses --shading pbr: " + peerNote;
    peerOptions.insert(peerOptions.end(),
                       {"--shading", "pbr", "--ibl-size", std::to_string(options.peerIblSize),
                        "--lut-size", std::to_string(options.peerLutSize)});
  } else if (peer && renderAccepts(*peer, "--shading")) {
    peerOptions.insert(peerOptions.end(), {"--shading", "unlit"});
  }
  const bool havePeer = peerNote.empty();
  if (havePeer) contenders.push_back({"llvmpipe", *peer, peerOptions});
  if (havePeer && options.samples > 1) {
    // Whether llvmpipe draws that many samples, asked of it before anything
    // is written (Mesa 22.3 has 4 at most).
    const std::string refusal = peerRefusal(*peer, {"--samples", std::to_string(options.samples)});
    if (!refusal.empty()) throw Error(refusal);
  }
  RenderRun run{.width = options.width,
                .height = options.height,
                .threads = options.threads,
                .frames = 1,
                .options = {}};
  for (const std::string& folder : options.load.allowedPaths)
    run.options.insert(run.options.end(), {"--allow-path", folder});
  if (options.load.maxMemory != kDefaultMaxMemory)
    run.options.insert(run.options.end(), {"--max-memory", std::to_string(options.load.maxMemory)});
  if (options.samples > 1)
    run.options.insert(run.options.end(), {"--samples", std::to_string(options.samples)});
  if (options.shading == "pbr")
    run.options.insert(run.options.end(), {"--env", options.environment});

  fs::create_directories(imageDir, ec);
  if (ec || !fs::is_directory(imageDir))
    throw Error(options.outDir + ": cannot create the output directory");

  std::vector<FramesSceneResult> results;
  for (const SceneEntry& scene : scenes)
    results.push_back({scene, std::vector<Measurements>(contenders.size()), std::nullopt});
  for (int round = 0; round < options.rounds; ++round)
    for (std::size_t s = 0; s < results.size(); ++s) {
      FramesSceneResult& result = results[s];
      progress("report frames: round " + std::to_string(round + 1) + "/" +
               std::to_string(options.rounds) + ", scene " + std::to_string(s + 1) + "/" +
               std::to_string(results.size()) + " " + result.scene.label);
      // Taking turns at going first, so neither always meets the other's
      // leftovers in the caches and the page cache.
      std::vector<std::size_t> order(contenders.size());
      for (std::size_t c = 0; c < order.size(); ++c)
        order[c] = (c + std::size_t(round) + s) % contenders.size();
      const std::string stem = fileStem(result.scene.label);
      for (const bool endToEnd : {false, true})
        for (const std::size_t c : order) {
          const Contender& contender = contenders[c];
          Measurements& measured = result.byContender[c];
          // Every timing run writes the EXR, so every round times the same
          // work: both renderers produce depth for its Z channel.
          const fs::path image =
              imageDir / (stem + "." + contender.name + (endToEnd ? ".png" : ".exr"));
          double seconds = 0.0;
          run.frames = endToEnd ? 1 : options.frames;
          const auto line = runRender(contender, result.scene, run, image, outDir, seconds);
          if (endToEnd) {
            measured.endToEndSeconds.push_back(seconds);
          } else {
            measured.frameMs.push_back(std::stod(line.at("median")));
            measured.triangles = std::stoull(line.at("triangles"));
            measured.line = line;
          }
        }
      if (havePeer && round == 0)
        result.difference = compareImages(result.scene, imageDir / (stem + ".quadra.exr"),
                                          imageDir / (stem + ".llvmpipe.exr"));
    }
  progress("");

  std::ostringstream out, csv;
  out << "Frames at " << options.width << "x" << options.height << ", " << options.threads
      << " threads, "
      << (options.shading == "pbr" ? "lit (--shading pbr --env " + options.environment + "), "
                                   : std::string("unlit, "))
      << (options.samples > 1
              ? std::to_string(options.samples) + " samples per pixel (quadra: --samples " +
                    std::to_string(options.samples) +
                    ", shading once per pixel and visible triangle; llvmpipe: "
                    "MSAA resolved by glBlitFramebuffer), "
              : std::string())
      << "medians of " << options.rounds << " rounds (each run: the median of " << options.frames
      << " timed frames after a warm-up); end to end: `render SCENE --frames 1 "
      << "--out FILE.png` from process start to exit.\n";
  if (havePeer) {
    const auto& peerLine = results.front().byContender[1].line;
    const auto value = [&](const char* key) {
      return peerLine.count(key) ? peerLine.at(key) : std::string("unknown");
    };
    out << "llvmpipe: Mesa " << value("mesa") << ", " << value("vector_bits")
        << "-bit vectors, LP_NUM_THREADS=" << options.threads << ", OpenGL 4.5 through OSMesa, "
        << (options.peerFramebuffer == "srgba8" ? "8-bit sRGB" : "RGBA32F")
        << " colour + 32-bit float depth, each frame read "
           "back. Ratio: quadra / llvmpipe (below 1: quadra is faster). PSNR (peak 1) and max: "
           "R, G, B of the two linear EXR images.\n\n";
    out << "| scene | triangles | quadra ms | llvmpipe ms | ratio | quadra e2e s | llvmpipe e2e s "
           "| e2e ratio | PSNR dB | max diff |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
           "\n";
  } else {
    out << "llvmpipe: not measured: " << peerNote << ".\n\n";
    out << "| scene | triangles | quadra ms | quadra e2e s |\n|---|---:|---:|---:|\n";
  }
  csv << "scene,triangles,quadra_ms,llvmpipe_ms,ratio,quadra_e2e_s,llvmpipe_e2e_s,e2e_ratio,"
         "psnr_db,max_abs_diff,quadra_ms_rounds,llvmpipe_ms_rounds,quadra_e2e_s_rounds,"
         "llvmpipe_e2e_s_rounds\n";
  std::vector<double> frameRatios, endToEndRatios;
  for (const FramesSceneResult& result : results) {
    const Measurements& q = result.byContender[0];
    const double qMs = medianOf(q.frameMs), qSeconds = medianOf(q.endToEndSeconds);
    out << "| " << result.scene.label << " | " << withThousands(q.triangles) << " | "
        << figures(qMs) << " | ";
    csv << result.scene.label << ',' << q.triangles << ',' << format("%.4g", qMs) << ',';
    if (!havePeer) {
      out << format("%.3f", qSeconds) << " |\n";
      csv << ",," << format("%.4g", qSeconds) << ",,,,," << joined(q.frameMs, "%.4g") << ",,"
          << joined(q.endToEndSeconds, "%.4g") << ",\n";
      continue;
    }
    const Measurements& l = result.byContender[1];
    const double lMs = medianOf(l.frameMs), lSeconds = medianOf(l.endToEndSeconds);
    const double ratio = qMs / lMs, endToEndRatio = qSeconds / lSeconds;
    frameRatios.push_back(ratio);
    endToEndRatios.push_back(endToEndRatio);
    const ImageDifference& d = *result.difference;
    const std::string psnr = std::isinf(d.psnr) ? "inf" : format("%.1f", d.psnr);
    out << figures(lMs) << " | " << format("%.2f", ratio) << " | " << format("%.3f", qSeconds)
        << " | " << format("%.3f", lSeconds) << " | " << format("%.2f", endToEndRatio) << " | "
        << psnr << " | " << format("%.3f", d.maxAbs) << " |\n";
    csv << format("%.4g", lMs) << ',' << format("%.4g", ratio) << ',' << format("%.4g", qSeconds)
        << ',' << format("%.4g", lSeconds) << ',' << format("%.4g", endToEndRatio) << ',' << psnr
        << ',' << format("%.4g", d.maxAbs) << ',' << joined(q.frameMs, "%.4g") << ','
        << joined(l.frameMs, "%.4g") << ',' << joined(q.endToEndSeconds, "%.4g") << ','
        << joined(l.endToEndSeconds, "%.4g") << '\n';
  }
  if (havePeer)
    out << "\nGeometric mean over " << results.size() << " scenes: frame ratio "
        << format("%.3f", geometricMean(frameRatios)) << " (quadra "
        << format("%.2f", 1.0 / geometricMean(frameRatios)) << "x as fast), end-to-end ratio "
        << format("%.3f", geometricMean(endToEndRatios)) << " ("
        << format("%.2f", 1.0 / geometricMean(endToEndRatios)) << "x).\n";

  const fs::path csvPath = outDir / "frames.csv";
  writeText(csvPath, csv.str());
  std::cout << out.str() << "\nquadra wrote " << csvPath.string() << "\n";
  return 0;
}

}  // namespace quadra
