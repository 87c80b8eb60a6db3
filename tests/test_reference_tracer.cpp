// Self-tests of the double-precision reference ray caster
// (lab/reference/reference_tracer.h) against closed-form answers:
// box-filtered bilinear textures via hat-function integrals, exact
// pixel/half-plane areas, alpha compositing by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "api/renderer.h"
#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"
#include "param_names.h"

namespace quadra::ref {

namespace {

// Antiderivative of the unit hat function max(0, 1 - |t|).
double hatIntegralUpTo(double t) {
  if (t <= -1.0) return 0.0;
  if (t <= 0.0) return 0.5 * (t + 1.0) * (t + 1.0);
  if (t <= 1.0) return 1.0 - 0.5 * (1.0 - t) * (1.0 - t);
  return 1.0;
}

// Bilinear reconstruction is sum_i T[wrap(i)] hat(s - i) in texel space s; its
// mean over [s0, s1] weights texel i by the hat's integral there.
std::vector<std::pair<std::int64_t, double>> hatWeights(double s0, double s1) {
  std::vector<std::pair<std::int64_t, double>> weights;
  const double lo = std::min(s0, s1), hi = std::max(s0, s1);
  for (auto i = std::int64_t(std::floor(lo)) - 1; i <= std::int64_t(std::ceil(hi)) + 1; ++i) {
    const double w =
        (hatIntegralUpTo(s1 - double(i)) - hatIntegralUpTo(s0 - double(i))) / (s1 - s0);
    if (w != 0.0) weights.push_back({i, w});
  }
  return weights;
}

glm::dvec4 texelAt(const Image& image, int x, int y) {
  const float* t = image.texel(x, y);
  return {t[0], t[1], t[2], t[3]};
}

struct QuadSetup {
  Scene scene;
  Camera camera;
};

// An orthographic camera whose view is exactly filled by a textured quad at
// z = -1 with uv running over [uv0, uv1] (u left to right, v top to bottom).
QuadSetup fullScreenQuad(int width, int height, Image texture, const SamplerState& sampler,
                         const glm::dvec2& uv0, const glm::dvec2& uv1) {
  QuadSetup s;
  s.camera.type = Camera::Type::Orthographic;
  s.camera.ymag = 1.0f;
  s.camera.znear = 0.5f;
  s.camera.zfar = 2.0f;
  const float hx = float(width) / float(height);
  Mesh mesh;
  mesh.positions = {{-hx, 1, -1}, {hx, 1, -1}, {hx, -1, -1}, {-hx, -1, -1}};
  mesh.texcoords[0] = {glm::vec2(uv0.x, uv0.y), glm::vec2(uv1.x, uv0.y), glm::vec2(uv1.x, uv1.y),
                       glm::vec2(uv0.x, uv1.y)};
  mesh.colors = std::vector<glm::vec4>(4, glm::vec4(0.5f, 1.0f, 1.0f, 1.0f));
  mesh.indices = {0, 3, 2, 0, 2, 1};  // counter-clockwise seen from the camera
  mesh.material = 0;
  Material material;
  material.baseColorFactor = {1.0f, 0.25f, 1.0f, 1.0f};
  material.baseColorTexture = 0;
  s.scene.meshes.push_back(mesh);
  s.scene.materials.push_back(material);
  s.scene.textures.push_back(
      std::make_shared<Texture>(std::make_shared<Image>(std::move(texture)), sampler));
  s.scene.instances.push_back(Instance{});
  return s;
}

Image randomImage(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  Image image(width, height);
  for (float& v : image.rgba) v = value(rng);
  return image;
}

// Renders the quad and compares every pixel to the exact box filter of the
// bilinear reconstruction (times the constant factor and vertex colour).
double maxQuadError(int width, int height, const Image& texture, const SamplerState& sampler,
                    const glm::dvec2& uv0, const glm::dvec2& uv1, int samplesPerAxis) {
  const QuadSetup s = fullScreenQuad(width, height, texture, sampler, uv0, uv1);
  const Image rendered = ReferenceTracer(s.scene, s.camera, width, height).render(samplesPerAxis);
  const glm::dvec4 tint(0.5, 0.25, 1.0, 1.0);
  double worst = 0.0;
  for (int y = 0; y < height; ++y) {
    const double v0 = uv0.y + (uv1.y - uv0.y) * y / height;
    const double v1 = uv0.y + (uv1.y - uv0.y) * (y + 1) / height;
    const auto wy = hatWeights(v0 * texture.height - 0.5, v1 * texture.height - 0.5);
    for (int x = 0; x < width; ++x) {
      const double u0 = uv0.x + (uv1.x - uv0.x) * x / width;
      const double u1 = uv0.x + (uv1.x - uv0.x) * (x + 1) / width;
      const auto wx = hatWeights(u0 * texture.width - 0.5, u1 * texture.width - 0.5);
      glm::dvec4 expected(0.0);
      for (const auto& [j, weightY] : wy)
        for (const auto& [i, weightX] : wx) {
          const std::int64_t ti = wrapTexel(i, texture.width, sampler.wrapU);
          const std::int64_t tj = wrapTexel(j, texture.height, sampler.wrapV);
          const glm::dvec4 texel = (ti < 0 || tj < 0)
                                       ? glm::dvec4(sampler.borderColor[0], sampler.borderColor[1],
                                                    sampler.borderColor[2], sampler.borderColor[3])
                                       : texelAt(texture, int(ti), int(tj));
          expected += weightX * weightY * texel;
        }
      expected *= tint;
      expected = glm::dvec4(glm::dvec3(expected), 1.0);  // OPAQUE: alpha 1
      for (int c = 0; c < 4; ++c)
        worst = std::max(worst, std::fabs(double(rendered.texel(x, y)[c]) - expected[c]));
    }
  }
  return worst;
}

TEST(ReferenceTracer, BilinearWrapModesAtTexelCentresAndBetween) {
  Image image(2, 1);
  image.texel(0, 0)[0] = 1.0f;
  image.texel(1, 0)[0] = 3.0f;
  SamplerState sampler;
  sampler.wrapU = WrapMode::Repeat;
  EXPECT_DOUBLE_EQ(sampleBilinear(image, sampler, {0.25, 0.5}).r, 1.0);
  EXPECT_DOUBLE_EQ(sampleBilinear(image, sampler, {0.5, 0.5}).r, 2.0);
  EXPECT_DOUBLE_EQ(sampleBilinear(image, sampler, {0.0, 0.5}).r, 2.0);  // wraps to texel 1
  sampler.wrapU = WrapMode::ClampToEdge;
  EXPECT_DOUBLE_EQ(sampleBilinear(image, sampler, {0.0, 0.5}).r, 1.0);
  EXPECT_DOUBLE_EQ(sampleBilinear(image, sampler, {-3.0, 0.5}).r, 1.0);
  sampler.wrapU = WrapMode::MirroredRepeat;
  EXPECT_DOUBLE_EQ(sampleBilinear(image, sampler, {-0.25, 0.5}).r, 1.0);  // texel -1 mirrors to 0
  EXPECT_DOUBLE_EQ(sampleBilinear(image, sampler, {1.25, 0.5}).r, 3.0);   // texel 2 mirrors to 1
  sampler.wrapU = WrapMode::ClampToBorder;
  sampler.borderColor[0] = 5.0f;
  EXPECT_DOUBLE_EQ(sampleBilinear(image, sampler, {0.0, 0.5}).r, 3.0);  // half border, half texel 0
}

// Texel centres land on pixel edges (8 texels over 32 pixels), so every
// subsample cell sees one bilinear patch and the midpoint rule is exact.
TEST(ReferenceTracer, FullScreenQuadIsTheBoxFilteredTexture) {
  const Image texture = randomImage(8, 4, 7);
  EXPECT_LT(maxQuadError(32, 16, texture, SamplerState{}, {0, 0}, {1, 1}, 4), 1e-6);
}

// Texel centres anywhere and uv outside [0, 1]: the stratified average only
// converges, with a midpoint-rule error below (slope jump) * h^2 / 8 per kink.
TEST(ReferenceTracer, FullScreenQuadWrapModesConverge) {
  const Image texture = randomImage(5, 3, 11);
  for (const WrapMode mode : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge,
                              WrapMode::ClampToBorder}) {
    SamplerState sampler;
    sampler.wrapU = sampler.wrapV = mode;
    sampler.borderColor[1] = 0.75f;
    SCOPED_TRACE(wrapName(mode));
    EXPECT_LT(maxQuadError(24, 12, texture, sampler, {-0.7, 1.4}, {1.6, -0.3}, 16), 2e-3);
  }
}

// Area of the unit pixel square [x, x+1] x [y, y+1] where (b - a) x (p - a) >= 0,
// by clipping the square against the line.
double pixelAreaLeftOf(const glm::dvec2& a, const glm::dvec2& b, int x, int y) {
  const glm::dvec2 square[4] = {{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}};
  std::vector<glm::dvec2> kept;
  const auto side = [&](const glm::dvec2& p) {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
  };
  for (int i = 0; i < 4; ++i) {
    const glm::dvec2 &p = square[i], &q = square[(i + 1) % 4];
    const double sp = side(p), sq = side(q);
    if (sp >= 0) kept.push_back(p);
    if ((sp >= 0) != (sq >= 0)) kept.push_back(p + (q - p) * (sp / (sp - sq)));
  }
  double twiceArea = 0.0;
  for (std::size_t i = 0; i < kept.size(); ++i)
    twiceArea +=
        kept[i].x * kept[(i + 1) % kept.size()].y - kept[(i + 1) % kept.size()].x * kept[i].y;
  return std::fabs(twiceArea) / 2.0;
}

// A huge perspective triangle with one slanted edge across the view: each
// pixel's alpha is the covered fraction of its square. Counting an S x S grid
// under a straight edge misses less than one sample per column: error < 1/S.
TEST(ReferenceTracer, EdgeCoverageIsThePixelArea) {
  Scene scene;
  Mesh mesh;
  // The edge from a to b crosses the whole view; c and the other edges are far
  // outside it.
  const glm::dvec3 a(-2.7, -7, -2), b(2.9, 7, -2), c(-60, 0, -2);
  mesh.positions = {glm::vec3(a), glm::vec3(b), glm::vec3(c)};
  mesh.indices = {0, 1, 2};
  scene.meshes.push_back(mesh);
  scene.instances.push_back(Instance{});
  Camera camera;
  camera.yfov = 1.0f;
  const int width = 24, height = 16, samples = 32;
  const ReferenceTracer tracer(scene, camera, width, height);
  const Image image = tracer.render(samples);
  // The edge's end points in window space.
  const double f = 1.0 / std::tan(0.5), aspect = double(width) / height;
  const auto toWindow = [&](const glm::dvec3& p) {
    return glm::dvec2((f / aspect * p.x / -p.z + 1.0) * width / 2,
                      (1.0 - f * p.y / -p.z) * height / 2);
  };
  glm::dvec2 from = toWindow(a), to = toWindow(b);
  const glm::dvec2 inside = toWindow(c);
  if ((to.x - from.x) * (inside.y - from.y) - (to.y - from.y) * (inside.x - from.x) < 0)
    std::swap(from, to);
  int partial = 0, full = 0, empty = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double area = pixelAreaLeftOf(from, to, x, y);
      partial += area > 0.0 && area < 1.0, full += area == 1.0, empty += area == 0.0;
      ASSERT_NEAR(image.texel(x, y)[3], area, 1.0 / samples) << x << "," << y;
    }
  EXPECT_GT(partial, 10);
  EXPECT_GT(full, 10);
  EXPECT_GT(empty, 10);
}

Scene coloredQuads(const std::vector<std::pair<float, glm::vec4>>& depthAndColour, AlphaMode mode) {
  Scene scene;
  for (const auto& [z, colour] : depthAndColour) {
    Mesh mesh;
    mesh.positions = {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.material = int(scene.materials.size());
    Material material;
    material.baseColorFactor = colour;
    material.alphaMode = mode;
    scene.materials.push_back(material);
    scene.instances.push_back({int(scene.meshes.size()), glm::mat4(1.0f)});
    scene.meshes.push_back(mesh);
  }
  return scene;
}

TEST(ReferenceTracer, AlphaModes) {
  Camera camera;
  std::vector<TracerHit> scratch;
  const glm::dvec2 centre(4.0, 4.0);  // on the quads' shared diagonal, too
  const glm::vec4 red(1, 0, 0, 0.25f), green(0, 1, 0, 0.5f);
  {
    const Scene scene = coloredQuads({{-3.0f, red}, {-5.0f, green}}, AlphaMode::Blend);
    const glm::dvec4 got = ReferenceTracer(scene, camera, 8, 8).shade(centre, scratch);
    // red over green, premultiplied: each edge hit counted once.
    const glm::dvec4 expected = glm::dvec4(0.25, 0, 0, 0.25) + 0.75 * glm::dvec4(0, 0.5, 0, 0.5);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], expected[c], 1e-6);
  }
  {
    const Scene scene = coloredQuads({{-3.0f, red}, {-5.0f, green}}, AlphaMode::Mask);
    // red (0.25 < 0.5 cutoff) is discarded; green passes with alpha forced to 1.
    const glm::dvec4 got = ReferenceTracer(scene, camera, 8, 8).shade(centre, scratch);
    EXPECT_EQ(got, glm::dvec4(0, 1, 0, 1));
  }
  {
    const Scene scene = coloredQuads({{-5.0f, green}, {-3.0f, red}}, AlphaMode::Opaque);
    EXPECT_EQ(ReferenceTracer(scene, camera, 8, 8).shade(centre, scratch), glm::dvec4(1, 0, 0, 1));
  }
}

TEST(ReferenceTracer, CullingNearPlaneAndMirroring) {
  Camera camera;
  camera.znear = 4.0f;
  std::vector<TracerHit> scratch;
  const glm::vec4 red(1, 0, 0, 1), green(0, 1, 0, 1);
  const glm::dvec2 centre(4.5, 3.5);
  // The red quad is nearer than the near plane, so only green is seen.
  Scene scene = coloredQuads({{-3.0f, red}, {-5.0f, green}}, AlphaMode::Opaque);
  EXPECT_EQ(ReferenceTracer(scene, camera, 8, 8).shade(centre, scratch), glm::dvec4(0, 1, 0, 1));
  // Flipping the green quad's winding makes it a culled back face...
  std::swap(scene.meshes[1].indices[1], scene.meshes[1].indices[2]);
  std::swap(scene.meshes[1].indices[4], scene.meshes[1].indices[5]);
  EXPECT_EQ(ReferenceTracer(scene, camera, 8, 8).shade(centre, scratch), glm::dvec4(0.0));
  // ...which a mirroring instance (z scaled by -1, quad moved to z = +5) makes front again.
  scene.meshes[1].positions = {{-1, -1, 5}, {1, -1, 5}, {1, 1, 5}, {-1, 1, 5}};
  scene.instances[1].world = glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0),
                                       glm::vec4(0, 0, -1, 0), glm::vec4(0, 0, 0, 1));
  EXPECT_EQ(ReferenceTracer(scene, camera, 8, 8).shade(centre, scratch), glm::dvec4(0, 1, 0, 1));
  // Double-sided materials draw either winding.
  scene.instances[1].world = glm::mat4(1.0f);
  scene.meshes[1].positions = {{-1, -1, -5}, {1, -1, -5}, {1, 1, -5}, {-1, 1, -5}};
  scene.materials[1].doubleSided = true;
  EXPECT_EQ(ReferenceTracer(scene, camera, 8, 8).shade(centre, scratch), glm::dvec4(0, 1, 0, 1));
}

// A vertex 1e30 away weighs ~1e-30 at every visible point: the other two
// weights must not swallow it (1 - b1 - b2 would round it to nothing and the
// inside test would then miss about half the triangle at random). Every pixel
// centre clear of the analytic edges x = -3, y = -1 and y = 2 (the far
// vertex's edges are those lines to within 1e-29) hits at distance 6, and the
// weights rebuild the hit point.
TEST(ReferenceTracer, VertexFarAwayKeepsEveryHitAndWeight) {
  Scene scene;
  Mesh mesh;
  mesh.positions = {{1e30f, 0.3f, -6.0f}, {-3.0f, -1.0f, -6.0f}, {-3.0f, 2.0f, -6.0f}};
  mesh.indices = {0, 1, 2};
  mesh.material = 0;
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, glm::mat4(1.0f)});
  Material material;
  material.doubleSided = true;
  scene.materials.push_back(material);
  const Camera camera;
  constexpr int kSize = 64;
  const ReferenceTracer tracer(scene, camera, kSize, kSize);
  int inside = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Ray ray = tracer.primaryRay({x + 0.5, y + 0.5});
      const glm::dvec3 point = ray.direction * (6.0 / -ray.direction.z);
      const double margin = 1e-9;
      const bool expectHit =
          point.x > -3.0 + margin && point.y > -1.0 + margin && point.y < 2.0 - margin;
      const bool expectMiss =
          point.x < -3.0 - margin || point.y < -1.0 - margin || point.y > 2.0 + margin;
      const std::optional<TracerHit> hit = tracer.nearestHit({x + 0.5, y + 0.5});
      if (expectMiss) {
        EXPECT_FALSE(hit.has_value()) << x << "," << y;
      }
      if (!expectHit) continue;
      ++inside;
      ASSERT_TRUE(hit.has_value()) << x << "," << y;
      EXPECT_NEAR(hit->viewDistance, 6.0, 1e-12);
      glm::dvec3 rebuilt(0.0);
      for (int k = 0; k < 3; ++k) rebuilt += hit->bary[k] * glm::dvec3(mesh.positions[k]);
      EXPECT_NEAR(rebuilt.x, point.x, 1e-9 * std::max(1.0, std::fabs(point.x)));
      EXPECT_NEAR(rebuilt.y, point.y, 1e-9);
    }
  EXPECT_GT(inside, kSize * kSize / 8);
}

// The screen grid is only a faster way to find the same triangles: frames of
// every kind of built-in scene (perspective and orthographic, triangles
// crossing the eye plane, 1e30 coordinates, NaN vertices, 20000 random
// triangles) must equal the exhaustive search's bit for bit, at an odd
// sample count whose subsamples fall on cell borders too. One test per
// scene, so ctest spreads the exhaustive searches over the cores.
class ScreenGrid : public ::testing::TestWithParam<std::string> {};

TEST_P(ScreenGrid, FindsTheHitsTheExhaustiveSearchFinds) {
  const Scene scene = makeBuiltinScene(GetParam());
  const Camera camera = firstCameraOrDefault(scene);
  constexpr int kWidth = 40, kHeight = 24;
  const Image grid = ReferenceTracer(scene, camera, kWidth, kHeight).render(3);
  const Image exhaustive =
      ReferenceTracer(scene, camera, kWidth, kHeight, TracerSearch::Exhaustive).render(3);
  ASSERT_EQ(grid.rgba.size(), exhaustive.rgba.size());
  EXPECT_EQ(std::memcmp(grid.rgba.data(), exhaustive.rgba.data(), grid.rgba.size() * 4), 0);
}

std::vector<std::string> exhaustivelySearchableScenes() {
  std::vector<std::string> names = builtinSceneNames();
  // 2M triangles: minutes exhaustively; dense-mesh:2000 has its own test below.
  std::erase(names, "dense-mesh");
  return names;
}

INSTANTIATE_TEST_SUITE_P(ReferenceTracer, ScreenGrid,
                         ::testing::ValuesIn(exhaustivelySearchableScenes()), sceneTestName);

TEST(ReferenceTracer, ScreenGridFindsTheDenseMeshHitsTheExhaustiveSearchFinds) {
  const Scene dense = makeBuiltinScene("dense-mesh:2000");
  const Camera camera = firstCameraOrDefault(dense);
  const ReferenceTracer grid(dense, camera, 64, 36),
      exhaustive(dense, camera, 64, 36, TracerSearch::Exhaustive);
  std::vector<TracerHit> a, b;
  // Off-screen points (the grid covers only the screen) and points on it.
  for (const glm::dvec2 at : {glm::dvec2(-3.5, 10.25), glm::dvec2(70.0, 40.0), glm::dvec2(0.0, 0.0),
                              glm::dvec2(64.0, 36.0), glm::dvec2(31.5, 17.75)}) {
    grid.shade(at, a);
    exhaustive.shade(at, b);
    ASSERT_EQ(a.size(), b.size()) << at.x << "," << at.y;
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].triangle, b[i].triangle);
      EXPECT_EQ(a[i].viewDistance, b[i].viewDistance);
    }
  }
  const Image g = grid.render(2), e = exhaustive.render(2);
  EXPECT_EQ(std::memcmp(g.rgba.data(), e.rgba.data(), g.rgba.size() * 4), 0);
}
}  // namespace
}  // namespace quadra::ref
