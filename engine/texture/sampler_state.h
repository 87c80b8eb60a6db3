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
// Ripmap: bilinear on the levels prefiltered to the footprint's extent along u
// and along v, blended between the 4 nearest (texture/ripmap.h).
// SummedArea: the exact average of the bilinear reconstruction over the
// footprint's axis-aligned bounding box, from a summed-area table
// (texture/summed_area.h).
enum class Filter : std::uint8_t {
  Nearest,
  Bilinear,
  NearestMip,
  Trilinear,
  Anisotropic,
  Ewa,
  Area,
  SummedArea,
  Ripmap
};

// Every filter, in the order reports list them.
inline constexpr Filter kEveryFilter[] = {
    Filter::Nearest, Filter::Bilinear, Filter::NearestMip, Filter::Trilinear, Filter::Anisotropic,
    Filter::Ewa,     Filter::Area,     Filter::SummedArea, Filter::Ripmap};

inline bool needsMips(Filter f) {
  return f == Filter::NearestMip || f == Filter::Trilinear || f == Filter::Anisotropic ||
         f == Filter::Ewa || f == Filter::Area;
}

// Where a lookup's footprint (the screen derivatives of u, v) comes from:
// the exact derivatives of the triangle's attribute planes at the pixel
// centre (by the quotient rule on a/w and 1/w), or differences across the
// 2x2 quad from its top-left pixel, helper lanes included, as GPUs take them
// (for output that matches a GPU's).
enum class DerivativeMode : std::uint8_t { Analytic, Quad };

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
// Parses nearest|bilinear|nearest-mip|trilinear|aniso|ewa|area|sat|ripmap; false when unknown.
bool parseFilter(const std::string& name, Filter& out);
// The canonical filter names, comma separated, for error messages.
std::string filterNames();
const char* wrapName(WrapMode w);
bool parseWrap(const std::string& name, WrapMode& out);

}  // namespace quadra
