// Test helpers shared by the rendering tests: one frame through a fresh
// Renderer, the one call every test otherwise spells out, and the kernel
// paths this CPU can run.
#pragma once

#include <optional>
#include <vector>

#include "api/renderer.h"

namespace quadra {

// Scalar first, then every SIMD path the CPU has.
inline std::vector<Isa> supportedIsas() {
  std::vector<Isa> isas;
  for (Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512})
    if (isaSupported(isa)) isas.push_back(isa);
  return isas;
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
