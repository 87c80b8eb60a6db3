// The mip chain builder: exact box-area reduction, separable, accumulated in
// double and rounded to float once per texel (error <= 0.5 float ulp of the
// result plus a few double ulps), so NPOT levels lose no row or column.
#include "texture/mip_chain.h"

#include <algorithm>
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

MipChain::MipChain(const Image& level0, const Executor* executor) : level0_(&level0) {
  int w = level0.width;
  int h = level0.height;
  if (w <= 0 || h <= 0) return;
  // floor(floor(w / 2^l) / 2) == floor(w / 2^(l+1)), so halving the previous
  // level's size gives exactly the header's per-level formula.
  while (w > 1 || h > 1) {
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
    const Image& previous = levels_.empty() ? level0 : levels_.back();
    Image next = downsampleBox(previous, w, h, executor);
    levels_.push_back(std::move(next));
  }
}

}  // namespace quadra
