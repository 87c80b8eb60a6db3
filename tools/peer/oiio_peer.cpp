// quadra_oiio_peer.so: OpenImageIO's TextureSystem behind the C table of
// texture_peer_abi.h, loaded by `quadra report textures` (tools/oiio_reference.cpp)
// so that quadra's binary never links OpenImageIO. Nothing of quadra's is
// linked in: the texture arrives as raw floats, footprints as float arrays.
// Exceptions stop here; the table's functions report failure in C terms.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>

#include "texture_peer_abi.h"

struct QuadraPeerTexture {
  std::filesystem::path file;
  OIIO::TextureSystem* system = nullptr;
  OIIO::TextureSystem::TextureHandle* handle = nullptr;
  int maxAniso = 16;

  ~QuadraPeerTexture() {
    if (system) OIIO::TextureSystem::destroy(system);
    std::error_code ignored;
    std::filesystem::remove(file, ignored);
  }
};

namespace {

void setError(char* error, size_t errorSize, const std::string& message) {
  if (error && errorSize > 0) std::snprintf(error, errorSize, "%s", message.c_str());
}

// The texture written with make_texture (tiled 64x64, float, box-filtered mip
// levels, periodic wrap) to scratchFile and read through a private
// TextureSystem, so no other user's cache settings or files interfere.
QuadraPeerTexture* create(int width, int height, const float* rgba, const char* scratchFile,
                          int maxAniso, char* error, size_t errorSize) {
  try {
    auto texture = std::make_unique<QuadraPeerTexture>();
    texture->file = scratchFile;
    texture->maxAniso = maxAniso;
    const OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::FLOAT);
    const OIIO::ImageBuf source(spec, const_cast<float*>(rgba));
    OIIO::ImageSpec config;
    config.tile_width = config.tile_height = 64;
    config.format = OIIO::TypeDesc::FLOAT;
    config.attribute("wrapmodes", "periodic,periodic");
    config.attribute("maketx:filtername", "box");
    if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, source, scratchFile,
                                          config)) {
      setError(error, errorSize,
               std::string(scratchFile) + ": OpenImageIO make_texture failed: " + OIIO::geterror());
      return nullptr;
    }
    texture->system = OIIO::TextureSystem::create(false);
    texture->system->attribute("max_memory_MB", 4096.0f);
    texture->handle = texture->system->get_texture_handle(OIIO::ustring(scratchFile));
    if (!texture->handle) {
      setError(error, errorSize, std::string(scratchFile) + ": OpenImageIO cannot open it");
      return nullptr;
    }
    return texture.release();
  } catch (const std::exception& e) {
    setError(error, errorSize, std::string(scratchFile) + ": OpenImageIO: " + e.what());
    return nullptr;
  }
}

// Bilinear interpolation, periodic wrap, one TextureSystem::texture call per
// lookup (OIIO's batched call loops per lookup and measured no faster).
void lookup(const QuadraPeerTexture* texture, int mode, size_t count, const float* u,
            const float* v, const float* dudx, const float* dvdx, const float* dudy,
            const float* dvdy, float* rgba) {
  OIIO::TextureOpt options;
  options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
  options.interpmode = OIIO::TextureOpt::InterpBilinear;
  options.mipmode = mode == QUADRA_PEER_ANISOTROPIC ? OIIO::TextureOpt::MipModeAniso
                                                    : OIIO::TextureOpt::MipModeTrilinear;
  options.anisotropic = texture->maxAniso;
  OIIO::TextureSystem::Perthread* thread = texture->system->get_perthread_info();
  for (size_t i = 0; i < count; ++i)
    texture->system->texture(texture->handle, thread, options, u[i], v[i], dudx[i], dvdx[i],
                             dudy[i], dvdy[i], 4, rgba + 4 * i);
}

void destroy(QuadraPeerTexture* texture) {
  delete texture;
}

const QuadraTexturePeer kPeer = {
    QUADRA_TEXTURE_PEER_ABI, "OpenImageIO", OIIO_VERSION_STRING, create, lookup, destroy};

}  // namespace

// The module's only exported symbol (it is built with hidden visibility).
extern "C" __attribute__((visibility("default"))) const QuadraTexturePeer* quadra_texture_peer() {
  return &kPeer;
}
