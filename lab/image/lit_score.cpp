// Tone-mapped sRGB PSNR of lit frames (see lit_score.h).
#include "lab/image/lit_score.h"

#include <algorithm>
#include <cmath>

namespace quadra {

glm::dvec3 pbrNeutral(const glm::dvec3& linear) {
  // The specification's constants: F90 = 0.04, compression from Ks = 0.8 -
  // F90, desaturation speed Kd = 0.15.
  constexpr double kF90 = 0.04, kStart = 0.8 - kF90, kDesaturation = 0.15;
  glm::dvec3 c = glm::max(linear, glm::dvec3(0.0));
  const double x = std::min({c.r, c.g, c.b});
  const double offset = x <= 2.0 * kF90 ? x - x * x / (4.0 * kF90) : kF90;
  c -= offset;
  const double peak = std::max({c.r, c.g, c.b});
  if (peak <= kStart) return c;
  const double d = 1.0 - kStart;
  const double newPeak = 1.0 - d * d / (peak + d - kStart);
  const double g = 1.0 / (kDesaturation * (peak - newPeak) + 1.0);
  return c * (newPeak / peak) * g + glm::dvec3(newPeak) * (1.0 - g);
}

double srgbEncode(double linear) {
  const double x = std::clamp(linear, 0.0, 1.0);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

Image toneMappedSrgb(const Image& linear, double exposure) {
  Image out(linear.width, linear.height);
  const double scale = std::exp2(exposure);
  for (std::size_t i = 0; i < linear.rgba.size(); i += 4) {
    const glm::dvec3 mapped =
        pbrNeutral(scale * glm::dvec3(linear.rgba[i], linear.rgba[i + 1], linear.rgba[i + 2]));
    for (int c = 0; c < 3; ++c) out.rgba[i + std::size_t(c)] = float(srgbEncode(mapped[c]));
    out.rgba[i + 3] = linear.rgba[i + 3];
  }
  return out;
}

LitScore scoreLitFrame(const Image& frame, const Image& ideal,
                       const std::vector<std::uint8_t>& interior, double exposure) {
  const Image a = toneMappedSrgb(frame, exposure), b = toneMappedSrgb(ideal, exposure);
  LitScore score;
  score.all = imageDifference(a, b);
  score.interior = imageDifference(a, b, interior);
  score.interiorPixels = std::size_t(std::count_if(
      interior.begin(), interior.end(), [](std::uint8_t inside) { return inside != 0; }));
  return score;
}

}  // namespace quadra
