// Filter quality on builtin:checker-plane against the frame reference (dense
// supersampling of exact hits and level-0 bilinear lookups, box filtered):
// trilinear must beat bilinear and nearest, which alias towards the horizon.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "api/renderer.h"
#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"
#include "render_helpers.h"

namespace quadra {
namespace {

constexpr int kWidth = 256;
constexpr int kHeight = 144;
// 32 x 32 subsamples (~2 s on two cores): the reference's own residual (its
// rows near the horizon are not converged) stays well below the differences
// between the filters.
constexpr int kSamplesPerAxis = 32;

Frame renderFiltered(const Scene& scene, const Camera& camera, Filter filter) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.filter = filter;
  return renderOnce(scene, camera, settings);
}

// Over the colour channels of every pixel (sky included: both sides clear it).
double rmse(const Frame& frame, const Image& reference) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < frame.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = double(frame.rgba[i]) - double(reference.rgba[i]);
    sum += d * d;
    ++n;
  }
  return std::sqrt(sum / double(n));
}

TEST(CheckerPlaneQuality, MipFiltersBeatBilinearAndNearest) {
  const Scene scene = makeBuiltinScene("checker-plane");
  const Camera camera = firstCameraOrDefault(scene);

  const auto start = std::chrono::steady_clock::now();
  const Image reference =
      ref::ReferenceTracer(scene, camera, kWidth, kHeight).render(kSamplesPerAxis);
  const double referenceSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const Frame nearest = renderFiltered(scene, camera, Filter::Nearest);
  const Frame bilinear = renderFiltered(scene, camera, Filter::Bilinear);
  const Frame trilinear = renderFiltered(scene, camera, Filter::Trilinear);
  const Frame anisotropic = renderFiltered(scene, camera, Filter::Anisotropic);
  const Frame ewa = renderFiltered(scene, camera, Filter::Ewa);
  const Frame area = renderFiltered(scene, camera, Filter::Area);
  ASSERT_EQ(trilinear.rgba.size(), reference.rgba.size());
  const double eNearest = rmse(nearest, reference);
  const double eBilinear = rmse(bilinear, reference);
  const double eTrilinear = rmse(trilinear, reference);
  const double eAnisotropic = rmse(anisotropic, reference);
  const double eEwa = rmse(ewa, reference);
  const double eArea = rmse(area, reference);
  std::printf(
      "[ checker-plane %dx%d, reference %dx%d spp in %.1f s ] RMSE nearest %.5f "
      "bilinear %.5f trilinear %.5f aniso16 %.5f ewa %.5f area %.5f\n",
      kWidth, kHeight, kSamplesPerAxis, kSamplesPerAxis, referenceSeconds, eNearest, eBilinear,
      eTrilinear, eAnisotropic, eEwa, eArea);
  EXPECT_LT(eTrilinear, eBilinear);
  // Trilinear over-blurs the receding plane; probing along the footprint's
  // major axis recovers detail.
  EXPECT_LT(eAnisotropic, eTrilinear);
  EXPECT_LT(eEwa, eTrilinear);
  // The area filter averages the footprint itself, as the reference does.
  EXPECT_LT(eArea, eAnisotropic);
  EXPECT_LT(eTrilinear, eNearest);
  // The comparison means something: an empty frame scores far worse.
  Frame empty = trilinear;
  std::fill(empty.rgba.begin(), empty.rgba.end(), 0.0f);
  EXPECT_LT(eTrilinear, 0.5 * rmse(empty, reference));
}

}  // namespace
}  // namespace quadra
