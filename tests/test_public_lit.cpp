// Lit frames through the public C++ API (quadra/environment.hpp,
// RenderOptions' Pbr members): an Environment made from the embedder's float
// texels lights the frame the CLI renders from an EXR of those texels, bit
// for bit, in float (its EXR) and in 8 bits (its PNG, tone mapped, exposed);
// built-in names and files give their texels; an Environment is checked and
// repaired by --env's rules (docs/lighting.md "Environments"), and bad ones
// and bad lighting options are one-line errors. The C and Python APIs have
// the same comparisons (tests/c_api, tests/python).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "cli_helpers.h"
#include "png_reader.h"
#include "quadra/quadra.hpp"

namespace quadra {
namespace {

namespace api = quadra::api;

constexpr int kWidth = 64, kHeight = 48;
constexpr int kEnvWidth = 64, kEnvHeight = 32;

std::string boxModel() {
  return std::string(QUADRA_FUZZ_DIR) + "/corpus/glb/BoxTextured.glb";
}

// A panorama no symmetry maps onto itself: brighter and redder toward +Y,
// green varying around the horizon, and a small sun of radiance 50 off the
// centre, so a turned, flipped or shifted lookup changes the frame.
std::vector<float> panorama() {
  std::vector<float> rgb(std::size_t(kEnvWidth) * kEnvHeight * 3);
  for (int j = 0; j < kEnvHeight; ++j)
    for (int i = 0; i < kEnvWidth; ++i) {
      const float u = (float(i) + 0.5f) / kEnvWidth, v = (float(j) + 0.5f) / kEnvHeight;
      float* t = &rgb[(std::size_t(j) * kEnvWidth + std::size_t(i)) * 3];
      const bool sun = i >= 20 && i < 23 && j >= 9 && j < 11;
      t[0] = sun ? 50.0f : 0.2f + 0.8f * (1.0f - v);
      t[1] = sun ? 45.0f : 0.5f + 0.5f * std::sin(6.2831853f * u);
      t[2] = sun ? 40.0f : 0.7f * v;
    }
  return rgb;
}

struct Frame4 {
  std::vector<float> rgba = std::vector<float>(std::size_t(kWidth) * kHeight * 4);
  std::vector<std::uint8_t> srgb8 = std::vector<std::uint8_t>(std::size_t(kWidth) * kHeight * 4);
};

// The frame in both target formats, rendered by one Renderer.
Frame4 renderLit(api::Renderer& renderer, const api::Scene& scene,
                 const api::RenderOptions& options) {
  Frame4 out;
  renderer.render(scene,
                  {.pixels = std::as_writable_bytes(std::span(out.rgba)),
                   .width = kWidth,
                   .height = kHeight,
                   .rowStride = kWidth * 16,
                   .format = api::PixelFormat::Rgba32F},
                  nullptr, options);
  renderer.render(scene,
                  {.pixels = std::as_writable_bytes(std::span(out.srgb8)),
                   .width = kWidth,
                   .height = kHeight,
                   .rowStride = kWidth * 4,
                   .format = api::PixelFormat::Rgba8Srgb},
                  nullptr, options);
  return out;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// `quadra render BOX ARGS` at the test's size into an EXR and a PNG.
struct CliFrame {
  std::vector<float> rgba;
  std::vector<std::uint8_t> srgb8;
};
CliFrame cliFrame(const std::string& args, const std::string& name) {
  const fs::path exr = tempPath(name + ".exr"), png = tempPath(name + ".png");
  const RunResult r = run("render " + boxModel() + " --width " + std::to_string(kWidth) +
                          " --height " + std::to_string(kHeight) + " --threads 2 " + args +
                          " --out " + exr.string() + " --out " + png.string());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  if (r.exitCode != 0) return {};
  return {readImage(exr.string()).rgba, readPngDirectly(png.string()).bytes};
}

template <typename Call>
void expectErrorContaining(Call&& call, const std::string& part) {
  try {
    call();
    ADD_FAILURE() << "no error, expected one containing: " << part;
  } catch (const api::Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(part), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(PublicLit, ArrayEnvironmentLightsTheCliFrameOfItsExr) {
  const std::vector<float> texels = panorama();
  const fs::path envFile = tempPath("panorama.exr");
  writeExrRgb(texels.data(), kEnvWidth, kEnvHeight, envFile.string());

  const api::Scene scene = api::load(boxModel());
  api::Renderer renderer({.threads = 2});
  api::RenderOptions options{
      .shading = api::Shading::Pbr,
      .environment = api::Environment::fromTexels(texels, kEnvWidth, kEnvHeight)};
  const Frame4 api = renderLit(renderer, scene, options);
  const CliFrame cli = cliFrame("--shading pbr --env " + envFile.string(), "array");
  ASSERT_EQ(cli.rgba.size(), api.rgba.size());
  EXPECT_TRUE(sameBits(api.rgba, cli.rgba));
  EXPECT_EQ(api.srgb8, cli.srgb8);  // the tone-mapped bytes: pbr-neutral by default
  // Not vacuous: the box and the environment behind it, in many values.
  std::size_t distinct = 0;
  for (std::size_t i = 0; i < api.rgba.size(); i += 4) distinct += api.rgba[i] != api.rgba[0];
  EXPECT_GT(distinct, api.rgba.size() / 16);

  // Turned, scaled, exposed, ACES, without the background: the CLI's options
  // of the same names.
  options.environmentRotation = 75.0f;
  options.environmentIntensity = 2.5f;
  options.exposure = -1.5f;
  options.toneMap = api::ToneMap::Aces;
  options.background = api::Background::Transparent;
  const Frame4 turned = renderLit(renderer, scene, options);
  const CliFrame turnedCli = cliFrame("--env " + envFile.string() +
                                          " --env-rotation 75 --env-intensity 2.5 --exposure -1.5 "
                                          "--tonemap aces --background transparent",
                                      "turned");
  EXPECT_TRUE(sameBits(turned.rgba, turnedCli.rgba));
  EXPECT_EQ(turned.srgb8, turnedCli.srgb8);
  EXPECT_FALSE(sameBits(turned.rgba, api.rgba));
}

TEST(PublicLit, BuiltinsFilesAndTheDefaultAreTheirTexels) {
  const api::Scene scene = api::load(boxModel());
  api::Renderer renderer({.threads = 2});
  // A built-in by name and its texels as an array light alike; so do a file
  // and its texels.
  const api::Environment sky = api::Environment::load("builtin:sky");
  EXPECT_EQ(sky.name(), "builtin:sky");
  EXPECT_EQ(sky.texels().size(), std::size_t(sky.width()) * std::size_t(sky.height()) * 3);
  const Frame4 byName =
      renderLit(renderer, scene, {.shading = api::Shading::Pbr, .environment = sky});
  const Frame4 byTexels = renderLit(
      renderer, scene,
      {.shading = api::Shading::Pbr,
       .environment = api::Environment::fromTexels(sky.texels(), sky.width(), sky.height())});
  EXPECT_TRUE(sameBits(byName.rgba, byTexels.rgba));

  const std::vector<float> texels = panorama();
  const fs::path envFile = tempPath("file_panorama.exr");
  writeExrRgb(texels.data(), kEnvWidth, kEnvHeight, envFile.string());
  const api::Environment file = api::Environment::load(envFile.string());
  ASSERT_EQ(file.width(), kEnvWidth);
  ASSERT_EQ(file.height(), kEnvHeight);
  EXPECT_TRUE(std::equal(file.texels().begin(), file.texels().end(), texels.begin()));
  EXPECT_EQ(file.repairedValues(), 0u);

  // No environment: builtin:studio, which the CLI lights with by default
  // (pbr being its default shading).
  const Frame4 studio = renderLit(renderer, scene, {.shading = api::Shading::Pbr});
  const CliFrame cli = cliFrame("", "default");
  EXPECT_TRUE(sameBits(studio.rgba, cli.rgba));
  EXPECT_EQ(studio.srgb8, cli.srgb8);
  EXPECT_FALSE(sameBits(studio.rgba, byName.rgba));

  // Unlit frames keep their bytes: exposure 0, no tone map but the clamp.
  const Frame4 unlit = renderLit(renderer, scene, {});
  const CliFrame unlitCli = cliFrame("--shading unlit", "unlit");
  EXPECT_TRUE(sameBits(unlit.rgba, unlitCli.rgba));
  EXPECT_EQ(unlit.srgb8, unlitCli.srgb8);
}

TEST(PublicLit, TexelRuleRepairsWhatWouldPoisonTheFrame) {
  // NaN and negative values light as 0, values above 2^32 as 2^32: the frame
  // is that of the repaired texels, which texels() gives back.
  std::vector<float> texels = panorama(), repaired = texels;
  const float inf = std::numeric_limits<float>::infinity();
  texels[0] = std::numeric_limits<float>::quiet_NaN();
  texels[100] = -3.0f;
  texels[200] = -inf;
  texels[301] = inf;
  texels[402] = 1e38f;
  repaired[0] = repaired[100] = repaired[200] = 0.0f;
  repaired[301] = repaired[402] = 4294967296.0f;
  const api::Environment bad = api::Environment::fromTexels(texels, kEnvWidth, kEnvHeight);
  EXPECT_EQ(bad.repairedValues(), 5u);
  EXPECT_TRUE(std::equal(bad.texels().begin(), bad.texels().end(), repaired.begin()));

  const api::Scene scene = api::load(boxModel());
  api::Renderer renderer({.threads = 2});
  const Frame4 a = renderLit(renderer, scene, {.shading = api::Shading::Pbr, .environment = bad});
  const Frame4 b =
      renderLit(renderer, scene,
                {.shading = api::Shading::Pbr,
                 .environment = api::Environment::fromTexels(repaired, kEnvWidth, kEnvHeight)});
  EXPECT_TRUE(sameBits(a.rgba, b.rgba));
  for (float value : a.rgba) ASSERT_TRUE(std::isfinite(value));
}

TEST(PublicLit, BadEnvironmentsAndLightingAreOneLineErrors) {
  const std::vector<float> none;
  expectErrorContaining([&] { api::Environment::fromTexels(none, 0, 0); }, "at least 2 texels");
  const std::vector<float> one{1.0f, 1.0f, 1.0f};
  expectErrorContaining([&] { api::Environment::fromTexels(one, 1, 1); }, "at least 2 texels");
  const std::vector<float> texels = panorama();
  expectErrorContaining([&] { api::Environment::fromTexels(texels, kEnvWidth, kEnvHeight + 1); },
                        "texels need");
  expectErrorContaining([&] { api::Environment::fromTexels(texels, -4, -8); }, "at least 2 texels");
  const std::string missing = (testDir() / "no_such_panorama.hdr").string();
  expectErrorContaining([&] { api::Environment::load(missing); }, missing);
  expectErrorContaining([&] { api::Environment::load("builtin:nowhere"); }, "builtin:nowhere");
  // A file over the memory budget is refused before its texels are made.
  const fs::path envFile = tempPath("budget_panorama.exr");
  writeExrRgb(texels.data(), kEnvWidth, kEnvHeight, envFile.string());
  expectErrorContaining([&] { api::Environment::load(envFile.string(), 1024); }, "memory budget");

  const api::Scene scene = api::load(boxModel());
  api::Renderer renderer({.threads = 2});
  std::vector<float> pixels(std::size_t(kWidth) * kHeight * 4, -1.0f);
  const std::vector<float> untouched = pixels;
  const api::Target target{.pixels = std::as_writable_bytes(std::span(pixels)),
                           .width = kWidth,
                           .height = kHeight,
                           .rowStride = kWidth * 16,
                           .format = api::PixelFormat::Rgba32F};
  const auto renderWith = [&](const api::RenderOptions& options) {
    renderer.render(scene, target, nullptr, options);
  };
  expectErrorContaining([&] { renderWith({.shading = api::Shading::Pbr, .exposure = 65.0f}); },
                        "exposure");
  expectErrorContaining(
      [&] { renderWith({.shading = api::Shading::Pbr, .environmentIntensity = -1.0f}); },
      "environmentIntensity");
  expectErrorContaining(
      [&] {
        renderWith({.shading = api::Shading::Pbr,
                    .environmentRotation = std::numeric_limits<float>::quiet_NaN()});
      },
      "environmentRotation");
  expectErrorContaining([&] { renderWith({.shading = api::Shading(7)}); }, "shading");
  EXPECT_TRUE(sameBits(pixels, untouched));
}

}  // namespace
}  // namespace quadra
