// Building the prepared environment's cube maps (prepared_environment.h): the
// panorama resampled onto cube faces, the mip chain with each level's borders
// copied from the neighbouring faces, the irradiance cube, the sample pattern.
// Every texel is computed by itself in a fixed order, so the threads only
// split the work: the bits do not depend on their number.
#include "shading/prepared_environment.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "shading/brdf_table.h"
#include "shading/cube_layout.h"
#include "shading/environment_image.h"

namespace quadra {
namespace {

constexpr int kIrradianceSourceSize = 64;
constexpr int kTexelFloats =
    EnvironmentView::kTexelFloats;  // face size of the level the irradiance integrates

std::size_t faceFloats(int n) {
  return std::size_t(n + 2) * std::size_t(n + 2) * kTexelFloats;
}

// LIGHTING.md's radiance of direction d (unnormalized) in the panorama:
// bilinear at u = 0.5 + atan2(x, -z) / 2 pi, v = acos(y) / pi, wrapping in u,
// clamping in v.
void panoramaRadiance(const EnvironmentImage& image, const double d[3], float out[3]) {
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double u = 0.5 + std::atan2(d[0], -d[2]) / (2.0 * M_PI);
  const double v = std::acos(std::clamp(d[1] / len, -1.0, 1.0)) / M_PI;
  const double x = u * image.width - 0.5, y = v * image.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const float ax = float(x - fx), ay = float(y - fy);
  int i0 = int(fx) % image.width;
  if (i0 < 0) i0 += image.width;
  const int i1 = i0 + 1 == image.width ? 0 : i0 + 1;
  const int j0 = std::clamp(int(fy), 0, image.height - 1);
  const int j1 = std::clamp(int(fy) + 1, 0, image.height - 1);
  const float *t00 = image.texel(i0, j0), *t10 = image.texel(i1, j0);
  const float *t01 = image.texel(i0, j1), *t11 = image.texel(i1, j1);
  for (int c = 0; c < 3; ++c) {
    const float top = t00[c] + (t10[c] - t00[c]) * ax;
    const float bottom = t01[c] + (t11[c] - t01[c]) * ax;
    out[c] = top + (bottom - top) * ay;
  }
}

// Bilinear lookup of face `face`'s inner texels at face coordinates (s, t),
// clamped to the face: how a level's border texels take the neighbours' values.
void faceBilinear(const float* level, int n, int face, double s, double t, float out[3]) {
  const double x = std::clamp((s + 1.0) * 0.5 * n + 0.5, 1.0, double(n));
  const double y = std::clamp((t + 1.0) * 0.5 * n + 0.5, 1.0, double(n));
  const int x0 = std::min(int(x), n), y0 = std::min(int(y), n);
  const int x1 = std::min(x0 + 1, n), y1 = std::min(y0 + 1, n);
  const float ax = float(x - x0), ay = float(y - y0);
  const float* f = level + face * faceFloats(n);
  const auto at = [&](int px, int py) {
    return f + (std::size_t(py) * (n + 2) + px) * kTexelFloats;
  };
  for (int c = 0; c < 3; ++c) {
    const float top = at(x0, y0)[c] + (at(x1, y0)[c] - at(x0, y0)[c]) * ax;
    const float bottom = at(x0, y1)[c] + (at(x1, y1)[c] - at(x0, y1)[c]) * ax;
    out[c] = top + (bottom - top) * ay;
  }
}

void fillBorders(float* level, int n) {
  for (int face = 0; face < cube::kFaces; ++face) {
    float* f = level + face * faceFloats(n);
    for (int q = 0; q < n + 2; ++q) {
      for (int p = 0; p < n + 2; ++p) {
        if (p > 0 && p <= n && q > 0 && q <= n) continue;
        double d[3], s, t;
        cube::faceDirection(face, cube::paddedCentre(p, n), cube::paddedCentre(q, n), d);
        const int other = cube::directionFace(d, s, t);
        faceBilinear(level, n, other, s, t, f + (std::size_t(q) * (n + 2) + p) * kTexelFloats);
      }
    }
  }
}

}  // namespace

int PreparedEnvironment::cubeSizeFor(int width) {
  int size = 16;
  while (size < 1024 && size * 2 * 4 <= width + width / 2) size *= 2;
  return size;
}

PreparedEnvironment::PreparedEnvironment(const EnvironmentImage& image,
                                         const EnvironmentPlacement& placement,
                                         const Executor& executor) {
  size_ = cubeSizeFor(image.width);
  levelCount_ = 1;
  while ((size_ >> (levelCount_ - 1)) > 1) ++levelCount_;
  std::size_t total = 0;
  for (int l = 0; l < levelCount_; ++l) {
    levelOffset_.push_back(std::int64_t(total));
    total += cube::kFaces * faceFloats(size_ >> l);
  }
  radiance_.resize(total);

  // Level 0: the panorama at each padded texel's centre (the border texels'
  // directions lie in the neighbouring faces, so level 0 needs no copying).
  const double angle = double(placement.rotationDegrees) * M_PI / 180.0;
  const double c = std::cos(angle), sn = std::sin(angle);
  const float intensity = placement.intensity;
  const int n0 = size_;
  executor.parallelFor(std::size_t(cube::kFaces) * (n0 + 2), 8, [&](std::size_t b, std::size_t e) {
    for (std::size_t row = b; row < e; ++row) {
      const int face = int(row / (n0 + 2)), q = int(row % (n0 + 2));
      float* out =
          radiance_.data() + face * faceFloats(n0) + std::size_t(q) * (n0 + 2) * kTexelFloats;
      for (int p = 0; p < n0 + 2; ++p) {
        double d[3];
        cube::faceDirection(face, cube::paddedCentre(p, n0), cube::paddedCentre(q, n0), d);
        // R_y(-angle) d: the panorama's direction of world direction d.
        const double r[3] = {c * d[0] - sn * d[2], d[1], sn * d[0] + c * d[2]};
        panoramaRadiance(image, r, out + p * kTexelFloats);
        for (int k = 0; k < 3; ++k) out[p * kTexelFloats + k] *= intensity;
      }
    }
  });

  // The mip chain: each level from the one above by the separable binomial
  // filter [1 3 3 1] / 8 (its taps reach one texel past a face's edge, into
  // the border), so a level's texel is a smooth, nearly Gaussian average
  // rather than a box; then the borders.
  for (int l = 1; l < levelCount_; ++l) {
    const int n = size_ >> l, m = n * 2;
    const float* above = radiance_.data() + levelOffset_[l - 1];
    float* level = radiance_.data() + levelOffset_[l];
    executor.parallelFor(std::size_t(cube::kFaces) * n, 8, [&](std::size_t b, std::size_t e) {
      std::vector<float> rows(std::size_t(m + 2) * kTexelFloats);
      for (std::size_t row = b; row < e; ++row) {
        const int face = int(row / n), j = int(row % n);
        const float* src = above + face * faceFloats(m);
        // Vertical pass: padded rows 2j .. 2j + 3 of the level above.
        const std::size_t stride = std::size_t(m + 2) * kTexelFloats;
        const float* r0 = src + std::size_t(2 * j) * stride;
        for (std::size_t k = 0; k < stride; ++k)
          rows[k] = ((r0[k] + r0[k + 3 * stride]) + 3.0f * (r0[k + stride] + r0[k + 2 * stride])) *
                    0.125f;
        float* dst =
            level + face * faceFloats(n) + (std::size_t(j + 1) * (n + 2) + 1) * kTexelFloats;
        for (int i = 0; i < n; ++i)
          for (int k = 0; k < 3; ++k) {
            const float* t = rows.data() + std::size_t(2 * i) * kTexelFloats + k;
            dst[i * kTexelFloats + k] = ((t[0] + t[12]) + 3.0f * (t[4] + t[8])) * 0.125f;
          }
      }
    });
    fillBorders(level, n);
  }

  // Irradiance: (1/pi) sum over a level's texels of L x solid angle x max(0, n.d),
  // accumulated in 8 fixed partial sums (vectorizable, same order every run).
  int sourceLevel = 0;
  while ((size_ >> sourceLevel) > kIrradianceSourceSize) ++sourceLevel;
  const int ns = size_ >> sourceLevel;
  const std::size_t count = std::size_t(cube::kFaces) * ns * ns;
  const std::size_t padded = (count + 7) / 8 * 8;
  std::vector<float> sx(padded, 0.0f), sy(padded, 0.0f), sz(padded, 0.0f);
  std::vector<float> sr(padded, 0.0f), sg(padded, 0.0f), sb(padded, 0.0f);
  {
    const float* level = radiance_.data() + levelOffset_[sourceLevel];
    std::size_t k = 0;
    for (int face = 0; face < cube::kFaces; ++face) {
      for (int j = 0; j < ns; ++j) {
        for (int i = 0; i < ns; ++i, ++k) {
          const double s0 = 2.0 * i / ns - 1.0, t0 = 2.0 * j / ns - 1.0;
          const double omega = cube::rectangleSolidAngle(s0, t0, s0 + 2.0 / ns, t0 + 2.0 / ns);
          double d[3];
          cube::faceDirection(face, s0 + 1.0 / ns, t0 + 1.0 / ns, d);
          const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
          sx[k] = float(d[0] / len), sy[k] = float(d[1] / len), sz[k] = float(d[2] / len);
          const float* texel = level + face * faceFloats(ns) +
                               (std::size_t(j + 1) * (ns + 2) + i + 1) * kTexelFloats;
          const double w = omega / M_PI;
          sr[k] = float(texel[0] * w), sg[k] = float(texel[1] * w), sb[k] = float(texel[2] * w);
        }
      }
    }
  }
  constexpr int ni = kIrradianceSize;
  irradiance_.resize(cube::kFaces * faceFloats(ni));
  executor.parallelFor(irradiance_.size() / kTexelFloats, 64, [&](std::size_t b, std::size_t e) {
    for (std::size_t t = b; t < e; ++t) {
      const int face = int(t / ((ni + 2) * (ni + 2)));
      const int rest = int(t % ((ni + 2) * (ni + 2)));
      double d[3];
      cube::faceDirection(face, cube::paddedCentre(rest % (ni + 2), ni),
                          cube::paddedCentre(rest / (ni + 2), ni), d);
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const float nx = float(d[0] / len), ny = float(d[1] / len), nz = float(d[2] / len);
      float ar[8] = {}, ag[8] = {}, ab[8] = {};
      for (std::size_t k = 0; k < padded; k += 8) {
        for (int j = 0; j < 8; ++j) {
          const float cosine = std::max(nx * sx[k + j] + ny * sy[k + j] + nz * sz[k + j], 0.0f);
          ar[j] += sr[k + j] * cosine, ag[j] += sg[k + j] * cosine, ab[j] += sb[k + j] * cosine;
        }
      }
      float* out = irradiance_.data() + t * kTexelFloats;
      out[0] = ((ar[0] + ar[1]) + (ar[2] + ar[3])) + ((ar[4] + ar[5]) + (ar[6] + ar[7]));
      out[1] = ((ag[0] + ag[1]) + (ag[2] + ag[3])) + ((ag[4] + ag[5]) + (ag[6] + ag[7]));
      out[2] = ((ab[0] + ab[1]) + (ab[2] + ab[3])) + ((ab[4] + ab[5]) + (ab[6] + ab[7]));
    }
  });

  // The filtered importance samples, one set per size (lighting.h): a (u1,
  // u2) Hammersley set, u1 stratified and u2 the base-2 radical inverse,
  // stored as Heitz's disc point (t1, t2) and sqrt(1 - t1^2) (the lane code
  // needs no trigonometry).
  for (int set = 0; set < EnvironmentView::kFisSets; ++set) {
    const int count = EnvironmentView::kFisSetSize[set];
    for (int i = 0; i < count; ++i) {
      unsigned bits = unsigned(i), reversed = 0;
      for (int k = 0; k < 16; ++k) reversed = (reversed << 1) | ((bits >> k) & 1u);
      const double u1 = (i + 0.5) / count;
      const double u2 = reversed / 65536.0 + 0.5 / count;
      const double r = std::sqrt(u1), phi = 2.0 * M_PI * u2;
      const double t1 = r * std::cos(phi);
      fisSamples_.push_back(float(t1));
      fisSamples_.push_back(float(r * std::sin(phi)));
      fisSamples_.push_back(float(std::sqrt(1.0 - t1 * t1)));
    }
  }
  brdfTable_ = brdfAlbedoTable(executor);
  for (int l = 0; l < levelCount_; ++l)
    levelTexels_[l] = reinterpret_cast<const std::uint8_t*>(radiance_.data() + levelOffset_[l]);
  irradianceTexels_[0] = reinterpret_cast<const std::uint8_t*>(irradiance_.data());
}

EnvironmentView PreparedEnvironment::view() const {
  EnvironmentView v;
  v.radiance = radiance_.data();
  v.levelOffset = levelOffset_.data();
  v.levelTexels = levelTexels_;
  v.irradianceTexels = irradianceTexels_;
  v.size = size_;
  v.levelCount = levelCount_;
  v.irradiance = irradiance_.data();
  v.irradianceSize = kIrradianceSize;
  v.brdfTable = brdfTable_;
  v.fisSamples = fisSamples_.data();
  return v;
}

std::size_t PreparedEnvironment::bytes() const {
  return (radiance_.size() + irradiance_.size() + fisSamples_.size()) * sizeof(float) +
         levelOffset_.size() * sizeof(std::int64_t);
}

}  // namespace quadra
