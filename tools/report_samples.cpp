// `quadra report samples`: what each sample count and shading rate costs and
// buys. For every scene it renders the ideal image once with the
// double-precision reference tracer (lab/reference), then renders the scene
// in-process at each sample count and both shading rates (one run at 1
// sample, where the rate changes nothing), timing the configurations in
// alternating rounds. It prints a markdown table of ms/frame against PSNR and
// max difference from the ideal, and writes DIR/samples.csv and
// DIR/samples.svg (ms/frame, log, against PSNR: one line per scene and rate).
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "api/renderer.h"
#include "cli_options.h"
#include "commands.h"
#include "core/error.h"
#include "lab/image/image_difference.h"
#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"
#include "render_options.h"
#include "report_output.h"
#include "svg_plot.h"
#include "window/sample_pattern.h"

namespace quadra {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSamplesUsage =
    R"(usage: quadra report samples [--width W] [--height H] [--threads N] [--isa ISA]
                             [--frames K] [--rounds R] [--scenes LIST] [--samples LIST]
                             [--filter F] [--aniso N] [--reference-spp N]
                             [--reference area|rays|none] [--out-dir DIR]
                             [--allow-path DIR] [--max-memory SIZE]
  --width W --height H  frame size (default 480x270: the reference frames of the
                        default scenes then take 1-8 s each on two threads, ~50 s in
                        all with their checks)
  --threads N           threads of the renderer and of the reference tracer
                        (default: all cores)
  --isa ISA             auto|scalar|sse2|avx2|avx512 (default auto)
  --frames K            timed frames per run, after one warm-up (default 5)
  --rounds R            rounds of runs, each running every configuration of the scene
                        once, starting at a different one each round; ms/frame is the
                        median over the rounds of each run's median (default 3)
  --scenes LIST         comma-separated builtin:NAME or .gltf/.glb files (default: every
                        built-in scene and hard case but z-fighting, whose two
                        view-filling quads put no edge on screen (it measures depth
                        precision, which samples do not change), random-triangles,
                        whose reference takes ~40 minutes at 480x270 (about a
                        thousand of its triangles overlap each pixel),
                        invalid-input, whose NaN attributes the tracer shades, and
                        flyover, the sequence scene, whose still showcase covers)
  --allow-path DIR      a folder the glTF files' URIs may read besides their own
                        (repeatable; as for quadra render)
  --max-memory SIZE     the memory budget of each load and frame, as for quadra render
                        (default 8G)
  --samples LIST        comma-separated sample counts, each 1, 2, 4, 8 or 16
                        (default 1,4,8,16)
  --filter F --aniso N  one texture filter for every texture (nearest|bilinear|
                        nearest-mip|trilinear|aniso|ewa|area|sat|ripmap; default: each
                        glTF sampler's) and the anisotropic maximum (default 16)
  --reference-spp N     the reference's subsamples per pixel axis, N x N per pixel
                        (default 16)
  --reference KIND      area (default): each pixel's area integrated exactly where its
                        visible triangles do not overlap on screen (opaque, textured or
                        not, no vertex colours), the N x N rays elsewhere; rays: the
                        N x N rays everywhere (point samples of every texture); none:
                        no reference, the times alone (no PSNR, no plot), for the cost
                        of samples at sizes whose reference would take hours
  --out-dir DIR         where samples.csv and samples.svg go (default out)
Shading rates: pixel shades once per pixel and visible triangle (multisampling),
sample shades every sample (supersampling); at 1 sample they are the same frame,
rendered once. Each scene is seen through its own first camera, unlit, with its
samplers' own filters, as `quadra render SCENE --samples N --shading-rate RATE`
draws it. PSNR (peak 1) and max difference over R, G, B against the reference
tracer's box-filtered frame (exact area integrals or N x N exact ray hits per
pixel, level-0 bilinear textures). "x 1 sample": the median over the rounds of
a run's time over the same round's 1-sample run (with 1 in --samples), the
cost of the samples with the machine's drift between rounds divided out; in
brackets (from 3 rounds), a 95% bootstrap interval of that median: the 2.5th
and 97.5th percentiles of the medians of 4000 resamples of the rounds' ratios,
drawn from a fixed seed (CSV ratio_low, ratio_high).
)";

// 16 x 16 rays per pixel. Measured against 48 x 48 at 240x135 (PSNR, dB):
// 48.6 showcase, 50.6 slivers, 55.9-64.2 near-plane, huge-1e6, grazing,
// watertight, shared-edge, subpixel-plane, alpha-quads, 71.0-71.3
// closed-mesh and dense-mesh, identical on huge-1e30; edges converge fast
// enough. Not checker-plane, 37.6: point samples of its level-0 checker
// converge only as 1/N where it is minified toward the horizon, so 24 x 24
// (2.25x the time) would gain ~3.5 dB there and 48 x 48 is itself not
// converged. The report prints each scene's half-rate check so that a reader
// sees where the reference limits a row.
constexpr int kDefaultReferenceSpp = 16;

// Which reference frame the table is scored against (--reference); None
// scores nothing.
enum class ReferenceKind { Area, Rays, None };

// Scenes the default list leaves out, and why (kSamplesUsage says the same).
// z-fighting's frame is one quad filling the view in front of another: no
// edge is on screen, and what it measures is depth precision.
// random-triangles: two thirds of its 20000 triangles have their corners
// anywhere in the view (a random triangle covers 11/144 of its square on
// average), so about a thousand overlap each pixel and every reference ray
// tests them all: 92 s at 96x54 with 16 x 16 rays per pixel on 2 threads,
// ~40 minutes at the default size, against 2-12 s for each other scene.
// invalid-input: its second mesh's NaN texture coordinates, which the engine
// drops with their triangles as the contract says, are shaded by the tracer
// into NaN pixels: the ideal frame is undefined there.
// flyover: the sequence scene; at rest it is showcase's ground, cube, ball and
// masked panel, which showcase already measures.
const char* const kLeftOutByDefault[] = {"z-fighting", "random-triangles", "invalid-input",
                                         "flyover"};

struct SamplesOptions {
  int width = 480;
  int height = 270;
  int threads = 0;
  std::optional<Isa> isa;
  int frames = 5;
  int rounds = 3;
  std::string scenes;
  std::vector<int> sampleCounts = {1, 4, 8, 16};
  int referenceSpp = kDefaultReferenceSpp;
  ReferenceKind reference = ReferenceKind::Area;
  std::string outDir = "out";
  std::optional<Filter> filter;  // unset: the scenes' samplers decide
  int maxAniso = 16;
  float lodBias = 0.0f;
  LoadOptions load;  // --allow-path, --max-memory (also each frame's)
};

std::optional<SamplesOptions> parseSamples(const std::vector<std::string>& args) {
  SamplesOptions options;
  CommandOptions parser("report samples", kSamplesUsage);
  addSizeOptions(parser, options.width, options.height);
  addThreadsOption(parser, options.threads);
  addIsaOption(parser, options.isa);
  parser.integer("--frames", options.frames, 1, 1000);
  parser.integer("--rounds", options.rounds, 1, 100);
  parser.text("--scenes", options.scenes);
  parser.value("--samples", [&options](const std::string& option, const std::string& text) {
    options.sampleCounts.clear();
    for (const std::string& entry : splitList(option, text))
      options.sampleCounts.push_back(parseSampleCount(option, entry));
    std::sort(options.sampleCounts.begin(), options.sampleCounts.end());
    options.sampleCounts.erase(
        std::unique(options.sampleCounts.begin(), options.sampleCounts.end()),
        options.sampleCounts.end());
  });
  addFilterOptions(parser, options.filter, options.maxAniso, options.lodBias);
  parser.integer("--reference-spp", options.referenceSpp, 1, 256);
  parser.choice(
      "--reference", "reference",
      {{"area", ReferenceKind::Area}, {"rays", ReferenceKind::Rays}, {"none", ReferenceKind::None}},
      options.reference);
  parser.text("--out-dir", options.outDir);
  addAllowPathOption(parser, options.load);
  addMaxMemoryOption(parser, options.load);
  if (parser.parse(args) == Parsed::HelpShown) return std::nullopt;
  if (options.threads == 0)
    options.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  return options;
}

// The SCENE arguments to measure, each checked to load before any work starts.
std::vector<std::string> chooseSamplesScenes(const SamplesOptions& options) {
  std::vector<std::string> scenes;
  if (options.scenes.empty()) {
    for (const std::string& name : builtinSceneNames())
      if (std::find(std::begin(kLeftOutByDefault), std::end(kLeftOutByDefault), name) ==
          std::end(kLeftOutByDefault))
        scenes.push_back(kBuiltinScenePrefix + name);
    return scenes;
  }
  for (const std::string& entry : splitList("--scenes", options.scenes)) {
    const bool builtin = entry.rfind(kBuiltinScenePrefix, 0) == 0;
    if (!builtin && !endsWithIgnoringCase(entry, ".gltf") && !endsWithIgnoringCase(entry, ".glb"))
      throw UsageError("--scenes: '" + entry + "' is neither builtin:NAME nor a .gltf/.glb file");
    scenes.push_back(entry);
  }
  return scenes;
}

// One way of rendering a scene; shading is irrelevant at one sample.
struct Configuration {
  int samples = 1;
  ShadingRate rate = ShadingRate::Pixel;
  const char* rateName() const {
    return samples == 1 ? "any" : rate == ShadingRate::Pixel ? "pixel" : "sample";
  }
};

std::vector<Configuration> configurations(const std::vector<int>& sampleCounts) {
  std::vector<Configuration> list;
  for (const int samples : sampleCounts) {
    list.push_back({samples, ShadingRate::Pixel});
    if (samples > 1) list.push_back({samples, ShadingRate::Sample});
  }
  return list;
}

struct Measured {
  Configuration configuration;
  std::vector<double> runMs;  // each round's median frame time
  ImageDifference difference;
  // Its time over the 1-sample row's, round by round: their median and its
  // bootstrap interval (setRatioToOneSample); NaN without a 1-sample row.
  double ratioToOneSample = NAN, ratioLow = NAN, ratioHigh = NAN;
  double ms() const { return summarizeFrameTimes(runMs).median; }
};

// The median over the rounds of `row`'s run over the same round's run of
// `base` (a ratio of runs close in time, where a ratio of the medians would
// take in the shared machine's drift between rounds), and from 3 rounds a
// 95% bootstrap interval of it: the 2.5th and 97.5th percentiles of the
// medians of kResamples resamples of the rounds' ratios, with replacement,
// drawn from a fixed seed so that a CSV's interval follows from its rounds.
void setRatioToOneSample(Measured& row, const Measured& base) {
  std::vector<double> ratios;
  for (std::size_t r = 0; r < row.runMs.size() && r < base.runMs.size(); ++r)
    ratios.push_back(row.runMs[r] / base.runMs[r]);
  row.ratioToOneSample = summarizeFrameTimes(ratios).median;
  if (ratios.size() < 3) return;
  constexpr int kResamples = 4000;
  std::mt19937 random(20261130u);
  std::uniform_int_distribution<std::size_t> pick(0, ratios.size() - 1);
  std::vector<double> medians, resample(ratios.size());
  for (int i = 0; i < kResamples; ++i) {
    for (double& ratio : resample) ratio = ratios[pick(random)];
    medians.push_back(summarizeFrameTimes(resample).median);
  }
  std::sort(medians.begin(), medians.end());
  row.ratioLow = medians[kResamples / 40];
  row.ratioHigh = medians[kResamples - 1 - kResamples / 40];
}

struct SamplesSceneResult {
  std::string label;
  std::size_t triangles = 0;
  double referenceSeconds = 0.0;
  double referenceCheckPsnr = NAN;  // the half-rate reference against the reference
  double exactShare = NAN;          // area reference: the share of the area integrated exactly
  // Per sample count: the tracer's own frame from exact hits and point
  // lookups at the engine's sample positions, against the reference.
  std::vector<std::pair<int, ImageDifference>> points;
  std::vector<Measured> rows;
  bool scored = true;  // against a reference (not --reference none)
};

Image imageOf(Frame frame) {
  Image image;
  image.width = frame.width;
  image.height = frame.height;
  image.rgba = std::move(frame.rgba);
  return image;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

SamplesSceneResult measureScene(const std::string& argument, const Scene& scene,
                                const SamplesOptions& options, Renderer& renderer,
                                tbb::task_arena& arena) {
  SamplesSceneResult result;
  result.label = argument;
  result.triangles = scene.triangleCount();
  const Camera camera = firstCameraOrDefault(scene);
  const bool scored = result.scored = options.reference != ReferenceKind::None;
  const auto referenceStart = std::chrono::steady_clock::now();
  std::optional<ref::ReferenceTracer> tracer;
  if (scored) tracer.emplace(scene, camera, options.width, options.height);
  // The area reference at half the rays and fewer quadrature nodes is its
  // check (below): 2 Gauss nodes against 1 (the midpoint) between breakpoints.
  const auto referenceFrame = [&](int spp, int gaussNodes, ref::ReferenceTracer::AreaStats* stats) {
    return arena.execute([&] {
      return options.reference == ReferenceKind::Rays
                 ? tracer->render(spp)
                 : tracer->renderArea({.samplesPerAxis = spp, .gaussNodes = gaussNodes}, stats);
    });
  };
  ref::ReferenceTracer::AreaStats stats;
  const Image ideal = scored ? referenceFrame(options.referenceSpp, 2, &stats) : Image{};
  result.referenceSeconds = scored ? secondsSince(referenceStart) : NAN;
  if (options.reference == ReferenceKind::Area) result.exactShare = stats.exactArea;
  // How near the truth the reference is: the PSNR of the same frame at half
  // the rays per axis (and, for the area reference, the midpoint rule
  // between breakpoints instead of 2 Gauss nodes) against it. A regular grid's errors (at edges,
  // and texture aliasing) halve per doubling with the same sign, so the difference then equals the
  // reference's own error; errors less alike make it larger. The reference's own PSNR is about this
  // or higher, and rows near it measure the reference as much as the engine.
  if (scored && options.referenceSpp >= 2) {
    const Image coarse = referenceFrame(options.referenceSpp / 2, 1, nullptr);
    result.referenceCheckPsnr = imageDifference(coarse, ideal).psnr;
  }

  // The best a sampler at those N positions resolves to without filtering
  // its textures: for untextured scenes the limit of N coverage samples.
  for (const int count : options.sampleCounts) {
    if (!scored) break;
    const SamplePattern& pattern = samplePattern(count);
    std::vector<glm::dvec2> offsets;
    for (int k = 0; k < pattern.count; ++k)
      offsets.push_back(glm::dvec2(pattern.offsets[k].x, pattern.offsets[k].y) /
                        double(kSampleUnitsPerPixel));
    const Image points = arena.execute([&] { return tracer->renderPoints(offsets); });
    result.points.push_back({count, imageDifference(points, ideal)});
  }

  RenderSettings settings;
  settings.width = options.width;
  settings.height = options.height;
  settings.frameDepth = false;  // nothing here reads depth
  settings.filter = options.filter;
  settings.maxAniso = options.maxAniso;
  settings.lodBias = options.lodBias;
  settings.maxMemory = options.load.maxMemory;
  for (const Configuration& c : configurations(options.sampleCounts)) {
    settings.samples = c.samples;
    settings.shadingRate = c.rate;
    Frame frame;
    renderer.render(scene, camera, settings, frame);  // warm-up, and the frame scored
    Measured row;
    row.configuration = c;
    if (scored) row.difference = imageDifference(imageOf(std::move(frame)), ideal);
    result.rows.push_back(row);
  }
  // Round r starts at configuration r, so no configuration always runs first
  // (after the reference) or always follows the same neighbour's caches.
  Frame frame;
  for (int round = 0; round < options.rounds; ++round)
    for (std::size_t k = 0; k < result.rows.size(); ++k) {
      Measured& row = result.rows[(k + std::size_t(round)) % result.rows.size()];
      settings.samples = row.configuration.samples;
      settings.shadingRate = row.configuration.rate;
      std::vector<double> times;
      for (int i = 0; i < options.frames; ++i) {
        const auto start = std::chrono::steady_clock::now();
        renderer.render(scene, camera, settings, frame);
        times.push_back(1000.0 * secondsSince(start));
      }
      row.runMs.push_back(summarizeFrameTimes(times).median);
    }
  const Measured& first = result.rows.front();  // the fewest samples
  if (first.configuration.samples == 1)
    for (Measured& row : result.rows) setRatioToOneSample(row, first);
  return result;
}

// "-" for a check not made, "nan" for a frame with NaN pixels.
std::string psnrText(double psnr, const char* nanText = "nan") {
  return std::isnan(psnr) ? nanText : std::isinf(psnr) ? "inf" : format("%.2f", psnr);
}

std::string ratioText(double ratio) {
  return std::isnan(ratio) ? "-" : format("%.3f", ratio);
}

// The table's "x 1 sample": the median ratio and, where there is one, its
// interval.
std::string ratioCell(const Measured& row) {
  if (std::isnan(row.ratioLow)) return ratioText(row.ratioToOneSample);
  return ratioText(row.ratioToOneSample) + " [" + format("%.2f", row.ratioLow) + ", " +
         format("%.2f", row.ratioHigh) + "]";
}

std::string tableText(const std::vector<SamplesSceneResult>& results) {
  std::ostringstream out;
  out << "| scene | samples | shading | ms/frame | x 1 sample | PSNR dB | max diff |\n"
         "|---|---:|---|---:|---:|---:|---:|\n";
  for (const SamplesSceneResult& scene : results)
    for (const Measured& row : scene.rows)
      out << "| " << scene.label << " | " << row.configuration.samples << " | "
          << row.configuration.rateName() << " | " << figures(row.ms()) << " | " << ratioCell(row)
          << " | " << (scene.scored ? psnrText(row.difference.psnr) : "-") << " | "
          << (scene.scored ? format("%.3f", row.difference.maxAbs) : "-") << " |\n";
  return out.str();
}

std::string samplesCsvText(const std::vector<SamplesSceneResult>& results) {
  std::ostringstream csv;
  csv << "scene,triangles,samples,shading,ms_per_frame,psnr_db,max_abs_diff,reference_s,"
         "reference_check_db,ms_rounds,ratio_to_1_sample,ratio_low,ratio_high\n";
  for (const SamplesSceneResult& scene : results)
    for (const Measured& row : scene.rows) {
      const bool scored = scene.scored;
      csv << scene.label << ',' << scene.triangles << ',' << row.configuration.samples << ','
          << row.configuration.rateName() << ',' << format("%.4g", row.ms()) << ','
          << (scored ? psnrText(row.difference.psnr) : "-") << ','
          << (scored ? format("%.4g", row.difference.maxAbs) : "-") << ','
          << (scored ? format("%.3g", scene.referenceSeconds) : "-") << ','
          << psnrText(scene.referenceCheckPsnr, "-") << ',' << joined(row.runMs, "%.4g") << ','
          << ratioText(row.ratioToOneSample) << ',' << ratioText(row.ratioLow) << ','
          << ratioText(row.ratioHigh) << '\n';
    }
  return csv.str();
}

// Distinct hues for up to 16 scenes (the default list has 13), repeated
// beyond (the legend and the dash pattern of the rate still tell lines apart).
const char* sceneColour(std::size_t index) {
  static const char* const kColours[] = {
      "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf",
      "#7f7f7f", "#bcbd22", "#393b79", "#637939", "#000000", "#ad494a", "#3182bd", "#e6550d"};
  return kColours[index % (sizeof kColours / sizeof kColours[0])];
}

// ms/frame (log) against PSNR: per scene one solid line (pixel rate) and one
// dashed line (sample rate), both from the 1-sample point, each point labelled
// with its sample count. An infinite PSNR (a frame equal to the reference) is
// drawn on the top edge; a NaN one (NaN pixels) is left out.
std::string samplesSvgText(const std::vector<SamplesSceneResult>& results,
                           const std::string& subtitle) {
  double msMin = 1e300, msMax = 0, psnrMin = 1e300, psnrMax = -1e300;
  for (const SamplesSceneResult& scene : results)
    for (const Measured& row : scene.rows) {
      msMin = std::min(msMin, row.ms());
      msMax = std::max(msMax, row.ms());
      if (!std::isfinite(row.difference.psnr)) continue;
      psnrMin = std::min(psnrMin, row.difference.psnr);
      psnrMax = std::max(psnrMax, row.difference.psnr);
    }
  if (psnrMin > psnrMax) psnrMin = psnrMax = 100.0;  // every frame exact
  SvgPlot plot{.x = PlotAxis::logarithmicAround(msMin, msMax, 1e-3, "ms per frame (log)"),
               .y = PlotAxis::linearAround(psnrMin, psnrMax, "PSNR against the reference (dB)")};
  plot.width = 980;
  plot.height = 640;
  plot.right = 250;  // the legend
  std::ostringstream svg;
  svg << plot.begin("quadra samples per pixel: time against error", subtitle);
  const auto pointY = [&](double psnr) {
    return std::isinf(psnr) ? plot.toY(plot.y.hi) : plot.toY(psnr);
  };
  for (std::size_t s = 0; s < results.size(); ++s) {
    const SamplesSceneResult& scene = results[s];
    for (const ShadingRate rate : {ShadingRate::Pixel, ShadingRate::Sample}) {
      std::ostringstream points;
      for (const Measured& row : scene.rows)
        if (!std::isnan(row.difference.psnr) &&
            (row.configuration.samples == 1 || row.configuration.rate == rate))
          points << plot.toX(row.ms()) << ',' << pointY(row.difference.psnr) << ' ';
      svg << "<polyline points=\"" << points.str() << "\" fill=\"none\" stroke=\"" << sceneColour(s)
          << "\" stroke-width=\"1.5\""
          << (rate == ShadingRate::Sample ? " stroke-dasharray=\"5,3\"" : "") << "><title>"
          << svgEscaped(scene.label) << ", " << (rate == ShadingRate::Pixel ? "pixel" : "sample")
          << " rate</title></polyline>\n";
    }
    for (const Measured& row : scene.rows) {
      if (std::isnan(row.difference.psnr)) continue;  // NaN pixels: no place on the axis
      const double x = plot.toX(row.ms()), y = pointY(row.difference.psnr);
      svg << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"3\" fill=\"" << sceneColour(s)
          << "\"/>\n<text x=\"" << x + 4 << "\" y=\"" << y - 4 << "\" font-size=\"10\" fill=\""
          << sceneColour(s) << "\">" << row.configuration.samples << "</text>\n";
    }
  }
  const double legendX = plot.width - plot.right + 16;
  double legendY = plot.top + 8;
  for (std::size_t s = 0; s < results.size(); ++s, legendY += 18)
    svg << "<line x1=\"" << legendX << "\" y1=\"" << legendY << "\" x2=\"" << legendX + 24
        << "\" y2=\"" << legendY << "\" stroke=\"" << sceneColour(s)
        << "\" stroke-width=\"2\"/>\n<text x=\"" << legendX + 30 << "\" y=\"" << legendY + 4
        << "\">" << svgEscaped(results[s].label) << "</text>\n";
  legendY += 10;
  for (const bool dashed : {false, true}) {
    svg << "<line x1=\"" << legendX << "\" y1=\"" << legendY << "\" x2=\"" << legendX + 24
        << "\" y2=\"" << legendY << "\" stroke=\"black\" stroke-width=\"1.5\""
        << (dashed ? " stroke-dasharray=\"5,3\"" : "") << "/>\n<text x=\"" << legendX + 30
        << "\" y=\"" << legendY + 4 << "\">"
        << (dashed ? "sample rate (supersampling)" : "pixel rate (multisampling)") << "</text>\n";
    legendY += 18;
  }
  svg << "<text x=\"" << legendX << "\" y=\"" << legendY + 4
      << "\" fill=\"#555\">labels: samples per pixel</text>\n";
  svg << SvgPlot::end();
  return svg.str();
}

}  // namespace

int runSamplesReport(const std::vector<std::string>& args) {
  const std::optional<SamplesOptions> parsed = parseSamples(args);
  if (!parsed) return 0;
  const SamplesOptions& options = *parsed;
  const std::vector<std::string> scenes = chooseSamplesScenes(options);
  // Every scene is loaded before the first slow reference: a typo in the
  // last one should not cost the first ones' minutes.
  std::vector<Scene> loaded;
  for (const std::string& scene : scenes)
    loaded.push_back(loadSceneArgument(scene, options.load, "quadra"));
  Renderer renderer({.threads = options.threads, .isa = options.isa});  // checks --isa
  const fs::path outDir(options.outDir);
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec || !fs::is_directory(outDir))
    throw Error(options.outDir + ": cannot create the output directory");

  tbb::task_arena arena(options.threads);
  std::vector<SamplesSceneResult> results;
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    progress("report samples: scene " + std::to_string(s + 1) + "/" +
             std::to_string(scenes.size()) + " " + scenes[s]);
    results.push_back(measureScene(scenes[s], loaded[s], options, renderer, arena));
  }
  progress("");

  const bool scored = options.reference != ReferenceKind::None;
  const std::string settings =
      std::to_string(options.width) + "x" + std::to_string(options.height) + ", " +
      std::to_string(renderer.threadCount()) + " threads, isa " + isaName(renderer.isa()) +
      (scored ? ", reference " +
                    std::string(options.reference == ReferenceKind::Area ? "area integrals, else "
                                                                         : "") +
                    std::to_string(options.referenceSpp) + "x" +
                    std::to_string(options.referenceSpp) + " rays per pixel"
              : std::string(", no reference")) +
      ", filter " +
      (options.filter ? filterName(*options.filter) + std::string(" (max aniso ") +
                            std::to_string(options.maxAniso) + ")"
                      : std::string("the samplers'"));
  std::ostringstream out;
  out << "Samples per pixel at " << settings << ". ms/frame: the median over " << options.rounds
      << " rounds of each run's median of " << options.frames
      << " frames (configurations take turns); x 1 sample: the median over the rounds of a "
         "run's time over the same round's 1-sample run, in brackets a 95% bootstrap "
         "interval of that median; "
      << (scored ? "PSNR (peak 1) and max diff over R, G, B against the reference tracer's frame"
                 : "no PSNR (--reference none)")
      << ". Shading: pixel = once per pixel and visible triangle, sample = every sample; at 1 "
         "sample the two are one frame.\n\n"
      << tableText(results);
  const fs::path csvPath = outDir / "samples.csv", svgPath = outDir / "samples.svg";
  if (!scored) {
    // Nothing to plot against: the table and the CSV only. An earlier
    // scored run's plot would sit beside this CSV describing other frames.
    writeText(csvPath, samplesCsvText(results));
    std::cout << out.str() << "\nquadra wrote " << csvPath.string() << "\n";
    std::error_code ignored;
    if (fs::remove(svgPath, ignored))
      std::cout << "quadra removed " << svgPath.string() << " (an earlier run's plot)\n";
    return 0;
  }
  out << "\nReference frames: "
      << (options.reference == ReferenceKind::Area
              ? "each pixel's area integrated exactly where its visible triangles do not "
                "overlap on screen, else "
              : "")
      << options.referenceSpp << "x" << options.referenceSpp << " rays per pixel, "
      << options.threads
      << " threads. Check: the PSNR of the same frame traced at half the rays per axis "
      << (options.reference == ReferenceKind::Area
              ? "(and 1 Gauss node between breakpoints, not 2) "
              : "")
      << "against it; the reference's own PSNR is about that or higher, and rows near it "
         "measure the reference as much as quadra. Exact: the share of the frame's area "
         "integrated exactly (the rest took rays).\n\n"
         "| scene | triangles | reference s | check dB | exact % |\n|---|---:|---:|---:|---:|\n";
  for (const SamplesSceneResult& scene : results)
    out << "| " << scene.label << " | " << scene.triangles << " | "
        << format("%.1f", scene.referenceSeconds) << " | "
        << psnrText(scene.referenceCheckPsnr, "-") << " | "
        << (std::isnan(scene.exactShare) ? std::string("-")
                                         : format("%.1f", 100.0 * scene.exactShare))
        << " |\n";

  out << "\nThe reference tracer's own frame from exact hits and level-0 point lookups at "
         "the engine's N sample positions (no texture filtering), against the reference: "
         "what N point samples there resolve to at best, for untextured scenes the limit "
         "of N coverage samples.\n\n| scene | samples | points PSNR dB | max diff |\n"
         "|---|---:|---:|---:|\n";
  for (const SamplesSceneResult& scene : results)
    for (const auto& [count, difference] : scene.points)
      out << "| " << scene.label << " | " << count << " | " << psnrText(difference.psnr) << " | "
          << format("%.3f", difference.maxAbs) << " |\n";

  const std::string csv = samplesCsvText(results), svg = samplesSvgText(results, settings);
  writeText(csvPath, csv);
  writeText(svgPath, svg);
  std::cout << out.str() << "\nquadra wrote " << csvPath.string() << "\nquadra wrote "
            << svgPath.string() << "\n";
  return 0;
}

}  // namespace quadra
