// An OpenGL 4.5 core context on Mesa's llvmpipe through OSMesa, for the peer
// renderer that quadra is measured against (tools/peer/llvmpipe_main.cpp).
// OSMesa rather than EGL surfaceless: one library (libosmesa6-dev), no display
// or platform to choose, and in Mesa 22.3 it is the same gallium llvmpipe
// driver that EGL would load. The context draws into framebuffer objects of
// its own; OSMesa's window-system buffer is a 1x1 placeholder.
#pragma once

#include <GL/osmesa.h>

#include <cstdint>
#include <string>

namespace quadra {

class OsMesaContext {
 public:
  // llvmpipe reads LP_NUM_THREADS (its rasterizer threads) and GALLIUM_DRIVER
  // when the context is created, so both are set here, before. Throws Error
  // when no 4.5 core context can be made or it is not llvmpipe.
  explicit OsMesaContext(int threads);
  ~OsMesaContext();
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)", and GL_VERSION.
  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }
  // An entry point Mesa does not export by name (glClipControl is one).
  void* procAddress(const char* name) const;

 private:
  OSMesaContext context_ = nullptr;
  std::uint32_t placeholder_ = 0;  // the 1x1 RGBA8 window-system buffer
  std::string renderer_, version_;
};

}  // namespace quadra
