// SummedAreaTable: the prefix sums of a texture's level 0 and the box filter
// they give (Crow 1984): the average of the bilinear reconstruction over the
// axis-aligned bounding box of a pixel's footprint, in constant time.
//
// The precision problem: a float table of an 8192^2 texture holds sums near
// 3e7, where a float step is 2 to 4, so a small box (the difference of four
// such entries) loses every digit (quadra report sat-precision measures it).
// Here texels are stored as fixed-point integers and the table as wrapping
// 64-bit integer sums: a box sum, the difference of table entries, is then
// exact, whatever the magnitude of the entries. The only error left is the
// texels' rounding to the fixed point, at most 2^-(fractionBits + 1) each, so
// at most that on any average; fractionBits is chosen per texture so that
// the largest box a lookup can form (64 texture periods per axis) fits.
//
// The bilinear reconstruction's integral from -inf to x along a row is the
// prefix sum at the texel left of x plus two quadratic partial terms; by
// summation by parts it is a weighted sum of three prefix sums. A box is
// then 3 x 3 table entries per corner, read relative to one corner so every
// product is of box-sized numbers. Wrap modes extend the table analytically
// (repeat and mirror by whole periods, clamp by the edge texels, border by
// the border colour), so footprints of any size and position are exact.
//
// Memory: 32 bytes per texel (4 channels of int64), 2 GiB at 8192^2: a filter
// for offline quality, built on first use.
#pragma once

#include <cstdint>
#include <vector>

#include "texture/texel_format.h"
#include "texture/texture_view.h"

namespace quadra {

class Executor;

class SummedAreaTable {
 public:
  // The table of `level` (texels in `format`, decoded as the kernels decode
  // them), built in parallel on `executor` when given. Non-finite texels
  // count as 0, as the filters' storage encodes them.
  SummedAreaTable(const TextureLevel& level, TexelFormat format, const Executor* executor);

  int width() const { return width_; }
  int height() const { return height_; }
  int fractionBits() const { return fractionBits_; }

  // The box filter for one lookup, in scalar double arithmetic: the
  // reference the lane kernels (sampleSummedArea, sample_lanes.h), which do
  // the same across SIMD lanes, match bit for bit. (u, v) normalized,
  // derivatives the Jacobian per pixel; wrap modes and border colour from `view`. The box is
  // the footprint parallelogram's bounding box, at least 2^-15 texels and at
  // most 64 texture periods on a side. NaN/Inf positions read as 0.
  void lookup(const TextureView& view, float u, float v, float dudx, float dvdx, float dudy,
              float dvdy, float rgba[4]) const;

  // lookup() in parts, for the lane kernels (sampleSummedArea in
  // sample_lanes.h): they form the box, its corner terms and the weighted sum
  // across lanes in double, with the operations of lookup() in its order, and
  // leave to these scalar functions the table reads and their exact integer
  // sums. The box's side limits, which boxOf applies:
  static constexpr double kMaxBoxPeriods = 64.0;
  // A footprint of zero size (zero derivatives) becomes a box this small,
  // whose average is the bilinear value to about this many texels times the
  // local slope.
  static constexpr double kMinHalfSide = 1.0 / 65536.0;
  // A box corner's three prefix indices per axis are first, first + 1 and
  // first + 2 (cornerTerms in summed_area.cpp); these are the firsts of x0
  // and x1 (m) and of y0 and y1 (n).
  struct CornerIndices {
    long m[2], n[2];
  };
  // Asks the memory system for the table entries boxSums() will read (where
  // the box lies inside the table, or anywhere under periodic wraps) and
  // returns: they are 12 or more scattered cache lines per lookup, so a SIMD
  // group prefetches all its lanes' before the first lane waits on one.
  void prefetch(const TextureView& view, const CornerIndices& corners) const;
  // The box sums boxAverage() weights: for a and b in 1 .. 5 (the six prefix
  // indices along x, x0's three then x1's, and the six along y), the exact
  // sum over the box from the first corner (index 0, 0) to (a, b), modulo
  // 2^64, channel c at out[((a - 1) * 5 + b - 1) * boxStride + c]: the
  // channels side by side (4 SSE2 or 2 AVX2 registers of them), boxStride 4
  // for one lookup, 4 W for a lane group's [box][lane][channel] layout.
  void boxSums(const TextureView& view, const CornerIndices& corners, std::int64_t* out,
               std::size_t boxStride) const;

  // The exact average of the level's bilinear reconstruction over the texel-
  // space box [x0, x1] x [y0, y1] (texel i covers [i, i + 1)), up to the
  // fixed-point rounding; x1 > x0 and y1 > y0.
  void boxAverage(const TextureView& view, double x0, double x1, double y0, double y1,
                  double rgba[4]) const;

  // The exact sum of the wrap-extended texels [m0, m1) x [n0, n1), up to the
  // fixed-point rounding (what the table stores, for precision checks).
  void texelSum(const TextureView& view, long m0, long m1, long n0, long n1, double rgba[4]) const;

 private:
  // The texel-space box [x0, x1] x [y0, y1] lookup() averages (summed_area.cpp).
  struct Box {
    double x0, x1, y0, y1;
  };
  Box boxOf(const TextureView& view, float u, float v, float dudx, float dvdx, float dudy,
            float dvdy) const;
  // A prefix bound m along one axis, as table entries (summed_area.cpp).
  struct AxisExtension;
  static AxisExtension extendAxis(long m, long n, WrapMode mode);
  // The sum of the wrap-extended texels over [0, m) x [0, n) (signed: a
  // negative bound counts the texels below 0 negatively), in fixed point,
  // modulo 2^64; x and y are m and n extended along their axes.
  void extendedSum(const TextureView& view, const AxisExtension& x, const AxisExtension& y, long n,
                   std::uint64_t out[4]) const;
  // boxSums() where the wrap modes of both axes are periodic (repeat or
  // mirrored repeat) and the box leaves the table; m and n are its six
  // prefix bounds per axis (summed_area.cpp).
  void periodicBoxSums(const TextureView& view, const long m[6], const long n[6], std::int64_t* out,
                       std::size_t boxStride) const;
  const std::uint64_t* entry(long m, long n) const {
    return &sums_[(std::size_t(n) * std::size_t(width_ + 1) + std::size_t(m)) * 4];
  }

  int width_ = 0, height_ = 0;
  int fractionBits_ = 0;
  double valueBound_ = 1.0;          // the largest magnitude a texel or border colour may have
  std::vector<std::uint64_t> sums_;  // (height + 1) rows of (width + 1) RGBA sums
};

}  // namespace quadra
