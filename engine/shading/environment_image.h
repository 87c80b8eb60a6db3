// The environment as the lit shading receives it: an equirectangular panorama
// of linear RGB radiance in ../shared/LIGHTING.md's convention (direction d
// maps to u = 0.5 + atan2(d.x, -d.z) / 2 pi, v = acos(d.y) / pi; row 0 is the
// top, +Y; texel (i, j) is centred at ((i + 0.5) / W, (j + 0.5) / H)), whose
// radiance in a direction is the bilinear interpolation of its texels at
// (u, v), wrapping in u and clamping in v. Decoders (.hdr, .exr) and the
// built-in environments produce it; the shading stage preprocesses it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace quadra {

struct EnvironmentImage {
  std::string name;  // file path or builtin:NAME, for messages
  int width = 0, height = 0;
  // width x height texels, row by row from the top, R G B each: finite and
  // non-negative (decoders apply the rule for other values).
  std::vector<float> rgb;

  std::size_t texelCount() const { return std::size_t(width) * std::size_t(height); }
  const float* texel(int i, int j) const { return rgb.data() + 3 * (std::size_t(j) * width + i); }
};

}  // namespace quadra
