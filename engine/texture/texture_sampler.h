// TextureSampler: the sampler as a product of its own — batches of lookups
// (position + screen-space derivatives) in, linear RGBA out — running the
// same per-ISA filter code as the tile stage.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "simd/isa.h"
#include "texture/texture.h"
#include "texture/texture_view.h"

namespace quadra {

// Structure-of-arrays lookups: normalized (u, v) and the Jacobian of (u, v)
// with respect to screen x and y, per lookup.
struct LookupBatch {
  const float* u = nullptr;
  const float* v = nullptr;
  const float* dudx = nullptr;
  const float* dvdx = nullptr;
  const float* dudy = nullptr;
  const float* dvdy = nullptr;
  std::size_t count = 0;
};

// How a draw or a batch filters a texture, beyond the texture's own sampler.
struct FilterSettings {
  std::optional<Filter> filter;  // set: this filter for minification and magnification
  int maxAniso = 16;
  float lodBias = 0.0f;
  float minLod = 0.0f;
  float maxLod = 1000.0f;
  LodRule lodRule = LodRule::Box;
  // Hardware gathers for float texels (TextureView::gatherTexels): off, as
  // measured faster on every ISA here; for benchmarks.
  bool gatherTexels = false;

  FilterSettings(std::optional<Filter> f = std::nullopt, int aniso = 16)
      : filter(f), maxAniso(aniso) {}
};

// The view a kernel reads for a texture: its sampler's wrap modes and filter,
// overridden by `settings`. Builds the texture's mip chain on first use when
// the filter needs one (in parallel on `executor` when given).
TextureView makeTextureView(const Texture& texture, const FilterSettings& settings,
                            const Executor* executor = nullptr);

// The bytes of what makeTextureView reads for this texture and filter, built
// yet or not (the renderer charges them to its memory budget before the view
// is made): level 0 in the storage format, the premultiplied copy of level 0
// for a texture whose alpha is premultiplied, and the mip chain (linear float
// and storage format), the summed-area table or the ripmap when the filter
// reads them. From the sizes alone, so opaque images' copies count too.
std::uint64_t textureViewBytes(const Texture& texture, const FilterSettings& settings);

class TextureSampler {
 public:
  // isa must be supported (isaSupported); settings as for makeTextureView.
  TextureSampler(const Texture& texture, const FilterSettings& settings, Isa isa);

  Isa isa() const { return isa_; }
  const TextureView& view() const { return view_; }

  // Lookups [begin, end) into rgba[4*i .. 4*i+3]. Reentrant: threads may
  // sample disjoint ranges of one batch at once.
  void sample(const LookupBatch& lookups, std::size_t begin, std::size_t end, float* rgba) const;

 private:
  TextureView view_;
  Isa isa_;
  void (*kernel_)(const TextureView&, const LookupBatch&, std::size_t, std::size_t, float*);
};

// Per-ISA batch kernels (texture/sample_kernel_impl.h).
using SampleBatchKernel = void (*)(const TextureView&, const LookupBatch&, std::size_t, std::size_t,
                                   float*);
SampleBatchKernel sampleKernelScalar();
SampleBatchKernel sampleKernelSse2();
SampleBatchKernel sampleKernelAvx2();
SampleBatchKernel sampleKernelAvx512();

}  // namespace quadra
