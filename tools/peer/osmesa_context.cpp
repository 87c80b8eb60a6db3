// Creating the llvmpipe context (see osmesa_context.h).
#include "osmesa_context.h"

#include <cstdlib>
#include <string>

#include "core/error.h"

namespace quadra {

OsMesaContext::OsMesaContext(int threads) {
  ::setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
  ::setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            4,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            5,
                            0};
  context_ = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!context_) throw Error("OSMesa: cannot create an OpenGL 4.5 core context");
  if (!OSMesaMakeCurrent(context_, &placeholder_, GL_UNSIGNED_BYTE, 1, 1)) {
    OSMesaDestroyContext(context_);
    throw Error("OSMesa: cannot make the context current");
  }
  const auto text = [](GLenum name) {
    const GLubyte* value = glGetString(name);
    return value ? std::string(reinterpret_cast<const char*>(value)) : std::string();
  };
  renderer_ = text(GL_RENDERER);
  version_ = text(GL_VERSION);
  if (renderer_.rfind("llvmpipe", 0) != 0) {
    OSMesaDestroyContext(context_);
    throw Error("OSMesa: the context renders with '" + renderer_ + "', not llvmpipe");
  }
}

OsMesaContext::~OsMesaContext() {
  OSMesaDestroyContext(context_);
}

void* OsMesaContext::procAddress(const char* name) const {
  return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
}

}  // namespace quadra
