// The hard-case scenes (see hard_case_scenes.h). Perspective scenes use an
// untextured-looking 2x2 texture: what matters is TEXCOORD_0, which every
// mesh sets to an affine function of position so its exact value anywhere on
// a triangle's plane is known.
#include "lab/scene/hard_case_scenes.h"

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace quadra {

namespace {

using Triangle = std::array<glm::vec3, 3>;
using UvOfPosition = glm::vec2 (*)(const glm::vec3&);

Camera lookAtCamera(const glm::vec3& eye, const glm::vec3& target, float yfov, float znear,
                    float zfar) {
  Camera camera;
  camera.world = glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
  camera.yfov = yfov;
  camera.znear = znear;
  camera.zfar = zfar;
  return camera;
}

// A scene of one double-sided material reading TEXCOORD_0 from a small
// nearest-filtered texture, and no meshes yet.
Scene texturedScene(const std::string& name) {
  Scene scene;
  scene.name = "builtin:" + name;
  Image image(2, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const float shade = (x + y) % 2 ? 0.8f : 0.3f;
      float* texel = image.texel(x, y);
      texel[0] = shade, texel[1] = shade, texel[2] = 0.6f, texel[3] = 1.0f;
    }
  SamplerState sampler;
  sampler.wrapU = sampler.wrapV = WrapMode::Repeat;
  scene.textures.push_back(
      std::make_shared<const Texture>(std::make_shared<const Image>(std::move(image)), sampler));
  Material material;
  material.doubleSided = true;
  material.baseColorTexture = 0;
  scene.materials.push_back(material);
  return scene;
}

// Appends a mesh of the triangles (unshared vertices) with uv = uvOf(position)
// and one identity instance of it.
void addTriangles(Scene& scene, const std::vector<Triangle>& triangles, UvOfPosition uvOf,
                  int material = 0) {
  Mesh mesh;
  for (const Triangle& t : triangles)
    for (const glm::vec3& p : t) {
      mesh.indices.push_back(std::uint32_t(mesh.positions.size()));
      mesh.positions.push_back(p);
      mesh.texcoords[0].push_back(uvOf(p));
    }
  mesh.material = material;
  scene.meshes.push_back(std::move(mesh));
  scene.instances.push_back({int(scene.meshes.size()) - 1, glm::mat4(1.0f)});
}

glm::vec2 groundUv(const glm::vec3& p) {
  return {p.x / 4.0f, p.z / 4.0f};
}

glm::vec2 wallUv(const glm::vec3& p) {
  return {p.x / 4.0f, p.y / 4.0f};
}

Triangle windowTriangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return {worldFromWindow(a.x, a.y), worldFromWindow(b.x, b.y), worldFromWindow(c.x, c.y)};
}

// ---- perspective cases ----------------------------------------------------------

// A ground triangle whose two back vertices are 5 units behind the eye (w < 0)
// and 1e4 to the sides, so the near plane cuts it along a visible line; and a
// ceiling triangle with one vertex exactly on the eye plane (w = 0).
Scene nearPlane() {
  Scene scene = texturedScene("near-plane");
  addTriangles(scene, {{{{-1e4f, -0.5f, 5.0f}, {1e4f, -0.5f, 5.0f}, {0.0f, -0.5f, -60.0f}}}},
               groundUv);
  addTriangles(scene, {{{{0.0f, 0.5f, 0.0f}, {-40.0f, 0.5f, -30.0f}, {40.0f, 0.5f, -30.0f}}}},
               groundUv);
  scene.cameras.push_back(lookAtCamera({0, 0, 0}, {0, 0, -1}, 0.9f, 2.0f, 0.0f));
  return scene;
}

// A ground fan around a hub below and 0.5 behind the eye: 12 rim vertices
// `extent` away in every direction, so half the rim is behind the eye (w < 0),
// each rim edge that passes behind crosses the w = 0 plane `extent` to the
// side, and each edge from the hub to a rim vertex ahead crosses the near
// plane next to the eye (a crossing from the far end lands anywhere); and a
// wall triangle 6 ahead with one vertex `extent` to the right. At 1e6
// (a float position's ulp is 1/16) the ground's TEXCOORD_0 is (x, z) / 4, so
// texture coordinates near the eye come from vertices 1e6 away. At 1e30
// (~1e29 pixels beyond the guard band) it is 0.5 + (x, z) / 2e30 instead: a
// coordinate of 1e29 at every rim vertex could not be interpolated back to
// the eye in any floating-point format (the wall's single far vertex can).
Scene hugeCoordinates(const std::string& name, float extent) {
  Scene scene = texturedScene(name);
  const glm::vec3 hub(0.0f, -1.0f, 0.5f);
  constexpr int kRim = 12;
  std::vector<Triangle> fan;
  const auto rim = [&](int i) {
    const float angle = 2.0f * std::numbers::pi_v<float> * (float(i % kRim) + 0.3f) / kRim;
    return hub + extent * glm::vec3(std::cos(angle), 0.0f, std::sin(angle));
  };
  for (int i = 0; i < kRim; ++i) fan.push_back({hub, rim(i), rim(i + 1)});
  const UvOfPosition farGroundUv = [](const glm::vec3& p) {
    return glm::vec2(0.5f + 0.5e-30f * p.x, 0.5f + 0.5e-30f * p.z);
  };
  addTriangles(scene, fan, extent <= 1e6f ? groundUv : farGroundUv);
  addTriangles(scene, {{{{extent, 0.3f, -6.0f}, {-3.0f, -1.0f, -6.0f}, {-3.0f, 2.0f, -6.0f}}}},
               wallUv);
  scene.cameras.push_back(lookAtCamera({0, 0, 0}, {0, 0, -1}, 0.9f, 0.1f, 0.0f));
  return scene;
}

// A ground plane 1e4 units long seen from 0.05 above it, looking along it: the
// far part is at a grazing angle of a few thousandths of a degree.
Scene grazing() {
  Scene scene = texturedScene("grazing");
  const glm::vec3 a(-50.0f, 0.0f, -0.2f), b(50.0f, 0.0f, -0.2f), c(50.0f, 0.0f, -1e4f),
      d(-50.0f, 0.0f, -1e4f);
  addTriangles(scene, {{{a, b, c}}, {{a, c, d}}}, groundUv);
  scene.cameras.push_back(lookAtCamera({0, 0.05f, 0}, {0, 0.05f, -1}, 0.9f, 0.1f, 0.0f));
  return scene;
}

// A closed mesh: a UV sphere whose vertex radii are random in [0.6, 1.4]
// (star-shaped, so still closed and manifold), 2 units ahead. Every pixel
// centre's ray crosses its surface an even number of times.
Scene closedMesh() {
  Scene scene = texturedScene("closed-mesh");
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> radius(0.6f, 1.4f);
  constexpr int kStacks = 24, kSlices = 40;
  Mesh mesh;
  const glm::vec3 centre(0.0f, 0.0f, -2.5f);
  mesh.positions.push_back(centre + glm::vec3(0, radius(rng), 0));  // north pole
  for (int i = 1; i < kStacks; ++i) {
    const float theta = std::numbers::pi_v<float> * float(i) / kStacks;
    for (int j = 0; j < kSlices; ++j) {
      const float phi = 2.0f * std::numbers::pi_v<float> * float(j) / kSlices;
      const glm::vec3 dir(std::sin(theta) * std::cos(phi), std::cos(theta),
                          std::sin(theta) * std::sin(phi));
      mesh.positions.push_back(centre + radius(rng) * dir);
    }
  }
  mesh.positions.push_back(centre - glm::vec3(0, radius(rng), 0));  // south pole
  const auto ring = [](int i, int j) { return std::uint32_t(1 + (i - 1) * kSlices + j % kSlices); };
  const auto south = std::uint32_t(mesh.positions.size() - 1);
  for (int j = 0; j < kSlices; ++j) {
    mesh.indices.insert(mesh.indices.end(), {0, ring(1, j + 1), ring(1, j)});
    for (int i = 1; i + 1 < kStacks; ++i)
      mesh.indices.insert(mesh.indices.end(), {ring(i, j), ring(i, j + 1), ring(i + 1, j + 1),
                                               ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)});
    mesh.indices.insert(mesh.indices.end(),
                        {ring(kStacks - 1, j), ring(kStacks - 1, j + 1), south});
  }
  for (const glm::vec3& p : mesh.positions) mesh.texcoords[0].push_back(groundUv(p));
  mesh.material = 0;
  scene.meshes.push_back(std::move(mesh));
  scene.instances.push_back({0, glm::mat4(1.0f)});
  scene.cameras.push_back(lookAtCamera({0.3f, 0.2f, 0}, {0, 0, -2.5f}, 0.9f, 0.1f, 0.0f));
  return scene;
}

// ---- pixel-exact (orthographic) cases --------------------------------------------

Scene pixelExactScene(const std::string& name) {
  Scene scene = texturedScene(name);
  scene.cameras.push_back(pixelExactCamera());
  return scene;
}

glm::vec2 windowUv(const glm::vec3& p) {
  return {p.x / 64.0f, p.y / 64.0f};
}

// 1000:1 slivers at many angles, sub-pixel triangles, and 1-pixel-wide
// triangles from corner to corner across every tile row and column.
Scene slivers() {
  Scene scene = pixelExactScene("slivers");
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> grid(0, kPixelExactSize * 256);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
  const auto onGrid = [&] { return glm::dvec2(grid(rng), grid(rng)) / 256.0; };
  const auto snap = [](const glm::dvec2& p) { return glm::round(p * 256.0) / 256.0; };
  std::vector<Triangle> triangles;
  for (int n = 0; n < 120; ++n) {  // 200 px long, 0.2 px wide
    const glm::dvec2 at = onGrid() * 0.5 + 64.0;
    const double a = angle(rng);
    const glm::dvec2 along(std::cos(a), std::sin(a)), across(-along.y, along.x);
    triangles.push_back(windowTriangle(snap(at - 100.0 * along), snap(at + 100.0 * along),
                                       snap(at + 0.2 * across)));
  }
  std::uniform_int_distribution<int> tiny(-96, 96);  // within 0.375 px
  for (int n = 0; n < 3000; ++n) {
    const glm::dvec2 at = onGrid();
    triangles.push_back(windowTriangle(at, at + glm::dvec2(tiny(rng), tiny(rng)) / 256.0,
                                       at + glm::dvec2(tiny(rng), tiny(rng)) / 256.0));
  }
  for (int k = 0; k < 8; ++k) {  // long and thin, crossing tiles diagonally
    const double shift = 32.0 * k;
    triangles.push_back(windowTriangle({0.0, shift}, {256.0 - shift, 256.0}, {1.0, shift}));
    triangles.push_back(windowTriangle({shift, 0.0}, {256.0, 256.0 - shift}, {shift, 1.0}));
  }
  addTriangles(scene, triangles, windowUv);
  return scene;
}

// A grid over the left half (lines on tile, block and pixel-centre positions,
// inner vertices jittered by half pixels, random diagonals, alternating
// windings) and fans in the right half around centres on a pixel centre, a
// tile corner and neither, with rim vertices on pixel centres and borders.
Scene watertight() {
  Scene scene = pixelExactScene("watertight");
  std::mt19937 rng(5);
  const std::vector<double> lines = {-10.0, 0.0,  8.0,  16.5, 24.0,  32.0,  40.5,  48.0, 56.25,
                                     64.0,  72.5, 80.0, 96.0, 104.5, 112.0, 120.0, 128.0};
  const int n = int(lines.size());
  std::vector<glm::dvec2> vertex(std::size_t(n * n));
  std::bernoulli_distribution coin(0.5);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      glm::dvec2 p(lines[i], lines[j] * 2.0);  // rows twice as tall: reach y = 256
      const bool inner = i > 0 && j > 0 && i + 1 < n && j + 1 < n;
      if (inner && coin(rng)) p += glm::dvec2(coin(rng) ? 0.5 : -0.5, coin(rng) ? 0.5 : -0.5);
      vertex[std::size_t(j * n + i)] = p;
    }
  // The last column stays at x = 128 exactly: the grid's right border.
  std::vector<Triangle> triangles;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const glm::dvec2 a = vertex[std::size_t(j * n + i)], b = vertex[std::size_t(j * n + i + 1)],
                       c = vertex[std::size_t((j + 1) * n + i + 1)],
                       d = vertex[std::size_t((j + 1) * n + i)];
      if (coin(rng)) {
        triangles.push_back(windowTriangle(a, b, c));
        triangles.push_back(windowTriangle(a, d, c));  // opposite winding: both drawn
      } else {
        triangles.push_back(windowTriangle(a, b, d));
        triangles.push_back(windowTriangle(b, c, d));
      }
    }
  const glm::dvec2 centres[] = {{168.5, 40.5}, {192.0, 128.0}, {170.3, 210.7}};
  for (const glm::dvec2& centre : centres) {
    constexpr int kRim = 23;
    for (int k = 0; k < kRim; ++k) {
      const auto rim = [&](int i) {
        const double a = 2.0 * std::numbers::pi * i / kRim;
        return glm::round((centre + 36.0 * glm::dvec2(std::cos(a), std::sin(a))) * 2.0) / 2.0;
      };
      triangles.push_back(windowTriangle(centre, rim(k), rim(k + 1)));
    }
  }
  addTriangles(scene, triangles, windowUv);
  return scene;
}

// Valid triangles, degenerate ones (collinear, repeated index, one vertex
// three times, thinner than the snapping grid) in instance 0, and triangles
// with NaN or Inf in a position or a texture coordinate in instance 1. The
// material reads TEXCOORD_0, so the texture coordinates matter.
Scene invalidInput() {
  Scene scene = pixelExactScene("invalid-input");
  Mesh good;
  const auto add = [](Mesh& mesh, const glm::vec3& p, const glm::vec2& uv) {
    mesh.positions.push_back(p);
    mesh.texcoords[0].push_back(uv);
    return std::uint32_t(mesh.positions.size() - 1);
  };
  const auto w = [](double x, double y) { return worldFromWindow(x, y); };
  const std::uint32_t a = add(good, w(20, 20), {0, 0}), b = add(good, w(230, 30), {1, 0}),
                      c = add(good, w(120, 240), {0, 1}), d = add(good, w(60, 60), {0.5f, 0.5f}),
                      e = add(good, w(100, 100), {0.2f, 0.2f}),
                      f = add(good, w(140, 140), {0.4f, 0.4f}),
                      g = add(good, w(200.5, 200.5), {0, 0}),
                      h = add(good, w(200.5 + 1.0 / 1024, 220.5), {0, 0}),
                      i = add(good, w(200.5 - 1.0 / 1024, 240.5), {0, 0});
  good.indices = {a, b, c,   // valid
                  d, e, f,   // collinear
                  a, a, b,   // repeated index
                  c, c, c,   // one vertex three times
                  g, h, i,   // collinear only after snapping
                  d, b, e};  // valid
  good.material = 0;
  Mesh bad;
  constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const glm::vec3 p0 = w(10, 200), p1 = w(90, 250), p2 = w(50, 130);
  const glm::vec2 uv(0.5f, 0.5f);
  struct Corner {
    glm::vec3 position;
    glm::vec2 texcoord;
  };
  const Corner broken[][3] = {
      {{{kNan, p0.y, p0.z}, uv}, {p1, uv}, {p2, uv}},
      {{p0, uv}, {{p1.x, kInf, p1.z}, uv}, {p2, uv}},
      {{p0, uv}, {p1, uv}, {{p2.x, p2.y, -kInf}, uv}},
      {{p0, {kNan, 0.5f}}, {p1, uv}, {p2, uv}},
      {{p0, uv}, {p1, {0.5f, kInf}}, {p2, uv}},
  };
  for (const auto& triangle : broken)
    for (const Corner& corner : triangle)
      bad.indices.push_back(add(bad, corner.position, corner.texcoord));
  bad.material = 0;
  scene.meshes = {good, bad};
  scene.instances = {{0, glm::mat4(1.0f)}, {1, glm::mat4(1.0f)}};
  return scene;
}

}  // namespace

Camera pixelExactCamera() {
  Camera camera;
  camera.type = Camera::Type::Orthographic;
  camera.xmag = camera.ymag = kPixelExactSize / 2;
  camera.znear = 0.5f;
  camera.zfar = 4.0f;
  return camera;
}

glm::vec3 worldFromWindow(double windowX, double windowY) {
  return {float(windowX - kPixelExactSize / 2), float(kPixelExactSize / 2 - windowY), -1.0f};
}

Scene zFightingScene(double distance, double separation) {
  Scene scene;
  scene.name = "builtin:z-fighting";
  Material green, red;
  green.baseColorFactor = {0.0f, 1.0f, 0.0f, 1.0f};
  red.baseColorFactor = {1.0f, 0.0f, 0.0f, 1.0f};
  scene.materials = {green, red};
  const float half = float(distance * 2.0);
  const auto facingQuad = [half](double z, int material) {
    Mesh mesh;
    const float depth = float(z);
    mesh.positions = {
        {-half, -half, depth}, {half, -half, depth}, {half, half, depth}, {-half, half, depth}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.material = material;
    return mesh;
  };
  scene.meshes = {facingQuad(-(distance + separation), 0), facingQuad(-distance, 1)};
  scene.instances = {{0, glm::mat4(1.0f)}, {1, glm::mat4(1.0f)}};  // the far one first
  Camera camera;
  camera.yfov = 0.8f;
  camera.znear = 1e-3f;
  camera.zfar = 1e6f;
  scene.cameras = {camera};
  return scene;
}

Scene randomTrianglesScene(int count, std::uint32_t seed) {
  Scene scene = pixelExactScene("random-triangles");
  std::mt19937 rng(seed);
  const int size = kPixelExactSize;
  std::uniform_int_distribution<int> halfPixel(-40 * 2, (size + 40) * 2);
  std::uniform_int_distribution<int> subpixel(-40 * 256, (size + 40) * 256);
  std::uniform_int_distribution<int> small(-6 * 256, 6 * 256);
  std::vector<Triangle> triangles;
  for (int n = 0; n < count; ++n) {
    std::array<glm::dvec2, 3> t;
    if (n % 3 == 0) {
      for (glm::dvec2& p : t) p = {halfPixel(rng) / 2.0, halfPixel(rng) / 2.0};
    } else if (n % 3 == 1) {
      for (glm::dvec2& p : t) p = {subpixel(rng) / 256.0, subpixel(rng) / 256.0};
    } else {
      const glm::dvec2 at(subpixel(rng) / 256.0, subpixel(rng) / 256.0);
      for (glm::dvec2& p : t) p = at + glm::dvec2(small(rng), small(rng)) / 256.0;
    }
    triangles.push_back(windowTriangle(t[0], t[1], t[2]));
  }
  addTriangles(scene, triangles, windowUv);
  return scene;
}

Scene groundPlaneScene(int cellsPerSide) {
  QUADRA_CHECK(cellsPerSide >= 1);
  Scene scene = texturedScene(cellsPerSide == 1 ? "shared-edge" : "subpixel-plane");
  std::vector<Triangle> triangles;
  const float dx = 2.0f * kGroundHalfWidth / float(cellsPerSide);
  const float dz = (kGroundFarZ - kGroundNearZ) / float(cellsPerSide);
  for (int j = 0; j < cellsPerSide; ++j)
    for (int i = 0; i < cellsPerSide; ++i) {
      const float x0 = -kGroundHalfWidth + dx * float(i), z0 = kGroundNearZ + dz * float(j);
      const float x1 = i + 1 == cellsPerSide ? kGroundHalfWidth : x0 + dx;
      const float z1 = j + 1 == cellsPerSide ? kGroundFarZ : z0 + dz;
      const glm::vec3 a(x0, kGroundY, z0), b(x1, kGroundY, z0), c(x1, kGroundY, z1),
          d(x0, kGroundY, z1);
      triangles.push_back({a, b, c});
      triangles.push_back({a, c, d});
    }
  addTriangles(scene, triangles, groundUv);
  scene.cameras.push_back(lookAtCamera({0, 0, 0}, {0, -1, -1.9f}, 0.9f, 0.1f, 0.0f));
  return scene;
}

namespace {

struct HardCase {
  const char* name;
  Scene (*make)();
};

// The one list of hard cases, in report order.
const HardCase kHardCases[] = {
    {"near-plane", nearPlane},
    {"huge-1e6", [] { return hugeCoordinates("huge-1e6", 1e6f); }},
    {"huge-1e30", [] { return hugeCoordinates("huge-1e30", 1e30f); }},
    {"grazing", grazing},
    {"slivers", slivers},
    {"watertight", watertight},
    {"closed-mesh", closedMesh},
    {"random-triangles", [] { return randomTrianglesScene(20000, 1); }},
    {"z-fighting", [] { return zFightingScene(1e3, 0.01); }},
    {"invalid-input", invalidInput},
    {"shared-edge", [] { return groundPlaneScene(1); }},
    {"subpixel-plane", [] { return groundPlaneScene(200); }},
};

}  // namespace

std::vector<std::string> hardCaseSceneNames() {
  std::vector<std::string> names;
  for (const HardCase& c : kHardCases) names.push_back(c.name);
  return names;
}

bool makeHardCaseScene(const std::string& name, Scene& out) {
  for (const HardCase& c : kHardCases)
    if (name == c.name) {
      out = c.make();
      return true;
    }
  return false;
}

}  // namespace quadra
