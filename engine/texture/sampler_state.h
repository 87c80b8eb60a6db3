// How a texture is addressed and filtered: the glTF sampler, plus the filter
// the renderer resolves it to for one draw.
#pragma once

#include <cstdint>
#include <string>

namespace quadra {

enum class WrapMode : std::uint8_t { Repeat, MirroredRepeat, ClampToEdge, ClampToBorder };

// The filter a lookup actually runs. Mip-based ones need the texture's MipChain.
// Area: the bilinear reconstruction averaged over the pixel's footprint
// parallelogram on a midpoint grid, on the finest level whose grid fits the
// sample budget (sample_lanes.h sampleArea): the offline-quality filter.
enum class Filter : std::uint8_t {
  Nearest,
  Bilinear,
  NearestMip,
  Trilinear,
  Anisotropic,
  Ewa,
  Area
};

inline bool needsMips(Filter f) {
  return f == Filter::NearestMip || f == Filter::Trilinear || f == Filter::Anisotropic ||
         f == Filter::Ewa || f == Filter::Area;
}

// glTF sampler state (the minification filter decides mip use; magnification
// is nearest or linear).
struct SamplerState {
  WrapMode wrapU = WrapMode::Repeat;
  WrapMode wrapV = WrapMode::Repeat;
  bool magLinear = true;
  Filter minFilter = Filter::Trilinear;  // default when glTF leaves it unset
  float borderColor[4] = {0.0f, 0.0f, 0.0f, 0.0f};
};

const char* filterName(Filter f);
// Parses nearest|bilinear|nearest-mip|trilinear|aniso|ewa|area; false when unknown.
bool parseFilter(const std::string& name, Filter& out);
const char* wrapName(WrapMode w);
bool parseWrap(const std::string& name, WrapMode& out);

}  // namespace quadra
