// Loading quadra_oiio_peer.so and calling it through its C table
// (oiio_reference.h, peer/texture_peer_abi.h).
#include "oiio_reference.h"

#include <dlfcn.h>

#include <array>

#include "core/error.h"
#include "subprocess.h"

namespace quadra {

namespace {

std::optional<OiioPeer> openPeer(const std::filesystem::path& file, std::string& whyNot) {
  // RTLD_LOCAL: OpenImageIO's symbols stay out of quadra's namespace;
  // RTLD_NOW: a missing dependency fails here, not in the middle of the report.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    whyNot = dlerror();
    return std::nullopt;
  }
  const auto entry =
      reinterpret_cast<QuadraTexturePeerEntry>(dlsym(handle, QUADRA_TEXTURE_PEER_ENTRY));
  const QuadraTexturePeer* table = entry ? entry() : nullptr;
  if (!table) {
    whyNot = file.string() + ": no " + QUADRA_TEXTURE_PEER_ENTRY + " entry point";
  } else if (table->abi != QUADRA_TEXTURE_PEER_ABI) {
    whyNot = file.string() + ": built for peer ABI " + std::to_string(table->abi) +
             ", this quadra takes " + std::to_string(QUADRA_TEXTURE_PEER_ABI);
  } else {
    return OiioPeer{file, table};
  }
  dlclose(handle);  // nothing of it ran but the entry point
  return std::nullopt;
}

}  // namespace

std::optional<OiioPeer> loadOiioPeer(const std::string& file, std::string& whyNot) {
  if (!file.empty()) return openPeer(file, whyNot);
  const std::filesystem::path bin = executablePath().parent_path();
  const std::array<std::filesystem::path, 2> places = {
      bin / kOiioPeerFile, (bin / QUADRA_OIIO_PEER_INSTALL_DIR / kOiioPeerFile).lexically_normal()};
  for (const std::filesystem::path& place : places) {
    std::error_code ec;
    if (std::filesystem::exists(place, ec)) return openPeer(place, whyNot);
  }
  whyNot = std::string(kOiioPeerFile) + " is neither beside this quadra nor in " +
           places[1].parent_path().string() +
           " (it is built where libopenimageio-dev is installed, by scripts/test.sh or `cmake "
           "--build build --target quadra_oiio_peer`)";
  return std::nullopt;
}

OiioTexture::OiioTexture(const OiioPeer& peer, const Image& image,
                         const std::filesystem::path& scratchFile, int maxAniso)
    : table_(peer.table) {
  std::array<char, 1024> error{};
  texture_ = table_->create(image.width, image.height, image.rgba.data(), scratchFile.c_str(),
                            maxAniso, error.data(), error.size());
  if (!texture_) throw Error(error.data());
}

OiioTexture::~OiioTexture() {
  table_->destroy(texture_);
}

std::vector<std::string> OiioTexture::labels(int maxAniso) {
  return {"oiio-trilinear", "oiio-aniso-" + std::to_string(maxAniso)};
}

std::vector<BatchLookup> OiioTexture::lookups() const {
  const auto make = [this](int mode) -> BatchLookup {
    return [this, mode](const LookupBatch& batch, std::size_t begin, std::size_t end, float* rgba) {
      table_->lookup(texture_, mode, end - begin, batch.u + begin, batch.v + begin,
                     batch.dudx + begin, batch.dvdx + begin, batch.dudy + begin, batch.dvdy + begin,
                     rgba + 4 * begin);
    };
  };
  return {make(QUADRA_PEER_TRILINEAR), make(QUADRA_PEER_ANISOTROPIC)};
}

}  // namespace quadra
