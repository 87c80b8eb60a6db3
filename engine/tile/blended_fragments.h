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
//
// Every kept fragment is an affine step on what lies behind it,
// dst' = color + keep * dst (premultiplied "over": color = rgb*a and a,
// keep = 1 - a), so two steps compose into one: the overflow fallback below.
#pragma once

#include <cstdint>
#include <vector>

#include "tile/tile_buffers.h"

namespace quadra {

struct BlendedFragment {
  float depth;
  float color[4];      // premultiplied R, G, B and A it adds
  float keep;          // the fraction of what lies behind that shows through
  std::uint32_t next;  // the sample's fragment that arrived before it, or kNoFragment
};

class BlendedFragments {
 public:
  // The budget: a sample holds at most this many fragments. A further one
  // merges the sample's two farthest into one step (exact unless a later
  // fragment falls between those two), so a tile's memory stays within
  // planes * kPixels * kMaxPerSample fragments of 28 bytes, plus 13 bytes a
  // sample for the lists' heads and counts and the order pass.
  static constexpr int kMaxPerSample = 8;
  static constexpr std::uint32_t kNoFragment = 0xFFFFFFFFu;

  // Empty, for a tile of `planes` samples per pixel, before its first
  // blended triangle. depthGreater: reversed depth, where the far fragments
  // hold the smaller depths.
  void begin(int planes, bool depthGreater);
  bool empty() const { return touched_.empty(); }

  // Per sample of plane `plane`, in TileBuffers order: the depth of the
  // latest fragment the order pass saw, and 1 where a fragment arrived
  // strictly behind the one before it (its fragments are kept here), else 0.
  float* latest(int plane) { return &latest_[std::size_t(plane) * TileBuffers::kPixels]; }
  float* late(int plane) { return &late_[std::size_t(plane) * TileBuffers::kPixels]; }
  const float* late(int plane) const { return &late_[std::size_t(plane) * TileBuffers::kPixels]; }

  // Adds a fragment at pixel `pixel` (TileBuffers index) of sample plane
  // `plane`. Out of line: the ISA kernels call it, and an inline copy in each
  // would be one symbol the linker picks from any of them.
  void add(int plane, int pixel, float depth, const float color[4], float keep);

  // Composites every kept sample's fragments over its colour in `planes`
  // (one TileBuffers per sample plane), far to near; fragments at equal
  // depths in the order they arrived. Leaves the store empty.
  void composite(TileBuffers* planes);

 private:
  // A sample's fragments far to near (equal depths in the order they
  // arrived); returns how many.
  int sorted(std::uint32_t slot, BlendedFragment* out) const;
  void addBeyondBudget(std::uint32_t slot, float depth, const float color[4], float keep);

  std::vector<BlendedFragment> pool_;
  std::vector<std::uint32_t> head_;     // per slot (plane * kPixels + pixel): its newest fragment
  std::vector<std::uint8_t> count_;     // per slot
  std::vector<std::uint32_t> touched_;  // slots holding fragments, in the order first touched
  std::vector<float> latest_, late_;    // per slot, for the order pass
  bool depthGreater_ = false;
};

}  // namespace quadra
