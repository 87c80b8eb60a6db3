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
  // Within a mip level when minified, for NearestMip and Trilinear: bilinear,
  // or the nearest texel (glTF's and GL's NEAREST_MIPMAP_NEAREST and
  // NEAREST_MIPMAP_LINEAR: the nearest texel of the nearest level, or of the
  // two nearest levels blended).
  bool minLinear = true;
  float borderColor[4] = {0.0f, 0.0f, 0.0f, 0.0f};
};

const char* filterName(Filter f);
// Parses nearest|bilinear|nearest-mip|trilinear|aniso|ewa|area|sat|ripmap; false when unknown.
bool parseFilter(const std::string& name, Filter& out);
// The canonical filter names, comma separated, for error messages.
std::string filterNames();
const char* wrapName(WrapMode w);
bool parseWrap(const std::string& name, WrapMode& out);

// How trilinear filtering chooses its level λ from the footprint's longer
// side ρ (level-0 texels per pixel):
// - Box (default): λ = log2(ρ) + kBoxLodOffset, nearer the level whose
//   prefilter matches the pixel's own box footprint, which quadra's ideal
//   image averages (the area filter; lab/texture/ground_truth.h);
// - Gl: λ = log2(ρ), as OpenGL and GPUs define it, for GPU-matching output.
// At GL's λ a level's texel (2^λ wide) and the bilinear tent add 4^λ/4 of
// variance per axis where the pixel's box has ρ²/12, so trilinear frames come
// out blurrier than the box ideal (an offset of -0.79 would match the two;
// aliasing and anisotropic footprints want less). Frames against the area
// filter's, 1920x1080, PSNR by offset 0 / -0.2 / -0.3 / -0.6: checker-plane
// 25.97 / 26.77 / 27.09 / 27.55 dB, dense-mesh 43.42 / 44.56 / 45.00 / 45.65,
// WaterBottle 59.24 / 61.18 / 62.02 (Mesa's llvmpipe, GL's λ with its own
// rounding: 26.08, 43.60, 59.35). Against the box ground truth per lookup
// (`quadra report textures`, 2048 lookups per texture) trilinear's RMSE
// goes 0.0403 / 0.0385 / 0.0381 / 0.0391, every texture's and scale
// bucket's at or below GL's at -0.2 but for footprints under 2:1 (0.0249 ->
// 0.0264): -0.2 is the largest offset that costs the checker texture
// nothing (0.0494 -> 0.0493; 0.0501 at -0.3). Nearest-mip keeps GL's λ: its
// rounding to a level leaves it worse on the checker at any offset.
enum class LodRule { Box, Gl };
constexpr float kBoxLodOffset = -0.2f;

}  // namespace quadra
