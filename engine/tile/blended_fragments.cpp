// The per-sample fragment store's slow parts: sorting a sample's fragments,
// compositing them, and merging when a sample is over its budget.
#include "tile/blended_fragments.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace quadra {
namespace {

constexpr std::uint64_t kArrivalMask = 0xFF;

// Fragments sort by these keys far to near, equal depths by arrival (the
// key's low bits, kArrivalMask).
std::uint64_t farToNearKey(float depth, int arrival, bool depthGreater) {
  // The float's bits made to sort as it does (-0 as +0, which it equals),
  // reversed for standard depth, whose far fragments hold the larger depths;
  // below them the arrival, so equal depths keep their order.
  if (depth == 0.0f) depth = 0.0f;
  std::uint32_t bits;
  std::memcpy(&bits, &depth, sizeof bits);
  bits = (bits & 0x80000000u) != 0 ? ~bits : bits | 0x80000000u;
  if (!depthGreater) bits = ~bits;
  return std::uint64_t(bits) << 32 | std::uint32_t(arrival);
}

void sortKeys(std::uint64_t* keys, int n) {
  // Insertion sort: n is at most kMaxPerSample + 1, mostly in order already.
  for (int i = 1; i < n; ++i) {
    const std::uint64_t key = keys[i];
    int j = i;
    for (; j > 0 && keys[j - 1] > key; --j) keys[j] = keys[j - 1];
    keys[j] = key;
  }
}

}  // namespace

void BlendedFragments::begin(int planes, bool depthGreater) {
  const std::size_t slots = std::size_t(planes) * TileBuffers::kPixels;
  if (slots_ != slots) {
    // Zeroed, so every page is resident from the first tile: a store kept
    // from frame to frame (TileWorkspace) would otherwise take a few more
    // pages each frame, as fragments reach layers the tiles before did not.
    layers_.reset(new BlendedFragment[kMaxPerSample * slots]());
    touched_.reset(new std::uint32_t[slots]);
    slots_ = slots;
    count_.assign(slots, 0);
    touchedCount_ = 0;
    latest_.resize(slots);
    late_.assign(slots, 0.0f);
    lateMarked_ = false;
  }
  clearTouched();
  depthGreater_ = depthGreater;
  // Only after an order pass: a tile that skips it (most of a frame whose
  // blended layers arrive far to near) writes neither list, where clearing
  // both was 512 KiB a tile at 16 samples.
  if (lateMarked_) std::fill(late_.begin(), late_.end(), 0.0f);
  lateMarked_ = false;
  if (covered_.empty()) covered_.assign(TileBuffers::kPixels, 0u);  // zero from then on
}

void BlendedFragments::beginOrderPass() {
  // Before the first fragment, any depth is "not behind": the far end.
  std::fill(latest_.begin(), latest_.end(),
            depthGreater_ ? -std::numeric_limits<float>::infinity()
                          : std::numeric_limits<float>::infinity());
  lateMarked_ = true;
}

void BlendedFragments::add(int plane, int index, std::uint32_t lanes, const float* depth,
                           const float* const color[4], const float* keep) {
  // Locals, not members: the counts' byte stores may alias anything.
  BlendedFragment* const layers = layers_.get();
  std::uint8_t* const counts = count_.data();
  const std::size_t slots = slots_;
  const std::uint32_t first = std::uint32_t(plane * TileBuffers::kPixels + index);
  for (; lanes != 0; lanes &= lanes - 1) {
    const int k = __builtin_ctz(lanes);
    const std::uint32_t slot = first + std::uint32_t(k);
    const int count = counts[slot];
    if (count == kMaxPerSample) {
      addBeyondBudget(slot,
                      {depth[k], {color[0][k], color[1][k], color[2][k], color[3][k]}, keep[k]});
      continue;
    }
    if (count == 0) touched_[touchedCount_++] = slot;
    counts[slot] = std::uint8_t(count + 1);
    // Field by field: a fragment built whole on the stack and copied was
    // read back before its parts' stores could forward (perf: most of add).
    BlendedFragment& f = layers[std::size_t(count) * slots + slot];
    f.depth = depth[k];
    for (int c = 0; c < 4; ++c) f.color[c] = color[c][k];
    f.keep = keep[k];
  }
}

void BlendedFragments::addBeyondBudget(std::uint32_t slot, const BlendedFragment& newest) {
  // The sample's fragments and the newcomer, the newest, far to near.
  constexpr int n = kMaxPerSample + 1;
  BlendedFragment arrived[n];
  std::uint64_t keys[n];
  for (int k = 0; k < kMaxPerSample; ++k) arrived[k] = at(k, slot);
  arrived[kMaxPerSample] = newest;
  for (int k = 0; k < n; ++k) keys[k] = farToNearKey(arrived[k].depth, k, depthGreater_);
  sortKeys(keys, n);
  // The two farthest become one step: the nearer applied after the farther.
  const BlendedFragment& farthest = arrived[keys[0] & kArrivalMask];
  BlendedFragment merged = arrived[keys[1] & kArrivalMask];
  for (int c = 0; c < 4; ++c) merged.color[c] += merged.keep * farthest.color[c];
  merged.keep *= farthest.keep;
  // Back into the sample's layers far to near, as if they had arrived in
  // that order, so later sorts keep this order among equal depths.
  at(0, slot) = merged;
  for (int k = 2; k < n; ++k) at(k - 1, slot) = arrived[keys[k] & kArrivalMask];
}

void BlendedFragments::composite(TileBuffers* planes) {
  const std::size_t touched = touchedCount_;  // a local: the colour stores may alias it
  for (std::size_t i = 0; i < touched; ++i) {
    const std::uint32_t slot = touched_[i];
    const int n = count_[slot];
    std::uint64_t keys[kMaxPerSample];
    for (int k = 0; k < n; ++k) keys[k] = farToNearKey(at(k, slot).depth, k, depthGreater_);
    sortKeys(keys, n);
    TileBuffers& plane = planes[slot / TileBuffers::kPixels];
    const int pixel = int(slot % TileBuffers::kPixels);
    float dst[4] = {plane.color[0][pixel], plane.color[1][pixel], plane.color[2][pixel],
                    plane.color[3][pixel]};
    for (int k = 0; k < n; ++k) {
      const BlendedFragment& f = at(int(keys[k] & kArrivalMask), slot);
      for (int c = 0; c < 4; ++c) dst[c] = f.color[c] + dst[c] * f.keep;
    }
    for (int c = 0; c < 4; ++c) plane.color[c][pixel] = dst[c];
  }
  clearTouched();
}

void BlendedFragments::clearTouched() {
  for (std::size_t i = 0; i < touchedCount_; ++i) count_[touched_[i]] = 0;
  touchedCount_ = 0;
}

}  // namespace quadra
