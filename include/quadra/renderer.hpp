// quadra::api::Renderer: renders a Scene into the embedder's own memory.
//
// Thread safety: one frame at a time per Renderer (it keeps its working
// buffers between frames); for concurrent frames use one Renderer per
// thread. Renderers share no global state. A Renderer uses its own worker
// threads (`threads`), which render() waits for, or those of the embedder's
// oneTBB task_arena (quadra/tbb.hpp rendererIn).
// Ownership: render() only writes into the target's, depth target's and AOV
// targets' bytes during the call and keeps no pointer to them.
// Errors: quadra::api::Error with a one-line message; a target that fails
// validation is left untouched.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "quadra/environment.hpp"
#include "quadra/error.hpp"
#include "quadra/export.h"
#include "quadra/scene.hpp"

namespace quadra::api {

namespace detail {
struct RendererAccess;
}

// The target's pixel layout, 4 channels r, g, b, a per pixel, row 0 the top:
// Rgba32F: premultiplied linear floats, the renderer's own values bit for bit;
// Rgba16F: those rounded to IEEE halves (to nearest, ties to even);
// Rgba8Srgb: straight (alpha divided out) r, g, b through RenderOptions'
// tone map, as 8-bit sRGB codes, and a as UNORM8, exactly the bytes
// `quadra render --out FILE.png` writes with the same options.
// The float formats hold radiance x 2^exposure, never tone mapped (the CLI's
// EXR).
enum class PixelFormat : std::uint8_t { Rgba8Srgb, Rgba16F, Rgba32F };

// Bytes per pixel of a format: 4, 8 or 16.
constexpr std::size_t bytesPerPixel(PixelFormat format) {
  return format == PixelFormat::Rgba8Srgb ? 4 : format == PixelFormat::Rgba16F ? 8 : 16;
}

// The embedder's colour buffer. rowStride >= width x bytesPerPixel and a
// multiple of the channel size; pixels must hold rowStride x (height - 1) +
// width x bytesPerPixel bytes and be aligned to the channel size. Bytes past
// each row's pixels (padding) are never written.
struct Target {
  std::span<std::byte> pixels = {};
  int width = 0;  // 1 .. 8192 each
  int height = 0;
  std::size_t rowStride = 0;
  PixelFormat format = PixelFormat::Rgba8Srgb;
};

// An optional depth buffer of floats, the same width and height as the
// target: window depth in [0, 1] of the nearest sample, 1 where nothing is
// drawn. Rules of stride, size and alignment as Target's, with 4-byte pixels.
struct DepthTarget {
  std::span<std::byte> bytes = {};
  std::size_t rowStride = 0;
};

// One AOV plane in the embedder's memory: row 0 the top, each pixel the
// AOV's 4-byte channels (floats, or uint32 for the ids) in a row. Rules of
// stride, size and alignment as Target's, with 4-byte channels. Bytes left
// null (the default) mean the AOV is not asked for.
struct AovTarget {
  std::span<std::byte> bytes = {};
  std::size_t rowStride = 0;
};

// The surface AOVs a render can write besides colour and depth, each only
// when its target is given (and only then computed: a render that asks for
// none costs nothing more). What each holds, from which surface, and its
// value where nothing is drawn are the CLI's `--aov` channels of the same
// name, defined in docs/cli.md "AOVs" (the table there). Channels per pixel:
struct AovTargets {
  AovTarget normal;       // 3 floats: the N.X N.Y N.Z channels
  AovTarget position;     // 3 floats: P.X P.Y P.Z
  AovTarget uv;           // 2 floats: uv.U uv.V
  AovTarget mask;         // 1 float: mask
  AovTarget primitiveId;  // 1 uint32: id.primitive (any id asked computes all three)
  AovTarget nodeId;       // 1 uint32: id.node; a Scene built in code: the InstanceHandle
  AovTarget materialId;   // 1 uint32: id.material; built in code: the MaterialHandle
};
// Not here: `motion` (docs/cli.md "AOVs"), which needs the previous frame's pose,
// and a Scene has only the present one.

enum class Shading : std::uint8_t {
  Unlit,  // base colour x texture x vertex colour
  Lit,    // that times the Lambert term of a light at the camera (needs normals)
  // glTF's metallic-roughness material under the environment and a loaded
  // scene's KHR_lights_punctual lights (../shared/LIGHTING.md,
  // docs/lighting.md); KHR_materials_unlit materials stay unlit. The CLI's
  // default; here Unlit stays the default so that existing code renders as
  // before.
  Pbr,
};

// What a Pbr frame shows where no surface is (the CLI's --background): the
// environment seen through the pixel, filtered over its footprint; the
// clear colour made opaque (its r, g, b, alpha 1: --background color with
// --background-color r,g,b); or nothing (alpha 0).
enum class Background : std::uint8_t { Environment, Color, Transparent };

// How a Rgba8Srgb target maps radiance to [0, 1] before sRGB encoding (the
// CLI's --tonemap): Khronos PBR Neutral, ACES (Hill's fit) or a clamp.
enum class ToneMap : std::uint8_t { PbrNeutral, Aces, None };

struct RenderOptions {
  Shading shading = Shading::Unlit;
  int samples = 1;                                          // per pixel: 1, 2, 4, 8 or 16
  std::array<float, 4> clearColor{0.0f, 0.0f, 0.0f, 0.0f};  // premultiplied linear
  // The bytes a frame may hold (the CLI's --max-memory): its buffers, the
  // tile stage's working memory and the texture levels its filters read,
  // checked before anything is allocated; over it, render throws an Error
  // naming what and how much (docs/cli.md "Memory budget").
  std::uint64_t maxMemory = kDefaultMaxMemory;

  // Pbr's light, each the CLI's option of that name (docs/cli.md, render):
  // --env: unset, builtin:studio (the Renderer makes it once and keeps it).
  std::optional<Environment> environment = {};
  float environmentRotation = 0.0f;   // --env-rotation: degrees about +Y, |x| <= 36000
  float environmentIntensity = 1.0f;  // --env-intensity: 0 .. 1e9
  bool punctualLights = true;         // --lights on|off
  Background background = Background::Environment;  // --background
  // --exposure EV (|EV| <= 64): every shading's radiance x 2^EV.
  float exposure = 0.0f;
  // --tonemap, for Rgba8Srgb targets; unset: PbrNeutral for Pbr, None for
  // Unlit and Lit (their bytes as before tone maps existed).
  std::optional<ToneMap> toneMap = {};
};

struct RendererOptions {
  int threads = 0;  // <= 0: all cores
};

class QUADRA_API Renderer {
 public:
  explicit Renderer(const RendererOptions& options = {});
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  int threadCount() const;

  // Renders `scene` through its camera into `target` (and `depth` and the
  // AOV targets `aovs` gives, when not null). Output is the same bits
  // whatever the thread count or CPU.
  void render(const Scene& scene, const Target& target, const DepthTarget* depth = nullptr,
              const RenderOptions& options = {}, const AovTargets* aovs = nullptr);

 private:
  friend struct detail::RendererAccess;
  struct Impl;
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace quadra::api
