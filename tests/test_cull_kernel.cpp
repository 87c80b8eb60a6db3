// Setup's cull kernel on every ISA path against a reference written here in
// int64 and double: each triangle's verdict in setup's order (not finite,
// beyond one viewport plane, needs clipping, zero area, back face, no pixel
// centre, small and covering no sample), including triangles whose two
// cross-product terms round to the same float, and a kept triangle's
// pixel-centre box, winding and sample coverage, at every sample count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>

#include "setup/cull_kernel.h"

namespace quadra {
namespace {

enum class Verdict { NotFinite, Outside, Clip, Degenerate, BackFace, NoPixel, NoSample, Keep };

struct Expected {
  Verdict verdict;
  std::int64_t area;
  bool productsTie;  // the two terms of the area are the same float
  std::int32_t minX, minY, maxX, maxY;
  bool small;         // the kernel decides its sample coverage (cull_kernel.h)
  bool coversSample;  // a sample of a pixel in the box (computed for small ones)
};

// Pixels whose centre px + 0.5 lies in [lo, hi] (1/256 units), in [0, limit):
// by the definition, in floating point on exact values.
void centresIn(std::int64_t lo, std::int64_t hi, int limit, std::int32_t& first,
               std::int32_t& last) {
  first = std::int32_t(std::max(0.0, std::ceil(double(lo) / kSubpixelScale - 0.5)));
  last = std::int32_t(std::min(double(limit - 1), std::floor(double(hi) / kSubpixelScale - 0.5)));
}

// Whether a triangle (clockwise in y-down window space once its area's sign
// is known) covers a sample of a pixel of the box: each edge p->q's function
// dx (Y - yp) - dy (X - xp) at the sample, plus one on a top or left edge, by
// the definition in int64.
bool coversSample(const std::int64_t x[3], const std::int64_t y[3], bool negative,
                  const Expected& e, const SamplePattern& pattern) {
  int c[3] = {0, 1, 2};
  if (negative) std::swap(c[1], c[2]);
  for (std::int64_t py = e.minY; py <= e.maxY; ++py)
    for (std::int64_t px = e.minX; px <= e.maxX; ++px)
      for (int s = 0; s < pattern.count; ++s) {
        constexpr int kUnit = kSubpixelScale / kSampleUnitsPerPixel;
        const std::int64_t sx =
            px * kSubpixelScale + kSubpixelScale / 2 + kUnit * pattern.offsets[s].x;
        const std::int64_t sy =
            py * kSubpixelScale + kSubpixelScale / 2 + kUnit * pattern.offsets[s].y;
        bool inside = true;
        for (int k = 0; k < 3; ++k) {
          const int p = c[(k + 1) % 3], q = c[(k + 2) % 3];
          const std::int64_t dx = x[q] - x[p], dy = y[q] - y[p];
          const bool topLeft = dy < 0 || (dy == 0 && dx > 0);
          inside = inside && dx * (sy - y[p]) - dy * (sx - x[p]) + (topLeft ? 1 : 0) > 0;
        }
        if (inside) return true;
      }
  return false;
}

Expected expect(const TransformedVertices& v, const std::uint32_t* corner, const Viewport& view,
                const SamplePattern& pattern, FaceCulling faces) {
  constexpr std::uint8_t kOutsideViewport =
      kOutsideNear | kOutsideFar | kOutsideLeft | kOutsideRight | kOutsideBottom | kOutsideTop;
  const std::uint8_t c0 = v.outcode[corner[0]], c1 = v.outcode[corner[1]],
                     c2 = v.outcode[corner[2]];
  Expected e;
  std::int64_t x[3], y[3];
  for (int k = 0; k < 3; ++k) x[k] = v.subpixel[corner[k]].x, y[k] = v.subpixel[corner[k]].y;
  e.area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  e.productsTie =
      float(x[1] - x[0]) * float(y[2] - y[0]) == float(x[2] - x[0]) * float(y[1] - y[0]);
  const std::int64_t reach = pattern.reachSubpixels();
  const std::int64_t lowX = std::min({x[0], x[1], x[2]}), highX = std::max({x[0], x[1], x[2]});
  const std::int64_t lowY = std::min({y[0], y[1], y[2]}), highY = std::max({y[0], y[1], y[2]});
  centresIn(lowX - reach, highX + reach, view.width, e.minX, e.maxX);
  centresIn(lowY - reach, highY + reach, view.height, e.minY, e.maxY);
  e.small = e.maxX - e.minX < kCoverageBox && e.maxY - e.minY < kCoverageBox &&
            highX - lowX <= kMaxCoverageExtent && highY - lowY <= kMaxCoverageExtent &&
            !e.productsTie;
  // Only where some kernel decides it (a big box would take long to walk).
  e.coversSample = e.small && e.area != 0 && coversSample(x, y, e.area < 0, e, pattern);
  const bool front = (e.area < 0) != faces.frontIsClockwise;
  if ((c0 | c1 | c2) & kNotFinite)
    e.verdict = Verdict::NotFinite;
  else if (c0 & c1 & c2 & kOutsideViewport)
    e.verdict = Verdict::Outside;
  else if ((c0 | c1 | c2) & kNeedsClipping)
    e.verdict = Verdict::Clip;
  else if (e.area == 0)
    e.verdict = Verdict::Degenerate;
  else if (faces.cullBackFaces && !front)
    e.verdict = Verdict::BackFace;
  else if (e.minX > e.maxX || e.minY > e.maxY)
    e.verdict = Verdict::NoPixel;
  else if (e.small && !e.coversSample)
    e.verdict = Verdict::NoSample;
  else
    e.verdict = Verdict::Keep;
  return e;
}

TEST(CullKernel, EveryPathMatchesTheExactReference) {
  const Viewport view{1920, 1080};
  // Within the guard band a snapped coordinate is below 2^22 in magnitude.
  constexpr std::int32_t kLimit = (1 << 22) - 1;
  std::mt19937 rng(11);
  TransformedVertices v;
  std::vector<std::uint32_t> indices;
  const auto add = [&](SubpixelPosition p, std::uint8_t code) {
    v.subpixel.push_back(p);
    v.outcode.push_back(code);
    indices.push_back(std::uint32_t(v.subpixel.size() - 1));
  };
  std::uniform_int_distribution<std::int32_t> anywhere(-kLimit, kLimit);
  std::uniform_int_distribution<std::int32_t> onScreen(-512, 2000 * kSubpixelScale);
  std::uniform_int_distribution<std::int32_t> small(-700, 700), tiny(-150, 150);
  std::uniform_int_distribution<int> codeBit(0, 15);
  int nearTies = 0;  // non-zero areas whose products are equal floats
  for (int t = 0; t < 20000; ++t) {
    const int kind = t % 4;
    SubpixelPosition p[3];
    if (kind == 0) {  // anywhere in the guard band
      for (auto& q : p) q = {anywhere(rng), anywhere(rng)};
    } else if (kind == 1) {  // small or tiny, near or across pixel centres and samples
      const SubpixelPosition at{onScreen(rng), onScreen(rng)};
      auto& offset = t / 4 % 2 == 0 ? small : tiny;
      for (auto& q : p) q = {at.x + offset(rng), at.y + offset(rng)};
    } else if (kind == 2) {  // (a+1)(a-1) against a*a: one apart, the same as floats
      const std::int32_t a = std::uniform_int_distribution<std::int32_t>(1 << 20, 1 << 21)(rng);
      const std::int32_t x0 = -a / 2, y0 = -a / 2;
      const int flip = t / 4 % 3;  // area -1, +1 or 0
      p[0] = {x0, y0};
      if (flip == 0) p[1] = {x0 + a + 1, y0 + a}, p[2] = {x0 + a, y0 + a - 1};
      if (flip == 1) p[1] = {x0 + a, y0 + a - 1}, p[2] = {x0 + a + 1, y0 + a};
      if (flip == 2) p[1] = {x0 + a, y0 + a}, p[2] = {x0 + a / 2, y0 + a / 2};
    } else {  // collinear on a random line, or a repeated vertex
      const SubpixelPosition at{onScreen(rng), onScreen(rng)}, d{small(rng), small(rng)};
      p[0] = at, p[1] = {at.x + d.x, at.y + d.y};
      p[2] = t % 8 == 3 ? at : SubpixelPosition{at.x + 3 * d.x, at.y + 3 * d.y};
    }
    for (const auto& q : p) {
      const int bit = codeBit(rng);  // mostly none, sometimes one flag of the eight
      add(q, bit < 8 ? std::uint8_t(1u << bit) : std::uint8_t(0));
    }
  }
  // Every compiled kernel, the 16-lane one too (setup runs the 8-lane one on
  // AVX-512 machines).
  const std::pair<Isa, const CullKernel& (*)()> kernels[] = {{Isa::Scalar, cullKernelScalar},
                                                             {Isa::Sse2, cullKernelSse2},
                                                             {Isa::Avx2, cullKernelAvx2},
                                                             {Isa::Avx512, cullKernelAvx512}};
  int smallDropped = 0, smallKept = 0;  // the kernel tested them: covering no sample, or one
  for (const auto& [isa, kernelOf] : kernels) {
    if (!isaSupported(isa)) continue;
    const CullKernel& kernel = kernelOf();
    const std::size_t triangles = indices.size() / 3;
    for (const int samples : {1, 2, 4, 8, 16}) {
      const SamplePattern& pattern = samplePattern(samples);
      for (const FaceCulling faces :
           {FaceCulling{true, false}, FaceCulling{true, true}, FaceCulling{false, false}}) {
        for (std::size_t first = 0; first < triangles;) {
          // Every group size, the short last group included.
          const int count = int(std::min<std::size_t>(
              std::size_t(kernel.lanes) - first / std::size_t(kernel.lanes) % 3,
              triangles - first));
          CullGroup group;
          kernel.cull(&indices[3 * first], count, v.subpixel.data(), v.outcode.data(), view,
                      pattern, pattern.reachSubpixels(), faces, group);
          int counted[8] = {};
          for (int k = 0; k < count; ++k) {
            const Expected e = expect(v, &indices[3 * (first + k)], view, pattern, faces);
            SCOPED_TRACE(testing::Message() << isaName(isa) << " triangle " << first + k << ", "
                                            << samples << " samples");
            ++counted[int(e.verdict)];
            EXPECT_EQ(bool(group.keep >> k & 1), e.verdict == Verdict::Keep);
            EXPECT_EQ(bool(group.clip >> k & 1), e.verdict == Verdict::Clip);
            if (e.verdict == Verdict::Keep) {
              EXPECT_EQ(bool(group.negative >> k & 1), e.area < 0);
              EXPECT_EQ(group.minX[k], e.minX);
              EXPECT_EQ(group.minY[k], e.minY);
              EXPECT_EQ(group.maxX[k], e.maxX);
              EXPECT_EQ(group.maxY[k], e.maxY);
              // Found covering exactly when it does, for the triangles it tests.
              if (e.small) {
                EXPECT_TRUE(group.covers >> k & 1);
              }
              if (group.covers >> k & 1) {
                EXPECT_TRUE(e.coversSample);
              }
              smallKept += e.small ? 1 : 0;
            }
            smallDropped += e.verdict == Verdict::NoSample ? 1 : 0;
            if (isa == Isa::Scalar && samples == 1 && e.area != 0 && e.productsTie) ++nearTies;
          }
          const std::uint32_t beyond = count == 32 ? 0u : ~0u << count;
          EXPECT_EQ((group.keep | group.clip | group.covers) & beyond, 0u);
          EXPECT_EQ(group.covers & ~group.keep, 0u);
          EXPECT_EQ(group.notFinite, counted[int(Verdict::NotFinite)]);
          EXPECT_EQ(group.outside, counted[int(Verdict::Outside)] + counted[int(Verdict::NoPixel)] +
                                       counted[int(Verdict::NoSample)]);
          EXPECT_EQ(group.degenerate, counted[int(Verdict::Degenerate)]);
          EXPECT_EQ(group.backFace, counted[int(Verdict::BackFace)]);
          first += std::size_t(count);
        }
      }
    }
  }
  EXPECT_GT(smallDropped, 1000);
  EXPECT_GT(smallKept, 1000);
  EXPECT_GT(nearTies, 1000);
}

}  // namespace
}  // namespace quadra
