// The README's API example: a vertex-coloured triangle built from arrays,
// rendered into the program's own 8-bit sRGB buffer; prints its centre pixel.
#include <cstdint>
#include <cstdio>
#include <span>
#include <vector>

#include <quadra/quadra.hpp>

int main() {
  namespace api = quadra::api;
  const float positions[] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
  const float colors[] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1};  // linear RGBA per vertex
  const std::uint32_t indices[] = {0, 1, 2};
  api::Scene scene;
  auto mesh = scene.addMesh({.positions = positions, .colors = colors, .indices32 = indices});
  auto material = scene.addMaterial({.baseColor = {1, 1, 1, 1}});
  scene.addInstance(mesh, material);  // identity transform
  scene.setCamera({.world = api::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0})});

  std::vector<std::uint8_t> pixels(640 * 360 * 4);  // the program's own buffer
  api::Renderer renderer({.threads = 2});
  try {
    renderer.render(scene, {.pixels = std::as_writable_bytes(std::span(pixels)),
                            .width = 640,
                            .height = 360,
                            .rowStride = 640 * 4,
                            .format = api::PixelFormat::Rgba8Srgb});
  } catch (const api::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());  // one line
    return 1;
  }
  const std::uint8_t* centre = &pixels[(180 * 640 + 320) * 4];
  std::printf("quadra %s: centre pixel %d %d %d %d\n", quadra::version(), centre[0], centre[1],
              centre[2], centre[3]);
  return centre[3] == 255 ? 0 : 1;
}
