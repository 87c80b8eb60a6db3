// PSNR and max difference over R, G, B (see image_difference.h).
#include "lab/image/image_difference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace quadra {

ImageDifference imageDifference(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw Error("images of different sizes: " + std::to_string(a.width) + "x" +
                std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                std::to_string(b.height));
  double sumSquared = 0.0, maxAbs = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4)
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = double(a.rgba[i + c]) - double(b.rgba[i + c]);
      sumSquared += d * d;
      maxAbs = std::max(maxAbs, std::fabs(d));
    }
  const double values = 3.0 * double(a.width) * double(a.height);
  const double mse = values > 0.0 ? sumSquared / values : 0.0;
  // A NaN on either side is no match (std::max above would pass over it).
  if (std::isnan(sumSquared)) return {NAN, NAN};
  return {mse > 0.0 ? -10.0 * std::log10(mse) : std::numeric_limits<double>::infinity(), maxAbs};
}

}  // namespace quadra
