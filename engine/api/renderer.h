// quadra's embedding API: a Renderer (threads + kernel path, no global state)
// turns a Scene seen through a Camera into a Frame.
//
//   quadra::Scene scene = quadra::loadGltf("model.glb");
//   quadra::Renderer renderer({.threads = 0});           // all cores, best ISA
//   quadra::Frame frame;
//   renderer.render(scene, scene.cameras.at(0), {.width = 1280, .height = 720}, frame);
//   quadra::writeFrame(frame, "out.exr");
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "api/camera.h"
#include "core/memory_budget.h"
#include "core/parallel.h"
#include "io/frame.h"
#include "scene/scene.h"
#include "shading/environment_image.h"
#include "simd/isa.h"
#include "texture/sampler_state.h"
#include "window/sample_pattern.h"
#include "window/window_space.h"

namespace quadra {

struct RendererConfig {
  int threads = 0;         // <= 0: all cores
  std::optional<Isa> isa;  // unset: the best the CPU has; set: must be supported
  // Set: frames run inside this arena of the embedder's (which must outlive
  // the renderer), with its concurrency as the thread count; threads is unused.
  TaskArena* arena = nullptr;
};

enum class Shading : std::uint8_t {
  Unlit,  // baseColorFactor x baseColorTexture (sRGB-decoded) x COLOR_0
  Lit,    // unlit colour x Lambert term of a head light (needs NORMAL)
  // glTF's metallic-roughness material under the environment and the
  // scene's punctual lights: ../shared/LIGHTING.md (docs/lighting.md).
  // KHR_materials_unlit materials stay unlit.
  Pbr,
};

// What a Pbr frame's pixels show where no surface covers them: the
// environment seen through the pixel (filtered over its footprint), the
// frame's clear colour, or nothing (alpha 0).
enum class Background : std::uint8_t { Environment, Color, Transparent };

// What a test or report can ask the tile stage to output instead of colour.
enum class DebugView : std::uint8_t {
  None,
  CoverageCount,  // R = number of triangles covering the pixel; no depth test
  TexCoord,       // R, G = perspective-correct TEXCOORD_0 at the pixel centre; A = 1
  // R, G, B, A = du/dx, dv/dx, du/dy, dv/dy of TEXCOORD_0 as the sampler gets
  // them (RenderSettings::derivatives: exact at each pixel centre, or one
  // footprint per 2x2 quad from its top-left pixel, helper lanes included),
  // in normalized texture units per pixel; depth-tested.
  Derivatives,
};

// How opaque and masked draws are shaded. TwoPass: a visibility pass keeps
// each sample's nearest triangle, then only the visible pixels are shaded,
// packed densely into SIMD lanes. Forward: each triangle is shaded as it is
// rasterized (every covered pixel that passes the depth test so far). Both
// write the same bits; Forward is there for measurement and tests.
enum class OpaqueShading : std::uint8_t { TwoPass, Forward };

// Where a sequence's scene stood one frame earlier (t - 1/fps), for the
// motion AOV: that frame's camera and every instance's world matrix, in
// Scene::instances order, and, for skinned and morphed instances, their
// joint matrices and morph weights then (as Instance holds them). Left
// empty, the deformations are taken as they are now: only the camera and
// the world matrices move.
struct PreviousPose {
  Camera camera;
  std::vector<glm::mat4> instanceWorlds;
  std::vector<std::vector<glm::mat4>> instanceJoints;
  std::vector<std::vector<float>> instanceMorphWeights;
};

// What RenderSettings' light and exposure accept, as the CLI's options
// (--env-rotation, --env-intensity, --exposure) and the public API check them:
// 100 turns either way, a scale up to 1e9, 64 EV either way (2^64 x the
// largest texel kept, 2^32, stays far inside float's range).
constexpr double kMaxEnvironmentRotation = 36000.0;
constexpr double kMaxEnvironmentIntensity = 1e9;
constexpr double kMaxExposure = 64.0;

struct RenderSettings {
  int width = 1920;
  int height = 1080;
  std::optional<Filter> filter;  // unset: each texture's glTF sampler decides
  int maxAniso = 16;
  float lodBias = 0.0f;  // added to every texture lookup's LOD
  // Trilinear's level: nearer the pixel's box footprint (default), or GL's λ
  // for GPU-matching output (texture/sampler_state.h LodRule).
  LodRule lodRule = LodRule::Box;
  Shading shading = Shading::Unlit;
  glm::vec4 clearColor{0.0f};  // premultiplied linear
  // Pbr shading's light (LIGHTING.md "The environment", "The light"): the
  // panorama (required for Pbr), turned about +Y by environmentRotation
  // degrees and scaled by environmentIntensity, and the scene's
  // KHR_lights_punctual lights unless punctualLights is off. The renderer
  // preprocesses a panorama once and keeps the result while the same image
  // (the same shared object) is asked for again.
  std::shared_ptr<const EnvironmentImage> environment;
  float environmentRotation = 0.0f;
  float environmentIntensity = 1.0f;
  bool punctualLights = true;
  Background background = Background::Environment;
  // Every shading: the frame holds radiance x 2^exposure.
  float exposure = 0.0f;
  // Reversed: depth 1 at near and 0 at far, test GREATER, clear to 0; the
  // frame's depth (and the EXR Z channel) then holds reversed depth.
  DepthMode depth = DepthMode::Standard;
  DebugView debugView = DebugView::None;
  // Texture footprints from the triangles' exact derivatives (default) or
  // from 2x2 quad differences as GPUs take them; Quad shades forward.
  DerivativeMode derivatives = DerivativeMode::Analytic;
  OpaqueShading opaqueShading = OpaqueShading::TwoPass;
  // Coverage and depth samples per pixel: 1, 2, 4, 8 or 16, at the
  // positions of window/sample_pattern.h. The frame is their pixelFilter
  // (premultiplied linear); its depth the nearest sample's.
  int samples = 1;
  ShadingRate shadingRate = ShadingRate::Pixel;  // window/sample_pattern.h
  // Box: each pixel the mean of its own samples. BlackmanHarris: every sample
  // within 2 px of the pixel's centre, weighted (tile/pixel_filter.h).
  PixelFilter pixelFilter = PixelFilter::Box;
  // Fill Frame::depth (the EXR Z channel); off, the frame's depth stays empty
  // and resolve writes a fifth less memory.
  bool frameDepth = true;
  // Fill Frame::coverage (the EXR mask channel), filtered by pixelFilter.
  bool frameCoverage = false;
  // MASK materials: instead of testing alpha against their cutoff, cover
  // round(alpha * samples) of a pixel's samples (alpha to coverage: each
  // sample k of N passes where its own alpha is at least (k + 0.5) / N; at
  // one sample, alpha 0.5 is the cutoff), so alpha-tested edges resolve to
  // their alpha instead of a hard step.
  bool alphaToCoverage = false;
  // The surface AOVs to fill (io/frame.h Aov bits; docs/cli.md "AOVs"): none by
  // default, and then nothing of their work is done. They need every
  // depth-writing draw in the visibility pass (analytic derivatives,
  // two-pass opaque shading, no debug view); render throws otherwise.
  AovSet aovs = 0;
  // The motion AOV's previous pose; null: a still, whose motion is 0.
  const PreviousPose* previousPose = nullptr;
  // The bytes a frame may hold (--max-memory): the frame's buffers, the tile
  // stage's working memory for this renderer's threads, and the levels of
  // every texture drawn as its filter reads them (built yet or not, so the
  // outcome is the same for the first frame and the thousandth). Checked
  // before anything is allocated; over it, render throws an Error naming what
  // and how much. The rules: docs/cli.md, "Memory budget".
  std::uint64_t maxMemory = kDefaultMaxMemory;
};

// Where a frame's time went, in ms of wall time. Setup and bin run in one
// parallel pass over the front-end chunks, and raster, shade and resolve in
// one task per tile: such a pass's wall time is split among its stages in
// proportion to the thread time each took, so the stages add up to the frame.
struct StageTimes {
  // Preparing a lit frame's environment (shading/prepared_environment.h),
  // within `draws`; 0 for a frame that reused the one before's.
  double environment = 0.0;
  double draws = 0.0;   // the draw list, with texture levels built on first use
  double vertex = 0.0;  // vertex stage
  double setup = 0.0;   // clip and triangle setup
  double bin = 0.0;
  double raster = 0.0;  // tile stage: coverage and depth (and shading, until it has its own pass)
  double shade = 0.0;   // tile stage: shading pass
  double resolve = 0.0;
};

// Counts of what the front end did with the frame's triangles, and where the
// frame's time went.
struct FrameStats {
  std::size_t trianglesIn = 0;     // submitted (instances x triangles)
  std::size_t trianglesDrawn = 0;  // set up and binned (after clipping splits)
  std::size_t culledBackFace = 0;
  std::size_t culledOutside = 0;      // entirely outside a clip plane / the viewport
  std::size_t droppedDegenerate = 0;  // zero area after snapping (or clipped onto the eye)
  std::size_t droppedInvalid = 0;     // NaN or Inf in a position or an attribute read
  std::size_t clipped = 0;            // needed clipping against near/far/guard band
  StageTimes stages;
};

class Renderer {
 public:
  struct Impl;
  explicit Renderer(const RendererConfig& config = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  Isa isa() const;
  int threadCount() const;

  // Renders one frame; throws Error for settings it cannot honour (size out of
  // range). out is resized as needed; its previous contents are irrelevant,
  // except out.metadata.strings, which are kept for the writers.
  // One frame at a time per Renderer (it keeps its working buffers between
  // frames); concurrent frames need a Renderer each.
  FrameStats render(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                    Frame& out);

 private:
  std::unique_ptr<Impl> impl_;
};

// The largest width or height render accepts: window coordinates then stay
// inside the 16.8 fixed-point guard band.
constexpr int kMaxViewportSize = kMaxViewport;

// A camera framing the whole scene from the front (+Z side, slightly above),
// for scenes that have none.
Camera defaultCamera(const Scene& scene);

// View `view` of `views` (0 <= view < views) of a turntable around the scene:
// defaultCamera's framing turned about the vertical through the bounds'
// centre by 360 degrees x view / views, counter-clockwise seen from above;
// view 0 is defaultCamera. The scene's own cameras play no part.
Camera orbitCamera(const Scene& scene, int view, int views);

// The scene's first camera, or defaultCamera when it has none.
Camera firstCameraOrDefault(const Scene& scene);

// The order a colour frame draws the scene's instances in, as indices into
// scene.instances: first every instance whose material does not blend or
// that has a DrawState of its own, in scene order, then the blended ones
// (alphaMode BLEND, no DrawState) back to front by the
// view-space depth of their mesh's bounding-box centre (ties keep scene
// order). Instances of meshes without triangles are left out. The tile stage
// composites blended fragments in depth order per sample whatever the draw
// order; back to front, most arrive in order and blend at once
// (tile/blended_fragments.h). Public so that a peer renderer drawn for
// comparison composites in the same order.
std::vector<std::size_t> instanceDrawOrder(const Scene& scene, const glm::mat4& view);

}  // namespace quadra
