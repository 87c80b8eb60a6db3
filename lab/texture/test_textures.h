// Textures generated in code for measuring filters: high-frequency ones that
// punish aliasing (a fine checker, a zone plate, per-texel value noise) and a
// smooth natural-looking one (low-frequency fractal value noise). All tile
// seamlessly except the zone plate, whose seam is part of the test.
#pragma once

#include <cstdint>

#include "texture/image.h"

namespace quadra {

// Squares of `cellTexels` texels, 1 (white) and 0 (black), alpha 1; the square
// at the top-left corner is white.
Image makeCheckerTexture(int width, int height, int cellTexels);
// 0.5 + 0.5 cos(pi r^2 / size) about the centre: the local frequency grows
// linearly from 0 to the Nyquist limit (0.5 cycles per texel) at the edges.
Image makeZonePlateTexture(int width, int height);
// An independent uniform random value per texel and channel (RGB), alpha 1.
Image makeValueNoiseTexture(int width, int height, std::uint64_t seed);
// Fractal value noise: octaves of lattice noise with periods from size/4 down
// to 8 texels, smoothly interpolated and periodic, coloured; alpha 1.
Image makeSmoothNoiseTexture(int width, int height, std::uint64_t seed);

}  // namespace quadra
