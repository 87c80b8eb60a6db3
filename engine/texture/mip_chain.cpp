// The mip chain builder: exact box-area reduction, separable, accumulated in
// double and rounded to float once per texel (error <= 0.5 float ulp of the
// result plus a few double ulps), so NPOT levels lose no row or column.
#include "texture/mip_chain.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/error.h"
#include "core/parallel.h"

namespace quadra {

namespace {

// The source texels under each destination texel along one axis, with the
// fraction of the footprint each one covers.
struct AxisTaps {
  std::vector<int> first;          // per destination texel: first source texel
  std::vector<std::size_t> begin;  // per destination texel + 1: offsets into weight
  std::vector<double> weight;
  int maxTaps = 0;
};

// Footprint of destination texel j is [j*src/dst, (j+1)*src/dst). Scaling by dst
// makes every boundary an integer, so the overlaps below are exact and sum to src.
AxisTaps boxTaps(int srcSize, int dstSize) {
  AxisTaps taps;
  taps.first.resize(std::size_t(dstSize));
  taps.begin.resize(std::size_t(dstSize) + 1);
  const std::int64_t src = srcSize;
  const std::int64_t dst = dstSize;
  for (std::int64_t j = 0; j < dst; ++j) {
    const std::int64_t lo = j * src;
    const std::int64_t hi = (j + 1) * src;
    const std::int64_t firstTexel = lo / dst;
    const std::int64_t lastTexel = (hi - 1) / dst;
    taps.first[std::size_t(j)] = int(firstTexel);
    taps.begin[std::size_t(j)] = taps.weight.size();
    for (std::int64_t i = firstTexel; i <= lastTexel; ++i) {
      const std::int64_t overlap = std::min(hi, (i + 1) * dst) - std::max(lo, i * dst);
      taps.weight.push_back(double(overlap) / double(src));
    }
    taps.maxTaps = std::max(taps.maxTaps, int(lastTexel - firstTexel + 1));
  }
  taps.begin[std::size_t(dst)] = taps.weight.size();
  return taps;
}

// Destination rows [rowBegin, rowEnd): horizontal taps per source row, then the
// vertical weight, both in double. Each row's arithmetic is independent of how
// rows are grouped into tasks, which keeps parallel output bit-identical.
void reduceRows(const Image& src, const AxisTaps& xTaps, const AxisTaps& yTaps, Image& dst,
                std::size_t rowBegin, std::size_t rowEnd) {
  std::vector<double> acc(std::size_t(dst.width) * 4);
  for (std::size_t y = rowBegin; y < rowEnd; ++y) {
    std::fill(acc.begin(), acc.end(), 0.0);
    for (std::size_t ky = yTaps.begin[y]; ky < yTaps.begin[y + 1]; ++ky) {
      const int srcRow = yTaps.first[y] + int(ky - yTaps.begin[y]);
      const double wy = yTaps.weight[ky];
      for (int x = 0; x < dst.width; ++x) {
        double h[4] = {0.0, 0.0, 0.0, 0.0};
        const std::size_t tapBegin = xTaps.begin[std::size_t(x)];
        const float* texel = src.texel(xTaps.first[std::size_t(x)], srcRow);
        for (std::size_t kx = tapBegin; kx < xTaps.begin[std::size_t(x) + 1]; ++kx, texel += 4) {
          const double wx = xTaps.weight[kx];
          for (int c = 0; c < 4; ++c) h[c] += wx * double(texel[c]);
        }
        double* a = &acc[std::size_t(x) * 4];
        for (int c = 0; c < 4; ++c) a[c] += wy * h[c];
      }
    }
    float* out = dst.texel(0, int(y));
    for (std::size_t i = 0; i < acc.size(); ++i) out[i] = float(acc[i]);
  }
}

}  // namespace

Image downsampleBox(const Image& src, int dstW, int dstH, const Executor* executor) {
  QUADRA_CHECK(src.width > 0 && src.height > 0);
  QUADRA_CHECK(dstW > 0 && dstH > 0);
  QUADRA_CHECK_OP(src.rgba.size(), ==, std::size_t(src.width) * std::size_t(src.height) * 4);
  const AxisTaps xTaps = boxTaps(src.width, dstW);
  const AxisTaps yTaps = boxTaps(src.height, dstH);
  Image dst(dstW, dstH, executor);
  const auto body = [&](std::size_t begin, std::size_t end) {
    reduceRows(src, xTaps, yTaps, dst, begin, end);
  };
  if (executor == nullptr) {
    body(0, std::size_t(dstH));
    return dst;
  }
  // Aim for ~64K source texel reads per task so scheduling cost stays small.
  const std::size_t readsPerRow =
      std::size_t(xTaps.maxTaps) * std::size_t(dstW) * std::size_t(yTaps.maxTaps);
  const std::size_t grain = std::max<std::size_t>(1, (std::size_t(1) << 16) / readsPerRow);
  executor->parallelFor(std::size_t(dstH), grain, body);
  return dst;
}

namespace {

// Coverage is measured as Castaño measures it: on the bilinear reconstruction
// of alpha, at n x n points per texel, so a stroke thinner than a texel covers
// the fraction of the area it should (counting whole texels, a one-texel
// line on level 1 covers twice its level-0 share and can only be kept or
// dropped whole). n is 4 while that stays within 2^18 points (a 128² level),
// then 2, then 1 (the texel count, fine enough for levels that large), which
// keeps the rescale of a 1024² MASK texture's chain near 30 ms; edges clamp.
std::vector<float> coverageSamples(const Image& level, const Executor* executor) {
  constexpr std::size_t kMaxPoints = std::size_t(1) << 18;
  const std::size_t texels = std::size_t(level.width) * std::size_t(level.height);
  const int n = texels * 16 <= kMaxPoints ? 4 : texels * 4 <= kMaxPoints ? 2 : 1;
  const std::size_t rowPoints = std::size_t(level.width) * std::size_t(n * n);
  std::vector<float> samples(texels * std::size_t(n * n));
  const auto alpha = [&](int x, int y) {
    return double(
        level.texel(std::clamp(x, 0, level.width - 1), std::clamp(y, 0, level.height - 1))[3]);
  };
  const auto rows = [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y) {
      float* out = &samples[std::size_t(y) * rowPoints];
      if (n == 1) {  // one point per texel, at its centre: the texel itself
        for (int x = 0; x < level.width; ++x) *out++ = level.texel(x, y)[3];
        continue;
      }
      for (int x = 0; x < level.width; ++x)
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            // Texel space with texel centres at integers: x + (i + 0.5) / n - 0.5.
            const double sx = x + (i + 0.5) / n - 0.5, sy = y + (j + 0.5) / n - 0.5;
            const double fx0 = std::floor(sx), fy0 = std::floor(sy);
            const int x0 = int(fx0), y0 = int(fy0);
            const double fx = sx - fx0, fy = sy - fy0;
            const double top = (1 - fx) * alpha(x0, y0) + fx * alpha(x0 + 1, y0);
            const double bottom = (1 - fx) * alpha(x0, y0 + 1) + fx * alpha(x0 + 1, y0 + 1);
            *out++ = float((1 - fy) * top + fy * bottom);
          }
    }
  };
  if (executor == nullptr) {
    rows(0, std::size_t(level.height));
  } else {
    executor->parallelFor(std::size_t(level.height), 16, rows);
  }
  return samples;
}

// The fraction of the samples at or above `threshold`.
double fractionAtLeast(const std::vector<float>& samples, float threshold) {
  std::size_t count = 0;
  for (const float value : samples) count += value >= threshold ? 1 : 0;
  return double(count) / double(samples.size());
}

}  // namespace

double alphaCoverage(const Image& image, float cutoff, const Executor* executor) {
  return fractionAtLeast(coverageSamples(image, executor), cutoff);
}

void scaleAlphaToCoverage(Image& level, float cutoff, double coverage, const Executor* executor) {
  if (!(cutoff > 0.0f && cutoff <= 1.0f)) return;
  const std::vector<float> samples = coverageSamples(level, executor);
  // Scaling a sample's texels by s scales the sample (the clamp at 1 aside),
  // so it passes at scale s when it is at least cutoff / s.
  const auto coverageAt = [&](double scale) {
    return fractionAtLeast(samples, float(double(cutoff) / scale));
  };
  float smallest = 2.0f;  // the smallest sample above 0
  for (const float value : samples)
    if (value > 0.0f) smallest = std::min(smallest, value);
  if (smallest > 1.0f) return;  // nothing to scale up
  // At `high` every sample above 0 passes: no larger scale covers more.
  double low = 0.0, high = std::max(1.0, double(cutoff) / double(smallest));
  // 24 halvings bring the interval to 2^-24 of `high`, a float step of the
  // threshold, so the two ends differ by at most the samples at one value.
  for (int step = 0; step < 24; ++step) {
    const double middle = 0.5 * (low + high);
    (coverageAt(middle) < coverage ? low : high) = middle;
  }
  const double scale =
      std::abs(coverageAt(low) - coverage) < std::abs(coverageAt(high) - coverage) ? low : high;
  for (std::size_t i = 0; i < level.rgba.size(); i += 4) {
    const float alpha = level.rgba[i + 3];
    if (!(alpha > 0.0f)) continue;
    const float scaled = float(std::min(1.0, double(alpha) * scale));
    const double factor = double(scaled) / double(alpha);
    for (int c = 0; c < 3; ++c) level.rgba[i + c] = float(double(level.rgba[i + c]) * factor);
    level.rgba[i + 3] = scaled;
  }
}

MipChain::MipChain(const Image& level0, const Executor* executor,
                   std::optional<float> coverageCutoff)
    : level0_(&level0) {
  int w = level0.width;
  int h = level0.height;
  if (w <= 0 || h <= 0) return;
  const double coverage0 = coverageCutoff ? alphaCoverage(level0, *coverageCutoff, executor) : 0.0;
  // With a cutoff, each level is reduced from the previous one before its
  // alpha scale, so scales do not compound down the chain (as NVTT does).
  Image unscaled;
  // floor(floor(w / 2^l) / 2) == floor(w / 2^(l+1)), so halving the previous
  // level's size gives exactly the header's per-level formula.
  while (w > 1 || h > 1) {
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
    const Image& previous = levels_.empty() ? level0 : coverageCutoff ? unscaled : levels_.back();
    Image next = downsampleBox(previous, w, h, executor);
    if (coverageCutoff) {
      unscaled = next;
      scaleAlphaToCoverage(next, *coverageCutoff, coverage0, executor);
    }
    levels_.push_back(std::move(next));
  }
}

}  // namespace quadra
