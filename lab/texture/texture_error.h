// Error and speed of a texture filter over a footprint set: RMSE and max abs
// error against the ground truth (overall, per scale bucket, per anisotropy
// bucket) and the time per lookup. Errors are over the R, G, B channels of
// every lookup (alpha is constant in most textures and would only dilute them).
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "lab/texture/footprints.h"
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

// Lookups [begin, end) of a batch into rgba: a TextureSampler, or another
// library's texture lookups measured the same way (the report's comparison).
using BatchLookup =
    std::function<void(const LookupBatch&, std::size_t begin, std::size_t end, float* rgba)>;

// Compares RGBA values (4 floats per footprint) with truth (4 doubles each).
FilterError errorOfValues(const std::vector<float>& rgba, const FootprintSet& footprints,
                          const std::vector<double>& truth);

// Samples every footprint (in parallel; the values do not depend on the
// split) and compares with truth (4 doubles per footprint). `values`, when
// given, receives the sampler's RGBA.
FilterError measureFilterError(const TextureSampler& sampler, const FootprintSet& footprints,
                               const std::vector<double>& truth, const Executor& executor,
                               std::vector<float>* values = nullptr);

// Time of the lookups alone on the calling thread, ns per lookup, for several
// lookup functions over the same footprints: each batch is run repeatedly
// until minSeconds pass, in interleaved rounds (one timed run of each per
// round), so a burst of load from other processes falls on all of them alike
// rather than on whichever ran then; the median of the rounds is returned.
std::vector<double> timeLookupsInterleavedNs(const std::vector<BatchLookup>& lookups,
                                             const FootprintSet& footprints, int rounds = 5,
                                             double minSeconds = 0.02);
BatchLookup batchLookupOf(const TextureSampler& sampler);

}  // namespace quadra
