// BlendedFragments: a tile's blended ("over") fragments that arrive out of
// depth order, kept per sample while the tile's draws are rasterized and
// composited afterwards over the sample's colour in exact depth order, far
// to near. Sorting draws by their centres orders whole draws at best;
// surfaces that interpenetrate or overlap themselves on screen need the
// order per sample, which this is.
//
// Most samples' fragments arrive far to near already (the renderer sorts
// blended draws back to front), and blending those at once is exact. So a
// first pass over the tile's blended triangles, depth only, marks the
// samples where a fragment arrives strictly behind the one before it
// ("late"); the shading pass blends the other samples' fragments at once and
// keeps only the late samples' fragments here. The two give the same bits.
// A tile whose blended triangles' depth ranges show that each arrives
// nowhere behind those before it has no late sample and skips the first
// pass (tile_stage.cpp blendedArriveFarToNear).
//
// Every kept fragment is an affine step on what lies behind it,
// dst' = color + keep * dst (premultiplied "over": color = rgb*a and a,
// keep = 1 - a), so two steps compose into one: the overflow fallback below.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#include "tile/tile_buffers.h"

namespace quadra {

class BlendedFragments {
 public:
  // The budget: a sample holds at most this many fragments. A further one
  // merges the sample's two farthest into one step (exact unless a later
  // fragment falls between those two). The store is kMaxPerSample layers of
  // one fragment per sample, fragment k of a sample in layer k, each layer
  // kFields planes of one float per sample slot (structure of arrays, so a
  // lane group's fragments of one layer load as one register each):
  // planes * kPixels * kMaxPerSample fragments of 24 bytes, allocated and
  // zeroed once for a plane count, plus 13 bytes a sample for the counts,
  // the order pass and the covered samples (4 bytes a pixel, counted per
  // sample), and a bit per kGroupSlots samples for the touched groups.
  static constexpr int kMaxPerSample = 8;
  enum Field { kDepth, kRed, kGreen, kBlue, kAlpha, kKeep, kFields };
  static constexpr std::size_t kBytesPerSample = kMaxPerSample * kFields * sizeof(float) + 13;
  // Fragments are tracked, composited and cleared by groups of this many
  // consecutive slots: a lane group of every ISA lies within one.
  static constexpr int kGroupSlots = 16;

  // Empty, for a tile of `planes` samples per pixel, before its first
  // blended triangle. depthGreater: reversed depth, where the far fragments
  // hold the smaller depths.
  void begin(int planes, bool depthGreater);
  bool empty() const { return !anyTouched_; }
  bool depthGreater() const { return depthGreater_; }

  // Before the tile's order pass (tile_stage.cpp skips it where no sample
  // can be late): every sample's latest depth at the far end. Without it the
  // tile's samples are none of them late.
  void beginOrderPass();

  // Per sample of plane `plane`, in TileBuffers order: the depth of the
  // latest fragment the order pass saw, and 1 where a fragment arrived
  // strictly behind the one before it (its fragments are kept here), else 0.
  float* latest(int plane) { return &latest_[std::size_t(plane) * TileBuffers::kPixels]; }
  float* late(int plane) { return &late_[std::size_t(plane) * TileBuffers::kPixels]; }
  const float* late(int plane) const { return &late_[std::size_t(plane) * TileBuffers::kPixels]; }
  // Whether the tile ran the order pass: else no sample is late.
  bool orderPassRan() const { return lateMarked_; }

  // Per pixel, in TileBuffers order, bit k for sample k: the samples the
  // triangle being shaded per pixel covers (TileKernels::coverBlended). Zero
  // between triangles: shadeBlendedPixels clears every word coverBlended set
  // (the triangle's box), so it is zeroed only when first allocated.
  std::uint32_t* covered() { return covered_.data(); }

  // Adds a lane group's fragments to sample plane `plane`: for each lane k
  // set in `lanes`, one at pixel index + k (TileBuffers order) with depth
  // depth[k], premultiplied colour color[c][k] and keep[k]. Out of line
  // (the ISA kernels call it, and an inline copy in each would be one symbol
  // the linker picks from any of them), so a call a group, not a fragment.
  void add(int plane, int index, std::uint32_t lanes, const float* depth,
           const float* const color[4], const float* keep);

  // The layers as the kernels read and write them (deferOver adds a lane
  // group's fragments of one layer at once; compositeBlended reads the store
  // and then clears it). Slot s is sample plane s / kPixels, pixel s %
  // kPixels. field(layer, f)[s]: field f of the sample's fragment `layer`
  // (its arrival order, below counts()[s], how many it holds); 64-byte
  // aligned, as TileBuffers' planes. A kernel that writes fragments of a
  // lane group starting at slot s calls markTouched(s) too.
  // touchedGroups(): bit g of word g / 64 set where slots [g * kGroupSlots,
  // (g + 1) * kGroupSlots) may hold fragments; the others hold none.
  const float* field(int layer, int f) const {
    return &layers_[(std::size_t(layer) * kFields + std::size_t(f)) * fieldStride_];
  }
  float* field(int layer, int f) {
    return &layers_[(std::size_t(layer) * kFields + std::size_t(f)) * fieldStride_];
  }
  const std::uint8_t* counts() const { return count_.data(); }
  std::uint8_t* counts() { return count_.data(); }
  void markTouched(std::size_t slot) {
    touched_[slot / kGroupSlots / 64] |= std::uint64_t(1) << (slot / kGroupSlots % 64);
    anyTouched_ = true;
  }
  const std::vector<std::uint64_t>& touchedGroups() const { return touched_; }
  void clear();  // every kept sample's count back to 0: empty

 private:
  // Layers rather than a pool of linked nodes: consecutive samples'
  // fragments arrive together (a triangle's pixels in turn) and are
  // composited together, and both then run along each layer, where walking
  // per-sample lists through a shared pool was a chain of dependent loads, a
  // quarter of intersecting-glass's frame (perf, 1 thread).
  float& at(int layer, int f, std::uint32_t slot) {
    return layers_[(std::size_t(layer) * kFields + std::size_t(f)) * fieldStride_ + slot];
  }
  void addBeyondBudget(std::uint32_t slot, const float (&newest)[kFields]);

  struct AlignedDelete {
    void operator()(float* p) const { ::operator delete[](p, std::align_val_t(64)); }
  };
  // kMaxPerSample * kFields planes of fieldStride_ floats, 64-byte aligned.
  std::unique_ptr<float[], AlignedDelete> layers_;
  std::size_t slots_ = 0, fieldStride_ = 0;
  std::vector<std::uint8_t> count_;     // per slot
  std::vector<std::uint64_t> touched_;  // per kGroupSlots slots, a bit
  bool anyTouched_ = false;
  std::vector<float> latest_, late_;    // per slot, for the order pass
  bool lateMarked_ = false;             // an order pass ran since late_ was cleared
  std::vector<std::uint32_t> covered_;  // per pixel
  bool depthGreater_ = false;
};

}  // namespace quadra
