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
#include <vector>

#include "tile/tile_buffers.h"

namespace quadra {

struct BlendedFragment {
  float depth;
  float color[4];  // premultiplied R, G, B and A it adds
  float keep;      // the fraction of what lies behind that shows through
};

class BlendedFragments {
 public:
  // The budget: a sample holds at most this many fragments. A further one
  // merges the sample's two farthest into one step (exact unless a later
  // fragment falls between those two). The store is kMaxPerSample layers of
  // one fragment per sample, fragment k of a sample in layer k: planes *
  // kPixels * kMaxPerSample fragments of 24 bytes, allocated and zeroed
  // once for a plane count, plus 17 bytes a sample for the counts, the
  // touched list, the order pass and the covered samples (4 bytes a pixel,
  // counted per sample).
  static constexpr int kMaxPerSample = 8;
  static constexpr std::size_t kBytesPerSample = kMaxPerSample * sizeof(BlendedFragment) + 17;

  // Empty, for a tile of `planes` samples per pixel, before its first
  // blended triangle. depthGreater: reversed depth, where the far fragments
  // hold the smaller depths.
  void begin(int planes, bool depthGreater);
  bool empty() const { return touchedCount_ == 0; }

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

  // Composites every kept sample's fragments over its colour in `planes`
  // (one TileBuffers per sample plane), far to near; fragments at equal
  // depths in the order they arrived. Leaves the store empty.
  void composite(TileBuffers* planes);

 private:
  // Fragment `layer` of sample slot (plane * kPixels + pixel). Layers rather
  // than a pool of linked nodes: consecutive samples' fragments arrive
  // together (a triangle's pixels in turn) and are composited together, and
  // both then run along each layer, where walking per-sample lists through
  // a shared pool was a chain of dependent loads, a quarter of
  // intersecting-glass's frame (perf, 1 thread).
  BlendedFragment& at(int layer, std::uint32_t slot) {
    return layers_[std::size_t(layer) * slots_ + slot];
  }
  const BlendedFragment& at(int layer, std::uint32_t slot) const {
    return layers_[std::size_t(layer) * slots_ + slot];
  }
  void addBeyondBudget(std::uint32_t slot, const BlendedFragment& newest);
  void clearTouched();  // every kept sample's count back to 0

  std::unique_ptr<BlendedFragment[]> layers_;  // kMaxPerSample * slots_
  std::size_t slots_ = 0;
  std::vector<std::uint8_t> count_;  // per slot
  // The slots holding fragments, in the order first touched: room for every slot.
  std::unique_ptr<std::uint32_t[]> touched_;
  std::size_t touchedCount_ = 0;
  std::vector<float> latest_, late_;    // per slot, for the order pass
  bool lateMarked_ = false;             // an order pass ran since late_ was cleared
  std::vector<std::uint32_t> covered_;  // per pixel
  bool depthGreater_ = false;
};

}  // namespace quadra
