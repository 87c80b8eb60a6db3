// The EWA ideal (ewa_ideal.h): a radially weighted screen-space disk mapped
// through the Jacobian, integrated on midpoint grids in double.
#include "lab/texture/ewa_ideal.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace quadra {

namespace {

// The weighted average on one nx × ny midpoint grid over the screen square
// [-radius, radius]^2 (the weight is 0 outside the disk).
void integrateEwaGrid(const BilinearReference& reference, const Footprint& footprint,
                      const EwaShape& shape, int nx, int ny, double rgba[4]) {
  const double w = reference.image().width, h = reference.image().height;
  const double cx = footprint.u * w - 0.5, cy = footprint.v * h - 0.5;
  const double exX = footprint.dudx * w, exY = footprint.dvdx * h;
  const double eyX = footprint.dudy * w, eyY = footprint.dvdy * h;
  double sum[4] = {0.0, 0.0, 0.0, 0.0}, weights = 0.0;
  for (int j = 0; j < ny; ++j) {
    const double t = ((j + 0.5) / ny - 0.5) * 2.0;  // in [-1, 1]: screen y / radius
    double row[4] = {0.0, 0.0, 0.0, 0.0}, rowWeights = 0.0;
    for (int i = 0; i < nx; ++i) {
      const double s = ((i + 0.5) / nx - 0.5) * 2.0;
      const double weight = ewaWeight(shape, s * s + t * t);
      if (weight <= 0.0) continue;
      double value[4];
      reference.lookupTexel(cx + shape.radius * (s * exX + t * eyX),
                            cy + shape.radius * (s * exY + t * eyY), value);
      for (int c = 0; c < 4; ++c) row[c] += weight * value[c];
      rowWeights += weight;
    }
    for (int c = 0; c < 4; ++c) sum[c] += row[c];
    weights += rowWeights;
  }
  for (int c = 0; c < 4; ++c) rgba[c] = weights > 0.0 ? sum[c] / weights : 0.0;
}

}  // namespace

GroundTruthValue ewaIdeal(const BilinearReference& reference, const Footprint& footprint,
                          const EwaShape& shape, const GroundTruthOptions& options) {
  QUADRA_CHECK(shape.radius > 0.0);
  const double w = reference.image().width, h = reference.image().height;
  // The disk's diameter along each screen axis, in texels; the weight falls
  // off over the disk, so its rim needs the grid as much as the texels do: at
  // least 16 samples across.
  const double edgeX = 2.0 * shape.radius * std::hypot(footprint.dudx * w, footprint.dvdx * h);
  const double edgeY = 2.0 * shape.radius * std::hypot(footprint.dudy * w, footprint.dvdy * h);
  return refineGrid(std::max(16, gridCellsFor(edgeX, options)),
                    std::max(16, gridCellsFor(edgeY, options)), options,
                    [&](int nx, int ny, double rgba[4]) {
                      integrateEwaGrid(reference, footprint, shape, nx, ny, rgba);
                    });
}

GroundTruthSet ewaIdealSet(const BilinearReference& reference,
                           const std::vector<Footprint>& footprints, const EwaShape& shape,
                           const GroundTruthOptions& options, const Executor& executor) {
  return truthSet(
      footprints, [&](const Footprint& f) { return ewaIdeal(reference, f, shape, options); },
      executor);
}

}  // namespace quadra
