// Scene: everything a frame draws, decoded and validated, independent of the
// file format it came from (glTF loader and built-in scenes both produce it).
//
// Geometry is kept per primitive as plain triangle lists (strips and fans are
// expanded at load), with attributes as float arrays: the vertex stage reads
// nothing else. The node tree the instances and cameras hang from is kept with
// the file's animations, so that a frame at time t can move them
// (scene/animation.h); a scene without animations never needs it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_precision.hpp>

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

// A texture a material reads besides its base colour: which one, through
// which TEXCOORD_n set, and that set's KHR_texture_transform.
struct MaterialTexture {
  int texture = -1;  // index into Scene::textures, -1 when none
  int texCoord = 0;  // 0 or 1
  TextureTransform transform;
  bool present() const { return texture >= 0; }
};

// glTF 2.0's metallic-roughness material. The lit shading's reading of each
// field is ../shared/LIGHTING.md "The material"; unlit and lit shading read
// only the base colour, alpha and sidedness.
struct Material {
  glm::vec4 baseColorFactor{1.0f};
  int baseColorTexture = -1;            // index into Scene::textures, -1 when none
  int baseColorTexCoord = 0;            // which TEXCOORD_n set the texture reads (0 or 1)
  TextureTransform baseColorTransform;  // applied to that set before the lookup
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
  int fileIndex = -1;  // the material's index in the glTF file; -1: built in

  float metallicFactor = 1.0f;
  float roughnessFactor = 1.0f;
  MaterialTexture metallicRoughness;  // linear; B metallic, G roughness
  MaterialTexture normal;             // linear tangent-space normal map
  float normalScale = 1.0f;
  MaterialTexture occlusion;  // linear; R
  float occlusionStrength = 1.0f;
  MaterialTexture emissive;  // sRGB
  glm::vec3 emissiveFactor{0.0f};
  float emissiveStrength = 1.0f;  // KHR_materials_emissive_strength
  float ior = 1.5f;               // KHR_materials_ior
  // KHR_materials_specular: the specular weight (A of its texture) and the
  // f0 colour (RGB of its texture, sRGB).
  float specularFactor = 1.0f;
  MaterialTexture specular;
  glm::vec3 specularColorFactor{1.0f};
  MaterialTexture specularColor;
  bool unlit = false;  // KHR_materials_unlit: every shading shows the unlit colour
};

// A morph target's per-vertex deltas (glTF 2.0 §3.7.2.2). Each array is
// empty when the target does not move that attribute, else has one entry per
// vertex of its mesh (sparse accessors are expanded at load).
struct MorphTarget {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> texcoords[2];
  std::vector<glm::vec4> colors;    // COLOR_0 deltas (vec3 inputs get alpha delta 0)
  std::vector<glm::vec3> tangents;  // TANGENT deltas (xyz; w is the base's)
};

// One glTF primitive, as a triangle list. Attribute arrays are empty when the
// primitive does not have them; otherwise they have positions.size() entries.
struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> texcoords[2];  // TEXCOORD_0, TEXCOORD_1
  std::vector<glm::vec4> colors;        // COLOR_0 (vec3 inputs get alpha 1)
  // TANGENT: xyz a unit vector, w = +-1 the bitangent's sign (B = w N x T).
  // Where a primitive whose material has a normal map has none, the
  // MikkTSpace tangents of its (u, 1 - v) are generated at load (LIGHTING.md).
  std::vector<glm::vec4> tangents;
  std::vector<std::uint32_t> indices;  // 3 per triangle, all < positions.size()
  int material = -1;                   // -1: the glTF default material
  // JOINTS_0/1 and WEIGHTS_0/1: up to 8 skin influences per vertex (indices
  // into the skin's joints, weights as decoded). Set 1 only with set 0.
  std::vector<glm::u16vec4> joints[2];
  std::vector<glm::vec4> weights[2];
  std::vector<MorphTarget> targets;
};

// glTF 2.0 §3.7.3: the nodes whose world transforms move a skinned mesh's
// vertices, and each one's inverse bind matrix (the identity by default).
struct Skin {
  std::vector<int> joints;  // Scene::nodes indices
  std::vector<glm::mat4> inverseBindMatrices;
};

// Per-draw state: the fixed-function state one instance is drawn with (depth
// test and write, the depth compare function, face culling, blending), as an
// embedder states it per draw, in the vocabulary of GL's glDepthFunc /
// glCullFace / glBlendFuncSeparate / glBlendEquationSeparate. An instance
// without one is drawn as its material says (Instance::drawState).
//
// Colours are premultiplied linear floats in the frame, so the blend's
// "source" is the shaded colour premultiplied by its alpha: premultiplied
// "over" is (Add, One, OneMinusSrcAlpha) on every channel.
// Passes when `fragment OP stored` holds. Stated for DepthMode::Standard
// (smaller = nearer); a reversed-depth frame (larger = nearer) swaps Less
// with Greater and LessEqual with GreaterEqual (api/camera.h DepthMode), so
// a draw's "nearer wins" stays that whatever the frame's depth mode.
enum class CompareFunction : std::uint8_t {
  Never,
  Less,
  Equal,
  LessEqual,
  Greater,
  NotEqual,
  GreaterEqual,
  Always
};

// Which faces are dropped. Front faces are counter-clockwise with y up
// (glTF's and GL's default), mirrored by a world matrix of negative determinant.
enum class CullMode : std::uint8_t { None, Back, Front };

// result = equation(source * sourceFactor, destination * destinationFactor);
// Min and Max take the unscaled colours (GL ignores the factors there too).
enum class BlendEquation : std::uint8_t { Add, Subtract, ReverseSubtract, Min, Max };

// A factor per channel: the colour ones take each channel's own value (the
// alpha channel's is alpha), the alpha ones take alpha on every channel.
enum class BlendFactor : std::uint8_t {
  Zero,
  One,
  SrcColor,
  OneMinusSrcColor,
  DstColor,
  OneMinusDstColor,
  SrcAlpha,
  OneMinusSrcAlpha,
  DstAlpha,
  OneMinusDstAlpha
};

struct BlendState {
  bool enabled = false;  // off: the fragment replaces what is there
  BlendEquation colorEquation = BlendEquation::Add;
  BlendEquation alphaEquation = BlendEquation::Add;
  BlendFactor srcColor = BlendFactor::One, dstColor = BlendFactor::Zero;
  BlendFactor srcAlpha = BlendFactor::One, dstAlpha = BlendFactor::Zero;

  // glBlendFunc / glBlendEquation: one setting for colour and alpha alike.
  static constexpr BlendState uniform(BlendEquation equation, BlendFactor src, BlendFactor dst) {
    return {true, equation, equation, src, dst, src, dst};
  }
  // Premultiplied "over": dst' = src + (1 - src alpha) dst.
  static constexpr BlendState premultipliedOver() {
    return uniform(BlendEquation::Add, BlendFactor::One, BlendFactor::OneMinusSrcAlpha);
  }
  // dst' = src + dst.
  static constexpr BlendState additive() {
    return uniform(BlendEquation::Add, BlendFactor::One, BlendFactor::One);
  }
  bool operator==(const BlendState&) const = default;
};

struct DrawState {
  // Off: every fragment passes and none writes depth (GL: a disabled depth
  // test does not update the depth buffer), whatever depthWrite says.
  bool depthTest = true;
  bool depthWrite = true;
  CompareFunction depthCompare = CompareFunction::Less;
  CullMode cull = CullMode::Back;
  BlendState blend;
  bool operator==(const DrawState&) const = default;
};

// The compare a frame's kernels run for `compare` stated for standard depth:
// in a reversed-depth frame, Less becomes Greater (and so on).
constexpr CompareFunction compareForDepth(CompareFunction compare, bool reversed) {
  if (!reversed) return compare;
  switch (compare) {
    case CompareFunction::Less:
      return CompareFunction::Greater;
    case CompareFunction::LessEqual:
      return CompareFunction::GreaterEqual;
    case CompareFunction::Greater:
      return CompareFunction::Less;
    case CompareFunction::GreaterEqual:
      return CompareFunction::LessEqual;
    default:
      return compare;
  }
}

// A mesh placed in the world: one node's instance of one primitive.
// A skinned instance (skin >= 0) is placed by its joints: its world is the
// identity and jointMatrices[j] = world of joint j * its inverse bind
// matrix, set with the node transforms (scene/animation.h placeOnNodes).
// morphWeights (one per mesh target) are its node's current weights; both
// stay empty for instances nothing deforms (scene/deformation.h).
// drawState: how the instance is drawn (depth, culling, blending; an
// embedder's per-draw state); none, as its material says: back faces culled
// unless double-sided, BLEND drawn after everything else as depth-ordered
// premultiplied "over" without depth write. Instances with a state are drawn
// in scene order among the opaque and masked ones.
struct Instance {
  int mesh = 0;
  glm::mat4 world{1.0f};
  int node = -1;  // the Scene::nodes entry it hangs from; -1: placed once (built-in scenes)
  int skin = -1;  // index into Scene::skins
  std::vector<glm::mat4> jointMatrices{};
  std::vector<float> morphWeights{};
  std::optional<DrawState> drawState{};
};

// A node of the glTF tree the scene was placed from. Scene::nodes lists them
// parents first (a pre-order walk), so one pass in order composes every
// node's world transform. A node given by a matrix keeps it (glTF forbids
// animating such a node); the others keep their translation, rotation and
// scale, which an animation channel replaces one property at a time.
struct Node {
  int parent = -1;     // index into Scene::nodes, smaller than this node's; -1: a root
  int fileIndex = -1;  // the node's index in the glTF file
  bool hasMatrix = false;
  glm::mat4 local{1.0f};  // the rest transform as loaded (T * R * S, or the matrix)
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z; normalized
  glm::vec3 scale{1.0f};
  // Rest morph weights of the node's mesh (the node's, else the mesh's, else
  // zeros); empty when its mesh has no morph targets.
  std::vector<float> weights;
};

// glTF 2.0 §3.11 animation samplers: `times` are seconds, non-decreasing;
// each key has `components` floats (3 for translation and scale, 4 for a
// rotation quaternion x, y, z, w, one per morph target for weights), and
// CUBICSPLINE keys three such groups: in-tangent, value, out-tangent.
enum class Interpolation : std::uint8_t { Step, Linear, CubicSpline };
struct AnimationSampler {
  Interpolation interpolation = Interpolation::Linear;
  int components = 3;
  std::vector<float> times;
  std::vector<float> values;
};

// Node properties a channel can drive. Weights (glTF path "weights") drive
// the node's morph weights, which its instances' vertices blend.
enum class AnimatedProperty : std::uint8_t { Translation, Rotation, Scale, Weights };
struct AnimationChannel {
  int sampler = 0;  // index into Animation::samplers
  int node = 0;     // index into Scene::nodes
  AnimatedProperty property = AnimatedProperty::Translation;
};

struct Animation {
  std::string name;  // may be empty
  std::vector<AnimationSampler> samplers;
  std::vector<AnimationChannel> channels;
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
  int node = -1;          // the Scene::nodes entry it hangs from; -1: placed once
};

// KHR_lights_punctual: a light at its node's origin shining down the node's
// -Z, in the extension's units (intensity in candela for point and spot
// lights, lux for directional ones; colour linear).
struct Light {
  enum class Type : std::uint8_t { Directional, Point, Spot };
  Type type = Type::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float range = 0.0f;                     // 0: unlimited
  float innerConeAngle = 0.0f;            // radians, spot only
  float outerConeAngle = 0.78539816339f;  // pi / 4
  glm::mat4 world{1.0f};                  // the node's world transform (scale ignored)
  int node = -1;                          // the Scene::nodes entry it hangs from; -1: placed once
};

struct Scene {
  std::string name;  // file path or builtin:NAME, for messages
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<std::shared_ptr<const Texture>> textures;
  std::vector<Instance> instances;
  std::vector<Camera> cameras;
  std::vector<Node> nodes;  // empty for scenes not loaded from a node tree
  std::vector<Skin> skins;
  std::vector<Animation> animations;
  std::vector<Light> lights;  // KHR_lights_punctual, placed by their nodes

  std::size_t triangleCount() const;  // over instances
  // World-space bounds of all instances, skinned and morphed ones as posed;
  // min > max when the scene is empty.
  void bounds(glm::vec3& lo, glm::vec3& hi) const;
};

// Camera::world for a camera on a node with world transform `nodeWorld`:
// a rigid transform, the node's scale divided out.
glm::mat4 cameraWorldOf(glm::mat4 nodeWorld);

// How the material reads its base colour texture's alpha, and so which
// variant of the texture it samples (Texture::forAlpha). For MASK, the cutoff
// on the texture's own alpha is the material's divided by the base colour
// factor's alpha (above 1, nothing passes).
TextureAlpha textureAlphaOf(const Material& material);

// Re-stores every texture of the scene in `format` (sharing the images), for
// comparing storage formats on one scene.
void setTextureStorage(Scene& scene, TexelFormat format);

}  // namespace quadra
