// The shading AOVs (docs/cli.md "AOVs": albedo, roughness, metallic,
// emission, diffuse, specular): emission + diffuse + specular against the
// colour the shading pass wrote, on lab scenes under an environment with a
// sun and punctual lights and on a shared model with every texture
// (normal, occlusion, emissive); the material terms against the scene's own
// factors; unlit draws' albedo against their colour; the EXR channels as
// OpenEXR and other tools read them; the CLI's --aov names.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "api/camera.h"
#include "api/renderer.h"
#include "cli_helpers.h"
#include "exr_channels.h"
#include "lab/scene/builtin_scenes.h"
#include "lab/scene/lit_scenes.h"
#include "render_helpers.h"
#include "scene/gltf_loader.h"

namespace quadra {
namespace {

constexpr AovSet kTermAovs = kShadingAovs | AovSet(Aov::Ids);

std::string sharedModel(const std::string& name) {
  return std::string(QUADRA_ASSETS_DIR) + "/" + name + "/glTF/" + name + ".gltf";
}

RenderSettings pbrSettings(int width, int height) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.shading = Shading::Pbr;
  settings.environment = std::make_shared<EnvironmentImage>(sunnySkyEnvironment(128, 64));
  settings.aovs = kTermAovs;
  return settings;
}

// The spheres of metallic x roughness lit by the sky, its sun, a point light
// and a spot light aimed at the middle sphere.
Scene litSpheres() {
  Scene scene = metalRoughSpheresScene(3, 3, glm::vec3(0.9f, 0.6f, 0.3f));
  Light point;
  point.color = glm::vec3(1.0f, 0.9f, 0.7f);
  point.intensity = 40.0f;
  point.world = glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f, 4.0f, 5.0f));
  Light spot;
  spot.type = Light::Type::Spot;
  spot.intensity = 80.0f;
  spot.range = 30.0f;
  spot.outerConeAngle = 0.3f;
  spot.world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 6.0f));  // looks down -Z
  scene.lights = {point, spot};
  return scene;
}

// Over the pixels an opaque surface covers (its id written, alpha 1),
// emission + diffuse + specular against the colour, within float rounding
// of the terms' magnitudes. Returns the pixels checked; counts those whose
// diffuse and whose specular light is not 0.
int expectTermsSumToColour(const Frame& frame, int& diffuseLit, int& specularLit) {
  int checked = 0;
  diffuseLit = specularLit = 0;
  for (std::size_t p = 0; p < frame.primitiveId.size(); ++p) {
    if (frame.primitiveId[p] == kNoId || frame.rgba[4 * p + 3] != 1.0f) continue;
    ++checked;
    bool diffuse = false, specular = false;
    for (std::size_t c = 0; c < 3; ++c) {
      const double e = frame.emission[3 * p + c], d = frame.diffuse[3 * p + c],
                   s = frame.specular[3 * p + c];
      const double sum = (e + d) + s, magnitude = std::fabs(e) + std::fabs(d) + std::fabs(s);
      EXPECT_NEAR(frame.rgba[4 * p + c], sum, 2e-6 * magnitude + 1e-30)
          << "pixel " << p << " channel " << c << ": emission " << e << " diffuse " << d
          << " specular " << s;
      EXPECT_GE(d, 0.0) << "pixel " << p;
      EXPECT_GE(s, 0.0) << "pixel " << p;
      diffuse |= d > 0.0, specular |= s > 0.0;
    }
    diffuseLit += diffuse, specularLit += specular;
  }
  return checked;
}

TEST(ShadingAovs, EmissionDiffuseAndSpecularSumToTheColour) {
  const Scene scene = litSpheres();
  const Frame frame = renderOnce(scene, firstCameraOrDefault(scene), pbrSettings(192, 192));
  int diffuseLit = 0, specularLit = 0;
  const int checked = expectTermsSumToColour(frame, diffuseLit, specularLit);
  EXPECT_GT(checked, 3000);
  EXPECT_GT(specularLit, checked * 9 / 10);
  // The top row's metals have no diffuse lobe at all: exactly 0 there.
  EXPECT_GT(diffuseLit, checked / 2);
  EXPECT_LT(diffuseLit, checked * 3 / 4);
}

// Normal, occlusion and emissive maps, Toksvig's roughness where the normal
// map is minified, KHR_materials_emissive_strength: the same sum.
TEST(ShadingAovs, SumHoldsWithEveryTextureOfASharedModel) {
  const std::string path = sharedModel("WaterBottle");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "sample model absent: " << path;
  const Scene scene = loadGltf(path);
  const Frame frame = renderOnce(scene, firstCameraOrDefault(scene), pbrSettings(96, 128));
  int diffuseLit = 0, specularLit = 0;
  const int checked = expectTermsSumToColour(frame, diffuseLit, specularLit);
  EXPECT_GT(checked, 2000);
  EXPECT_GT(diffuseLit, checked / 2);
  EXPECT_GT(specularLit, checked / 2);
  int emitting = 0;
  for (std::size_t p = 0; p < frame.primitiveId.size(); ++p)
    emitting += frame.primitiveId[p] != kNoId && frame.emission[3 * p] > 0.0f;
  EXPECT_GT(emitting, 20) << "the bottle's emissive label";
}

// Every term where no surface is: 0.
void expectClearWhereNothingIs(const Frame& frame) {
  for (std::size_t p = 0; p < frame.primitiveId.size(); ++p) {
    if (frame.primitiveId[p] != kNoId) continue;
    for (const std::vector<float>* plane : {&frame.albedo, &frame.roughness, &frame.metallic,
                                            &frame.emission, &frame.diffuse, &frame.specular}) {
      const std::size_t channels = plane->size() / frame.primitiveId.size();
      for (std::size_t c = 0; c < channels; ++c)
        ASSERT_EQ((*plane)[channels * p + c], 0.0f) << "pixel " << p;
    }
  }
}

// Untextured spheres: albedo, roughness and metallic are each sphere's
// factors, exactly, and nothing is emitted.
TEST(ShadingAovs, MaterialTermsOfUntexturedSpheresAreTheirFactors) {
  const glm::vec3 base(0.9f, 0.6f, 0.3f);
  const Scene scene = metalRoughSpheresScene(3, 3, base);
  const Frame frame = renderOnce(scene, firstCameraOrDefault(scene), pbrSettings(160, 160));
  std::vector<int> seen(scene.materials.size(), 0);
  for (std::size_t p = 0; p < frame.primitiveId.size(); ++p) {
    const std::uint32_t id = frame.materialId[p];
    if (id == kNoId) continue;
    const Material& m = scene.materials.at(id);
    ++seen[id];
    for (std::size_t c = 0; c < 3; ++c) {
      ASSERT_EQ(frame.albedo[3 * p + c], base[int(c)]) << "pixel " << p;
      ASSERT_EQ(frame.emission[3 * p + c], 0.0f) << "pixel " << p;
    }
    ASSERT_EQ(frame.roughness[p], m.roughnessFactor) << "pixel " << p;
    ASSERT_EQ(frame.metallic[p], m.metallicFactor) << "pixel " << p;
  }
  for (std::size_t m = 0; m < seen.size(); ++m) EXPECT_GT(seen[m], 100) << "material " << m;
  expectClearWhereNothingIs(frame);
}

// KHR_materials_emissive_strength on a shared model: each cube's emission
// is its emissiveFactor x emissiveStrength (and its colour that plus its
// light); the textured backdrop emits nothing.
TEST(ShadingAovs, EmissionIsTheFactorTimesTheStrength) {
  const std::string path = sharedModel("EmissiveStrengthTest");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "sample model absent: " << path;
  const Scene scene = loadGltf(path);
  const Frame frame = renderOnce(scene, firstCameraOrDefault(scene), pbrSettings(240, 80));
  int emitting = 0, dark = 0;
  for (std::size_t p = 0; p < frame.materialId.size(); ++p) {
    const std::uint32_t id = frame.materialId[p];
    if (id == kNoId) continue;
    const Material& m = scene.materials.at(id);
    ASSERT_FALSE(m.emissive.present()) << "the test model's emission has no texture";
    const glm::vec3 expected = m.emissiveFactor * m.emissiveStrength;
    for (int c = 0; c < 3; ++c) ASSERT_EQ(frame.emission[3 * p + c], expected[c]) << "pixel " << p;
    (expected.x > 0.0f ? emitting : dark) += 1;
  }
  EXPECT_GT(emitting, 50);
  EXPECT_GT(dark, 500);
}

// Unlit draws: albedo is the colour they show (exactly, at one sample), the
// other terms 0; --exposure scales the colour, not the albedo. The showcase
// without its glass, which composites over surfaces whose AOVs it leaves.
TEST(ShadingAovs, UnlitAlbedoIsTheBaseColourWithoutTheExposure) {
  Scene scene = makeBuiltinScene("showcase");
  std::erase_if(scene.instances, [&](const Instance& instance) {
    const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
    return scene.materials[std::size_t(mesh.material)].alphaMode == AlphaMode::Blend;
  });
  ASSERT_EQ(scene.instances.size(), 6u);
  RenderSettings settings;
  settings.width = 96;
  settings.height = 54;
  settings.aovs = kTermAovs;
  const Frame plain = renderOnce(scene, firstCameraOrDefault(scene), settings);
  settings.exposure = 1.0f;
  const Frame exposed = renderOnce(scene, firstCameraOrDefault(scene), settings);
  EXPECT_TRUE(plain.albedo == exposed.albedo);
  int checked = 0;
  for (std::size_t p = 0; p < plain.primitiveId.size(); ++p) {
    if (plain.primitiveId[p] == kNoId || plain.rgba[4 * p + 3] != 1.0f) continue;
    ++checked;
    for (std::size_t c = 0; c < 3; ++c) {
      ASSERT_EQ(plain.albedo[3 * p + c], plain.rgba[4 * p + c]) << "pixel " << p;
      ASSERT_EQ(plain.emission[3 * p + c] + plain.diffuse[3 * p + c] + plain.specular[3 * p + c],
                0.0f)
          << "pixel " << p;
    }
    ASSERT_EQ(plain.roughness[p] + plain.metallic[p], 0.0f) << "pixel " << p;
  }
  EXPECT_GT(checked, 1000);
  expectClearWhereNothingIs(plain);
}

// Asking for the shading AOVs moves no bit of the colour or depth.
TEST(ShadingAovs, LeaveTheColourAndDepthBitsAlone) {
  const Scene scene = litSpheres();
  RenderSettings settings = pbrSettings(96, 96);
  settings.aovs = 0;
  const Frame plain = renderOnce(scene, firstCameraOrDefault(scene), settings);
  settings.aovs = kShadingAovs;
  const Frame withAovs = renderOnce(scene, firstCameraOrDefault(scene), settings);
  EXPECT_EQ(std::memcmp(plain.rgba.data(), withAovs.rgba.data(), plain.rgba.size() * 4), 0);
  EXPECT_EQ(std::memcmp(plain.depth.data(), withAovs.depth.data(), plain.depth.size() * 4), 0);
  EXPECT_TRUE(plain.albedo.empty() && plain.specular.empty());
  EXPECT_EQ(withAovs.specular.size(), withAovs.depth.size() * 3);
  EXPECT_EQ(withAovs.roughness.size(), withAovs.depth.size());
}

// The CLI: --aov's shading names into the EXR as RGB layers and single
// channels, read back with OpenEXR and, where installed, OpenEXR's and
// OpenImageIO's tools; the sum holds in the file too (on an opaque scene:
// a blended surface's colour is not its AOVs').
TEST(ShadingAovsCli, WritesTheChannelsOtherToolsRead) {
  const fs::path exr = tempPath("cli_shading_aovs.exr");
  const RunResult r =
      run("render builtin:checker-plane --shading pbr --env builtin:sky --width 48 --height 32 "
          "--threads 2 --aov albedo,roughness,metallic --aov emission,diffuse,specular,id --out " +
          exr.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  {
    Imf::InputFile file(exr.string().c_str());
    for (const char* name : {"albedo.R", "albedo.G", "albedo.B", "roughness", "metallic",
                             "emission.R", "emission.G", "emission.B", "diffuse.R", "diffuse.G",
                             "diffuse.B", "specular.R", "specular.G", "specular.B"}) {
      const Imf::Channel* channel = file.header().channels().findChannel(name);
      ASSERT_NE(channel, nullptr) << name;
      EXPECT_EQ(channel->type, Imf::FLOAT) << name;
    }
  }
  int width = 0, height = 0;
  const std::vector<std::uint32_t> ids =
      readChannel<std::uint32_t>(exr, "id.primitive", width, height);
  const std::vector<float> alpha = readChannel<float>(exr, "A", width, height);
  int checked = 0;
  for (const char* c : {"R", "G", "B"}) {
    const std::vector<float> colour = readChannel<float>(exr, c, width, height);
    const std::vector<float> e =
        readChannel<float>(exr, (std::string("emission.") + c).c_str(), width, height);
    const std::vector<float> d =
        readChannel<float>(exr, (std::string("diffuse.") + c).c_str(), width, height);
    const std::vector<float> s =
        readChannel<float>(exr, (std::string("specular.") + c).c_str(), width, height);
    for (std::size_t p = 0; p < colour.size(); ++p) {
      if (ids[p] == kNoId || alpha[p] != 1.0f) continue;
      const double sum = (double(e[p]) + d[p]) + s[p];
      EXPECT_NEAR(colour[p], sum, 2e-6 * (std::fabs(e[p]) + std::fabs(d[p]) + s[p]) + 1e-30)
          << c << " pixel " << p;
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);

  int toolsRun = 0;
  if (runProgram("command", "-v exrheader").exitCode == 0) {
    const RunResult header = runProgram("exrheader", exr.string());
    EXPECT_EQ(header.exitCode, 0) << header.err;
    for (const char* name :
         {"albedo.G, 32-bit floating-point", "roughness, 32-bit floating-point",
          "metallic, 32-bit floating-point", "specular.B, 32-bit floating-point"})
      EXPECT_NE(header.out.find(name), std::string::npos) << name << " not in\n" << header.out;
    ++toolsRun;
  }
  if (runProgram("command", "-v iinfo").exitCode == 0) {
    const RunResult info = runProgram("iinfo", "-v " + exr.string());
    EXPECT_EQ(info.exitCode, 0) << info.err;
    for (const char* name : {"albedo.R", "roughness", "metallic", "emission.G", "diffuse.B"})
      EXPECT_NE(info.out.find(name), std::string::npos) << name << " not in iinfo's\n" << info.out;
    ++toolsRun;
  }
  if (toolsRun == 0) GTEST_SKIP() << "neither iinfo nor exrheader installed";
}

}  // namespace
}  // namespace quadra
