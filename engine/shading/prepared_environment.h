// An environment made ready for lookups: from an EnvironmentImage (LIGHTING.md's
// equirectangular panorama), its rotation about +Y and its intensity, the
// tables the lane code reads (lighting.h EnvironmentView):
//  - radiance: a cube map with mip levels down to 1 x 1 (level 0 the bilinear
//    panorama at the texel centres, each level the [1 3 3 1] binomial
//    downsample of the one above), read by filtered importance sampling of
//    the GGX lobe and by the background's footprint-filtered lookup;
//  - irradiance: (1/pi) x the cosine-weighted integral of the radiance, a
//    32 x 32 cube computed from the environment itself (no spherical harmonics);
//  - the BRDF's directional albedo table (brdf_table.h) and the sample pattern.
// docs/shading.md has the design and its measured error.
#pragma once

#include <cstdint>
#include <vector>

#include "shading/lighting.h"

namespace quadra {

class Executor;
struct EnvironmentImage;

struct EnvironmentPlacement {
  float rotationDegrees = 0.0f;  // --env-rotation: a lookup in d reads R_y(-deg) d
  float intensity = 1.0f;        // --env-intensity
};

class PreparedEnvironment {
 public:
  // Holds pointers into itself: neither copied nor moved.
  PreparedEnvironment(const PreparedEnvironment&) = delete;
  PreparedEnvironment& operator=(const PreparedEnvironment&) = delete;
  // The image must hold width x height >= 1 finite non-negative texels.
  // Multithreaded over `executor`; the same bits for any thread count.
  PreparedEnvironment(const EnvironmentImage& image, const EnvironmentPlacement& placement,
                      const Executor& executor);

  EnvironmentView view() const;
  int cubeSize() const { return size_; }
  int levelCount() const { return levelCount_; }
  std::size_t bytes() const;
  const std::vector<float>& radiance() const { return radiance_; }
  const std::vector<float>& irradianceTexels() const { return irradiance_; }

  // Level 0's face size for a panorama `width` texels wide: the power of two
  // nearest width / 4 (a face's centre texel then spans the panorama's
  // equator texel), clamped to [16, 1024].
  static int cubeSizeFor(int width);

  static constexpr int kIrradianceSize = 32;

 private:
  int size_ = 0, levelCount_ = 0;
  std::vector<float> radiance_;
  std::vector<std::int64_t> levelOffset_;
  alignas(64) const std::uint8_t* levelTexels_[16] = {};
  alignas(64) const std::uint8_t* irradianceTexels_[16] = {};
  std::vector<float> irradiance_;
  std::vector<float> fisSamples_;
  const float* brdfTable_ = nullptr;
};

}  // namespace quadra
