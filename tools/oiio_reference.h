// OpenImageIO's TextureSystem on the report's footprints, so `quadra report
// textures` shows it beside quadra's filters in the same run. Built only when
// Debian's libopenimageio-dev is found (tools/CMakeLists.txt defines
// QUADRA_HAVE_OIIO); the report says so when it is not.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "lab/texture/texture_error.h"
#include "texture/image.h"

namespace quadra {

// The OpenImageIO version quadra was built against, e.g. "2.4.7".
std::string oiioVersion();

// One texture as OIIO sees it: written with make_texture (tiled 64x64, float,
// box-filtered mip levels, periodic wrap) to `scratchFile`, which is removed
// again on destruction, and read through a private TextureSystem.
class OiioTexture {
 public:
  OiioTexture(const Image& image, const std::filesystem::path& scratchFile, int maxAniso);
  ~OiioTexture();
  OiioTexture(const OiioTexture&) = delete;
  OiioTexture& operator=(const OiioTexture&) = delete;

  // The report's names for lookups(), in its order: "oiio-trilinear" and
  // "oiio-aniso-N".
  static std::vector<std::string> labels(int maxAniso);
  // Trilinear and anisotropic lookups: bilinear interpolation, periodic wrap,
  // one TextureSystem::texture call per lookup (OIIO's batched call loops per
  // lookup and measured no faster).
  std::vector<BatchLookup> lookups() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace quadra
