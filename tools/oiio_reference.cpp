// OpenImageIO's TextureSystem as the report's outside reference (oiio_reference.h).
#include "oiio_reference.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>

#include "core/error.h"

namespace quadra {

std::string oiioVersion() {
  return OIIO_VERSION_STRING;
}

struct OiioTexture::State {
  std::filesystem::path file;
  OIIO::TextureSystem* system = nullptr;
  OIIO::TextureSystem::TextureHandle* handle = nullptr;
  int maxAniso = 16;
};

OiioTexture::OiioTexture(const Image& image, const std::filesystem::path& scratchFile, int maxAniso)
    : state_(std::make_unique<State>()) {
  state_->file = scratchFile;
  state_->maxAniso = maxAniso;
  const OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
  const OIIO::ImageBuf source(spec, const_cast<float*>(image.rgba.data()));
  OIIO::ImageSpec config;
  config.tile_width = config.tile_height = 64;
  config.format = OIIO::TypeDesc::FLOAT;
  config.attribute("wrapmodes", "periodic,periodic");
  config.attribute("maketx:filtername", "box");
  if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, source,
                                        scratchFile.string(), config))
    throw Error(scratchFile.string() + ": OpenImageIO make_texture failed: " + OIIO::geterror());
  state_->system = OIIO::TextureSystem::create(false);
  state_->system->attribute("max_memory_MB", 4096.0f);
  state_->handle = state_->system->get_texture_handle(OIIO::ustring(scratchFile.string()));
  if (!state_->handle) throw Error(scratchFile.string() + ": OpenImageIO cannot open it");
}

OiioTexture::~OiioTexture() {
  if (state_->system) OIIO::TextureSystem::destroy(state_->system);
  std::error_code ignored;
  std::filesystem::remove(state_->file, ignored);
}

std::vector<std::string> OiioTexture::labels(int maxAniso) {
  return {"oiio-trilinear", "oiio-aniso-" + std::to_string(maxAniso)};
}

std::vector<BatchLookup> OiioTexture::lookups() const {
  const auto make = [this](OIIO::TextureOpt::MipMode mode) -> BatchLookup {
    return [this, mode](const LookupBatch& batch, std::size_t begin, std::size_t end, float* rgba) {
      OIIO::TextureOpt options;
      options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
      options.interpmode = OIIO::TextureOpt::InterpBilinear;
      options.mipmode = mode;
      options.anisotropic = state_->maxAniso;
      OIIO::TextureSystem::Perthread* thread = state_->system->get_perthread_info();
      for (std::size_t i = begin; i < end; ++i)
        state_->system->texture(state_->handle, thread, options, batch.u[i], batch.v[i],
                                batch.dudx[i], batch.dvdx[i], batch.dudy[i], batch.dvdy[i], 4,
                                rgba + 4 * i);
    };
  };
  return {make(OIIO::TextureOpt::MipModeTrilinear), make(OIIO::TextureOpt::MipModeAniso)};
}

}  // namespace quadra
