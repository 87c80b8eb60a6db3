// The per-sample fragment store's slow parts: sorting a sample's fragments,
// compositing them, and merging when a sample is over its budget.
#include "tile/blended_fragments.h"

#include <limits>

namespace quadra {

void BlendedFragments::begin(int planes, bool depthGreater) {
  const std::size_t slots = std::size_t(planes) * TileBuffers::kPixels;
  if (head_.size() != slots) {
    head_.assign(slots, kNoFragment);
    count_.assign(slots, 0);
    touched_.clear();
  }
  for (const std::uint32_t slot : touched_) head_[slot] = kNoFragment, count_[slot] = 0;
  touched_.clear();
  pool_.clear();
  depthGreater_ = depthGreater;
  // Before the first fragment, any depth is "not behind": the far end.
  latest_.assign(slots, depthGreater ? -std::numeric_limits<float>::infinity()
                                     : std::numeric_limits<float>::infinity());
  late_.assign(slots, 0.0f);
}

void BlendedFragments::add(int plane, int pixel, float depth, const float color[4], float keep) {
  const std::uint32_t slot = std::uint32_t(plane * TileBuffers::kPixels + pixel);
  std::uint8_t& count = count_[slot];
  if (count == kMaxPerSample) return addBeyondBudget(slot, depth, color, keep);
  if (count++ == 0) touched_.push_back(slot);
  pool_.push_back({depth, {color[0], color[1], color[2], color[3]}, keep, head_[slot]});
  head_[slot] = std::uint32_t(pool_.size() - 1);
}

int BlendedFragments::sorted(std::uint32_t slot, BlendedFragment* out) const {
  int n = count_[slot];
  // The list runs newest first: filled from the back, it is in arrival order.
  int k = n;
  for (std::uint32_t i = head_[slot]; i != kNoFragment; i = pool_[i].next) out[--k] = pool_[i];
  // Insertion sort, stable (a fragment passes only strictly nearer ones), so
  // equal depths keep their arrival order; n is at most kMaxPerSample + 1.
  const bool greater = depthGreater_;
  const auto farther = [greater](float a, float b) { return greater ? a < b : a > b; };
  for (int i = 1; i < n; ++i) {
    const BlendedFragment f = out[i];
    int j = i;
    for (; j > 0 && farther(f.depth, out[j - 1].depth); --j) out[j] = out[j - 1];
    out[j] = f;
  }
  return n;
}

void BlendedFragments::addBeyondBudget(std::uint32_t slot, float depth, const float color[4],
                                       float keep) {
  BlendedFragment f[kMaxPerSample + 1];
  const int n = sorted(slot, f);
  // The newcomer, the newest, goes in front of the ones it is strictly nearer than.
  const bool greater = depthGreater_;
  int j = n;
  for (; j > 0 && (greater ? f[j - 1].depth > depth : f[j - 1].depth < depth); --j) f[j] = f[j - 1];
  f[j] = {depth, {color[0], color[1], color[2], color[3]}, keep, kNoFragment};
  // The two farthest become one step: the nearer applied after the farther.
  BlendedFragment& merged = f[1];
  for (int c = 0; c < 4; ++c) merged.color[c] += merged.keep * f[0].color[c];
  merged.keep *= f[0].keep;
  // Back into the sample's own nodes, newest first as nearest first, so
  // later sorts keep this order among equal depths and the pool does not grow.
  std::uint32_t node = head_[slot];
  for (int k = n; k >= 1; --k) {
    const std::uint32_t next = pool_[node].next;
    pool_[node] = f[k];
    pool_[node].next = next;
    node = next;
  }
}

void BlendedFragments::composite(TileBuffers* planes) {
  BlendedFragment f[kMaxPerSample];
  for (const std::uint32_t slot : touched_) {
    const int n = sorted(slot, f);
    TileBuffers& plane = planes[slot / TileBuffers::kPixels];
    const int pixel = int(slot % TileBuffers::kPixels);
    for (int c = 0; c < 4; ++c) {
      float dst = plane.color[c][pixel];
      for (int k = 0; k < n; ++k) dst = f[k].color[c] + dst * f[k].keep;
      plane.color[c][pixel] = dst;
    }
  }
  for (const std::uint32_t slot : touched_) head_[slot] = kNoFragment, count_[slot] = 0;
  touched_.clear();
  pool_.clear();
}

}  // namespace quadra
