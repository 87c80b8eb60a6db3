// The anisotropic filter's definition and knobs (the kernel is
// sampleAnisotropic in texture/sample_lanes.h; tests/test_anisotropic.cpp
// checks it against this definition evaluated in double).
//
// The footprint is the unit pixel square mapped through the Jacobian J; its
// singular values are major >= minor, (ex, ey) the screen-space singular
// vector of major. The spec's N = min(ceil(major / minor), maxAniso) gives
// the level λ = log2(major / N) whose texels fit the footprint's width.
//
// Taps: bilinear lookups on a line through the centre along the major axis,
// tap j of a run of n at o_j = (j + 1/2) / n - 1/2 of the line from the
// centre, its weight normalized over the run.
// - Below kBlendBelowRatio:1 the two levels around λ are read and blended by
//   its fraction, each with equal taps over the line (major long), as the
//   spec places its probes.
// - Above it the nearest level alone, and the line is the footprint's whole
//   shadow on the major axis: J's columns project onto it as a = major |ex|
//   and b = major |ey|, and the parallelogram's shadow is the convolution of
//   two boxes of those widths, a trapezoid a + b long whose sides ramp over
//   min(a, b); tap j weighs clamp((1/2 - |o_j|) (a + b) / min(a, b), 0, 1),
//   the trapezoid there. Equal taps over major instead miss the ends of a
//   sheared footprint and overweight its middle: RMSE 0.0102 instead of
//   0.0077 at 8-16:1, 0.0116 instead of 0.0080 at 32-64:1 (7.6 taps a lookup
//   instead of 8.8). Near-isotropic footprints are the other way round: the
//   trapezoid is a poor model of a nearly square footprint, and blended
//   trapezoids give the smooth textures 0.0051 instead of 0.0048.
// - Spacing: while major / N < 1 (magnified across the minor axis) level 0 is
//   read with taps major / kMagnifiedTaps apart, but at least major / N and
//   at most a texel; else kTapSpacing (kBlendedTapSpacing) texels of the
//   level read (floor(λ) and floor(λ) + 1 when blended, else round(λ)).
// - n = the line over the spacing, rounded up to whole chunks (kChunk)
//   beyond a single tap. The spacing comes from λ before the LOD controls:
//   a bias moves the level read, not the number of taps.
//
// The figures below: `quadra report textures` (seed 1, its five textures,
// RMSE against the box ideal), and taps (bilinear lookups) per lookup on its
// footprint stream. With these knobs: RMSE 0.0117 for 8.8 taps, where the
// previous filter (N trilinear probes at λ, 2 N bilinear lookups) had 0.0134
// for 13.6; each texture, and each scale and anisotropy bucket, at or below
// it.
#pragma once

namespace quadra::aniso {

// Spacing of the taps along the major axis, in texels of the level they read
// (one level). Below about 1.2 the level's bilinear signal is sampled with no
// texel skipped; wider, whole texels fall between taps and the error jumps:
// 1.05 gives RMSE 0.0116 for 9.4 taps, 1.13 0.0117 for 8.8, 1.3 0.0122 for
// 8.0 (the 2-8 scale bucket above the previous filter's), 1.5 0.0144.
constexpr float kTapSpacing = 1.13f;

// The same where two levels are blended. 0.95 gives 0.0117; 1.0 lets the
// 1/8-1/2 scale bucket rise above the previous filter's (0.00144 against
// 0.00140); 0.75 costs 0.4 taps for 0.0116.
constexpr float kBlendedTapSpacing = 0.95f;

// Taps over the major axis where the footprint is magnified across its minor
// axis. 3.25 holds the 1/8-1/2 scale bucket at 0.00125 (the previous
// filter's N probes: 0.00140; one bilinear tap: 0.0055) for 4.3 taps there,
// and the 4-8:1 bucket at 0.0101 (0.0102); 3 leaves it at 0.01016 against
// 0.01017, 2 above it (0.0102); 4 costs 5.2 taps there for 0.0115 overall.
// Spacing them major / N apart (at least 1/8 texel) as the previous filter
// did costs 8.0 taps a lookup on the footprints from 1/2 to 2 texels.
constexpr float kMagnifiedTaps = 3.25f;

// Below this anisotropy two levels are blended, and for every footprint
// where maxAniso is below it: a single level then jumps by a whole level
// between footprints N clamps alike (--aniso 2 gave RMSE 0.0267 on the
// report against the previous filter's 0.0260; blended: see docs/texture-
// filters.md). Near-isotropic footprints
// have few taps, and without the blend the jump between levels costs
// accuracy (never blending: 0.0202 at 1-2:1 and 0.0162 at 2-4:1 against the
// previous filter's 0.0217 and 0.0154, and 0.0068 at 128-512 texels against
// 0.0062; below 3:1 the smooth texture gets 0.00495 instead of 0.00480).
constexpr float kBlendBelowRatio = 4.0f;

// Taps one SIMD lane runs for one lookup before it takes the next job (the
// kernel packs jobs from every lookup of a lane group densely, so no lane
// idles while another lookup finishes). Chunks of 2 and 1 cost the same on
// AVX-512 (1 runs twice the per-job setup, 2 wastes a lane where a run has
// an odd number of taps, hence the rounding up above); 3 and 4 are 5-8%
// slower.
constexpr int kChunk = 2;

// A bound the taps per run never reach (at most 2 N + 1: the spacing is at
// least major / (sqrt(2) N) and the shadow at most sqrt(2) major, N <= 64);
// it only keeps hostile footprints finite.
constexpr float kMaxTapsPerRun = 130.0f;

}  // namespace quadra::aniso
