// The anisotropic filter: the kernel against its definition (texture/anisotropic.h)
// evaluated in double on the same mip chain; each lookup's value independent
// of the lookups sharing its lane group (the kernel packs their taps together);
// and no less accurate against the box ideal than the filter it replaced (N
// trilinear probes at λ = log2(major / N)), evaluated in double here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>
#include <vector>

#include "core/parallel.h"
#include "lab/texture/footprints.h"
#include "lab/texture/ground_truth.h"
#include "lab/texture/test_textures.h"
#include "sampler_helpers.h"
#include "texture/anisotropic.h"
#include "texture/mip_chain.h"
#include "texture/texture_sampler.h"

namespace quadra {
namespace {

// The mip chain as double-precision bilinear references, and the footprint's
// singular value decomposition, shared by the two filters written out below.
class MipReference {
 public:
  MipReference(const Texture& texture) : mips_(texture.mips()) {
    for (int l = 0; l < mips_.levelCount(); ++l)
      levels_.emplace_back(mips_.level(l), texture.sampler());
  }
  int levels() const { return int(levels_.size()); }
  void bilinear(int level, double u, double v, double rgba[4]) const {
    levels_[std::size_t(level)].lookup(u, v, rgba);
  }
  int width() const { return mips_.level(0).width; }
  int height() const { return mips_.level(0).height; }

 private:
  const MipChain& mips_;
  std::vector<BilinearReference> levels_;
};

struct Axes {
  double major = 0, minor = 0;
  double ex = 1, ey = 0;          // screen-space singular vector of major
  double axisU = 0, axisV = 0;    // J (ex, ey): the major axis in uv
  double probes = 1, lod = -126;  // N and log2(major / N)
};

Axes axesOf(const MipReference& mips, const Lookup& l, int maxAniso) {
  const double xu = l[2] * mips.width(), xv = l[3] * mips.height();
  const double yu = l[4] * mips.width(), yv = l[5] * mips.height();
  const double p = xu * xu + xv * xv, q = xu * yu + xv * yv, r = yu * yu + yv * yv;
  const double root = std::sqrt(0.25 * (p - r) * (p - r) + q * q);
  Axes a;
  a.major = std::sqrt(0.5 * (p + r) + root);
  a.minor = std::sqrt(std::max(0.5 * (p + r) - root, 0.0));
  double ex = p >= r ? 0.5 * (p + r) + root - r : q, ey = p >= r ? q : 0.5 * (p + r) + root - p;
  const double length = std::hypot(ex, ey);
  if (length > 0) a.ex = ex / length, a.ey = ey / length;
  a.axisU = l[2] * a.ex + l[4] * a.ey;
  a.axisV = l[3] * a.ex + l[5] * a.ey;
  a.probes = std::clamp(std::ceil(a.major / std::max(a.minor, 1e-30)), 1.0, double(maxAniso));
  if (a.major > 0) a.lod = std::log2(a.major / a.probes);
  return a;
}

// texture/anisotropic.h, word for word, in double.
void anisotropicDefinition(const MipReference& mips, const Lookup& l, double rgba[4],
                           int maxAniso = 16) {
  using namespace aniso;
  const Axes a = axesOf(mips, l, maxAniso);
  const int last = mips.levels() - 1;
  const double read = std::clamp(a.lod, 0.0, double(last));
  const bool blend =
      a.major < double(kBlendBelowRatio) * a.minor || double(maxAniso) < double(kBlendBelowRatio);
  // The line as a multiple of the major axis, and the trapezoid's ramps on it.
  const double line = blend ? 1.0 : std::abs(a.ex) + std::abs(a.ey);
  const double rampWidth = std::min(std::abs(a.ex), std::abs(a.ey)) / line;
  const double tapSpacing = blend ? double(kBlendedTapSpacing) : double(kTapSpacing);
  auto spacing = [&](double naturalLevel) {
    if (a.lod < 0)
      return std::max(a.major / a.probes, std::min(a.major / double(kMagnifiedTaps), 1.0));
    return std::ldexp(1.0, int(naturalLevel));
  };
  auto run = [&](int level, double space, double out[4]) {
    double n = std::ceil(a.major * line / (tapSpacing * space));
    if (n > 1) n = std::ceil(n / kChunk) * kChunk;
    n = std::max(n, 1.0);
    double sum[4] = {0, 0, 0, 0}, weights = 0;
    for (int j = 0; j < int(n); ++j) {
      const double o = (j + 0.5) / n - 0.5;
      const double w = blend ? 1.0 : std::clamp((0.5 - std::abs(o)) / rampWidth, 0.0, 1.0);
      double c[4];
      mips.bilinear(level, l[0] + a.axisU * line * o, l[1] + a.axisV * line * o, c);
      for (int k = 0; k < 4; ++k) sum[k] += w * c[k];
      weights += w;
    }
    for (int k = 0; k < 4; ++k) out[k] = sum[k] / weights;
  };
  if (blend) {
    const int fine = int(std::floor(read));
    const double t = read - fine;
    const double space = spacing(std::floor(a.lod));
    run(fine, space, rgba);
    if (t > 0) {
      double coarse[4];
      run(std::min(fine + 1, last), a.lod < 0 ? space : 2 * space, coarse);
      for (int k = 0; k < 4; ++k) rgba[k] += (coarse[k] - rgba[k]) * t;
    }
    return;
  }
  run(std::min(int(std::floor(read + 0.5)), last), spacing(std::floor(a.lod + 0.5)), rgba);
}

// The filter this one replaced: N trilinear probes at λ along the major axis.
void previousFilter(const MipReference& mips, const Lookup& l, double rgba[4], int maxAniso) {
  const Axes a = axesOf(mips, l, maxAniso);
  const int last = mips.levels() - 1;
  const double lod = std::clamp(a.lod, 0.0, double(last));
  const int fine = int(std::floor(lod));
  const double t = lod - fine;
  for (int k = 0; k < 4; ++k) rgba[k] = 0;
  for (int i = 0; i < int(a.probes); ++i) {
    const double o = (i + 0.5) / a.probes - 0.5;
    double c[4], coarse[4];
    mips.bilinear(fine, l[0] + a.axisU * o, l[1] + a.axisV * o, c);
    mips.bilinear(std::min(fine + 1, last), l[0] + a.axisU * o, l[1] + a.axisV * o, coarse);
    for (int k = 0; k < 4; ++k) rgba[k] += (c[k] + (coarse[k] - c[k]) * t) / a.probes;
  }
}

std::vector<Lookup> lookupsOf(const FootprintSet& set) {
  std::vector<Lookup> lookups;
  for (std::size_t i = 0; i < set.size(); ++i)
    lookups.push_back({set.u[i], set.v[i], set.dudx[i], set.dvdx[i], set.dudy[i], set.dvdy[i]});
  return lookups;
}

// Float positions and weights against double ones: the kernel's values stay
// within float rounding of the definition's, except where a tap count or a
// level is decided at a boundary the two precisions put on different sides
// (a different but equally valid filter there).
TEST(Anisotropic, KernelMatchesItsDefinitionInDouble) {
  for (const WrapMode wrap : {WrapMode::Repeat, WrapMode::ClampToEdge}) {
    const auto image = std::make_shared<Image>(makeValueNoiseTexture(96, 64, 21));
    const Texture texture(image, samplerWith(wrap));
    const MipReference mips(texture);
    const std::vector<Lookup> lookups = lookupsOf(
        makeFootprintSet({.count = 36 * 40, .seed = 3, .textureWidth = 96, .textureHeight = 64}));
    const std::vector<float> got = sampleAll(texture, Filter::Anisotropic, Isa::Scalar, lookups);
    std::size_t close = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i < lookups.size(); ++i) {
      double want[4];
      anisotropicDefinition(mips, lookups[i], want);
      double error = 0.0;
      for (int c = 0; c < 4; ++c)
        error = std::max(error, std::abs(double(got[i * 4 + std::size_t(c)]) - want[c]));
      close += error <= 2e-5 ? 1 : 0;
      worst = std::max(worst, error);
    }
    std::printf(
        "[ aniso ] %s: %zu of %zu lookups within 2e-5 of the double definition, worst %.3g\n",
        wrapName(wrap), close, lookups.size(), worst);
    EXPECT_GE(close, lookups.size() * 99 / 100) << wrapName(wrap);
    EXPECT_LT(worst, 0.05) << wrapName(wrap);
  }
}

// The kernel packs the taps of a lane group's lookups densely: a lookup's
// value must not depend on which lookups share its group, on any path.
TEST(Anisotropic, ValueDoesNotDependOnTheOtherLookupsOfItsGroup) {
  const auto image = std::make_shared<Image>(makeValueNoiseTexture(64, 64, 4));
  const Texture texture(image, SamplerState{});
  std::vector<Lookup> lookups = randomLookups(96, 31);
  std::vector<Lookup> shuffled(lookups.rbegin(), lookups.rend());
  std::rotate(shuffled.begin(), shuffled.begin() + 5, shuffled.end());
  for (const Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
    if (!isaSupported(isa)) continue;
    const std::vector<float> inOrder = sampleAll(texture, Filter::Anisotropic, isa, lookups);
    const std::vector<float> reordered = sampleAll(texture, Filter::Anisotropic, isa, shuffled);
    for (std::size_t i = 0; i < lookups.size(); ++i) {
      const std::size_t j = (lookups.size() - 1 - i + lookups.size() - 5) % lookups.size();
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(inOrder[i * 4 + std::size_t(c)], reordered[j * 4 + std::size_t(c)])
            << isaName(isa) << " lookup " << i;
    }
  }
}

// No loss of accuracy against the box ideal, on per-texel noise and on smooth
// noise: over a stratified footprint set the kernel's RMSE is at most the
// previous filter's overall, and well below it from 8:1 on (the trapezoid
// over the whole shadow). The magnified and near-isotropic footprints, 180
// here, move by a few percent either way with the texture and the sample
// (on smooth textures the near-isotropic ones lose up to 4%: 0.0087 against
// 0.0084 in the report's smooth texture); they are judged on the report's
// 20480 footprints, where every bucket is at or below the previous filter.
TEST(Anisotropic, AtLeastAsAccurateAsThePreviousFilter) {
  const Executor executor(0);
  const int size = 128;
  const struct {
    const char* name;
    Image image;
  } textures[] = {{"noise", makeValueNoiseTexture(size, size, 5)},
                  {"smooth", makeSmoothNoiseTexture(size, size, 5)}};
  for (const auto& t : textures) {
    const auto image = std::make_shared<Image>(t.image);
    const Texture texture(image, SamplerState{});
    const MipReference mips(texture);
    const FootprintSet set = makeFootprintSet(
        {.count = 36 * 30, .seed = 9, .textureWidth = size, .textureHeight = size});
    const std::vector<Lookup> lookups = lookupsOf(set);
    const BilinearReference level0(*image, SamplerState{});
    const GroundTruthSet truth = groundTruthSet(level0, set.footprints(), {}, executor);
    // The default maximum, and 2, where both filters blend two levels for
    // every footprint (texture/anisotropic.h, kBlendBelowRatio): there the
    // smooth texture's sheared footprints lose up to 2% (0.0246 against
    // 0.0242 here) and the report's five textures gain (0.0250 against 0.0260).
    for (const int maxAniso : {16, 2}) {
      std::vector<float> got(lookups.size() * 4);
      TextureSampler(texture, FilterSettings(Filter::Anisotropic, maxAniso), Isa::Scalar)
          .sample(set.batch(), 0, set.size(), got.data());
      struct Sums {
        double now = 0, before = 0;
        int n = 0;
        double rmse(double s) const { return std::sqrt(s / (3.0 * n)); }
      } all, magnified, nearIsotropic, anisotropic;
      for (std::size_t i = 0; i < lookups.size(); ++i) {
        double previous[4];
        previousFilter(mips, lookups[i], previous, maxAniso);
        double now = 0, before = 0;
        for (int c = 0; c < 3; ++c) {
          const double want = truth.rgba[i * 4 + std::size_t(c)];
          now += std::pow(got[i * 4 + std::size_t(c)] - want, 2);
          before += std::pow(previous[c] - want, 2);
        }
        for (Sums* s : {&all, set.scaleBucket[i] == 0 ? &magnified : nullptr,
                        set.anisoBucket[i] == 0 ? &nearIsotropic : nullptr,
                        set.anisoBucket[i] >= 3 ? &anisotropic : nullptr})
          if (s) s->now += now, s->before += before, ++s->n;
      }
      for (const auto& [category, s, allowance] :
           {std::tuple{"all", all, maxAniso == 16 ? 1.0 : 1.02},
            std::tuple{"magnified", magnified, 1.05},
            std::tuple{"near-isotropic", nearIsotropic, 1.05},
            std::tuple{"8:1 and more", anisotropic, maxAniso == 16 ? 0.9 : 1.02}}) {
        const double now = s.rmse(s.now), before = s.rmse(s.before);
        std::printf("[ aniso-%d ] %s, %s: RMSE %.5f, previous filter %.5f (%d footprints)\n",
                    maxAniso, t.name, category, now, before, s.n);
        EXPECT_LE(now, allowance * before) << maxAniso << " " << t.name << " " << category;
      }
    }
  }
}

}  // namespace
}  // namespace quadra
