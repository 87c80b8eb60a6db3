// The surface AOVs (docs/cli.md "AOVs"): depth, normal, position, uv and ids at
// pixel centres against the double-precision reference tracer on built-in
// scenes and shared glTF models; motion against an analytic camera move;
// lod and anisotropy against analytic footprints and against the colour
// trilinear filtering produced with them; the EXR channels and header attributes read back with
// OpenEXR (and, where installed, with OpenImageIO's and OpenEXR's own tools); the CLI's --aov.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "api/camera.h"
#include "api/renderer.h"
#include "cli_helpers.h"
#include "core/error.h"
#include "exr_channels.h"
#include "io/image_io.h"
#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"
#include "lab/texture/ground_truth.h"
#include "lab/texture/test_textures.h"
#include "param_names.h"
#include "render_helpers.h"
#include "scene/animation.h"
#include "scene/gltf_loader.h"
#include "texture/mip_chain.h"

namespace quadra {
namespace {

constexpr AovSet kAllSurfaceAovs = AovSet(Aov::Normal) | AovSet(Aov::Position) | AovSet(Aov::Uv) |
                                   AovSet(Aov::Motion) | AovSet(Aov::Ids);

// The nearest hit a depth-writing surface makes along the ray through a
// window point: blended surfaces skipped, masked ones where their alpha
// (level-0 bilinear) is below the cutoff.
std::optional<ref::TracerHit> nearestDepthWritingHit(const Scene& scene,
                                                     const ref::ReferenceTracer& tracer,
                                                     const glm::dvec2& window,
                                                     std::vector<ref::TracerHit>& hits) {
  tracer.allHits(tracer.primaryRay(window), hits);
  for (const ref::TracerHit& hit : hits) {
    const Mesh& mesh = scene.meshes[std::size_t(scene.instances[std::size_t(hit.instance)].mesh)];
    if (mesh.material < 0) return hit;
    const Material& material = scene.materials[std::size_t(mesh.material)];
    if (material.alphaMode == AlphaMode::Blend) continue;
    if (material.alphaMode == AlphaMode::Mask &&
        tracer.surfaceColour(hit).a < double(material.alphaCutoff))
      continue;
    return hit;
  }
  return std::nullopt;
}

// The ids docs/cli.md "AOVs" defines for an instance.
std::uint32_t expectedNode(const Scene& scene, int instance) {
  const int node = scene.instances[std::size_t(instance)].node;
  return node >= 0 ? std::uint32_t(scene.nodes[std::size_t(node)].fileIndex)
                   : std::uint32_t(instance);
}
std::uint32_t expectedMaterial(const Scene& scene, int instance) {
  const int material =
      scene.meshes[std::size_t(scene.instances[std::size_t(instance)].mesh)].material;
  if (material < 0) return kNoId;
  const int file = scene.materials[std::size_t(material)].fileIndex;
  return std::uint32_t(file >= 0 ? file : material);
}

struct AovCase {
  std::string name;  // builtin:NAME or a shared model's folder
  std::string path;  // the glTF file, for a shared model
};

void PrintTo(const AovCase& c, std::ostream* out) {
  *out << c.name;
}

class AovsMatchReference : public ::testing::TestWithParam<AovCase> {};

// At one sample per pixel, each pixel whose triangle is the tracer's
// nearest depth-writing hit at the pixel centre has that hit's depth,
// world position, normal, uv and ids; pixels where the two disagree about
// the triangle (a centre on a shared edge, a snapped edge, a filtered alpha
// test) are few.
TEST_P(AovsMatchReference, AtPixelCentres) {
  const AovCase& c = GetParam();
  Scene scene;
  if (c.path.empty()) {
    scene = makeBuiltinScene(c.name);
  } else {
    if (!std::filesystem::exists(c.path)) GTEST_SKIP() << "sample model absent: " << c.path;
    scene = loadGltf(c.path);
  }
  RenderSettings settings;
  settings.width = 160;
  settings.height = 96;
  settings.aovs = kAllSurfaceAovs;
  const Camera camera = firstCameraOrDefault(scene);
  const Frame frame = renderOnce(scene, camera, settings);
  const ref::ReferenceTracer tracer(scene, camera, settings.width, settings.height);
  const glm::dmat4 projection(
      projectionMatrix(camera, double(settings.width) / settings.height, settings.depth));

  glm::dvec3 lo, hi;
  {
    glm::vec3 l, h;
    scene.bounds(l, h);
    lo = l, hi = h;
  }
  const double size = glm::length(hi - lo);
  std::vector<ref::TracerHit> hits;
  int compared = 0, otherTriangle = 0, coverageDiffers = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const std::size_t p = std::size_t(y) * std::size_t(settings.width) + std::size_t(x);
      const std::optional<ref::TracerHit> hit =
          nearestDepthWritingHit(scene, tracer, glm::dvec2(x + 0.5, y + 0.5), hits);
      const bool drawn = frame.primitiveId[p] != kNoId;
      if (drawn != hit.has_value()) {
        ++coverageDiffers;
        continue;
      }
      if (!hit) {
        // Clear values.
        EXPECT_EQ(frame.nodeId[p], kNoId);
        EXPECT_EQ(frame.materialId[p], kNoId);
        for (int k = 0; k < 3; ++k) EXPECT_EQ(frame.normal[3 * p + std::size_t(k)], 0.0f);
        for (int k = 0; k < 3; ++k) EXPECT_EQ(frame.position[3 * p + std::size_t(k)], 0.0f);
        EXPECT_EQ(frame.uv[2 * p], 0.0f);
        EXPECT_EQ(frame.depth[p], 1.0f);
        continue;
      }
      if (frame.primitiveId[p] != std::uint32_t(hit->triangle) ||
          frame.nodeId[p] != expectedNode(scene, hit->instance) ||
          frame.materialId[p] != expectedMaterial(scene, hit->instance)) {
        ++otherTriangle;
        continue;
      }
      ++compared;
      SCOPED_TRACE("pixel " + std::to_string(x) + "," + std::to_string(y));
      const Instance& instance = scene.instances[std::size_t(hit->instance)];
      const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
      const glm::dmat4 world(instance.world);
      glm::dvec3 object(0.0), normal(0.0);
      glm::dvec2 uv = tracer.texCoord(*hit, 0);
      std::uint32_t index[3];
      for (int k = 0; k < 3; ++k) {
        index[k] = mesh.indices[std::size_t(hit->triangle) * 3 + std::size_t(k)];
        object += hit->bary[k] * glm::dvec3(mesh.positions[index[k]]);
        if (!mesh.normals.empty()) normal += hit->bary[k] * glm::dvec3(mesh.normals[index[k]]);
      }
      if (mesh.normals.empty())
        normal = glm::cross(glm::dvec3(mesh.positions[index[1]] - mesh.positions[index[0]]),
                            glm::dvec3(mesh.positions[index[2]] - mesh.positions[index[0]]));
      normal = glm::normalize(glm::transpose(glm::inverse(glm::dmat3(world))) * normal);
      const glm::dvec3 position(world * glm::dvec4(object, 1.0));
      const glm::dvec4 clip = projection * glm::dvec4(0.0, 0.0, -hit->viewDistance, 1.0);
      // Z is the pipeline's float depth plane (through float vertices), not
      // the AOV pass's: up to 5e-6 (80 ulp) near the checker plane's horizon.
      EXPECT_NEAR(frame.depth[p], clip.z / clip.w, 1e-5);
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(frame.position[3 * p + std::size_t(k)], position[k], 1e-5 * size) << k;
        EXPECT_NEAR(frame.normal[3 * p + std::size_t(k)], normal[k], 1e-5) << k;
      }
      // Relative: the checker plane repeats its texture far toward the horizon.
      EXPECT_NEAR(frame.uv[2 * p], uv.x, 1e-5 * std::max(1.0, std::fabs(uv.x)));
      EXPECT_NEAR(frame.uv[2 * p + 1], uv.y, 1e-5 * std::max(1.0, std::fabs(uv.y)));
      EXPECT_EQ(frame.motion[2 * p], 0.0f);  // a still
      EXPECT_EQ(frame.motion[2 * p + 1], 0.0f);
      if (::testing::Test::HasFailure()) return;  // one pixel's report is enough
    }
  const int pixels = settings.width * settings.height;
  EXPECT_GT(compared, pixels / 20) << "too little of the scene drawn to compare";
  EXPECT_LE(coverageDiffers, pixels / 100) << "drawn where the tracer hits nothing, or not";
  EXPECT_LE(otherTriangle, compared / 50 + 4) << "another triangle than the tracer's";
}

std::vector<AovCase> aovCases() {
  std::vector<AovCase> cases;
  for (const char* name : {"showcase", "checker-plane", "alpha-quads", "intersecting-glass"})
    cases.push_back({name, ""});
  for (const char* model : {"Box", "BoxTextured", "NegativeScaleTest", "OrientationTest"})
    cases.push_back(
        {model, std::string(QUADRA_ASSETS_DIR) + "/" + model + "/glTF/" + model + ".gltf"});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Aovs, AovsMatchReference, ::testing::ValuesIn(aovCases()),
                         [](const ::testing::TestParamInfo<AovCase>& info) {
                           return asTestName(info.param.name);
                         });

// Asking for AOVs moves no colour or depth bit (the tiles that would shade
// one triangle forward shade it in two passes instead, which the precision
// contract makes the same bits), and with several samples the AOVs follow
// the sample Z reports.
TEST(Aovs, LeaveColourDepthAndCoverageBitsAlone) {
  const Scene scene = makeBuiltinScene("showcase");
  const Camera camera = firstCameraOrDefault(scene);
  for (const int samples : {1, 4}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.samples = samples;
    settings.frameCoverage = true;
    const Frame plain = renderOnce(scene, camera, settings);
    settings.aovs = kAllSurfaceAovs | kFootprintAovs;
    const Frame withAovs = renderOnce(scene, camera, settings);
    EXPECT_EQ(std::memcmp(plain.rgba.data(), withAovs.rgba.data(), plain.rgba.size() * 4), 0);
    EXPECT_EQ(std::memcmp(plain.depth.data(), withAovs.depth.data(), plain.depth.size() * 4), 0);
    EXPECT_EQ(
        std::memcmp(plain.coverage.data(), withAovs.coverage.data(), plain.coverage.size() * 4), 0);
    EXPECT_TRUE(plain.normal.empty() && plain.primitiveId.empty() && plain.lod.empty());
    // Where a surface is, its position projects to the pixel's depth (at
    // one sample: with several, Z is the nearest sample's, P the centre's).
    if (samples > 1) continue;
    const glm::dmat4 toNdc(withAovs.metadata.worldToNDC);
    int checked = 0;
    for (std::size_t p = 0; p < withAovs.depth.size(); ++p) {
      if (withAovs.primitiveId[p] == kNoId) continue;
      const glm::dvec4 clip =
          toNdc * glm::dvec4(withAovs.position[3 * p], withAovs.position[3 * p + 1],
                             withAovs.position[3 * p + 2], 1.0);
      ASSERT_NEAR(clip.z / clip.w, withAovs.depth[p], 1e-5) << "pixel " << p;
      ++checked;
    }
    EXPECT_GT(checked, 1000);
  }
}

// A camera moved sideways between the previous pose and this one moves
// every surface the same number of pixels under an orthographic camera.
TEST(Aovs, MotionOfAnOrthographicCameraMoveIsUniform) {
  const Scene scene = makeBuiltinScene("showcase");
  Camera camera = firstCameraOrDefault(scene);
  camera.type = Camera::Type::Orthographic;
  camera.xmag = 4.0f;
  camera.ymag = 2.25f;
  camera.zfar = 100.0f;
  PreviousPose previous;
  previous.camera = camera;
  // One world unit to the camera's left: 160 / 8 = 20 pixels a unit.
  previous.camera.world[3] -= camera.world[0];
  for (const Instance& instance : scene.instances)
    previous.instanceWorlds.push_back(instance.world);
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.aovs = AovSet(Aov::Motion) | AovSet(Aov::Ids);
  settings.previousPose = &previous;
  const Frame frame = renderOnce(scene, camera, settings);
  int moved = 0;
  for (std::size_t p = 0; p < frame.primitiveId.size(); ++p) {
    if (frame.primitiveId[p] == kNoId) {
      EXPECT_EQ(frame.motion[2 * p], 0.0f);
      continue;
    }
    // Seen from one unit further left, a point sat 20 pixels further right.
    ASSERT_NEAR(frame.motion[2 * p], -20.0f, 1e-3) << "pixel " << p;
    ASSERT_NEAR(frame.motion[2 * p + 1], 0.0f, 1e-3) << "pixel " << p;
    ++moved;
  }
  EXPECT_GT(moved, 1000);

  // A previous pose for another scene is an error, not a read past the end.
  previous.instanceWorlds.pop_back();
  EXPECT_THROW(renderOnce(scene, camera, settings), Error);
}

// A square of value-noise texels (a different value per texel, so every
// mip level differs from the next) on TEXCOORD_0 of the scene's first mesh.
std::shared_ptr<Texture> noiseTexture() {
  return std::make_shared<Texture>(std::make_shared<Image>(makeValueNoiseTexture(256, 256, 7)),
                                   SamplerState{});
}

// One quad (two triangles) of `material` from corners lo to hi in the plane
// z = depth, texture coordinates uvAt(position).
Mesh quadMesh(glm::vec2 lo, glm::vec2 hi, float depth, int material,
              const std::function<glm::vec2(const glm::vec3&)>& uvAt) {
  Mesh mesh;
  mesh.positions = {
      {lo.x, lo.y, depth}, {hi.x, lo.y, depth}, {hi.x, hi.y, depth}, {lo.x, hi.y, depth}};
  for (const glm::vec3& p : mesh.positions) mesh.texcoords[0].push_back(uvAt(p));
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.material = material;
  return mesh;
}

// lod and anisotropy against their analytic values: an orthographic camera
// over a plane facing it, 20 px a unit, texture coordinates scaled so that a
// pixel spans `across` texels along x and `down` along y (no shear), so
// every pixel's footprint is the same axis-aligned rectangle. Left of
// x = 1 the plane is textured, then an untextured one up to x = 2.5, then
// nothing (both 0 and 0).
TEST(Aovs, LodAndAnisotropyOfAPlaneFacingTheCamera) {
  constexpr double kPixelsPerUnit = 20.0, kTexels = 256.0;
  const auto sceneWith = [&](double across, double down) {
    Scene scene;
    scene.textures.push_back(noiseTexture());
    Material textured, plain;
    textured.baseColorTexture = 0;
    textured.doubleSided = plain.doubleSided = true;
    scene.materials = {textured, plain};
    const auto uvAt = [&](const glm::vec3& p) {
      return glm::vec2(float(p.x * kPixelsPerUnit * across / kTexels),
                       float(-p.y * kPixelsPerUnit * down / kTexels));
    };
    scene.meshes.push_back(quadMesh({-4.0f, -2.25f}, {1.0f, 2.25f}, -5.0f, 0, uvAt));
    scene.meshes.push_back(quadMesh({1.0f, -2.25f}, {2.5f, 2.25f}, -5.0f, 1, uvAt));
    for (int m = 0; m < 2; ++m) {
      Instance instance;
      instance.mesh = m;
      scene.instances.push_back(instance);
    }
    return scene;
  };
  Camera camera;
  camera.type = Camera::Type::Orthographic;
  camera.xmag = 4.0f;
  camera.ymag = 2.25f;
  camera.zfar = 100.0f;
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.aovs = kFootprintAovs | AovSet(Aov::Ids);
  struct Case {
    std::optional<Filter> filter;
    LodRule rule;
    double across, down, lod, anisotropy;
  };
  const double box = double(kBoxLodOffset);
  const Case cases[] = {
      {std::nullopt, LodRule::Gl, 4.0, 4.0, 2.0, 1.0},  // the glTF sampler's: trilinear
      {Filter::Trilinear, LodRule::Box, 4.0, 4.0, 2.0 + box, 1.0},
      {Filter::Trilinear, LodRule::Gl, 8.0, 2.0, 3.0, 1.0},  // the longer side
      {Filter::NearestMip, LodRule::Gl, 3.0, 3.0, std::log2(3.0), 1.0},
      // N = ceil(major / minor) = ceil(3.6) = 4 probes, each over 8 / 4 = 2
      // texels: level 1 (ratios clear of whole numbers, which float
      // derivatives could round either way); 40:1 is capped at --aniso 16.
      {Filter::Anisotropic, LodRule::Gl, 8.0, 2.2, 1.0, 4.0},
      {Filter::Anisotropic, LodRule::Gl, 2.5, 6.0, 1.0, 3.0},
      {Filter::Anisotropic, LodRule::Gl, 40.0, 1.0, std::log2(40.0 / 16.0), 16.0},
      // Magnified: level 0; filters without levels read level 0.
      {Filter::Trilinear, LodRule::Gl, 0.5, 0.5, 0.0, 1.0},
      {Filter::Bilinear, LodRule::Gl, 4.0, 4.0, 0.0, 1.0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE((c.filter ? filterName(*c.filter) : "sampler's") + std::string(" ") +
                 std::to_string(c.across) + " x " + std::to_string(c.down));
    settings.filter = c.filter;
    settings.lodRule = c.rule;
    const Frame frame = renderOnce(sceneWith(c.across, c.down), camera, settings);
    int textured = 0, plain = 0, empty = 0;
    for (std::size_t p = 0; p < frame.lod.size(); ++p) {
      const std::uint32_t material = frame.materialId[p];
      if (material == 0) {
        // log2's error is below 1e-6; the derivatives are exact to a few ulps.
        ASSERT_NEAR(frame.lod[p], c.lod, 1e-5) << "pixel " << p;
        ASSERT_EQ(frame.anisotropy[p], float(c.anisotropy)) << "pixel " << p;
        ++textured;
      } else {
        ASSERT_EQ(frame.lod[p], 0.0f) << "pixel " << p;
        ASSERT_EQ(frame.anisotropy[p], 0.0f) << "pixel " << p;
        ++(material == 1 ? plain : empty);
      }
    }
    EXPECT_EQ(textured, 100 * 90);
    EXPECT_EQ(plain, 30 * 90);
    EXPECT_EQ(empty, 30 * 90);
  }
}

// The lod AOV is the level trilinear filtering read, shown by the colour: on
// a ground plane seen at a grazing angle (every level from magnified to the
// last), each pixel's colour is the blend of the bilinear lookups of mip
// levels floor(lod) and floor(lod) + 1 (double, at the uv AOV's coordinates)
// by lod's fraction. A level 0.2 off (GL's rule instead of the box rule the
// frame used) misses most pixels by far more than the tolerance.
TEST(Aovs, LodIsTheLevelTrilinearFilteringRead) {
  const Mesh ground = quadMesh({-20.0f, 0.5f}, {20.0f, 60.0f}, 0.0f, 0, [](const glm::vec3& p) {
    return glm::vec2(p.x, p.y) * 0.05f;  // 12.8 texels a unit
  });
  Scene scene = doubleSidedMeshScene(ground);
  scene.textures.push_back(noiseTexture());
  scene.materials[0].baseColorTexture = 0;
  // The quad lies in z = 0: turned onto the ground plane y = -1, its y
  // becoming the distance ahead (-z).
  scene.instances[0].world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -1.0f, 0.0f)) *
                             glm::rotate(glm::mat4(1.0f), -1.5707963f, glm::vec3(1.0f, 0.0f, 0.0f));
  Camera camera;
  camera.yfov = 0.9f;
  camera.zfar = 500.0f;
  RenderSettings settings;
  settings.width = 160;
  settings.height = 96;
  settings.filter = Filter::Trilinear;
  settings.aovs = kFootprintAovs | AovSet(Aov::Uv);
  const Frame frame = renderOnce(scene, camera, settings);

  const MipChain& mips = scene.textures[0]->mips();
  std::vector<BilinearReference> levels;
  for (int l = 0; l < mips.levelCount(); ++l) levels.emplace_back(mips.level(l), SamplerState{});
  const int last = mips.levelCount() - 1;
  // The blend of the levels around `lod` at (u, v).
  const auto trilinear = [&](double lod, double u, double v, double rgb[3]) {
    lod = std::clamp(lod, 0.0, double(last));
    const int fine = int(std::floor(lod)), coarse = std::min(fine + 1, last);
    double a[4], b[4];
    levels[std::size_t(fine)].lookup(u, v, a);
    levels[std::size_t(coarse)].lookup(u, v, b);
    for (int c = 0; c < 3; ++c) rgb[c] = a[c] + (b[c] - a[c]) * (lod - fine);
  };
  double worst = 0.0, lowest = 1e9, highest = -1e9;
  int drawn = 0, missedByOffset = 0;
  for (std::size_t p = 0; p < frame.lod.size(); ++p) {
    if (frame.anisotropy[p] == 0.0f) continue;
    const double lod = frame.lod[p], u = frame.uv[2 * p], v = frame.uv[2 * p + 1];
    double expected[3], offset[3];
    trilinear(lod, u, v, expected);
    trilinear(lod - double(kBoxLodOffset), u, v, offset);
    double error = 0.0, offsetError = 0.0;
    for (int c = 0; c < 3; ++c) {
      error = std::max(error, std::fabs(expected[c] - frame.rgba[4 * p + std::size_t(c)]));
      offsetError =
          std::max(offsetError, std::fabs(offset[c] - frame.rgba[4 * p + std::size_t(c)]));
    }
    worst = std::max(worst, error);
    missedByOffset += offsetError > 1e-3;
    lowest = std::min(lowest, lod), highest = std::max(highest, lod);
    ++drawn;
  }
  EXPECT_GT(drawn, 160 * 40);
  EXPECT_EQ(lowest, 0.0);          // magnified in front
  EXPECT_GT(highest, last - 1.0);  // the horizon reaches the coarsest levels
  // uv is the AOV's double value rounded to float, the kernel's its own
  // float evaluation: they differ by a few ulps of u, ~1e-4 texels of level 0.
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(missedByOffset, drawn / 2);
}

TEST(Aovs, NeedTheVisibilityPass) {
  const Scene scene = makeBuiltinScene("checker-plane");
  RenderSettings settings;
  settings.width = 32;
  settings.height = 32;
  settings.aovs = AovSet(Aov::Normal);
  settings.derivatives = DerivativeMode::Quad;
  EXPECT_THROW(renderOnce(scene, firstCameraOrDefault(scene), settings), Error);
}

// Every channel of every AOV written and read back bit for bit, the ids as
// UINT, with the header's camera matrices and strings.
TEST(Aovs, ExrRoundTripKeepsEveryChannelAndTheHeader) {
  const Scene scene = makeBuiltinScene("showcase");
  RenderSettings settings;
  settings.width = 67;  // odd, so rows are not a multiple of anything
  settings.height = 41;
  settings.aovs = kAllSurfaceAovs | kFootprintAovs;
  settings.frameCoverage = true;
  Frame frame = renderOnce(scene, firstCameraOrDefault(scene), settings);
  frame.metadata.strings = {{"quadraVersion", "9.9.9"}, {"quadraRenderSettings", "width=67"}};
  const fs::path path = tempPath("aovs.exr");
  writeExr(frame, path.string());

  Imf::InputFile file(path.string().c_str());
  const Imf::Header& header = file.header();
  const std::size_t pixels = std::size_t(frame.width) * std::size_t(frame.height);
  struct Expected {
    const char* name;
    const void* data;
    int stride;
    Imf::PixelType type;
  };
  const std::vector<Expected> channels = {
      {"Z", frame.depth.data(), 1, Imf::FLOAT},
      {"mask", frame.coverage.data(), 1, Imf::FLOAT},
      {"N.X", frame.normal.data(), 3, Imf::FLOAT},
      {"N.Y", frame.normal.data() + 1, 3, Imf::FLOAT},
      {"N.Z", frame.normal.data() + 2, 3, Imf::FLOAT},
      {"P.X", frame.position.data(), 3, Imf::FLOAT},
      {"P.Y", frame.position.data() + 1, 3, Imf::FLOAT},
      {"P.Z", frame.position.data() + 2, 3, Imf::FLOAT},
      {"uv.U", frame.uv.data(), 2, Imf::FLOAT},
      {"uv.V", frame.uv.data() + 1, 2, Imf::FLOAT},
      {"motion.X", frame.motion.data(), 2, Imf::FLOAT},
      {"motion.Y", frame.motion.data() + 1, 2, Imf::FLOAT},
      {"id.primitive", frame.primitiveId.data(), 1, Imf::UINT},
      {"id.node", frame.nodeId.data(), 1, Imf::UINT},
      {"id.material", frame.materialId.data(), 1, Imf::UINT},
      {"lod", frame.lod.data(), 1, Imf::FLOAT},
      {"anisotropy", frame.anisotropy.data(), 1, Imf::FLOAT},
  };
  int channelCount = 0;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) ++channelCount;
  EXPECT_EQ(channelCount, 4 + int(channels.size()));
  std::vector<std::vector<std::uint32_t>> read(channels.size(), std::vector<std::uint32_t>(pixels));
  Imf::FrameBuffer buffer;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const Imf::Channel* channel = header.channels().findChannel(channels[c].name);
    ASSERT_NE(channel, nullptr) << channels[c].name;
    EXPECT_EQ(channel->type, channels[c].type) << channels[c].name;
    buffer.insert(channels[c].name,
                  Imf::Slice(channels[c].type, reinterpret_cast<char*>(read[c].data()), 4,
                             4 * std::size_t(frame.width)));
  }
  file.setFrameBuffer(buffer);
  file.readPixels(0, frame.height - 1);
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const auto* expected = static_cast<const std::uint32_t*>(channels[c].data);
    for (std::size_t p = 0; p < pixels; ++p)
      ASSERT_EQ(read[c][p], expected[p * std::size_t(channels[c].stride)])
          << channels[c].name << " pixel " << p;
  }

  ASSERT_TRUE(Imf::hasWorldToCamera(header));
  ASSERT_TRUE(Imf::hasWorldToNDC(header));
  const Imath::M44f toCamera = Imf::worldToCamera(header), toNdc = Imf::worldToNDC(header);
  // Imath multiplies row vectors: a world point p goes to p * M.
  const glm::vec4 point(1.0f, 2.0f, -3.0f, 1.0f);
  const Imath::V4f imathPoint = Imath::V4f(1.0f, 2.0f, -3.0f, 1.0f) * toCamera;
  const glm::vec4 glmPoint = frame.metadata.worldToCamera * point;
  for (int k = 0; k < 4; ++k) EXPECT_FLOAT_EQ(imathPoint[k], glmPoint[k]);
  const Imath::V4f ndcPoint = Imath::V4f(1.0f, 2.0f, -3.0f, 1.0f) * toNdc;
  const glm::vec4 glmNdc = frame.metadata.worldToNDC * point;
  for (int k = 0; k < 4; ++k) EXPECT_FLOAT_EQ(ndcPoint[k], glmNdc[k]);
  const auto* version = header.findTypedAttribute<Imf::StringAttribute>("quadraVersion");
  ASSERT_NE(version, nullptr);
  EXPECT_EQ(version->value(), "9.9.9");
  const auto* described = header.findTypedAttribute<Imf::StringAttribute>("quadraRenderSettings");
  ASSERT_NE(described, nullptr);
  EXPECT_EQ(described->value(), "width=67");
}

// The CLI: --aov's names into the EXR, the header's settings and version;
// OpenImageIO's iinfo and OpenEXR's exrheader read the file where installed.
TEST(AovsCli, WritesTheChannelsOtherToolsRead) {
  const fs::path exr = tempPath("cli_aovs.exr");
  const RunResult r =
      run("render builtin:showcase --width 64 --height 36 --threads 2 "
          "--aov N,P --aov uv,id,motion,mask,Z --out " +
          exr.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  Imf::InputFile file(exr.string().c_str());
  for (const char* name :
       {"R", "G", "B", "A", "Z", "mask", "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "uv.U", "uv.V",
        "motion.X", "motion.Y", "id.primitive", "id.node", "id.material"})
    EXPECT_NE(file.header().channels().findChannel(name), nullptr) << name;
  const auto* settings =
      file.header().findTypedAttribute<Imf::StringAttribute>("quadraRenderSettings");
  ASSERT_NE(settings, nullptr);
  EXPECT_NE(settings->value().find("width=64 height=36"), std::string::npos) << settings->value();
  EXPECT_NE(settings->value().find("aov=Z,N,P,uv,motion,id,mask"), std::string::npos)
      << settings->value();
  const auto* version = file.header().findTypedAttribute<Imf::StringAttribute>("quadraVersion");
  ASSERT_NE(version, nullptr);
  EXPECT_EQ(version->value(), QUADRA_VERSION_STRING);

  int toolsRun = 0;
  if (runProgram("command", "-v iinfo").exitCode == 0) {
    const RunResult info = runProgram("iinfo", "-v " + exr.string());
    EXPECT_EQ(info.exitCode, 0) << info.err;
    for (const char* name : {"N.X", "P.Z", "uv.U", "motion.Y", "id.primitive", "id.material",
                             "worldToCamera", "worldToNDC", "quadraVersion"})
      EXPECT_NE(info.out.find(name), std::string::npos) << name << " not in iinfo's\n" << info.out;
    EXPECT_NE(info.out.find("uint"), std::string::npos) << "the ids' type\n" << info.out;
    ++toolsRun;
  }
  if (runProgram("command", "-v exrheader").exitCode == 0) {
    const RunResult header = runProgram("exrheader", exr.string());
    EXPECT_EQ(header.exitCode, 0) << header.err;
    for (const char* name : {"id.node, 32-bit unsigned integer", "N.Y, 32-bit floating-point",
                             "worldToCamera", "worldToNDC", "quadraRenderSettings"})
      EXPECT_NE(header.out.find(name), std::string::npos) << name << " not in\n" << header.out;
    ++toolsRun;
  }
  if (toolsRun == 0) GTEST_SKIP() << "neither iinfo nor exrheader installed";
}

// A sequence's motion against an independent evaluation: each pixel's
// world position (P, checked against the tracer above) taken back to its
// node's object space with this frame's pose, then to the window with the
// previous frame's pose (scene/animation.h, posed here in the test), lands
// where the pixel centre minus its motion says. BoxAnimated's box turns and
// moves rigidly; without a camera of its own, the CLI frames the rest pose
// once, as firstCameraOrDefault does here.
TEST(AovsCli, SequenceMotionMatchesThePosesOfBothFrames) {
  const std::string model = std::string(QUADRA_ASSETS_DIR) + "/BoxAnimated/glTF/BoxAnimated.gltf";
  if (!fs::exists(model)) GTEST_SKIP() << "sample model absent: " << model;
  const fs::path dir = testDir() / "motion_sequence";
  fs::remove_all(dir);
  fs::create_directories(dir);
  constexpr int kWidth = 160, kHeight = 120;
  const RunResult r = run("render " + model + " --width 160 --height 120 --threads 2 " +
                          "--sequence 6:6 --aov motion,id,P --out " + (dir / "f_##.exr").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const fs::path exr = dir / "f_06.exr";
  int width = 0, height = 0;
  const auto node = readChannel<std::uint32_t>(exr, "id.node", width, height);
  ASSERT_EQ(width, kWidth);
  ASSERT_EQ(height, kHeight);
  std::vector<float> position[3], motion[2];
  for (int c = 0; c < 3; ++c)
    position[c] =
        readChannel<float>(exr, std::string("P.").append(1, "XYZ"[c]).c_str(), width, height);
  for (int c = 0; c < 2; ++c)
    motion[c] =
        readChannel<float>(exr, std::string("motion.").append(1, "XY"[c]).c_str(), width, height);

  Scene scene = loadGltf(model);
  const Camera camera = firstCameraOrDefault(scene);  // the rest pose's framing
  const glm::dmat4 viewToClip =
      glm::dmat4(projectionMatrix(camera, double(kWidth) / kHeight, DepthMode::Standard)) *
      glm::dmat4(viewMatrix(camera));
  NodePose posedNow, posedBefore;
  poseNodes(scene, 0, 6.0 / 24.0, posedNow);
  poseNodes(scene, 0, 5.0 / 24.0, posedBefore);
  const std::vector<glm::mat4>& now = posedNow.worlds;
  const std::vector<glm::mat4>& before = posedBefore.worlds;
  const auto nodeOfFile = [&](std::uint32_t fileIndex) {
    for (std::size_t n = 0; n < scene.nodes.size(); ++n)
      if (std::uint32_t(scene.nodes[n].fileIndex) == fileIndex) return n;
    return scene.nodes.size();
  };
  int moving = 0, checked = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
      if (node[p] == kNoId) {
        EXPECT_EQ(motion[0][p], 0.0f);
        continue;
      }
      const std::size_t n = nodeOfFile(node[p]);
      ASSERT_LT(n, scene.nodes.size()) << "id.node " << node[p];
      const glm::dvec4 world(position[0][p], position[1][p], position[2][p], 1.0);
      const glm::dvec4 object = glm::inverse(glm::dmat4(now[n])) * world;
      const glm::dvec4 clip = viewToClip * glm::dmat4(before[n]) * object;
      const double previousX = (clip.x / clip.w + 1.0) * 0.5 * kWidth;
      const double previousY = (1.0 - clip.y / clip.w) * 0.5 * kHeight;
      EXPECT_NEAR(motion[0][p], x + 0.5 - previousX, 2e-3) << "pixel " << x << "," << y;
      EXPECT_NEAR(motion[1][p], y + 0.5 - previousY, 2e-3) << "pixel " << x << "," << y;
      if (::testing::Test::HasFailure()) return;
      moving += std::fabs(motion[0][p]) + std::fabs(motion[1][p]) > 0.25f;
      ++checked;
    }
  EXPECT_GT(checked, 500);
  EXPECT_GT(moving, 100) << "nothing moved between the frames";
}

TEST(AovsCli, BadInputIsOneLineAndWritesNothing) {
  const fs::path exr = tempPath("bad_aovs.exr");
  const std::string out = " --width 32 --height 32 --out " + exr.string();
  expectOneLineError(run("render builtin:showcase --aov N,normals" + out),
                     "--aov: 'normals' is not an AOV quadra writes (valid: Z, N, P, uv, motion, "
                     "id, mask, lod, anisotropy, albedo, roughness, metallic, emission, "
                     "diffuse, specular)");
  expectOneLineError(run("render builtin:showcase --aov ''" + out), "--aov");
  expectOneLineError(run("render builtin:showcase --aov N --derivatives quad" + out),
                     "AOVs need analytic derivatives");
  EXPECT_FALSE(fs::exists(exr));
}

}  // namespace
}  // namespace quadra
