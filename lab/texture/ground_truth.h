// Ground truth for texture lookups (DESIGN.md "Accuracy: what error means"):
// the ideal value of a lookup is the average of the bilinearly reconstructed
// level-0 texture, with the sampler's wrap modes, over the pixel's footprint —
// the unit pixel square [-0.5, 0.5]^2 mapped through the Jacobian
// [[dudx, dudy], [dvdx, dvdy]] around (u, v) — in double precision. Also the
// double-precision bilinear lookup itself, the reference the filters are built on.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "texture/image.h"
#include "texture/sampler_state.h"

namespace quadra {

class Executor;

// One lookup in double: normalized (u, v) and the Jacobian of (u, v) with
// respect to screen x and y.
struct Footprint {
  double u = 0.0, v = 0.0;
  double dudx = 0.0, dvdx = 0.0, dudy = 0.0, dvdy = 0.0;
};

// Level-0 bilinear reconstruction in double, texel centres at i + 0.5 (a lookup
// at u reads x = u*W - 0.5), wrap modes and border colour from `sampler`.
// Non-finite coordinates read as 0, as the engine's kernels do.
class BilinearReference {
 public:
  BilinearReference(const Image& image, const SamplerState& sampler);

  // Normalized coordinates → linear RGBA.
  void lookup(double u, double v, double rgba[4]) const;
  // Texel-space coordinates (x = u*W - 0.5, y = v*H - 0.5) → linear RGBA.
  void lookupTexel(double x, double y, double rgba[4]) const;

  const Image& image() const { return image_; }

 private:
  // Texel index → row/column inside the image, or -1 for the border colour.
  long wrapIndex(long i, long n, WrapMode mode) const;

  const Image& image_;
  SamplerState sampler_;
};

// How hard to integrate. The footprint is integrated with the midpoint rule on
// a regular grid (one sample at the centre of each of nx × ny equal cells of
// the parallelogram); the grid starts from at least `samplesPerTexel` samples
// per texel along each edge and doubles per axis until the last doubling moved
// the result by at most tolerance / 4 (max abs over RGBA) or the next grid
// would exceed `maxSamples`. The midpoint rule's error falls as h^2, so the
// next doubling would move it by about a quarter as much again; the factor 4
// also absorbs the error's wobble between grids, which makes a single small
// change an unreliable sign on its own. The stated bound is `tolerance`: one
// more doubling moves a converged value by less than that (tested).
struct GroundTruthOptions {
  double tolerance = 1e-4;
  double samplesPerTexel = 4.0;
  int minSamplesPerAxis = 8;
  int maxSamplesPerAxis = 4096;
  std::size_t maxSamples = std::size_t(1) << 18;  // per grid, a few ms of work
};

struct GroundTruthValue {
  double rgba[4] = {0.0, 0.0, 0.0, 0.0};
  int samplesX = 0, samplesY = 0;  // the finest grid used (the value is from it)
  // Max abs change (over RGBA) from the previous grid, half as fine per axis:
  // the stated residual of this value.
  double change = 0.0;
  bool converged = false;  // change <= tolerance / 4
};

// The average of the bilinear reconstruction over the footprint on one
// nx × ny midpoint grid (exposed so tests can check convergence themselves).
void integrateFootprintGrid(const BilinearReference& reference, const Footprint& footprint,
                            int samplesX, int samplesY, double rgba[4]);

GroundTruthValue groundTruth(const BilinearReference& reference, const Footprint& footprint,
                             const GroundTruthOptions& options = {});

// The refinement both ideals share: integrate(nx, ny, rgba) on grids from
// (nx, ny) (cut to the sample budget), doubled per axis until converged as
// GroundTruthOptions describes.
GroundTruthValue refineGrid(int nx, int ny, const GroundTruthOptions& options,
                            const std::function<void(int, int, double[4])>& integrate);
// Grid cells along an edge `texels` long: options.samplesPerTexel per texel,
// within the options' per-axis bounds (non-finite lengths give the minimum).
int gridCellsFor(double texels, const GroundTruthOptions& options);

// Ground truth of many footprints, in parallel over footprints (each value is
// computed by one task, so the results do not depend on the thread count).
struct GroundTruthSet {
  std::vector<double> rgba;  // 4 per footprint
  std::size_t converged = 0;
  double maxChange = 0.0;      // the largest residual over the set
  double rmsChange = 0.0;      // root mean square residual over the set
  std::size_t maxSamples = 0;  // the largest grid used
};
GroundTruthSet groundTruthSet(const BilinearReference& reference,
                              const std::vector<Footprint>& footprints,
                              const GroundTruthOptions& options, const Executor& executor);
// The same for any per-footprint ideal.
GroundTruthSet truthSet(const std::vector<Footprint>& footprints,
                        const std::function<GroundTruthValue(const Footprint&)>& ideal,
                        const Executor& executor);

}  // namespace quadra
