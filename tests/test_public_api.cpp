// The public C++ API (include/quadra): each target format against the
// engine's own frame of the same scene built with the internal records, row
// strides with guard bytes, the depth and AOV targets, every misuse error,
// and that an update replaces only what it names; rendering in the
// embedder's arena.
#include <gtest/gtest.h>
#include <oneapi/tbb/task_scheduler_observer.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include "api/public_scene.h"
#include "api/renderer.h"
#include "io/srgb8.h"
#include "quadra/quadra.hpp"
#include "quadra/tbb.hpp"
#include "scene/gltf_loader.h"
#include "texture/image.h"
#include "texture/texel_format.h"

namespace {

namespace api = quadra::api;

constexpr int kWidth = 37;  // odd sizes: rows that do not fill tiles or SIMD lanes
constexpr int kHeight = 23;
constexpr std::byte kGuard{0xA5};

// Two quads: a textured opaque one, and a vertex-coloured half-transparent
// one in front of it, so the frame holds background, opaque and blended
// pixels (the sRGB target divides alpha out of the last).
struct SceneArrays {
  std::vector<float> quadPositions{-0.8f, -0.8f, 0, 0.5f, -0.8f, 0, 0.5f, 0.5f, 0, -0.8f, 0.5f, 0};
  std::vector<float> quadUvs{0, 1, 1, 1, 1, 0, 0, 0};
  std::vector<std::uint16_t> quadIndices{0, 1, 2, 0, 2, 3};
  std::vector<float> triPositions{-0.3f, -0.9f, 0.2f, 0.9f, -0.2f, 0.2f, 0.1f, 0.9f, 0.2f};
  std::vector<float> triColors{1, 0, 0, 1, 0, 1, 0, 0.5f, 0, 0, 1, 0.25f};
  std::vector<std::uint32_t> triIndices{0, 1, 2};
  // 2x2 sRGB texels, straight alpha.
  std::vector<std::uint8_t> texels{255, 0,  0,   255, 0,   200, 0,   255,
                                   10,  20, 250, 255, 255, 255, 128, 255};
};

api::TextureData textureData(const SceneArrays& a) {
  return {.width = 2,
          .height = 2,
          .format = api::TextureFormat::Rgba8Srgb,
          .texels = std::as_bytes(std::span(a.texels)),
          .filter = api::Filter::Nearest};
}

api::CameraData cameraData() {
  return {.projection = api::CameraData::Projection::Orthographic,
          .ymag = 1.0f,
          .znear = 0.5f,
          .zfar = 2.0f,
          .world = api::lookAt({0, 0, 1}, {0, 0, 0}, {0, 1, 0})};
}

struct PublicScene {
  api::Scene scene;
  api::MeshHandle quad, tri;
  api::TextureHandle texture;
};

PublicScene publicScene(const SceneArrays& a) {
  PublicScene s;
  s.texture = s.scene.addTexture(textureData(a));
  s.quad =
      s.scene.addMesh({.positions = a.quadPositions, .uvs = a.quadUvs, .indices16 = a.quadIndices});
  s.tri = s.scene.addMesh(
      {.positions = a.triPositions, .colors = a.triColors, .indices32 = a.triIndices});
  const auto textured = s.scene.addMaterial({.texture = s.texture});
  const auto blended = s.scene.addMaterial(
      {.baseColor = {1, 1, 1, 0.8f}, .alphaMode = api::AlphaMode::Blend, .doubleSided = true});
  s.scene.addInstance(s.quad, textured);
  s.scene.addInstance(s.tri, blended);
  s.scene.setCamera(cameraData());
  return s;
}

// The same scene spelled in the engine's records, and its frame; triState:
// the triangle instance's draw state; withAovs: every AOV and the coverage.
quadra::Frame internalFrame(const SceneArrays& a,
                            const std::optional<quadra::DrawState>& triState = std::nullopt,
                            bool withAovs = false) {
  quadra::Scene scene;
  auto image = std::make_shared<quadra::Image>(2, 2);
  for (int t = 0; t < 4; ++t) {
    for (int c = 0; c < 3; ++c) image->rgba[t * 4 + c] = quadra::srgb8ToLinear(a.texels[t * 4 + c]);
    image->rgba[t * 4 + 3] = a.texels[t * 4 + 3] * quadra::kUnorm8Scale;
  }
  quadra::SamplerState sampler;
  sampler.magLinear = false;
  sampler.minFilter = quadra::Filter::Nearest;
  scene.textures.push_back(
      std::make_shared<const quadra::Texture>(image, sampler, quadra::TexelFormat::Rgba8Srgb));
  quadra::Material textured;
  textured.baseColorTexture = 0;
  quadra::Material blended;
  blended.baseColorFactor = {1, 1, 1, 0.8f};
  blended.alphaMode = quadra::AlphaMode::Blend;
  blended.doubleSided = true;
  scene.materials = {textured, blended};
  quadra::Mesh quad;
  for (int v = 0; v < 4; ++v) {
    quad.positions.push_back(
        {a.quadPositions[v * 3], a.quadPositions[v * 3 + 1], a.quadPositions[v * 3 + 2]});
    quad.texcoords[0].push_back({a.quadUvs[v * 2], a.quadUvs[v * 2 + 1]});
  }
  quad.indices.assign(a.quadIndices.begin(), a.quadIndices.end());
  quad.material = 0;
  quadra::Mesh tri;
  for (int v = 0; v < 3; ++v) {
    tri.positions.push_back(
        {a.triPositions[v * 3], a.triPositions[v * 3 + 1], a.triPositions[v * 3 + 2]});
    tri.colors.push_back({a.triColors[v * 4], a.triColors[v * 4 + 1], a.triColors[v * 4 + 2],
                          a.triColors[v * 4 + 3]});
  }
  tri.indices = a.triIndices;
  tri.material = 1;
  scene.meshes = {quad, tri};
  scene.instances = {quadra::Instance{.mesh = 0}, quadra::Instance{.mesh = 1}};
  scene.instances[1].drawState = triState;
  quadra::Camera camera;
  camera.type = quadra::Camera::Type::Orthographic;
  camera.xmag = camera.ymag = 1.0f;
  camera.znear = 0.5f;
  camera.zfar = 2.0f;
  camera.world = quadra::lookAtWorld({0, 0, 1}, {0, 0, 0}, {0, 1, 0});
  quadra::RendererConfig config;
  config.threads = 2;
  quadra::Renderer renderer(config);
  quadra::RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  if (withAovs) {
    settings.aovs = std::uint32_t(quadra::Aov::Normal) | std::uint32_t(quadra::Aov::Position) |
                    std::uint32_t(quadra::Aov::Uv) | std::uint32_t(quadra::Aov::Ids);
    settings.frameCoverage = true;
  }
  quadra::Frame frame;
  renderer.render(scene, camera, settings, frame);
  return frame;
}

// A buffer of `rowStride`-byte rows plus a guard row, all guard bytes.
std::vector<std::byte> guarded(std::size_t rowStride) {
  return std::vector<std::byte>(rowStride * (kHeight + 1), kGuard);
}

// Every byte outside the first rowBytes of each of the kHeight rows is still
// the guard.
void expectGuardsKept(const std::vector<std::byte>& buffer, std::size_t rowStride,
                      std::size_t rowBytes) {
  std::size_t changed = 0;
  for (std::size_t i = 0; i < buffer.size(); ++i) {
    const bool pixel = i / rowStride < std::size_t(kHeight) && i % rowStride < rowBytes;
    if (!pixel) changed += buffer[i] != kGuard;
  }
  EXPECT_EQ(changed, 0u);
}

api::Target target(std::vector<std::byte>& buffer, std::size_t rowStride, api::PixelFormat format) {
  return {.pixels = buffer,
          .width = kWidth,
          .height = kHeight,
          .rowStride = rowStride,
          .format = format};
}

class PublicApi : public ::testing::Test {
 protected:
  SceneArrays arrays;
  quadra::Frame frame = internalFrame(arrays);
  api::Renderer renderer{{.threads = 2}};
};

TEST_F(PublicApi, Rgba32FIsTheEngineFrameBitForBit) {
  PublicScene s = publicScene(arrays);
  const std::size_t stride = kWidth * 16 + 32;  // padded rows
  std::vector<std::byte> buffer = guarded(stride);
  renderer.render(s.scene, target(buffer, stride, api::PixelFormat::Rgba32F));
  std::size_t differing = 0, drawn = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int i = 0; i < kWidth * 4; ++i) {
      float value;
      std::memcpy(&value, &buffer[y * stride + i * 4], 4);
      const float expected = frame.rgba[std::size_t(y) * kWidth * 4 + i];
      differing += std::memcmp(&value, &expected, 4) != 0;
      drawn += expected != 0.0f;
    }
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(drawn, std::size_t(kWidth * kHeight));  // the scene is on screen
  expectGuardsKept(buffer, stride, kWidth * 16);
}

// Contiguous RGBA32F rows and depth rows are resolved into in place (no
// frame copy, docs/api.md "Targets"); the bits are the same, whichever path a
// target takes and in whichever order targets of both kinds come.
TEST_F(PublicApi, ContiguousTargetsResolvedInPlaceHoldTheSameBits) {
  PublicScene s = publicScene(arrays);
  const std::size_t pixels = std::size_t(kWidth) * kHeight;
  for (const bool padded : {false, true, false}) {
    const std::size_t stride = kWidth * 16 + (padded ? 16 : 0);
    // Floats: 16-byte aligned as operator new gives; one row more as a guard.
    std::vector<float> color(stride / 4 * (kHeight + 1), -7.0f), depth(pixels + kWidth, -7.0f);
    const api::DepthTarget depthTarget{.bytes = std::as_writable_bytes(std::span(depth)),
                                       .rowStride = kWidth * 4};
    renderer.render(s.scene,
                    {.pixels = std::as_writable_bytes(std::span(color)),
                     .width = kWidth,
                     .height = kHeight,
                     .rowStride = stride,
                     .format = api::PixelFormat::Rgba32F},
                    &depthTarget);
    std::size_t differing = 0, guardsChanged = 0;
    for (int y = 0; y <= kHeight; ++y)
      for (std::size_t i = 0; i < stride / 4; ++i) {
        const float value = color[y * stride / 4 + i];
        if (y == kHeight || i >= std::size_t(kWidth) * 4)
          guardsChanged += value != -7.0f;
        else
          differing += std::memcmp(&value, &frame.rgba[y * kWidth * 4 + i], 4) != 0;
      }
    for (std::size_t i = 0; i < pixels + kWidth; ++i)
      if (i < pixels)
        differing += std::memcmp(&depth[i], &frame.depth[i], 4) != 0;
      else
        guardsChanged += depth[i] != -7.0f;
    EXPECT_EQ(differing, 0u) << (padded ? "padded" : "contiguous");
    EXPECT_EQ(guardsChanged, 0u) << (padded ? "padded" : "contiguous");
  }
}

TEST_F(PublicApi, Rgba16FIsTheFrameRoundedToHalves) {
  PublicScene s = publicScene(arrays);
  const std::size_t stride = kWidth * 8 + 6;  // a stride that is no multiple of a pixel
  std::vector<std::byte> buffer = guarded(stride);
  renderer.render(s.scene, target(buffer, stride, api::PixelFormat::Rgba16F));
  std::size_t differing = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int i = 0; i < kWidth * 4; ++i) {
      std::uint16_t half;
      std::memcpy(&half, &buffer[y * stride + i * 2], 2);
      differing += half != quadra::floatToHalf(frame.rgba[std::size_t(y) * kWidth * 4 + i]);
    }
  EXPECT_EQ(differing, 0u);
  expectGuardsKept(buffer, stride, kWidth * 8);
}

// Against the codes' definition (srgb8Code, through pow), not the fast
// encoder the target is written with.
TEST_F(PublicApi, Rgba8SrgbHoldsTheStraightSrgbCodesOfTheFrame) {
  PublicScene s = publicScene(arrays);
  const std::size_t stride = kWidth * 4 + 3;
  std::vector<std::byte> buffer = guarded(stride);
  renderer.render(s.scene, target(buffer, stride, api::PixelFormat::Rgba8Srgb));
  std::size_t differing = 0, translucent = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const float* p = &frame.rgba[(std::size_t(y) * kWidth + x) * 4];
      const std::byte* out = &buffer[y * stride + x * 4];
      translucent += p[3] > 0.0f && p[3] < 1.0f;
      for (int c = 0; c < 3; ++c) {
        const float straight = p[3] > 0.0f ? p[c] / p[3] : p[c];
        differing += std::uint8_t(out[c]) != quadra::srgb8Code(straight);
      }
      differing += std::uint8_t(out[3]) != std::uint8_t(std::lround(std::min(p[3], 1.0f) * 255.0));
    }
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(translucent, 10u);  // the blended triangle's alpha is divided out
  expectGuardsKept(buffer, stride, kWidth * 4);
}

TEST_F(PublicApi, DepthTargetHoldsTheFrameDepthWithItsOwnStride) {
  PublicScene s = publicScene(arrays);
  std::vector<std::byte> color(kWidth * 4 * kHeight);
  const std::size_t depthStride = kWidth * 4 + 20;
  std::vector<std::byte> depth = guarded(depthStride);
  const api::DepthTarget depthTarget{.bytes = depth, .rowStride = depthStride};
  renderer.render(s.scene, target(color, kWidth * 4, api::PixelFormat::Rgba8Srgb), &depthTarget);
  std::size_t differing = 0, onQuad = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      float value;
      std::memcpy(&value, &depth[y * depthStride + x * 4], 4);
      const float expected = frame.depth[std::size_t(y) * kWidth + x];
      differing += std::memcmp(&value, &expected, 4) != 0;
      // The opaque quad at z = 0 seen from z = 1, near 0.5, far 2: depth
      // (1 - 0.5) / (2 - 0.5) = 1/3.
      if (std::abs(value - 1.0f / 3.0f) < 1e-6f) ++onQuad;
    }
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(onQuad, std::size_t(kWidth * kHeight / 4));
  expectGuardsKept(depth, depthStride, kWidth * 4);
}

// One misuse, its message, and that nothing was written.
template <typename Call>
void expectError(Call&& call, const std::string& message) {
  try {
    call();
    ADD_FAILURE() << "no error, expected: " << message;
  } catch (const api::Error& error) {
    EXPECT_EQ(std::string(error.what()), message);
  }
}

TEST_F(PublicApi, TargetMisuseIsAnErrorAndWritesNothing) {
  PublicScene s = publicScene(arrays);
  std::vector<std::byte> buffer = guarded(kWidth * 4);
  const auto untouched = buffer;
  auto render = [&](api::Target t, const api::DepthTarget* depth = nullptr) {
    return [&, t, depth] { renderer.render(s.scene, t, depth); };
  };
  api::Target t = target(buffer, kWidth * 4, api::PixelFormat::Rgba8Srgb);
  expectError(render({.pixels = buffer, .width = 0, .height = 5, .rowStride = 16}),
              "render target: 0x5 is not within 1..8192 pixels each way");
  api::Target shortStride = t;
  shortStride.rowStride = kWidth * 4 - 1;
  expectError(render(shortStride),
              "render target: row stride 147 bytes is less than a row's 37 x 4 = 148");
  api::Target shortBuffer = t;
  shortBuffer.pixels = std::span(buffer).first(kWidth * 4 * kHeight - 1);
  expectError(render(shortBuffer),
              "render target: 37x23 at row stride 148 needs 3404 bytes, the buffer has 3403");
  api::Target oddStride = target(buffer, kWidth * 16 + 2, api::PixelFormat::Rgba32F);
  expectError(render(oddStride),
              "render target: row stride 594 bytes is not a multiple of the channel size 4");
  std::vector<std::byte> depth(kWidth * 4 * kHeight);
  const api::DepthTarget shortDepth{.bytes = std::span(depth).first(100), .rowStride = kWidth * 4};
  expectError(render(t, &shortDepth),
              "depth target: 37x23 at row stride 148 needs 3404 bytes, the buffer has 100");
  EXPECT_EQ(buffer, untouched);
}

// The public AOV targets, each in a buffer of its own padded stride (the
// guard rows and padding say what was written), and the engine's planes of
// them in the same order.
struct AovBuffers {
  static constexpr std::size_t kChannels[7] = {3, 3, 2, 1, 1, 1, 1};
  static constexpr const char* kNames[7] = {"normal",      "position", "uv",        "mask",
                                            "primitiveId", "nodeId",   "materialId"};
  std::vector<std::byte> bytes[7];
  api::AovTargets targets;  // over bytes: not to be copied
  AovBuffers(const AovBuffers&) = delete;
  AovBuffers() {
    api::AovTarget* planes[7] = {&targets.normal,    &targets.position,    &targets.uv,
                                 &targets.mask,      &targets.primitiveId, &targets.nodeId,
                                 &targets.materialId};
    for (int i = 0; i < 7; ++i) {
      bytes[i] = guarded(stride(i));
      *planes[i] = {.bytes = bytes[i], .rowStride = stride(i)};
    }
  }
  // Padded by a pixel and a float, so no two planes share a stride.
  static std::size_t stride(int i) { return (kWidth + 1) * kChannels[i] * 4 + 4; }
  static const void* enginePlane(const quadra::Frame& f, int i) {
    const void* planes[7] = {f.normal.data(),    f.position.data(),    f.uv.data(),
                             f.coverage.data(),  f.primitiveId.data(), f.nodeId.data(),
                             f.materialId.data()};
    return planes[i];
  }
  // Plane i's value at pixel (x, y), channel c, as 4 bytes.
  template <typename T>
  T at(int i, int x, int y, int c = 0) const {
    T value;
    std::memcpy(&value, &bytes[i][y * stride(i) + (x * kChannels[i] + c) * 4], 4);
    return value;
  }
};

// Each AOV target holds the engine frame's plane bit for bit, rows at the
// target's stride, nothing written past them; the colour is unchanged.
TEST_F(PublicApi, AovTargetsAreTheEngineFramesPlanesBitForBit) {
  PublicScene s = publicScene(arrays);
  const quadra::Frame engine = internalFrame(arrays, std::nullopt, true);
  AovBuffers aovs;
  std::vector<float> color(std::size_t(kWidth) * kHeight * 4);
  renderer.render(s.scene,
                  {.pixels = std::as_writable_bytes(std::span(color)),
                   .width = kWidth,
                   .height = kHeight,
                   .rowStride = kWidth * 16,
                   .format = api::PixelFormat::Rgba32F},
                  nullptr, {}, &aovs.targets);
  for (int i = 0; i < 7; ++i) {
    const std::size_t rowBytes = kWidth * AovBuffers::kChannels[i] * 4;
    std::size_t differing = 0;
    for (int y = 0; y < kHeight; ++y)
      differing += std::memcmp(&aovs.bytes[i][y * AovBuffers::stride(i)],
                               static_cast<const std::byte*>(AovBuffers::enginePlane(engine, i)) +
                                   y * rowBytes,
                               rowBytes) != 0;
    EXPECT_EQ(differing, 0u) << AovBuffers::kNames[i] << ": rows differ";
    expectGuardsKept(aovs.bytes[i], AovBuffers::stride(i), rowBytes);
  }
  EXPECT_EQ(std::memcmp(color.data(), frame.rgba.data(), color.size() * 4), 0);
}

// The opaque quad ([-0.8, 0.5]^2 at z = 0, uv (0, 1) at its (-0.8, -0.8)
// corner and (1, 0) at (0.5, 0.5), triangles (0, 1, 2) below its diagonal
// and (0, 2, 3) above) seen orthographically down -z over x in [-37/23,
// 37/23], y in [-1, 1]: at each pixel centre well inside it, N = (0, 0, 1),
// P = (x, y, 0), uv linear in x and y, its ids and full coverage; well
// outside it the clear values. Here the quad is instance 1 with material
// 2, so that no two ids agree, and the blended triangle in front of it is
// instance 0: it writes no AOV.
TEST_F(PublicApi, AovsOfTheQuadAreItsAnalyticValuesAtPixelCentres) {
  api::Scene scene;
  const auto blended = scene.addMaterial(
      {.baseColor = {1, 1, 1, 0.5f}, .alphaMode = api::AlphaMode::Blend, .doubleSided = true});
  scene.addMaterial({});
  const auto opaque = scene.addMaterial({});
  scene.addInstance(scene.addMesh({.positions = arrays.triPositions,
                                   .colors = arrays.triColors,
                                   .indices32 = arrays.triIndices}),
                    blended);
  scene.addInstance(scene.addMesh({.positions = arrays.quadPositions,
                                   .uvs = arrays.quadUvs,
                                   .indices16 = arrays.quadIndices}),
                    opaque);
  scene.setCamera(cameraData());
  AovBuffers aovs;
  std::vector<std::byte> color(kWidth * 4 * kHeight);
  renderer.render(scene, target(color, kWidth * 4, api::PixelFormat::Rgba8Srgb), nullptr, {},
                  &aovs.targets);
  const double halfWidth = double(kWidth) / kHeight;
  const double margin = 0.05;  // about half a pixel: centres this close to an edge are skipped
  std::size_t inside = 0, outside = 0, wrong = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double wx = ((x + 0.5) / kWidth * 2 - 1) * halfWidth;
      const double wy = 1 - (y + 0.5) / kHeight * 2;
      const double edge = std::min({wx + 0.8, 0.5 - wx, wy + 0.8, 0.5 - wy});
      if (edge > margin && std::abs(wx - wy) > margin) {
        ++inside;
        const float expected[] = {0, 0, 1, float(wx), float(wy), 0};
        for (int c = 0; c < 3; ++c) {
          wrong += aovs.at<float>(0, x, y, c) != expected[c];
          wrong += std::abs(aovs.at<float>(1, x, y, c) - expected[3 + c]) > 1e-6f;
        }
        wrong += std::abs(aovs.at<float>(2, x, y, 0) - (wx + 0.8) / 1.3) > 1e-6;
        wrong += std::abs(aovs.at<float>(2, x, y, 1) - (0.5 - wy) / 1.3) > 1e-6;
        wrong += aovs.at<float>(3, x, y) != 1.0f;
        wrong += aovs.at<std::uint32_t>(4, x, y) != (wx > wy ? 0u : 1u);
        wrong += aovs.at<std::uint32_t>(5, x, y) != 1u;  // the quad's InstanceHandle
        wrong += aovs.at<std::uint32_t>(6, x, y) != 2u;  // its MaterialHandle
      } else if (edge < -margin) {
        ++outside;
        for (int i = 0; i < 4; ++i)
          for (std::size_t c = 0; c < AovBuffers::kChannels[i]; ++c)
            wrong += aovs.at<float>(i, x, y, int(c)) != 0.0f;
        for (int i = 4; i < 7; ++i) wrong += aovs.at<std::uint32_t>(i, x, y) != quadra::kNoId;
      }
    }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(inside, std::size_t(kWidth * kHeight / 5));
  EXPECT_GT(outside, std::size_t(kWidth * kHeight / 5));
}

// An AOV target that fails validation is an error naming it, and no target
// (colour or AOV) is written; a null one is simply not asked for.
TEST_F(PublicApi, AovTargetMisuseIsAnErrorNamingTheAovAndWritesNothing) {
  PublicScene s = publicScene(arrays);
  std::vector<std::byte> color = guarded(kWidth * 4);
  const auto colorBefore = color;
  const auto expectRefused = [&](const api::AovTargets& targets, const std::string& message) {
    expectError(
        [&] {
          renderer.render(s.scene, target(color, kWidth * 4, api::PixelFormat::Rgba8Srgb), nullptr,
                          {}, &targets);
        },
        message);
    EXPECT_EQ(color, colorBefore);
  };
  AovBuffers aovs;
  const AovBuffers untouched;
  api::AovTargets shortPosition = aovs.targets;
  shortPosition.position.bytes = shortPosition.position.bytes.first(100);
  expectRefused(shortPosition,
                "position AOV target: 37x23 at row stride 460 needs 10564 bytes, the buffer has "
                "100");
  api::AovTargets shortStride = aovs.targets;
  shortStride.uv.rowStride = kWidth * 8 - 4;
  expectRefused(shortStride,
                "uv AOV target: row stride 292 bytes is less than a row's 37 x 8 = 296");
  api::AovTargets oddStride = aovs.targets;
  oddStride.materialId.rowStride = kWidth * 4 + 2;
  expectRefused(oddStride,
                "materialId AOV target: row stride 150 bytes is not a multiple of the channel "
                "size 4");
  api::AovTargets misaligned = aovs.targets;
  misaligned.mask.bytes = misaligned.mask.bytes.subspan(1);
  expectRefused(misaligned, "mask AOV target: buffer is not aligned to 4 bytes");
  for (int i = 0; i < 7; ++i) EXPECT_EQ(aovs.bytes[i], untouched.bytes[i]) << AovBuffers::kNames[i];

  // Only the node ids asked: that plane written, none of the other AOVs' buffers.
  api::AovTargets nodeOnly;
  nodeOnly.nodeId = aovs.targets.nodeId;
  renderer.render(s.scene, target(color, kWidth * 4, api::PixelFormat::Rgba8Srgb), nullptr, {},
                  &nodeOnly);
  for (int i = 0; i < 7; ++i)
    EXPECT_EQ(aovs.bytes[i] == untouched.bytes[i], i != 5) << AovBuffers::kNames[i];
}

// RenderOptions::maxMemory is the CLI's --max-memory for a frame: refused
// before anything is drawn, with the engine's one-line message.
TEST_F(PublicApi, FrameOverItsMemoryBudgetIsAnErrorAndWritesNothing) {
  PublicScene s = publicScene(arrays);
  std::vector<std::byte> buffer = guarded(kWidth * 16);
  const std::vector<std::byte> before = buffer;
  expectError(
      [&] {
        renderer.render(s.scene, target(buffer, kWidth * 16, api::PixelFormat::Rgba32F), nullptr,
                        {.maxMemory = 1000});
      },
      "render: the 37x23 frame needs 13.3 KiB, over the memory budget of 1000 bytes (24 bytes "
      "already used; --max-memory raises it)");
  EXPECT_EQ(buffer, before);
  renderer.render(s.scene, target(buffer, kWidth * 16, api::PixelFormat::Rgba32F), nullptr,
                  {.maxMemory = 1 << 30});
  EXPECT_NE(buffer, before);
}

TEST_F(PublicApi, SceneMisuseIsAnErrorAndChangesNothing) {
  PublicScene s = publicScene(arrays);
  std::vector<float> positions = arrays.triPositions;
  std::vector<std::uint32_t> badIndices{0, 1, 3};
  expectError([&] { s.scene.addMesh({.positions = positions, .indices32 = badIndices}); },
              "mesh: index 3 (entry 2) is out of range for 3 vertices");
  std::vector<float> shortNormals(8);
  expectError(
      [&] {
        s.scene.addMesh(
            {.positions = positions, .normals = shortNormals, .indices32 = arrays.triIndices});
      },
      "mesh: normals hold 8 floats, 3 vertices need 9");
  std::vector<float> shortUvs(5);
  expectError(
      [&] {
        s.scene.updateMesh(
            s.tri, {.positions = positions, .uvs = shortUvs, .indices32 = arrays.triIndices});
      },
      "mesh: uvs hold 5 floats, 3 vertices need 6");
  std::vector<float> ragged(7);
  expectError([&] { s.scene.addMesh({.positions = ragged, .indices32 = arrays.triIndices}); },
              "mesh: positions hold 7 floats, not 3 per vertex");
  expectError([&] { s.scene.addMesh({.positions = positions}); },
              "mesh: no indices (give indices32 or indices16)");
  expectError([&] { s.scene.addTexture({.width = 0, .height = 4}); },
              "texture: 0x4 texels; a texture needs at least one");
  api::TextureData shortTexels = textureData(arrays);
  shortTexels.texels = shortTexels.texels.first(15);
  expectError([&] { s.scene.addTexture(shortTexels); },
              "texture: 2x2 texels need 16 bytes, the array has 15");
  api::Matrix4 transform = api::kIdentity;
  transform[13] = std::nanf("");
  const auto material = s.scene.addMaterial({});
  expectError([&] { s.scene.addInstance(s.quad, material, transform); },
              "instance transform: element 13 (column 3, row 1) is NaN");
  transform[13] = INFINITY;
  expectError([&] { s.scene.setTransform({0}, transform); },
              "instance transform: element 13 (column 3, row 1) is infinite");
  expectError([&] { s.scene.addInstance({7}, material); },
              "addInstance mesh: handle 7 is not one of this scene's 2");
  EXPECT_EQ(s.scene.meshCount(), 2u);
  EXPECT_EQ(s.scene.instanceCount(), 2u);
  expectError([] { api::load("/nonexistent/model.gltf"); },
              []() {
                try {
                  quadra::loadGltf("/nonexistent/model.gltf");
                } catch (const std::exception& e) {
                  return std::string(e.what());
                }
                return std::string();
              }());
}

// updateMesh replaces that mesh's arrays and nothing else: the other mesh's
// and the textures' storage stays where it was (so its built levels are
// kept), and the frame equals one of a scene built with the new arrays.
TEST_F(PublicApi, UpdatingOneMeshOrTextureLeavesTheRestAlone) {
  PublicScene s = publicScene(arrays);
  std::vector<std::byte> before(kWidth * 16 * kHeight), after(before.size()), fresh(before.size());
  renderer.render(s.scene, target(before, kWidth * 16, api::PixelFormat::Rgba32F));
  const quadra::Scene& inside = api::detail::SceneAccess::of(s.scene).scene;
  const glm::vec3* quadPositions = inside.meshes[0].positions.data();
  const quadra::Texture* texture = inside.textures[0].get();

  SceneArrays moved = arrays;
  for (std::size_t i = 0; i < moved.triPositions.size(); i += 3) moved.triPositions[i] += 0.25f;
  s.scene.updateMesh(
      s.tri,
      {.positions = moved.triPositions, .colors = moved.triColors, .indices32 = moved.triIndices});
  EXPECT_EQ(inside.meshes[0].positions.data(), quadPositions);
  EXPECT_EQ(inside.textures[0].get(), texture);
  renderer.render(s.scene, target(after, kWidth * 16, api::PixelFormat::Rgba32F));
  PublicScene rebuilt = publicScene(moved);
  renderer.render(rebuilt.scene, target(fresh, kWidth * 16, api::PixelFormat::Rgba32F));
  EXPECT_EQ(after, fresh);
  EXPECT_NE(after, before);

  moved.texels[0] = 7;  // one texel changes
  s.scene.updateTexture(s.texture, textureData(moved));
  EXPECT_EQ(inside.meshes[0].positions.data(), quadPositions);
  EXPECT_NE(inside.textures[0].get(), texture);
  renderer.render(s.scene, target(after, kWidth * 16, api::PixelFormat::Rgba32F));
  rebuilt = publicScene(moved);
  renderer.render(rebuilt.scene, target(fresh, kWidth * 16, api::PixelFormat::Rgba32F));
  EXPECT_EQ(after, fresh);
}

// rendererIn: the frames run in the embedder's arena (its observer sees a
// thread enter it during the render), with its concurrency as the thread
// count, and are the same bits as a renderer of quadra's own arena.
TEST_F(PublicApi, RendererInTheEmbeddersArenaRunsThereWithTheSameBits) {
  struct EntryCounter : tbb::task_scheduler_observer {
    std::atomic<int> entries{0};
    explicit EntryCounter(tbb::task_arena& arena) : tbb::task_scheduler_observer(arena) {
      observe(true);
    }
    ~EntryCounter() override { observe(false); }
    void on_scheduler_entry(bool) override { ++entries; }
  };
  tbb::task_arena arena(2);
  arena.initialize();
  EntryCounter counter(arena);
  api::Renderer inArena = api::rendererIn(arena);
  EXPECT_EQ(inArena.threadCount(), 2);
  PublicScene s = publicScene(arrays);
  // Large enough that its loops are split into tasks, not run inline.
  const int size = 512;
  std::vector<std::byte> ours(std::size_t(size) * size * 16), theirs(ours.size());
  auto big = [&](std::vector<std::byte>& buffer) {
    return api::Target{.pixels = buffer,
                       .width = size,
                       .height = size,
                       .rowStride = std::size_t(size) * 16,
                       .format = api::PixelFormat::Rgba32F};
  };
  inArena.render(s.scene, big(theirs));
  EXPECT_GT(counter.entries.load(), 0);
  renderer.render(s.scene, big(ours));
  EXPECT_EQ(ours, theirs);
}

// RenderOptions reach the engine's settings, and a loaded file renders as the
// engine renders it through its first camera or the default one.
// setDrawState reaches the engine as the same DrawState: the triangle drawn
// over the quad without depth test, reverse-subtracted with separate alpha
// factors, is the engine's frame of that state bit for bit; nullopt goes back
// to the material's blend; values outside an enum are errors.
TEST_F(PublicApi, DrawStateIsTheEnginesDrawState) {
  PublicScene s = publicScene(arrays);
  const api::InstanceHandle tri{1};
  api::DrawStateData state;
  state.depthTest = false;
  state.cull = api::CullMode::Front;  // the triangle is double-sided, so culling must drop nothing
  state.blend = {.enabled = true,
                 .colorEquation = api::BlendEquation::ReverseSubtract,
                 .alphaEquation = api::BlendEquation::Max,
                 .srcColor = api::BlendFactor::DstAlpha,
                 .dstColor = api::BlendFactor::OneMinusSrcColor,
                 .srcAlpha = api::BlendFactor::One,
                 .dstAlpha = api::BlendFactor::One};
  s.scene.setDrawState(tri, state);
  quadra::DrawState engine;
  engine.depthTest = false;
  engine.cull = quadra::CullMode::Front;
  engine.blend = {true,
                  quadra::BlendEquation::ReverseSubtract,
                  quadra::BlendEquation::Max,
                  quadra::BlendFactor::DstAlpha,
                  quadra::BlendFactor::OneMinusSrcColor,
                  quadra::BlendFactor::One,
                  quadra::BlendFactor::One};
  const quadra::Frame expected = internalFrame(arrays, engine);
  std::vector<float> pixels(std::size_t(kWidth) * kHeight * 4);
  const api::Target floats{.pixels = std::as_writable_bytes(std::span(pixels)),
                           .width = kWidth,
                           .height = kHeight,
                           .rowStride = kWidth * 16,
                           .format = api::PixelFormat::Rgba32F};
  renderer.render(s.scene, floats);
  EXPECT_EQ(std::memcmp(pixels.data(), expected.rgba.data(), pixels.size() * 4), 0);
  EXPECT_NE(std::memcmp(pixels.data(), frame.rgba.data(), pixels.size() * 4), 0);

  s.scene.setDrawState(tri, std::nullopt);
  renderer.render(s.scene, floats);
  EXPECT_EQ(std::memcmp(pixels.data(), frame.rgba.data(), pixels.size() * 4), 0);

  api::DrawStateData bad;
  bad.blend.dstAlpha = api::BlendFactor(77);
  try {
    s.scene.setDrawState(tri, bad);
    ADD_FAILURE() << "a factor outside the enum was taken";
  } catch (const api::Error& e) {
    EXPECT_STREQ(e.what(), "setDrawState: blend.dstAlpha 77 is not one of its values");
  }
  try {
    s.scene.setDrawState(api::InstanceHandle{9}, state);
    ADD_FAILURE() << "a made-up instance handle was taken";
  } catch (const api::Error&) {
  }
}

TEST(PublicApiLoad, LoadedFileWithOptionsIsTheEngineFrame) {
  const std::string path = QUADRA_FUZZ_DIR "/corpus/glb/BoxTextured.glb";
  const api::Scene scene = api::load(path);
  const api::RenderOptions options{
      .shading = api::Shading::Lit, .samples = 4, .clearColor = {0.1f, 0.2f, 0.3f, 1.0f}};
  std::vector<float> pixels(std::size_t(kWidth) * kHeight * 4);
  api::Renderer renderer({.threads = 2});
  renderer.render(scene,
                  {.pixels = std::as_writable_bytes(std::span(pixels)),
                   .width = kWidth,
                   .height = kHeight,
                   .rowStride = kWidth * 16,
                   .format = api::PixelFormat::Rgba32F},
                  nullptr, options);

  const quadra::Scene inside = quadra::loadGltf(path);
  quadra::RendererConfig config;
  config.threads = 1;  // another thread count: the same bits
  quadra::Renderer engine(config);
  quadra::RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.shading = quadra::Shading::Lit;
  settings.samples = 4;
  settings.clearColor = {0.1f, 0.2f, 0.3f, 1.0f};
  quadra::Frame frame;
  engine.render(inside, quadra::firstCameraOrDefault(inside), settings, frame);
  ASSERT_EQ(frame.rgba.size(), pixels.size());
  EXPECT_EQ(std::memcmp(frame.rgba.data(), pixels.data(), pixels.size() * 4), 0);
  std::size_t background = 0;
  for (std::size_t i = 0; i < pixels.size(); i += 4) background += pixels[i + 2] == 0.3f;
  EXPECT_GT(background, 0u);                                      // the clear colour
  EXPECT_LT(background, std::size_t(kWidth) * kHeight * 9 / 10);  // and the box

  // Loaded on the embedder's arena: the same frame.
  tbb::task_arena arena(2);
  const api::Scene inArena = api::loadIn(path, arena);
  std::vector<float> again(pixels.size());
  renderer.render(inArena,
                  {.pixels = std::as_writable_bytes(std::span(again)),
                   .width = kWidth,
                   .height = kHeight,
                   .rowStride = kWidth * 16,
                   .format = api::PixelFormat::Rgba32F},
                  nullptr, options);
  EXPECT_EQ(std::memcmp(again.data(), pixels.data(), pixels.size() * 4), 0);
}

TEST(PublicApiVersion, RuntimeVersionIsTheHeadersAndProjects) {
  EXPECT_STREQ(quadra::version(), QUADRA_VERSION_STRING);
  const std::string composed = std::to_string(QUADRA_VERSION_MAJOR) + "." +
                               std::to_string(QUADRA_VERSION_MINOR) + "." +
                               std::to_string(QUADRA_VERSION_PATCH);
  EXPECT_EQ(composed, QUADRA_VERSION_STRING);
}

}  // namespace
