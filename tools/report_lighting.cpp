// `quadra report lighting`: lit frames of quadra and of the llvmpipe peer's
// split-sum method (tools/peer/) against the lab's lit ideal and against
// each other's time, per scene and environment. Accuracy: the ideal of
// LIGHTING.md (lab/reference/lit_reference.h, in this process, cached on
// disk) at a small size, and `quadra render --shading pbr` at 1 sample and at
// 16 supersampled, and `quadra-llvmpipe render --shading pbr`, each written
// as EXR and scored as LIGHTING.md "Output" says (lab/image/lit_score.h).
// Speed: the same renderers as separate processes at a large size, in R
// rounds taking turns at going first, as `quadra report frames` times them
// (report_runs.h): float frames, 8-bit tone-mapped frames (quadra's PNG,
// llvmpipe's sRGB8 target) and end to end. It prints two markdown tables and
// the issue-46 checks, and writes DIR/lighting.csv and DIR/lighting.svg
// (ms/frame, log, against interior PSNR).
#include <sys/stat.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "io/image_io.h"
#include "lab/image/lit_score.h"
#include "lab/reference/lit_reference.h"
#include "render_options.h"
#include "report_output.h"
#include "report_runs.h"
#include "subprocess.h"
#include "svg_plot.h"

namespace quadra {
namespace {

namespace fs = std::filesystem;

constexpr const char* kLightingUsage =
    R"(usage: quadra report lighting [--scenes LIST] [--envs LIST] [--accuracy-size WxH]
                              [--speed-size WxH] [--threads N] [--frames K] [--rounds R]
                              [--ideal-spp N] [--ideal-check] [--assets DIR] [--out-dir DIR]
                              [--allow-path DIR] [--llvmpipe-ibl-size N]
                              [--llvmpipe-lut-size N]
  --scenes LIST         comma-separated sample model names (folders of --assets),
                        .gltf/.glb files or builtin:NAME (default: WaterBottle,
                        BoomBoxWithAxes, Avocado, Suzanne, NormalTangentMirrorTest,
                        MetalRoughSpheresNoTextures, LightsPunctualLamp,
                        EmissiveStrengthTest, CesiumMilkTruck)
  --envs LIST           comma-separated environments, builtin:NAME or .hdr/.exr files
                        (default: builtin:studio and chinese_garden_1k.hdr of
                        --assets/environments)
  --accuracy-size WxH   the frames scored against the ideal (default 320x180)
  --speed-size WxH      the timed frames (default 1920x1080)
  --threads N           threads of both renderers and of the ideal (default: all cores)
  --frames K            timed frames per timing run, after one warm-up (default 5)
  --rounds R            rounds of timing runs; each time is the median over them
                        (default 3)
  --ideal-spp N         the ideal's rays per pixel axis, N x N a pixel (default 8),
                        each with 16 + 16 environment samples
  --ideal-check         also trace each ideal with a second seed and print what the
                        two disagree on: the ideal's noise floor (twice the time)
  --assets DIR          the sample models, DIR/<Model>/glTF/<Model>.gltf, and the
                        environments, DIR/environments (default: ../shared/assets
                        beside the source tree)
  --out-dir DIR         where lighting.csv, lighting.svg and the images (DIR/lighting/)
                        go (default out); the ideals stay there as a cache, reused by a
                        later run of the same scene, environment, size and settings
  --allow-path DIR      a folder the glTF files' URIs may read besides their own
                        (repeatable; passed to both renderers)
  --llvmpipe-ibl-size N llvmpipe's prefiltered cubes' face size (its --ibl-size;
                        default 256, the Sample Viewer's)
  --llvmpipe-lut-size N llvmpipe's GGX table's side (its --lut-size; default 1024, the
                        Sample Viewer's)
Each scene and environment is rendered by `quadra render --shading pbr --env ENV`
and, where it was built beside this quadra and draws pbr, by `quadra-llvmpipe
render --shading pbr --env ENV` (the split-sum method on Mesa's llvmpipe), as
separate processes. Accuracy: PSNR (peak 1) of the frames tone-mapped by PBR
Neutral and sRGB-encoded against the lab's ideal (LIGHTING.md), over all pixels
and interior pixels, for quadra at 1 sample, quadra at --samples 16
--shading-rate sample, and llvmpipe. Speed: ms/frame, the median over the
rounds of each run's median of K frames, float (EXR; llvmpipe's RGBA32F target)
and 8-bit (PNG: quadra's tone-mapped bytes; llvmpipe's sRGB8 target), and end
to end: `render SCENE --frames 1 --out FILE.png` from process start to exit.
Ratios are quadra / llvmpipe (below 1: quadra is faster).
)";

const char* const kDefaultScenes[] = {"WaterBottle",
                                      "BoomBoxWithAxes",
                                      "Avocado",
                                      "Suzanne",
                                      "NormalTangentMirrorTest",
                                      "MetalRoughSpheresNoTextures",
                                      "LightsPunctualLamp",
                                      "EmissiveStrengthTest",
                                      "CesiumMilkTruck"};

struct LightingReportOptions {
  std::string scenes, environments;
  int accuracyWidth = 320, accuracyHeight = 180;
  int speedWidth = 1920, speedHeight = 1080;
  int threads = 0;
  int frames = 5;
  int rounds = 3;
  int idealSpp = 8;
  bool idealCheck = false;
  std::string assets = QUADRA_ASSETS_DIR;
  std::string outDir = "out";
  LoadOptions load;  // --allow-path, passed on
  // The peer's preparation sizes; smaller ones prepare in seconds (for tests).
  int peerIblSize = 256, peerLutSize = 1024;
};

// "WxH", each side 1..kMaxViewportSize.
void parseSize(const std::string& option, const std::string& text, int& width, int& height) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos)
    throw UsageError(option + ": expected WxH (e.g. 320x180), got '" + text + "'");
  width = parseInteger(option, text.substr(0, x), 1, kMaxViewportSize);
  height = parseInteger(option, text.substr(x + 1), 1, kMaxViewportSize);
}

std::optional<LightingReportOptions> parseLighting(const std::vector<std::string>& args) {
  LightingReportOptions options;
  CommandOptions parser("report lighting", kLightingUsage);
  parser.text("--scenes", options.scenes);
  parser.integer("--llvmpipe-ibl-size", options.peerIblSize, 16, 1024);
  parser.integer("--llvmpipe-lut-size", options.peerLutSize, 16, 4096);
  parser.text("--envs", options.environments);
  parser.value("--accuracy-size", [&options](const std::string& option, const std::string& text) {
    parseSize(option, text, options.accuracyWidth, options.accuracyHeight);
  });
  parser.value("--speed-size", [&options](const std::string& option, const std::string& text) {
    parseSize(option, text, options.speedWidth, options.speedHeight);
  });
  addThreadsOption(parser, options.threads);
  parser.integer("--frames", options.frames, 1, 1000);
  parser.integer("--rounds", options.rounds, 1, 100);
  parser.integer("--ideal-spp", options.idealSpp, 1, 64);
  parser.flag("--ideal-check", [&options] { options.idealCheck = true; });
  parser.text("--assets", options.assets);
  parser.text("--out-dir", options.outDir);
  addAllowPathOption(parser, options.load);
  if (parser.parse(args) == Parsed::HelpShown) return std::nullopt;
  if (options.threads == 0)
    options.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  return options;
}

// An environment of the report: what `--env` is given and what the table calls it.
struct EnvironmentEntry {
  std::string label;     // the built-in's name or the file's stem
  std::string argument;  // builtin:NAME or a file path
};

std::vector<EnvironmentEntry> chooseEnvironments(const LightingReportOptions& options) {
  std::vector<std::string> arguments;
  if (options.environments.empty())
    arguments = {kDefaultEnvironment,
                 (fs::path(options.assets) / "environments" / "chinese_garden_1k.hdr").string()};
  else
    arguments = splitList("--envs", options.environments);
  std::vector<EnvironmentEntry> entries;
  const std::string prefix = kBuiltinScenePrefix;
  for (const std::string& argument : arguments)
    entries.push_back({argument.rfind(prefix, 0) == 0 ? argument.substr(prefix.size())
                                                      : fs::path(argument).stem().string(),
                       argument});
  return entries;
}

// One scene under one environment: a row of both tables.
struct LightingRow {
  SceneEntry scene;
  EnvironmentEntry environment;
  std::string stem;  // its files' names start with it
  std::size_t triangles = 0;
  double idealSeconds = NAN;  // NaN: read from the cache
  std::optional<LitScore> idealCheck;
  std::optional<LitScore> quadra1, quadra16, peer;  // against the ideal
  // Per round; the speed runs. quadra16Ms: --samples 16 --shading-rate sample, float.
  std::vector<double> quadraMs, quadra16Ms, peerMs, quadra8Ms, peer8Ms, quadraE2e, peerE2e;
  double peerPrepareMs = NAN;  // llvmpipe's environment preprocessing, last float run
};

// The ideal's file name: the row, size and settings, and a hash of what
// else decides its pixels (the scene's and environment's files by path,
// size and time), so that a changed input is traced anew.
std::string idealKey(const LightingRow& row, const LightingReportOptions& options,
                     std::uint32_t seed) {
  std::string identity = row.scene.argument + '\n' + row.environment.argument + '\n';
  for (const std::string& file : {row.scene.argument, row.environment.argument}) {
    struct stat info {};
    if (::stat(file.c_str(), &info) == 0)
      identity += std::to_string(info.st_size) + ' ' + std::to_string(info.st_mtim.tv_sec) + '.' +
                  std::to_string(info.st_mtim.tv_nsec) + '\n';
  }
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
  for (const char c : identity) hash = (hash ^ std::uint8_t(c)) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return row.stem + ".ideal." + std::to_string(options.accuracyWidth) + "x" +
         std::to_string(options.accuracyHeight) + ".spp" + std::to_string(options.idealSpp) +
         ".env16+16.seed" + std::to_string(seed) + "." + hex;
}

// The ideal frame of the row, from the cache (DIR/lighting/KEY.exr and
// KEY.interior) or traced and stored there.
ref::LitFrame idealFrame(LightingRow& row, const LightingReportOptions& options, const Scene& scene,
                         const EnvironmentImage& environment, const fs::path& imageDir,
                         std::uint32_t seed, tbb::task_arena& arena) {
  const std::string key = idealKey(row, options, seed);
  const fs::path exr = imageDir / (key + ".exr"), mask = imageDir / (key + ".interior");
  const std::size_t pixels = std::size_t(options.accuracyWidth) * options.accuracyHeight;
  std::error_code ec;
  if (fs::is_regular_file(exr, ec) && fs::file_size(mask, ec) == pixels) {
    ref::LitFrame frame;
    frame.image = readImage(exr.string());
    std::ifstream in(mask, std::ios::binary);
    frame.interior.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (frame.image.width == options.accuracyWidth &&
        frame.image.height == options.accuracyHeight && frame.interior.size() == pixels)
      return frame;
  }
  const auto start = std::chrono::steady_clock::now();
  const ref::ReferenceEnvironment reference(environment);
  const ref::LitReference ideal(scene, firstCameraOrDefault(scene), options.accuracyWidth,
                                options.accuracyHeight, &reference);
  ref::LitSettings settings;
  settings.samplesPerAxis = options.idealSpp;
  settings.seed = seed;
  ref::LitFrame frame = arena.execute([&] { return ideal.render(settings); });
  if (seed == 1)
    row.idealSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // RGB alone: the scores read R, G, B of premultiplied radiance.
  std::vector<float> rgb(pixels * 3);
  for (std::size_t i = 0; i < pixels; ++i)
    for (std::size_t c = 0; c < 3; ++c) rgb[i * 3 + c] = frame.image.rgba[i * 4 + c];
  writeExrRgb(rgb.data(), frame.image.width, frame.image.height, exr.string());
  writeText(mask, std::string(frame.interior.begin(), frame.interior.end()));
  return frame;
}

LitScore scoreFile(const LightingRow& row, const fs::path& file, const ref::LitFrame& ideal) {
  try {
    return scoreLitFrame(readImage(file.string()), ideal.image, ideal.interior);
  } catch (const Error& e) {
    throw Error(row.scene.label + ": " + e.what());
  }
}

std::string dbText(const std::optional<LitScore>& score, bool interior) {
  if (!score) return "-";
  const double psnr = interior ? score->interior.psnr : score->all.psnr;
  return std::isinf(psnr) ? "inf" : format("%.1f", psnr);
}

std::string msText(const std::vector<double>& runs) {
  return runs.empty() ? "-" : figures(medianOf(runs));
}

std::string ratioText(const std::vector<double>& mine, const std::vector<double>& theirs,
                      const char* spec = "%.2f") {
  return mine.empty() || theirs.empty() ? "-" : format(spec, medianOf(mine) / medianOf(theirs));
}

std::string secondsText(const std::vector<double>& runs) {
  return runs.empty() ? "-" : format("%.2f", medianOf(runs));
}

std::string csvText(const std::vector<LightingRow>& rows) {
  std::ostringstream csv;
  csv << "scene,environment,triangles,ideal_s,ideal_check_all_db,ideal_check_interior_db,"
         "quadra_1spp_all_db,quadra_1spp_interior_db,quadra_16spp_all_db,"
         "quadra_16spp_interior_db,llvmpipe_all_db,llvmpipe_interior_db,quadra_ms,"
         "quadra_16spp_ms,llvmpipe_ms,ratio,quadra_8bit_ms,llvmpipe_8bit_ms,ratio_8bit,"
         "quadra_e2e_s,llvmpipe_e2e_s,e2e_ratio,llvmpipe_prepare_ms,quadra_ms_rounds,"
         "quadra_16spp_ms_rounds,llvmpipe_ms_rounds,quadra_8bit_ms_rounds,"
         "llvmpipe_8bit_ms_rounds,quadra_e2e_s_rounds,llvmpipe_e2e_s_rounds\n";
  const auto db = [](const std::optional<LitScore>& score, bool interior) {
    const std::string text = dbText(score, interior);
    return text == "-" ? std::string() : text;
  };
  const auto median = [](const std::vector<double>& runs) {
    return runs.empty() ? std::string() : format("%.4g", medianOf(runs));
  };
  const auto ratio = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.empty() || b.empty() ? std::string() : format("%.4g", medianOf(a) / medianOf(b));
  };
  for (const LightingRow& row : rows)
    csv << row.scene.label << ',' << row.environment.label << ',' << row.triangles << ','
        << (std::isnan(row.idealSeconds) ? std::string() : format("%.3g", row.idealSeconds)) << ','
        << db(row.idealCheck, false) << ',' << db(row.idealCheck, true) << ','
        << db(row.quadra1, false) << ',' << db(row.quadra1, true) << ',' << db(row.quadra16, false)
        << ',' << db(row.quadra16, true) << ',' << db(row.peer, false) << ',' << db(row.peer, true)
        << ',' << median(row.quadraMs) << ',' << median(row.quadra16Ms) << ',' << median(row.peerMs)
        << ',' << ratio(row.quadraMs, row.peerMs) << ',' << median(row.quadra8Ms) << ','
        << median(row.peer8Ms) << ',' << ratio(row.quadra8Ms, row.peer8Ms) << ','
        << median(row.quadraE2e) << ',' << median(row.peerE2e) << ','
        << ratio(row.quadraE2e, row.peerE2e) << ','
        << (std::isnan(row.peerPrepareMs) ? std::string() : format("%.4g", row.peerPrepareMs))
        << ',' << joined(row.quadraMs, "%.4g") << ',' << joined(row.quadra16Ms, "%.4g") << ','
        << joined(row.peerMs, "%.4g") << ',' << joined(row.quadra8Ms, "%.4g") << ','
        << joined(row.peer8Ms, "%.4g") << ',' << joined(row.quadraE2e, "%.4g") << ','
        << joined(row.peerE2e, "%.4g") << '\n';
  return csv.str();
}

// ms/frame (log) against interior PSNR: a point per row and renderer, one
// colour per renderer, each point's scene and environment in its tooltip
// and the three points of a row joined by a faint line.
std::string svgText(const std::vector<LightingRow>& rows, const std::string& subtitle) {
  struct Series {
    const char* label;
    const char* colour;
    const std::vector<double> LightingRow::*ms;
    const std::optional<LitScore> LightingRow::*score;
  };
  const Series series[] = {
      {"quadra, 1 sample", "#1f77b4", &LightingRow::quadraMs, &LightingRow::quadra1},
      {"quadra, 16 samples (sample rate)", "#2ca02c", &LightingRow::quadra16Ms,
       &LightingRow::quadra16},
      {"llvmpipe, split sum", "#d62728", &LightingRow::peerMs, &LightingRow::peer}};
  const auto has = [](const LightingRow& row, const Series& s) {
    return !(row.*s.ms).empty() && (row.*s.score) && std::isfinite((row.*s.score)->interior.psnr);
  };
  double msMin = 1e300, msMax = 0, dbMin = 1e300, dbMax = -1e300;
  for (const LightingRow& row : rows)
    for (const Series& s : series)
      if (has(row, s)) {
        msMin = std::min(msMin, medianOf(row.*s.ms));
        msMax = std::max(msMax, medianOf(row.*s.ms));
        dbMin = std::min(dbMin, (row.*s.score)->interior.psnr);
        dbMax = std::max(dbMax, (row.*s.score)->interior.psnr);
      }
  if (msMin > msMax) msMin = msMax = 1.0, dbMin = dbMax = 40.0;  // nothing to draw
  SvgPlot plot{
      .x = PlotAxis::logarithmicAround(msMin, msMax, 1e-3, "ms per frame (log)"),
      .y = PlotAxis::linearAround(dbMin, dbMax, "interior PSNR against the lit ideal (dB)")};
  plot.width = 980;
  plot.height = 640;
  plot.right = 260;  // the legend
  std::ostringstream svg;
  svg << plot.begin("quadra and llvmpipe lit frames: time against accuracy", subtitle);
  for (const LightingRow& row : rows) {
    std::ostringstream points;
    for (const Series& s : series)
      if (has(row, s))
        points << plot.toX(medianOf(row.*s.ms)) << ',' << plot.toY((row.*s.score)->interior.psnr)
               << ' ';
    svg << "<polyline points=\"" << points.str()
        << "\" fill=\"none\" stroke=\"#bbb\" stroke-width=\"1\"/>\n";
  }
  for (const LightingRow& row : rows)
    for (const Series& s : series) {
      if (!has(row, s)) continue;
      svg << "<circle cx=\"" << plot.toX(medianOf(row.*s.ms)) << "\" cy=\""
          << plot.toY((row.*s.score)->interior.psnr) << "\" r=\"4\" fill=\"" << s.colour
          << "\"><title>"
          << svgEscaped(row.scene.label + ", " + row.environment.label + ", " + s.label)
          << "</title></circle>\n";
    }
  const double legendX = plot.width - plot.right + 16;
  double legendY = plot.top + 8;
  for (const Series& s : series) {
    svg << "<circle cx=\"" << legendX + 6 << "\" cy=\"" << legendY << "\" r=\"4\" fill=\""
        << s.colour << "\"/>\n<text x=\"" << legendX + 16 << "\" y=\"" << legendY + 4 << "\">"
        << svgEscaped(s.label) << "</text>\n";
    legendY += 18;
  }
  svg << "<text x=\"" << legendX << "\" y=\"" << legendY + 4
      << "\" fill=\"#555\">grey lines: one scene and</text>\n<text x=\"" << legendX << "\" y=\""
      << legendY + 20 << "\" fill=\"#555\">environment</text>\n"
      << SvgPlot::end();
  return svg.str();
}

// "k of n" rows meeting a check; rows without the figures are not counted.
std::string checkLine(const std::string& what, int met, int counted, int rows) {
  std::string line = "- " + what + ": " + std::to_string(met) + " of " + std::to_string(counted);
  if (counted < rows) line += " (" + std::to_string(rows - counted) + " rows not measured)";
  return line + "\n";
}

}  // namespace

int runLightingReport(const std::vector<std::string>& args) {
  const std::optional<LightingReportOptions> parsed = parseLighting(args);
  if (!parsed) return 0;
  const LightingReportOptions& options = *parsed;
  std::vector<SceneEntry> scenes;
  if (options.scenes.empty())
    for (const char* model : kDefaultScenes) scenes.push_back(sceneEntryOf(model, options.assets));
  else
    for (const std::string& entry : splitList("--scenes", options.scenes))
      scenes.push_back(sceneEntryOf(entry, options.assets));
  // Every environment and scene is loaded before the first slow ideal: a typo
  // in the last one should not cost the first ones' minutes.
  const std::vector<EnvironmentEntry> environmentEntries = chooseEnvironments(options);
  std::vector<std::unique_ptr<const EnvironmentImage>> environments;
  for (const EnvironmentEntry& entry : environmentEntries) {
    MemoryBudget budget(options.load.maxMemory, "--envs");
    environments.push_back(
        std::make_unique<const EnvironmentImage>(loadEnvironmentArgument(entry.argument, budget)));
  }
  std::vector<Scene> loaded;
  for (const SceneEntry& scene : scenes)
    loaded.push_back(loadSceneArgument(scene.argument, options.load, "quadra"));

  const std::optional<fs::path> peer = findLlvmpipePeer();
  std::string peerNote;  // why llvmpipe is not measured
  if (!peer)
    peerNote =
        "quadra-llvmpipe is not beside this quadra (it is built where libosmesa6-dev is "
        "installed, by scripts/test.sh or `cmake --build build --target quadra-llvmpipe`)";
  else if (const std::string refusal = peerRefusal(*peer, {"--shading", "pbr"}); !refusal.empty())
    peerNote = "quadra-llvmpipe refuses --shading pbr: " + refusal;
  const bool havePeer = peerNote.empty();

  const fs::path outDir(options.outDir), imageDir = outDir / "lighting";
  std::error_code ec;
  fs::create_directories(imageDir, ec);
  if (ec || !fs::is_directory(imageDir))
    throw Error(options.outDir + ": cannot create the output directory");

  const fs::path quadraProgram = executablePath().parent_path() / "quadra";
  const Contender quadra1{"quadra", quadraProgram, {}};
  const Contender quadra16{
      "quadra", quadraProgram, {"--samples", "16", "--shading-rate", "sample"}};
  const std::string iblSize = std::to_string(options.peerIblSize),
                    lutSize = std::to_string(options.peerLutSize);
  const Contender peerFloat{
      "llvmpipe",
      peer.value_or(fs::path()),
      {"--framebuffer", "rgba32f", "--ibl-size", iblSize, "--lut-size", lutSize}};
  const Contender peer8{"llvmpipe",
                        peer.value_or(fs::path()),
                        {"--framebuffer", "srgba8", "--ibl-size", iblSize, "--lut-size", lutSize}};

  std::vector<LightingRow> rows;
  for (std::size_t s = 0; s < scenes.size(); ++s)
    for (std::size_t e = 0; e < environmentEntries.size(); ++e) {
      LightingRow row;
      row.scene = scenes[s];
      row.environment = environmentEntries[e];
      row.stem = fileStem(row.scene.label) + "." + fileStem(row.environment.label);
      row.triangles = loaded[s].triangleCount();
      rows.push_back(row);
    }
  const auto runOptions = [&](const LightingRow& row, int width, int height, int frames) {
    RenderRun run{.width = width,
                  .height = height,
                  .threads = options.threads,
                  .frames = frames,
                  .options = {"--shading", "pbr", "--env", row.environment.argument}};
    for (const std::string& folder : options.load.allowedPaths)
      run.options.insert(run.options.end(), {"--allow-path", folder});
    return run;
  };

  // Accuracy: each row's ideal (cached), then its three frames at that size.
  tbb::task_arena arena(options.threads);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    LightingRow& row = rows[r];
    progress("report lighting: accuracy " + std::to_string(r + 1) + "/" +
             std::to_string(rows.size()) + " " + row.scene.label + ", " + row.environment.label);
    const Scene& scene = loaded[r / environmentEntries.size()];
    const EnvironmentImage& environment = *environments[r % environmentEntries.size()];
    const ref::LitFrame ideal = idealFrame(row, options, scene, environment, imageDir, 1, arena);
    if (options.idealCheck) {
      const ref::LitFrame second = idealFrame(row, options, scene, environment, imageDir, 2, arena);
      row.idealCheck = scoreLitFrame(second.image, ideal.image, ideal.interior);
    }
    const RenderRun run =
        runOptions(row, options.accuracyWidth, options.accuracyHeight, /*frames=*/1);
    double seconds = 0.0;
    const fs::path one = imageDir / (row.stem + ".quadra-1spp.exr"),
                   sixteen = imageDir / (row.stem + ".quadra-16spp.exr"),
                   split = imageDir / (row.stem + ".llvmpipe.exr");
    runRender(quadra1, row.scene, run, one, outDir, seconds);
    row.quadra1 = scoreFile(row, one, ideal);
    runRender(quadra16, row.scene, run, sixteen, outDir, seconds);
    row.quadra16 = scoreFile(row, sixteen, ideal);
    if (havePeer) {
      runRender(peerFloat, row.scene, run, split, outDir, seconds);
      row.peer = scoreFile(row, split, ideal);
    }
  }

  // Speed: R rounds over the rows, each run's pair taking turns at going first.
  const fs::path speedDir = imageDir / "speed";
  fs::create_directories(speedDir, ec);
  for (int round = 0; round < options.rounds; ++round)
    for (std::size_t r = 0; r < rows.size(); ++r) {
      LightingRow& row = rows[r];
      progress("report lighting: speed, round " + std::to_string(round + 1) + "/" +
               std::to_string(options.rounds) + ", " + std::to_string(r + 1) + "/" +
               std::to_string(rows.size()) + " " + row.scene.label + ", " + row.environment.label);
      struct Timed {
        const Contender* contender;
        std::vector<double>* into;
        const char* file;
        bool endToEnd;
      };
      const std::vector<std::vector<Timed>> pairs = {
          {{&quadra1, &row.quadraMs, "quadra.exr", false},
           {&peerFloat, &row.peerMs, "llvmpipe.exr", false}},
          {{&quadra1, &row.quadra8Ms, "quadra.png", false},
           {&peer8, &row.peer8Ms, "llvmpipe.png", false}},
          {{&quadra1, &row.quadraE2e, "quadra.e2e.png", true},
           {&peer8, &row.peerE2e, "llvmpipe.e2e.png", true}},
          {{&quadra16, &row.quadra16Ms, "quadra-16spp.exr", false}}};
      for (const std::vector<Timed>& pair : pairs)
        for (std::size_t k = 0; k < pair.size(); ++k) {
          const Timed& timed = pair[(k + std::size_t(round) + r) % pair.size()];
          if (timed.contender->name == "llvmpipe" && !havePeer) continue;
          const RenderRun run = runOptions(row, options.speedWidth, options.speedHeight,
                                           timed.endToEnd ? 1 : options.frames);
          double seconds = 0.0;
          const auto line = runRender(*timed.contender, row.scene, run,
                                      speedDir / (row.stem + "." + timed.file), outDir, seconds);
          timed.into->push_back(timed.endToEnd ? seconds : std::stod(line.at("median")));
          if (timed.into == &row.peerMs && line.count("prepare_ms"))
            row.peerPrepareMs = std::stod(line.at("prepare_ms"));
        }
    }
  progress("");

  std::ostringstream out;
  const std::string accuracySize =
      std::to_string(options.accuracyWidth) + "x" + std::to_string(options.accuracyHeight);
  const std::string speedSize =
      std::to_string(options.speedWidth) + "x" + std::to_string(options.speedHeight);
  out << "Lit frames (--shading pbr), " << options.threads << " threads. Accuracy at "
      << accuracySize << ": PSNR (dB, peak 1) of the PBR Neutral, sRGB-encoded frame against "
      << "the lab's lit ideal (" << options.idealSpp << "x" << options.idealSpp
      << " rays a pixel, 16 + 16 environment samples a ray), all pixels / interior pixels; "
         "1 spp: `quadra render --shading pbr`; 16 spp: with --samples 16 --shading-rate "
         "sample; gain: quadra 1 spp's interior dB minus llvmpipe's.\n";
  if (havePeer) {
    out << "llvmpipe: `quadra-llvmpipe render --shading pbr` (split sum on Mesa's llvmpipe).\n\n";
  } else {
    out << "llvmpipe: not measured: " << peerNote << ".\n\n";
  }
  out << "| scene | environment | ideal s | quadra 1 spp all | interior | quadra 16 spp all | "
         "interior | llvmpipe all | interior | gain dB |\n"
         "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  int gainMet = 0, gainCounted = 0, sixteenMet = 0, speedMet = 0, speedCounted = 0, speed8Met = 0,
      speed8Counted = 0, e2eMet = 0, e2eCounted = 0;
  for (const LightingRow& row : rows) {
    std::string gain = "-";
    if (row.quadra1 && row.peer) {
      const double dB = row.quadra1->interior.psnr - row.peer->interior.psnr;
      gain = format("%.1f", dB);
      ++gainCounted;
      if (dB >= 6.0) ++gainMet;
    }
    if (row.quadra16 && row.quadra16->all.psnr >= 40.0) ++sixteenMet;
    out << "| " << row.scene.label << " | " << row.environment.label << " | "
        << (std::isnan(row.idealSeconds) ? std::string("cached") : format("%.1f", row.idealSeconds))
        << " | " << dbText(row.quadra1, false) << " | " << dbText(row.quadra1, true) << " | "
        << dbText(row.quadra16, false) << " | " << dbText(row.quadra16, true) << " | "
        << dbText(row.peer, false) << " | " << dbText(row.peer, true) << " | " << gain << " |\n";
  }
  if (options.idealCheck) {
    out << "\nThe ideal's noise floor: the same ideal traced with seed 2 against seed 1, "
           "all / interior dB.\n\n| scene | environment | all | interior |\n|---|---|---:|---:|\n";
    for (const LightingRow& row : rows)
      out << "| " << row.scene.label << " | " << row.environment.label << " | "
          << dbText(row.idealCheck, false) << " | " << dbText(row.idealCheck, true) << " |\n";
  }
  out << "\nSpeed at " << speedSize << ", " << options.threads << " threads: ms/frame, medians of "
      << options.rounds << " rounds (each run: the median of " << options.frames
      << " timed frames after a warm-up); float: EXR output, llvmpipe into RGBA32F; 8-bit: "
         "PNG output, llvmpipe into sRGB8; e2e: `render SCENE --frames 1 --out FILE.png` "
         "(llvmpipe into sRGB8) from process start to exit, seconds. Ratio: quadra / "
         "llvmpipe.\n\n"
         "| scene | environment | triangles | quadra ms | 16 spp ms | llvmpipe ms | ratio | "
         "quadra 8-bit ms | llvmpipe 8-bit ms | ratio | quadra e2e s | llvmpipe e2e s | ratio |\n"
         "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const LightingRow& row : rows) {
    const auto count = [](const std::vector<double>& a, const std::vector<double>& b, int& met,
                          int& counted) {
      if (a.empty() || b.empty()) return;
      ++counted;
      if (medianOf(a) / medianOf(b) <= 0.5) ++met;
    };
    count(row.quadraMs, row.peerMs, speedMet, speedCounted);
    count(row.quadra8Ms, row.peer8Ms, speed8Met, speed8Counted);
    count(row.quadraE2e, row.peerE2e, e2eMet, e2eCounted);
    out << "| " << row.scene.label << " | " << row.environment.label << " | "
        << withThousands(row.triangles) << " | " << msText(row.quadraMs) << " | "
        << msText(row.quadra16Ms) << " | " << msText(row.peerMs) << " | "
        << ratioText(row.quadraMs, row.peerMs) << " | " << msText(row.quadra8Ms) << " | "
        << msText(row.peer8Ms) << " | " << ratioText(row.quadra8Ms, row.peer8Ms) << " | "
        << secondsText(row.quadraE2e) << " | " << secondsText(row.peerE2e) << " | "
        << ratioText(row.quadraE2e, row.peerE2e) << " |\n";
  }
  const int n = int(rows.size());
  out << "\nIssue 46's checks, rows meeting them:\n"
      << checkLine("quadra 1 spp at least 6 dB closer to the ideal than llvmpipe (interior)",
                   gainMet, gainCounted, n)
      << checkLine("quadra 16 spp at least 40 dB (all pixels)", sixteenMet, n, n)
      << checkLine("quadra's float frame at most 0.5x llvmpipe's", speedMet, speedCounted, n)
      << checkLine("quadra's 8-bit frame at most 0.5x llvmpipe's", speed8Met, speed8Counted, n)
      << checkLine("end to end at most 0.5x llvmpipe's", e2eMet, e2eCounted, n);

  const std::string subtitle = "accuracy " + accuracySize + ", speed " + speedSize + " float, " +
                               std::to_string(options.threads) + " threads";
  const fs::path csvPath = outDir / "lighting.csv", svgPath = outDir / "lighting.svg";
  writeText(csvPath, csvText(rows));
  writeText(svgPath, svgText(rows, subtitle));
  std::cout << out.str() << "\nquadra wrote " << csvPath.string() << "\nquadra wrote "
            << svgPath.string() << "\nquadra wrote the frames and the ideals to "
            << imageDir.string() << "\n";
  return 0;
}

}  // namespace quadra
