// OpenImageIO's TextureSystem on the report's footprints, so `quadra report
// textures` shows it beside quadra's filters in the same run. OpenImageIO
// lives in a module of its own, quadra_oiio_peer.so (tools/peer/oiio_peer.cpp,
// built where Debian's libopenimageio-dev is installed), which this file
// loads with dlopen only when the report runs: quadra itself never links it,
// so no other command pays for its ~250 shared libraries at start-up.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lab/texture/texture_error.h"
#include "peer/texture_peer_abi.h"
#include "texture/image.h"

namespace quadra {

// The module's file name, in the build tree beside quadra.
inline constexpr const char* kOiioPeerFile = "quadra_oiio_peer.so";

// A loaded peer module; it stays loaded until the process exits (unloading
// OpenImageIO under its own worker threads and exit handlers is not safe).
struct OiioPeer {
  std::filesystem::path file;
  const QuadraTexturePeer* table = nullptr;
};

// Loads `file`, or when it is empty the first module found: beside this
// quadra (the build tree), then in the install's lib/quadra folder. nullopt,
// with the reason in one line in `whyNot`, when there is none or it cannot
// be loaded (dlopen fails, no entry point, another ABI version).
std::optional<OiioPeer> loadOiioPeer(const std::string& file, std::string& whyNot);

// One texture as the peer sees it: written with make_texture (tiled 64x64,
// float, box-filtered mip levels, periodic wrap) to `scratchFile`, which is
// removed again on destruction, and read through a private TextureSystem.
class OiioTexture {
 public:
  OiioTexture(const OiioPeer& peer, const Image& image, const std::filesystem::path& scratchFile,
              int maxAniso);
  ~OiioTexture();
  OiioTexture(const OiioTexture&) = delete;
  OiioTexture& operator=(const OiioTexture&) = delete;

  // The report's names for lookups(), in its order: "oiio-trilinear" and
  // "oiio-aniso-N".
  static std::vector<std::string> labels(int maxAniso);
  // Trilinear and anisotropic lookups: bilinear interpolation, periodic wrap,
  // one TextureSystem::texture call per lookup, a call into the module per
  // batch.
  std::vector<BatchLookup> lookups() const;

 private:
  const QuadraTexturePeer* table_;
  QuadraPeerTexture* texture_;
};

}  // namespace quadra
