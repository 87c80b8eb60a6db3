// The EWA ideal: what an elliptical weighted average approximates, computed
// exactly. A screen-space radial weight w(|s| / radius) around the pixel
// centre, s in pixels, mapped through the Jacobian onto the texture, averages
// the bilinear level-0 reconstruction: ∫ f(c + J s) w(|s| / radius) ds over
// ∫ w(|s| / radius) ds, in double precision on midpoint grids doubled until
// converged (as the box ground truth, lab/texture/ground_truth.h). It is the
// reference an EWA filter is scored against for the error its own shortcuts
// add (mip levels, texel-centre sums, reconstruction), apart from the
// difference between its Gaussian and the box ideal.
#pragma once

#include <vector>

#include "lab/texture/ground_truth.h"
#include "texture/ewa.h"

namespace quadra {

class Executor;

// One lookup of the ideal for the filter shape `shape` (texture/ewa.h). The
// footprint's own ellipse is used as it is: the eccentricity clamp a filter
// applies (maxAniso) is one of the shortcuts measured against it.
GroundTruthValue ewaIdeal(const BilinearReference& reference, const Footprint& footprint,
                          const EwaShape& shape, const GroundTruthOptions& options = {});

// In parallel over footprints, as groundTruthSet.
GroundTruthSet ewaIdealSet(const BilinearReference& reference,
                           const std::vector<Footprint>& footprints, const EwaShape& shape,
                           const GroundTruthOptions& options, const Executor& executor);

}  // namespace quadra
