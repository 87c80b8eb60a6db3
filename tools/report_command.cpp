// quadra-report, the program `quadra report SUBJECT` runs (quadra_main.cpp):
// its entry point and choice of subject, and `quadra report textures`: every
// filter's speed against its error. For each test texture (generated in code,
// plus --texture FILE) it draws a seeded footprint set, integrates the ground
// truth (DESIGN.md "Accuracy"), runs each filter over the same footprints,
// and prints a markdown table; it writes DIR/textures.csv (every figure, per
// scale and anisotropy bucket) and DIR/textures.svg (log-log ns/lookup
// against RMSE with the Pareto front).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "core/error.h"
#include "core/parallel.h"
#include "io/image_io.h"
#include "lab/texture/footprints.h"
#include "lab/texture/ground_truth.h"
#include "lab/texture/test_textures.h"
#include "lab/texture/texture_error.h"
#include "oiio_reference.h"
#include "report_output.h"
#include "report_subjects.h"
#include "svg_plot.h"
#include "texture/texture_sampler.h"

namespace quadra {
namespace {

constexpr const char* kReportUsage =
    R"(usage: quadra report textures [--size N] [--lookups N] [--seed S] [--threads N] [--isa ISA]
                              [--aniso N] [--texture FILE.png|FILE.jpg|FILE.exr] [--out-dir DIR]
                              [--oiio-peer FILE|none]
  --size N       generated textures are N x N (default 512)
  --lookups N    footprints per texture (default 4096)
  --seed S       footprint set and noise seed (default 1)
  --threads N    threads for the ground truth and the error pass (default: all cores);
                 ns/lookup is always timed on one thread
  --isa ISA      auto|scalar|sse2|avx2|avx512 (default auto)
  --aniso N      max anisotropy of the aniso filter (default 16)
  --texture FILE also measure on this texture (PNG and JPEG read as sRGB, EXR as linear)
  --out-dir DIR  where textures.csv and textures.svg go (default out)
  --oiio-peer FILE|none
                 the OpenImageIO module measured beside quadra's filters (default:
                 quadra_oiio_peer.so beside quadra, or in the install's lib/quadra);
                 none: quadra's filters only
Textures are sampled with repeat wrapping. Error: RMSE and max abs over R, G, B
against the average of the bilinear level-0 texture over each pixel footprint.
)";

struct ReportOptions {
  int size = 512;
  int lookups = 4096;
  std::uint64_t seed = 1;
  int threads = 0;
  std::optional<Isa> isa;
  int maxAniso = 16;
  std::string texturePath;
  std::string outDir = "out";
  std::string oiioPeer;  // empty: the default places; "none": not measured
};

// nullopt: --help printed the usage.
std::optional<ReportOptions> parseReport(const std::vector<std::string>& args) {
  ReportOptions report;
  CommandOptions options("report textures", kReportUsage);
  options.integer("--size", report.size, 1, 8192);
  options.integer("--lookups", report.lookups, 36, 1 << 24);
  addSeedOption(options, report.seed);
  addThreadsOption(options, report.threads);
  addAnisoOption(options, report.maxAniso);
  options.text("--texture", report.texturePath);
  options.text("--out-dir", report.outDir);
  options.text("--oiio-peer", report.oiioPeer);
  addIsaOption(options, report.isa);
  if (options.parse(args) == Parsed::HelpShown) return std::nullopt;
  return report;
}

struct TestTexture {
  std::string name;
  std::shared_ptr<const Image> image;
};

std::vector<TestTexture> makeTestTextures(const ReportOptions& options) {
  const int n = options.size;
  std::vector<TestTexture> textures = {
      {"checker", std::make_shared<Image>(makeCheckerTexture(n, n, 2))},
      {"zone-plate", std::make_shared<Image>(makeZonePlateTexture(n, n))},
      {"noise", std::make_shared<Image>(makeValueNoiseTexture(n, n, options.seed))},
      {"smooth", std::make_shared<Image>(makeSmoothNoiseTexture(n, n, options.seed))},
  };
  if (!options.texturePath.empty()) {
    const std::string stem = std::filesystem::path(options.texturePath).stem().string();
    textures.push_back({stem, std::make_shared<Image>(readImage(options.texturePath))});
  }
  return textures;
}

struct FilterRow {
  Filter filter;          // quadra's filter, unless external
  bool external = false;  // another library's lookups (OpenImageIO), same footprints
  std::string label;
  std::vector<FilterError> perTexture;
  std::vector<double> nsPerTexture;
  ErrorStats pooled;  // over every texture's lookups
  std::array<ErrorStats, kScaleBuckets> pooledScale;
  std::array<ErrorStats, kAnisoBuckets> pooledAniso;
  double ns = 0.0;  // mean over textures
};

void merge(ErrorStats& into, const ErrorStats& from) {
  into.lookups += from.lookups;
  into.sumSquared += from.sumSquared;
  into.maxAbs = std::max(into.maxAbs, from.maxAbs);
}

std::string csvText(const std::vector<TestTexture>& textures, const std::vector<FilterRow>& rows) {
  std::ostringstream csv;
  csv << "texture,filter,bucket_kind,bucket,lookups,rmse,max_abs,ns_per_lookup\n";
  const auto line = [&](const std::string& texture, const FilterRow& row, const char* kind,
                        const std::string& bucket, const ErrorStats& stats, double ns) {
    csv << texture << ',' << row.label << ',' << kind << ',' << bucket << ',' << stats.lookups
        << ',' << format("%.6g", stats.rmse()) << ',' << format("%.6g", stats.maxAbs) << ','
        << format("%.4g", ns) << '\n';
  };
  for (const FilterRow& row : rows) {
    for (std::size_t t = 0; t < textures.size(); ++t) {
      const FilterError& e = row.perTexture[t];
      const double ns = row.nsPerTexture[t];
      line(textures[t].name, row, "all", "all", e.overall, ns);
      for (int b = 0; b < kScaleBuckets; ++b)
        line(textures[t].name, row, "scale", scaleBucketName(b), e.perScale[std::size_t(b)], ns);
      for (int b = 0; b < kAnisoBuckets; ++b)
        line(textures[t].name, row, "aniso", anisoBucketName(b), e.perAniso[std::size_t(b)], ns);
    }
    line("all", row, "all", "all", row.pooled, row.ns);
    for (int b = 0; b < kScaleBuckets; ++b)
      line("all", row, "scale", scaleBucketName(b), row.pooledScale[std::size_t(b)], row.ns);
    for (int b = 0; b < kAnisoBuckets; ++b)
      line("all", row, "aniso", anisoBucketName(b), row.pooledAniso[std::size_t(b)], row.ns);
  }
  return csv.str();
}

// Log-log scatter of pooled ns/lookup (x) against pooled RMSE (y), one labelled
// marker per filter; the Pareto front (no other filter is both faster and
// more accurate) is drawn as a dashed staircase through filled markers.
std::string svgText(const std::vector<FilterRow>& rows, const std::string& subtitle) {
  double xMin = 1e300, xMax = 0, yMin = 1e300, yMax = 0;
  for (const FilterRow& row : rows) {
    xMin = std::min(xMin, row.ns);
    xMax = std::max(xMax, row.ns);
    yMin = std::min(yMin, row.pooled.rmse());
    yMax = std::max(yMax, row.pooled.rmse());
  }
  const SvgPlot plot{
      .x = PlotAxis::logarithmicAround(xMin, xMax, 1e-3, "ns per lookup (one thread, log)"),
      .y = PlotAxis::logarithmicAround(yMin, yMax, 1e-6, "RMSE against the box ideal (log)")};
  const double width = plot.width, right = plot.right, top = plot.top;
  const auto px = [&](double ns) { return plot.toX(ns); };
  const auto py = [&](double rmse) { return plot.toY(rmse); };
  std::ostringstream svg;
  svg << plot.begin("quadra texture filters: speed against error", subtitle);

  std::vector<std::size_t> order(rows.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return rows[a].ns < rows[b].ns ||
           (rows[a].ns == rows[b].ns && rows[a].pooled.rmse() < rows[b].pooled.rmse());
  });
  std::vector<bool> onFront(rows.size(), false);
  std::ostringstream staircase;  // each front point: down from the previous best, then the point
  double best = 1e300;
  for (const std::size_t i : order) {
    const double rmse = rows[i].pooled.rmse();
    if (rmse < best) {
      onFront[i] = true;
      const double x = px(rows[i].ns);
      staircase << x << ',' << py(best < 1e299 ? best : rmse) << ' ' << x << ',' << py(rmse) << ' ';
      best = rmse;
    }
  }
  svg << "<polyline points=\"" << staircase.str()
      << "\" fill=\"none\" stroke=\"#c33\" stroke-width=\"1.5\" stroke-dasharray=\"5,4\"/>\n";
  // Labels go right of their marker, moved below or above when they would
  // overlap one already placed (about 7 px per character at this font size).
  struct Box {
    double x0, y0, x1, y1;
  };
  std::vector<Box> placed;
  for (const std::size_t i : order) {
    const double x = px(rows[i].ns), y = py(rows[i].pooled.rmse());
    const std::string label = rows[i].label + " (" + format("%.3g", rows[i].ns) + " ns, " +
                              format("%.3g", rows[i].pooled.rmse()) + ")";
    const double labelWidth = 7.0 * double(label.size());
    // Near the right edge the label goes left of the marker instead.
    const bool leftSide = x + 9 + labelWidth > width - right;
    const double labelX = leftSide ? x - 9 - labelWidth : x + 9;
    double labelY = y - 8;
    for (const double candidate : {y - 8, y + 20, y - 24, y + 36}) {
      labelY = candidate;
      const Box box{labelX, candidate - 13, labelX + labelWidth, candidate + 3};
      const bool clear = std::none_of(placed.begin(), placed.end(), [&](const Box& b) {
        return box.x0 < b.x1 && b.x0 < box.x1 && box.y0 < b.y1 && b.y0 < box.y1;
      });
      if (clear) break;
    }
    placed.push_back({labelX, labelY - 13, labelX + labelWidth, labelY + 3});
    svg << "<circle cx=\"" << x << "\" cy=\"" << y
        << "\" r=\"6\" stroke=\"#c33\" stroke-width=\"2\""
        << " fill=\"" << (onFront[i] ? "#c33" : "white") << "\"/>\n"
        << "<text x=\"" << labelX << "\" y=\"" << labelY << "\">" << label << "</text>\n";
  }
  svg << "<text x=\"" << width - right - 6 << "\" y=\"" << top + 16
      << "\" text-anchor=\"end\" fill=\"#c33\">filled + dashed: Pareto front</text>\n"
      << SvgPlot::end();
  return svg.str();
}

int runTexturesReport(const std::vector<std::string>& rest) {
  const std::optional<ReportOptions> parsed = parseReport(rest);
  if (!parsed) return 0;
  const ReportOptions& options = *parsed;
  const Isa isa = supportedIsa(options.isa);
  const std::filesystem::path outDir(options.outDir);
  std::error_code ec;
  std::filesystem::create_directories(outDir, ec);
  if (ec || !std::filesystem::is_directory(outDir))
    throw Error(options.outDir + ": cannot create the output directory");

  const Executor executor(options.threads);
  const std::vector<TestTexture> textures = makeTestTextures(options);
  std::vector<FilterRow> rows;
  for (const Filter f : kEveryFilter) {
    FilterRow row;
    row.filter = f;
    row.label = f == Filter::Anisotropic
                    ? std::string(filterName(f)) + "-" + std::to_string(options.maxAniso)
                    : filterName(f);
    rows.push_back(row);
  }

  // OpenImageIO's module is loaded here, by the one report that uses it.
  std::string externalNote;
  std::optional<OiioPeer> oiio;
  if (options.oiioPeer == "none") {
    externalNote = "OpenImageIO: not measured (--oiio-peer none).\n";
  } else {
    std::string whyNot;
    oiio = loadOiioPeer(options.oiioPeer, whyNot);
    if (!oiio) externalNote = "OpenImageIO: not measured: " + whyNot + ".\n";
  }
  if (oiio) {
    for (const std::string& label : OiioTexture::labels(options.maxAniso)) {
      FilterRow row;
      row.external = true;
      row.label = label;
      rows.push_back(row);
    }
    externalNote =
        std::string(oiio->table->name) + " " + oiio->table->version +
        " TextureSystem: the same footprints, one texture() call per lookup, a float texture "
        "made by make_texture (64x64 tiles, box mips, periodic), bilinear interpolation.\n";
  }

  SamplerState state;  // repeat: footprints cross the wrap seams
  const GroundTruthOptions truthOptions;
  std::ostringstream notes;
  for (const TestTexture& texture : textures) {
    const auto start = std::chrono::steady_clock::now();
    const FootprintSet footprints = makeFootprintSet({.count = std::size_t(options.lookups),
                                                      .seed = options.seed,
                                                      .textureWidth = texture.image->width,
                                                      .textureHeight = texture.image->height});
    const BilinearReference reference(*texture.image, state);
    const GroundTruthSet truth =
        groundTruthSet(reference, footprints.footprints(), truthOptions, executor);
    const double truthSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    notes << "- " << texture.name << " (" << texture.image->width << "x" << texture.image->height
          << "): ground truth converged (last doubling moved it <= "
          << format("%g", 0.25 * truthOptions.tolerance) << ") for " << truth.converged << " of "
          << footprints.size() << " footprints; residual RMS " << format("%.2g", truth.rmsChange)
          << ", largest " << format("%.2g", truth.maxChange) << ", largest grid "
          << truth.maxSamples << " samples, " << format("%.1f", truthSeconds) << " s\n";
    const Texture sampled(texture.image, state);
    // One lookup function per row, in row order: quadra's samplers, and the
    // external rows' lookups in the order their labels were given.
    std::vector<BatchLookup> external;
    std::optional<OiioTexture> oiioTexture;
    if (oiio) {
      oiioTexture.emplace(*oiio, *texture.image, outDir / ("oiio-" + texture.name + ".exr"),
                          options.maxAniso);
      external = oiioTexture->lookups();
    }
    std::vector<std::unique_ptr<TextureSampler>> samplers(rows.size());
    std::vector<BatchLookup> timed;
    for (std::size_t f = 0, nextExternal = 0; f < rows.size(); ++f) {
      if (rows[f].external) {
        timed.push_back(external.at(nextExternal++));
        continue;
      }
      samplers[f] = std::make_unique<TextureSampler>(
          sampled, FilterSettings(rows[f].filter, options.maxAniso), isa);
      timed.push_back(batchLookupOf(*samplers[f]));
    }
    const std::vector<double> ns = timeLookupsInterleavedNs(timed, footprints);
    for (std::size_t f = 0; f < rows.size(); ++f) {
      FilterRow& row = rows[f];
      FilterError error;
      if (row.external) {
        std::vector<float> values(footprints.size() * 4);
        timed[f](footprints.batch(), 0, footprints.size(), values.data());
        error = errorOfValues(values, footprints, truth.rgba);
      } else {
        error = measureFilterError(*samplers[f], footprints, truth.rgba, executor);
      }
      row.perTexture.push_back(error);
      row.nsPerTexture.push_back(ns[f]);
      merge(row.pooled, error.overall);
      for (std::size_t b = 0; b < kScaleBuckets; ++b) merge(row.pooledScale[b], error.perScale[b]);
      for (std::size_t b = 0; b < kAnisoBuckets; ++b) merge(row.pooledAniso[b], error.perAniso[b]);
    }
  }
  for (FilterRow& row : rows) {
    for (const double ns : row.nsPerTexture) row.ns += ns;
    row.ns /= double(row.nsPerTexture.size());
  }

  std::ostringstream out;
  const std::string settings = std::to_string(options.lookups) + " footprints per texture, seed " +
                               std::to_string(options.seed) + ", isa " + isaName(isa) +
                               ", repeat wrap";
  out << "Texture filters, " << settings << ". ns/lookup: median of 5 timed runs on one thread, "
      << "filters interleaved "
      << "(mean over textures); RMSE / max over R,G,B against the box-filtered bilinear level "
         "0.\n\n";
  out << "| filter | ns/lookup | RMSE | max |";
  for (const TestTexture& t : textures) out << ' ' << t.name << " RMSE |";
  out << "\n|---|---:|---:|---:|";
  for (std::size_t t = 0; t < textures.size(); ++t) out << "---:|";
  out << '\n';
  for (const FilterRow& row : rows) {
    out << "| " << row.label << " | " << format("%.1f", row.ns) << " | "
        << format("%.4f", row.pooled.rmse()) << " | " << format("%.3f", row.pooled.maxAbs) << " |";
    for (const FilterError& e : row.perTexture)
      out << ' ' << format("%.4f", e.overall.rmse()) << " |";
    out << '\n';
  }
  out << "\nRMSE per scale bucket (major axis, texels per pixel), all textures:\n\n| filter |";
  for (int b = 0; b < kScaleBuckets; ++b) out << ' ' << scaleBucketName(b) << " |";
  out << "\n|---|";
  for (int b = 0; b < kScaleBuckets; ++b) out << "---:|";
  out << '\n';
  for (const FilterRow& row : rows) {
    out << "| " << row.label << " |";
    for (const ErrorStats& s : row.pooledScale) out << ' ' << format("%.4f", s.rmse()) << " |";
    out << '\n';
  }
  out << "\nRMSE per anisotropy bucket (major/minor), all textures:\n\n| filter |";
  for (int b = 0; b < kAnisoBuckets; ++b) out << ' ' << anisoBucketName(b) << " |";
  out << "\n|---|";
  for (int b = 0; b < kAnisoBuckets; ++b) out << "---:|";
  out << '\n';
  for (const FilterRow& row : rows) {
    out << "| " << row.label << " |";
    for (const ErrorStats& s : row.pooledAniso) out << ' ' << format("%.4f", s.rmse()) << " |";
    out << '\n';
  }
  out << "\n" << externalNote << "\nGround truth:\n" << notes.str();

  const std::filesystem::path csvPath = outDir / "textures.csv", svgPath = outDir / "textures.svg";
  writeText(csvPath, csvText(textures, rows));
  writeText(svgPath, svgText(rows, settings));
  std::cout << out.str() << "\nquadra wrote " << csvPath.string() << "\nquadra wrote "
            << svgPath.string() << "\n";
  return 0;
}

}  // namespace

int runReport(const std::vector<std::string>& args) {
  const std::string subject = args.empty() ? "" : args[0];
  const std::vector<std::string> rest(args.begin() + (args.empty() ? 0 : 1), args.end());
  if (subject == "textures") return runTexturesReport(rest);
  if (subject == "sat-precision") return runSatPrecisionReport(rest);
  if (subject == "stability") return runStabilityReport(rest);
  if (subject == "frames") return runFramesReport(rest);
  if (subject == "samples") return runSamplesReport(rest);
  if (subject == "lighting") return runLightingReport(rest);
  if (subject == "--help" || subject == "-h") {
    std::cout << "usage: quadra report SUBJECT [options]\nsubjects:\n" +
                     summaryLines(reportSubjects()) +
                     "'quadra report SUBJECT --help' prints a subject's options.\n";
    return 0;
  }
  const std::string expected =
      "report: expected a subject, 'textures', 'sat-precision', 'stability', 'frames', "
      "'samples' or 'lighting'";
  if (subject.empty() || subject.rfind("--", 0) == 0)
    throw UsageError(expected + " (see quadra report --help)");
  std::vector<std::string> names;
  for (const auto& known : reportSubjects()) names.push_back(known.first);
  const std::string suggestion = didYouMean(subject, names);
  throw UsageError("report: unknown subject '" + subject + "' " +
                   (suggestion.empty() ? "(see quadra report --help)" : suggestion.substr(1)));
}

}  // namespace quadra

// `quadra report ARGS` replaces itself with `quadra-report ARGS`, so the
// messages name quadra, as every other command's do.
int main(int argc, char** argv) {
  return quadra::runMain("quadra", argc, argv, quadra::runReport);
}
