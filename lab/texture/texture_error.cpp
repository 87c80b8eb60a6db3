// Comparing a TextureSampler with the ground truth, and timing it.
#include "lab/texture/texture_error.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace quadra {

void ErrorStats::add(const float* got, const double* want) {
  ++lookups;
  for (int c = 0; c < 3; ++c) {
    const double e = double(got[c]) - want[c];
    sumSquared += e * e;
    // NaN must count as the worst error, not vanish in max().
    maxAbs = std::isnan(e) ? e : std::max(maxAbs, std::abs(e));
  }
}

double ErrorStats::rmse() const {
  return lookups ? std::sqrt(sumSquared / (3.0 * lookups)) : 0.0;
}

FilterError errorOfValues(const std::vector<float>& rgba, const FootprintSet& footprints,
                          const std::vector<double>& truth) {
  const std::size_t n = footprints.size();
  QUADRA_CHECK_OP(truth.size(), ==, n * 4);
  QUADRA_CHECK_OP(rgba.size(), ==, n * 4);
  FilterError error;
  for (std::size_t i = 0; i < n; ++i) {
    const float* got = &rgba[i * 4];
    const double* want = &truth[i * 4];
    error.overall.add(got, want);
    error.perScale[std::size_t(footprints.scaleBucket[i])].add(got, want);
    error.perAniso[std::size_t(footprints.anisoBucket[i])].add(got, want);
  }
  return error;
}

FilterError measureFilterError(const TextureSampler& sampler, const FootprintSet& footprints,
                               const std::vector<double>& truth, const Executor& executor,
                               std::vector<float>* values) {
  std::vector<float> local;
  std::vector<float>& rgba = values ? *values : local;
  rgba.assign(footprints.size() * 4, 0.0f);
  const LookupBatch batch = footprints.batch();
  executor.parallelFor(footprints.size(), 1024, [&](std::size_t begin, std::size_t end) {
    sampler.sample(batch, begin, end, rgba.data());
  });
  return errorOfValues(rgba, footprints, truth);
}

BatchLookup batchLookupOf(const TextureSampler& sampler) {
  return [&sampler](const LookupBatch& batch, std::size_t begin, std::size_t end, float* rgba) {
    sampler.sample(batch, begin, end, rgba);
  };
}

std::vector<double> timeLookupsInterleavedNs(const std::vector<BatchLookup>& lookups,
                                             const FootprintSet& footprints, int rounds,
                                             double minSeconds) {
  const LookupBatch batch = footprints.batch();
  std::vector<double> medians(lookups.size(), 0.0);
  if (batch.count == 0) return medians;
  std::vector<float> rgba(batch.count * 4);
  for (const BatchLookup& lookup : lookups)  // warm caches and the mip chains
    lookup(batch, 0, batch.count, rgba.data());
  std::vector<std::vector<double>> perLookup(lookups.size());
  for (int r = 0; r < std::max(1, rounds); ++r)
    for (std::size_t s = 0; s < lookups.size(); ++s) {
      const auto start = std::chrono::steady_clock::now();
      std::size_t done = 0;
      double seconds = 0.0;
      do {
        lookups[s](batch, 0, batch.count, rgba.data());
        done += batch.count;
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      } while (seconds < minSeconds);
      perLookup[s].push_back(seconds * 1e9 / double(done));
    }
  for (std::size_t s = 0; s < lookups.size(); ++s) {
    std::sort(perLookup[s].begin(), perLookup[s].end());
    medians[s] = perLookup[s][perLookup[s].size() / 2];
  }
  return medians;
}

}  // namespace quadra
