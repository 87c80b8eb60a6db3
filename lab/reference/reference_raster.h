// The test suite's exact reference rasterizer: coverage of window-space
// triangles on the 1/256-pixel grid, decided in 128-bit integers from the
// conventions as DESIGN.md states them (not from the engine's code), plus the
// double-precision projection that turns a Scene seen through a Camera into
// such triangles, so a test can feed one scene to both the engine and this.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace quadra::ref {

constexpr int kSubpixelUnits = 256;  // window coordinates snap to 1/256 pixel

// A window-space point on the 1/256-pixel grid (y down).
struct GridPoint {
  std::int64_t x = 0;
  std::int64_t y = 0;
};

// Which facing the reference drops. Front faces run counter-clockwise in NDC
// (y up), which is counter-clockwise as seen on screen too: in window
// coordinates (y down) they have a negative doubleSignedArea.
enum class CullMode : std::uint8_t {
  None,   // double-sided: both windings are drawn
  Back,   // the glTF default
  Front,  // a single-sided material on an instance with a mirroring matrix
};

struct GridTriangle {
  std::array<GridPoint, 3> v;
  CullMode cull = CullMode::None;
};

// Window coordinate (pixels) → grid units, rounded to nearest, ties to even.
std::int64_t snapToGrid(double windowCoordinate);
// A triangle given in pixels, snapped.
GridTriangle snapTriangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                          CullMode cull = CullMode::None);

// (towards - origin) x (p - origin), exactly.
__int128 cross(const GridPoint& origin, const GridPoint& towards, const GridPoint& p);

// Twice the signed area in grid units², (b - a) x (c - a) in window
// coordinates: positive when the vertices run clockwise as seen (a back face).
__int128 doubleSignedArea(const GridTriangle& t);

// Whether the triangle covers grid point p under the top-left rule, ignoring
// culling. Zero-area triangles cover nothing.
bool coversPoint(const GridTriangle& t, const GridPoint& p);
// The same at the centre of pixel (px, py).
bool coversPixelCentre(const GridTriangle& t, std::int64_t px, std::int64_t py);

// Sample `sample` of pixel (px, py) among `samplesPerPixel` (1, 2, 4, 8, 16),
// at Direct3D's standard multisample positions as this file states them
// (from the pixel's top-left corner, in 1/16 pixel; one sample: the centre).
GridPoint samplePoint(std::int64_t px, std::int64_t py, int sample, int samplesPerPixel);
// Whether the culling mode of t keeps it.
bool survivesCulling(const GridTriangle& t);

struct CoverageImage {
  int width = 0;
  int height = 0;
  // Triangles covering each pixel centre; with several samples per pixel,
  // the covered samples summed over the triangles.
  std::vector<int> count;
  std::vector<int> lastTriangle;  // index of the last covering triangle, -1 for none

  int at(int x, int y) const { return count[std::size_t(y) * std::size_t(width) + x]; }
};

// Coverage of a width x height viewport by the triangles, in order, at
// samplePoint's positions (lastTriangle: the last to cover any sample).
CoverageImage rasterizeCoverage(const std::vector<GridTriangle>& triangles, int width, int height,
                                int samplesPerPixel = 1);

// ---------------------------------------------------------------------------
// Projection of a scene, in double, per the camera conventions.

// A vertex after projection: where it lands and where it came from, so a test
// can interpolate any attribute of the source triangle.
struct ProjectedVertex {
  glm::dvec2 window;       // snapped to the 1/256 grid
  glm::dvec2 windowExact;  // before snapping
  double depth = 0.0;      // z_ndc in [0, 1]
  double clipW = 1.0;      // w_c (view depth for perspective, 1 for orthographic)
  glm::dvec3 sourceBary;   // barycentric weights of the source triangle's vertices
};

// One source triangle's contribution; a triangle clipped by the near or far
// plane becomes a fan of several, all with the same source.
struct ProjectedTriangle {
  std::array<ProjectedVertex, 3> v;
  int instance = 0;
  int triangle = 0;  // index within the instance's mesh
  CullMode cull = CullMode::None;

  GridTriangle grid() const;
};

// View matrix per DESIGN.md: the inverse of the camera-to-world matrix with the
// scale of its axes removed.
glm::dmat4 referenceViewMatrix(const Camera& camera);
// Clip coordinates of a view-space point: x_c, y_c, z_c, w_c (depth = z_c / w_c).
glm::dvec4 referenceClip(const Camera& camera, double aspect, const glm::dvec3& viewPoint);

// |x|, |y| <= kReferenceGuard * w in clip space: 2^20 viewport half-widths,
// so snapped coordinates stay within int64 (and their products within
// int128) for vertices at any finite distance, e.g. 1e30.
constexpr double kReferenceGuard = 0x1p20;

// Every instance triangle of the scene in submission order (instances, then
// triangles), clipped in double against the near (and a finite far) plane
// and the sides at kReferenceGuard (never near the viewport), projected and
// snapped. The integer rasterizer takes any window coordinate in that range.
std::vector<ProjectedTriangle> projectScene(const Scene& scene, const Camera& camera, int width,
                                            int height);

std::vector<GridTriangle> gridTriangles(const std::vector<ProjectedTriangle>& projected);

// Distance from p to the segment a-b, and to the nearest edge of any of the
// projected (snapped) triangles: how close a pixel centre is to where
// snapping or clipping may legitimately decide its coverage either way.
double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b);
double distanceToEdges(const std::vector<ProjectedTriangle>& triangles, const glm::dvec2& p);

}  // namespace quadra::ref
