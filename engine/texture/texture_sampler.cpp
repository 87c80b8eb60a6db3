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

std::uint64_t textureViewBytes(const Texture& texture, const FilterSettings& settings) {
  const Filter filter = settings.filter.value_or(texture.sampler().minFilter);
  const std::uint64_t stored = std::uint64_t(bytesPerTexel(texture.storage()));
  constexpr std::uint64_t kLinearTexel = 4 * sizeof(float);
  const std::uint64_t w = std::uint64_t(texture.image().width);
  const std::uint64_t h = std::uint64_t(texture.image().height);
  std::uint64_t bytes = (w + 1) * h * stored;  // PaddedLevel rows are width + 1 long
  if (texture.alpha().premultiplied()) bytes += w * h * kLinearTexel;
  // Levels 1.. of a chain, max(1, size >> l) per side (mip_chain.h).
  const auto chain = [](std::uint64_t size, int level) {
    return std::max<std::uint64_t>(1, size >> level);
  };
  if (needsMips(filter)) {
    for (int l = 1; chain(w, l - 1) > 1 || chain(h, l - 1) > 1; ++l)
      bytes += chain(h, l) * (chain(w, l) * kLinearTexel + (chain(w, l) + 1) * stored);
  }
  if (filter == Filter::SummedArea) bytes += w * h * 32;  // summed_area.h: 32 bytes a texel
  if (filter == Filter::Ripmap) {
    for (int i = 0; i == 0 || chain(w, i - 1) > 1; ++i)
      for (int j = 0; j == 0 || chain(h, j - 1) > 1; ++j)
        bytes += chain(h, j) * (chain(w, i) * kLinearTexel + (chain(w, i) + 1) * stored);
  }
  return bytes;
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
