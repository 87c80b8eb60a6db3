// The memory budget (--max-memory, LoadOptions::maxMemory,
// RenderSettings::maxMemory): the SIZE syntax, and one scene per category
// crafted to go over it — a buffer, a mesh decode, images whose headers claim
// more than the budget holds, a texture whose mip chain tips it over, tile
// memory at 16 samples — each refused with one line naming what and how
// much, before the allocation: several of them claim more than this machine
// has, so only an error raised first lets the test finish at all.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "api/renderer.h"
#include "bin/bins.h"
#include "cli_helpers.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "lab/scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "setup/triangle_record.h"
#include "texture/texture_sampler.h"
#include "tile/tile_stage.h"

namespace quadra {
namespace {

constexpr std::uint64_t kMiB = std::uint64_t(1) << 20;
constexpr std::uint64_t kGiB = std::uint64_t(1) << 30;

std::string sizeError(const std::string& text) {
  try {
    parseMemorySize("--max-memory", text);
  } catch (const Error& e) {
    return e.what();
  }
  return "accepted";
}

TEST(MemoryBudget, SizesAreBytesOrBinaryMultiples) {
  EXPECT_EQ(parseMemorySize("--max-memory", "65536"), 65536u);
  EXPECT_EQ(parseMemorySize("--max-memory", "1b"), 1u);
  EXPECT_EQ(parseMemorySize("--max-memory", "2K"), 2048u);
  EXPECT_EQ(parseMemorySize("--max-memory", "512M"), 512 * kMiB);
  EXPECT_EQ(parseMemorySize("--max-memory", "512MiB"), 512 * kMiB);
  EXPECT_EQ(parseMemorySize("--max-memory", "512mb"), 512 * kMiB);
  EXPECT_EQ(parseMemorySize("--max-memory", "4G"), 4 * kGiB);
  EXPECT_EQ(parseMemorySize("--max-memory", "1.5G"), 3 * kGiB / 2);
  EXPECT_EQ(parseMemorySize("--max-memory", "2T"), 2048 * kGiB);
  const std::string syntax =
      "' is not a size (bytes, or a number with K, M, G or T, 1024-based: 512M, 4G)";
  for (const char* bad : {"", "G", "12Q", "-1", "1e9", "0x10", "1..5M", ".", "4 G", "4GG", "4Gi"})
    EXPECT_EQ(sizeError(bad), std::string("--max-memory: '") + bad + syntax) << bad;
  EXPECT_EQ(parseMemorySize("--max-memory", "1024T"), std::uint64_t(1) << 50);
  for (const char* outOfRange : {"0", "0.4", "1025T", "2000000T"})
    EXPECT_EQ(sizeError(outOfRange),
              std::string("--max-memory: '") + outOfRange + "' is out of range (1 byte to 1024T)")
        << outOfRange;
}

TEST(MemoryBudget, ChargesUntilTheLimitAndNamesWhatWentOver) {
  MemoryBudget budget(10 * kMiB, "scene.gltf");
  budget.charge("a", 4 * kMiB);
  budget.charge("b", 6 * kMiB);  // exactly the limit
  EXPECT_EQ(budget.used(), 10 * kMiB);
  try {
    budget.charge("image 3 decoded", 1);
    ADD_FAILURE() << "a byte over the limit was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "scene.gltf: image 3 decoded needs 1 byte, over the memory budget of 10.0 MiB "
              "(10.0 MiB already used; --max-memory raises it)");
  }
  EXPECT_EQ(budget.used(), 10 * kMiB);  // a refused charge counts nothing
}

// ---- loading --------------------------------------------------------------------------

fs::path writeText(const std::string& name, const std::string& text) {
  const fs::path path = tempPath(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::vector<std::uint8_t> fileBytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string loadError(const fs::path& path, const LoadOptions& options) {
  try {
    loadGltf(path.string(), options);
  } catch (const Error& e) {
    return e.what();
  }
  return "loaded";
}

// The budget's one line: the file first, then what and how much.
void expectOver(const std::string& message, const fs::path& file, const std::string& what) {
  EXPECT_EQ(message.rfind(file.string() + ": " + what + " needs ", 0), 0u) << message;
  EXPECT_NE(message.find(", over the memory budget of "), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

std::string base64(const std::string& bytes) {
  static const char* const digits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t left = bytes.size() - i;
    std::uint32_t group = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (left > 1) group |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    if (left > 2) group |= std::uint8_t(bytes[i + 2]);
    out += digits[(group >> 18) & 63];
    out += digits[(group >> 12) & 63];
    out += left > 1 ? digits[(group >> 6) & 63] : '=';
    out += left > 2 ? digits[group & 63] : '=';
  }
  return out;
}

const std::string kAsset = R"("asset":{"version":"2.0"})";

// A buffer the file itself holds (a data URI): the file fits the budget, the
// decoded buffer on top of it does not.
TEST(MemoryBudget, ABufferOverTheBudgetIsRefused) {
  const std::string data(4096, '\x7f');
  const fs::path path = writeText(
      "budget_buffer.gltf", "{" + kAsset + R"(,"buffers":[{"byteLength":4096,"uri":")" +
                                "data:application/octet-stream;base64," + base64(data) + "\"}]}");
  const std::uint64_t fileBytes = fs::file_size(path);
  const std::uint64_t json = parsedJsonBytes(path.string(), fileBytesOf(path));
  LoadOptions options;
  options.maxMemory = fileBytes + json + 4095;
  expectOver(loadError(path, options), path, "buffer 0");
  options.maxMemory = fileBytes + json + 4096;
  EXPECT_EQ(loadError(path, options), "loaded");
  // The file alone over the budget: refused before it is read.
  options.maxMemory = fileBytes - 1;
  expectOver(loadError(path, options), path, "the file (" + std::to_string(fileBytes) + " bytes)");
}

// A few bytes of JSON can parse to a big structure: each "{}" in a
// materials array is an empty material of over 2 KiB in tinygltf's model.
// The parse is charged from the text's structure before it is parsed; braces
// inside strings are text, not objects.
TEST(MemoryBudget, JsonThatParsesToMoreThanTheBudgetIsRefusedBeforeParsing) {
  std::string materials;
  for (int m = 0; m < 100000; ++m) materials += m == 0 ? "{}" : ",{}";
  const fs::path path =
      writeText("budget_json.gltf", "{" + kAsset + R"(,"materials":[)" + materials + "]}");
  const std::uint64_t text = fs::file_size(path);
  ASSERT_LT(text, 400 * 1024u);
  // At least tinygltf's own material struct for each: the bound is not loose
  // the wrong way.
  const std::uint64_t charged = parsedJsonBytes(path.string(), fileBytesOf(path));
  EXPECT_GE(charged, 100000 * sizeof(tinygltf::Material));
  LoadOptions options;
  options.maxMemory = 64 * kMiB;
  ASSERT_LT(text + 64 * kMiB / 2, charged);
  expectOver(loadError(path, options), path,
             "the parsed JSON (" + std::to_string(text) + " bytes of text)");

  // The same number of braces inside a string: text, a few hundred KiB.
  const fs::path quoted = writeText("budget_json_string.gltf",
                                    "{" + kAsset + R"(,"extras":{"note":")" + materials + "\"}}");
  EXPECT_LT(parsedJsonBytes(quoted.string(), fileBytesOf(quoted)), 2 * fs::file_size(quoted));
  EXPECT_EQ(loadError(quoted, options).find("memory budget"), std::string::npos);
}

// A buffer file of 64 GiB (sparse: no disk used), more than this machine's
// memory: the default budget refuses it before reading a byte.
TEST(MemoryBudget, AHugeBufferFileIsRefusedBeforeItIsRead) {
  const fs::path bin = tempPath("budget_huge.bin");
  { std::ofstream(bin, std::ios::binary).put('\0'); }
  fs::resize_file(bin, 64 * kGiB);
  const fs::path path = writeText(
      "budget_huge.gltf",
      "{" + kAsset + R"(,"buffers":[{"byteLength":68719476736,"uri":"budget_huge.bin"}]})");
  expectOver(loadError(path, {}), path,
             "file '" + fs::canonical(bin).string() + "' (68719476736 bytes)");
  fs::remove(bin);
}

// Accessors without a bufferView are zeros the loader allocates itself, up to
// 2^28 elements each (3 GiB as VEC3, and 1 GiB more for the indices of a
// draw without them): four meshes of them claim 16 GiB from a file of a few
// hundred bytes. The budget is charged for every primitive before any is
// decoded, so the second is refused and nothing is allocated.
TEST(MemoryBudget, MeshDecodesOverTheDefaultBudgetAreRefusedBeforeAnyIsDecoded) {
  std::string accessors, meshes, nodes;
  for (int i = 0; i < 4; ++i) {
    const std::string sep = i ? "," : "";
    accessors += sep + R"({"componentType":5126,"count":268435456,"type":"VEC3"})";
    meshes += sep + R"({"primitives":[{"attributes":{"POSITION":)" + std::to_string(i) + "}}]}";
    nodes += sep + R"({"mesh":)" + std::to_string(i) + "}";
  }
  const fs::path path =
      writeText("budget_meshes.gltf",
                "{" + kAsset + R"(,"scene":0,"scenes":[{"nodes":[0,1,2,3]}],)" + R"("nodes":[)" +
                    nodes + R"(],"meshes":[)" + meshes + R"(],"accessors":[)" + accessors + "]}");
  const std::string message = loadError(path, {});
  expectOver(message, path, "mesh 1 primitive 0 decoded");
  EXPECT_NE(message.find("needs 4.0 GiB"), std::string::npos) << message;
  EXPECT_NE(message.find("over the memory budget of 8.0 GiB (4.0 GiB already used"),
            std::string::npos)
      << message;
}

// An animation's key times and values, decoded before it is posed: zeros
// without a bufferView (never decreasing, so valid times) claim 2 GiB.
TEST(MemoryBudget, AnimationSamplersAreChargedBeforeTheyAreDecoded) {
  const fs::path path =
      writeText("budget_animation.gltf",
                "{" + kAsset + R"(,"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{}],)" +
                    R"("accessors":[{"componentType":5126,"count":134217728,"type":"SCALAR"},)" +
                    R"({"componentType":5126,"count":134217728,"type":"VEC3"}],)" +
                    R"("animations":[{"samplers":[{"input":0,"output":1}],)" +
                    R"("channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}]}]})");
  LoadOptions options;
  options.maxMemory = 1 * kGiB;
  const std::string message = loadError(path, options);
  expectOver(message, path, "animation 0 sampler 0 decoded");
  EXPECT_NE(message.find("needs 2.0 GiB"), std::string::npos) << message;
}

// A PNG header (signature and IHDR; no pixels follow) that claims width x
// height RGBA8 texels. The CRC is not checked before the size is.
std::string pngHeader(std::uint32_t width, std::uint32_t height) {
  std::string png = "\x89PNG\r\n\x1a\n";
  const auto u32 = [&png](std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) png += char((v >> shift) & 0xFF);
  };
  u32(13);
  png += "IHDR";
  u32(width);
  u32(height);
  png += std::string("\x08\x06\x00\x00\x00", 5);
  u32(0);  // CRC
  return png;
}

// A triangle per image, each textured with its own image (data URIs).
fs::path texturedScene(const std::string& name, const std::vector<std::string>& pngs) {
  std::string images, textures, materials, primitives;
  for (std::size_t i = 0; i < pngs.size(); ++i) {
    const std::string sep = i ? "," : "";
    const std::string n = std::to_string(i);
    images += sep + R"({"uri":"data:image/png;base64,)" + base64(pngs[i]) + "\"}";
    textures += sep + R"({"source":)" + n + "}";
    materials += sep + R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":)" + n + "}}}";
    primitives += sep + R"({"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":)" + n + "}";
  }
  return writeText(name, "{" + kAsset + R"(,"scene":0,"scenes":[{"nodes":[0]}],)" +
                             R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[)" + primitives +
                             R"(]}],"accessors":[{"componentType":5126,"count":3,"type":"VEC3"},)" +
                             R"({"componentType":5126,"count":3,"type":"VEC2"}],)" +
                             R"("images":[)" + images + R"(],"textures":[)" + textures +
                             R"(],"materials":[)" + materials + "]}");
}

// The issue's example: an image of 2^28 texels (16384², 4 GiB decoded) is
// allowed once per scene under the default budget, a second one is refused
// before either is decoded; and a smaller budget refuses the first.
TEST(MemoryBudget, ImagesAreChargedFromTheirHeadersBeforeDecoding) {
  const std::string huge = pngHeader(16384, 16384);
  const fs::path two = texturedScene("budget_two_images.gltf", {huge, huge});
  const std::string message = loadError(two, {});
  expectOver(message, two, "image 1 decoded to 16384x16384 linear float");
  EXPECT_NE(message.find("needs 4.0 GiB"), std::string::npos) << message;

  const fs::path one = texturedScene("budget_one_image.gltf", {pngHeader(8192, 4096)});
  LoadOptions options;
  options.maxMemory = 512 * kMiB;
  expectOver(loadError(one, options), one, "image 0 decoded to 8192x4096 linear float");
  // Within the budget the same header reaches the decoder, which finds no pixels.
  options.maxMemory = 1 * kGiB;
  const std::string decoded = loadError(one, options);
  EXPECT_EQ(decoded.find("memory budget"), std::string::npos) << decoded;
  EXPECT_NE(decoded, "loaded");
}

// ---- rendering ------------------------------------------------------------------------

// A draw list for tileMemoryBytes: one draw, composited in depth order or not.
std::vector<Draw> oneDraw(bool blended) {
  std::vector<Draw> draws(1);
  draws[0].shade.depthOrdered = blended;
  draws[0].shade.depthWrite = !blended;
  return draws;
}

std::uint64_t tileBytes(const RenderSettings& settings, int threads, bool blended) {
  return tileMemoryBytes(TileGrid::forViewport(settings.width, settings.height), settings.samples,
                         threads, 0, 0, oneDraw(blended));
}

// Room for the front end's arrays of the scenes below that have a few
// dozen triangles (what each takes: FrontEndArraysOfAManyTriangleScene...).
constexpr std::uint64_t kSmallFrontEnd = 64 * 1024;

// What a frame of `settings` charges besides its textures, with room for a
// small scene's front end; blended: some draw is composited in depth order
// (its fragments take tile memory).
std::uint64_t frameAndTiles(const RenderSettings& settings, int threads, bool blended) {
  const std::uint64_t pixels = std::uint64_t(settings.width) * std::uint64_t(settings.height);
  return pixels * 5 * sizeof(float) + tileBytes(settings, threads, blended) +  // RGBA and depth
         kSmallFrontEnd;
}

// The scene's textures as a bilinear filter reads them, with room for a
// premultiplied copy of each.
std::uint64_t bilinearTextureBytes(const Scene& scene) {
  std::uint64_t bytes = 0;
  for (const auto& texture : scene.textures)
    bytes += textureViewBytes(*texture, {Filter::Bilinear}) +
             std::uint64_t(texture->image().width) * std::uint64_t(texture->image().height) * 16;
  return bytes;
}

std::string renderError(const Scene& scene, const RenderSettings& settings, Frame& frame) {
  RendererConfig config;
  config.threads = 2;
  Renderer renderer(config);
  try {
    renderer.render(scene, firstCameraOrDefault(scene), settings, frame);
  } catch (const Error& e) {
    return e.what();
  }
  return "rendered";
}

// The mip chain of checker-plane's 512² texture, as the trilinear filter reads
// it: each level in linear float (16 bytes a texel) and again in the storage
// format with its rows one texel longer (padded_level.h).
std::uint64_t mipChainBytes(int width, int height, int storedBytes) {
  std::uint64_t bytes = 0;
  while (width > 1 || height > 1) {
    width = std::max(1, width / 2);
    height = std::max(1, height / 2);
    bytes += std::uint64_t(height) *
             (std::uint64_t(width) * 16 + std::uint64_t(width + 1) * std::uint64_t(storedBytes));
  }
  return bytes;
}

TEST(MemoryBudget, AMipChainThatTipsTheBudgetOverIsRefused) {
  const Scene scene = makeBuiltinScene("checker-plane");
  ASSERT_EQ(scene.textures.size(), 1u);
  const Texture& texture = *scene.textures[0];
  RenderSettings settings;
  settings.width = 64;
  settings.height = 64;
  settings.filter = Filter::Bilinear;
  const std::uint64_t level0 = textureViewBytes(texture, {Filter::Bilinear});
  settings.maxMemory = frameAndTiles(settings, 2, false) + level0;
  Frame frame;
  EXPECT_EQ(renderError(scene, settings, frame), "rendered");

  settings.filter = Filter::Trilinear;
  const std::uint64_t withMips = textureViewBytes(texture, {Filter::Trilinear});
  EXPECT_EQ(withMips - level0, mipChainBytes(texture.image().width, texture.image().height,
                                             bytesPerTexel(texture.storage())));
  // The frame is short by exactly the mip chain: refused, at the texture's
  // charge or (the textures are charged first, and the frame's tile memory
  // may outweigh the chain) at a later one.
  const std::string message = renderError(scene, settings, frame);
  EXPECT_EQ(message.rfind("render: ", 0), 0u) << message;
  EXPECT_NE(message.find(", over the memory budget of "), std::string::npos) << message;
  settings.maxMemory += withMips - level0;
  EXPECT_EQ(renderError(scene, settings, frame), "rendered");
}

// alpha-quads blends five textured quads: at 16 samples its tile memory
// (blended fragments per sample) is what goes over.
TEST(MemoryBudget, TileMemoryAtSixteenSamplesIsRefusedBeforeTheFrameIsAllocated) {
  const Scene scene = makeBuiltinScene("alpha-quads");
  RenderSettings settings;
  settings.width = 1024;
  settings.height = 1024;
  settings.filter = Filter::Bilinear;
  settings.maxMemory = frameAndTiles(settings, 2, true) + bilinearTextureBytes(scene);
  Frame frame;
  EXPECT_EQ(renderError(scene, settings, frame), "rendered");
  settings.samples = 16;
  ASSERT_GT(frameAndTiles(settings, 2, true), settings.maxMemory);
  Frame untouched;
  const std::string message = renderError(scene, settings, untouched);
  EXPECT_EQ(
      message.rfind("render: tile memory (16 samples, 2 threads) needs " +
                        formatBytes(tileBytes(settings, 2, true)) + ", over the memory budget",
                    0),
      0u)
      << message;
  EXPECT_TRUE(untouched.rgba.empty());
  // The largest frame at 16 samples is far over a small budget: refused first.
  settings.width = settings.height = kMaxViewportSize;
  settings.maxMemory = 256 * kMiB;
  EXPECT_EQ(renderError(scene, settings, untouched)
                .rfind("render: the " + std::to_string(kMaxViewportSize) + "x" +
                           std::to_string(kMaxViewportSize) + " frame needs ",
                       0),
            0u);
  EXPECT_TRUE(untouched.rgba.empty());
}

// The front end's arrays (transformed vertices, triangle records and
// their planes, bin entries) grow with the triangle count a file sets, and
// are charged before they are allocated: at least a TriangleRecord a
// triangle, and well under 512 bytes a triangle.
TEST(MemoryBudget, FrontEndArraysOfAManyTriangleSceneAreChargedBeforeTheFrame) {
  const Scene scene = makeBuiltinScene("dense-mesh:200000");
  const std::uint64_t triangles = scene.triangleCount();
  ASSERT_GT(triangles, 150000u);
  std::uint64_t vertices = 0;
  for (const Instance& instance : scene.instances)
    vertices += scene.meshes.at(std::size_t(instance.mesh)).positions.size();
  RenderSettings settings;
  settings.width = 64;
  settings.height = 64;
  settings.filter = Filter::Bilinear;
  const std::uint64_t frame =
      frameAndTiles(settings, 2, false) - kSmallFrontEnd + bilinearTextureBytes(scene);
  settings.maxMemory = frame + triangles * sizeof(TriangleRecord);
  Frame untouched;
  const std::string message = renderError(scene, settings, untouched);
  EXPECT_EQ(message.rfind("render: the front end (" + std::to_string(vertices) + " vertices, " +
                              std::to_string(triangles) + " triangles) needs ",
                          0),
            0u)
      << message;
  EXPECT_TRUE(untouched.rgba.empty());
  settings.maxMemory = frame + triangles * 512;
  Frame frameOut;
  EXPECT_EQ(renderError(scene, settings, frameOut), "rendered");
}

// ---- the command line ------------------------------------------------------------------

TEST(MemoryBudget, TheCliRefusesWithOneLineAndWritesNothing) {
  const fs::path out = tempPath("budget.png");
  const RunResult tiles =
      run("render builtin:alpha-quads --width 2048 --height 2048 --samples 16 --threads 2 "
          "--max-memory 100M --out " +
          out.string());
  EXPECT_EQ(tiles.exitCode, 1);
  expectOneLineError(tiles, "render: tile memory (16 samples, 2 threads) needs ");
  EXPECT_FALSE(fs::exists(out));

  const fs::path scene = texturedScene("budget_cli.gltf", {pngHeader(4096, 4096)});
  const RunResult image =
      run("render " + scene.string() + " --max-memory 64M --out " + out.string());
  EXPECT_EQ(image.exitCode, 1);
  expectOneLineError(image, scene.string() +
                                ": image 0 decoded to 4096x4096 linear float needs "
                                "256.0 MiB, over the memory budget of 64.0 MiB");
  EXPECT_FALSE(fs::exists(out));

  const RunResult syntax =
      run("render builtin:checker-plane --max-memory 4GB2 --out " + out.string());
  EXPECT_EQ(syntax.exitCode, 2);  // the command line's fault
  expectOneLineError(syntax, "--max-memory: '4GB2' is not a size");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace quadra
