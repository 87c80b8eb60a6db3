// Renderer: turns a scene and camera into the frame's draw list, then runs the
// pipeline stages in order: vertex → clip/setup → bin → tile → resolve.
#include "api/renderer.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "api/camera.h"
#include "bin/bins.h"
#include "core/error.h"
#include "core/large_buffer.h"
#include "core/parallel.h"
#include "core/stage_clock.h"
#include "setup/triangle_setup.h"
#include "shading/lighting.h"
#include "shading/prepared_environment.h"
#include "texture/texture_sampler.h"
#include "tile/tile_stage.h"
#include "vertex/vertex_stage.h"
#include "window/sample_pattern.h"
#include "window/window_space.h"

namespace quadra {

struct Renderer::Impl {
  Executor executor;
  TileKernelSelection kernels;
  const CullKernel& cull;
  // The front end's buffers, kept from frame to frame (sized to the largest
  // frame so far): allocated afresh, dense-mesh's ~100 MB of them cost it a
  // fifth of each frame in page faults.
  std::vector<TransformedVertices> vertices;
  std::vector<FrontEndChunk> chunks;
  std::vector<TileTimes> tileTimes;
  TileWorkspace tiles;  // the tile stage's per-worker scratch, kept likewise
  // The last lit frame's environment, prepared (shading/prepared_environment.h),
  // and what it was prepared from: kept while frames ask for the same image.
  std::shared_ptr<const EnvironmentImage> preparedFrom;
  float preparedRotation = 0.0f, preparedScale = 1.0f;
  std::unique_ptr<PreparedEnvironment> prepared;
  Impl(const RendererConfig& config, Isa isa)
      : executor(config.arena ? Executor(*config.arena) : Executor(config.threads)),
        kernels(selectTileKernels(isa)),
        cull(cullKernel(isa)) {}
};

namespace {

// Triangles per front-end task. Fixed (not derived from the thread count) so
// chunk boundaries, and with them everything downstream, are the same for
// any number of threads.
constexpr std::size_t kChunkTriangles = 8192;

// What every draw of a frame shares.
struct FrameContext {
  const Scene& scene;
  const RenderSettings& settings;
  const Executor& executor;  // builds mip chains on first use
  glm::mat4 view, projection;
  MemoryBudget& budget;                       // charged for each texture's levels once
  std::set<const Texture*>& chargedTextures;  // the texture variants charged so far
  // Lit frames: the light, and where each lit draw's material is kept (a
  // deque: the draws point into it).
  const LightingView* lighting;
  std::deque<MaterialShading>& materials;
};

// A view of texture `index` (the variant `alpha` asks for) as the frame's
// filter settings read it, its levels charged to the frame once.
TextureView frameTextureView(const FrameContext& frame, int index, const TextureAlpha& alpha) {
  const RenderSettings& settings = frame.settings;
  FilterSettings filtering(settings.filter, settings.maxAniso);
  filtering.lodBias = settings.lodBias;
  filtering.lodRule = settings.lodRule;
  const Texture& texture = frame.scene.textures.at(std::size_t(index))->forAlpha(alpha);
  if (frame.chargedTextures.insert(&texture).second)
    frame.budget.charge("texture " + std::to_string(index) + " (" +
                            std::to_string(texture.image().width) + "x" +
                            std::to_string(texture.image().height) + ") levels",
                        textureViewBytes(texture, filtering));
  return makeTextureView(texture, filtering, &frame.executor);
}

// Lit shading's draw state for `material` on `mesh`: the attributes it
// interpolates (into `a`) and each texture it can read (one whose
// coordinate set the mesh has; a normal map needs the mesh's tangents too).
const MaterialShading* litMaterial(const FrameContext& frame, const Material& material,
                                   const Mesh& mesh, AttributeLayout& a) {
  MaterialShading& m = frame.materials.emplace_back();
  m.lighting = frame.lighting;
  const glm::mat4 worldFromView = glm::inverse(frame.view);
  m.worldFromView = glm::mat3(worldFromView);
  m.eye = glm::vec3(worldFromView[3]);
  m.position = a.position = a.count, a.count += 3;
  m.normalAttribute = a.normal = a.count, a.count += 3;
  const auto texture = [&](const MaterialTexture& from, MaterialTextureLookup& to,
                           const TextureAlpha& alpha) {
    const int set = std::clamp(from.texCoord, 0, 1);
    if (!from.present() || mesh.texcoords[set].empty()) return;
    if (m.texcoordAttribute[set] < 0) {
      int& attribute = set == 0 ? a.texcoord : a.texcoord1;
      m.texcoordAttribute[set] = attribute = a.count, a.count += 2;
    }
    to.texcoord = set;
    to.transformed = !from.transform.isIdentity();
    if (to.transformed) to.transform = from.transform.matrix();
    to.view = frameTextureView(frame, from.texture, alpha);
  };
  texture({material.baseColorTexture, material.baseColorTexCoord, material.baseColorTransform},
          m.baseColor, textureAlphaOf(material));
  texture(material.metallicRoughness, m.metallicRoughness, {});
  if (!mesh.tangents.empty()) texture(material.normal, m.normal, {});
  if (m.normal.present()) m.tangent = a.tangent = a.count, a.count += 4;
  texture(material.occlusion, m.occlusion, {});
  texture(material.emissive, m.emissive, {});
  texture(material.specular, m.specular, {});
  texture(material.specularColor, m.specularColor, {});
  if (!mesh.colors.empty()) m.color = a.color = a.count, a.count += 4;
  m.baseColorFactor = material.baseColorFactor;
  m.metallic = material.metallicFactor;
  m.roughness = material.roughnessFactor;
  m.normalScale = material.normalScale;
  m.occlusionStrength = material.occlusionStrength;
  m.emission =
      material.emissiveFactor * material.emissiveStrength * std::exp2(frame.settings.exposure);
  m.ior = material.ior;
  m.specularFactor = material.specularFactor;
  m.specularColorFactor = material.specularColorFactor;
  return &m;
}

const Material& materialOf(const Scene& scene, const Mesh& mesh) {
  static const Material kDefaultMaterial;
  return mesh.material >= 0 ? scene.materials.at(std::size_t(mesh.material)) : kDefaultMaterial;
}

// View-space depth of the mesh's bounding-box centre (larger = farther).
float viewDepthOfCentre(const Mesh& mesh, const glm::mat4& modelView) {
  if (mesh.positions.empty()) return 0.0f;
  glm::vec3 lo = mesh.positions[0], hi = lo;
  for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec4 centre = modelView * glm::vec4(0.5f * (lo + hi), 1.0f);
  return -centre.z;
}

// afterForward: an earlier draw of the list takes the forward path; the tile
// stage runs two-pass draws before forward ones, so this one must go forward
// too to keep submission order (only draws with state of their own come to
// that: the material-only lists put every two-pass draw first).
Draw makeDraw(const FrameContext& frame, const Instance& instance, bool afterForward) {
  const Scene& scene = frame.scene;
  const RenderSettings& settings = frame.settings;
  const Mesh& mesh = scene.meshes.at(std::size_t(instance.mesh));
  const Material& material = materialOf(scene, mesh);
  Draw draw;
  DrawGeometry& g = draw.geometry;
  ShadeState& s = draw.shade;
  g.mesh = &mesh;
  g.morphWeights = instance.morphWeights;
  g.jointMatrices = instance.jointMatrices;
  g.modelView = frame.view * instance.world;
  g.projection = frame.projection;
  const bool mirrored = glm::determinant(glm::mat3(instance.world)) < 0.0f;
  g.cullBackFaces = !material.doubleSided;
  g.frontIsClockwise = mirrored;
  g.mirrored = mirrored;
  g.texcoordSet = std::clamp(material.baseColorTexCoord, 0, 1);

  // The unlit shadings' colour is the radiance they show.
  s.baseColor = material.baseColorFactor;
  if (settings.exposure != 0.0f)
    s.baseColor = glm::vec4(glm::vec3(s.baseColor) * std::exp2(settings.exposure), s.baseColor.a);
  s.alphaMode = material.alphaMode;
  s.alphaCutoff = material.alphaCutoff;
  s.textured = material.baseColorTexture >= 0 && !mesh.texcoords[g.texcoordSet].empty();
  g.transformTexcoords = s.textured && !material.baseColorTransform.isIdentity();
  if (g.transformTexcoords) g.texcoordTransform = material.baseColorTransform.matrix();
  if (s.textured && !(settings.shading == Shading::Pbr && !material.unlit))
    s.texture = frameTextureView(frame, material.baseColorTexture, textureAlphaOf(material));
  s.vertexColor = !mesh.colors.empty();
  s.depthGreater = settings.depth == DepthMode::Reversed;
  s.depthCompare = compareForDepth(CompareFunction::Less, s.depthGreater);
  s.lit = settings.shading == Shading::Lit;
  if (instance.drawState) {
    // The embedder's state; the material still says how alpha is made
    // (opaque: 1, mask: tested, blend: kept).
    const DrawState& state = *instance.drawState;
    // Culling front faces is culling back faces with the winding flipped.
    g.cullBackFaces = state.cull != CullMode::None;
    g.frontIsClockwise = mirrored != (state.cull == CullMode::Front);
    s.depthCompare = state.depthTest ? compareForDepth(state.depthCompare, s.depthGreater)
                                     : CompareFunction::Always;
    s.depthWrite = state.depthTest && state.depthWrite;
    s.blend = state.blend;
  } else if (s.alphaMode == AlphaMode::Blend) {
    s.blend = BlendState::premultipliedOver();
    s.depthWrite = false;
    s.depthOrdered = true;
  }
  if (s.alphaMode == AlphaMode::Mask && settings.alphaToCoverage) {
    s.alphaToCoverage = true;
    s.alphaCutoff = 0.5f;  // one sample's; several samples' are the tile stage's
  }
  if (settings.debugView == DebugView::CoverageCount) {
    s = ShadeState{};
    s.baseColor = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
    s.blend = BlendState::additive();
    s.depthCompare = CompareFunction::Always;
    s.depthWrite = false;
    g.texcoordSet = 0;
    g.transformTexcoords = false;
  } else if (settings.debugView == DebugView::TexCoord ||
             settings.debugView == DebugView::Derivatives) {
    s.textured = s.vertexColor = s.lit = false;
    s.alphaMode = AlphaMode::Opaque;
    s.blend = BlendState{};
    s.depthOrdered = false;
    s.depthCompare = compareForDepth(CompareFunction::Less, s.depthGreater);
    s.depthWrite = true;
    s.output = settings.debugView == DebugView::TexCoord ? ShadeOutput::TexCoord
                                                         : ShadeOutput::Derivatives;
    g.texcoordSet = 0;  // TEXCOORD_0 as stored, whatever the material reads
    g.transformTexcoords = false;
  }

  s.derivatives = settings.derivatives;
  // The visibility pass tests "nearer" and writes depth, and the shading
  // pass replaces colour.
  s.twoPass = !afterForward && s.alphaMode != AlphaMode::Blend && !s.blend.enabled &&
              s.depthCompare == compareForDepth(CompareFunction::Less, s.depthGreater) &&
              s.depthWrite && s.output == ShadeOutput::Color &&
              s.derivatives == DerivativeMode::Analytic &&
              settings.opaqueShading == OpaqueShading::TwoPass;
  // Every sample is shaded in a supersampled frame, and a multisampled
  // frame's other forward draws are shaded per sample too: each such lookup
  // filters for the sample spacing.
  if (settings.samples > 1 &&
      (settings.shadingRate == ShadingRate::Sample || s.shadedPerSampleAtPixelRate()))
    s.footprintScale = float(1.0 / std::sqrt(double(settings.samples)));

  // Interpolate only what the shading reads.
  AttributeLayout& a = g.attributes;
  if (settings.shading == Shading::Pbr && !material.unlit && s.output == ShadeOutput::Color &&
      settings.debugView == DebugView::None) {
    // The material reads its own textures and coordinate sets, as stored.
    s.textured = s.vertexColor = false;
    s.lit = true;
    g.texcoordSet = 0;
    g.transformTexcoords = false;
    s.material = litMaterial(frame, material, mesh, a);
    if (mesh.normals.empty()) g.faceNormal = a.normal;
    if (material.doubleSided) {
      for (int k = 0; k < 3; ++k) g.negatedOnBackFaces |= 1u << (a.normal + k);
      if (a.tangent >= 0)
        for (int k = 0; k < 4; ++k) g.negatedOnBackFaces |= 1u << (a.tangent + k);
    }
    s.attributes = a;
    return draw;
  }
  if (s.textured || s.output != ShadeOutput::Color) a.texcoord = a.count, a.count += 2;
  if (s.vertexColor) a.color = a.count, a.count += 4;
  if (s.lit) a.normal = a.count, a.count += 3;
  s.attributes = a;
  return draw;
}

// The frame's draws, and in `instances` each one's index in scene.instances.
std::vector<Draw> buildDrawList(const Scene& scene, const Camera& camera,
                                const RenderSettings& settings, const Executor& executor,
                                std::vector<std::size_t>& instances, MemoryBudget& budget,
                                const LightingView* lighting,
                                std::deque<MaterialShading>& materials) {
  std::set<const Texture*> chargedTextures;
  const FrameContext frame{
      scene,
      settings,
      executor,
      viewMatrix(camera),
      projectionMatrix(camera, double(settings.width) / settings.height, settings.depth),
      budget,
      chargedTextures,
      lighting,
      materials};
  std::vector<Draw> draws;
  instances.clear();
  if (settings.debugView == DebugView::None) {
    instances = instanceDrawOrder(scene, frame.view);
    bool forward = false;
    for (const std::size_t i : instances) {
      draws.push_back(makeDraw(frame, scene.instances[i], forward));
      forward = forward || !draws.back().shade.twoPass;
    }
    return draws;
  }
  // Debug views never blend: scene order.
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    Draw draw = makeDraw(frame, scene.instances[i], true);  // test views shade forward
    if (draw.geometry.mesh->indices.empty()) continue;
    draws.push_back(std::move(draw));
    instances.push_back(i);
  }
  return draws;
}

// What the tile stage's AOV pass reads per draw (tile/surface_aov.h): the
// ids as docs/cli.md "AOVs" defines them and the matrices, in double.
AovFrame makeAovFrame(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                      const std::vector<Draw>& draws, const std::vector<std::size_t>& instances) {
  AovFrame aov;
  aov.aovs = settings.aovs;
  aov.width = settings.width;
  aov.height = settings.height;
  const double aspect = double(settings.width) / settings.height;
  const glm::dmat4 projection(projectionMatrix(camera, aspect, settings.depth));
  const PreviousPose* previous = settings.previousPose;
  aov.hasPreviousPose = previous != nullptr;
  aov.albedoScale = std::exp2(-settings.exposure);
  glm::dmat4 previousViewToClip(1.0);
  if (previous) {
    if (previous->instanceWorlds.size() != scene.instances.size())
      throw Error("render: the previous pose has " +
                  std::to_string(previous->instanceWorlds.size()) +
                  " instance matrices for a scene of " + std::to_string(scene.instances.size()));
    previousViewToClip = glm::dmat4(projectionMatrix(previous->camera, aspect, settings.depth)) *
                         glm::dmat4(viewMatrix(previous->camera));
    const auto checkCount = [&](std::size_t count, const char* what) {
      if (count != 0 && count != scene.instances.size())
        throw Error("render: the previous pose has " + std::to_string(count) + " " + what +
                    " for a scene of " + std::to_string(scene.instances.size()) + " instances");
    };
    checkCount(previous->instanceJoints.size(), "joint matrix lists");
    checkCount(previous->instanceMorphWeights.size(), "morph weight lists");
  }
  aov.draws.resize(draws.size());
  for (std::size_t d = 0; d < draws.size(); ++d) {
    const std::size_t i = instances[d];
    const Instance& instance = scene.instances[i];
    AovDraw& a = aov.draws[d];
    a.mesh = draws[d].geometry.mesh;
    a.morphWeights = draws[d].geometry.morphWeights;
    a.jointMatrices = draws[d].geometry.jointMatrices;
    a.objectToClip = projection * glm::dmat4(draws[d].geometry.modelView);
    a.world = glm::dmat4(instance.world);
    a.normalToWorld = glm::transpose(glm::inverse(glm::dmat3(a.world)));
    a.previousMorphWeights = a.morphWeights;
    a.previousJointMatrices = a.jointMatrices;
    if (previous) {
      a.previousObjectToClip = previousViewToClip * glm::dmat4(previous->instanceWorlds[i]);
      // The same deformation with that pose's joints and weights; the
      // deformer checks them against the mesh like the current ones.
      if (!previous->instanceJoints.empty() &&
          previous->instanceJoints[i].size() == a.jointMatrices.size())
        a.previousJointMatrices = previous->instanceJoints[i];
      if (!previous->instanceMorphWeights.empty() &&
          previous->instanceMorphWeights[i].size() == a.morphWeights.size())
        a.previousMorphWeights = previous->instanceMorphWeights[i];
    }
    a.node = instance.node >= 0
                 ? std::uint32_t(scene.nodes.at(std::size_t(instance.node)).fileIndex)
                 : std::uint32_t(i);
    const int material = a.mesh->material;
    if (material >= 0) {
      const int file = scene.materials.at(std::size_t(material)).fileIndex;
      a.material = std::uint32_t(file >= 0 ? file : material);
    }
  }
  return aov;
}

void checkSettings(const RenderSettings& s) {
  if (s.width < 1 || s.height < 1 || s.width > kMaxViewport || s.height > kMaxViewport)
    throw Error("render: size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                " is out of range (1.." + std::to_string(kMaxViewport) + " per side)");
  if (!(std::fabs(s.lodBias) <= 32.0f))
    throw Error("render: LOD bias " + std::to_string(s.lodBias) + " is out of range (-32..32)");
  if (!isSampleCount(s.samples))
    throw Error("render: " + std::to_string(s.samples) +
                " samples per pixel is not supported (1, 2, 4, 8 or 16)");
  if (s.maxAniso < 1 || s.maxAniso > 64)
    throw Error("render: max anisotropy " + std::to_string(s.maxAniso) +
                " is out of range (1..64)");
  // The AOV pass reads the visibility pass's winners: every depth-writing
  // draw must go through it (makeDraw's twoPass).
  if (s.aovs != 0 && (s.debugView != DebugView::None || s.derivatives != DerivativeMode::Analytic ||
                      s.opaqueShading != OpaqueShading::TwoPass))
    throw Error(
        "render: AOVs need analytic derivatives, two-pass opaque shading and no debug view");
}

// The frame's buffers and the tile stage's memory, charged after the draw
// list (whose textures are charged as it is built: the tile memory depends on
// whether some draw blends) and before any of them is allocated.
void chargeFrame(const RenderSettings& settings, int threads, const std::vector<Draw>& draws,
                 MemoryBudget& budget) {
  const std::uint64_t pixels = std::uint64_t(settings.width) * std::uint64_t(settings.height);
  // 4-byte channels: colour, depth, coverage and the surface AOVs' planes.
  const std::uint64_t channels = 4 + (settings.frameDepth ? 1 : 0) +
                                 (settings.frameCoverage ? 1 : 0) +
                                 std::uint64_t(aovChannels(settings.aovs));
  const std::string size = std::to_string(settings.width) + "x" + std::to_string(settings.height);
  budget.charge("the " + size + " frame", pixels * channels * sizeof(float));
  const int ringChannels =
      settings.pixelFilter == PixelFilter::Box ? 0 : (settings.frameCoverage ? 5 : 4);
  budget.charge("tile memory (" + std::to_string(settings.samples) + " samples, " +
                    std::to_string(threads) + " threads)",
                tileMemoryBytes(TileGrid::forViewport(settings.width, settings.height),
                                settings.samples, threads, ringChannels, settings.aovs, draws));
  // The front end's arrays grow with the scene's vertices and triangles,
  // which a file controls through its index count alone (a small vertex
  // buffer indexed millions of times). Charged at what every triangle takes
  // if kept whole and binned once; clipping's extra pieces and triangles
  // spanning several tiles add to it, culled ones take less.
  std::uint64_t vertices = 0, triangles = 0, bytes = 0;
  for (const Draw& draw : draws) {
    const std::uint64_t v = draw.geometry.mesh->positions.size();
    const std::uint64_t t = draw.geometry.mesh->indices.size() / 3;
    const std::uint64_t interpolated = std::uint64_t(draw.geometry.attributes.count);
    vertices += v;
    triangles += t;
    bytes += v * ((4 + interpolated) * sizeof(float) + sizeof(ScreenVertex) +
                  sizeof(SubpixelPosition) + sizeof(std::uint8_t));
    bytes += t * (sizeof(TriangleRecord) + (2 + interpolated) * sizeof(Plane) +
                  sizeof(std::uint32_t) * (settings.aovs != 0 ? 2 : 1));
  }
  budget.charge("the front end (" + std::to_string(vertices) + " vertices, " +
                    std::to_string(triangles) + " triangles)",
                bytes);
}

// A parallel pass's wall time split between two of its stages in proportion
// to the thread time each took (StageTimes).
void splitWallTime(double wall, double threadA, double threadB, double& a, double& b) {
  const double total = threadA + threadB;
  a = total > 0.0 ? wall * threadA / total : 0.0;
  b = wall - a;
}

}  // namespace

std::vector<std::size_t> instanceDrawOrder(const Scene& scene, const glm::mat4& view) {
  std::vector<std::size_t> order, blended;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Mesh& mesh = scene.meshes.at(std::size_t(scene.instances[i].mesh));
    if (mesh.indices.empty()) continue;
    const bool depthOrdered =
        materialOf(scene, mesh).alphaMode == AlphaMode::Blend && !scene.instances[i].drawState;
    (depthOrdered ? blended : order).push_back(i);
  }
  // Farthest first; stable, so ties keep scene order.
  std::vector<std::pair<float, std::size_t>> keyed;
  for (const std::size_t i : blended) {
    const Instance& instance = scene.instances[i];
    keyed.push_back(
        {-viewDepthOfCentre(scene.meshes[std::size_t(instance.mesh)], view * instance.world), i});
  }
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  for (const auto& entry : keyed) order.push_back(entry.second);
  return order;
}

Renderer::Renderer(const RendererConfig& config) {
  const Isa isa = config.isa.value_or(detectBestIsa());
  if (!isaSupported(isa))
    throw Error(std::string("--isa ") + isaName(isa) +
                ": this CPU does not support it (best: " + isaName(detectBestIsa()) + ")");
  impl_ = std::make_unique<Impl>(config, isa);
}

Renderer::~Renderer() = default;

Isa Renderer::isa() const {
  return impl_->kernels.wide->isa;
}
int Renderer::threadCount() const {
  return impl_->executor.threadCount();
}

// A lit frame's light: the environment (prepared on first use, kept in
// `impl` while later frames ask for the same one) and the scene's punctual
// lights, all scaled by 2^exposure.
struct FrameLighting {
  std::vector<PunctualLight> lights;
  LightingView view;
  BackgroundView background;
  double prepareMs = 0.0;
};

void prepareLighting(Renderer::Impl& impl, const Scene& scene, const Camera& camera,
                     const RenderSettings& settings, FrameLighting& lighting) {
  if (!settings.environment)
    throw Error("render: pbr shading needs an environment (RenderSettings::environment)");
  const float scale = settings.environmentIntensity * std::exp2(settings.exposure);
  if (impl.preparedFrom != settings.environment ||
      impl.preparedRotation != settings.environmentRotation || impl.preparedScale != scale) {
    const double started = stageClockMs();
    impl.prepared.reset();
    impl.prepared = std::make_unique<PreparedEnvironment>(
        *settings.environment, EnvironmentPlacement{settings.environmentRotation, scale},
        impl.executor);
    impl.preparedFrom = settings.environment;
    impl.preparedRotation = settings.environmentRotation;
    impl.preparedScale = scale;
    lighting.prepareMs = stageClockMs() - started;
  }
  if (settings.punctualLights) {
    const float exposure = std::exp2(settings.exposure);
    for (const Light& light : scene.lights) {
      Light scaled = light;
      scaled.intensity *= exposure;
      lighting.lights.push_back(punctualLightOf(scaled));
    }
  }
  lighting.view = lightingViewOf(impl.prepared.get(), lighting.lights);
  BackgroundView& b = lighting.background;
  b.lighting = &lighting.view;
  b.worldFromView = glm::mat3(glm::inverse(viewMatrix(camera)));
  b.perspective = camera.type == Camera::Type::Perspective;
  const double aspect = double(settings.width) / settings.height;
  const double tanY = std::tan(0.5 * double(camera.yfov));
  b.scaleX = float(2.0 * tanY * aspect / settings.width);
  b.scaleY = float(2.0 * tanY / settings.height);
  b.centreX = 0.5f * float(settings.width);
  b.centreY = 0.5f * float(settings.height);
}

FrameStats Renderer::render(const Scene& scene, const Camera& camera,
                            const RenderSettings& settings, Frame& out) {
  checkSettings(settings);
  const Executor& executor = impl_->executor;
  const double start = stageClockMs();
  MemoryBudget budget(settings.maxMemory, "render");
  std::optional<FrameLighting> lighting;
  if (settings.shading == Shading::Pbr && settings.debugView == DebugView::None) {
    lighting.emplace();
    prepareLighting(*impl_, scene, camera, settings, *lighting);
  }
  std::vector<std::size_t> drawInstances;
  std::deque<MaterialShading> materials;
  const std::vector<Draw> draws =
      buildDrawList(scene, camera, settings, executor, drawInstances, budget,
                    lighting ? &lighting->view : nullptr, materials);
  chargeFrame(settings, executor.threadCount(), draws, budget);
  std::optional<AovFrame> aov;
  if (settings.aovs != 0) {
    // The AOV pass reads the visibility pass's winners (checkSettings).
    for (std::size_t d = 0; d < draws.size(); ++d)
      if (draws[d].shade.depthWrite && !draws[d].shade.twoPass)
        throw Error("render: AOVs need every depth-writing draw in the visibility pass; instance " +
                    std::to_string(drawInstances[d]) +
                    "'s draw state (blend, depth compare, or a blended or forward draw before "
                    "it) shades it forward");
    aov = makeAovFrame(scene, camera, settings, draws, drawInstances);
  }
  const double drawsDone = stageClockMs();

  // Vertex stage.
  const Viewport viewport{settings.width, settings.height};
  std::vector<TransformedVertices>& vertices = impl_->vertices;
  vertices.resize(draws.size());
  for (std::size_t d = 0; d < draws.size(); ++d)
    transformVertices(draws[d].geometry, viewport, executor, vertices[d]);
  const double vertexDone = stageClockMs();

  // Clip, setup and bin, in chunks of kChunkTriangles consecutive triangles
  // of the draw list, which may span draws: chunk count, bin memory and the
  // tile stage's walk over the chunks grow with triangles, not with draws.
  struct DrawRange {
    std::uint32_t draw;
    std::size_t first, last;
  };
  std::vector<DrawRange> ranges;
  std::vector<std::size_t> chunkStart;  // first range of each chunk, then the end
  std::size_t filled = 0;               // triangles in the chunk being filled
  for (std::uint32_t d = 0; d < draws.size(); ++d) {
    const std::size_t triangles = draws[d].geometry.mesh->indices.size() / 3;
    for (std::size_t first = 0; first < triangles;) {
      if (filled == 0) chunkStart.push_back(ranges.size());
      const std::size_t last = std::min(first + (kChunkTriangles - filled), triangles);
      ranges.push_back({d, first, last});
      filled = (filled + last - first) % kChunkTriangles;
      first = last;
    }
  }
  chunkStart.push_back(ranges.size());
  const TileGrid grid = TileGrid::forViewport(settings.width, settings.height);
  const SamplePattern& samples = samplePattern(settings.samples);
  std::vector<FrontEndChunk>& chunks = impl_->chunks;
  chunks.resize(chunkStart.size() - 1);
  executor.parallelFor(chunks.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      FrontEndChunk& chunk = chunks[c];
      const double started = stageClockMs();
      chunk.setup.clear();
      chunk.setup.recordSources = aov.has_value();
      for (std::size_t i = chunkStart[c]; i < chunkStart[c + 1]; ++i) {
        const DrawRange& r = ranges[i];
        setupTriangles(draws[r.draw].geometry, vertices[r.draw], r.draw, r.first, r.last, viewport,
                       samples, impl_->cull, chunk.setup);
      }
      const double setUp = stageClockMs();
      binTriangles(chunk.setup.triangles, grid, samples.reachSubpixels(), chunk.bins);
      chunk.setupMs = setUp - started;
      chunk.binMs = stageClockMs() - setUp;
    }
  });
  const double frontEndDone = stageClockMs();

  // Tile stage and resolve.
  out.width = settings.width;
  out.height = settings.height;
  const std::size_t pixels = std::size_t(out.width) * std::size_t(out.height);
  resizeLarge(out.rgba, out.rgbaInto ? 0 : pixels * 4, 0.0f, &executor);
  resizeLarge(out.depth, settings.frameDepth && !out.depthInto ? pixels : 0, 0.0f, &executor);
  resizeLarge(out.coverage, settings.frameCoverage ? pixels : 0, 0.0f, &executor);
  // The AOV pass writes every pixel of the planes asked for, clear values too.
  const auto aovPixels = [&](Aov a) {
    return hasAov(settings.aovs, a) ? pixels * std::size_t(aovChannels(a)) : 0;
  };
  const std::pair<std::vector<float>*, Aov> floatPlanes[] = {{&out.normal, Aov::Normal},
                                                             {&out.position, Aov::Position},
                                                             {&out.uv, Aov::Uv},
                                                             {&out.motion, Aov::Motion},
                                                             {&out.lod, Aov::Lod},
                                                             {&out.anisotropy, Aov::Anisotropy},
                                                             {&out.albedo, Aov::Albedo},
                                                             {&out.roughness, Aov::Roughness},
                                                             {&out.metallic, Aov::Metallic},
                                                             {&out.emission, Aov::Emission},
                                                             {&out.diffuse, Aov::Diffuse},
                                                             {&out.specular, Aov::Specular}};
  for (const auto& [plane, aov] : floatPlanes) resizeLarge(*plane, aovPixels(aov), 0.0f, &executor);
  for (std::vector<std::uint32_t>* ids : {&out.primitiveId, &out.nodeId, &out.materialId})
    resizeLarge(*ids, hasAov(settings.aovs, Aov::Ids) ? pixels : 0, kNoId, &executor);
  const double aspect = double(settings.width) / settings.height;
  out.metadata.hasCamera = true;
  out.metadata.worldToCamera = viewMatrix(camera);
  out.metadata.worldToNDC =
      projectionMatrix(camera, aspect, settings.depth) * out.metadata.worldToCamera;
  std::optional<PixelFilterWeights> pixelFilter;
  if (settings.pixelFilter == PixelFilter::BlackmanHarris)
    pixelFilter = PixelFilterWeights::blackmanHarris(samples);
  const float clearDepth = settings.depth == DepthMode::Reversed ? 0.0f : 1.0f;
  // A lit frame's uncovered pixels: the environment composited behind its
  // surfaces, the clear colour, or nothing.
  glm::vec4 clearColor = settings.clearColor;
  if (lighting && settings.background != Background::Color) clearColor = glm::vec4(0.0f);
  if (settings.exposure != 0.0f)
    clearColor = glm::vec4(glm::vec3(clearColor) * std::exp2(settings.exposure), clearColor.a);
  const TileFrame tileFrame{
      grid,
      draws,
      chunks,
      impl_->kernels,
      clearColor,
      clearDepth,
      settings.depth == DepthMode::Reversed,
      samples,
      settings.shadingRate == ShadingRate::Sample,
      pixelFilter ? &*pixelFilter : nullptr,
      settings.frameCoverage,
      aov ? &*aov : nullptr,
      lighting && settings.background == Background::Environment ? &lighting->background : nullptr};
  renderTiles(tileFrame, executor, impl_->tiles, out, impl_->tileTimes);
  const double tilesDone = stageClockMs();

  SetupCounters total;
  double setupMs = 0.0, binMs = 0.0;
  for (const FrontEndChunk& chunk : chunks) {
    total.add(chunk.setup.counters);
    setupMs += chunk.setupMs;
    binMs += chunk.binMs;
  }
  TileTimes tiles;
  for (const TileTimes& t : impl_->tileTimes) {
    tiles.raster += t.raster;
    tiles.shade += t.shade;
    tiles.resolve += t.resolve;
  }
  FrameStats stats;
  StageTimes& stages = stats.stages;
  stages.draws = drawsDone - start;
  stages.environment = lighting ? lighting->prepareMs : 0.0;
  stages.vertex = vertexDone - drawsDone;
  splitWallTime(frontEndDone - vertexDone, setupMs, binMs, stages.setup, stages.bin);
  // Three ways: raster and shade against resolve, then raster against shade.
  double rasterAndShade = 0.0;
  splitWallTime(tilesDone - frontEndDone, tiles.raster + tiles.shade, tiles.resolve, rasterAndShade,
                stages.resolve);
  splitWallTime(rasterAndShade, tiles.raster, tiles.shade, stages.raster, stages.shade);
  stats.trianglesIn = total.in;
  stats.trianglesDrawn = total.drawn;
  stats.culledBackFace = total.backFace;
  stats.culledOutside = total.outside;
  stats.droppedDegenerate = total.degenerate;
  stats.droppedInvalid = total.invalid;
  stats.clipped = total.clipped;
  return stats;
}

}  // namespace quadra
