// The area filter's plan for one lookup (the per-lane loop is sampleArea in
// sample_lanes.h): the DESIGN.md ideal, the bilinear reconstruction averaged
// over the pixel's footprint parallelogram, taken as the mean of a midpoint
// grid of bilinear samples. The grid has kAreaSamplesPerTexel samples per
// texel along each edge of the parallelogram, on the finest mip level where
// that grid fits kAreaSampleBudget samples; level 0 (exact up to the
// quadrature) whenever the footprint is that small, a box-filtered level only
// when it spans many of that level's texels, so its prefilter matters little.
#pragma once

#include "texture/texture_view.h"

namespace quadra {

// The budget trades cost for the box-prefilter error of the coarser levels
// (quadra report textures, seed 1, AVX-512, this project's VM): 256 samples
// RMSE 0.0079 at ~0.55 us per lookup, 512: 0.0058 at ~0.9 us, 1024: 0.0037 at
// ~1.4 us (anisotropic-16: 0.0149 at ~0.12 us). 1024 keeps level 0 for
// footprints up to 16x16 texels.
constexpr int kAreaSampleBudget = 1024;
constexpr int kAreaSamplesPerTexel = 2;
// Even a sub-texel footprint averages a curved surface (the bilinear cross
// term, the kinks at texel centres): never fewer than 4 x 4 samples.
constexpr int kAreaMinSamples = 4;

struct AreaGrid {
  int level = 0;
  int columns = 1;  // samples along the footprint's screen-x edge (dudx, dvdx)
  int rows = 1;     // samples along its screen-y edge (dudy, dvdy)
};

// NaN or infinite derivatives give the last level and a single sample.
AreaGrid planAreaGrid(const TextureView& view, float dudx, float dvdx, float dudy, float dvdy);

}  // namespace quadra
