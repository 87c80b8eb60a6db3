// EWA: an elliptical weighted average, Heckbert's filter, made to match its
// own ideal. The filter is a radial weight in screen space (EwaShape) whose
// image under the Jacobian is the footprint ellipse; its ideal is that weight
// integrated against the bilinear level-0 texture (lab/texture/ewa_ideal.h).
// This file owns the definition and each lookup's plan (scalar code compiled
// once, so every ISA path plans alike); the kernels in texture/sample_lanes.h
// (sampleEwa) sum the plan's samples in SIMD lanes, in a fixed order.
//
// Two ways to sum, by the ellipse's minor radius after the eccentricity
// clamp (maxAniso):
// - below kEwaGridBelow level-0 texels (small or needle-thin ellipses): a grid
//   of bilinear level-0 samples over the screen disk, along the footprint's
//   singular vectors, kEwaGridPerTexel per texel of each axis (at least
//   kEwaMinGrid): the ideal's own integral on a grid, exact up to the
//   quadrature (the eccentricity clamp is not needed here: the minor radius
//   bounds the work);
// - else texel centres on the level where the minor radius spans
//   kEwaTexelsPerRadius texels, the ellipse's quadratic form corrected for
//   the level's box prefilter and for the bilinear reconstruction the ideal
//   has (texel-centre sums of a box-filtered level add (s^2 - 1) / 12 of
//   variance per axis, s texels of level 0 to the texel; the reconstruction
//   adds 1/6; the ellipse gives the difference back, over the shape's
//   variance per unit radius).
//
// The old filter (pbrt's: semi-axes of one pixel, the level where the minor
// axis spans a texel, a unit disk of level texels added for reconstruction)
// had halved its semi-axes to the pixel's half width but kept the level and
// the added disk: at the level read the minor semi-axis spanned half a
// texel and the added unit disk dominated, so its Gaussian was about 2.2x
// too wide across the footprint, and its weights jumped to 0 at the rim.
// It was further from the ideal of its own shape (RMSE 0.0232; the report's
// stream, 1536 footprints per texture, lab/texture/ewa_ideal.h) than from
// the box ideal (0.0216). Now, on 128² noise and
// a 2-texel checker (Ewa.WithinAFifthOfItsDoublePrecisionIdealsErrorAgainstTheBox):
// 0.0035 / 0.0060 from the ideal, and 1.17x / 1.12x the ideal's own
// distance to the box ideal; `quadra report textures`: 0.0069 against the
// box (was 0.0216).
#pragma once

#include <cmath>

#include "texture/texture_view.h"

namespace quadra {

// The filter's shape in screen space: a radial weight over the disk of
// `radius` pixels around the pixel centre (its image under the Jacobian is
// the footprint ellipse), w(r^2) = exp(-alpha r^2), less exp(-alpha) where
// zeroAtRim (so the weight falls to 0 at the rim), with r the distance over
// the radius; 0 from the rim on.
struct EwaShape {
  double radius = 0.8;
  double alpha = 2.0;
  bool zeroAtRim = true;
};

// quadra's EWA: radius 0.8 gives the weight the per-axis variance of the
// unit pixel box (0.136 r^2 = 0.087 against 1/12), and its ideal is the one
// closest to the box ideal: RMSE 0.0063 on the report's stream (radius 0.7:
// 0.0106, 0.9: 0.0085, 1.0 as pbrt: 0.0133; alpha 1 or 3: 0.0064, 0.0086;
// radius 0.5 with the rim cut, the old filter: 0.0216).
inline constexpr EwaShape kEwaShape{0.8, 2.0, true};
// The weight's variance per axis over a unit radius (computed for kEwaShape).
inline constexpr double kEwaShapeVariance = 0.13608;

inline double ewaWeight(const EwaShape& shape, double r2) {
  if (!(r2 < 1.0)) return 0.0;
  return std::exp(-shape.alpha * r2) - (shape.zeroAtRim ? std::exp(-shape.alpha) : 0.0);
}

// The knobs, measured on the report's stream against the ideal / the box
// ideal, with the samples each lookup sums:
// kEwaGridBelow 2 and kEwaGridPerTexel 2: 0.0033 / 0.0071 for 76 samples;
// per texel 1.5: 0.0038 / 0.0073 for 65; below 1.5: 0.0038 / 0.0073 for 68.
// kEwaTexelsPerRadius 2.5: 0.0026 / 0.0067 for 101; 2: 0.0033 / 0.0071 for
// 76 (1.13x the ideal's 0.0063 against the box, but 1.26x on 128² noise, the
// test's texture: Ewa.WithinAFifthOfItsDoublePrecisionIdealsErrorAgainstTheBox);
// 1.5: 0.0052 / 0.0086 for 56. Without the grid (texel centres on level 0
// too): 0.0096 / 0.0110.
constexpr double kEwaGridBelow = 2.0;
constexpr double kEwaGridPerTexel = 2.0;
constexpr int kEwaMinGrid = 4;
constexpr double kEwaTexelsPerRadius = 2.5;

// One lookup's samples.
struct EwaPlan {
  bool grid = true;
  int level = 0;
  // Grid: sample (i, j) of columns x rows at (u, v) + a * axisA + b * axisB
  // (normalized coordinates), a = ((i + 1/2) / columns - 1/2) * 2 and b
  // likewise, weighing w(a^2 + b^2).
  int columns = 1, rows = 1;
  float u = 0, v = 0, axisAu = 0, axisAv = 0, axisBu = 0, axisBv = 0;
  // Texel centres: texel (x, y) of the level weighs w(r^2) with
  // r^2 = qa dx^2 + qb dx dy + qc dy^2, (dx, dy) = (x, y) - (cx, cy); rows
  // y0 .. y1, each's span from ewaRowSpan.
  float cx = 0, cy = 0, qa = 0, qb = 0, qc = 0;
  int y0 = 0, y1 = -1;
};

// (u, v) normalized; derivatives are the Jacobian of (u, v) per pixel.
// NaN/Inf inputs read as position 0 / a point footprint.
EwaPlan planEwa(const TextureView& view, float u, float v, float dudx, float dvdx, float dudy,
                float dvdy);

// The texels of row y inside the plan's ellipse: x0 .. x1 (empty when x1 < x0).
void ewaRowSpan(const EwaPlan& plan, int y, int& x0, int& x1);

}  // namespace quadra
