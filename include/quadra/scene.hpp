// quadra::api::Scene: what a frame draws, built by the embedder in code from
// its own arrays (meshes, textures, materials, instances, a camera) or loaded
// from glTF (quadra::api::load). Everything the embedder passes is validated
// and copied in; nothing refers to the embedder's memory afterwards.
//
// Why a namespace of its own: the engine's internal types are quadra::Scene,
// quadra::Mesh, ...; the facade that converts between them needs both in one
// translation unit (docs/api.md).
//
// Thread safety: a Scene is a value. Several Renderers may render one Scene
// at once (const access); changing it (add*, update*, set*) while a render
// reads it is a data race, so change it between frames.
// Errors: every function throws quadra::api::Error (quadra/error.hpp) with a
// one-line message naming what is wrong; on a throw the scene is unchanged.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "quadra/error.hpp"
#include "quadra/export.h"

namespace quadra::api {

// A 4x4 matrix in column-major order (glTF's and OpenGL's): element
// [column * 4 + row]; the translation is elements 12, 13, 14.
using Matrix4 = std::array<float, 16>;
constexpr Matrix4 kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

// Handles index the scene that made them; one of another scene, or made up,
// is an Error when used.
struct MeshHandle {
  std::uint32_t index = 0;
};
struct TextureHandle {
  std::uint32_t index = 0;
};
struct MaterialHandle {
  std::uint32_t index = 0;
};
struct InstanceHandle {
  std::uint32_t index = 0;
};

// Every member has a default (= {}), so designated initializers may name
// only the ones used without -Wmissing-field-initializers.
// A triangle list. Counts are checked: positions.size() must be a multiple
// of 3 (the vertex count V is a third of it), each optional attribute either
// empty or exactly V entries long, and exactly one of the two index arrays
// non-empty, a multiple of 3 long, every index < V.
struct MeshData {
  std::span<const float> positions = {};  // x, y, z per vertex
  std::span<const float> normals = {};    // x, y, z per vertex (needed by Shading::Lit)
  std::span<const float> uvs = {};        // u, v per vertex; v = 0 is the texture's top row (glTF)
  std::span<const float> colors = {};     // linear r, g, b, a per vertex
  std::span<const std::uint32_t> indices32 = {};
  std::span<const std::uint16_t> indices16 = {};
};

// How texels are given, and also how they are stored for sampling (each is
// kept exactly: no precision is lost or made up). Rgba8Srgb: r, g, b 8-bit
// sRGB codes, a UNORM; Rgba8Unorm: all four UNORM (linear); Rgba16F: IEEE
// halves; Rgba32F: floats. Colours are straight (not premultiplied).
enum class TextureFormat : std::uint8_t { Rgba8Srgb, Rgba8Unorm, Rgba16F, Rgba32F };
enum class Wrap : std::uint8_t { Repeat, MirroredRepeat, ClampToEdge };
// Nearest and Bilinear read level 0 only; Trilinear and Anisotropic build
// the mip chain on the first frame that needs it.
enum class Filter : std::uint8_t { Nearest, Bilinear, Trilinear, Anisotropic };

struct TextureData {
  int width = 0;  // at least 1 each
  int height = 0;
  TextureFormat format = TextureFormat::Rgba8Srgb;
  // Row 0 is the top row. rowStride: bytes from one row to the next; 0 means
  // tightly packed (width x 4 channels x channel size).
  std::span<const std::byte> texels = {};
  std::size_t rowStride = 0;
  Wrap wrapU = Wrap::Repeat;
  Wrap wrapV = Wrap::Repeat;
  Filter filter = Filter::Trilinear;
};

enum class AlphaMode : std::uint8_t { Opaque, Mask, Blend };  // glTF's alphaMode

// glTF's metallic-roughness base colour, which is what quadra shades:
// baseColor x texture (when given) x the mesh's colours (when given).
struct MaterialData {
  std::array<float, 4> baseColor{1.0f, 1.0f, 1.0f, 1.0f};  // linear, straight
  std::optional<TextureHandle> texture = {};               // read at the mesh's uvs
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;  // Mask only
  bool doubleSided = false;  // false: back faces (clockwise on screen) are culled
};

// Per-draw state (setDrawState), as OpenGL states it. Depth compares are
// stated with smaller = nearer; colours are premultiplied linear floats, so
// the blend's source is the shaded colour premultiplied by its alpha, and
// premultiplied "over" is (Add, One, OneMinusSrcAlpha).
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
// Front faces are counter-clockwise on screen (y up), as glTF and GL have it.
enum class CullMode : std::uint8_t { None, Back, Front };
// result = equation(source x srcFactor, destination x dstFactor); Min and Max
// take the colours unscaled.
enum class BlendEquation : std::uint8_t { Add, Subtract, ReverseSubtract, Min, Max };
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
struct BlendData {
  bool enabled = false;  // off: the fragment replaces what is there
  BlendEquation colorEquation = BlendEquation::Add;
  BlendEquation alphaEquation = BlendEquation::Add;
  BlendFactor srcColor = BlendFactor::One, dstColor = BlendFactor::Zero;
  BlendFactor srcAlpha = BlendFactor::One, dstAlpha = BlendFactor::Zero;
};
// An instance with a draw state is drawn in submission order with it
// (blending in that order, per sample); without one (the default) its
// material decides: opaque and masked first, then BLEND materials composited
// per sample in exact depth order (order-independent). A disabled depth test
// writes no depth either.
struct DrawStateData {
  bool depthTest = true;
  bool depthWrite = true;
  CompareFunction depthCompare = CompareFunction::Less;
  CullMode cull = CullMode::Back;
  BlendData blend = {};
};

// The camera looks down its own -Z with +Y up; `world` places it
// (camera-to-world, a rigid transform). The viewport's aspect ratio is the
// render target's, so pixels stay square. Depth is 0 at znear, 1 at zfar.
struct CameraData {
  enum class Projection : std::uint8_t { Perspective, Orthographic };
  Projection projection = Projection::Perspective;
  float yfov = 0.8f;  // radians, perspective
  float ymag = 1.0f;  // half-height of the view, orthographic
  float znear = 0.1f;
  float zfar = 0.0f;  // 0: infinite (perspective only)
  Matrix4 world = kIdentity;
};

// Camera-to-world matrix of a camera at eye looking at target.
QUADRA_API Matrix4 lookAt(const std::array<float, 3>& eye, const std::array<float, 3>& target,
                          const std::array<float, 3>& up);

namespace detail {
struct SceneAccess;
}

class QUADRA_API Scene {
 public:
  Scene();  // empty: no meshes, no camera
  ~Scene();
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;
  Scene(const Scene&) = delete;  // a scene may be large: copies are explicit
  Scene& operator=(const Scene&) = delete;

  MeshHandle addMesh(const MeshData& mesh);
  // Replaces the geometry of that mesh (its vertex count may change) for
  // every instance drawing it; no other mesh or texture is touched.
  void updateMesh(MeshHandle handle, const MeshData& mesh);

  TextureHandle addTexture(const TextureData& texture);
  // Replaces that texture's texels and state; materials reading it read the
  // new one from the next frame. Other textures keep their built mip chains.
  void updateTexture(TextureHandle handle, const TextureData& texture);

  MaterialHandle addMaterial(const MaterialData& material);

  // One draw of `mesh` with `material`, placed by `transform` (object to
  // world; every element finite).
  InstanceHandle addInstance(MeshHandle mesh, MaterialHandle material,
                             const Matrix4& transform = kIdentity);
  void setTransform(InstanceHandle instance, const Matrix4& transform);
  // Gives the instance its own depth, cull and blend state; nullopt goes
  // back to its material's.
  void setDrawState(InstanceHandle instance, const std::optional<DrawStateData>& state);

  // The camera render() uses. Without one: a loaded scene's first camera,
  // else a camera framing the whole scene from the front (+Z).
  void setCamera(const CameraData& camera);

  std::size_t meshCount() const;
  std::size_t instanceCount() const;

  // A loaded scene's glTF animations (a scene built in code has none).
  int animationCount() const;
  std::string animationName(int animation) const;  // "" when the file names none
  double animationDuration(int animation) const;   // seconds: its last key's time
  // Poses the file's nodes `seconds` into `animation` (-1: the rest pose, as
  // loaded): node transforms, skins, morph weights and the cameras on nodes,
  // as `quadra render --sequence F:L --fps R` poses frame f at f / R, so
  // the frames are the CLI's bit for bit. Instances added in code keep their
  // transforms. Without any camera (none set, none in the file) the scene is
  // framed once, at the rest pose, when it is first posed, as the CLI frames
  // a sequence. seconds must be finite.
  void setAnimationTime(int animation, double seconds);

 private:
  friend struct detail::SceneAccess;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// What a load may read and allocate: the guards for a file from someone you
// do not trust (docs/cli.md "Scene sandbox" and "Memory budget" give the rules;
// they are the CLI's --allow-path, --max-memory and --scene).
inline constexpr std::uint64_t kDefaultMaxMemory = std::uint64_t(8) << 30;  // 8 GiB
struct LoadOptions {
  // Folders besides the file's own that its buffer and image URIs may read;
  // each must exist.
  std::vector<std::string> allowedPaths = {};
  // Bytes the load may allocate for what the file controls (the files read,
  // decoded buffers, meshes, images), each charged before it is allocated:
  // going over is an Error naming the file and the allocation.
  std::uint64_t maxMemory = kDefaultMaxMemory;
  int scene = -1;  // the glTF scene to place; -1: the file's default (or scene 0)
};

// Loads a .gltf or .glb file, its buffers and images (which must lie in the
// file's folder unless options.allowedPaths says otherwise). Meshes and
// textures can be added to the result; the file's own meshes have no handles.
QUADRA_API Scene load(const std::string& path, const LoadOptions& options = {});

}  // namespace quadra::api
