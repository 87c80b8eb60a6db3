// The per-sample fragment store: adding fragments, and merging when a sample
// is over its budget. Compositing is a tile kernel (compositeBlended), which
// sorts a lane group's samples at once.
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
    // Each field plane padded by a cache line: unpadded, a fragment's six
    // fields sit a multiple of 16 KiB apart and alias in the L1 sets (as
    // TileBuffers::kPlaneStride). Zeroed, so every page is resident from the
    // first tile: a store kept from frame to frame (TileWorkspace) would
    // otherwise take a few more pages each frame, as fragments reach layers
    // the tiles before did not.
    const std::size_t stride = slots + 16;
    const std::size_t floats = std::size_t(kMaxPerSample) * kFields * stride;
    layers_.reset(new (std::align_val_t(64)) float[floats]());
    slots_ = slots;
    fieldStride_ = stride;
    count_.assign(slots, 0);
    touched_.assign((slots / kGroupSlots + 63) / 64, 0);
    anyTouched_ = false;
    latest_.resize(slots);
    late_.assign(slots, 0.0f);
    lateMarked_ = false;
  }
  clear();
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
  float* const layers = layers_.get();
  std::uint8_t* const counts = count_.data();
  const std::size_t stride = fieldStride_;
  const std::uint32_t first = std::uint32_t(plane * TileBuffers::kPixels + index);
  markTouched(first);  // a lane group lies within one group of slots
  for (; lanes != 0; lanes &= lanes - 1) {
    const int k = __builtin_ctz(lanes);
    const std::uint32_t slot = first + std::uint32_t(k);
    const int count = counts[slot];
    if (count == kMaxPerSample) {
      addBeyondBudget(slot,
                      {depth[k], color[0][k], color[1][k], color[2][k], color[3][k], keep[k]});
      continue;
    }
    counts[slot] = std::uint8_t(count + 1);
    float* const f = layers + std::size_t(count) * kFields * stride + slot;
    f[kDepth * stride] = depth[k];
    for (int c = 0; c < 4; ++c) f[(kRed + c) * stride] = color[c][k];
    f[kKeep * stride] = keep[k];
  }
}

void BlendedFragments::addBeyondBudget(std::uint32_t slot, const float (&newest)[kFields]) {
  // The sample's fragments and the newcomer, the newest, far to near.
  constexpr int n = kMaxPerSample + 1;
  float arrived[n][kFields];
  std::uint64_t keys[n];
  for (int k = 0; k < kMaxPerSample; ++k)
    for (int f = 0; f < kFields; ++f) arrived[k][f] = at(k, f, slot);
  for (int f = 0; f < kFields; ++f) arrived[kMaxPerSample][f] = newest[f];
  for (int k = 0; k < n; ++k) keys[k] = farToNearKey(arrived[k][kDepth], k, depthGreater_);
  sortKeys(keys, n);
  // The two farthest become one step: the nearer applied after the farther.
  const float* const farthest = arrived[keys[0] & kArrivalMask];
  float merged[kFields];
  std::copy_n(arrived[keys[1] & kArrivalMask], kFields, merged);
  for (int c = kRed; c <= kAlpha; ++c) merged[c] += merged[kKeep] * farthest[c];
  merged[kKeep] *= farthest[kKeep];
  // Back into the sample's layers far to near, as if they had arrived in
  // that order, so later sorts keep this order among equal depths.
  for (int f = 0; f < kFields; ++f) at(0, f, slot) = merged[f];
  for (int k = 2; k < n; ++k)
    for (int f = 0; f < kFields; ++f) at(k - 1, f, slot) = arrived[keys[k] & kArrivalMask][f];
}

void BlendedFragments::clear() {
  if (!anyTouched_) return;  // touched_ is all zero then
  for (std::size_t w = 0; w < touched_.size(); ++w)
    for (std::uint64_t bits = touched_[w]; bits != 0; bits &= bits - 1) {
      const std::size_t group = w * 64 + std::size_t(__builtin_ctzll(bits));
      std::fill_n(count_.begin() + std::ptrdiff_t(group * kGroupSlots), kGroupSlots, 0);
    }
  std::fill(touched_.begin(), touched_.end(), 0);
  anyTouched_ = false;
}

}  // namespace quadra
