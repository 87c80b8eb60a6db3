// Where an environment comes from: a built-in's name or a panorama file
// (Radiance .hdr or OpenEXR, chosen by the file's first bytes), checked and
// made safe to light with. The shading stage itself sees only the resulting
// EnvironmentImage; the decoders are io/'s. The rules (size, texel values)
// are docs/lighting.md "Environments".
#pragma once

#include <cstdint>
#include <string>

#include "core/memory_budget.h"
#include "shading/environment_image.h"

namespace quadra {

// The largest texel value kept: larger ones, +inf included, become it. 2^32
// leaves float room for what preprocessing does with texels (a sum over 2^28
// of them times 4 pi, a square) without overflowing to inf; real panoramas
// stay far below it (the brightest suns in unclipped HDRIs are near 1e5-1e6).
constexpr float kMaxEnvironmentRadiance = 4294967296.0f;

// How many texel values (channels, not texels) the texel rule changed.
struct TexelRepairs {
  std::uint64_t notANumber = 0;  // NaN -> 0
  std::uint64_t negative = 0;    // below 0, -inf included -> 0
  std::uint64_t clamped = 0;     // above kMaxEnvironmentRadiance, +inf included -> it
  std::uint64_t total() const { return notANumber + negative + clamped; }
};

// The texel rule on `count` values: NaN and negative values become 0 (-0
// becomes +0, uncounted), values above kMaxEnvironmentRadiance become it.
TexelRepairs applyTexelRule(float* values, std::size_t count);

// A panorama needs at least 2 texels and at most kMaxImagePixels; throws
// Error("<name>: <problem>") otherwise.
void checkEnvironmentSize(const std::string& name, std::int64_t width, std::int64_t height);

// A panorama file, decoded and put through checkEnvironmentSize (before any
// pixel is allocated), the budget (its encoded bytes for .hdr, then its
// texels) and the texel rule; `repairs` (when given) receives what the rule
// changed. Throws Error("<path>: <problem>") for a missing, unreadable,
// truncated or malformed file; the budget's Error when over it.
EnvironmentImage readEnvironmentFile(const std::string& path, MemoryBudget& budget,
                                     TexelRepairs* repairs = nullptr);

// "builtin:NAME" (builtinEnvironment, its texels charged to the budget) or a
// file path (readEnvironmentFile).
EnvironmentImage loadEnvironment(const std::string& source, MemoryBudget& budget,
                                 TexelRepairs* repairs = nullptr);

}  // namespace quadra
