// `quadra report stability`: every hard case of numerical stability (the
// builtin: scenes of lab/scene/hard_case_scenes.h, plus sweeps), rendered by the
// engine and checked against the double-precision references of
// lab/reference: the exact integer rasterizer for coverage, ray-plane hits
// for texture coordinates and their derivatives, counts for what must be
// dropped, and bit comparisons for determinism. Prints one table row per
// check (case, check, figure, bound, pass/fail); exits 1 if any check fails.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "api/renderer.h"
#include "cli_options.h"
#include "commands.h"
#include "core/error.h"
#include "lab/reference/reference_raster.h"
#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"
#include "lab/scene/hard_case_scenes.h"

namespace quadra {
namespace {

constexpr const char* kStabilityUsage =
    R"(usage: quadra report stability [--threads N] [--isa auto|scalar|sse2|avx2|avx512]
                              [--sections LIST]
  --threads N  threads for the frames (default: all cores; the determinism
               and random-triangle checks also use 1, 2, 3 and 8)
  --isa ISA    kernel path for the frames (default: the best the CPU has)
  --sections LIST  only these, comma-separated (default: all, in this order):
               perspective, coverage, random-triangles, samples,
               samples-random-triangles, invalid-input, z-fighting, lod,
               determinism
Prints: case, check, measured figure, bound, pass/fail. Exit status 1 when
any check fails. The cases are builtin: scenes (quadra render builtin:NAME).
)";

// Perspective scenes are drawn at this size; pixel-exact ones at 256 x 256.
constexpr int kWidth = 256, kHeight = 160;

enum class Bound : std::uint8_t { AtMost, AtLeast, Equal, Info };

struct Row {
  std::string scene, check;
  double figure = 0.0;
  Bound kind = Bound::Info;
  double bound = 0.0;
  bool pass() const {
    switch (kind) {
      case Bound::AtMost:
        return figure <= bound;
      case Bound::AtLeast:
        return figure >= bound;
      case Bound::Equal:
        return figure == bound;
      default:
        return true;
    }
  }
};

struct Context {
  int threads = 0;
  std::optional<Isa> isa;
  std::vector<Row> rows;

  void add(const std::string& scene, const std::string& check, double figure, Bound kind,
           double bound) {
    rows.push_back({scene, check, figure, kind, bound});
  }

  Frame render(const Scene& scene, int width, int height, DebugView view,
               FrameStats* stats = nullptr, std::optional<int> threadCount = std::nullopt,
               std::optional<Isa> path = std::nullopt, DepthMode depth = DepthMode::Standard,
               DerivativeMode derivatives = DerivativeMode::Analytic, int samples = 1) const {
    RendererConfig config;
    config.threads = threadCount.value_or(threads);
    config.isa = path ? path : isa;
    Renderer renderer(config);
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.debugView = view;
    settings.depth = depth;
    settings.derivatives = derivatives;
    settings.samples = samples;
    Frame frame;
    const FrameStats s = renderer.render(scene, scene.cameras.at(0), settings, frame);
    if (stats) *stats = s;
    return frame;
  }
};

Scene hardCase(const std::string& name) {
  Scene scene;
  QUADRA_CHECK(makeHardCaseScene(name, scene));
  return scene;
}

const float* pixelOf(const Frame& frame, int x, int y) {
  return &frame.rgba[(std::size_t(y) * std::size_t(frame.width) + std::size_t(x)) * 4];
}

// The exact reference rasterizer's view of a scene through its camera.
// (With several samples per pixel, each pixel's count is its covered samples.)
struct ReferenceCoverage {
  std::vector<ref::ProjectedTriangle> projected;
  ref::CoverageImage image;
  int samples;

  ReferenceCoverage(const Scene& scene, int width, int height, int samplesPerPixel = 1)
      : projected(ref::projectScene(scene, scene.cameras[0], width, height)),
        image(
            ref::rasterizeCoverage(ref::gridTriangles(projected), width, height, samplesPerPixel)),
        samples(samplesPerPixel) {}
};

// Pixels whose coverage count differs from the exact reference rasterizer's,
// not counting those within `margin` px of a reference edge (0: count all).
// A perspective vertex's window position comes from the engine's float clip
// coordinates, so it may snap one 1/256 grid unit away from the double
// reference's: that moves an edge by at most sqrt(2)/256 px < 1/128 px. With
// several samples the engine's pixel is the mean of its samples' counts, and
// the margin grows by how far a sample lies from the centre (at most
// sqrt(2)/2 px).
int coverageMismatches(const Context& ctx, const Scene& scene, const ReferenceCoverage& expected,
                       double margin, std::optional<int> threads = std::nullopt) {
  const int width = expected.image.width, height = expected.image.height;
  const Frame frame =
      ctx.render(scene, width, height, DebugView::CoverageCount, nullptr, threads, std::nullopt,
                 DepthMode::Standard, DerivativeMode::Analytic, expected.samples);
  const double reach = margin == 0.0 || expected.samples == 1 ? 0.0 : 0.7072;
  int mismatches = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (pixelOf(frame, x, y)[0] * float(expected.samples) != float(expected.image.at(x, y)) &&
          (margin == 0.0 ||
           ref::distanceToEdges(expected.projected, {x + 0.5, y + 0.5}) > margin + reach))
        ++mismatches;
  return mismatches;
}

double maxAbs(const glm::dvec2& v) {
  return std::max(std::fabs(v.x), std::fabs(v.y));
}

// TEXCOORD_0 at pixel centres against the exact ray-plane value of the
// nearest hit, at pixels farther than 1/32 px from every reference edge (a
// clipped polygon's edges may sit that far from exact arithmetic's). Two
// figures: the error relative to max(1, |uv|), i.e. in float ulps of the
// value the sampler gets; and the error in pixels of screen motion, |uv
// error| / |uv change per pixel|, the shift a user sees, over the pixels
// where uv moves at least 2^-14 per pixel (elsewhere the texture is
// magnified so much, 1e30 units across on huge-1e30, that a float uv cannot
// say where in the pixel it is and the relative figure is the one that means
// something).
struct TexCoordError {
  double relative = 0.0;  // max |uv - exact| / max(1, |exact|)
  double shift = 0.0;     // max |uv - exact| / (uv change per pixel), in px
  int compared = 0, shiftCompared = 0;
};

TexCoordError texCoordError(const Context& ctx, const Scene& scene) {
  const Frame frame = ctx.render(scene, kWidth, kHeight, DebugView::TexCoord);
  const auto projected = ref::projectScene(scene, scene.cameras[0], kWidth, kHeight);
  const ref::ReferenceTracer tracer(scene, scene.cameras[0], kWidth, kHeight);
  TexCoordError result;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const glm::dvec2 at(x + 0.5, y + 0.5);
      const std::optional<ref::TracerHit> hit = tracer.nearestHit(at);
      if (!hit || pixelOf(frame, x, y)[3] == 0.0f) continue;
      if (ref::distanceToEdges(projected, at) <= 1.0 / 32) continue;
      const auto uvAt = [&](const glm::dvec2& p) {
        return tracer.planeTexCoord(*hit, tracer.primaryRay(p), 0);
      };
      const glm::dvec2 got(pixelOf(frame, x, y)[0], pixelOf(frame, x, y)[1]);
      const glm::dvec2 exact = uvAt(at);
      const double error = maxAbs(got - exact);
      const double scale = std::max(1.0, maxAbs(exact));
      result.relative = std::max(result.relative, error / scale);
      ++result.compared;
      const double perPixel =
          std::max(maxAbs(uvAt(at + glm::dvec2(0.5, 0)) - uvAt(at - glm::dvec2(0.5, 0))),
                   maxAbs(uvAt(at + glm::dvec2(0, 0.5)) - uvAt(at - glm::dvec2(0, 0.5))));
      if (perPixel < 0x1p-14 * scale) continue;
      result.shift = std::max(result.shift, error / perPixel);
      ++result.shiftCompared;
    }
  return result;
}

void perspectiveCase(Context& ctx, const std::string& name) {
  const Scene scene = hardCase(name);
  ctx.add(name, "pixels != reference coverage, > 1/128 px from an edge",
          coverageMismatches(ctx, scene, ReferenceCoverage(scene, kWidth, kHeight), 1.0 / 128),
          Bound::Equal, 0);
  const TexCoordError uv = texCoordError(ctx, scene);
  ctx.add(name, "pixels with uv compared", uv.compared, Bound::AtLeast, 1000);
  ctx.add(name, "uv error at pixel centres / max(1, |uv|)", uv.relative, Bound::AtMost, 0x1p-20);
  ctx.add(name, "pixels where uv moves >= 2^-14 per px", uv.shiftCompared, Bound::AtLeast, 1000);
  ctx.add(name, "uv error at pixel centres (px of screen motion)", uv.shift, Bound::AtMost,
          1.0 / 1024);
}

void pixelExactCoverage(Context& ctx, const std::string& name) {
  const Scene scene = hardCase(name);
  ctx.add(name, "pixels != reference coverage (all pixels)",
          coverageMismatches(ctx, scene, ReferenceCoverage(scene, kPixelExactSize, kPixelExactSize),
                             0.0),
          Bound::Equal, 0);
}

// Coverage per sample (4 per pixel) on the same scenes as the one-sample
// checks: the perspective hard cases away from their edges, the pixel-exact
// ones (`exact`) at every pixel.
void sampleCoverageCases(Context& ctx, bool perspective, const std::vector<std::string>& exact) {
  constexpr int kSamples = 4;
  for (const char* name : {"near-plane", "huge-1e6", "huge-1e30", "grazing"}) {
    if (!perspective) break;
    const Scene scene = hardCase(name);
    ctx.add(name, "4 samples: pixels != reference sample coverage, > 1/128 px from an edge",
            coverageMismatches(ctx, scene, ReferenceCoverage(scene, kWidth, kHeight, kSamples),
                               1.0 / 128),
            Bound::Equal, 0);
  }
  for (const std::string& name : exact) {
    const Scene scene = hardCase(name);
    ctx.add(
        name, "4 samples: pixels != reference sample coverage (all pixels)",
        coverageMismatches(
            ctx, scene, ReferenceCoverage(scene, kPixelExactSize, kPixelExactSize, kSamples), 0.0),
        Bound::Equal, 0);
  }
}

// The grid covers window x < 128 exactly once; each fan covers its rim
// polygon's interior once; nothing is covered twice.
void watertightCase(Context& ctx) {
  const std::string name = "watertight";
  const Scene scene = hardCase(name);
  pixelExactCoverage(ctx, name);
  const Frame frame = ctx.render(scene, kPixelExactSize, kPixelExactSize, DebugView::CoverageCount);
  // Fans: a centre strictly inside the rim (> 1e-9 px from it) must be covered.
  const Mesh& mesh = scene.meshes[0];
  const auto windowOf = [](const glm::vec3& p) {
    return glm::dvec2(double(p.x) + kPixelExactSize / 2, kPixelExactSize / 2 - double(p.y));
  };
  int cracks = 0, doubleHits = 0;
  for (int y = 0; y < kPixelExactSize; ++y)
    for (int x = 0; x < kPixelExactSize; ++x) {
      const float count = pixelOf(frame, x, y)[0];
      if (count >= 2.0f) ++doubleHits;
      if (count != 0.0f) continue;
      const glm::dvec2 at(x + 0.5, y + 0.5);
      bool inside = x < 128;
      // Fan triangles come after the grid's; a centre strictly inside any of
      // them, or on an edge shared by two of them, is inside the fan.
      for (std::size_t t = 0; !inside && t * 3 < mesh.indices.size(); ++t) {
        const glm::dvec2 a = windowOf(mesh.positions[mesh.indices[t * 3]]),
                         b = windowOf(mesh.positions[mesh.indices[t * 3 + 1]]),
                         c = windowOf(mesh.positions[mesh.indices[t * 3 + 2]]);
        if (a.x < 128 && b.x < 128 && c.x < 128) continue;  // grid triangle
        const auto side = [&](const glm::dvec2& p, const glm::dvec2& q) {
          return (q.x - p.x) * (at.y - p.y) - (q.y - p.y) * (at.x - p.x);
        };
        const double s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
        // Inside or on an inner edge: only the rim edge b-c may be excluded.
        const bool sameSign =
            (s0 >= 0 && s1 > 1e-9 && s2 >= 0) || (s0 <= 0 && s1 < -1e-9 && s2 <= 0);
        inside = sameSign;
      }
      if (inside) ++cracks;
    }
  ctx.add(name, "cracks: uncovered pixels inside the meshes", cracks, Bound::Equal, 0);
  ctx.add(name, "double hits: pixels covered twice", doubleHits, Bound::Equal, 0);
}

// A closed mesh is crossed an even number of times by every ray.
void closedMeshCase(Context& ctx) {
  const std::string name = "closed-mesh";
  const Frame frame = ctx.render(hardCase(name), kWidth, kHeight, DebugView::CoverageCount);
  int odd = 0, covered = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const int count = int(pixelOf(frame, x, y)[0]);
      odd += count % 2;
      covered += count > 0;
    }
  ctx.add(name, "pixels covered by the closed mesh", covered, Bound::AtLeast, 5000);
  ctx.add(name, "pixels with an odd count (crack or double hit)", odd, Bound::Equal, 0);
}

void randomTrianglesCase(Context& ctx) {
  const std::string name = "random-triangles";
  const Scene scene = hardCase(name);
  const ReferenceCoverage expected(scene, kPixelExactSize, kPixelExactSize);
  for (int threads : {1, 2, 3, 8})
    ctx.add(name,
            std::to_string(scene.triangleCount()) + " triangles, " + std::to_string(threads) +
                " threads: pixels != reference",
            coverageMismatches(ctx, scene, expected, 0.0, threads), Bound::Equal, 0);
}

void invalidInputCase(Context& ctx) {
  const std::string name = "invalid-input";
  const Scene scene = hardCase(name);
  FrameStats stats;
  const Frame frame = ctx.render(scene, kPixelExactSize, kPixelExactSize, DebugView::None, &stats);
  const std::size_t broken = scene.meshes[1].indices.size() / 3;
  // The reference sees only instance 0; its degenerate triangles cover nothing.
  Scene valid = scene;
  valid.instances.resize(1);
  const auto projected =
      ref::projectScene(valid, valid.cameras[0], kPixelExactSize, kPixelExactSize);
  const auto grid = ref::gridTriangles(projected);
  std::size_t degenerate = 0;
  for (const ref::GridTriangle& t : grid) degenerate += ref::doubleSignedArea(t) == 0;
  const ref::CoverageImage expected =
      ref::rasterizeCoverage(grid, kPixelExactSize, kPixelExactSize);
  int wrong = 0;
  for (int y = 0; y < kPixelExactSize; ++y)
    for (int x = 0; x < kPixelExactSize; ++x)
      wrong += (pixelOf(frame, x, y)[3] > 0.0f) != (expected.at(x, y) > 0);
  ctx.add(name, "NaN/Inf triangles counted as invalid", double(stats.droppedInvalid), Bound::Equal,
          double(broken));
  ctx.add(name, "degenerate triangles counted", double(stats.droppedDegenerate), Bound::Equal,
          double(degenerate));
  ctx.add(name, "pixels drawn != valid triangles' coverage", wrong, Bound::Equal, 0);
}

// Standard against reversed float depth on two quads at distance D, s apart.
void zFightingCases(Context& ctx) {
  for (const double distance : {1.0, 100.0, 1e4})
    for (const double relative : {1e-3, 1e-5}) {
      const double separation = distance * relative;
      const Scene scene = zFightingScene(distance, separation);
      char name[64];
      std::snprintf(name, sizeof name, "z-fighting D=%g s=%g", distance, separation);
      for (const DepthMode depth : {DepthMode::Standard, DepthMode::Reversed}) {
        const Frame frame =
            ctx.render(scene, 48, 48, DebugView::None, nullptr, std::nullopt, std::nullopt, depth);
        std::size_t red = 0;
        for (std::size_t i = 0; i < frame.rgba.size(); i += 4)
          red += frame.rgba[i] == 1.0f && frame.rgba[i + 1] == 0.0f;
        const double fraction = double(red) / double(48 * 48);
        if (depth == DepthMode::Standard)
          ctx.add(name, "correct pixels, standard depth", fraction, Bound::Info, 0);
        else
          ctx.add(name, "correct pixels, reversed depth", fraction, Bound::Equal, 1.0);
      }
    }
}

// Screen derivatives of uv, and the isotropic LOD of a 1024^2 texture from them.
struct Derivatives {
  double dudx, dvdx, dudy, dvdy;
  double lod() const {
    return 0.5 * std::log2(std::max(dudx * dudx + dvdx * dvdx, dudy * dudy + dvdy * dvdy) * 1024.0 *
                           1024.0);
  }
};

// The LOD that DebugView::Derivatives frames imply, against the exact one of
// the ground plane (every triangle lies on it). Returns, over covered pixels
// (nearEdgeOnly: those within 2 px of the quad's shared diagonal), the worst
// |LOD error| and, for neighbouring pixels on different triangles, the worst
// error of their LOD difference (a discontinuity the exact field has not).
struct LodErrors {
  double worst = 0.0, worstJump = 0.0;
  int pixels = 0;
};

// The exact derivatives each mode approximates: analytic ones are the plane's
// own at the pixel centre (central differences over 2^-10 px in double, whose
// error is far below float's); quad ones are finite differences of the exact
// plane uv over one pixel from the quad's top-left pixel centre.
LodErrors lodErrors(const Context& ctx, const Scene& scene, bool nearEdgeOnly,
                    DerivativeMode mode) {
  const Frame frame = ctx.render(scene, kWidth, kHeight, DebugView::Derivatives, nullptr,
                                 std::nullopt, std::nullopt, DepthMode::Standard, mode);
  const ref::ReferenceTracer tracer(scene, scene.cameras[0], kWidth, kHeight);
  const glm::dmat4 world = glm::inverse(ref::referenceViewMatrix(scene.cameras[0]));
  const auto planeUv = [&](const glm::dvec2& window) {
    const ref::Ray ray = tracer.primaryRay(window);
    const glm::dvec3 origin = glm::dvec3(world * glm::dvec4(ray.origin, 1.0));
    const glm::dvec3 direction = glm::dvec3(world * glm::dvec4(ray.direction, 0.0));
    const double t = (double(kGroundY) - origin.y) / direction.y;
    const glm::dvec3 hit = origin + t * direction;
    return glm::dvec2(hit.x / 4.0, hit.z / 4.0);
  };
  // Which triangle covers each pixel centre: the exact rasterizer's answer,
  // which for one plane of 80k triangles is also far cheaper than tracing.
  const ReferenceCoverage coverage(scene, kWidth, kHeight);
  std::vector<double> lodError(std::size_t(kWidth * kHeight), NAN);
  std::vector<int> triangleAt(std::size_t(kWidth * kHeight), -1);
  LodErrors e;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const float* p = pixelOf(frame, x, y);
      const std::size_t i = std::size_t(y * kWidth + x);
      const int covering = coverage.image.lastTriangle[i];
      if (covering < 0 || (p[0] == 0 && p[1] == 0 && p[2] == 0 && p[3] == 0)) continue;
      if (nearEdgeOnly) {
        const ref::ProjectedTriangle& t = coverage.projected[0];
        if (ref::distanceToSegment({x + 0.5, y + 0.5}, t.v[0].window, t.v[2].window) > 2.0)
          continue;
      }
      Derivatives exact;
      if (mode == DerivativeMode::Quad) {
        const glm::dvec2 origin((x & ~1) + 0.5, (y & ~1) + 0.5);
        const glm::dvec2 uv0 = planeUv(origin), uvx = planeUv(origin + glm::dvec2(1, 0)),
                         uvy = planeUv(origin + glm::dvec2(0, 1));
        exact = {uvx.x - uv0.x, uvx.y - uv0.y, uvy.x - uv0.x, uvy.y - uv0.y};
      } else {
        constexpr double h = 1.0 / 1024.0;
        const glm::dvec2 centre(x + 0.5, y + 0.5);
        const glm::dvec2 ddx =
            (planeUv(centre + glm::dvec2(h, 0)) - planeUv(centre - glm::dvec2(h, 0))) / (2 * h);
        const glm::dvec2 ddy =
            (planeUv(centre + glm::dvec2(0, h)) - planeUv(centre - glm::dvec2(0, h))) / (2 * h);
        exact = {ddx.x, ddx.y, ddy.x, ddy.y};
      }
      const Derivatives got{p[0], p[1], p[2], p[3]};
      lodError[i] = got.lod() - exact.lod();
      triangleAt[i] = coverage.projected[std::size_t(covering)].triangle;
      e.worst = std::max(e.worst, std::fabs(lodError[i]));
      ++e.pixels;
    }
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t i = std::size_t(y * kWidth + x);
      for (const std::size_t j : {i + 1, i + std::size_t(kWidth)}) {
        if (j >= lodError.size() || (j == i + 1 && x + 1 == kWidth)) continue;
        if (triangleAt[i] < 0 || triangleAt[j] < 0 || triangleAt[i] == triangleAt[j]) continue;
        e.worstJump = std::max(e.worstJump, std::fabs(lodError[i] - lodError[j]));
      }
    }
  return e;
}

void lodCases(Context& ctx) {
  for (const DerivativeMode mode : {DerivativeMode::Analytic, DerivativeMode::Quad}) {
    const bool quad = mode == DerivativeMode::Quad;
    const std::string suffix = quad ? ", quad derivatives" : "";
    const LodErrors edge = lodErrors(ctx, hardCase("shared-edge"), true, mode);
    ctx.add("shared-edge", "pixels within 2 px of the shared edge" + suffix, edge.pixels,
            Bound::AtLeast, 200);
    ctx.add("shared-edge", "LOD error near the shared edge (levels)" + suffix, edge.worst,
            Bound::AtMost, 1e-3);
    ctx.add("shared-edge", "LOD jump across the edge, beyond exact (levels)" + suffix,
            edge.worstJump, Bound::AtMost, 1e-3);
    const LodErrors tiny = lodErrors(ctx, hardCase("subpixel-plane"), false, mode);
    ctx.add("subpixel-plane",
            quad ? "LOD error, helper lanes of sub-pixel triangles (levels)" + suffix
                 : "LOD error at the pixel centres of sub-pixel triangles (levels)",
            tiny.worst, Bound::AtMost, 1e-3);
    ctx.add("subpixel-plane", "LOD jump between neighbouring triangles (levels)" + suffix,
            tiny.worstJump, Bound::AtMost, 1e-3);
  }
}

// Bitwise differences of colour and depth between two frames.
std::size_t differingValues(const Frame& a, const Frame& b) {
  std::size_t n = std::max(a.rgba.size(), b.rgba.size()) - std::min(a.rgba.size(), b.rgba.size());
  for (std::size_t i = 0; i < std::min(a.rgba.size(), b.rgba.size()); ++i)
    n += std::memcmp(&a.rgba[i], &b.rgba[i], sizeof(float)) != 0;
  for (std::size_t i = 0; i < std::min(a.depth.size(), b.depth.size()); ++i)
    n += std::memcmp(&a.depth[i], &b.depth[i], sizeof(float)) != 0;
  return n;
}

void determinismCases(Context& ctx) {
  for (const std::string name : {"showcase", "checker-plane", "huge-1e30"}) {
    const Scene scene = makeBuiltinScene(name);
    const Frame one = ctx.render(scene, 320, 180, DebugView::None, nullptr, 1, Isa::Scalar);
    std::size_t threadDiffs = 0, isaDiffs = 0;
    std::string isas = "scalar";
    for (int threads : {2, 3, 8})
      threadDiffs += differingValues(
          one, ctx.render(scene, 320, 180, DebugView::None, nullptr, threads, Isa::Scalar));
    for (const Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
      if (!isaSupported(isa)) continue;
      isas += std::string("/") + isaName(isa);
      isaDiffs +=
          differingValues(one, ctx.render(scene, 320, 180, DebugView::None, nullptr, 3, isa));
    }
    ctx.add(name, "values differing, threads 1/2/3/8", double(threadDiffs), Bound::Equal, 0);
    ctx.add(name, "values differing, " + isas, double(isaDiffs), Bound::Equal, 0);
  }
}

std::string formatFigure(double v) {
  char text[32];
  if (v == std::floor(v) && std::fabs(v) < 1e9)
    std::snprintf(text, sizeof text, "%.0f", v);
  else
    std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

std::string formatBound(const Row& row) {
  switch (row.kind) {
    case Bound::AtMost:
      return "<= " + formatFigure(row.bound);
    case Bound::AtLeast:
      return ">= " + formatFigure(row.bound);
    case Bound::Equal:
      return "= " + formatFigure(row.bound);
    default:
      return "(info)";
  }
}

}  // namespace

int runStabilityReport(const std::vector<std::string>& args) {
  Context ctx;
  CommandOptions options("report stability", kStabilityUsage);
  addThreadsOption(options, ctx.threads);
  addIsaOption(options, ctx.isa);
  std::string sectionList;
  options.text("--sections", sectionList);
  if (options.parse(args) == Parsed::HelpShown) return 0;
  supportedIsa(ctx.isa);  // fails before the first frame

  // The report's parts, in its order; each can run alone (the tests run them
  // side by side, the whole report being the suite's longest test under the
  // sanitizers).
  const std::vector<std::pair<std::string, std::function<void()>>> sections = {
      {"perspective",
       [&] {
         for (const char* name : {"near-plane", "huge-1e6", "huge-1e30", "grazing"})
           perspectiveCase(ctx, name);
       }},
      {"coverage",
       [&] {
         pixelExactCoverage(ctx, "slivers");
         watertightCase(ctx);
         closedMeshCase(ctx);
       }},
      {"random-triangles", [&] { randomTrianglesCase(ctx); }},
      {"samples", [&] { sampleCoverageCases(ctx, true, {"slivers"}); }},
      {"samples-random-triangles", [&] { sampleCoverageCases(ctx, false, {"random-triangles"}); }},
      {"invalid-input", [&] { invalidInputCase(ctx); }},
      {"z-fighting", [&] { zFightingCases(ctx); }},
      {"lod", [&] { lodCases(ctx); }},
      {"determinism", [&] { determinismCases(ctx); }},
  };
  std::vector<std::string> chosen;
  for (const auto& section : sections) chosen.push_back(section.first);
  if (!sectionList.empty()) {
    chosen = splitList("--sections", sectionList);
    for (const std::string& name : chosen) {
      const bool known = std::any_of(sections.begin(), sections.end(),
                                     [&](const auto& section) { return section.first == name; });
      if (known) continue;
      std::string names;
      for (const auto& section : sections) names += (names.empty() ? "" : ", ") + section.first;
      throw UsageError("--sections: unknown section '" + name + "' (" + names + ")" +
                       didYouMean(name, names));
    }
  }
  for (const auto& section : sections)
    if (std::find(chosen.begin(), chosen.end(), section.first) != chosen.end()) section.second();

  int failed = 0;
  std::printf("%-26s %-74s %12s %10s  %s\n", "case", "check", "figure", "bound", "result");
  for (const Row& row : ctx.rows) {
    failed += !row.pass();
    std::printf("%-26s %-74s %12s %10s  %s\n", row.scene.c_str(), row.check.c_str(),
                formatFigure(row.figure).c_str(), formatBound(row).c_str(),
                row.kind == Bound::Info ? "-"
                : row.pass()            ? "pass"
                                        : "FAIL");
  }
  std::printf("quadra stability checks=%zu failed=%d\n", ctx.rows.size(), failed);
  return failed == 0 ? 0 : 1;
}

}  // namespace quadra
