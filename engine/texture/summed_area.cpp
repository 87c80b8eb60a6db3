// The summed-area table: fixed-point choice, the parallel build, the wrap
// extension of prefix sums and the box integral (summed_area.h).
#include "texture/summed_area.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace quadra {

namespace {

// A lookup's box is at most kMaxBoxPeriods texture periods on a side; the
// fixed point leaves room for its sum (and a few texels of margin) in 63 bits.
constexpr int kMaxFractionBits = 40;  // 1e-12 per texel: finer buys nothing

double finiteOrZero(float value) {
  return std::isfinite(value) ? double(value) : 0.0;
}

// Rows of texels handed to one task while building.
void forEachRange(const Executor* executor, std::size_t count, std::size_t grain,
                  const std::function<void(std::size_t, std::size_t)>& body) {
  if (executor)
    executor->parallelFor(count, grain, body);
  else
    body(0, count);
}

}  // namespace

// The prefix sum P(m) = sum of the extended row's texels over [0, m) as a
// combination of the table's prefix sums P(0..n): up to two integer-weighted
// entries, plus, for the border mode, the count of border texels in [0, m)
// (signed) and of texture texels.
struct SummedAreaTable::AxisExtension {
  long index[2] = {0, 0};
  std::int64_t weight[2] = {0, 0};
  int terms = 1;
  long borderCount = 0;   // m - clamp(m, 0, n) under the border mode, else 0
  long textureCount = 0;  // the signed count of [0, m) positions that read texels
};

namespace {

long floorDiv(long a, long b) {
  const long q = a / b;
  return q * b > a ? q - 1 : q;
}

}  // namespace

SummedAreaTable::AxisExtension SummedAreaTable::extendAxis(long m, long n, WrapMode mode) {
  AxisExtension e;
  e.textureCount = m;
  switch (mode) {
    case WrapMode::Repeat: {  // q whole periods and the remainder
      const long q = floorDiv(m, n);
      e.index[0] = m - q * n, e.weight[0] = 1;
      e.index[1] = n, e.weight[1] = q;
      e.terms = q == 0 ? 1 : 2;  // inside the texture: one table read, not two
      return e;
    }
    case WrapMode::MirroredRepeat: {  // a period is the row and its reflection
      const long q = floorDiv(m, 2 * n), r = m - q * 2 * n;
      e.terms = 2;
      e.index[1] = n;
      if (r <= n) {
        e.index[0] = r, e.weight[0] = 1, e.weight[1] = 2 * q;
      } else {  // P(n) + (P(n) - P(2n - r)): the reflected part read backwards
        e.index[0] = 2 * n - r, e.weight[0] = -1, e.weight[1] = 2 * q + 2;
      }
      if (e.weight[1] == 0) e.terms = 1;
      return e;
    }
    case WrapMode::ClampToEdge:
      if (m < 0) {  // m copies of texel 0, counted negatively
        e.index[0] = 1, e.weight[0] = m;
      } else if (m > n) {  // the row, then m - n copies of the last texel
        e.index[0] = n, e.weight[0] = m - n + 1;
        e.index[1] = n - 1, e.weight[1] = -(m - n);
        e.terms = 2;
      } else {
        e.index[0] = m, e.weight[0] = 1;
      }
      return e;
    case WrapMode::ClampToBorder: {
      const long inside = std::clamp(m, 0L, n);
      e.index[0] = inside, e.weight[0] = 1;
      e.borderCount = m - inside;
      e.textureCount = inside;
      return e;
    }
  }
  return e;
}

namespace {

// The prefix of the bilinear reconstruction's integral along one axis up to
// x (texel space): with j the texel whose centre is at or left of x and s the
// distance past that centre, it is P(j) + t_j (1 - (1-s)^2/2) + t_{j+1} s^2/2,
// which regrouped over prefix sums is P(j), P(j+1), P(j+2) with these weights.
struct CornerTerms {
  long index[3];
  double weight[3];
};

CornerTerms cornerTerms(double x, double sign) {
  const double j = std::floor(x - 0.5), s = x - 0.5 - j;
  const long base = long(j);
  return {{base, base + 1, base + 2},
          {sign * 0.5 * (1.0 - s) * (1.0 - s), sign * (0.5 + s - s * s), sign * 0.5 * s * s}};
}

}  // namespace

SummedAreaTable::SummedAreaTable(const TextureLevel& level, TexelFormat format,
                                 const Executor* executor)
    : width_(level.width), height_(level.height) {
  const std::size_t w = std::size_t(width_), h = std::size_t(height_),
                    texelBytes = bytesPerTexel(format);
  auto decodedRow = [&](std::size_t y, std::vector<float>& row) {
    row.resize(w * 4);
    const std::uint8_t* texels = level.texels + y * std::size_t(level.stride) * texelBytes;
    for (std::size_t x = 0; x < w; ++x) {
      decodeTexel(format, texels + x * texelBytes, &row[x * 4]);
      for (std::size_t c = 0; c < 4; ++c) row[x * 4 + c] = float(finiteOrZero(row[x * 4 + c]));
    }
  };

  // The fixed point: the largest box sum, (64 periods + margin)^2 texels of
  // the largest magnitude (at least 1, which also covers border colours in
  // [0, 1]), must stay below 2^62.
  std::vector<float> rowMax(h, 0.0f);
  forEachRange(executor, h, 16, [&](std::size_t begin, std::size_t end) {
    std::vector<float> row;
    for (std::size_t y = begin; y < end; ++y) {
      decodedRow(y, row);
      for (const float value : row) rowMax[y] = std::max(rowMax[y], std::abs(value));
    }
  });
  valueBound_ = std::max(1.0, double(*std::max_element(rowMax.begin(), rowMax.end())));
  const double largestBox =
      (kMaxBoxPeriods * width_ + 8.0) * (kMaxBoxPeriods * height_ + 8.0) * valueBound_;
  fractionBits_ = std::min(kMaxFractionBits, int(std::floor(62.0 - std::log2(largestBox))));
  const double scale = std::ldexp(1.0, fractionBits_);

  // Row prefix sums, then column prefix sums; integer additions, so the
  // result does not depend on how the work is split.
  const std::size_t rowLength = (w + 1) * 4;
  sums_.assign((h + 1) * rowLength, 0);
  forEachRange(executor, h, 16, [&](std::size_t begin, std::size_t end) {
    std::vector<float> row;
    for (std::size_t y = begin; y < end; ++y) {
      decodedRow(y, row);
      std::uint64_t* out = &sums_[(y + 1) * rowLength];
      for (std::size_t x = 0; x < w; ++x)
        for (std::size_t c = 0; c < 4; ++c)
          out[(x + 1) * 4 + c] =
              out[x * 4 + c] + std::uint64_t(std::llround(double(row[x * 4 + c]) * scale));
    }
  });
  forEachRange(executor, rowLength, 256, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = 1; y <= h; ++y) {
      std::uint64_t* out = &sums_[y * rowLength];
      const std::uint64_t* above = out - rowLength;
      for (std::size_t i = begin; i < end; ++i) out[i] += above[i];
    }
  });
}

void SummedAreaTable::extendedSum(const TextureView& view, const AxisExtension& ex,
                                  const AxisExtension& ey, long n, std::uint64_t out[4]) const {
  for (int c = 0; c < 4; ++c) out[c] = 0;
  for (int i = 0; i < ex.terms; ++i) {
    for (int j = 0; j < ey.terms; ++j) {
      const std::uint64_t weight = std::uint64_t(ex.weight[i]) * std::uint64_t(ey.weight[j]);
      const std::uint64_t* sum = entry(ex.index[i], ey.index[j]);
      for (int c = 0; c < 4; ++c) out[c] += weight * sum[c];
    }
  }
  // Border texels: those outside in u (all n rows of them), then those inside
  // in u but outside in v.
  const std::int64_t borderTexels =
      std::int64_t(ex.borderCount) * n + std::int64_t(ex.textureCount) * ey.borderCount;
  if (borderTexels == 0) return;
  const double scale = std::ldexp(1.0, fractionBits_);
  for (int c = 0; c < 4; ++c) {
    const double border = std::clamp(finiteOrZero(view.border[c]), -valueBound_, valueBound_);
    out[c] += std::uint64_t(borderTexels) * std::uint64_t(std::llround(border * scale));
  }
}

namespace {

// The whole-period terms of a periodic box sum (periodicBoxSums, below).
struct PeriodTerms {
  std::uint64_t dqX[6], dqY[6];  // periods counted at each bound, relative to bound 0
  std::uint64_t columns[6][4];   // s_a T(r_a, H) - s_0 T(r_0, H), where some dqY is not 0
  std::uint64_t rows[6][4];      // s_b T(W, r_b) - s_0 T(W, r_0), where some dqX is not 0
  const std::uint64_t* whole;    // T(W, H)
};

// The box sums S(a, b) - S(a, 0) - S(0, b) + S(0, 0) of 6 x 6 prefix sums (plus
// the period terms, where given), laid out as boxSums() writes them. The
// reference lines are held in locals: out (int64) may alias the uint64 sums,
// so every store would otherwise reload them.
void writeBoxSums(const std::uint64_t* const sumAt[6][6], const PeriodTerms* periods,
                  std::int64_t* out, std::size_t boxStride) {
  std::uint64_t alongY[6][4];  // S(0, b) - S(0, 0)
  for (int b = 1; b < 6; ++b)
    for (int c = 0; c < 4; ++c) alongY[b][c] = sumAt[0][b][c] - sumAt[0][0][c];
  for (int a = 1; a < 6; ++a) {  // a = 0 or b = 0 is the reference corner's own line: 0
    std::uint64_t alongX[4];
    for (int c = 0; c < 4; ++c) alongX[c] = sumAt[a][0][c];
    for (int b = 1; b < 6; ++b) {
      const std::uint64_t* corner = sumAt[a][b];
      std::uint64_t sum[4];
      for (int c = 0; c < 4; ++c) sum[c] = corner[c] - alongX[c] - alongY[b][c];
      if (periods && (periods->dqX[a] | periods->dqY[b]) != 0) {
        const std::uint64_t dqX = periods->dqX[a], dqY = periods->dqY[b];
        for (int c = 0; c < 4; ++c)
          sum[c] += dqY * periods->columns[a][c] + dqX * periods->rows[b][c] +
                    dqX * dqY * periods->whole[c];
      }
      std::int64_t* box = out + ((a - 1) * 5 + b - 1) * boxStride;
      for (int c = 0; c < 4; ++c) box[c] = std::int64_t(sum[c]);
    }
  }
}

bool isPeriodic(WrapMode mode) {
  return mode == WrapMode::Repeat || mode == WrapMode::MirroredRepeat;
}

}  // namespace

void SummedAreaTable::boxSums(const TextureView& view, const CornerIndices& corners,
                              std::int64_t* out, std::size_t boxStride) const {
  // Every entry is read relative to the box's first corner (mRef, nRef): the
  // weights of each axis sum to zero, so subtracting terms constant along an
  // axis changes nothing, and what remains are exact integer sums over boxes
  // the size of this one, small enough to weight in double.
  long m[6], n[6];
  bool insideX[6], insideY[6], inside = true;
  for (int i = 0; i < 6; ++i) {
    m[i] = corners.m[i / 3] + i % 3, n[i] = corners.n[i / 3] + i % 3;
    insideX[i] = m[i] >= 0 && m[i] <= width_;
    insideY[i] = n[i] >= 0 && n[i] <= height_;
    inside = inside && insideX[i] && insideY[i];
  }
  if (!inside && isPeriodic(view.wrapU) && isPeriodic(view.wrapV))
    return periodicBoxSums(view, m, n, out, boxStride);
  // The 6 x 6 prefix sums: table entries where both bounds lie in the table
  // (every one, for most boxes), the wrap extension only for the others.
  const std::uint64_t* sumAt[6][6];
  std::uint64_t extended[6][6][4];
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b)
      sumAt[a][b] = insideX[a] && insideY[b] ? entry(m[a], n[b]) : extended[a][b];
  if (!inside) {
    // Initialized from extendAxis directly: default-constructed arrays were
    // zero-filled first, a tenth of an extended lookup.
    const auto x = [&](int i) { return extendAxis(m[i], width_, view.wrapU); };
    const auto y = [&](int i) { return extendAxis(n[i], height_, view.wrapV); };
    const AxisExtension ex[6] = {x(0), x(1), x(2), x(3), x(4), x(5)};
    const AxisExtension ey[6] = {y(0), y(1), y(2), y(3), y(4), y(5)};
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
        if (!(insideX[a] && insideY[b])) extendedSum(view, ex[a], ey[b], n[b], extended[a][b]);
  }
  writeBoxSums(sumAt, nullptr, out, boxStride);
}

// Under repeat and mirrored repeat, extendAxis gives every prefix sum as
// P(m) = s P(r) + q P(n): r inside the table, the sign s = +-1 (-1 where a
// mirrored row is read backwards) and q rows or columns counted whole. The
// box sum from bound 0 to bound a along x and b along y (the difference of
// four such products) is then, with the signed entries G(a, b) =
// s_a s_b T(r_a, r_b) and dq_i = q_i - q_0,
//   G(a, b) - G(a, 0) - G(0, b) + G(0, 0)           the entries' own box sum
//   + dq_b (s_a T(r_a, H) - s_0 T(r_0, H))         whole columns, rows r_0 .. r_a
//   + dq_a (s_b T(W, r_b) - s_0 T(W, r_0))         whole rows
//   + dq_a dq_b T(W, H)                             whole periods,
// all modulo 2^64. Most dq are 0 (the bounds of one corner lie in one
// period), where the entry-by-entry extension multiplied four entries for
// every one of the 36 prefix sums, a third of an extended lookup's time.
void SummedAreaTable::periodicBoxSums(const TextureView& view, const long m[6], const long n[6],
                                      std::int64_t* out, std::size_t boxStride) const {
  struct Bound {
    long r;
    std::uint64_t negate;  // all ones where s = -1: (x ^ negate) - negate is s x
    std::uint64_t periods;
  };
  const auto bound = [](long at, long size, WrapMode mode) {
    if (at >= 0 && at <= size) return Bound{at, 0, 0};  // no division inside the table
    const AxisExtension e = extendAxis(at, size, mode);
    return Bound{e.index[0], e.weight[0] < 0 ? ~std::uint64_t(0) : 0, std::uint64_t(e.weight[1])};
  };
  Bound x[6], y[6];
  for (int i = 0; i < 6; ++i)
    x[i] = bound(m[i], width_, view.wrapU), y[i] = bound(n[i], height_, view.wrapV);
  const auto signedSum = [](const std::uint64_t* sum, std::uint64_t negate, int c) {
    return (sum[c] ^ negate) - negate;
  };
  // The signed entries G: the entries themselves, negated where one bound
  // (not both) reads a mirrored period backwards.
  const std::uint64_t* sumAt[6][6];
  std::uint64_t negated[6][6][4];
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      sumAt[a][b] = entry(x[a].r, y[b].r);
      const std::uint64_t negate = x[a].negate ^ y[b].negate;
      if (negate == 0) continue;
      for (int c = 0; c < 4; ++c) negated[a][b][c] = signedSum(sumAt[a][b], negate, c);
      sumAt[a][b] = negated[a][b];
    }
  PeriodTerms periods;
  std::uint64_t anyX = 0, anyY = 0;
  for (int i = 0; i < 6; ++i) {
    periods.dqX[i] = x[i].periods - x[0].periods, periods.dqY[i] = y[i].periods - y[0].periods;
    anyX |= periods.dqX[i], anyY |= periods.dqY[i];
  }
  // Whole columns and rows only where some bound counts them: each is a
  // table line of its own, a cache miss on a large table.
  for (int i = 0; i < 6; ++i)
    for (int c = 0; c < 4; ++c) periods.columns[i][c] = periods.rows[i][c] = 0;
  if (anyY != 0) {
    const std::uint64_t* column0 = entry(x[0].r, height_);
    for (int i = 1; i < 6; ++i) {
      const std::uint64_t* column = entry(x[i].r, height_);
      for (int c = 0; c < 4; ++c)
        periods.columns[i][c] =
            signedSum(column, x[i].negate, c) - signedSum(column0, x[0].negate, c);
    }
  }
  if (anyX != 0) {
    const std::uint64_t* row0 = entry(width_, y[0].r);
    for (int i = 1; i < 6; ++i) {
      const std::uint64_t* row = entry(width_, y[i].r);
      for (int c = 0; c < 4; ++c)
        periods.rows[i][c] = signedSum(row, y[i].negate, c) - signedSum(row0, y[0].negate, c);
    }
  }
  periods.whole = entry(width_, height_);
  writeBoxSums(sumAt, &periods, out, boxStride);
}

void SummedAreaTable::boxAverage(const TextureView& view, double x0, double x1, double y0,
                                 double y1, double rgba[4]) const {
  const CornerTerms xs[2] = {cornerTerms(x0, -1.0), cornerTerms(x1, 1.0)};
  const CornerTerms ys[2] = {cornerTerms(y0, -1.0), cornerTerms(y1, 1.0)};
  std::int64_t boxSum[25][4];
  boxSums(view, {{xs[0].index[0], xs[1].index[0]}, {ys[0].index[0], ys[1].index[0]}}, &boxSum[0][0],
          4);
  double sum[4] = {0.0, 0.0, 0.0, 0.0};
  for (int a = 1; a < 6; ++a) {
    for (int b = 1; b < 6; ++b) {
      const double weight = xs[a / 3].weight[a % 3] * ys[b / 3].weight[b % 3];
      for (int c = 0; c < 4; ++c) sum[c] += weight * double(boxSum[(a - 1) * 5 + b - 1][c]);
    }
  }
  const double norm = 1.0 / (std::ldexp(1.0, fractionBits_) * (x1 - x0) * (y1 - y0));
  for (int c = 0; c < 4; ++c) rgba[c] = sum[c] * norm;
}

void SummedAreaTable::texelSum(const TextureView& view, long m0, long m1, long n0, long n1,
                               double rgba[4]) const {
  const AxisExtension x0 = extendAxis(m0, width_, view.wrapU);
  const AxisExtension x1 = extendAxis(m1, width_, view.wrapU);
  const AxisExtension y0 = extendAxis(n0, height_, view.wrapV);
  const AxisExtension y1 = extendAxis(n1, height_, view.wrapV);
  std::uint64_t s00[4], s01[4], s10[4], s11[4];
  extendedSum(view, x0, y0, n0, s00);
  extendedSum(view, x1, y0, n0, s10);
  extendedSum(view, x0, y1, n1, s01);
  extendedSum(view, x1, y1, n1, s11);
  const double unit = std::ldexp(1.0, -fractionBits_);
  for (int c = 0; c < 4; ++c)
    rgba[c] = double(std::int64_t(s11[c] - s10[c] - s01[c] + s00[c])) * unit;
}

SummedAreaTable::Box SummedAreaTable::boxOf(const TextureView& view, float u, float v, float dudx,
                                            float dvdx, float dudy, float dvdy) const {
  const double w = width_, h = height_;
  // Half sides of the footprint's bounding box in texels; NaN counts as 0.
  auto halfSide = [](float a, float b, double size) {
    const double side = 0.5 * (std::abs(double(a)) + std::abs(double(b))) * size;
    return std::isnan(side) ? kMinHalfSide
                            : std::clamp(side, kMinHalfSide, 0.5 * kMaxBoxPeriods * size);
  };
  // The centre, brought near the texture without changing the answer:
  // whole periods for repeat and mirror; for the clamp modes, far enough out
  // that the largest box there reads only the extension.
  auto centre = [](double t, WrapMode mode) {
    if (mode == WrapMode::Repeat) return t - std::floor(t);
    if (mode == WrapMode::MirroredRepeat) return t - 2.0 * std::floor(0.5 * t);
    return std::clamp(t, -1.0 - 0.5 * kMaxBoxPeriods, 2.0 + 0.5 * kMaxBoxPeriods);
  };
  const double hx = halfSide(dudx, dudy, w), hy = halfSide(dvdx, dvdy, h);
  const double cx = centre(finiteOrZero(u), view.wrapU) * w;
  const double cy = centre(finiteOrZero(v), view.wrapV) * h;
  return {cx - hx, cx + hx, cy - hy, cy + hy};
}

void SummedAreaTable::lookup(const TextureView& view, float u, float v, float dudx, float dvdx,
                             float dudy, float dvdy, float rgba[4]) const {
  const Box box = boxOf(view, u, v, dudx, dvdx, dudy, dvdy);
  double average[4];
  boxAverage(view, box.x0, box.x1, box.y0, box.y1, average);
  for (int c = 0; c < 4; ++c) rgba[c] = float(average[c]);
}

void SummedAreaTable::prefetch(const TextureView& view, const CornerIndices& corners) const {
  // A corner's first prefix index, or where a periodic wrap reads it
  // (periodicBoxSums): its remainder, the start of the three entries read
  // backwards in a mirrored period. -1: read from the extension, no entry.
  const bool periodic = isPeriodic(view.wrapU) && isPeriodic(view.wrapV);
  bool wrapped = false;
  const auto first = [&](long at, long size, WrapMode mode) {
    if (at >= 0 && at + 2 <= size) return at;
    if (!periodic || size < 2) return -1L;
    wrapped = true;
    const AxisExtension e = extendAxis(at, size, mode);
    return std::clamp(e.weight[0] < 0 ? e.index[0] - 2 : e.index[0], 0L, size - 2);
  };
  const long m[2] = {first(corners.m[0], width_, view.wrapU),
                     first(corners.m[1], width_, view.wrapU)};
  const long n[2] = {first(corners.n[0], height_, view.wrapV),
                     first(corners.n[1], height_, view.wrapV)};
  // Each corner reads entries (m .. m + 2, n .. n + 2): three rows of 96
  // bytes, two cache lines each at most.
  // Only entries inside the table: a box's bounds may lie outside it, and
  // forming an address beyond the vector is undefined even for a prefetch
  // (clang's UBSan pointer-overflow check, SamplerHardCases.*).
  const auto prefetchEntry = [this](long column, long row, int channel) {
    if (column >= 0 && row >= 0 && column <= width_ && row <= height_)
      __builtin_prefetch(entry(column, row) + channel);
  };
  for (const long row0 : n)
    for (const long column : m)
      for (long row = row0; row <= row0 + 2; ++row) {
        prefetchEntry(column, row, 0);
        prefetchEntry(column + 2, row, 3);
      }
  if (!wrapped) return;
  // The whole columns (the last row) and whole rows (the last column) a
  // wrapped box may count.
  for (const long column : m) {
    prefetchEntry(column, height_, 0);
    prefetchEntry(column + 2, height_, 3);
  }
  for (const long row0 : n)
    for (long row = row0; row <= row0 + 2; ++row) prefetchEntry(width_, row, 0);
}

}  // namespace quadra
