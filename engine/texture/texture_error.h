// Error and speed of a texture filter over a footprint set: RMSE and max abs
// error against the ground truth (overall, per scale bucket, per anisotropy
// bucket) and the time per lookup. Errors are over the R, G, B channels of
// every lookup (alpha is constant in most textures and would only dilute them).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "texture/footprints.h"
#include "texture/texture_sampler.h"

namespace quadra {

class Executor;

struct ErrorStats {
  std::size_t lookups = 0;
  double sumSquared = 0.0;  // over lookups x RGB
  double maxAbs = 0.0;

  void add(const float* got, const double* want);  // one lookup, RGBA in
  double rmse() const;
};

struct FilterError {
  ErrorStats overall;
  std::array<ErrorStats, kScaleBuckets> perScale;
  std::array<ErrorStats, kAnisoBuckets> perAniso;
};

// Samples every footprint (in parallel; the values do not depend on the
// split) and compares with truth (4 doubles per footprint). `values`, when
// given, receives the sampler's RGBA.
FilterError measureFilterError(const TextureSampler& sampler, const FootprintSet& footprints,
                               const std::vector<double>& truth, const Executor& executor,
                               std::vector<float>* values = nullptr);

// Time of the lookups alone on the calling thread, ns per lookup: the batch is
// run repeatedly until minSeconds pass, `repeats` times; the median is returned.
double timeLookupsNs(const TextureSampler& sampler, const FootprintSet& footprints, int repeats = 5,
                     double minSeconds = 0.02);

// The same for several samplers over the same footprints, in interleaved
// rounds (one timed run of each per round), so a burst of load from other
// processes falls on all of them alike rather than on whichever ran then.
std::vector<double> timeLookupsInterleavedNs(const std::vector<const TextureSampler*>& samplers,
                                             const FootprintSet& footprints, int rounds = 5,
                                             double minSeconds = 0.02);

}  // namespace quadra
