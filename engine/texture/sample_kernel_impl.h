// Batch texture lookups over SIMD lanes, compiled once per ISA: loads a lane
// group of lookups, runs the same filter code as the tile stage, and writes
// interleaved RGBA. Included only by the generated sample_kernel_<isa>.cpp.
#pragma once

#include <algorithm>

#include "simd/kernel_isa.h"
#include "texture/sample_lanes.h"
#include "texture/texture_sampler.h"

namespace quadra {

// Compiled once per ISA with that ISA's tile kernels (tile/tile_kernel_impl.h).
extern template Rgba<simd::Lanes<QUADRA_KERNEL_ARCH>> sampleTexture(
    const TextureView& view, const simd::Lanes<QUADRA_KERNEL_ARCH>::F& u,
    const simd::Lanes<QUADRA_KERNEL_ARCH>::F& v,
    const UvDerivatives<simd::Lanes<QUADRA_KERNEL_ARCH>>& d);

namespace QUADRA_KERNEL_NAMESPACE {
namespace {

using L = simd::Lanes<QUADRA_KERNEL_ARCH>;
using F = L::F;
constexpr int W = L::kWidth;

// Lanes [first, first + W) of one input array; a short tail repeats its last
// lookup so every lane holds a valid one.
F loadLanes(const float* values, std::size_t first, std::size_t end) {
  if (first + W <= end) return F::load_unaligned(values + first);
  alignas(64) float padded[W];
  for (int k = 0; k < W; ++k) padded[k] = values[std::min(first + k, end - 1)];
  return F::load_aligned(padded);
}

void sampleBatch(const TextureView& view, const LookupBatch& in, std::size_t begin, std::size_t end,
                 float* rgba) {
  for (std::size_t first = begin; first < end; first += W) {
    const F u = loadLanes(in.u, first, end), v = loadLanes(in.v, first, end);
    const UvDerivatives<L> d{loadLanes(in.dudx, first, end), loadLanes(in.dvdx, first, end),
                             loadLanes(in.dudy, first, end), loadLanes(in.dvdy, first, end)};
    const Rgba<L> c = sampleTexture<L>(view, u, v, d);
    alignas(64) float channel[4][W];
    c.r.store_aligned(channel[0]);
    c.g.store_aligned(channel[1]);
    c.b.store_aligned(channel[2]);
    c.a.store_aligned(channel[3]);
    const std::size_t count = std::min<std::size_t>(W, end - first);
    for (std::size_t k = 0; k < count; ++k)
      for (int ch = 0; ch < 4; ++ch) rgba[(first + k) * 4 + ch] = channel[ch][k];
  }
}

}  // namespace
}  // namespace QUADRA_KERNEL_NAMESPACE

SampleBatchKernel QUADRA_KERNEL_ENTRY(sampleKernel)() {
  return &QUADRA_KERNEL_NAMESPACE::sampleBatch;
}

}  // namespace quadra
