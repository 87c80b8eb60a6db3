// TextureSampler: the sampler as a product of its own — batches of lookups
// (position + screen-space derivatives) in, linear RGBA out — running the
// same per-ISA filter code as the tile stage.
#pragma once

#include <cstddef>
#include <optional>

#include "scene/scene.h"
#include "simd/isa.h"
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

// The view a kernel reads for a texture: its sampler's wrap modes and filter,
// or `filter` for both minification and magnification when given. Builds the
// texture's mip chain on first use when the filter needs one.
// executor (optional) builds the mip chain in parallel.
TextureView makeTextureView(const Texture& texture, std::optional<Filter> filter, int maxAniso,
                            const Executor* executor = nullptr);

class TextureSampler {
 public:
  // isa must be supported (isaSupported); filter as for makeTextureView.
  TextureSampler(const Texture& texture, std::optional<Filter> filter, int maxAniso, Isa isa);

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
