// Test helpers shared by the sampler tests: seeded random lookups (positions
// across wrap seams, footprints from magnification to strong minification and
// anisotropy) and one batch of them through a TextureSampler.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "texture/texture_sampler.h"

namespace quadra {

// One lookup: u, v, dudx, dvdx, dudy, dvdy.
using Lookup = std::array<float, 6>;

// Footprints with the major axis 2^-10 .. 2^1 texture widths long, anisotropy
// up to 64, every orientation; positions in [-2, 3) so every wrap seam is crossed.
inline std::vector<Lookup> randomLookups(int count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> position(-2.0f, 3.0f), logScale(-10.0f, 1.0f),
      angle(0.0f, 6.2831853f), stretch(0.0f, 6.0f);
  std::vector<Lookup> lookups;
  for (int i = 0; i < count; ++i) {
    const float a = angle(rng), major = std::exp2(logScale(rng)),
                minor = major / std::exp2(stretch(rng));
    lookups.push_back({position(rng), position(rng), major * std::cos(a), major * std::sin(a),
                       -minor * std::sin(a), minor * std::cos(a)});
  }
  return lookups;
}

// A sampler with both wrap modes set and a border colour distinct from every
// test texture's texels.
inline SamplerState samplerWith(WrapMode wrap,
                                const std::array<float, 4>& border = {0.25f, 0.0f, 0.0f, 1.0f}) {
  SamplerState state;
  state.wrapU = state.wrapV = wrap;
  for (int c = 0; c < 4; ++c) state.borderColor[c] = border[c];
  return state;
}

// RGBA of every lookup, in order, through the given filter and kernel path
// (float texels through hardware gathers when asked).
inline std::vector<float> sampleAll(const Texture& texture, Filter filter, Isa isa,
                                    const std::vector<Lookup>& lookups, bool gatherTexels = false) {
  std::vector<float> column[6];
  for (const Lookup& l : lookups)
    for (int i = 0; i < 6; ++i) column[i].push_back(l[i]);
  const LookupBatch batch{column[0].data(), column[1].data(), column[2].data(), column[3].data(),
                          column[4].data(), column[5].data(), lookups.size()};
  std::vector<float> rgba(lookups.size() * 4);
  FilterSettings settings(filter, 16);
  settings.gatherTexels = gatherTexels;
  TextureSampler(texture, settings, isa).sample(batch, 0, lookups.size(), rgba.data());
  return rgba;
}

}  // namespace quadra
