// Engine coverage against the exact reference rasterizer: the top-left fill
// rule on shared edges and vertices at pixel centres, tile (64 px) and block
// (8 px) borders, watertight meshes, random and sliver triangles, culling.
//
// An orthographic camera with ymag = 128 on a 256 x 256 viewport maps world
// (x, y) to window (x + 128, 128 - y) with power-of-two scales only, so the
// engine's float transform is exact and both sides snap the same positions.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "api/renderer.h"
#include "lab/reference/reference_raster.h"
#include "render_helpers.h"

namespace quadra {
namespace {

constexpr int kSize = 256;
using WindowTriangle = std::array<glm::dvec2, 3>;

Camera pixelExactCamera() {
  Camera camera;
  camera.type = Camera::Type::Orthographic;
  camera.ymag = kSize / 2;
  camera.xmag = kSize / 2;
  camera.znear = 0.5f;
  camera.zfar = 4.0f;
  return camera;
}

glm::vec3 worldFromWindow(const glm::dvec2& w) {
  return {float(w.x - kSize / 2), float(kSize / 2 - w.y), -1.0f};
}

// One mesh holding all triangles, drawn in order. mirrored: the instance
// scales z by -1 (the mesh sits at z = +1), which flips the front winding.
Scene sceneFromWindow(const std::vector<WindowTriangle>& triangles, bool doubleSided,
                      bool mirrored = false) {
  Scene scene;
  Mesh mesh;
  for (const WindowTriangle& t : triangles)
    for (const glm::dvec2& p : t) {
      glm::vec3 world = worldFromWindow(p);
      if (mirrored) world.z = -world.z;
      mesh.indices.push_back(std::uint32_t(mesh.positions.size()));
      mesh.positions.push_back(world);
    }
  mesh.material = 0;
  Material material;
  material.doubleSided = doubleSided;
  scene.materials.push_back(material);
  scene.meshes.push_back(mesh);
  Instance instance;
  if (mirrored) instance.world[2][2] = -1.0f;
  scene.instances.push_back(instance);
  return scene;
}

// Renders the coverage count and compares it, pixel by pixel, with the
// reference fed the same scene through the double-precision projection.
// With several samples the engine's pixel is the mean of its samples'
// counts, so times the sample count it is the reference's covered samples,
// exactly. Returns the reference image for further checks.
ref::CoverageImage expectCoverageMatches(const Scene& scene, const std::vector<Isa>& isas,
                                         int samples = 1) {
  SCOPED_TRACE(std::to_string(samples) + " samples");
  const Camera camera = pixelExactCamera();
  const auto projected = ref::projectScene(scene, camera, kSize, kSize);
  const ref::CoverageImage expected =
      ref::rasterizeCoverage(ref::gridTriangles(projected), kSize, kSize, samples);
  RenderSettings settings;
  settings.width = settings.height = kSize;
  settings.debugView = DebugView::CoverageCount;
  settings.samples = samples;
  for (Isa isa : isas) {
    SCOPED_TRACE(isaName(isa));
    Renderer renderer({.threads = 2, .isa = isa});
    Frame frame;
    renderer.render(scene, camera, settings, frame);
    EXPECT_EQ(frame.width, kSize);
    EXPECT_EQ(frame.height, kSize);
    if (frame.width != kSize || frame.height != kSize) continue;
    int mismatches = 0;
    std::ostringstream first;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const float got = frame.rgba[(std::size_t(y) * kSize + x) * 4] * float(samples);
        if (got == float(expected.at(x, y))) continue;
        if (++mismatches <= 8)
          first << " (" << x << "," << y << "): engine " << got << " ref " << expected.at(x, y);
      }
    EXPECT_EQ(mismatches, 0) << "first mismatches:" << first.str();
  }
  return expected;
}

// The premise of this file: the reference projection lands exactly where the
// test placed the vertices.
TEST(RasterFillRule, OrthographicSetupIsPixelExact) {
  const WindowTriangle t = {{{0.5, 64.0}, {200.25, 8.00390625}, {255.99609375, 255.5}}};
  const auto projected =
      ref::projectScene(sceneFromWindow({t}, true), pixelExactCamera(), kSize, kSize);
  ASSERT_EQ(projected.size(), 1u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(projected[0].v[i].window, t[i]);
    EXPECT_EQ(projected[0].v[i].windowExact, t[i]);
  }
}

// A rectangular grid over (and past) the whole viewport whose lines sit on
// tile borders, block borders, pixel centres and in between, split along
// random diagonals; inner vertices jittered by half pixels so the slanted
// shared edges pass through pixel centres. Every pixel is covered once.
TEST(RasterFillRule, GridOverViewportCoversEveryPixelOnce) {
  const std::vector<double> lines = {-8,  0,     8,      13.5, 27.5,  40,    63.5,
                                     64,  64.5,  100.25, 128,  136,   150.5, 191.5,
                                     192, 200.5, 224,    248,  255.5, 256,   264};
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> jitter(-1, 1), coin(0, 1);
  const int n = int(lines.size());
  // Half-pixel jitter only where the neighbouring lines are >= 3 px away: the
  // quads then stay convex (each corner moves < 0.71 px, less than half the
  // 2.1 px from a corner to the opposite diagonal), so no triangle folds.
  const auto jitterable = [&](int i) {
    return i > 0 && i + 1 < n && lines[i] - lines[i - 1] >= 3 && lines[i + 1] - lines[i] >= 3;
  };
  std::vector<glm::dvec2> vertices;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool movable = jitterable(i) && jitterable(j);
      const double dx = movable ? 0.5 * jitter(rng) : 0.0, dy = movable ? 0.5 * jitter(rng) : 0.0;
      vertices.push_back({lines[i] + dx, lines[j] + dy});
    }
  std::vector<WindowTriangle> triangles;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const glm::dvec2 a = vertices[j * n + i], b = vertices[j * n + i + 1];
      const glm::dvec2 c = vertices[(j + 1) * n + i], d = vertices[(j + 1) * n + i + 1];
      // Alternate windings too: both are drawn (double-sided).
      if (coin(rng)) {
        triangles.push_back({a, b, d}), triangles.push_back({a, c, d});
      } else {
        triangles.push_back({a, b, c}), triangles.push_back({b, c, d});
      }
    }
  const ref::CoverageImage expected =
      expectCoverageMatches(sceneFromWindow(triangles, true), supportedIsas());
  for (int count : expected.count) ASSERT_EQ(count, 1);  // the reference agrees with the premise
}

// Fans around a vertex on a pixel centre, on tile corners, on a block/tile
// corner and on none of those; rim vertices on pixel centres and borders.
TEST(RasterFillRule, FansShareEdgesWithoutGapsOrOverlaps) {
  struct Fan {
    glm::dvec2 centre;
    double radius;
  };
  // Centres far enough apart that the discs do not overlap.
  const std::vector<Fan> fans = {{{64.5, 64.5}, 40},
                                 {{192, 64}, 40},
                                 {{64, 192}, 40},
                                 {{200, 192}, 40},
                                 {{128.25, 128.75}, 20}};
  std::vector<WindowTriangle> triangles;
  const int spokes = 23;
  for (const auto& [c, radius] : fans) {
    std::vector<glm::dvec2> rim;
    for (int k = 0; k < spokes; ++k) {
      const double angle = 2.0 * M_PI * k / spokes;
      // Rounded to half pixels: on pixel centres or pixel borders.
      rim.push_back({c.x + std::round(2 * radius * std::cos(angle)) / 2,
                     c.y + std::round(2 * radius * std::sin(angle)) / 2});
    }
    for (int k = 0; k < spokes; ++k) triangles.push_back({c, rim[k], rim[(k + 1) % spokes]});
  }
  const ref::CoverageImage expected =
      expectCoverageMatches(sceneFromWindow(triangles, true), supportedIsas());
  int covered = 0;
  for (int count : expected.count) {
    ASSERT_LE(count, 1);  // fans are disjoint and watertight
    covered += count;
  }
  EXPECT_GT(covered, 20000);  // four discs of radius 40 px and one of 20: ~21360 px
}

// Random triangles, many overlapping, half on a half-pixel lattice (edges
// through pixel centres) and half anywhere on the 1/256 grid; some reach
// outside the viewport, some are tiny or degenerate.
TEST(RasterFillRule, RandomTrianglesMatchReference) {
  std::mt19937 rng(77);
  std::uniform_int_distribution<int> halfPixel(-40 * 2, (kSize + 40) * 2);
  std::uniform_int_distribution<int> subpixel(-40 * 256, (kSize + 40) * 256);
  std::uniform_int_distribution<int> small(-6 * 256, 6 * 256);
  std::vector<WindowTriangle> triangles;
  for (int n = 0; n < 600; ++n) {
    WindowTriangle t;
    if (n % 3 == 0) {
      for (glm::dvec2& p : t) p = {halfPixel(rng) / 2.0, halfPixel(rng) / 2.0};
    } else if (n % 3 == 1) {
      for (glm::dvec2& p : t) p = {subpixel(rng) / 256.0, subpixel(rng) / 256.0};
    } else {  // small, around a random point
      const glm::dvec2 at(subpixel(rng) / 256.0, subpixel(rng) / 256.0);
      for (glm::dvec2& p : t) p = at + glm::dvec2(small(rng), small(rng)) / 256.0;
    }
    triangles.push_back(t);
  }
  expectCoverageMatches(sceneFromWindow(triangles, true), supportedIsas());
}

// Triangles far larger than the viewport whose one edge ends inside a tile,
// at and between pixel centres and one grid unit either side of a centre:
// the tile stage drops the edges that hold over a whole tile, so the lanes
// just past that edge (in a group the walk visits) must still be tested.
TEST(RasterFillRule, EdgesEndingInsideCoveredTilesMatchReference) {
  const double unit = 1.0 / 256;
  std::vector<WindowTriangle> triangles;
  const double ends[] = {37.3, 64.5, 70.5 + unit, 101.5 - unit, 130.0, 191.75, 250.5};
  for (double end : ends) {
    // Vertical right edge, vertical left edge, horizontal bottom, horizontal top.
    triangles.push_back({{{end, -2000.0}, {end, 2000.0}, {-3000.0, 128.0}}});
    triangles.push_back({{{end, 2000.0}, {end, -2000.0}, {3000.0, 128.0}}});
    triangles.push_back({{{-2000.0, end}, {2000.0, end}, {128.0, -3000.0}}});
    triangles.push_back({{{2000.0, end}, {-2000.0, end}, {128.0, 3000.0}}});
  }
  // And slanted edges across tiles that the other two edges cover whole.
  triangles.push_back({{{-1000.0, -900.0}, {3000.0, 200.3}, {-1000.0, 3000.0}}});
  triangles.push_back({{{3000.0, -1000.0}, {3000.0, 3000.0}, {-100.0, 3000.0}}});
  expectCoverageMatches(sceneFromWindow(triangles, true), supportedIsas());
}

// Random triangles thousands of pixels long (|a| + |b| beyond 2^27, where
// the unscaled edge functions would not fit 32-bit lanes) with vertices on
// arbitrary grid units, so that their edges cross blocks at every fraction
// of a pixel: the lanes' edges scaled down by 256 and rounded up
// (tile_kernel_impl.h LaneEdges) must keep every sign, at 1 and 4 samples.
TEST(RasterFillRule, TrianglesThousandsOfPixelsLongMatchReference) {
  std::mt19937 rng(2027);
  std::uniform_int_distribution<int> far(-5000 * 256, 5000 * 256);
  std::uniform_int_distribution<int> near(-20 * 256, (kSize + 20) * 256);
  std::vector<WindowTriangle> triangles;
  for (int n = 0; n < 60; ++n) {
    // One vertex near the viewport, two far out, so that most cross it.
    WindowTriangle t = {{{near(rng) / 256.0, near(rng) / 256.0},
                         {far(rng) / 256.0, far(rng) / 256.0},
                         {far(rng) / 256.0, far(rng) / 256.0}}};
    triangles.push_back(t);
  }
  for (const int samples : {1, 4})
    expectCoverageMatches(sceneFromWindow(triangles, true), supportedIsas(), samples);
}

// Wedges whose only pixels in the viewport lie in one 8x8 block at a corner,
// with their other vertices ~900 px outside: the small-triangle path
// (tile_kernel_impl.h rasterizeInOneBlock) must hand such a triangle, whose
// far edge is ~1e10 at the block's corner, back to the walk, and rasterize
// the truly small ones (apexes alone, just inside) itself.
TEST(RasterFillRule, TrianglesInOneBlockMatchReference) {
  std::vector<WindowTriangle> wedges, small;
  for (double apex : {0.6, 2.5, 4.2, 6.9, 7.5}) {
    // Towards the top-left corner, and from the bottom-right one outward.
    wedges.push_back({{{apex, apex + 0.4}, {-900.0, -600.0}, {-600.0, -900.0}}});
    const double far = kSize + 850.0, inner = kSize - apex;
    wedges.push_back({{{inner, inner - 0.3}, {far, far + 300.0}, {far + 300.0, far}}});
    // A small triangle inside a block.
    small.push_back({{{apex + 0.2, 12.1}, {apex + 3.3, 13.9}, {apex + 0.9, 15.7}}});
  }
  const ref::CoverageImage wedgesOnly =
      expectCoverageMatches(sceneFromWindow(wedges, true), supportedIsas());
  int covered = 0;
  for (int count : wedgesOnly.count) covered += count;
  EXPECT_GT(covered, 10);  // the wedges' tips do cover pixel centres
  wedges.insert(wedges.end(), small.begin(), small.end());
  expectCoverageMatches(sceneFromWindow(wedges, true), supportedIsas());
}

// Needles one grid unit wide that run along rows and columns of pixel centres
// and across many tiles, at shallow and steep slopes.
TEST(RasterFillRule, SliversMatchReference) {
  const double unit = 1.0 / 256;
  std::vector<WindowTriangle> triangles;
  for (int k = 0; k < 12; ++k) {
    const double row = 10.5 + 20 * k;
    triangles.push_back({{{0.5, row}, {255.5, row + k * unit}, {255.5, row + (k + 1) * unit}}});
    triangles.push_back({{{row, 0.5}, {row + unit, 250.5}, {row - k * unit, 255.5}}});
    triangles.push_back({{{3.5 + k, 0.0}, {250.0 - k, 256.0}, {250.0 - k + unit, 256.0}}});
    // Exactly horizontal and vertical slivers: top edge on a centre row, left
    // edge on a centre column.
    triangles.push_back({{{1.5, 5.5 + 20 * k}, {254.5, 5.5 + 20 * k}, {1.5, 5.5 + 20 * k + unit}}});
    triangles.push_back({{{5.5 + 20 * k, 1.5}, {5.5 + 20 * k, 254.5}, {5.5 + 20 * k + unit, 1.5}}});
  }
  const ref::CoverageImage expected =
      expectCoverageMatches(sceneFromWindow(triangles, true), supportedIsas());
  int covered = 0;
  for (int count : expected.count) covered += count;
  EXPECT_GT(covered, 12 * 2 * 250);  // the horizontal/vertical slivers cover a full line each
}

// Single-sided materials: only counter-clockwise (as seen) triangles are drawn,
// and a mirroring instance matrix swaps which winding that is.
TEST(RasterFillRule, CullingFollowsWindingAndMirroring) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> coord(-10 * 2, (kSize + 10) * 2);
  std::vector<WindowTriangle> triangles;
  for (int n = 0; n < 200; ++n) {
    WindowTriangle t;
    for (glm::dvec2& p : t) p = {coord(rng) / 2.0, coord(rng) / 2.0};
    triangles.push_back(t);
  }
  for (bool mirrored : {false, true}) {
    SCOPED_TRACE(mirrored ? "mirrored" : "plain");
    const Scene scene = sceneFromWindow(triangles, false, mirrored);
    const auto projected = ref::projectScene(scene, pixelExactCamera(), kSize, kSize);
    ASSERT_EQ(projected.size(), triangles.size());
    EXPECT_EQ(projected[0].cull, mirrored ? ref::CullMode::Front : ref::CullMode::Back);
    const ref::CoverageImage expected = expectCoverageMatches(scene, {detectBestIsa()});
    // The reference keeps only one winding: the counts are those of a subset.
    const ref::CoverageImage all = ref::rasterizeCoverage(
        ref::gridTriangles(
            ref::projectScene(sceneFromWindow(triangles, true), pixelExactCamera(), kSize, kSize)),
        kSize, kSize);
    long kept = 0, total = 0;
    for (std::size_t i = 0; i < all.count.size(); ++i)
      kept += expected.count[i], total += all.count[i];
    EXPECT_GT(kept, total / 4);
    EXPECT_LT(kept, total * 3 / 4);
  }
}

// Coverage per sample at every sample count, on every ISA: random triangles
// with vertices on the 1/16-pixel lattice the sample positions lie on (so
// edges run through samples and the top-left rule decides), anywhere on the
// grid, and tiny ones that fall between pixel centres but not between
// samples (setup must keep them), plus the one-block wedges and slivers.
TEST(RasterFillRule, EverySampleCountMatchesReference) {
  std::mt19937 rng(1613);
  std::uniform_int_distribution<int> sixteenth(-20 * 16, (kSize + 20) * 16);
  std::uniform_int_distribution<int> subpixel(-20 * 256, (kSize + 20) * 256);
  std::uniform_int_distribution<int> tiny(-180, 180);
  std::vector<WindowTriangle> triangles;
  for (int n = 0; n < 450; ++n) {
    WindowTriangle t;
    if (n % 3 == 0) {
      for (glm::dvec2& p : t) p = {sixteenth(rng) / 16.0, sixteenth(rng) / 16.0};
    } else if (n % 3 == 1) {
      for (glm::dvec2& p : t) p = {subpixel(rng) / 256.0, subpixel(rng) / 256.0};
    } else {
      const glm::dvec2 at(subpixel(rng) / 256.0, subpixel(rng) / 256.0);
      for (glm::dvec2& p : t) p = at + glm::dvec2(tiny(rng), tiny(rng)) / 256.0;
    }
    triangles.push_back(t);
  }
  const double unit = 1.0 / 256;
  for (double apex : {0.6, 4.2, 7.5}) {
    triangles.push_back({{{apex, apex + 0.4}, {-900.0, -600.0}, {-600.0, -900.0}}});
    triangles.push_back({{{apex + 0.2, 12.1}, {apex + 3.3, 13.9}, {apex + 0.9, 15.7}}});
  }
  for (int k = 0; k < 6; ++k) {
    const double row = 10.5 + 40 * k + 0.125;
    triangles.push_back({{{0.5, row}, {255.5, row + k * unit}, {255.5, row + (k + 1) * unit}}});
  }
  const Scene scene = sceneFromWindow(triangles, true);
  for (int samples : {2, 4, 8, 16}) {
    const ref::CoverageImage expected = expectCoverageMatches(scene, supportedIsas(), samples);
    // The scene puts edges through samples: the per-sample counts differ
    // from whole-pixel ones somewhere, or the test would prove nothing.
    const ref::CoverageImage centres = ref::rasterizeCoverage(
        ref::gridTriangles(ref::projectScene(scene, pixelExactCamera(), kSize, kSize)), kSize,
        kSize);
    int partial = 0;
    for (std::size_t i = 0; i < expected.count.size(); ++i)
      partial += expected.count[i] != centres.count[i] * samples;
    EXPECT_GT(partial, 1000);
  }
}

// Each sample takes the colour of the triangle that holds it, and the pixel
// is their mean: overlapping coloured triangles at one depth (the first
// drawn keeps a sample: LESS), many sharing pixels, shaded once per pixel
// and visible triangle or per sample. Colours are quarters and the
// orthographic view keeps them constant over each triangle, so the
// expected pixel is exact: the mean of its samples' colours from the
// reference's per-sample coverage.
TEST(RasterFillRule, EachSampleTakesItsTrianglesColour) {
  std::mt19937 rng(4242);
  std::uniform_int_distribution<int> where(16 * 256, 112 * 256);
  std::uniform_int_distribution<int> size(-4 * 256, 4 * 256);
  std::uniform_int_distribution<int> quarter(0, 4);
  std::vector<WindowTriangle> triangles;
  std::vector<glm::vec4> colours;  // per vertex
  for (int n = 0; n < 300; ++n) {
    const glm::dvec2 at(where(rng) / 256.0, where(rng) / 256.0);
    WindowTriangle t;
    for (glm::dvec2& p : t) p = at + glm::dvec2(size(rng), size(rng)) / 256.0;
    triangles.push_back(t);
    const glm::vec4 colour(quarter(rng) / 4.0f, quarter(rng) / 4.0f, quarter(rng) / 4.0f, 1.0f);
    colours.insert(colours.end(), 3, colour);
  }
  Scene scene = sceneFromWindow(triangles, true);
  Mesh& mesh = scene.meshes[0];
  mesh.colors = colours;
  const Camera camera = pixelExactCamera();
  const auto grid = ref::gridTriangles(ref::projectScene(scene, camera, kSize, kSize));
  ASSERT_EQ(grid.size(), triangles.size());

  for (const int samples : {4, 16}) {
    // The first triangle to hold each sample, per pixel and sample.
    std::vector<int> owner(std::size_t(kSize) * kSize * samples, -1);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        for (int k = 0; k < samples; ++k)
          for (std::size_t i = 0; i < grid.size(); ++i)
            if (std::abs(triangles[i][0].x - x) < 10 && std::abs(triangles[i][0].y - y) < 10 &&
                ref::coversPoint(grid[i], ref::samplePoint(x, y, k, samples))) {
              owner[(std::size_t(y) * kSize + x) * samples + k] = int(i);
              break;
            }
    int shared = 0;  // pixels whose samples several triangles (or none) hold
    for (std::size_t p = 0; p < std::size_t(kSize) * kSize; ++p)
      for (int k = 1; k < samples; ++k)
        if (owner[p * samples + k] != owner[p * samples]) {
          ++shared;
          break;
        }
    EXPECT_GT(shared, 1000) << "the scene must share pixels between triangles";
    for (const ShadingRate rate : {ShadingRate::Pixel, ShadingRate::Sample}) {
      for (const Isa isa : supportedIsas()) {
        SCOPED_TRACE(std::to_string(samples) + " samples, " +
                     (rate == ShadingRate::Pixel ? "per pixel, " : "per sample, ") + isaName(isa));
        RenderSettings settings;
        settings.width = settings.height = kSize;
        settings.samples = samples;
        settings.shadingRate = rate;
        Renderer renderer({.threads = 2, .isa = isa});
        Frame frame;
        renderer.render(scene, camera, settings, frame);
        int mismatches = 0;
        std::ostringstream first;
        for (int y = 0; y < kSize; ++y)
          for (int x = 0; x < kSize; ++x) {
            const std::size_t p = std::size_t(y) * kSize + x;
            glm::vec4 sum(0.0f);
            for (int k = 0; k < samples; ++k) {
              const int i = owner[p * samples + k];
              if (i >= 0) sum += mesh.colors[3 * std::size_t(i)];
            }
            const glm::vec4 expected = sum / float(samples);
            const float* got = &frame.rgba[p * 4];
            if (got[0] == expected.r && got[1] == expected.g && got[2] == expected.b &&
                got[3] == expected.a)
              continue;
            if (++mismatches <= 4)
              first << " (" << x << "," << y << "): engine " << got[0] << "," << got[1] << ","
                    << got[2] << "," << got[3] << " expected " << expected.r << "," << expected.g
                    << "," << expected.b << "," << expected.a;
          }
        EXPECT_EQ(mismatches, 0) << "first mismatches:" << first.str();
      }
    }
  }
}

}  // namespace
}  // namespace quadra
