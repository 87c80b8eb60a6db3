// Scoring a lit frame as ../shared/LIGHTING.md "Output" says: both images
// times 2^exposure, tone-mapped by Khronos PBR Neutral and sRGB-encoded, in
// [0, 1], then PSNR over all pixels and over interior pixels. In double, apart
// from the engine's tone map (engine/shading), so that it checks it.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "lab/image/image_difference.h"
#include "texture/image.h"

namespace quadra {

// Khronos PBR Neutral (KhronosGroup/ToneMapping, PBR_Neutral): linear Rec. 709
// in (negative components taken as 0), linear [0, 1] out.
glm::dvec3 pbrNeutral(const glm::dvec3& linear);
// The sRGB transfer function (IEC 61966-2-1, the piecewise curve) on [0, 1].
double srgbEncode(double linear);

// Each pixel's RGB (premultiplied, so as over black) x 2^exposure through
// pbrNeutral and srgbEncode; alpha kept.
Image toneMappedSrgb(const Image& linear, double exposure = 0.0);

struct LitScore {
  ImageDifference all, interior;
  std::size_t interiorPixels = 0;
};
// frame against ideal, both linear; interior: one entry per pixel (LitFrame::interior).
LitScore scoreLitFrame(const Image& frame, const Image& ideal,
                       const std::vector<std::uint8_t>& interior, double exposure = 0.0);

}  // namespace quadra
