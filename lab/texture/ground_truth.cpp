// Ground truth for texture lookups: double-precision bilinear reconstruction of
// level 0 and its midpoint-rule average over a pixel's parallelogram footprint.
#include "lab/texture/ground_truth.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace quadra {

BilinearReference::BilinearReference(const Image& image, const SamplerState& sampler)
    : image_(image), sampler_(sampler) {
  QUADRA_CHECK(image.width > 0 && image.height > 0);
}

long BilinearReference::wrapIndex(long i, long n, WrapMode mode) const {
  // lookupTexel hands in indices within a period or two of the texture, so a
  // compare and a subtraction wrap them; the general remainder (an integer
  // division, the costliest step of a sample) is only the fallback.
  switch (mode) {
    case WrapMode::Repeat: {
      if (i >= 0 && i < n) return i;
      if (i >= n && i < 2 * n) return i - n;
      const long r = i % n;
      return r < 0 ? r + n : r;
    }
    case WrapMode::MirroredRepeat: {
      long r = i;
      if (r < 0 || r >= 4 * n) {
        r %= 2 * n;
        if (r < 0) r += 2 * n;
      } else if (r >= 2 * n) {
        r -= 2 * n;
      }
      return r >= n ? 2 * n - 1 - r : r;
    }
    case WrapMode::ClampToEdge:
      return std::clamp(i, 0L, n - 1);
    case WrapMode::ClampToBorder:
      return i < 0 || i >= n ? -1 : i;
  }
  return 0;
}

void BilinearReference::lookupTexel(double x, double y, double rgba[4]) const {
  if (!std::isfinite(x)) x = -0.5;  // u = 0
  if (!std::isfinite(y)) y = -0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  // Coordinates far outside the texture only matter modulo the period (repeat,
  // mirror) or clamp anyway; bring them near before converting to integers.
  const long w = image_.width, h = image_.height;
  const auto near = [](double t, long n, WrapMode mode) {
    if (mode == WrapMode::Repeat || mode == WrapMode::MirroredRepeat) {
      const double period = mode == WrapMode::Repeat ? double(n) : 2.0 * double(n);
      if (t >= 0.0 && t < period) return long(t);
      return long(t - period * std::floor(t / period));
    }
    return long(std::clamp(t, -2.0, double(n) + 1.0));
  };
  const long ix = near(x0, w, sampler_.wrapU), iy = near(y0, h, sampler_.wrapV);
  const long xs[2] = {wrapIndex(ix, w, sampler_.wrapU), wrapIndex(ix + 1, w, sampler_.wrapU)};
  const long ys[2] = {wrapIndex(iy, h, sampler_.wrapV), wrapIndex(iy + 1, h, sampler_.wrapV)};
  const double wx[2] = {1.0 - fx, fx}, wy[2] = {1.0 - fy, fy};
  for (int c = 0; c < 4; ++c) rgba[c] = 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const double weight = wx[i] * wy[j];
      const float* texel =
          xs[i] < 0 || ys[j] < 0 ? sampler_.borderColor : image_.texel(int(xs[i]), int(ys[j]));
      for (int c = 0; c < 4; ++c) rgba[c] += weight * double(texel[c]);
    }
}

void BilinearReference::lookup(double u, double v, double rgba[4]) const {
  lookupTexel(u * image_.width - 0.5, v * image_.height - 0.5, rgba);
}

void integrateFootprintGrid(const BilinearReference& reference, const Footprint& footprint,
                            int samplesX, int samplesY, double rgba[4]) {
  QUADRA_CHECK(samplesX > 0 && samplesY > 0);
  const double w = reference.image().width, h = reference.image().height;
  // Everything in texel space: p(s, t) = centre + s * edgeX + t * edgeY, s, t in [-0.5, 0.5].
  const double cx = footprint.u * w - 0.5, cy = footprint.v * h - 0.5;
  const double exX = footprint.dudx * w, exY = footprint.dvdx * h;
  const double eyX = footprint.dudy * w, eyY = footprint.dvdy * h;
  double sum[4] = {0.0, 0.0, 0.0, 0.0};
  for (int j = 0; j < samplesY; ++j) {
    const double t = (j + 0.5) / samplesY - 0.5;
    // Per-row sums keep the running total's rounding error small on big grids.
    double row[4] = {0.0, 0.0, 0.0, 0.0};
    for (int i = 0; i < samplesX; ++i) {
      const double s = (i + 0.5) / samplesX - 0.5;
      double value[4];
      reference.lookupTexel(cx + s * exX + t * eyX, cy + s * exY + t * eyY, value);
      for (int c = 0; c < 4; ++c) row[c] += value[c];
    }
    for (int c = 0; c < 4; ++c) sum[c] += row[c];
  }
  const double count = double(samplesX) * double(samplesY);
  for (int c = 0; c < 4; ++c) rgba[c] = sum[c] / count;
}

int gridCellsFor(double texels, const GroundTruthOptions& options) {
  const double wanted = std::ceil(options.samplesPerTexel * (std::isfinite(texels) ? texels : 0.0));
  return int(
      std::clamp(wanted, double(options.minSamplesPerAxis), double(options.maxSamplesPerAxis)));
}

GroundTruthValue refineGrid(int nx, int ny, const GroundTruthOptions& options,
                            const std::function<void(int, int, double[4])>& integrate) {
  // Footprints covering thousands of texels: shrink both axes alike to the budget.
  while (std::size_t(nx) * std::size_t(ny) > options.maxSamples && (nx > 2 || ny > 2)) {
    nx = std::max(2, nx / 2);
    ny = std::max(2, ny / 2);
  }
  GroundTruthValue result;
  double coarse[4];
  integrate(std::max(1, nx / 2), std::max(1, ny / 2), coarse);
  for (;;) {
    integrate(nx, ny, result.rgba);
    result.change = 0.0;
    for (int c = 0; c < 4; ++c)
      result.change = std::max(result.change, std::abs(result.rgba[c] - coarse[c]));
    result.samplesX = nx;
    result.samplesY = ny;
    result.converged = result.change <= 0.25 * options.tolerance;
    const bool canDouble = 4 * std::size_t(nx) * std::size_t(ny) <= options.maxSamples &&
                           2 * std::max(nx, ny) <= options.maxSamplesPerAxis;
    if (result.converged || !canDouble) return result;
    std::copy(result.rgba, result.rgba + 4, coarse);
    nx *= 2;
    ny *= 2;
  }
}

GroundTruthValue groundTruth(const BilinearReference& reference, const Footprint& footprint,
                             const GroundTruthOptions& options) {
  const double w = reference.image().width, h = reference.image().height;
  const double edgeX = std::hypot(footprint.dudx * w, footprint.dvdx * h);
  const double edgeY = std::hypot(footprint.dudy * w, footprint.dvdy * h);
  return refineGrid(gridCellsFor(edgeX, options), gridCellsFor(edgeY, options), options,
                    [&](int nx, int ny, double rgba[4]) {
                      integrateFootprintGrid(reference, footprint, nx, ny, rgba);
                    });
}

GroundTruthSet truthSet(const std::vector<Footprint>& footprints,
                        const std::function<GroundTruthValue(const Footprint&)>& ideal,
                        const Executor& executor) {
  GroundTruthSet set;
  set.rgba.resize(footprints.size() * 4);
  std::vector<GroundTruthValue> values(footprints.size());
  executor.parallelFor(footprints.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) values[i] = ideal(footprints[i]);
  });
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::copy(values[i].rgba, values[i].rgba + 4, &set.rgba[i * 4]);
    set.converged += values[i].converged ? 1 : 0;
    set.maxChange = std::max(set.maxChange, values[i].change);
    set.rmsChange += values[i].change * values[i].change;
    set.maxSamples =
        std::max(set.maxSamples, std::size_t(values[i].samplesX) * std::size_t(values[i].samplesY));
  }
  if (!values.empty()) set.rmsChange = std::sqrt(set.rmsChange / double(values.size()));
  return set;
}

GroundTruthSet groundTruthSet(const BilinearReference& reference,
                              const std::vector<Footprint>& footprints,
                              const GroundTruthOptions& options, const Executor& executor) {
  return truthSet(
      footprints, [&](const Footprint& f) { return groundTruth(reference, f, options); }, executor);
}

}  // namespace quadra
