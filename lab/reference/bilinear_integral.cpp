// Exact segment integrals of the level-0 bilinear reconstruction (tests in
// tests/test_reference_area.cpp).
#include "lab/reference/bilinear_integral.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/error.h"
#include "lab/reference/reference_tracer.h"

namespace quadra::ref {

namespace {

bool periodic(WrapMode mode) {
  return mode == WrapMode::Repeat || mode == WrapMode::MirroredRepeat;
}

// Points a line tabulates: one period, or [-1, n] for the clamped modes.
std::size_t linePoints(int n, WrapMode mode) {
  return mode == WrapMode::Repeat           ? std::size_t(n) + 1
         : mode == WrapMode::MirroredRepeat ? 2 * std::size_t(n) + 1
                                            : std::size_t(n) + 2;
}

glm::dvec4 texelOf(const Image& image, int x, int y) {
  const float* t = image.texel(x, y);
  return {t[0], t[1], t[2], t[3]};
}

}  // namespace

std::size_t BilinearIntegral::bytesFor(int width, int height, const SamplerState& sampler) {
  const std::size_t perPoint = 3 * sizeof(glm::dvec4);
  return perPoint * (std::size_t(height) * linePoints(width, sampler.wrapU) +
                     std::size_t(width) * linePoints(height, sampler.wrapV));
}

BilinearIntegral::Line BilinearIntegral::makeLine(const std::vector<glm::dvec4>& texels,
                                                  WrapMode mode, const glm::dvec4& border) {
  const auto n = std::int64_t(texels.size());
  Line line;
  line.period = mode == WrapMode::Repeat           ? int(n)
                : mode == WrapMode::MirroredRepeat ? int(2 * n)
                                                   : 0;
  line.lo = periodic(mode) ? 0.0 : -1.0;
  const std::size_t points = linePoints(int(n), mode);
  line.hi = line.lo + double(points - 1);
  const auto at = [&](std::int64_t i) {
    const std::int64_t k = wrapTexel(i, n, mode);
    return k < 0 ? border : texels[std::size_t(k)];
  };
  line.below = at(std::int64_t(line.lo) - 1);
  line.above = at(std::int64_t(line.hi) + 1);
  line.value.resize(points);
  line.sum0.assign(points, glm::dvec4(0.0));
  line.sum1.assign(points, glm::dvec4(0.0));
  for (std::size_t k = 0; k < points; ++k)
    line.value[k] = at(std::int64_t(line.lo) + std::int64_t(k));
  for (std::size_t k = 0; k + 1 < points; ++k) {
    const glm::dvec4 a = line.value[k], b = line.value[k + 1];
    const double x = line.lo + double(k);
    // Over [x, x + 1] r = a + (b - a) t: its integral (a + b) / 2, and that
    // of x * r is x (a + b) / 2 + a / 6 + b / 3.
    line.sum0[k + 1] = line.sum0[k] + 0.5 * (a + b);
    line.sum1[k + 1] = line.sum1[k] + x * 0.5 * (a + b) + a / 6.0 + b / 3.0;
  }
  return line;
}

BilinearIntegral::BilinearIntegral(const Image& image, const SamplerState& sampler)
    : wrap_{sampler.wrapU, sampler.wrapV}, size_{image.width, image.height} {
  QUADRA_CHECK(image.width > 0 && image.height > 0);
  const glm::dvec4 border(sampler.borderColor[0], sampler.borderColor[1], sampler.borderColor[2],
                          sampler.borderColor[3]);
  std::vector<glm::dvec4> texels;
  lines_[0].reserve(std::size_t(image.height));
  for (int y = 0; y < image.height; ++y) {
    texels.clear();
    for (int x = 0; x < image.width; ++x) texels.push_back(texelOf(image, x, y));
    lines_[0].push_back(makeLine(texels, sampler.wrapU, border));
  }
  lines_[1].reserve(std::size_t(image.width));
  for (int x = 0; x < image.width; ++x) {
    texels.clear();
    for (int y = 0; y < image.height; ++y) texels.push_back(texelOf(image, x, y));
    lines_[1].push_back(makeLine(texels, sampler.wrapV, border));
  }
  border_ = makeLine({border}, WrapMode::Repeat, border);
}

void BilinearIntegral::antiderivatives(const Line& line, double x, glm::dvec4& f0, glm::dvec4& f1) {
  const auto local = [&line](double at, glm::dvec4& l0, glm::dvec4& l1) {
    const auto last = std::int64_t(line.value.size()) - 2;
    const std::int64_t i =
        std::clamp<std::int64_t>(std::int64_t(std::floor(at - line.lo)), 0, last);
    const double f = at - line.lo - double(i), xi = line.lo + double(i);
    const glm::dvec4 a = line.value[std::size_t(i)], b = line.value[std::size_t(i) + 1];
    const glm::dvec4 part = a * f + (b - a) * (0.5 * f * f);
    l0 = line.sum0[std::size_t(i)] + part;
    l1 = line.sum1[std::size_t(i)] + xi * part + a * (0.5 * f * f) + (b - a) * (f * f * f / 3.0);
  };
  if (line.period > 0) {
    // x >= 0 here (integrate moves its segment so): k whole periods, then the rest.
    const double period = line.period;
    const double k = std::floor(x / period);
    glm::dvec4 l0, l1;
    local(x - k * period, l0, l1);
    const glm::dvec4 s0 = line.sum0.back(), s1 = line.sum1.back();
    f0 = k * s0 + l0;
    f1 = k * s1 + (period * 0.5 * k * (k - 1.0)) * s0 + l1 + (k * period) * l0;
    return;
  }
  if (x < line.lo) {
    f0 = (x - line.lo) * line.below;
    f1 = (0.5 * (x * x - line.lo * line.lo)) * line.below;
  } else if (x > line.hi) {
    f0 = line.sum0.back() + (x - line.hi) * line.above;
    f1 = line.sum1.back() + (0.5 * (x * x - line.hi * line.hi)) * line.above;
  } else {
    local(x, f0, f1);
  }
}

glm::dvec4 BilinearIntegral::integrate(const Line& line, double x0, double x1, double alpha,
                                       double beta) {
  if (line.period > 0) {
    const double shift = std::floor(x0 / line.period) * line.period;
    x0 -= shift;
    x1 -= shift;
  }
  glm::dvec4 a0, a1, b0, b1;
  antiderivatives(line, x0, a0, a1);
  antiderivatives(line, x1, b0, b1);
  const glm::dvec4 i0 = b0 - a0;
  const glm::dvec4 i1 = (b1 - a1) - x0 * i0;  // the integral of (x - x0) r
  return alpha * i0 + beta * i1;
}

glm::dvec4 BilinearIntegral::integratePair(const Line& a, const Line& b, double x0, double x1,
                                           double fy0, double m) {
  if (a.period != b.period || a.period == 0 || a.lo != b.lo)
    return integrate(a, x0, x1, 1.0 - fy0, -m) + integrate(b, x0, x1, fy0, m);
  // The same layout: (1 - fy) r_a + fy r_b is one line's function with the
  // values blended, so one pass over the shared cell positions does both.
  const double period = a.period;
  const double shift = std::floor(x0 / period) * period;
  x0 -= shift;
  x1 -= shift;
  const auto both = [&](double x, glm::dvec4& fa0, glm::dvec4& fa1, glm::dvec4& fb0,
                        glm::dvec4& fb1) {
    const double k = std::floor(x / period);
    const double r = x - k * period;
    const auto last = std::int64_t(a.value.size()) - 2;
    const std::int64_t i = std::min<std::int64_t>(std::int64_t(r), last);
    const double f = r - double(i), xi = double(i);
    const double f2 = 0.5 * f * f, f3 = f * f * f / 3.0;
    const auto one = [&](const Line& line, glm::dvec4& g0, glm::dvec4& g1) {
      const glm::dvec4 va = line.value[std::size_t(i)], vb = line.value[std::size_t(i) + 1];
      const glm::dvec4 part = va * f + (vb - va) * f2;
      const glm::dvec4 l0 = line.sum0[std::size_t(i)] + part;
      const glm::dvec4 l1 = line.sum1[std::size_t(i)] + xi * part + va * f2 + (vb - va) * f3;
      const glm::dvec4 s0 = line.sum0.back(), s1 = line.sum1.back();
      g0 = k * s0 + l0;
      g1 = k * s1 + (period * 0.5 * k * (k - 1.0)) * s0 + l1 + (k * period) * l0;
    };
    one(a, fa0, fa1);
    one(b, fb0, fb1);
  };
  glm::dvec4 a00, a01, b00, b01, a10, a11, b10, b11;
  both(x0, a00, a01, b00, b01);
  both(x1, a10, a11, b10, b11);
  const glm::dvec4 ia0 = a10 - a00, ib0 = b10 - b00;
  const glm::dvec4 ia1 = (a11 - a01) - x0 * ia0, ib1 = (b11 - b01) - x0 * ib0;
  return (1.0 - fy0) * ia0 - m * ia1 + fy0 * ib0 + m * ib1;
}

const BilinearIntegral::Line& BilinearIntegral::lineAt(int axis, double index) const {
  // Rows are indexed by y and wrap as v does; columns by x, as u.
  const int across = 1 - axis;
  const std::int64_t k = wrapTexel(std::int64_t(index), size_[across], wrap_[across]);
  return k < 0 ? border_ : lines_[axis][std::size_t(k)];
}

glm::dvec4 BilinearIntegral::lineValue(const Line& line, double x) {
  if (line.period > 0) x -= std::floor(x / line.period) * line.period;
  if (x < line.lo) return line.below;
  if (x > line.hi) return line.above;
  const auto last = std::int64_t(line.value.size()) - 2;
  const std::int64_t i = std::clamp<std::int64_t>(std::int64_t(std::floor(x - line.lo)), 0, last);
  const double f = x - line.lo - double(i);
  return (1.0 - f) * line.value[std::size_t(i)] + f * line.value[std::size_t(i) + 1];
}

glm::dvec4 BilinearIntegral::pointValue(const glm::dvec2& at) const {
  const double j = std::floor(at.y), fy = at.y - j;
  return (1.0 - fy) * lineValue(lineAt(0, j), at.x) + fy * lineValue(lineAt(0, j + 1.0), at.x);
}

glm::dvec4 BilinearIntegral::segmentMean(const glm::dvec2& a, const glm::dvec2& b) const {
  const glm::dvec2 d = b - a;
  if (d.x == 0.0 && d.y == 0.0) return pointValue(a);
  // Along the segment's longer axis, so that it crosses at most as many
  // lines of the other axis as it is long.
  const int axis = std::fabs(d.x) >= std::fabs(d.y) ? 0 : 1;
  const int across = 1 - axis;
  double x0 = a[axis], y0 = a[across], x1 = b[axis], y1 = b[across];
  if (x0 > x1) {
    std::swap(x0, x1);
    std::swap(y0, y1);
  }
  const double m = (y1 - y0) / (x1 - x0);
  // Pieces between the crossings of whole y, each inside one band [j, j + 1].
  const double yLo = std::min(y0, y1), yHi = std::max(y0, y1);
  const double firstK = std::floor(yLo) + 1.0, lastK = std::ceil(yHi) - 1.0;
  const auto crossing = [&](double k) { return x0 + (k - y0) / m; };
  glm::dvec4 sum(0.0);
  double xa = x0;
  const auto piece = [&](double xb) {
    if (!(xb > xa)) return;
    const double j = std::floor(y0 + m * (0.5 * (xa + xb) - x0));
    const double fya = y0 + m * (xa - x0) - j;
    sum += integratePair(lineAt(axis, j), lineAt(axis, j + 1.0), xa, xb, fya, m);
    xa = xb;
  };
  if (m > 0.0)
    for (double k = firstK; k <= lastK; k += 1.0) piece(std::clamp(crossing(k), x0, x1));
  else if (m < 0.0)
    for (double k = lastK; k >= firstK; k -= 1.0) piece(std::clamp(crossing(k), x0, x1));
  piece(x1);
  return sum / (x1 - x0);
}

}  // namespace quadra::ref
