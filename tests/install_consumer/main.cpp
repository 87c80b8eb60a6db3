// An embedder's program, built against the installed package only (the
// public header quadra/quadra.hpp): one vertex-coloured quad built from its
// own arrays, rendered into its own padded float buffer and depth buffer.
//   consumer gltf DIR        write the same quad as DIR/quad.gltf + quad.bin,
//                            for the quadra CLI to render
//   consumer render OUT.raw  render it; write the pixels and depths, tightly
//                            packed, for read_reference to compare
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <quadra/quadra.hpp>

namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;

const float kPositions[] = {-0.7f, -0.6f, 0, 0.8f, -0.7f, 0, 0.6f, 0.7f, 0, -0.8f, 0.5f, 0};
const float kColors[] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 0.5f};
const std::uint16_t kIndices[] = {0, 1, 2, 0, 2, 3};

void writeGltf(const std::string& dir) {
  std::ofstream bin(dir + "/quad.bin", std::ios::binary);
  bin.write(reinterpret_cast<const char*>(kPositions), sizeof(kPositions));
  bin.write(reinterpret_cast<const char*>(kColors), sizeof(kColors));
  bin.write(reinterpret_cast<const char*>(kIndices), sizeof(kIndices));
  std::ofstream gltf(dir + "/quad.gltf");
  gltf << R"({"asset": {"version": "2.0"}, "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 1]}],
  "cameras": [{"type": "orthographic",
               "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.5, "zfar": 2}}],
  "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 1, 1]},
                 "doubleSided": true}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "COLOR_0": 1},
                              "indices": 2, "material": 0}]}],
  "buffers": [{"uri": "quad.bin", "byteLength": )"
       << sizeof(kPositions) + sizeof(kColors) + sizeof(kIndices) << R"(}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 64},
                  {"buffer": 0, "byteOffset": 112, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "min": [-0.8, -0.7, 0], "max": [0.8, 0.7, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC4"},
                {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]}
)";
}

int render(const std::string& outPath) {
  namespace api = quadra::api;
  api::Scene scene;
  const auto mesh =
      scene.addMesh({.positions = kPositions, .colors = kColors, .indices16 = kIndices});
  const auto material =
      scene.addMaterial({.baseColor = {0.9f, 0.8f, 1.0f, 1.0f}, .doubleSided = true});
  scene.addInstance(mesh, material);
  api::Matrix4 cameraWorld = api::kIdentity;
  cameraWorld[14] = 1.0f;  // at z = 1, as the glTF camera node's translation
  scene.setCamera({.projection = api::CameraData::Projection::Orthographic,
                   .ymag = 1.0f,
                   .znear = 0.5f,
                   .zfar = 2.0f,
                   .world = cameraWorld});

  // The embedder's own memory: rows padded to 1 KiB, depth rows to 300 bytes.
  const std::size_t stride = 1024, depthStride = 300;
  std::vector<float> pixels(stride / 4 * kHeight), depth(depthStride / 4 * kHeight);
  api::Renderer renderer({.threads = 2});
  const api::DepthTarget depthTarget{.bytes = std::as_writable_bytes(std::span(depth)),
                                     .rowStride = depthStride};
  renderer.render(scene,
                  {.pixels = std::as_writable_bytes(std::span(pixels)),
                   .width = kWidth,
                   .height = kHeight,
                   .rowStride = stride,
                   .format = api::PixelFormat::Rgba32F},
                  &depthTarget);
  std::ofstream out(outPath, std::ios::binary);
  for (int y = 0; y < kHeight; ++y)
    out.write(reinterpret_cast<const char*>(&pixels[y * stride / 4]), kWidth * 16);
  for (int y = 0; y < kHeight; ++y)
    out.write(reinterpret_cast<const char*>(&depth[y * depthStride / 4]), kWidth * 4);
  std::printf("consumer: quadra %s (headers %s), rendered %dx%d\n", quadra::version(),
              QUADRA_VERSION_STRING, kWidth, kHeight);
  return std::strcmp(quadra::version(), QUADRA_VERSION_STRING) == 0 && out ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc == 3 ? argv[1] : "";
  try {
    if (mode == "gltf") return writeGltf(argv[2]), 0;
    if (mode == "render") return render(argv[2]);
    std::fprintf(stderr, "usage: consumer gltf DIR | consumer render OUT.raw\n");
    return 1;
  } catch (const quadra::api::Error& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
