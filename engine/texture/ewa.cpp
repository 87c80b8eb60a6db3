// EWA plans (see ewa.h): the footprint's singular vectors, the eccentricity
// clamp, the choice between a level-0 grid and texel centres, the level, and
// the corrected ellipse on it.
#include "texture/ewa.h"

#include <algorithm>
#include <cmath>

namespace quadra {

namespace {

double finiteOr(double x, double fallback) {
  return std::isfinite(x) ? x : fallback;
}

// Positions far beyond the texture keep their wrap phase but not their
// magnitude (repeat and mirror are periodic in 1 and 2); under clamp and
// border, positions beyond [-2, 3] see only the edge or the border colour
// (the ellipse is capped at a texture's size below).
double reduce(double x, WrapMode mode) {
  if (mode == WrapMode::Repeat) return x - std::floor(x);
  if (mode == WrapMode::MirroredRepeat) return x - 2.0 * std::floor(x * 0.5);
  return std::clamp(x, -2.0, 3.0);
}

}  // namespace

EwaPlan planEwa(const TextureView& view, float uIn, float vIn, float dudx, float dvdx, float dudy,
                float dvdy) {
  const double u = reduce(finiteOr(uIn, 0.0), view.wrapU);
  const double v = reduce(finiteOr(vIn, 0.0), view.wrapV);
  const double width = view.levels[0].width, height = view.levels[0].height;
  // The Jacobian in level-0 texels: columns are the images of screen x and y.
  double xu = finiteOr(dudx, 0.0) * width, xv = finiteOr(dvdx, 0.0) * height;
  double yu = finiteOr(dudy, 0.0) * width, yv = finiteOr(dvdy, 0.0) * height;
  if (!std::isfinite(xu * xu + xv * xv + yu * yu + yv * yv)) xu = xv = yu = yv = 0.0;
  // Singular values and the screen-space singular vectors (c1, s1), (-s1, c1):
  // J maps them to the ellipse's orthogonal axes a (length major) and b.
  const double p = xu * xu + xv * xv, q = xu * yu + xv * yv, r = yu * yu + yv * yv;
  const double root = std::sqrt(0.25 * (p - r) * (p - r) + q * q);
  const double major = std::sqrt(std::max(0.5 * (p + r) + root, 0.0));
  const double minor = std::sqrt(std::max(0.5 * (p + r) - root, 0.0));
  double c1 = p >= r ? 0.5 * (p + r) + root - r : q, s1 = p >= r ? q : 0.5 * (p + r) + root - p;
  const double length = std::hypot(c1, s1);
  if (length > 0.0)
    c1 /= length, s1 /= length;
  else
    c1 = 1.0, s1 = 0.0;
  const double radius = kEwaShape.radius;
  // The eccentricity clamp (bounding the texel sums' work): the minor axis
  // lengthened to major / maxAniso.
  const double clamped = std::max(minor, major / double(std::clamp(view.maxAniso, 1, 64)));

  EwaPlan plan;
  // The level where the clamped minor radius spans kEwaTexelsPerRadius
  // texels, under the view's LOD controls.
  const int last = view.levelCount - 1;
  double lod = std::log2(std::max(radius * clamped / kEwaTexelsPerRadius, 1e-30));
  lod = std::clamp(lod + double(view.lodBias), double(view.minLod), double(view.maxLod));
  plan.level = int(std::clamp(std::floor(lod + 0.5), 0.0, double(last)));
  plan.grid = plan.level == 0 && radius * clamped < kEwaGridBelow;

  if (plan.grid) {  // the exact ellipse: its minor radius bounds the work
    plan.columns = std::max(kEwaMinGrid, int(std::ceil(2.0 * radius * major * kEwaGridPerTexel)));
    plan.rows = std::max(kEwaMinGrid, int(std::ceil(2.0 * radius * minor * kEwaGridPerTexel)));
    plan.u = float(u), plan.v = float(v);
    plan.axisAu = float(radius * (double(dudx) * c1 + double(dudy) * s1));
    plan.axisAv = float(radius * (double(dvdx) * c1 + double(dvdy) * s1));
    plan.axisBu = float(radius * (-double(dudx) * s1 + double(dudy) * c1));
    plan.axisBv = float(radius * (-double(dvdx) * s1 + double(dvdy) * c1));
    if (!(major > 0.0)) plan.axisAu = plan.axisAv = plan.axisBu = plan.axisBv = 0.0f;
    return plan;
  }

  // Texel centres: the ellipse's axes in level-0 texels, a along the major
  // axis, b perpendicular to it with the clamped minor length.
  double ax = xu * c1 + yu * s1, ay = xv * c1 + yv * s1;
  const double axisLength = std::hypot(ax, ay);
  if (axisLength > 0.0)
    ax /= axisLength, ay /= axisLength;
  else
    ax = 1.0, ay = 0.0;
  const double bx = -ay, by = ax;
  // Squared radii, corrected for the level's box prefilter and for the ideal's
  // bilinear reconstruction (ewa.h), each kept at 5% of itself at least (a
  // level forced coarser by the LOD controls would otherwise invert it).
  const TextureLevel& lev = view.levels[plan.level];
  const double texels = std::ldexp(1.0, plan.level);
  const double correction = (1.0 / 6.0 - (texels * texels - 1.0) / 12.0) / kEwaShapeVariance;
  const double ra = radius * major, rb = radius * clamped;
  double sa = std::max(ra * ra + correction, 0.05 * ra * ra);
  double sb = std::max(rb * rb + correction, 0.05 * rb * rb);
  // Each semi-axis capped at the level's size: a longer one only averages
  // whole periods again (and a level clamped by the chain or the controls
  // would be huge); capping the axes one by one keeps the minor axis's
  // averaging, where shrinking the ellipse whole cut it to a sliver (a
  // 1000:1 footprint on a 1x1 texture then held no texel centre at all).
  // At least one level texel, so a texel centre always falls inside.
  const double sx = double(lev.width) / width, sy = double(lev.height) / height;
  const double cap = double(std::max(lev.width, lev.height));
  const double scaleMax = std::max(sx, sy), scaleMin = std::min(sx, sy);
  const double least = 1.0 / (scaleMin * scaleMin);
  const double most = std::max(least, cap * cap / (scaleMax * scaleMax));
  sa = std::clamp(sa, least, most);
  sb = std::clamp(sb, least, most);
  // The covariance-like matrix S = sa a a^T + sb b b^T in level texels, and
  // its inverse as the quadratic form.
  const double sxx = (sa * ax * ax + sb * bx * bx) * sx * sx;
  const double sxy = (sa * ax * ay + sb * bx * by) * sx * sy;
  const double syy = (sa * ay * ay + sb * by * by) * sy * sy;
  const double det = sxx * syy - sxy * sxy;
  plan.qa = float(syy / det);
  plan.qb = float(-2.0 * sxy / det);
  plan.qc = float(sxx / det);
  plan.cx = float(u * lev.width - 0.5);
  plan.cy = float(v * lev.height - 0.5);
  const double halfHeight = std::sqrt(syy);
  plan.y0 = int(std::ceil(double(plan.cy) - halfHeight));
  plan.y1 = int(std::floor(double(plan.cy) + halfHeight));
  return plan;
}

void ewaRowSpan(const EwaPlan& plan, int y, int& x0, int& x1) {
  // qa dx^2 + (qb dy) dx + (qc dy^2 - 1) < 0 between the roots.
  const double dy = double(y) - double(plan.cy);
  const double qa = plan.qa, b = double(plan.qb) * dy, c = double(plan.qc) * dy * dy - 1.0;
  const double discriminant = b * b - 4.0 * qa * c;
  if (!(discriminant > 0.0) || !(qa > 0.0)) {
    x0 = 0, x1 = -1;
    return;
  }
  const double root = std::sqrt(discriminant);
  x0 = int(std::ceil(double(plan.cx) + (-b - root) / (2.0 * qa)));
  x1 = int(std::floor(double(plan.cx) + (-b + root) / (2.0 * qa)));
}

}  // namespace quadra
