// Internals of the glTF loader shared by its translation units: the model a
// load is reading plus its path (for messages), the checked accessor reader,
// primitive → Mesh conversion, animations, and the material/texture/image table. Not part
// of the public API; tinygltf types are only forward-declared here.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/parallel.h"
#include "io/image_io.h"
#include "scene/scene.h"

namespace tinygltf {
class Model;
class Value;
struct Image;
struct Material;
}  // namespace tinygltf

namespace quadra::gltf {

// The parsed file as tinygltf left it (nothing in it is trusted yet) and the
// path every message starts with.
struct ModelRef {
  const tinygltf::Model& model;
  const std::string& path;
  MemoryBudget* budget = nullptr;  // the load's (LoadOptions::maxMemory); null: unbounded
  // Where decoding runs in parallel (LoadOptions::threads / arena); null: on
  // the loading thread.
  const Executor* executor = nullptr;

  Error fail(const std::string& problem) const { return makeError(path, problem); }
  // Counts `bytes` against the load's budget before they are allocated for
  // `what`, or throws its one-line error. From the loading thread only, in
  // file order, so the message does not depend on scheduling.
  void charge(const std::string& what, std::uint64_t bytes) const {
    if (budget) budget->charge(what, bytes);
  }
  std::string note(const std::string& text) const { return path + ": " + text; }
};

// ---- accessors (gltf_accessor.cpp) -------------------------------------------

// An accessor after every reference and byte range in it was checked: its
// elements can be read without further checks.
struct AccessorView {
  int index = -1;
  int componentType = 0;  // a glTF componentType code (5120..5126)
  int components = 0;     // 1 for SCALAR .. 4 for VEC4, 16 for MAT4 (MAT2, MAT3 are rejected)
  bool normalized = false;
  std::uint64_t count = 0;
  const std::uint8_t* data = nullptr;  // null: no bufferView, the base values are zeros
  std::uint64_t stride = 0;            // bytes between elements
};

// Checks accessor `index` (what: the role it plays, for messages, e.g.
// "mesh 0 primitive 1 NORMAL").
AccessorView viewAccessor(const ModelRef& ref, int index, const std::string& what);

// The bytes decoding accessor `index` allocates (count * components 32-bit
// values), for charging the budget before decoding: 0 when the accessor is
// invalid (its reader reports why, naming the role it plays).
std::uint64_t decodedAccessorBytes(const ModelRef& ref, int index);

// count * components floats, glTF's normalization rules applied and sparse
// substitutions made.
std::vector<float> decodeFloats(const ModelRef& ref, const AccessorView& view);
// Integer elements of an unsigned SCALAR accessor (indices), sparse applied.
std::vector<std::uint32_t> decodeUnsigned(const ModelRef& ref, const AccessorView& view);

// The bytes of bufferView `index`, checked to lie inside its buffer.
struct ByteRange {
  const std::uint8_t* data = nullptr;
  std::uint64_t size = 0;
};
ByteRange bufferViewBytes(const ModelRef& ref, int index);

// ---- primitives (gltf_primitive.cpp) -----------------------------------------

// What of a primitive the scene needs beyond positions, normals and colours.
struct PrimitiveNeeds {
  bool texcoordSets[2] = {false, false};  // the TEXCOORD_n its material's textures read
  // The TEXCOORD_n its material's normal map reads: TANGENT (and its morph
  // deltas) is read, or MikkTSpace tangents generated; -1: no normal map.
  int normalMapSet = -1;
};

// Primitive `primitiveIndex` of glTF mesh `meshIndex` as a triangle list.
// Returns false (with a note) when the primitive draws nothing we rasterize.
bool buildMesh(const ModelRef& ref, int meshIndex, int primitiveIndex, const PrimitiveNeeds& needs,
               Mesh& out, std::vector<std::string>& notes);

// ---- animations (gltf_animation.cpp) ----------------------------------------

// The file's animations into scene.animations, in file order (so an index
// names the same animation in both). sceneNodeOf maps a glTF node to its
// Scene::nodes entry, -1 for nodes outside the chosen scene, whose channels
// are dropped. Every sampler's accessors are checked, used or not.
void readAnimations(const ModelRef& ref, const std::vector<int>& sceneNodeOf, Scene& scene,
                    std::vector<std::string>& notes);

// ---- materials, textures, images (gltf_material.cpp) -------------------------

// Encoded image bytes that tinygltf read for images given by URI (file or data
// URI), keyed by image index. Images inside bufferViews are not copied here:
// their bytes are taken from the (checked) bufferView when needed.
struct ImageStash {
  std::map<int, std::vector<std::uint8_t>> encoded;
};

// tinygltf's image callback: stashes the bytes instead of decoding, so only the
// images some used material reads get decoded (user_data: an ImageStash).
bool stashImageBytes(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn,
                     int requiredWidth, int requiredHeight, const unsigned char* bytes, int size,
                     void* userData);

// The scene's materials and textures, made on first use from the glTF ones a
// drawn primitive references.
class MaterialTable {
 public:
  MaterialTable(const ModelRef& ref, const ImageStash& stash, std::vector<std::string>& notes);

  // Scene material index for glTF material `gltfMaterial` (-1 stays -1).
  int sceneMaterial(int gltfMaterial);
  // The TEXCOORD sets and tangents a primitive drawn with the scene material
  // needs (-1: the default material, which reads nothing).
  PrimitiveNeeds needsOf(int sceneMaterialIndex) const;
  // Decodes the images the textures use and moves materials and textures into
  // the scene.
  void finish(Scene& scene);

 private:
  // How a material reads a texture, which decides its image's decode: colour
  // from sRGB, data (normals, metallic-roughness, occlusion) as linear codes,
  // and a texture of which only alpha is read (always linear) shares
  // whichever decode of its image another use needs.
  enum class TextureUse : std::uint8_t { Colour, Data, AlphaOnly };

  int sceneTexture(int gltfTexture, const std::string& what, TextureUse use);
  // One textureInfo (glTF 2.0 §5.25, with KHR_texture_transform): `what`
  // names it in messages ("material 2 normalTexture").
  MaterialTexture materialTexture(int index, int texCoord, const tinygltf::Value* transform,
                                  const std::string& what, TextureUse use);
  // A textureInfo given as JSON inside a material extension.
  MaterialTexture extensionTexture(const tinygltf::Value& info, const std::string& what,
                                   TextureUse use);
  void readExtensions(const tinygltf::Material& source, const std::string& what,
                      Material& material);
  // "image N ('uri')" for messages.
  std::string imageName(int imageIndex) const;
  // The image's encoded bytes (a checked bufferView or what tinygltf read).
  ByteRange encodedImage(int imageIndex) const;
  // Charges the budget for decoding the image, as its header gives the size.
  void chargeDecode(int imageIndex) const;
  // Linear float pixels, and the storage format that keeps the source's
  // precision: RGBA16F for 8-bit images, RGBA32F for 16-bit ones.
  std::shared_ptr<const Image> decodeImage(int imageIndex, ImageColour colour, TexelFormat& storage,
                                           const Executor& executor) const;

  struct PendingTexture {
    int image = -1;  // glTF image index
    SamplerState sampler;
    TextureUse use = TextureUse::Colour;
    int gltfTexture = -1;
  };

  const ModelRef& ref_;
  const ImageStash& stash_;
  std::vector<std::string>& notes_;
  std::vector<Material> materials_;
  std::vector<PendingTexture> textures_;
  std::map<int, int> materialOf_;                        // glTF material → scene material
  std::map<std::pair<int, TextureUse>, int> textureOf_;  // glTF texture, use → pending texture
};

}  // namespace quadra::gltf
