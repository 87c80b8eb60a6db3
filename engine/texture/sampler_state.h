// How a texture is addressed and filtered: the glTF sampler, plus the filter
// the renderer resolves it to for one draw.
#pragma once

#include <cstdint>
#include <string>

namespace quadra {

enum class WrapMode : std::uint8_t { Repeat, MirroredRepeat, ClampToEdge, ClampToBorder };

// The filter a lookup actually runs. Mip-based ones need the texture's MipChain.
enum class Filter : std::uint8_t { Nearest, Bilinear, NearestMip, Trilinear, Anisotropic, Ewa };

inline bool needsMips(Filter f) {
  return f == Filter::NearestMip || f == Filter::Trilinear || f == Filter::Anisotropic ||
         f == Filter::Ewa;
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
// Parses nearest|bilinear|nearest-mip|trilinear|aniso|ewa; false when unknown.
bool parseFilter(const std::string& name, Filter& out);
const char* wrapName(WrapMode w);
bool parseWrap(const std::string& name, WrapMode& out);

}  // namespace quadra
