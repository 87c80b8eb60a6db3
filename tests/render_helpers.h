// Test helpers shared by the rendering tests: one frame through a fresh
// Renderer, the one call every test otherwise spells out.
#pragma once

#include <optional>

#include "api/renderer.h"

namespace quadra {

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
