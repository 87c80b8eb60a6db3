// PSNR and max difference over R, G, B (see image_difference.h).
#include "lab/image/image_difference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace quadra {

namespace {

// Over every pixel, or those `pixels` marks when given.
ImageDifference differenceOver(const Image& a, const Image& b,
                               const std::vector<std::uint8_t>* pixels) {
  if (a.width != b.width || a.height != b.height)
    throw Error("images of different sizes: " + std::to_string(a.width) + "x" +
                std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                std::to_string(b.height));
  const std::size_t count = std::size_t(a.width) * std::size_t(a.height);
  if (pixels && pixels->size() != count)
    throw Error("a pixel mask of " + std::to_string(pixels->size()) + " entries for " +
                std::to_string(count) + " pixels");
  double sumSquared = 0.0, maxAbs = 0.0, values = 0.0;
  for (std::size_t p = 0; p < count; ++p) {
    if (pixels && (*pixels)[p] == 0) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = double(a.rgba[p * 4 + c]) - double(b.rgba[p * 4 + c]);
      sumSquared += d * d;
      maxAbs = std::max(maxAbs, std::fabs(d));
    }
    values += 3.0;
  }
  const double mse = values > 0.0 ? sumSquared / values : 0.0;
  // A NaN on either side is no match (std::max above would pass over it).
  if (std::isnan(sumSquared)) return {NAN, NAN};
  return {mse > 0.0 ? -10.0 * std::log10(mse) : std::numeric_limits<double>::infinity(), maxAbs};
}

}  // namespace

ImageDifference imageDifference(const Image& a, const Image& b) {
  return differenceOver(a, b, nullptr);
}

ImageDifference imageDifference(const Image& a, const Image& b,
                                const std::vector<std::uint8_t>& pixels) {
  return differenceOver(a, b, &pixels);
}

}  // namespace quadra
