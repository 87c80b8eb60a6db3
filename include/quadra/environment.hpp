// quadra::api::Environment: the light of Shading::Pbr, an equirectangular
// panorama of linear RGB radiance, made from the embedder's own float array,
// a built-in or a panorama file (the CLI's --env) and checked by the CLI's
// rules (docs/lighting.md "Environments").
//
// Ownership: an Environment is an immutable value that shares its texels
// among its copies; RenderOptions refers to one by holding a copy. A
// Renderer prepares an environment on the first frame that lights with it
// and keeps that preparation while later frames ask for the same one (a
// copy of it counts: the texels are shared), so keep one Environment for a
// run of frames instead of making it afresh for each.
// Thread safety: an Environment may be read by several renderers at once.
// Errors: quadra::api::Error with a one-line message naming the source.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "quadra/error.hpp"
#include "quadra/export.h"
#include "quadra/scene.hpp"

namespace quadra::api {

namespace detail {
struct EnvironmentAccess;
}

class QUADRA_API Environment {
 public:
  // width x height texels of R, G, B floats (rgb.size() must be width x
  // height x 3), row 0 the top (+Y), in ../shared/LIGHTING.md's convention:
  // the centre column faces -Z. Copied. At least 2 texels and at most
  // 2^28; the texel rule then makes it safe to light with: NaN and negative
  // values become 0, values above 2^32 (+inf included) become 2^32.
  static Environment fromTexels(std::span<const float> rgb, int width, int height);
  // The CLI's --env: "builtin:NAME" (studio, sky, white) or a Radiance .hdr
  // or OpenEXR file, decoded with its allocations charged to maxMemory, then
  // put through the same size check and texel rule.
  static Environment load(const std::string& source, std::uint64_t maxMemory = kDefaultMaxMemory);

  int width() const;
  int height() const;
  // The source for messages: the file path, builtin:NAME, or "texels".
  const std::string& name() const;
  // The texels as quadra lights with them (the texel rule applied), laid
  // out as fromTexels takes them.
  std::span<const float> texels() const;
  // How many values (channels, not texels) the texel rule changed.
  std::uint64_t repairedValues() const;

 private:
  friend struct detail::EnvironmentAccess;
  struct Impl;
  explicit Environment(std::shared_ptr<const Impl> impl);
  std::shared_ptr<const Impl> impl_;
};

}  // namespace quadra::api
