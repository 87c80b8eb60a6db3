// Per-draw state (scene/scene.h DrawState) against independent expectations: every
// blend equation and factor against its formula evaluated in double on the
// premultiplied colours, per channel; the depth compare functions, depth
// write and depth test off, and the three cull modes on a small orthographic
// scene whose outcome is known analytically; a blended scene bit-identical
// across ISA paths and thread counts; and instances given the state their
// material implies render what they render without one.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lab/scene/builtin_scenes.h"
#include "render_helpers.h"

namespace quadra {
namespace {

constexpr int kSize = 16;

// Looks down -Z at world x, y in [-1, 1], depth planes 0.5 to 20 away.
Camera orthoCamera() {
  Camera camera;
  camera.type = Camera::Type::Orthographic;
  camera.xmag = camera.ymag = 1.0f;
  camera.znear = 0.5f;
  camera.zfar = 20.0f;
  return camera;
}

RenderSettings smallSettings() {
  RenderSettings settings;
  settings.width = settings.height = kSize;
  return settings;
}

// An axis-aligned rectangle at view distance `distance`, counter-clockwise
// (front-facing) unless `clockwise`.
Mesh rectangle(float x0, float y0, float x1, float y1, float distance, bool clockwise = false) {
  Mesh mesh;
  mesh.positions = {
      {x0, y0, -distance}, {x1, y0, -distance}, {x1, y1, -distance}, {x0, y1, -distance}};
  mesh.indices = clockwise ? std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2}
                           : std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3};
  return mesh;
}

Mesh fullScreen(float distance) {
  return rectangle(-2.0f, -2.0f, 2.0f, 2.0f, distance);
}

// Adds `mesh` with a flat material of straight colour `color` and
// `alphaMode`, drawn with `state` (none: as the material says).
void addDraw(Scene& scene, Mesh mesh, glm::vec4 color, AlphaMode alphaMode,
             std::optional<DrawState> state) {
  Material material;
  material.baseColorFactor = color;
  material.alphaMode = alphaMode;
  mesh.material = int(scene.materials.size());
  scene.materials.push_back(material);
  scene.meshes.push_back(std::move(mesh));
  Instance instance;
  instance.mesh = int(scene.meshes.size()) - 1;
  instance.drawState = state;
  scene.instances.push_back(std::move(instance));
}

glm::vec4 pixel(const Frame& frame, int x, int y) {
  const float* p = &frame.rgba[(std::size_t(y) * std::size_t(frame.width) + std::size_t(x)) * 4];
  return {p[0], p[1], p[2], p[3]};
}

// --- Blending --------------------------------------------------------------

constexpr std::array<BlendEquation, 5> kEquations = {BlendEquation::Add, BlendEquation::Subtract,
                                                     BlendEquation::ReverseSubtract,
                                                     BlendEquation::Min, BlendEquation::Max};
constexpr std::array<BlendFactor, 10> kFactors = {
    BlendFactor::Zero,     BlendFactor::One,
    BlendFactor::SrcColor, BlendFactor::OneMinusSrcColor,
    BlendFactor::DstColor, BlendFactor::OneMinusDstColor,
    BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha,
    BlendFactor::DstAlpha, BlendFactor::OneMinusDstAlpha};

// GL's factor for channel `channel` (3: alpha), in double.
double factorOf(BlendFactor f, const glm::dvec4& src, const glm::dvec4& dst, int channel) {
  switch (f) {
    case BlendFactor::Zero:
      return 0.0;
    case BlendFactor::One:
      return 1.0;
    case BlendFactor::SrcColor:
      return src[channel];
    case BlendFactor::OneMinusSrcColor:
      return 1.0 - src[channel];
    case BlendFactor::DstColor:
      return dst[channel];
    case BlendFactor::OneMinusDstColor:
      return 1.0 - dst[channel];
    case BlendFactor::SrcAlpha:
      return src[3];
    case BlendFactor::OneMinusSrcAlpha:
      return 1.0 - src[3];
    case BlendFactor::DstAlpha:
      return dst[3];
    case BlendFactor::OneMinusDstAlpha:
      return 1.0 - dst[3];
  }
  return 0.0;
}

double equationOf(BlendEquation e, double s, double fs, double d, double fd) {
  switch (e) {
    case BlendEquation::Add:
      return s * fs + d * fd;
    case BlendEquation::Subtract:
      return s * fs - d * fd;
    case BlendEquation::ReverseSubtract:
      return d * fd - s * fs;
    case BlendEquation::Min:
      return std::min(s, d);
    case BlendEquation::Max:
      return std::max(s, d);
  }
  return 0.0;
}

// The blended colour of premultiplied `src` over premultiplied `dst`.
glm::dvec4 blendInDouble(const BlendState& b, const glm::dvec4& src, const glm::dvec4& dst) {
  glm::dvec4 out;
  for (int ch = 0; ch < 3; ++ch)
    out[ch] = equationOf(b.colorEquation, src[ch], factorOf(b.srcColor, src, dst, ch), dst[ch],
                         factorOf(b.dstColor, src, dst, ch));
  out[3] = equationOf(b.alphaEquation, src[3], factorOf(b.srcAlpha, src, dst, 3), dst[3],
                      factorOf(b.dstAlpha, src, dst, 3));
  return out;
}

// Straight source colour (its premultiplied form is what blends) and a
// premultiplied destination (the clear colour) with alpha below 1, so every
// factor differs from every other on some channel.
constexpr glm::vec4 kSource{0.8f, 0.3f, 0.55f, 0.6f};
constexpr glm::vec4 kDestination{0.1f, 0.35f, 0.2f, 0.45f};

// One blended full-screen rectangle over the clear colour.
Frame blendOverClear(const BlendState& blend, int samples = 1) {
  Scene scene;
  DrawState state;
  state.blend = blend;
  state.depthWrite = false;
  addDraw(scene, fullScreen(2.0f), kSource, AlphaMode::Blend, state);
  RenderSettings settings = smallSettings();
  settings.clearColor = kDestination;
  settings.samples = samples;
  return renderOnce(scene, orthoCamera(), settings);
}

// Each result takes at most five float roundings (the premultiply, a 1 - x,
// two products, the sum) of values below 2 in magnitude, each within 2^-23
// absolute: 5 * 2^-23 < 6e-7. A multisampled pixel adds the box filter's
// mean of equal samples, within a few more such roundings.
constexpr double kBlendTolerance = 1e-6;

void expectBlend(const BlendState& blend, int samples, const std::string& what) {
  const glm::dvec4 src(double(kSource.r) * kSource.a, double(kSource.g) * kSource.a,
                       double(kSource.b) * kSource.a, kSource.a);
  const glm::dvec4 expected = blendInDouble(blend, src, glm::dvec4(kDestination));
  const Frame frame = blendOverClear(blend, samples);
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{7, 9}, std::pair{15, 15}}) {
    const glm::vec4 got = pixel(frame, x, y);
    for (int ch = 0; ch < 4; ++ch)
      ASSERT_NEAR(got[ch], expected[ch], kBlendTolerance)
          << what << ", channel " << ch << ", pixel " << x << "," << y;
  }
}

// Every colour equation with every pair of colour factors; the alpha
// channel's equation and factors cycle through theirs alongside, different
// from the colour's, so separate colour and alpha state is checked too.
TEST(BlendState, EveryEquationAndFactorMatchesItsFormula) {
  for (std::size_t e = 0; e < kEquations.size(); ++e)
    for (std::size_t s = 0; s < kFactors.size(); ++s)
      for (std::size_t d = 0; d < kFactors.size(); ++d) {
        BlendState blend;
        blend.enabled = true;
        blend.colorEquation = kEquations[e];
        blend.srcColor = kFactors[s];
        blend.dstColor = kFactors[d];
        blend.alphaEquation = kEquations[(e + 1 + s) % kEquations.size()];
        blend.srcAlpha = kFactors[(s + 3 + d) % kFactors.size()];
        blend.dstAlpha = kFactors[(d + 7) % kFactors.size()];
        expectBlend(blend, 1,
                    "equation " + std::to_string(e) + ", factors " + std::to_string(s) + "/" +
                        std::to_string(d));
      }
}

// Multisampled, each sample blends on its own, and the filter's mean of equal
// samples is the same value.
TEST(BlendState, MultisampledBlendMatchesItsFormula) {
  for (const BlendEquation e : kEquations)
    expectBlend(BlendState::uniform(e, BlendFactor::SrcAlpha, BlendFactor::OneMinusDstColor), 4,
                "4 samples, equation " + std::to_string(int(e)));
}

// The preset is the formula, and over the clear colour it writes the bits a
// glTF BLEND material (depth-ordered "over") writes.
TEST(BlendState, PremultipliedOverIsTheGltfBlend) {
  expectBlend(BlendState::premultipliedOver(), 1, "premultiplied over");
  Scene scene;
  addDraw(scene, fullScreen(2.0f), kSource, AlphaMode::Blend, std::nullopt);
  RenderSettings settings = smallSettings();
  settings.clearColor = kDestination;
  EXPECT_EQ(renderOnce(scene, orthoCamera(), settings).rgba,
            blendOverClear(BlendState::premultipliedOver()).rgba);
}

// Blending off, a translucent draw replaces what is there with its
// premultiplied colour.
TEST(BlendState, DisabledBlendReplacesWithPremultipliedColour) {
  const glm::vec4 got = pixel(blendOverClear(BlendState{}), 5, 5);
  EXPECT_EQ(got, glm::vec4(kSource.r * kSource.a, kSource.g * kSource.a, kSource.b * kSource.a,
                           kSource.a));
}

// --- Depth -------------------------------------------------------------------

constexpr glm::vec4 kRed{1.0f, 0.0f, 0.0f, 1.0f};
constexpr glm::vec4 kGreen{0.0f, 1.0f, 0.0f, 1.0f};

// Whether `compare` passes a fragment at view distance `fragment` over a
// stored one at `stored`, stated for standard depth (Less: nearer).
bool passes(CompareFunction compare, float fragment, float stored) {
  switch (compare) {
    case CompareFunction::Never:
      return false;
    case CompareFunction::Less:
      return fragment < stored;
    case CompareFunction::Equal:
      return fragment == stored;
    case CompareFunction::LessEqual:
      return fragment <= stored;
    case CompareFunction::Greater:
      return fragment > stored;
    case CompareFunction::NotEqual:
      return fragment != stored;
    case CompareFunction::GreaterEqual:
      return fragment >= stored;
    case CompareFunction::Always:
      return true;
  }
  return false;
}

// A red full-screen rectangle at distance 4 (as its material says), then a
// green one at `distance` with `compare`: green where the compare passes.
// Both depth modes, since the compare is stated for standard depth.
TEST(DrawState, EveryDepthCompareFunction) {
  constexpr std::array<CompareFunction, 8> kCompares = {
      CompareFunction::Never,        CompareFunction::Less,    CompareFunction::Equal,
      CompareFunction::LessEqual,    CompareFunction::Greater, CompareFunction::NotEqual,
      CompareFunction::GreaterEqual, CompareFunction::Always};
  for (const DepthMode mode : {DepthMode::Standard, DepthMode::Reversed})
    for (const CompareFunction compare : kCompares)
      for (const float distance : {3.0f, 4.0f, 5.0f}) {
        Scene scene;
        addDraw(scene, fullScreen(4.0f), kRed, AlphaMode::Opaque, std::nullopt);
        DrawState state;
        state.depthCompare = compare;
        addDraw(scene, fullScreen(distance), kGreen, AlphaMode::Opaque, state);
        RenderSettings settings = smallSettings();
        settings.depth = mode;
        const Frame frame = renderOnce(scene, orthoCamera(), settings);
        const bool pass = passes(compare, distance, 4.0f);
        EXPECT_EQ(pixel(frame, 6, 10), pass ? kGreen : kRed)
            << "compare " << int(compare) << ", distance " << distance << ", reversed "
            << (mode == DepthMode::Reversed);
      }
}

// Depth write off: a later farther draw still passes where the first drew;
// on, it does not. Depth test off: the farther draw passes and leaves the
// stored depth alone.
TEST(DrawState, DepthWriteAndDepthTestOff) {
  const auto render = [](DrawState first, DrawState second) {
    Scene scene;
    addDraw(scene, fullScreen(3.0f), kRed, AlphaMode::Opaque, first);
    addDraw(scene, fullScreen(6.0f), kGreen, AlphaMode::Opaque, second);
    return renderOnce(scene, orthoCamera(), smallSettings());
  };
  DrawState noWrite;
  noWrite.depthWrite = false;
  const Frame unwritten = render(noWrite, DrawState{});
  EXPECT_EQ(pixel(unwritten, 3, 3), kGreen);
  const Frame written = render(DrawState{}, DrawState{});
  EXPECT_EQ(pixel(written, 3, 3), kRed);

  DrawState noTest;
  noTest.depthTest = false;  // and so no depth write, whatever depthWrite says
  const Frame untested = render(DrawState{}, noTest);
  EXPECT_EQ(pixel(untested, 3, 3), kGreen);
  // The stored depth is still the first rectangle's, nearer than the second's.
  ASSERT_FALSE(untested.depth.empty());
  EXPECT_EQ(untested.depth[3 * kSize + 3], written.depth[3 * kSize + 3]);
  EXPECT_LT(untested.depth[3 * kSize + 3], render(noWrite, DrawState{}).depth[3 * kSize + 3]);
}

// A front-facing (counter-clockwise) rectangle on the left half, a
// back-facing one on the right: each cull mode keeps what it should, and a
// mirroring world matrix swaps which is front (glTF's rule, as materials get it).
TEST(DrawState, CullModes) {
  struct Case {
    CullMode cull;
    bool mirrored;
    bool leftDrawn, rightDrawn;
  };
  for (const Case c :
       {Case{CullMode::None, false, true, true}, Case{CullMode::Back, false, true, false},
        Case{CullMode::Front, false, false, true}, Case{CullMode::Back, true, false, true},
        Case{CullMode::Front, true, true, false}}) {
    // Mirrored: the mesh at z = +3 and a world scale of -1 in z, the same
    // picture at distance 3 with the winding rule flipped.
    const float distance = c.mirrored ? -3.0f : 3.0f;
    Mesh mesh = rectangle(-1.0f, -1.0f, 0.0f, 1.0f, distance);
    const Mesh back = rectangle(0.0f, -1.0f, 1.0f, 1.0f, distance, true);
    for (const std::uint32_t i : back.indices) mesh.indices.push_back(i + 4);
    mesh.positions.insert(mesh.positions.end(), back.positions.begin(), back.positions.end());
    Scene scene;
    DrawState state;
    state.cull = c.cull;
    addDraw(scene, std::move(mesh), kGreen, AlphaMode::Opaque, state);
    if (c.mirrored) scene.instances[0].world[2][2] = -1.0f;
    const Frame frame = renderOnce(scene, orthoCamera(), smallSettings());
    const glm::vec4 none(0.0f);
    EXPECT_EQ(pixel(frame, 4, 8), c.leftDrawn ? kGreen : none)
        << "cull " << int(c.cull) << ", mirrored " << c.mirrored;
    EXPECT_EQ(pixel(frame, 12, 8), c.rightDrawn ? kGreen : none)
        << "cull " << int(c.cull) << ", mirrored " << c.mirrored;
  }
}

// --- Determinism and the glTF path -----------------------------------------

// Overlapping translucent rectangles of many sizes (so both kernel widths
// draw), each with another equation, some multisampled edges.
Scene blendedStateScene() {
  Scene scene;
  addDraw(scene, fullScreen(9.0f), {0.2f, 0.4f, 0.6f, 1.0f}, AlphaMode::Opaque, std::nullopt);
  for (int k = 0; k < 40; ++k) {
    const float x = -1.0f + 0.047f * float(k), y = -0.9f + 0.041f * float((k * 7) % 40);
    const float size = 0.02f + 0.03f * float(k % 9);
    DrawState state;
    state.depthWrite = k % 3 == 0;
    state.depthCompare = k % 4 == 0 ? CompareFunction::LessEqual : CompareFunction::Less;
    state.blend = BlendState::uniform(kEquations[std::size_t(k) % kEquations.size()],
                                      kFactors[std::size_t(k) % kFactors.size()],
                                      kFactors[std::size_t(k * 3 + 1) % kFactors.size()]);
    addDraw(scene, rectangle(x, y, x + size * 3.0f, y + size * 2.0f, 8.0f - 0.1f * float(k % 5)),
            {0.1f + 0.02f * float(k), 0.9f - 0.02f * float(k), 0.5f, 0.3f + 0.015f * float(k)},
            AlphaMode::Blend, state);
  }
  return scene;
}

TEST(BlendState, BlendedSceneIsIdenticalAcrossIsasAndThreads) {
  const Scene scene = blendedStateScene();
  for (const int samples : {1, 4}) {
    RenderSettings settings;
    settings.width = 160;
    settings.height = 112;
    settings.samples = samples;
    const Frame reference = renderOnce(scene, orthoCamera(), settings, 1, Isa::Scalar);
    for (const Isa isa : supportedIsas())
      for (const int threads : {1, 2}) {
        const Frame frame = renderOnce(scene, orthoCamera(), settings, threads, isa);
        EXPECT_EQ(frame.rgba, reference.rgba)
            << isaName(isa) << ", " << threads << " threads, " << samples << " samples";
        EXPECT_EQ(frame.depth, reference.depth)
            << isaName(isa) << ", " << threads << " threads, " << samples << " samples";
      }
  }
}

// A built-in scene's instances given, explicitly, the state their materials
// imply (opaque and masked: the default state, culling back faces unless
// double-sided) render the same bits as without one.
TEST(DrawState, ExplicitDefaultStateMatchesTheMaterialsState) {
  Scene scene = makeBuiltinScene("showcase");
  Scene explicitState = scene;
  for (Instance& instance : explicitState.instances) {
    const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
    const Material material =
        mesh.material >= 0 ? scene.materials[std::size_t(mesh.material)] : Material{};
    if (material.alphaMode == AlphaMode::Blend) continue;  // depth-ordered: only without state
    DrawState state;
    state.cull = material.doubleSided ? CullMode::None : CullMode::Back;
    instance.drawState = state;
  }
  RenderSettings settings;
  settings.width = 192;
  settings.height = 108;
  const Camera camera = firstCameraOrDefault(scene);
  const Frame before = renderOnce(scene, camera, settings);
  const Frame after = renderOnce(explicitState, camera, settings);
  EXPECT_EQ(after.rgba, before.rgba);
  EXPECT_EQ(after.depth, before.depth);
}

}  // namespace
}  // namespace quadra
