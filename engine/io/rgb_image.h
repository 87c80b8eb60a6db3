// RgbImage: the pixels of a decoded panorama (a Radiance .hdr or an EXR's
// R, G, B) as linear float RGB, before the shading stage's rules turn them
// into an environment (shading/environment_source.h). It lives here so the
// decoders do not depend on the stage that uses what they decode.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace quadra {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // width x height x 3, row by row from the top
};

// Called by a decoder with the image's size once it is known and before any
// pixel memory is allocated: the caller refuses a size (a memory budget, a
// minimum) by throwing its Error, so an absurd header costs nothing.
using AdmitImageSize = std::function<void(std::int64_t width, std::int64_t height)>;

}  // namespace quadra
