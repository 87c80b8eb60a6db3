// Scene: everything a frame draws, decoded and validated, independent of the
// file format it came from (glTF loader and built-in scenes both produce it).
//
// Geometry is kept per primitive as plain triangle lists (strips and fans are
// expanded at load), with attributes as float arrays: the vertex stage reads
// nothing else.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "texture/image.h"
#include "texture/sampler_state.h"
#include "texture/texel_format.h"

namespace quadra {

class Executor;
class MipChain;
struct PaddedLevel;
class SummedAreaTable;
struct Ripmap;

// A texture as the scene holds it: its level-0 image in linear float and its
// sampler. The mip chain is built on first use, once, and only for textures
// that a mip filter reads ("model only what a scene needs").
class Texture {
 public:
  // storage: the format the sampling kernels read (texture/texel_format.h).
  Texture(std::shared_ptr<const Image> image, SamplerState sampler,
          TexelFormat storage = TexelFormat::Rgba32F);
  ~Texture();

  const Image& image() const { return *image_; }
  const std::shared_ptr<const Image>& sharedImage() const { return image_; }
  const SamplerState& sampler() const { return sampler_; }
  TexelFormat storage() const { return storage_; }
  // Thread-safe; the first call builds the chain, in parallel on `executor`
  // when one is given.
  const MipChain& mips(const Executor* executor = nullptr) const;
  // The levels as the sampling kernels read them (texture/padded_level.h),
  // each built once on first use: level 0, and levels 1.. of the chain.
  const PaddedLevel& sampledLevel0() const;
  const std::vector<PaddedLevel>& sampledMipLevels(const Executor* executor = nullptr) const;
  // The summed-area table of the sampled level 0 (texture/summed_area.h),
  // built on first use: 32 bytes per texel, only for the `sat` filter.
  const SummedAreaTable& summedAreaTable(const Executor* executor = nullptr) const;
  // The ripmap (texture/ripmap.h), built on first use: about 4x level 0,
  // only for the `ripmap` filter.
  const Ripmap& ripmap(const Executor* executor = nullptr) const;

 private:
  std::shared_ptr<const Image> image_;
  SamplerState sampler_;
  TexelFormat storage_;
  mutable std::once_flag mipsOnce_, level0Once_, mipLevelsOnce_, summedAreaOnce_, ripmapOnce_;
  mutable std::unique_ptr<MipChain> mips_;
  mutable std::unique_ptr<PaddedLevel> level0_;
  mutable std::vector<PaddedLevel> mipLevels_;
  mutable std::unique_ptr<SummedAreaTable> summedArea_;
  mutable std::unique_ptr<Ripmap> ripmap_;
};

enum class AlphaMode : std::uint8_t { Opaque, Mask, Blend };

struct Material {
  glm::vec4 baseColorFactor{1.0f};
  int baseColorTexture = -1;  // index into Scene::textures, -1 when none
  int baseColorTexCoord = 0;  // which TEXCOORD_n set the texture reads (0 or 1)
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
};

// One glTF primitive, as a triangle list. Attribute arrays are empty when the
// primitive does not have them; otherwise they have positions.size() entries.
struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> texcoords[2];  // TEXCOORD_0, TEXCOORD_1
  std::vector<glm::vec4> colors;        // COLOR_0 (vec3 inputs get alpha 1)
  std::vector<std::uint32_t> indices;   // 3 per triangle, all < positions.size()
  int material = -1;                    // -1: the glTF default material
};

// A mesh placed in the world: one node's instance of one primitive.
struct Instance {
  int mesh = 0;
  glm::mat4 world{1.0f};
};

struct Camera {
  enum class Type : std::uint8_t { Perspective, Orthographic };
  Type type = Type::Perspective;
  float yfov = 0.8f;  // radians, perspective only
  float xmag = 1.0f;  // orthographic half-extents
  float ymag = 1.0f;
  float znear = 0.1f;
  float zfar = 0.0f;      // 0: infinite (perspective only)
  glm::mat4 world{1.0f};  // camera-to-world; the camera looks down its -Z
};

struct Scene {
  std::string name;  // file path or builtin:NAME, for messages
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<std::shared_ptr<const Texture>> textures;
  std::vector<Instance> instances;
  std::vector<Camera> cameras;

  std::size_t triangleCount() const;  // over instances
  // World-space bounds of all instances; min > max when the scene is empty.
  void bounds(glm::vec3& lo, glm::vec3& hi) const;
};

// Re-stores every texture of the scene in `format` (sharing the images), for
// comparing storage formats on one scene.
void setTextureStorage(Scene& scene, TexelFormat format);

}  // namespace quadra
