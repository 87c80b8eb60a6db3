// Test helpers shared by the rendering tests: one frame through a fresh
// Renderer, the one call every test otherwise spells out; the kernel paths
// this CPU can run; a frame as an Image.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "api/renderer.h"
#include "texture/image.h"

namespace quadra {

// Scalar first, then every SIMD path the CPU has.
inline std::vector<Isa> supportedIsas() {
  std::vector<Isa> isas;
  for (Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512})
    if (isaSupported(isa)) isas.push_back(isa);
  return isas;
}

// A scene of one double-sided mesh (material 0) placed once, as the tests
// that build their triangles by hand draw them.
inline Scene doubleSidedMeshScene(Mesh mesh) {
  Scene scene;
  mesh.material = 0;
  Material material;
  material.doubleSided = true;
  scene.materials.push_back(material);
  scene.meshes.push_back(std::move(mesh));
  scene.instances.push_back(Instance{});
  return scene;
}

// A frame's colour as an Image (premultiplied linear RGBA), for
// imageDifference against a reference.
inline Image frameImage(const Frame& frame) {
  Image image;
  image.width = frame.width;
  image.height = frame.height;
  image.rgba = frame.rgba;
  return image;
}

inline Frame renderOnce(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        int threads = 2, std::optional<Isa> isa = std::nullopt,
                        FrameStats* stats = nullptr) {
  RendererConfig config;
  config.threads = threads;
  config.isa = isa;
  Renderer renderer(config);
  Frame frame;
  const FrameStats s = renderer.render(scene, camera, settings, frame);
  if (stats) *stats = s;
  return frame;
}

}  // namespace quadra
