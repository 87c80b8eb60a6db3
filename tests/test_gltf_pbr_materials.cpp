// What the loader reads for lit shading: the metallic-roughness material's
// textures and factors (each textureInfo with its texCoord and
// KHR_texture_transform, each texture in the colour space glTF 2.0 §3.9
// gives its use), KHR_materials_emissive_strength, _ior, _specular and
// _unlit, KHR_lights_punctual lights placed by their nodes (and moved by
// animations), and TANGENT with its morph deltas. Small files are written
// here with known values; the shared models are checked against their JSON
// as tinygltf parses it, on its own.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "gltf_files.h"
#include "gltf_reference.h"
#include "scene/animation.h"
#include "scene/gltf_loader.h"
#include "texture/texel_format.h"

namespace quadra {
namespace {

using namespace gltf_files;

// A 2x1 RGBA8 image with known codes, as a data URI.
const std::vector<std::uint16_t> kCodes = {64, 128, 192, 255, 255, 0, 10, 100};

std::string imageJson() {
  return "{\"uri\":\"data:image/png;base64," + base64(encodePng(2, 1, 8, kCodes)) + "\"}";
}

double srgbDecode(double encoded) {  // IEC 61966-2-1, in double
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// The unit square seen from +Z with NORMAL, TEXCOORD_0 and TEXCOORD_1, drawn
// with material 0 by node 0; `extraAttributes` adds e.g. TANGENT.
Doc squareWithMaterial(const std::map<std::string, int>& extraAttributes = {}, Doc doc = Doc{}) {
  const int position =
      doc.addData(std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, kFloat, 3);
  const int normal = doc.addData(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, 3);
  const int uv = doc.addData(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}, kFloat, 2);
  const int indices = doc.addData(std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3}, kUShort, 1);
  std::map<std::string, int> attributes = {
      {"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}, {"TEXCOORD_1", uv}};
  attributes.insert(extraAttributes.begin(), extraAttributes.end());
  doc.addMesh(primitive(attributes, indices, -1, 0));
  doc.addNode("\"mesh\":0");
  return doc;
}

TEST(GltfPbrMaterials, EveryTextureAndFactorIsReadInItsColourSpace) {
  TempDir dir;
  Doc doc = squareWithMaterial();
  doc.images = {imageJson()};
  doc.samplers = {"{\"wrapS\":33071}"};
  doc.textures = {"{\"source\":0}", "{\"source\":0,\"sampler\":0}"};
  doc.materials = {
      "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
      "\"metallicFactor\":0.25,\"roughnessFactor\":0.75,"
      "\"metallicRoughnessTexture\":{\"index\":0,\"texCoord\":1,\"extensions\":"
      "{\"KHR_texture_transform\":{\"offset\":[0.5,0.25],\"rotation\":0.5,\"scale\":[2,3]}}}},"
      "\"normalTexture\":{\"index\":1,\"scale\":0.5},"
      "\"occlusionTexture\":{\"index\":0,\"strength\":0.25},"
      "\"emissiveTexture\":{\"index\":1,\"texCoord\":1},\"emissiveFactor\":[0.1,0.2,0.3],"
      "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":5},"
      "\"KHR_materials_ior\":{\"ior\":1.33},"
      "\"KHR_materials_specular\":{\"specularFactor\":0.6,\"specularTexture\":{\"index\":0},"
      "\"specularColorFactor\":[0.9,0.8,1.7],\"specularColorTexture\":{\"index\":1,"
      "\"extensions\":{\"KHR_texture_transform\":{\"texCoord\":1}}}}}}"};
  doc.extraTopLevel =
      "\"extensionsUsed\":[\"KHR_texture_transform\",\"KHR_materials_emissive_strength\","
      "\"KHR_materials_ior\",\"KHR_materials_specular\"]";
  std::vector<std::string> notes;
  const Scene scene = loadGltf(doc.writeGltf(dir, "all"), {}, &notes);
  EXPECT_TRUE(notes.empty()) << notes.front();

  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.metallicFactor, 0.25f);
  EXPECT_EQ(m.roughnessFactor, 0.75f);
  EXPECT_EQ(m.normalScale, 0.5f);
  EXPECT_EQ(m.occlusionStrength, 0.25f);
  EXPECT_EQ(m.emissiveFactor, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(m.emissiveStrength, 5.0f);
  EXPECT_EQ(m.ior, 1.33f);
  EXPECT_EQ(m.specularFactor, 0.6f);
  EXPECT_EQ(m.specularColorFactor, glm::vec3(0.9f, 0.8f, 1.7f));  // not bounded above
  EXPECT_FALSE(m.unlit);
  EXPECT_EQ(m.metallicRoughness.texCoord, 1);
  EXPECT_EQ(m.metallicRoughness.transform.offset, glm::vec2(0.5f, 0.25f));
  EXPECT_EQ(m.metallicRoughness.transform.rotation, 0.5f);
  EXPECT_EQ(m.metallicRoughness.transform.scale, glm::vec2(2.0f, 3.0f));
  EXPECT_EQ(m.emissive.texCoord, 1);
  EXPECT_EQ(m.specularColor.texCoord, 1);  // the transform's texCoord replaces the info's
  EXPECT_TRUE(m.occlusion.transform.isIdentity());

  // Four textures: glTF texture 0 as sRGB (base colour; specular reads only
  // its alpha, the same in both decodes, so shares it) and as linear
  // (metallic-roughness and occlusion share it); texture 1 as linear
  // (normal) and as sRGB (emissive and specular colour).
  ASSERT_EQ(scene.textures.size(), 4u);
  EXPECT_EQ(m.specular.texture, m.baseColorTexture);
  EXPECT_EQ(m.occlusion.texture, m.metallicRoughness.texture);
  EXPECT_EQ(m.specularColor.texture, m.emissive.texture);
  const std::set<int> distinct = {m.baseColorTexture, m.metallicRoughness.texture, m.normal.texture,
                                  m.emissive.texture};
  EXPECT_EQ(distinct.size(), 4u);
  const auto texture = [&](int index) -> const Texture& {
    return *scene.textures.at(std::size_t(index));
  };
  // One decode per colour space: the two sRGB textures share an Image, the
  // two linear ones another, whatever their samplers.
  EXPECT_EQ(texture(m.baseColorTexture).sharedImage(), texture(m.emissive.texture).sharedImage());
  EXPECT_EQ(texture(m.metallicRoughness.texture).sharedImage(),
            texture(m.normal.texture).sharedImage());
  EXPECT_NE(texture(m.baseColorTexture).sharedImage(), texture(m.normal.texture).sharedImage());
  EXPECT_EQ(texture(m.normal.texture).sampler().wrapU, WrapMode::ClampToEdge);
  EXPECT_EQ(texture(m.metallicRoughness.texture).sampler().wrapU, WrapMode::Repeat);
  for (int x = 0; x < 2; ++x) {
    const float* srgb = texture(m.baseColorTexture).image().texel(x, 0);
    const float* linear = texture(m.normal.texture).image().texel(x, 0);
    for (int c = 0; c < 4; ++c) {
      const double code = kCodes[std::size_t(x * 4 + c)];
      const double expected = c == 3 ? code / 255.0 : srgbDecode(code / 255.0);
      EXPECT_NEAR(srgb[c], expected, 1e-6) << x << " " << c;
      EXPECT_EQ(linear[c], float(code) * kUnorm8Scale) << x << " " << c;
    }
  }

  // The normal map without TANGENT: tangents generated; both TEXCOORD sets
  // read, as textures use both.
  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& mesh = scene.meshes[0];
  EXPECT_EQ(mesh.tangents.size(), mesh.positions.size());
  EXPECT_EQ(mesh.texcoords[0].size(), mesh.positions.size());
  EXPECT_EQ(mesh.texcoords[1].size(), mesh.positions.size());
  for (const glm::vec4& t : mesh.tangents) {
    // u grows along +X, and v downward in the image (y up here): (1, 0, 0, +1).
    EXPECT_NEAR(t.x, 1.0f, 1e-6f);
    EXPECT_NEAR(t.y, 0.0f, 1e-6f);
    EXPECT_NEAR(t.z, 0.0f, 1e-6f);
    EXPECT_EQ(t.w, 1.0f);
  }
}

TEST(GltfPbrMaterials, DefaultsAndUnlit) {
  TempDir dir;
  Doc doc = squareWithMaterial();
  doc.materials = {"{\"extensions\":{\"KHR_materials_unlit\":{}}}"};
  doc.extraTopLevel =
      "\"extensionsUsed\":[\"KHR_materials_unlit\"],"
      "\"extensionsRequired\":[\"KHR_materials_unlit\"]";
  const Scene scene = loadGltf(doc.writeGltf(dir, "defaults"));
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  const Material defaults;
  EXPECT_TRUE(m.unlit);
  EXPECT_EQ(m.metallicFactor, 1.0f);
  EXPECT_EQ(m.roughnessFactor, 1.0f);
  EXPECT_EQ(m.emissiveFactor, glm::vec3(0.0f));
  EXPECT_EQ(m.emissiveStrength, 1.0f);
  EXPECT_EQ(m.ior, 1.5f);
  EXPECT_EQ(m.specularFactor, 1.0f);
  EXPECT_EQ(m.specularColorFactor, glm::vec3(1.0f));
  EXPECT_EQ(m.normalScale, defaults.normalScale);
  EXPECT_EQ(m.occlusionStrength, defaults.occlusionStrength);
  for (const MaterialTexture* t :
       {&m.metallicRoughness, &m.normal, &m.occlusion, &m.emissive, &m.specular, &m.specularColor})
    EXPECT_FALSE(t->present());
  EXPECT_TRUE(scene.textures.empty());
  // Nothing reads coordinates or tangents: none kept.
  const Mesh& mesh = scene.meshes.at(0);
  EXPECT_TRUE(mesh.texcoords[0].empty());
  EXPECT_TRUE(mesh.texcoords[1].empty());
  EXPECT_TRUE(mesh.tangents.empty());
}

TEST(GltfPbrMaterials, FactorsOutsideTheirRangeAreClampedWithANote) {
  TempDir dir;
  Doc doc = squareWithMaterial();
  doc.materials = {
      "{\"pbrMetallicRoughness\":{\"metallicFactor\":1.5,\"roughnessFactor\":-0.5},"
      "\"emissiveFactor\":[2,0.5,-1],"
      "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":-3},"
      "\"KHR_materials_ior\":{\"ior\":0.5},"
      "\"KHR_materials_specular\":{\"specularFactor\":2}}}"};
  std::vector<std::string> notes;
  const Scene scene = loadGltf(doc.writeGltf(dir, "clamped"), {}, &notes);
  const Material& m = scene.materials.at(0);
  EXPECT_EQ(m.metallicFactor, 1.0f);
  EXPECT_EQ(m.roughnessFactor, 0.0f);
  EXPECT_EQ(m.emissiveFactor, glm::vec3(1.0f, 0.5f, 0.0f));
  EXPECT_EQ(m.emissiveStrength, 0.0f);
  EXPECT_EQ(m.ior, 1.0f);
  EXPECT_EQ(m.specularFactor, 1.0f);
  EXPECT_EQ(notes.size(), 7u);
  for (const std::string& note : notes) EXPECT_NE(note.find("material 0"), std::string::npos);
}

// Each bad value fails the load with one line naming the file and the
// culprit.
TEST(GltfPbrMaterials, BadValuesFailWithOneLineNamingTheFile) {
  TempDir dir;
  struct Case {
    const char* name;
    std::string materials, lights, node, problem;
  };
  const std::string light = "{\"type\":\"point\"}";
  const std::vector<Case> cases = {
      {"negative-intensity", "", "{\"type\":\"point\",\"intensity\":-1}", "0", "light 0 intensity"},
      {"infinite-intensity", "", "{\"type\":\"point\",\"intensity\":1e999}", "0", "1e999"},
      {"named-light", "", light + ",{\"type\":\"point\",\"name\":\"lamp\",\"intensity\":-2}", "1",
       "light 1 ('lamp') intensity"},
      {"negative-range", "", "{\"type\":\"point\",\"range\":-1}", "0", "light 0 range"},
      {"inner-not-below-outer", "",
       "{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0.5,\"outerConeAngle\":0.5}}", "0",
       "light 0 spot cone"},
      {"outer-past-right-angle", "", "{\"type\":\"spot\",\"spot\":{\"outerConeAngle\":1.6}}", "0",
       "light 0 spot cone"},
      {"negative-colour", "", "{\"type\":\"point\",\"color\":[1,-1,1]}", "0", "light 0 color"},
      {"unknown-type", "", "{\"type\":\"area\"}", "0", "unknown type 'area'"},
      {"light-out-of-range", "", light, "3", "refers to light 3, which does not exist"},
      {"normal-texture-out-of-range", "{\"normalTexture\":{\"index\":7}}", "", "",
       "material 0 normalTexture refers to texture 7"},
      {"specular-texture-out-of-range",
       "{\"extensions\":{\"KHR_materials_specular\":{\"specularTexture\":{\"index\":9}}}}", "", "",
       "material 0 KHR_materials_specular specularTexture refers to texture 9"},
      // JSON has no NaN, and a number past a double is the parser's error,
      // one line naming the file too.
      {"infinite-normal-scale", "{\"normalTexture\":{\"index\":0,\"scale\":-1e999}}", "", "",
       "-1e999"},
      {"string-ior", "{\"extensions\":{\"KHR_materials_ior\":{\"ior\":\"high\"}}}", "", "",
       "material 0 KHR_materials_ior ior"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Doc doc;
    doc.images = {imageJson()};
    doc.textures = {"{\"source\":0}"};
    doc.materials = {c.materials.empty() ? "{}" : c.materials};
    if (!c.lights.empty())
      doc.extraTopLevel =
          "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[" + c.lights + "]}}";
    doc = squareWithMaterial({}, doc);
    if (!c.node.empty())
      doc.nodes[0] =
          "{\"mesh\":0,\"extensions\":{\"KHR_lights_punctual\":{\"light\":" + c.node + "}}}";
    expectError(doc.writeGltf(dir, c.name), c.problem);
  }
}

TEST(GltfPbrMaterials, RequiredExtensionsNowImplementedLoad) {
  for (const char* name :
       {"KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_specular",
        "KHR_materials_unlit", "KHR_lights_punctual", "KHR_texture_transform"})
    EXPECT_TRUE(implementsGltfExtension(name)) << name;
  EXPECT_FALSE(implementsGltfExtension("KHR_materials_clearcoat"));
  EXPECT_FALSE(implementsGltfExtension("KHR_materials_transmission"));
}

// The node's world transform with its scale divided out, in double.
glm::dmat4 rigid(glm::dmat4 m) {
  for (int axis = 0; axis < 3; ++axis) m[axis] /= glm::length(glm::dvec3(m[axis]));
  return m;
}

void expectMatrixNear(const glm::mat4& actual, const glm::dmat4& expected) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(actual[c][r], expected[c][r], 1e-6) << c << r;
}

TEST(GltfPbrMaterials, LightsArePlacedByTheirNodesAndFollowAnimations) {
  TempDir dir;
  Doc doc;
  // Node 0: a parent scaled by 2 and turned; node 1 its child carrying a
  // spot light; node 2 a root carrying the directional light and animated.
  doc.nodes = {
      "{\"children\":[1],\"translation\":[1,2,3],"
      "\"rotation\":[0,0.7071067811865476,0,0.7071067811865476],\"scale\":[2,2,2]}",
      "{\"translation\":[0,0,-1],\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}}",
      "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}"};
  doc.scenes = {"{\"nodes\":[0,2]}"};
  const int times = doc.addData(std::vector<float>{0, 1}, kFloat, 1);
  const int values = doc.addData(std::vector<float>{0, 0, 0, 4, 6, 8}, kFloat, 3);
  doc.extraTopLevel =
      "\"extensionsUsed\":[\"KHR_lights_punctual\"],"
      "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":["
      "{\"type\":\"directional\",\"color\":[1,0.5,0.25],\"intensity\":3},"
      "{\"type\":\"spot\",\"intensity\":40,\"range\":7,"
      "\"spot\":{\"innerConeAngle\":0.25,\"outerConeAngle\":0.5}},"
      "{\"type\":\"point\"}]}},"
      "\"animations\":[{\"channels\":[{\"sampler\":0,\"target\":{\"node\":2,\"path\":"
      "\"translation\"}}],\"samplers\":[{\"input\":" +
      std::to_string(times) + ",\"output\":" + std::to_string(values) + "}]}]";
  Scene scene = loadGltf(doc.writeGltf(dir, "lights"));
  // Lights in node walk order: node 1's spot, then node 2's directional;
  // light 2, on no node, is not placed.
  ASSERT_EQ(scene.lights.size(), 2u);
  const Light& spot = scene.lights[0];
  EXPECT_EQ(spot.type, Light::Type::Spot);
  EXPECT_EQ(spot.color, glm::vec3(1.0f));
  EXPECT_EQ(spot.intensity, 40.0f);
  EXPECT_EQ(spot.range, 7.0f);
  EXPECT_EQ(spot.innerConeAngle, 0.25f);
  EXPECT_EQ(spot.outerConeAngle, 0.5f);
  ASSERT_GE(spot.node, 0);
  EXPECT_EQ(scene.nodes[std::size_t(spot.node)].fileIndex, 1);
  const glm::dmat4 parent =
      glm::translate(glm::dmat4(1.0), glm::dvec3(1, 2, 3)) *
      glm::mat4_cast(glm::dquat(0.7071067811865476, 0, 0.7071067811865476, 0)) *
      glm::scale(glm::dmat4(1.0), glm::dvec3(2.0));
  const glm::dmat4 child = parent * glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, -1));
  expectMatrixNear(spot.world, rigid(child));
  // The turn takes the child's -Z (its shining direction) to -X; its place
  // is the parent's origin plus twice that.
  EXPECT_NEAR(spot.world[3].x, -1.0f, 1e-6f);
  EXPECT_NEAR(spot.world[2].x, 1.0f, 1e-6f);

  const Light& sun = scene.lights[1];
  EXPECT_EQ(sun.type, Light::Type::Directional);
  EXPECT_EQ(sun.color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(sun.intensity, 3.0f);
  EXPECT_EQ(sun.range, 0.0f);
  expectMatrixNear(sun.world, glm::dmat4(1.0));

  NodePose pose;
  poseNodes(scene, 0, 0.5, pose);
  placeOnNodes(scene, pose);
  expectMatrixNear(scene.lights[1].world,
                   glm::translate(glm::dmat4(1.0), glm::dvec3(2.0, 3.0, 4.0)));
  expectMatrixNear(scene.lights[0].world, rigid(child));  // its nodes did not move
}

TEST(GltfPbrMaterials, TangentsAndTheirMorphDeltasAreRead) {
  TempDir dir;
  for (const bool quantized : {false, true}) {
    SCOPED_TRACE(quantized ? "normalized short" : "float");
    Doc doc;
    doc.images = {imageJson()};
    doc.textures = {"{\"source\":0}"};
    doc.materials = {"{\"normalTexture\":{\"index\":0}}"};
    int tangent = 0;
    if (quantized) {
      tangent = doc.addData(std::vector<std::int16_t>{0, 32767, 0, -32767, 0, 32767, 0, -32767,
                                                      32767, 0, 0, 32767, 32767, 0, 0, 32767},
                            kShort, 4, "\"normalized\":true");
      doc.extraTopLevel =
          "\"extensionsRequired\":[\"KHR_mesh_quantization\"],"
          "\"extensionsUsed\":[\"KHR_mesh_quantization\"]";
    } else {
      tangent = doc.addData(std::vector<float>{0, 1, 0, -1, 0, 1, 0, -1, 1, 0, 0, 1, 1, 0, 0, 1},
                            kFloat, 4);
    }
    // Morph deltas through a sparse accessor: vertex 2 only.
    const int sparseIndices = doc.addView(std::vector<std::uint16_t>{2});
    const int sparseValues = doc.addView(std::vector<float>{0.5f, -0.25f, 0.125f});
    const int delta = doc.addAccessor(
        -1, kFloat, 4, "VEC3",
        "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" + std::to_string(sparseIndices) +
            ",\"componentType\":5123},\"values\":{\"bufferView\":" + std::to_string(sparseValues) +
            "}}");
    doc = squareWithMaterial({{"TANGENT", tangent}}, doc);
    doc.meshes[0].insert(doc.meshes[0].find("\"indices\""),
                         "\"targets\":[{\"TANGENT\":" + std::to_string(delta) + "}],");
    const Scene scene = loadGltf(doc.writeGltf(dir, quantized ? "quantized" : "float"));
    const Mesh& mesh = scene.meshes.at(0);
    const std::vector<glm::vec4> expected = {
        {0, 1, 0, -1}, {0, 1, 0, -1}, {1, 0, 0, 1}, {1, 0, 0, 1}};
    ASSERT_EQ(mesh.tangents.size(), 4u);
    for (std::size_t v = 0; v < 4; ++v)
      EXPECT_EQ(mesh.tangents[v], expected[v]) << v;  // 32767 / 32767 is exactly 1
    ASSERT_EQ(mesh.targets.size(), 1u);
    const std::vector<glm::vec3> deltas = {{0, 0, 0}, {0, 0, 0}, {0.5f, -0.25f, 0.125f}, {0, 0, 0}};
    EXPECT_EQ(mesh.targets[0].tangents, deltas);
  }
}

// ---- the shared models -----------------------------------------------------------

// The glTF texture a textureInfo names, and whether glTF 2.0 gives its use
// sRGB colour, linear data, or alpha only (either decode).
enum class Use { Srgb, Linear, Alpha };

struct Slot {
  int texture = -1;
  int texCoord = 0;
  Use use = Use::Srgb;
};

Slot slotOf(const tinygltf::Value& extensions, const char* extension, const char* key, Use use) {
  if (!extensions.IsObject() || !extensions.Has(extension)) return {};
  const tinygltf::Value& info = extensions.Get(extension).Get(key);
  if (!info.IsObject()) return {};
  return {info.Get("index").GetNumberAsInt(),
          info.Has("texCoord") ? info.Get("texCoord").GetNumberAsInt() : 0, use};
}

// The texture slots of a material, in the order Material keeps them.
std::vector<Slot> slotsOf(const tinygltf::Material& m) {
  tinygltf::Value::Object object;
  for (const auto& [name, value] : m.extensions) object[name] = value;
  const tinygltf::Value extensions(object);
  const auto& pbr = m.pbrMetallicRoughness;
  return {{pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, Use::Srgb},
          {pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, Use::Linear},
          {m.normalTexture.index, m.normalTexture.texCoord, Use::Linear},
          {m.occlusionTexture.index, m.occlusionTexture.texCoord, Use::Linear},
          {m.emissiveTexture.index, m.emissiveTexture.texCoord, Use::Srgb},
          slotOf(extensions, "KHR_materials_specular", "specularTexture", Use::Alpha),
          slotOf(extensions, "KHR_materials_specular", "specularColorTexture", Use::Srgb)};
}

std::vector<const MaterialTexture*> slotsOf(const Material& m) {
  return {nullptr,     &m.metallicRoughness, &m.normal,       &m.occlusion,
          &m.emissive, &m.specular,          &m.specularColor};
}

Scene checkAgainstJson(const std::string& model, std::size_t expectedLights) {
  SCOPED_TRACE(model);
  const std::string path = assetPath(model);
  const tinygltf::Model json = parseReference(path);
  const Scene scene = loadGltf(path);
  // Distinct (glTF texture, decode) pairs the used materials need, alpha-only
  // uses taking the sRGB decode where their image has one anyway.
  std::set<std::pair<int, bool>> expectedTextures;
  std::set<int> srgbImages;
  for (const Material& material : scene.materials)
    for (const Slot& slot : slotsOf(json.materials.at(std::size_t(material.fileIndex))))
      if (slot.texture >= 0 && slot.use == Use::Srgb)
        srgbImages.insert(json.textures.at(std::size_t(slot.texture)).source);
  for (const Material& material : scene.materials) {
    const tinygltf::Material& source = json.materials.at(std::size_t(material.fileIndex));
    const std::vector<Slot> slots = slotsOf(source);
    const std::vector<const MaterialTexture*> fields = slotsOf(material);
    EXPECT_EQ(material.baseColorTexture >= 0, slots[0].texture >= 0);
    for (std::size_t s = 0; s < slots.size(); ++s) {
      if (slots[s].texture >= 0) {
        const int image = json.textures.at(std::size_t(slots[s].texture)).source;
        const bool srgb =
            slots[s].use == Use::Srgb || (slots[s].use == Use::Alpha && srgbImages.count(image));
        expectedTextures.insert({slots[s].texture, srgb});
      }
      if (!fields[s]) continue;
      EXPECT_EQ(fields[s]->present(), slots[s].texture >= 0) << "slot " << s;
      if (fields[s]->present()) {
        EXPECT_EQ(fields[s]->texCoord, slots[s].texCoord) << "slot " << s;
      }
    }
    const auto& pbr = source.pbrMetallicRoughness;
    EXPECT_EQ(material.metallicFactor, float(pbr.metallicFactor));
    EXPECT_EQ(material.roughnessFactor, float(pbr.roughnessFactor));
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(material.emissiveFactor[c], source.emissiveFactor.empty()
                                                ? 0.0f
                                                : float(source.emissiveFactor[std::size_t(c)]));
    const auto strength = source.extensions.find("KHR_materials_emissive_strength");
    EXPECT_EQ(material.emissiveStrength,
              strength == source.extensions.end()
                  ? 1.0f
                  : float(strength->second.Get("emissiveStrength").GetNumberAsDouble()));
    if (material.normal.present()) {
      EXPECT_EQ(material.normalScale, float(source.normalTexture.scale));
    }
    if (material.occlusion.present()) {
      EXPECT_EQ(material.occlusionStrength, float(source.occlusionTexture.strength));
    }
  }
  EXPECT_EQ(scene.textures.size(), expectedTextures.size());
  // Every mesh whose material has a normal map has a tangent per vertex.
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.material < 0 || !scene.materials[std::size_t(mesh.material)].normal.present()) {
      EXPECT_TRUE(mesh.tangents.empty());
      continue;
    }
    EXPECT_EQ(mesh.tangents.size(), mesh.positions.size());
    std::size_t bad = 0;
    for (const glm::vec4& t : mesh.tangents)  // stored ones are rounded
      bad += !(t.w == 1.0f || t.w == -1.0f) || std::fabs(glm::length(glm::vec3(t)) - 1.0f) > 1e-2f;
    EXPECT_EQ(bad, 0u);
  }
  EXPECT_EQ(scene.lights.size(), expectedLights);
  for (const Light& light : scene.lights) {
    const int file = scene.nodes.at(std::size_t(light.node)).fileIndex;
    const int index = json.nodes.at(std::size_t(file))
                          .extensions.at("KHR_lights_punctual")
                          .Get("light")
                          .GetNumberAsInt();
    const tinygltf::Light& source = json.lights.at(std::size_t(index));
    EXPECT_EQ(light.intensity, float(source.intensity));
    EXPECT_EQ(light.type == Light::Type::Point, source.type == "point");
    if (!source.color.empty()) {
      EXPECT_EQ(light.color,
                glm::vec3(float(source.color[0]), float(source.color[1]), float(source.color[2])));
    }
  }
  return scene;
}

TEST(GltfPbrMaterials, SharedModelsLoadTheirMaterialsAndLights) {
  const Scene bottle = checkAgainstJson("WaterBottle", 0);
  checkAgainstJson("BoomBoxWithAxes", 0);
  checkAgainstJson("NormalTangentTest", 0);
  checkAgainstJson("NormalTangentMirrorTest", 0);
  const Scene emissive = checkAgainstJson("EmissiveStrengthTest", 0);
  const Scene spheres = checkAgainstJson("MetalRoughSpheresNoTextures", 0);
  checkAgainstJson("LightsPunctualLamp", 5);

  // Figures the JSON gives, as a reader counts them.
  EXPECT_EQ(bottle.textures.size(), 4u);  // base, MR = occlusion (one texture), normal, emissive
  std::set<float> strengths;
  for (const Material& m : emissive.materials) strengths.insert(m.emissiveStrength);
  EXPECT_GT(strengths.size(), 2u);
  EXPECT_TRUE(spheres.textures.empty());
  const tinygltf::Model json = parseReference(assetPath("MetalRoughSpheresNoTextures"));
  std::set<std::pair<double, double>> fileFactors;
  for (const tinygltf::Material& m : json.materials)
    fileFactors.insert(
        {m.pbrMetallicRoughness.metallicFactor, m.pbrMetallicRoughness.roughnessFactor});
  std::set<std::pair<double, double>> loaded;
  for (const Material& m : spheres.materials) loaded.insert({m.metallicFactor, m.roughnessFactor});
  EXPECT_GT(loaded.size(), 40u);  // a grid of metallic x roughness
  EXPECT_LE(loaded.size(), fileFactors.size());
}

}  // namespace
}  // namespace quadra
