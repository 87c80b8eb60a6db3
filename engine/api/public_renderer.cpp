// The public Renderer (include/quadra/renderer.hpp): checks the embedder's
// buffers and renders through the engine's Renderer. An RGBA32F target (and
// a depth target) whose rows are contiguous is resolved into directly; any
// other is rendered into the Renderer's own float Frame and converted into
// the target's format row by row, leaving the rows' padding alone. The AOV
// targets the embedder gives are asked of the engine and copied row by row
// from its Frame. Pbr frames light with the embedder's Environment (or the
// Renderer's own builtin:studio), and a Rgba8Srgb target gets the tone map
// the CLI's PNG would. And quadra::version().
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "api/public_environment.h"
#include "api/public_scene.h"
#include "api/renderer.h"
#include "core/error.h"
#include "core/parallel.h"
#include "io/tone_map.h"
#include "quadra/quadra.hpp"
#include "quadra/tbb.hpp"
#include "shading/builtin_environments.h"
#include "texture/texel_format.h"

namespace quadra {

const char* version() {
  return QUADRA_VERSION_STRING;
}

}  // namespace quadra

namespace quadra::api {

namespace {

// Size, stride and alignment of one embedder buffer of width x height
// pixels of pixelBytes, channels of channelBytes each.
void checkBuffer(const char* what, std::span<std::byte> bytes, int width, int height,
                 std::size_t rowStride, std::size_t pixelBytes, std::size_t channelBytes) {
  const std::size_t rowBytes = std::size_t(width) * pixelBytes;
  if (rowStride < rowBytes)
    throw Error(std::string(what) + ": row stride " + std::to_string(rowStride) +
                " bytes is less than a row's " + std::to_string(width) + " x " +
                std::to_string(pixelBytes) + " = " + std::to_string(rowBytes));
  if (rowStride % channelBytes != 0)
    throw Error(std::string(what) + ": row stride " + std::to_string(rowStride) +
                " bytes is not a multiple of the channel size " + std::to_string(channelBytes));
  if (reinterpret_cast<std::uintptr_t>(bytes.data()) % channelBytes != 0)
    throw Error(std::string(what) + ": buffer is not aligned to " + std::to_string(channelBytes) +
                " bytes");
  const std::size_t needed = rowStride * (std::size_t(height) - 1) + rowBytes;
  if (bytes.size() < needed)
    throw Error(std::string(what) + ": " + std::to_string(width) + "x" + std::to_string(height) +
                " at row stride " + std::to_string(rowStride) + " needs " + std::to_string(needed) +
                " bytes, the buffer has " + std::to_string(bytes.size()));
}

// Rows in parallel (each row's bytes depend on that row alone, so the
// split changes nothing): the sRGB and half conversions cost more than a
// 1080p frame's render when done on one thread.
constexpr std::size_t kRowsPerTask = 16;

void writeColor(const Frame& frame, const Target& target, quadra::ToneMap toneMap,
                const Executor& executor) {
  const std::size_t floatsPerRow = std::size_t(frame.width) * 4;
  executor.parallelFor(
      std::size_t(frame.height), kRowsPerTask, [&](std::size_t first, std::size_t end) {
        for (std::size_t y = first; y < end; ++y) {
          const float* in = &frame.rgba[y * floatsPerRow];
          std::byte* out = target.pixels.data() + y * target.rowStride;
          switch (target.format) {
            case PixelFormat::Rgba32F:
              std::memcpy(out, in, floatsPerRow * sizeof(float));
              break;
            case PixelFormat::Rgba16F:
              for (std::size_t i = 0; i < floatsPerRow; ++i) {
                const std::uint16_t half = floatToHalf(in[i]);
                std::memcpy(out + 2 * i, &half, 2);
              }
              break;
            case PixelFormat::Rgba8Srgb:
              encodeDisplayRow(toneMap, in, frame.width, reinterpret_cast<std::uint8_t*>(out));
              break;
          }
        }
      });
}

// Rows of rowBytes each, contiguous in `rows`, into a buffer of rowStride
// apart (checked by checkBuffer), rows in parallel.
void copyRows(const void* rows, std::size_t rowBytes, int height, std::span<std::byte> out,
              std::size_t rowStride, const Executor& executor) {
  executor.parallelFor(std::size_t(height), kRowsPerTask, [&](std::size_t first, std::size_t end) {
    for (std::size_t y = first; y < end; ++y)
      std::memcpy(out.data() + y * rowStride, static_cast<const std::byte*>(rows) + y * rowBytes,
                  rowBytes);
  });
}

// Each public AOV target: its name in messages, its 4-byte channels per
// pixel, the engine's Aov bit that computes it (none for mask, which is the
// frame's coverage) and the Frame plane it is copied from.
struct AovPlane {
  AovTarget AovTargets::*target;
  const char* what;
  std::size_t channels;
  std::optional<Aov> aov;
  const void* (*plane)(const Frame&);
};
constexpr AovPlane kAovPlanes[] = {
    {&AovTargets::normal, "normal AOV target", 3, Aov::Normal,
     [](const Frame& f) -> const void* { return f.normal.data(); }},
    {&AovTargets::position, "position AOV target", 3, Aov::Position,
     [](const Frame& f) -> const void* { return f.position.data(); }},
    {&AovTargets::uv, "uv AOV target", 2, Aov::Uv,
     [](const Frame& f) -> const void* { return f.uv.data(); }},
    {&AovTargets::mask, "mask AOV target", 1, std::nullopt,
     [](const Frame& f) -> const void* { return f.coverage.data(); }},
    {&AovTargets::primitiveId, "primitiveId AOV target", 1, Aov::Ids,
     [](const Frame& f) -> const void* { return f.primitiveId.data(); }},
    {&AovTargets::nodeId, "nodeId AOV target", 1, Aov::Ids,
     [](const Frame& f) -> const void* { return f.nodeId.data(); }},
    {&AovTargets::materialId, "materialId AOV target", 1, Aov::Ids,
     [](const Frame& f) -> const void* { return f.materialId.data(); }},
};

// The AOV targets `aovs` gives (null bytes: not asked), each checked like
// the depth target.
std::vector<const AovPlane*> askedAovs(const AovTargets* aovs, int width, int height) {
  std::vector<const AovPlane*> asked;
  if (!aovs) return asked;
  for (const AovPlane& plane : kAovPlanes) {
    const AovTarget& target = aovs->*plane.target;
    if (!target.bytes.data()) continue;
    checkBuffer(plane.what, target.bytes, width, height, target.rowStride, plane.channels * 4, 4);
    asked.push_back(&plane);
  }
  return asked;
}

}  // namespace

struct Renderer::Impl {
  quadra::Renderer renderer;
  Frame frame;        // kept between frames: its buffers are reused
  Executor executor;  // for the conversion into the target, on the same threads or arena
  // The Pbr frames' environment when the options name none, made on the
  // first such frame: one object, so its preparation is kept too.
  std::optional<Environment> defaultEnvironment;
  explicit Impl(const RendererConfig& config)
      : renderer(config),
        executor(config.arena ? Executor(*config.arena) : Executor(config.threads)) {}
};

namespace detail {
struct RendererAccess {
  static Renderer make(const RendererConfig& config) {
    return Renderer(std::make_unique<Renderer::Impl>(config));
  }
};
}  // namespace detail

namespace {

RendererConfig configOf(const RendererOptions& options) {
  RendererConfig config;
  config.threads = options.threads;
  return config;
}

// The shading, Pbr's light and the exposure of `options` into `settings`,
// checked by the CLI's rules (its options' ranges, api/renderer.h); returns
// the tone map of a Rgba8Srgb target.
quadra::ToneMap applyLighting(const RenderOptions& options,
                              std::optional<Environment>& defaultEnvironment,
                              RenderSettings& settings) {
  switch (options.shading) {
    case Shading::Unlit:
      settings.shading = quadra::Shading::Unlit;
      break;
    case Shading::Lit:
      settings.shading = quadra::Shading::Lit;
      break;
    case Shading::Pbr:
      settings.shading = quadra::Shading::Pbr;
      break;
    default:
      throw Error("render options: unknown shading");
  }
  if (!(std::fabs(options.environmentRotation) <= kMaxEnvironmentRotation))
    throw Error("render options: environmentRotation " +
                std::to_string(options.environmentRotation) +
                " is out of range (-36000..36000 degrees)");
  if (!(options.environmentIntensity >= 0.0f &&
        options.environmentIntensity <= kMaxEnvironmentIntensity))
    throw Error("render options: environmentIntensity " +
                std::to_string(options.environmentIntensity) + " must be in 0..1e9");
  if (!(std::fabs(options.exposure) <= kMaxExposure))
    throw Error("render options: exposure " + std::to_string(options.exposure) +
                " is out of range (-64..64 EV)");
  switch (options.background) {
    case Background::Environment:
      settings.background = quadra::Background::Environment;
      break;
    case Background::Color:
      settings.background = quadra::Background::Color;
      settings.clearColor.a = 1.0f;  // opaque, as --background color
      break;
    case Background::Transparent:
      settings.background = quadra::Background::Transparent;
      break;
    default:
      throw Error("render options: unknown background");
  }
  settings.environmentRotation = options.environmentRotation;
  settings.environmentIntensity = options.environmentIntensity;
  settings.punctualLights = options.punctualLights;
  settings.exposure = options.exposure;
  if (settings.shading == quadra::Shading::Pbr) {
    if (!options.environment && !defaultEnvironment)
      defaultEnvironment = Environment::load(kDefaultEnvironment);
    settings.environment = detail::EnvironmentAccess::image(
        options.environment ? *options.environment : *defaultEnvironment);
  }
  if (!options.toneMap)
    return settings.shading == quadra::Shading::Pbr ? quadra::ToneMap::PbrNeutral
                                                    : quadra::ToneMap::None;
  switch (*options.toneMap) {
    case ToneMap::PbrNeutral:
      return quadra::ToneMap::PbrNeutral;
    case ToneMap::Aces:
      return quadra::ToneMap::Aces;
    case ToneMap::None:
      return quadra::ToneMap::None;
  }
  throw Error("render options: unknown tone map");
}

}  // namespace

Renderer::Renderer(const RendererOptions& options)
    : impl_(std::make_unique<Impl>(configOf(options))) {}
Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

Renderer rendererIn(tbb::task_arena& arena) {
  RendererConfig config;
  config.arena = &arena;
  return detail::RendererAccess::make(config);
}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

int Renderer::threadCount() const {
  return impl_->renderer.threadCount();
}

void Renderer::render(const Scene& scene, const Target& target, const DepthTarget* depth,
                      const RenderOptions& options, const AovTargets* aovs) {
  if (target.width < 1 || target.height < 1 || target.width > kMaxViewportSize ||
      target.height > kMaxViewportSize)
    throw Error("render target: " + std::to_string(target.width) + "x" +
                std::to_string(target.height) + " is not within 1.." +
                std::to_string(kMaxViewportSize) + " pixels each way");
  if (target.format != PixelFormat::Rgba8Srgb && target.format != PixelFormat::Rgba16F &&
      target.format != PixelFormat::Rgba32F)
    throw Error("render target: unknown pixel format");
  const std::size_t pixelBytes = bytesPerPixel(target.format);
  checkBuffer("render target", target.pixels, target.width, target.height, target.rowStride,
              pixelBytes, pixelBytes / 4);
  if (depth)
    checkBuffer("depth target", depth->bytes, target.width, target.height, depth->rowStride,
                sizeof(float), sizeof(float));
  const std::vector<const AovPlane*> askedPlanes = askedAovs(aovs, target.width, target.height);

  const auto& inside = detail::SceneAccess::of(scene);
  const quadra::Camera camera = inside.camera ? *inside.camera : firstCameraOrDefault(inside.scene);
  RenderSettings settings;
  settings.width = target.width;
  settings.height = target.height;
  settings.samples = options.samples;
  settings.clearColor = {options.clearColor[0], options.clearColor[1], options.clearColor[2],
                         options.clearColor[3]};
  const quadra::ToneMap toneMap = applyLighting(options, impl_->defaultEnvironment, settings);
  settings.frameDepth = depth != nullptr;
  settings.maxMemory = options.maxMemory;
  for (const AovPlane* plane : askedPlanes) {
    if (plane->aov)
      settings.aovs |= std::uint32_t(*plane->aov);
    else
      settings.frameCoverage = true;
  }
  // The tile stage's streaming stores need 16-byte aligned colour.
  Frame& frame = impl_->frame;
  const std::size_t width = std::size_t(target.width);
  const bool colorInPlace = target.format == PixelFormat::Rgba32F &&
                            target.rowStride == width * 16 &&
                            reinterpret_cast<std::uintptr_t>(target.pixels.data()) % 16 == 0;
  const bool depthInPlace = depth && depth->rowStride == width * sizeof(float);
  {
    // The frame must not keep the embedder's pointers past this call.
    struct Borrowed {
      Frame& frame;
      ~Borrowed() { frame.rgbaInto = frame.depthInto = nullptr; }
    } borrowed{frame};
    frame.rgbaInto = colorInPlace ? reinterpret_cast<float*>(target.pixels.data()) : nullptr;
    frame.depthInto = depthInPlace ? reinterpret_cast<float*>(depth->bytes.data()) : nullptr;
    try {
      impl_->renderer.render(inside.scene, camera, settings, frame);
    } catch (const quadra::Error& error) {  // the engine's, as the public type
      throw Error(error.what());
    } catch (const std::logic_error& error) {  // a failed internal check (core/error.h)
      throw Error(std::string("quadra: ") + error.what());
    }
  }

  if (!colorInPlace) writeColor(frame, target, toneMap, impl_->executor);
  if (depth && !depthInPlace)
    copyRows(frame.depth.data(), width * sizeof(float), target.height, depth->bytes,
             depth->rowStride, impl_->executor);
  for (const AovPlane* plane : askedPlanes) {
    const AovTarget& out = aovs->*plane->target;
    copyRows(plane->plane(frame), width * plane->channels * 4, target.height, out.bytes,
             out.rowStride, impl_->executor);
  }
}

}  // namespace quadra::api
