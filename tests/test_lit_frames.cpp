// Lit frames (Shading::Pbr) through the whole pipeline: the white furnace on
// a mirror and on a rough metal, the background's orientation against
// LIGHTING.md's direction mapping, double-sided back faces and meshes
// without normals shading as LIGHTING.md says, the same bits on every
// kernel path and thread count, and the prepared environment kept between
// frames.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include "api/renderer.h"
#include "core/error.h"
#include "render_helpers.h"
#include "scene/gltf_loader.h"

namespace quadra {
namespace {

// A unit sphere of `rings` x `segments` quads (two triangles each), with
// normals, counter-clockwise seen from outside.
Mesh uvSphere(int rings, int segments, bool withNormals = true) {
  Mesh mesh;
  for (int i = 0; i <= rings; ++i) {
    const double theta = std::numbers::pi * i / rings;
    for (int j = 0; j <= segments; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / segments;
      const glm::vec3 p(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                        float(-std::sin(theta) * std::sin(phi)));
      mesh.positions.push_back(p);
      if (withNormals) mesh.normals.push_back(p);
    }
  }
  const auto at = [&](int i, int j) { return std::uint32_t(i * (segments + 1) + j); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
    }
  return mesh;
}

Scene sphereScene(const Material& material, bool withNormals = true) {
  Scene scene;
  Mesh mesh = uvSphere(48, 96, withNormals);
  mesh.material = 0;
  scene.materials.push_back(material);
  scene.meshes.push_back(std::move(mesh));
  scene.instances.push_back(Instance{});
  return scene;
}

Camera lookingDownMinusZ(float distance) {
  Camera camera;
  camera.yfov = 0.7f;
  camera.znear = 0.1f;
  camera.world = glm::mat4(1.0f);
  camera.world[3] = glm::vec4(0.0f, 0.0f, distance, 1.0f);
  return camera;
}

// A panorama of one radiance everywhere.
std::shared_ptr<const EnvironmentImage> uniformEnvironment(float radiance, int width = 64) {
  auto image = std::make_shared<EnvironmentImage>();
  image->name = "uniform";
  image->width = width;
  image->height = width / 2;
  image->rgb.assign(image->texelCount() * 3, radiance);
  return image;
}

// A panorama whose red is u and green is v at each texel centre, blue 0.25:
// linear in u and v, so its bilinear reading is (u, v) between texel centres.
std::shared_ptr<const EnvironmentImage> uvEnvironment(int width, int height) {
  auto image = std::make_shared<EnvironmentImage>();
  image->name = "uv";
  image->width = width;
  image->height = height;
  image->rgb.resize(image->texelCount() * 3);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      float* t = image->rgb.data() + 3 * (std::size_t(j) * width + i);
      t[0] = (i + 0.5f) / float(width);
      t[1] = (j + 0.5f) / float(height);
      t[2] = 0.25f;
    }
  return image;
}

RenderSettings litSettings(std::shared_ptr<const EnvironmentImage> environment, int width = 160,
                           int height = 120) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.shading = Shading::Pbr;
  settings.environment = std::move(environment);
  return settings;
}

const float* pixel(const Frame& frame, int x, int y) {
  return frame.rgba.data() + 4 * (std::size_t(y) * std::size_t(frame.width) + std::size_t(x));
}

// White furnace: under uniform radiance 1 a white mirror (metal, roughness 0)
// reflects exactly 1 at every pixel, and the background is 1 too.
TEST(LitFrames, WhiteMirrorInAUniformEnvironmentIsOneEverywhere) {
  Material mirror;
  mirror.metallicFactor = 1.0f;
  mirror.roughnessFactor = 0.0f;
  const Frame frame = renderOnce(sphereScene(mirror), lookingDownMinusZ(3.0f),
                                 litSettings(uniformEnvironment(1.0f)));
  double worst = 0.0;
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x)
      for (int c = 0; c < 4; ++c) worst = std::max(worst, std::fabs(pixel(frame, x, y)[c] - 1.0));
  EXPECT_LT(worst, 2e-3) << "largest difference from 1";
}

// The directional albedo of a white GGX metal (F = 1) seen head-on, by
// quadrature over the hemisphere in double: D and the height-correlated V
// of glTF's Appendix B, independently of the engine's tables.
double whiteMetalAlbedoHeadOn(double alpha) {
  const double a2 = alpha * alpha;
  const int thetaSteps = 2000;
  double sum = 0.0;
  for (int i = 0; i < thetaSteps; ++i) {
    const double theta = (i + 0.5) * (std::numbers::pi / 2) / thetaSteps;
    const double nl = std::cos(theta);
    // n = v, so h is halfway between n and l: n.h = cos(theta / 2).
    const double nh = std::cos(0.5 * theta);
    const double d = a2 / (std::numbers::pi * std::pow(nh * nh * (a2 - 1.0) + 1.0, 2));
    const double nv = 1.0;
    const double v = 0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) +
                            nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
    // The integrand does not depend on phi: 2 pi sin(theta) dtheta.
    sum += d * v * nl * 2.0 * std::numbers::pi * std::sin(theta) *
           ((std::numbers::pi / 2) / thetaSteps);
  }
  return sum;
}

// A rough white metal in the same furnace reflects its directional albedo:
// at the sphere's centre, seen head-on, the quadrature's.
TEST(LitFrames, RoughWhiteMetalInAUniformEnvironmentReflectsItsAlbedo) {
  Material metal;
  metal.metallicFactor = 1.0f;
  metal.roughnessFactor = 0.6f;
  const Frame frame = renderOnce(sphereScene(metal), lookingDownMinusZ(3.0f),
                                 litSettings(uniformEnvironment(1.0f)));
  const float* centre = pixel(frame, frame.width / 2, frame.height / 2);
  const double albedo = whiteMetalAlbedoHeadOn(0.36);
  EXPECT_NEAR(centre[0], albedo, 5e-3 * albedo);
  EXPECT_FLOAT_EQ(centre[0], centre[1]);
  EXPECT_FLOAT_EQ(centre[0], centre[2]);
}

// The background is the environment seen through each pixel (LIGHTING.md):
// the camera looks down -Z, which the panorama's centre column holds
// (u = 0.5), its horizon at v = 0.5; right of centre is toward +X (u > 0.5)
// and up toward +Y (v < 0.5).
TEST(LitFrames, BackgroundFollowsTheEnvironmentsDirectionMapping) {
  Scene empty;
  const int width = 200, height = 100;
  RenderSettings settings = litSettings(uvEnvironment(512, 256), width, height);
  Camera camera = lookingDownMinusZ(0.0f);
  camera.yfov = 0.5f;
  const Frame frame = renderOnce(empty, camera, settings);
  const double tanY = std::tan(0.5 * camera.yfov), aspect = double(width) / height;
  for (const auto& [x, y] : {std::pair{100, 50}, std::pair{10, 50}, std::pair{190, 20},
                             std::pair{37, 91}, std::pair{160, 8}}) {
    // The pixel centre's ray in view space = world space (camera at rest).
    const double dx = (2.0 * (x + 0.5) / width - 1.0) * tanY * aspect;
    const double dy = (1.0 - 2.0 * (y + 0.5) / height) * tanY;
    const double length = std::sqrt(dx * dx + dy * dy + 1.0);
    const double u = 0.5 + std::atan2(dx / length, 1.0 / length) / (2.0 * std::numbers::pi);
    const double v = std::acos(dy / length) / std::numbers::pi;
    const float* p = pixel(frame, x, y);
    // The filtered lookup averages over the pixel's footprint, a fraction
    // of a texel here, on a field linear in u and v.
    EXPECT_NEAR(p[0], u, 4e-3) << "pixel " << x << "," << y;
    EXPECT_NEAR(p[1], v, 4e-3) << "pixel " << x << "," << y;
    EXPECT_NEAR(p[2], 0.25, 1e-3);
    EXPECT_EQ(p[3], 1.0f);
  }
}

// --env-rotation turns the environment about +Y: a lookup in direction d
// reads the panorama at R_y(-angle) d (LIGHTING.md). R_y(t) takes (x, z) to
// (x cos t + z sin t, -x sin t + z cos t), so at 90 degrees the view down
// -Z reads the panorama's +X direction, u = 0.75.
TEST(LitFrames, EnvironmentRotationTurnsThePanoramaAboutY) {
  Scene empty;
  RenderSettings settings = litSettings(uvEnvironment(512, 256), 64, 32);
  settings.environmentRotation = 90.0f;
  const Frame frame = renderOnce(empty, lookingDownMinusZ(0.0f), settings);
  // The four pixels around the centre straddle the view axis.
  double red = 0.0, green = 0.0;
  for (const auto& [x, y] :
       {std::pair{31, 15}, std::pair{32, 15}, std::pair{31, 16}, std::pair{32, 16}}) {
    red += 0.25 * pixel(frame, x, y)[0];
    green += 0.25 * pixel(frame, x, y)[1];
  }
  EXPECT_NEAR(red, 0.75, 2e-3);
  EXPECT_NEAR(green, 0.5, 2e-3);
}

// A double-sided surface seen from behind shades as its front does when the
// light is symmetric about it: the back face's normal turns to the viewer.
TEST(LitFrames, DoubleSidedBackFacesShadeWithTheirNormalTurnedToTheViewer) {
  Mesh quad;
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.normals.assign(4, glm::vec3(0, 0, 1));
  quad.indices = {0, 1, 2, 0, 2, 3};
  Scene scene = doubleSidedMeshScene(quad);
  scene.materials[0].metallicFactor = 0.0f;
  scene.materials[0].roughnessFactor = 0.5f;
  scene.materials[0].baseColorFactor = glm::vec4(0.8f, 0.4f, 0.2f, 1.0f);
  const RenderSettings settings = litSettings(uniformEnvironment(0.5f), 32, 32);
  const Frame front = renderOnce(scene, lookingDownMinusZ(2.0f), settings);
  Camera behind = lookingDownMinusZ(2.0f);
  behind.world = glm::mat4(glm::vec4(-1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, -1, 0),
                           glm::vec4(0, 0, -2, 1));
  const Frame back = renderOnce(scene, behind, settings);
  const float* f = pixel(front, 16, 16);
  const float* b = pixel(back, 16, 16);
  EXPECT_GT(f[0], 0.05f);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(b[c], f[c], 1e-5f) << "channel " << c;
}

// A mesh without NORMAL shades flat (glTF 2.0 §3.7.2.1): each triangle of a
// coarse sphere is one colour under a light that varies over the sphere.
TEST(LitFrames, MeshWithoutNormalsShadesEachTriangleFlat) {
  Material rough;
  rough.metallicFactor = 0.0f;
  rough.roughnessFactor = 1.0f;
  Scene smooth = sphereScene(rough, true), flat = sphereScene(rough, false);
  const RenderSettings settings = litSettings(uvEnvironment(64, 32), 96, 96);
  const Frame a = renderOnce(smooth, lookingDownMinusZ(3.0f), settings);
  const Frame b = renderOnce(flat, lookingDownMinusZ(3.0f), settings);
  // Both lit, both alike on average; the flat one differs from the smooth
  // one somewhere (the facets show) but nowhere by much on a fine sphere.
  double sumA = 0.0, sumB = 0.0, differs = 0.0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      sumA += pixel(a, x, y)[0];
      sumB += pixel(b, x, y)[0];
      differs = std::max(differs, double(std::fabs(pixel(a, x, y)[0] - pixel(b, x, y)[0])));
    }
  EXPECT_NEAR(sumB / sumA, 1.0, 0.02);
  EXPECT_GT(differs, 1e-4);
  EXPECT_LT(differs, 0.1);
}

// The same bits on every kernel path and thread count, for a sample model
// with every texture of the material (normal, occlusion, emissive,
// metallic-roughness) and for a sphere.
TEST(LitFrames, SameBitsOnEveryKernelPathAndThreadCount) {
  std::vector<std::pair<std::string, Scene>> scenes;
  Material metal;
  metal.metallicFactor = 0.7f;
  metal.roughnessFactor = 0.3f;
  scenes.emplace_back("sphere", sphereScene(metal));
  const std::string bottle = std::string(QUADRA_ASSETS_DIR) + "/WaterBottle/glTF/WaterBottle.gltf";
  if (std::filesystem::exists(bottle)) scenes.emplace_back("WaterBottle", loadGltf(bottle));
  for (const auto& [name, scene] : scenes) {
    const Camera camera = defaultCamera(scene);
    RenderSettings settings = litSettings(uvEnvironment(256, 128), 96, 64);
    const Frame reference = renderOnce(scene, camera, settings, 1, Isa::Scalar);
    for (const Isa isa : supportedIsas())
      for (const int threads : {1, 2}) {
        const Frame frame = renderOnce(scene, camera, settings, threads, isa);
        EXPECT_EQ(frame.rgba, reference.rgba) << name << " " << isaName(isa) << " " << threads;
      }
  }
}

// The environment is prepared once and kept while frames ask for the same
// one; another rotation prepares it again.
TEST(LitFrames, PreparedEnvironmentIsKeptBetweenFrames) {
  Material metal;
  metal.roughnessFactor = 0.2f;
  const Scene scene = sphereScene(metal);
  RenderSettings settings = litSettings(uvEnvironment(256, 128), 32, 32);
  RendererConfig config;
  config.threads = 2;
  Renderer renderer(config);
  Frame frame;
  const FrameStats first = renderer.render(scene, lookingDownMinusZ(3.0f), settings, frame);
  const FrameStats second = renderer.render(scene, lookingDownMinusZ(3.0f), settings, frame);
  settings.environmentRotation = 30.0f;
  const FrameStats third = renderer.render(scene, lookingDownMinusZ(3.0f), settings, frame);
  EXPECT_GT(first.stages.environment, 0.0);
  EXPECT_EQ(second.stages.environment, 0.0);
  EXPECT_GT(third.stages.environment, 0.0);
}

TEST(LitFrames, PbrWithoutAnEnvironmentIsAnError) {
  Material metal;
  RenderSettings settings = litSettings(nullptr, 16, 16);
  EXPECT_THROW(renderOnce(sphereScene(metal), lookingDownMinusZ(3.0f), settings), Error);
}

}  // namespace
}  // namespace quadra
