// Self-tests of the exact reference rasterizer and the double-precision scene
// projection (lab/reference/reference_raster.h): analytic cases and an
// independent symbolic-perturbation formulation of the fill rule.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lab/reference/reference_raster.h"

namespace quadra::ref {

namespace {

// An independent formulation of the top-left rule: a centre exactly on an edge
// belongs to the triangle iff the centre nudged by (eps, eps^2), eps -> 0+, is
// strictly inside. Left edges gain the +x nudge, top edges (where x does not
// change the edge function) the +y one; right and bottom edges lose it.
bool coveredByPerturbation(const GridTriangle& t, std::int64_t px, std::int64_t py) {
  const __int128 area = doubleSignedArea(t);
  if (area == 0) return false;
  const std::int64_t cx = (2 * px + 1) * 128, cy = (2 * py + 1) * 128;
  for (int i = 0; i < 3; ++i) {
    const GridPoint& a = t.v[i];
    const GridPoint& b = t.v[(i + 1) % 3];
    // e(p) = (b - a) x (p - a), oriented so the interior is positive.
    const __int128 orient = area > 0 ? 1 : -1;
    const __int128 e =
        orient * (__int128(b.x - a.x) * (cy - a.y) - __int128(b.y - a.y) * (cx - a.x));
    const __int128 dEdx = orient * -__int128(b.y - a.y);
    const __int128 dEdy = orient * __int128(b.x - a.x);
    const __int128 leading = e != 0 ? e : (dEdx != 0 ? dEdx : dEdy);
    if (leading <= 0) return false;
  }
  return true;
}

GridTriangle reversed(GridTriangle t) {
  std::swap(t.v[1], t.v[2]);
  return t;
}

TEST(ReferenceRaster, SnapRoundsToNearestTiesToEven) {
  EXPECT_EQ(snapToGrid(0.5 / 256), 0);
  EXPECT_EQ(snapToGrid(1.5 / 256), 2);
  EXPECT_EQ(snapToGrid(2.5 / 256), 2);
  EXPECT_EQ(snapToGrid(-0.5 / 256), 0);
  EXPECT_EQ(snapToGrid(-1.5 / 256), -2);
  EXPECT_EQ(snapToGrid(0.51 / 256), 1);
  EXPECT_EQ(snapToGrid(10.0), 2560);
}

// A rectangle whose corners sit on pixel centres: its left and top sides are
// inclusive, its right and bottom sides exclusive, for either diagonal and
// either winding.
TEST(ReferenceRaster, RectangleOnPixelCentresFollowsTopLeft) {
  const double x0 = 3.5, x1 = 11.5, y0 = 2.5, y1 = 7.5;
  const glm::dvec2 tl{x0, y0}, tr{x1, y0}, bl{x0, y1}, br{x1, y1};
  const std::vector<std::vector<GridTriangle>> variants = {
      {snapTriangle(tl, tr, br), snapTriangle(tl, br, bl)},
      {snapTriangle(tl, br, tr), snapTriangle(tl, bl, br)},
      {snapTriangle(tr, bl, tl), snapTriangle(tr, br, bl)},
      {snapTriangle(tr, tl, bl), snapTriangle(tr, bl, br)},
  };
  for (const auto& tris : variants) {
    const CoverageImage image = rasterizeCoverage(tris, 16, 12);
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 16; ++x) {
        const int expected = (x >= 3 && x < 11 && y >= 2 && y < 7) ? 1 : 0;
        ASSERT_EQ(image.at(x, y), expected) << "pixel " << x << "," << y;
      }
  }
}

TEST(ReferenceRaster, AgreesWithPerturbationFormulation) {
  std::mt19937 rng(1234);
  // Coordinates on a quarter-pixel lattice, so centres fall on edges and
  // vertices often; some triangles degenerate.
  std::uniform_int_distribution<std::int64_t> coord(0, 16 * 4);
  int onEdgeCases = 0;
  for (int n = 0; n < 3000; ++n) {
    GridTriangle t;
    for (GridPoint& p : t.v) p = {coord(rng) * 64, coord(rng) * 64};
    for (std::int64_t y = 0; y < 17; ++y)
      for (std::int64_t x = 0; x < 17; ++x) {
        const bool expected = coveredByPerturbation(t, x, y);
        ASSERT_EQ(coversPixelCentre(t, x, y), expected) << "triangle " << n;
        ASSERT_EQ(coversPixelCentre(reversed(t), x, y), expected) << "triangle " << n;
        const GridPoint c{(2 * x + 1) * 128, (2 * y + 1) * 128};
        for (int i = 0; i < 3; ++i)
          onEdgeCases += doubleSignedArea(t) != 0 && cross(t.v[i], t.v[(i + 1) % 3], c) == 0;
      }
  }
  EXPECT_GT(onEdgeCases, 1000);  // the lattice really exercises the tie rule
}

// A jittered grid mesh covering the whole viewport, including the far corner
// vertices outside it: no gaps, no double hits.
TEST(ReferenceRaster, WatertightMeshCoversEachPixelOnce) {
  std::mt19937 rng(99);
  std::uniform_int_distribution<int> jitter(-2, 2);
  const int cells = 8, size = 64, step = size / cells;
  std::vector<GridPoint> grid;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      const bool inner = i > 0 && i < cells && j > 0 && j < cells;
      // Half-pixel jitter steps put vertices on pixel centres and borders.
      const std::int64_t dx = inner ? jitter(rng) * 128 : 0, dy = inner ? jitter(rng) * 128 : 0;
      grid.push_back({std::int64_t(i * step) * 256 + dx, std::int64_t(j * step) * 256 + dy});
    }
  std::vector<GridTriangle> tris;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const GridPoint a = grid[j * (cells + 1) + i], b = grid[j * (cells + 1) + i + 1];
      const GridPoint c = grid[(j + 1) * (cells + 1) + i], d = grid[(j + 1) * (cells + 1) + i + 1];
      if ((i + j) % 2) {
        tris.push_back({{a, b, d}}), tris.push_back({{a, d, c}});
      } else {
        tris.push_back({{a, b, c}}), tris.push_back({{b, d, c}});
      }
    }
  const CoverageImage image = rasterizeCoverage(tris, size, size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) ASSERT_EQ(image.at(x, y), 1) << x << "," << y;
}

TEST(ReferenceRaster, CullingKeepsCounterClockwiseNdcAsFront) {
  // Seen on screen: top-left, bottom-left, top-right is counter-clockwise.
  const GridTriangle front = snapTriangle({1, 1}, {1, 9}, {9, 1}, CullMode::Back);
  EXPECT_LT(doubleSignedArea(front), 0);
  EXPECT_TRUE(survivesCulling(front));
  EXPECT_FALSE(survivesCulling(reversed(front)));
  GridTriangle mirrored = front;
  mirrored.cull = CullMode::Front;
  EXPECT_FALSE(survivesCulling(mirrored));
  EXPECT_TRUE(survivesCulling(reversed(mirrored)));
  EXPECT_EQ(rasterizeCoverage({reversed(front)}, 10, 10).at(2, 2), 0);
  EXPECT_EQ(rasterizeCoverage({front}, 10, 10).at(2, 2), 1);
}

Scene oneTriangleScene(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  Scene scene;
  Mesh mesh;
  mesh.positions = {glm::vec3(a), glm::vec3(b), glm::vec3(c)};
  mesh.indices = {0, 1, 2};
  mesh.material = 0;
  scene.meshes.push_back(mesh);
  scene.materials.push_back(Material{});
  scene.instances.push_back(Instance{});
  return scene;
}

TEST(ReferenceProjection, OrthographicPowerOfTwoMapsWorldToPixels) {
  Camera camera;
  camera.type = Camera::Type::Orthographic;
  camera.ymag = 128;
  camera.znear = 0.5f;
  camera.zfar = 10.0f;
  const Scene scene = oneTriangleScene({-128, 128, -1}, {-128, 0, -1}, {0.25f, 128, -1});
  const auto tris = projectScene(scene, camera, 256, 256);
  ASSERT_EQ(tris.size(), 1u);
  EXPECT_EQ(tris[0].v[0].window, glm::dvec2(0, 0));
  EXPECT_EQ(tris[0].v[1].window, glm::dvec2(0, 128));
  EXPECT_EQ(tris[0].v[2].window, glm::dvec2(128.25, 0));
  EXPECT_NEAR(tris[0].v[0].depth, 0.5 / 9.5, 1e-15);
  // CCW seen from the camera (+Z side): front, kept by back-face culling.
  EXPECT_EQ(tris[0].cull, CullMode::Back);
  EXPECT_TRUE(survivesCulling(tris[0].grid()));
}

TEST(ReferenceProjection, PerspectiveNearClipKeepsTheVisiblePart) {
  Camera camera;
  camera.yfov = 1.5f;
  const double f = 1.0 / std::tan(0.75);
  camera.znear = 1.0f;
  camera.zfar = 0.0f;
  // A ground triangle from 9 units in front of the camera to behind it.
  const glm::dvec3 a(-1, -1, -9), b(1, -1, -9), c(0, -1, 1);
  const Scene scene = oneTriangleScene(a, b, c);
  const auto tris = projectScene(scene, camera, 200, 100);
  ASSERT_EQ(tris.size(), 2u);  // a quadrilateral after the near clip
  for (const ProjectedTriangle& t : tris)
    for (const ProjectedVertex& v : t.v) {
      EXPECT_GE(v.depth, -1e-15);
      EXPECT_GE(v.clipW, 1.0 - 1e-12);
      EXPECT_NEAR(v.sourceBary.x + v.sourceBary.y + v.sourceBary.z, 1.0, 1e-12);
      // Interpolated source position reprojects to the window position.
      const glm::dvec3 p = v.sourceBary.x * a + v.sourceBary.y * b + v.sourceBary.z * c;
      const double aspect = 2.0;
      EXPECT_NEAR(v.windowExact.x, (f * p.x / aspect / -p.z + 1.0) * 100.0, 1e-9);
      EXPECT_NEAR(v.windowExact.y, (1.0 - f * p.y / -p.z) * 50.0, 1e-9);
    }
  // Infinite far plane: depth = 1 - znear / distance at a far vertex.
  EXPECT_NEAR(tris[0].v[0].depth, 1.0 - 1.0 / 9.0, 1e-12);
}

}  // namespace
}  // namespace quadra::ref
