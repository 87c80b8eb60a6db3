// How far apart two images of one frame are: PSNR and the largest
// difference over R, G and B, for comparing quadra's frames with another
// renderer's (`quadra report frames`) or with each other.
#pragma once

#include <cstdint>
#include <vector>

#include "texture/image.h"

namespace quadra {

struct ImageDifference {
  double psnr = 0.0;    // dB against a peak of 1 (linear white); infinite when equal
  double maxAbs = 0.0;  // the largest |a - b| of any R, G or B value
};

// Both images must have the same size (an Error otherwise); alpha is left out.
// Both figures are NaN when either image has a NaN in R, G or B.
ImageDifference imageDifference(const Image& a, const Image& b);
// The same over the pixels whose entry in `pixels` (row-major, one per pixel)
// is not 0, e.g. a frame's interior (lab/reference ReferenceTracer::interiorMask);
// an infinite PSNR when none is.
ImageDifference imageDifference(const Image& a, const Image& b,
                                const std::vector<std::uint8_t>& pixels);

}  // namespace quadra
