// An embedder's program, built against the installed package only: it builds
// a scene in code (one quad filling an orthographic view, textured with a 2x2
// image of four colours, nearest filtering), renders it, writes and reads back
// an EXR, and checks every pixel against the texel it must show.
#include <cstdio>
#include <memory>
#include <string>

#include "api/camera.h"
#include "api/renderer.h"
#include "core/error.h"
#include "io/image_io.h"
#include "scene/scene.h"

namespace {

quadra::Scene quadScene() {
  quadra::Scene scene;
  scene.name = "consumer-quad";
  auto image = std::make_shared<quadra::Image>(2, 2);
  const float colors[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
  for (int t = 0; t < 4; ++t)
    for (int c = 0; c < 4; ++c) image->texel(t % 2, t / 2)[c] = colors[t][c];
  quadra::SamplerState sampler;
  sampler.magLinear = false;
  sampler.minFilter = quadra::Filter::Nearest;
  scene.textures.push_back(std::make_shared<const quadra::Texture>(image, sampler));

  quadra::Material material;
  material.baseColorTexture = 0;
  scene.materials.push_back(material);

  quadra::Mesh quad;  // counter-clockwise seen from +Z; v = 0 at the top (glTF)
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.texcoords[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = 0;
  scene.meshes.push_back(quad);
  scene.instances.push_back({0, glm::mat4(1.0f)});

  quadra::Camera camera;
  camera.type = quadra::Camera::Type::Orthographic;
  camera.xmag = camera.ymag = 1.0f;
  camera.znear = 0.5f;
  camera.zfar = 2.0f;
  camera.world = quadra::lookAtWorld({0, 0, 1}, {0, 0, 0}, {0, 1, 0});
  scene.cameras.push_back(camera);
  return scene;
}

int check(const quadra::Frame& frame, const char* what) {
  int wrong = 0;
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      const int texel = (y * 2 / frame.height) * 2 + x * 2 / frame.width;
      const float expected[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
      for (int c = 0; c < 4; ++c)
        wrong += frame.rgba[(std::size_t(y) * frame.width + x) * 4 + c] != expected[texel][c];
    }
  std::printf("consumer: %s %dx%d, %d wrong values\n", what, frame.width, frame.height, wrong);
  return wrong;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string exrPath = argc > 1 ? argv[1] : "consumer.exr";
  try {
    const quadra::Scene scene = quadScene();
    quadra::Renderer renderer({.threads = 2});
    quadra::Frame frame;
    renderer.render(scene, scene.cameras.at(0), {.width = 64, .height = 64}, frame);
    int wrong = check(frame, "rendered");
    quadra::writeFrame(frame, exrPath);
    const quadra::Image read = quadra::readImage(exrPath);
    quadra::Frame reread{read.width, read.height, read.rgba, {}};
    wrong += check(reread, "read back");
    return wrong == 0 ? 0 : 1;
  } catch (const quadra::Error& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
