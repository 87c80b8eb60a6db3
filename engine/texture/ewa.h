// EWA: Heckbert's elliptical weighted average on the mip pyramid, one lookup
// at a time. The Gaussian-weighted average of the texels inside the pixel's
// footprint ellipse (eccentricity clamped to the view's maxAniso), on the two
// levels around the one where the ellipse's minor axis spans about a texel,
// blended by the fractional level.
//
// Plain scalar code compiled once (not per ISA): the per-ISA kernels call it
// lane by lane, so every path gets the same bits.
#pragma once

#include "texture/texture_view.h"

namespace quadra {

// (u, v) normalized; derivatives are the Jacobian of (u, v) per pixel.
// rgba receives linear RGBA. NaN/Inf inputs read as position 0 / a point footprint.
void ewaLookup(const TextureView& view, float u, float v, float dudx, float dvdx, float dudy,
               float dvdy, float rgba[4]);

}  // namespace quadra
