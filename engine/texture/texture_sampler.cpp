// TextureView construction (shared with the renderer) and the dispatch of
// batch lookups to the per-ISA kernel.
#include "texture/texture_sampler.h"

#include <algorithm>

#include "texture/image.h"
#include "texture/padded_level.h"
#include "texture/ripmap.h"
#include "texture/summed_area.h"

namespace quadra {

TextureView makeTextureView(const Texture& texture, const FilterSettings& settings,
                            const Executor* executor) {
  const std::optional<Filter>& filter = settings.filter;
  TextureView view;
  const SamplerState& sampler = texture.sampler();
  view.wrapU = sampler.wrapU;
  view.wrapV = sampler.wrapV;
  std::copy(std::begin(sampler.borderColor), std::end(sampler.borderColor), view.border);
  view.premultiplied = texture.alpha().premultiplied();
  if (view.premultiplied)
    for (int c = 0; c < 3; ++c) view.border[c] *= view.border[3];
  view.minFilter = filter.value_or(sampler.minFilter);
  // An explicit filter decides magnification too: nearest stays nearest.
  view.magLinear = filter ? *filter != Filter::Nearest : sampler.magLinear;
  view.minLinear = filter ? true : sampler.minLinear;
  view.maxAniso = settings.maxAniso;
  view.gatherTexels = settings.gatherTexels;
  const float ruleOffset = view.minFilter == Filter::Trilinear && settings.lodRule == LodRule::Box
                               ? kBoxLodOffset
                               : 0.0f;
  view.setLodControls(settings.lodBias + ruleOffset, settings.minLod, settings.maxLod);
  view.format = texture.storage();
  view.srgbTable = srgb8ToLinearTable();
  view.levels[0] = texture.sampledLevel0(executor).view();
  view.levelCount = 1;
  if (needsMips(view.minFilter)) {
    const std::vector<PaddedLevel>& mips = texture.sampledMipLevels(executor);
    view.levelCount = std::min(int(mips.size()) + 1, TextureView::kMaxLevels);
    for (int i = 1; i < view.levelCount; ++i) view.levels[i] = mips[std::size_t(i - 1)].view();
  }
  if (view.minFilter == Filter::SummedArea) view.summedArea = &texture.summedAreaTable(executor);
  if (view.minFilter == Filter::Ripmap) {
    const Ripmap& ripmap = texture.ripmap(executor);
    view.ripLevels = ripmap.levels.data();
    view.ripCountX = ripmap.countX;
    view.ripCountY = ripmap.countY;
  }
  return view;
}

namespace {

SampleBatchKernel kernelFor(Isa isa) {
  switch (isa) {
    case Isa::Avx512:
      return sampleKernelAvx512();
    case Isa::Avx2:
      return sampleKernelAvx2();
    case Isa::Sse2:
      return sampleKernelSse2();
    case Isa::Scalar:
      break;
  }
  return sampleKernelScalar();
}

}  // namespace

TextureSampler::TextureSampler(const Texture& texture, const FilterSettings& settings, Isa isa)
    : view_(makeTextureView(texture, settings)), isa_(isa), kernel_(kernelFor(isa)) {}

void TextureSampler::sample(const LookupBatch& lookups, std::size_t begin, std::size_t end,
                            float* rgba) const {
  kernel_(view_, lookups, begin, end, rgba);
}

}  // namespace quadra
