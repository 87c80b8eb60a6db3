// Scene: everything a frame draws, decoded and validated, independent of the
// file format it came from (glTF loader and built-in scenes both produce it).
//
// Geometry is kept per primitive as plain triangle lists (strips and fans are
// expanded at load), with attributes as float arrays: the vertex stage reads
// nothing else.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "texture/texel_format.h"
#include "texture/texture.h"

namespace quadra {

enum class AlphaMode : std::uint8_t { Opaque, Mask, Blend };

// glTF's KHR_texture_transform, as the file gives it: a texture reads
// uv' = T(offset) R(rotation) S(scale) (u, v, 1), with R turning (1, 0) to
// (cos r, -sin r), i.e. counter-clockwise as the image is viewed (v down).
// The default is the identity.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;  // radians
  glm::vec2 scale{1.0f};

  bool isIdentity() const {
    return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f);
  }
  // The 2x3 matrix above (columns: the images of u, of v, and the offset),
  // evaluated in double and rounded once per entry.
  glm::mat3x2 matrix() const;
};

struct Material {
  glm::vec4 baseColorFactor{1.0f};
  int baseColorTexture = -1;            // index into Scene::textures, -1 when none
  int baseColorTexCoord = 0;            // which TEXCOORD_n set the texture reads (0 or 1)
  TextureTransform baseColorTransform;  // applied to that set before the lookup
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

// How the material reads its base colour texture's alpha, and so which
// variant of the texture it samples (Texture::forAlpha). For MASK, the cutoff
// on the texture's own alpha is the material's divided by the base colour
// factor's alpha (above 1, nothing passes).
TextureAlpha textureAlphaOf(const Material& material);

// Re-stores every texture of the scene in `format` (sharing the images), for
// comparing storage formats on one scene.
void setTextureStorage(Scene& scene, TexelFormat format);

}  // namespace quadra
