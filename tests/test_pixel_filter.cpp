// The wide pixel filter (tile/pixel_filter.h) and the coverage channel against
// independent double-precision oracles: flat-coloured triangles on the
// pixel-exact orthographic view, whose every sample's colour and coverage
// follow from the reference rasterizer's per-sample coverage, filtered here
// with the Blackman–Harris window written out again from its definition.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "api/renderer.h"
#include "lab/reference/reference_raster.h"
#include "lab/scene/hard_case_scenes.h"
#include "render_helpers.h"

namespace quadra {
namespace {

constexpr int kSize = kPixelExactSize;  // 256: a 4x4 grid of 64 px tiles
using WindowTriangle = std::array<glm::dvec2, 3>;

struct ColouredTriangle {
  WindowTriangle at;
  glm::vec4 colour;  // opaque, constant over the triangle
};

// One unlit mesh with a colour per triangle, drawn in order at one depth.
Scene flatScene(const std::vector<ColouredTriangle>& triangles) {
  Mesh mesh;
  for (const ColouredTriangle& t : triangles)
    for (const glm::dvec2& p : t.at) {
      mesh.indices.push_back(std::uint32_t(mesh.positions.size()));
      mesh.positions.push_back(worldFromWindow(p.x, p.y));
      mesh.colors.push_back(t.colour);
    }
  return doubleSidedMeshScene(std::move(mesh));
}

// Per sample (pixel-major), the colour of the first triangle to hold it
// (depth LESS at one depth keeps the first), or 0 where none does: what
// every engine sample must hold, from the reference's exact coverage.
struct ReferenceSamples {
  int samples = 1;
  std::vector<glm::dvec4> colour;
  std::vector<double> covered;
};

ReferenceSamples referenceSamples(const Scene& scene, int samples) {
  const auto grid = ref::gridTriangles(ref::projectScene(scene, pixelExactCamera(), kSize, kSize));
  ReferenceSamples r;
  r.samples = samples;
  r.colour.assign(std::size_t(kSize) * kSize * samples, glm::dvec4(0.0));
  r.covered.assign(r.colour.size(), 0.0);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (int k = 0; k < samples; ++k)
        for (std::size_t i = 0; i < grid.size(); ++i)
          if (ref::coversPoint(grid[i], ref::samplePoint(x, y, k, samples))) {
            const std::size_t s = (std::size_t(y) * kSize + x) * samples + k;
            r.colour[s] = glm::dvec4(scene.meshes[0].colors[3 * i]);
            r.covered[s] = 1.0;
            break;
          }
  return r;
}

// The Blackman–Harris window of radius 2 px, from its textbook coefficients
// (the 4-term window over [-2, 2], 1 at the centre).
double blackmanHarrisWindow(double x) {
  if (std::abs(x) >= 2.0) return 0.0;
  const double t = (x + 2.0) / 4.0;  // 0..1 across the window
  return 0.35875 - 0.48829 * std::cos(2.0 * M_PI * t) + 0.14128 * std::cos(4.0 * M_PI * t) -
         0.01168 * std::cos(6.0 * M_PI * t);
}

// The filtered image in double: RGBA then coverage per pixel. Samples lie at
// samplePoint's 1/256-pixel grid positions.
std::vector<std::array<double, 5>> filterInDouble(const ReferenceSamples& r) {
  std::vector<std::array<double, 5>> out(std::size_t(kSize) * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      std::array<double, 5> sum{};
      double weights = 0.0;
      for (int sy = std::max(y - 2, 0); sy <= std::min(y + 2, kSize - 1); ++sy)
        for (int sx = std::max(x - 2, 0); sx <= std::min(x + 2, kSize - 1); ++sx)
          for (int k = 0; k < r.samples; ++k) {
            const ref::GridPoint p = ref::samplePoint(sx, sy, k, r.samples);
            const double dx = double(p.x) / ref::kSubpixelUnits - (x + 0.5);
            const double dy = double(p.y) / ref::kSubpixelUnits - (y + 0.5);
            const double w = blackmanHarrisWindow(dx) * blackmanHarrisWindow(dy);
            const std::size_t s = (std::size_t(sy) * kSize + sx) * r.samples + k;
            for (int c = 0; c < 4; ++c) sum[c] += w * r.colour[s][c];
            sum[4] += w * r.covered[s];
            weights += w;
          }
      for (double& v : sum) v /= weights;
      out[std::size_t(y) * kSize + x] = sum;
    }
  return out;
}

Frame renderFiltered(const Scene& scene, int samples, PixelFilter filter, int threads = 2) {
  RenderSettings settings;
  settings.width = settings.height = kSize;
  settings.samples = samples;
  settings.pixelFilter = filter;
  settings.frameCoverage = true;
  return renderOnce(scene, pixelExactCamera(), settings, threads);
}

// Triangles of several colours crossing the tile borders at 64, 128 and 192
// and the image's edges, overlapping in places, with slivers.
std::vector<ColouredTriangle> crossingTriangles() {
  return {
      {{glm::dvec2(-10.25, 20.5), glm::dvec2(100.75, 40.125), glm::dvec2(30.5, 140.375)},
       {0.9f, 0.2f, 0.1f, 1.0f}},
      {{glm::dvec2(60.125, 60.875), glm::dvec2(200.5, 70.25), glm::dvec2(130.75, 230.5)},
       {0.1f, 0.7f, 0.3f, 1.0f}},
      {{glm::dvec2(190.5, -5.0), glm::dvec2(270.0, 100.25), glm::dvec2(196.25, 262.0)},
       {0.2f, 0.3f, 0.95f, 1.0f}},
      {{glm::dvec2(0.0, 250.5), glm::dvec2(255.5, 126.25), glm::dvec2(256.0, 129.0)},
       {1.0f, 1.0f, 0.0f, 1.0f}},
  };
}

// The filter over the engine's samples equals the double-precision filter of
// the reference's samples. Tolerance 1e-6: float sums of up to 400 weighted
// terms in [0, 1] (measured worst 2.9e-7 at 16 samples).
TEST(PixelFilter, MatchesADoublePrecisionFilterOfTheReferenceSamples) {
  const Scene scene = flatScene(crossingTriangles());
  for (const int samples : {1, 16}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    const auto expected = filterInDouble(referenceSamples(scene, samples));
    const Frame frame = renderFiltered(scene, samples, PixelFilter::BlackmanHarris);
    double worst = 0.0;
    int partial = 0;  // pixels strictly between empty and covered
    for (std::size_t p = 0; p < expected.size(); ++p) {
      for (int c = 0; c < 4; ++c)
        worst = std::max(worst, std::abs(frame.rgba[p * 4 + c] - expected[p][c]));
      worst = std::max(worst, std::abs(frame.coverage[p] - expected[p][4]));
      partial += expected[p][4] > 0.01 && expected[p][4] < 0.99;
    }
    std::printf("[ %d samples ] worst difference from the double filter %.3g\n", samples, worst);
    EXPECT_LT(worst, 1e-6);
    EXPECT_GT(partial, 1000) << "the edges must be blurred over several pixels";
  }
}

// Translation invariance across tile borders: one triangle drawn inside a
// tile, then moved by whole pixels so that its edges cross the tile borders
// at x = 64 and y = 64, filters to the same pixels (moved). Only the
// grouping of the sums differs (the neighbours' parts are added last).
TEST(PixelFilter, AnEdgeAcrossATileBorderFiltersAsOneInsideATile) {
  const WindowTriangle inside = {glm::dvec2(10.375, 12.75), glm::dvec2(45.125, 20.25),
                                 glm::dvec2(25.625, 50.875)};
  const glm::dvec2 move(40.0, 30.0);
  WindowTriangle crossing = inside;
  for (glm::dvec2& p : crossing) p += move;
  for (const int samples : {1, 16}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    const Frame a = renderFiltered(flatScene({{inside, {0.8f, 0.4f, 0.2f, 1.0f}}}), samples,
                                   PixelFilter::BlackmanHarris);
    const Frame b = renderFiltered(flatScene({{crossing, {0.8f, 0.4f, 0.2f, 1.0f}}}), samples,
                                   PixelFilter::BlackmanHarris);
    double worst = 0.0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const std::size_t pa = std::size_t(y) * kSize + x;
        const std::size_t pb = std::size_t(y + int(move.y)) * kSize + std::size_t(x + int(move.x));
        for (int c = 0; c < 4; ++c)
          worst = std::max(worst, double(std::abs(a.rgba[pa * 4 + c] - b.rgba[pb * 4 + c])));
        worst = std::max(worst, double(std::abs(a.coverage[pa] - b.coverage[pb])));
      }
    std::printf("[ %d samples ] moved across the borders: worst difference %.3g\n", samples, worst);
    EXPECT_LT(worst, 5e-7);
  }
}

// The box filter's coverage is exactly the reference's covered fraction of
// each pixel's samples.
TEST(PixelFilter, BoxCoverageIsTheReferenceCoveredFraction) {
  const Scene scene = flatScene(crossingTriangles());
  for (const int samples : {1, 2, 4, 8, 16}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    const ReferenceSamples r = referenceSamples(scene, samples);
    const Frame frame = renderFiltered(scene, samples, PixelFilter::Box);
    int mismatches = 0;
    for (std::size_t p = 0; p < frame.coverage.size(); ++p) {
      double covered = 0.0;
      for (int k = 0; k < samples; ++k) covered += r.covered[p * samples + std::size_t(k)];
      mismatches += frame.coverage[p] != float(covered / samples);
    }
    EXPECT_EQ(mismatches, 0);
  }
}

// A flat opaque colour over the whole frame stays that colour, at the image's
// edges (where the weights are renormalized) and tile borders too: within 4
// ulp of each channel (a float sum of 25 or 400 terms divided by the float
// sum of their weights; measured worst 2 ulp).
TEST(PixelFilter, FlatOpaqueFrameKeepsItsColour) {
  const glm::vec4 colour(0.3f, 0.6f, 0.9f, 1.0f);
  const Scene scene =
      flatScene({{{glm::dvec2(-300, -300), glm::dvec2(900, -300), glm::dvec2(-300, 900)}, colour}});
  for (const int samples : {1, 4, 16}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    const Frame frame = renderFiltered(scene, samples, PixelFilter::BlackmanHarris);
    float worstUlps = 0.0f;
    for (std::size_t p = 0; p < frame.coverage.size(); ++p) {
      for (int c = 0; c < 4; ++c) {
        const float ulp = std::nextafter(colour[c], 2.0f) - colour[c];
        worstUlps = std::max(worstUlps, std::abs(frame.rgba[p * 4 + c] - colour[c]) / ulp);
      }
      const float ulp = std::nextafter(1.0f, 2.0f) - 1.0f;
      worstUlps = std::max(worstUlps, std::abs(frame.coverage[p] - 1.0f) / ulp);
    }
    std::printf("[ %d samples ] flat frame: worst %.1f ulp\n", samples, worstUlps);
    EXPECT_LE(worstUlps, 4.0f);
  }
}

}  // namespace
}  // namespace quadra
