// An embedder's program: render the checker plane through the installed API
// and check that the bottom row (the plane, close to the camera) is opaque.
#include <cstdio>

#include "api/renderer.h"
#include "scene/builtin_scenes.h"

int main() {
  const quadra::Scene scene = quadra::makeBuiltinScene("checker-plane");
  quadra::Renderer renderer({.threads = 1});
  quadra::Frame frame;
  renderer.render(scene, scene.cameras.at(0), {.width = 64, .height = 36}, frame);
  const float alpha = frame.rgba[4 * (35 * 64 + 32) + 3];
  std::printf("consumer rendered %dx%d, alpha %g\n", frame.width, frame.height, alpha);
  return alpha == 1.0f ? 0 : 1;
}
