// The shading stage (engine/shading) against independent references in double
// precision: each BRDF term against its formula, white furnaces against the
// directional albedo integrated on a hemisphere grid, the environment term
// on synthetic panoramas against LIGHTING.md's integral (and the plain split
// sum measured on the same cases), punctual lights against the
// KHR_lights_punctual formulas, the panorama's orientation and rotation,
// preprocessing bits for 1 and 2 threads, and the lane code's bits on every
// ISA path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <vector>

#include "core/parallel.h"
#include "scene/scene.h"
#include "shading/brdf_lanes.h"
#include "shading/environment_image.h"
#include "shading/prepared_environment.h"
#include "shading/shade_batch.h"
#include "shading/shade_lanes.h"
#include "simd/lanes.h"

namespace quadra {
namespace {

constexpr double kPiD = 3.14159265358979323846;

struct V3 {
  double x, y, z;
};
V3 operator+(V3 a, V3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
V3 operator-(V3 a, V3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
V3 operator*(double s, V3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
double dotD(V3 a, V3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
V3 normalized(V3 a) {
  return (1.0 / std::sqrt(dotD(a, a))) * a;
}
V3 crossD(V3 a, V3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Any orthonormal frame around n (the test's own, not the engine's).
void frameOf(V3 n, V3& t, V3& b) {
  const V3 up = std::fabs(n.y) < 0.9 ? V3{0, 1, 0} : V3{1, 0, 0};
  t = normalized(crossD(up, n));
  b = crossD(n, t);
}

// ------------------------------------------------ the formulas, in double
double ggxDRef(double nh, double a2) {
  const double d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (kPiD * d * d);
}
double smithVRef(double nv, double nl, double a2) {
  return 0.5 / (nl * std::sqrt(nv * nv * (1 - a2) + a2) + nv * std::sqrt(nl * nl * (1 - a2) + a2));
}
double schlickRef(double vh) {
  return std::pow(1.0 - vh, 5.0);
}

struct MaterialD {
  double baseColor[3] = {1, 1, 1};
  double metallic = 1, roughness = 0.5;
  double f0[3] = {0.04, 0.04, 0.04};  // dielectric f0 (ior, specular colour, specular)
  double f90 = 1.0;                   // dielectric f90 (specular)
};

// f(v, l) (n.l), channel c, glTF Appendix B with KHR_materials_specular's
// dielectric_brdf = F_d D V + (1 - max(F_d)) baseColor / pi.
double brdfCosRef(const MaterialD& m, V3 n, V3 v, V3 l, int c) {
  const double nl = dotD(n, l), nv = dotD(n, v);
  if (nl <= 0 || nv <= 0) return 0.0;
  const V3 h = normalized(v + l);
  const double a = m.roughness * m.roughness, a2 = a * a;
  const double dv = ggxDRef(std::max(0.0, dotD(n, h)), a2) * smithVRef(nv, nl, a2);
  const double w = schlickRef(std::clamp(dotD(v, h), 0.0, 1.0));
  double fd[3];
  for (int k = 0; k < 3; ++k) fd[k] = m.f0[k] + (m.f90 - m.f0[k]) * w;
  const double fdMax = std::max(fd[0], std::max(fd[1], fd[2]));
  const double dielectric = fd[c] * dv + (1.0 - fdMax) * m.baseColor[c] / kPiD;
  const double metal = (m.baseColor[c] + (1.0 - m.baseColor[c]) * w) * dv;
  return (dielectric + (metal - dielectric) * m.metallic) * nl;
}

// ------------------------------------------------ panoramas and their integral
V3 directionOfUv(double u, double v) {
  const double phi = 2 * kPiD * (u - 0.5), theta = kPiD * v;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// LIGHTING.md's radiance: bilinear at (u, v), wrapping u, clamping v.
void panoramaRef(const EnvironmentImage& e, V3 d, double out[3]) {
  d = normalized(d);
  const double u = 0.5 + std::atan2(d.x, -d.z) / (2 * kPiD);
  const double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPiD;
  const double x = u * e.width - 0.5, y = v * e.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y), ax = x - fx, ay = y - fy;
  const int i0 = ((int(fx) % e.width) + e.width) % e.width, i1 = (i0 + 1) % e.width;
  const int j0 = std::clamp(int(fy), 0, e.height - 1),
            j1 = std::clamp(int(fy) + 1, 0, e.height - 1);
  for (int c = 0; c < 3; ++c) {
    const double top = e.texel(i0, j0)[c] * (1 - ax) + e.texel(i1, j0)[c] * ax;
    const double bottom = e.texel(i0, j1)[c] * (1 - ax) + e.texel(i1, j1)[c] * ax;
    out[c] = top * (1 - ay) + bottom * ay;
  }
}

EnvironmentImage makePanorama(int w, int h, const std::function<void(V3, double[3])>& radiance) {
  EnvironmentImage e;
  e.name = "synthetic";
  e.width = w, e.height = h;
  e.rgb.resize(std::size_t(w) * h * 3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      double c[3];
      radiance(directionOfUv((i + 0.5) / w, (j + 0.5) / h), c);
      for (int k = 0; k < 3; ++k) e.rgb[(std::size_t(j) * w + i) * 3 + k] = float(c[k]);
    }
  return e;
}

// Heitz 2018's visible-normal sample (double), for the reference integrals.
V3 sampleVisibleNormal(V3 vLocal, double alpha, double u1, double u2) {
  const V3 vh = normalized({alpha * vLocal.x, alpha * vLocal.y, vLocal.z});
  const double lensq = vh.x * vh.x + vh.y * vh.y;
  const V3 t1 = lensq > 0 ? (1.0 / std::sqrt(lensq)) * V3{-vh.y, vh.x, 0} : V3{1, 0, 0};
  const V3 t2 = crossD(vh, t1);
  const double r = std::sqrt(u1), phi = 2 * kPiD * u2;
  const double p1 = r * std::cos(phi);
  const double s = 0.5 * (1 + vh.z);
  const double p2 = (1 - s) * std::sqrt(1 - p1 * p1) + s * r * std::sin(phi);
  const V3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2)) * vh;
  return normalized({alpha * nh.x, alpha * nh.y, std::max(1e-12, nh.z)});
}

// The pieces of the exact environment term, each converged on a stratified
// grid: the specular lobe's integrals of L (1 - w) DV cos and L w DV cos
// (visible-normal sampling), and the diffuse lobe's of L cos / pi and L w cos / pi
// (cosine sampling).
struct LobeIntegrals {
  double spec0[3] = {}, spec1[3] = {};
  double diff0[3] = {}, diff1[3] = {};
};

LobeIntegrals integrateLobes(const EnvironmentImage& e, V3 n, V3 v, double roughness, int grid) {
  V3 t, b;
  frameOf(n, t, b);
  const V3 vl{dotD(v, t), dotD(v, b), dotD(v, n)};
  const double alpha = roughness * roughness, a2 = alpha * alpha;
  const double nv = vl.z, gv = std::sqrt(nv * nv * (1 - a2) + a2);
  LobeIntegrals out;
  const double inv = 1.0 / (double(grid) * grid);
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      const double u1 = (i + 0.5) / grid, u2 = (j + 0.5) / grid;
      // Specular: weight G2 / G1(v).
      const V3 h = alpha > 0 ? sampleVisibleNormal(vl, alpha, u1, u2) : V3{0, 0, 1};
      const double vh = dotD(vl, h);
      const V3 l = 2 * vh * h - vl;
      if (l.z > 0) {
        const double gl = std::sqrt(l.z * l.z * (1 - a2) + a2);
        const double weight = l.z * (nv + gv) / (l.z * gv + nv * gl);
        const double w = schlickRef(std::clamp(vh, 0.0, 1.0));
        double rad[3];
        panoramaRef(e, l.x * t + l.y * b + l.z * n, rad);
        for (int c = 0; c < 3; ++c) {
          out.spec0[c] += rad[c] * weight * (1 - w) * inv;
          out.spec1[c] += rad[c] * weight * w * inv;
        }
      }
      // Diffuse: cosine-weighted l, estimator of (1/pi) integral L cos = mean L.
      const double r = std::sqrt(u1), phi = 2 * kPiD * u2;
      const V3 ld{r * std::cos(phi), r * std::sin(phi), std::sqrt(1 - u1)};
      const V3 hd = normalized(ld + vl);
      const double wd = schlickRef(std::clamp(dotD(vl, hd), 0.0, 1.0));
      double rad[3];
      panoramaRef(e, ld.x * t + ld.y * b + ld.z * n, rad);
      for (int c = 0; c < 3; ++c) {
        out.diff0[c] += rad[c] * inv;
        out.diff1[c] += rad[c] * wd * inv;
      }
    }
  }
  return out;
}

// The environment term of material m from the lobe integrals:
// specF0 x spec0 + specF90 x spec1 + baseColor (1 - metallic)
// ((1 - maxF0) diff0 + (maxF0 - f90) diff1) (brdf_lanes.h's split, written
// out again from LIGHTING.md's BRDF).
double environmentTerm(const MaterialD& m, const LobeIntegrals& lobes, int c) {
  const double specF0 = m.f0[c] * (1 - m.metallic) + m.baseColor[c] * m.metallic;
  const double specF90 = m.f90 * (1 - m.metallic) + m.metallic;
  const double maxF0 = std::max(m.f0[0], std::max(m.f0[1], m.f0[2]));
  return specF0 * lobes.spec0[c] + specF90 * lobes.spec1[c] +
         m.baseColor[c] * (1 - m.metallic) *
             ((1 - maxF0) * lobes.diff0[c] + (maxF0 - m.f90) * lobes.diff1[c]);
}

// The plain split sum (the Khronos Sample Viewer's method) with perfect
// tables: the radiance prefiltered by the GGX lobe for n = v = r (Karis 2013,
// weights n.l), read at the reflected direction, times the exact albedo
// integrals; its diffuse the same exact irradiance and Fresnel share as the
// reference, so only the specular approximation differs.
double splitSumTerm(const EnvironmentImage& e, const MaterialD& m, V3 n, V3 v,
                    const LobeIntegrals& exact, const LobeIntegrals& uniform, int grid, int c) {
  const V3 r = normalized(2 * dotD(n, v) * n - v);
  V3 t, b;
  frameOf(r, t, b);
  const double alpha = m.roughness * m.roughness, a2 = alpha * alpha;
  double sum = 0, weights = 0;
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      const double u1 = (i + 0.5) / grid, phi = 2 * kPiD * (j + 0.5) / grid;
      const double cos2 = (1 - u1) / (1 + (a2 - 1) * u1);  // GGX D(h) (n.h) sampling
      const double ch = std::sqrt(cos2), sh = std::sqrt(1 - cos2);
      const V3 h{sh * std::cos(phi), sh * std::sin(phi), ch};
      const V3 l = 2 * h.z * h - V3{0, 0, 1};
      if (l.z <= 0) continue;
      double rad[3];
      panoramaRef(e, l.x * t + l.y * b + l.z * r, rad);
      sum += rad[c] * l.z, weights += l.z;
    }
  const double prefiltered = sum / weights;
  LobeIntegrals approx = exact;
  for (int k = 0; k < 3; ++k) {
    approx.spec0[k] = prefiltered * uniform.spec0[k];
    approx.spec1[k] = prefiltered * uniform.spec1[k];
  }
  return environmentTerm(m, approx, c);
}

// ------------------------------------------------ running the engine
SurfaceRecord recordOf(const MaterialD& m, V3 n, V3 v) {
  SurfaceRecord s;
  const V3 p{0, 0, 0};
  const float pn[3][3] = {{float(p.x), float(p.y), float(p.z)},
                          {float(n.x), float(n.y), float(n.z)},
                          {float(v.x), float(v.y), float(v.z)}};
  std::copy(pn[0], pn[0] + 3, s.position);
  std::copy(pn[1], pn[1] + 3, s.normal);
  std::copy(pn[2], pn[2] + 3, s.view);
  for (int c = 0; c < 3; ++c) {
    s.baseColor[c] = float(m.baseColor[c]);
    s.dielectricF0[c] = float(m.f0[c]);
  }
  s.metallic = float(m.metallic), s.roughness = float(m.roughness);
  s.dielectricF90 = float(m.f90);
  return s;
}

std::vector<float> shade(const LightingView& view, const std::vector<SurfaceRecord>& s,
                         Isa isa = Isa::Scalar) {
  std::vector<float> rgb(s.size() * 3);
  shadeBatchKernel(isa)(view, s.data(), s.size(), rgb.data());
  return rgb;
}

// A view direction with n.v = nv, turned about n by `azimuth`.
V3 viewAt(V3 n, double nv, double azimuth) {
  V3 t, b;
  frameOf(n, t, b);
  const double s = std::sqrt(1 - nv * nv);
  return normalized(nv * n + s * std::cos(azimuth) * t + s * std::sin(azimuth) * b);
}

const Executor& executor2() {
  static Executor e(2);
  return e;
}

// ------------------------------------------------ BRDF terms
template <class L>
void laneTerms(const float nh[4], const float nv[4], const float nl[4], const float a2[4],
               float d[4], float v[4], float w[4]) {
  using F = typename L::F;
  const F vnh = F::load_unaligned(nh), vnv = F::load_unaligned(nv), vnl = F::load_unaligned(nl),
          va2 = F::load_unaligned(a2);
  shading::ggxD<L>(vnh, va2).store_unaligned(d);
  shading::smithGgxCorrelatedV<L>(vnv, vnl, va2).store_unaligned(v);
  shading::schlickWeight<L>(vnh).store_unaligned(w);
}

TEST(ShadingBrdf, TermsMatchTheirFormulasInDouble) {
  std::mt19937 rng(46);
  std::uniform_real_distribution<float> unit(0.02f, 1.0f);
  double worst[3] = {0, 0, 0};
  for (int i = 0; i < 5000; ++i) {
    float nh[4], nv[4], nl[4], a2[4], d[2][4], v[2][4], w[2][4];
    for (int k = 0; k < 4; ++k) {
      nh[k] = unit(rng), nv[k] = unit(rng), nl[k] = unit(rng);
      const float a = unit(rng) * unit(rng);
      a2[k] = a * a;
    }
    laneTerms<simd::Lanes<simd::ScalarArch>>(nh, nv, nl, a2, d[0], v[0], w[0]);
    laneTerms<simd::Lanes<xsimd::sse2>>(nh, nv, nl, a2, d[1], v[1], w[1]);
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(std::memcmp(&d[0][k], &d[1][k], 4), 0);
      EXPECT_EQ(std::memcmp(&v[0][k], &v[1][k], 4), 0);
      const double dr = ggxDRef(nh[k], a2[k]), vr = smithVRef(nv[k], nl[k], a2[k]);
      const double wr = schlickRef(nh[k]);
      // D's float error is its denominator's cancellation: 1 + (n.h)^2 (alpha^2 - 1)
      // loses up to ~2 ulp of 1 against d, and D goes as 1 / d^2.
      const double dd = double(nh[k]) * nh[k] * (a2[k] - 1.0) + 1.0;
      worst[0] = std::max(worst[0], std::fabs(d[0][k] - dr) / dr / (1e-6 + 5e-7 / dd));
      worst[1] = std::max(worst[1], std::fabs(v[0][k] - vr) / vr);
      worst[2] = std::max(worst[2], std::fabs(w[0][k] - wr));
    }
  }
  std::printf("D error / its bound %.2g, relative error V %.2g, absolute F weight %.2g\n", worst[0],
              worst[1], worst[2]);
  EXPECT_LT(worst[0], 1.0);
  EXPECT_LT(worst[1], 2e-6);
  EXPECT_LT(worst[2], 1e-6);
}

TEST(ShadingBrdf, IorAndSpecularChangeF0AsTheirSpecificationsSay) {
  using L = simd::Lanes<simd::ScalarArch>;
  using F = L::F;
  const float iors[4] = {1.5f, 1.0f, 2.0f, 0.0f};
  const RgbLanes<L> colour{F(1.0f, 0.5f, 2.0f, 30.0f), F(1.0f), F(0.25f)};
  const F specular(1.0f, 1.0f, 0.5f, 0.7f);
  const RgbLanes<L> f0 = shading::dielectricF0<L>(F::load_unaligned(iors), colour, specular);
  for (int k = 0; k < 4; ++k) {
    const double base = std::pow((iors[k] - 1.0) / (iors[k] + 1.0), 2.0);
    EXPECT_NEAR(f0.r.get(k), std::min(base * colour.r.get(k), 1.0) * specular.get(k), 1e-7);
    EXPECT_NEAR(f0.b.get(k), std::min(base * 0.25, 1.0) * specular.get(k), 1e-7);
  }
  EXPECT_NEAR(f0.r.get(0), 0.04f, 1e-7);  // glTF's default ior 1.5
}

TEST(ShadingBrdf, PunctualLightsMatchKhrLightsPunctual) {
  // One light of each type on a few surfaces; expected: f(v,l) (n.l) x E_l in double.
  std::vector<PunctualLight> lights(3);
  lights[0].type = PunctualLight::Type::Directional;
  const V3 travel = normalized({0.3, -1.0, -0.2});
  lights[0].direction[0] = float(travel.x), lights[0].direction[1] = float(travel.y),
  lights[0].direction[2] = float(travel.z);
  lights[0].radiance[0] = 2.0f, lights[0].radiance[1] = 3.0f, lights[0].radiance[2] = 1.0f;
  Light point;
  point.type = Light::Type::Point;
  point.color = glm::vec3(1.0f, 0.5f, 0.25f);
  point.intensity = 40.0f;
  point.range = 6.0f;
  point.world[3] = glm::vec4(1.0f, 3.0f, 0.5f, 1.0f);
  lights[1] = punctualLightOf(point);
  Light spot;
  spot.type = Light::Type::Spot;
  spot.intensity = 60.0f;
  spot.innerConeAngle = 0.2f, spot.outerConeAngle = 0.6f;
  // A node looking down -Y: its -Z axis is (0, -1, 0).
  spot.world = glm::mat4(1.0f);
  spot.world[1] = glm::vec4(0, 0, -1, 0);
  spot.world[2] = glm::vec4(0, 1, 0, 0);
  spot.world[3] = glm::vec4(-0.5f, 4.0f, 0.2f, 1.0f);
  lights[2] = punctualLightOf(spot);
  EXPECT_NEAR(lights[2].direction[1], -1.0f, 1e-7);

  MaterialD m;
  m.baseColor[0] = 0.8, m.baseColor[1] = 0.6, m.baseColor[2] = 0.3;
  m.metallic = 0.3, m.roughness = 0.45;
  std::vector<SurfaceRecord> surfaces;
  std::vector<V3> positions;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> spread(-1.0, 1.0);
  for (int i = 0; i < 64; ++i) {
    const V3 n = normalized({0.3 * spread(rng), 1.0, 0.3 * spread(rng)});
    const V3 v = viewAt(n, 0.2 + 0.8 * std::fabs(spread(rng)), 3 * spread(rng));
    const V3 p{2 * spread(rng), 0.1 * spread(rng), 2 * spread(rng)};
    SurfaceRecord s = recordOf(m, n, v);
    s.position[0] = float(p.x), s.position[1] = float(p.y), s.position[2] = float(p.z);
    surfaces.push_back(s);
    positions.push_back(p);
  }
  const LightingView view = lightingViewOf(nullptr, lights);
  const std::vector<float> got = shade(view, surfaces);
  double worst = 0;
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    const SurfaceRecord& s = surfaces[i];
    const V3 n{s.normal[0], s.normal[1], s.normal[2]}, v{s.view[0], s.view[1], s.view[2]};
    for (int c = 0; c < 3; ++c) {
      double want = brdfCosRef(m, n, v, -1.0 * travel, c) * lights[0].radiance[c];
      // Point: intensity x colour / d^2 x clamp(1 - (d / range)^4, 0, 1).
      const V3 toPoint = V3{1.0, 3.0, 0.5} - positions[i];
      const double d = std::sqrt(dotD(toPoint, toPoint));
      const double window = std::clamp(1 - std::pow(d / 6.0, 4.0), 0.0, 1.0);
      const double colour[3] = {1.0, 0.5, 0.25};
      want += brdfCosRef(m, n, v, normalized(toPoint), c) * 40.0 * colour[c] * window / (d * d);
      // Spot: x the cone's smooth step, squared.
      const V3 toSpot = V3{-0.5, 4.0, 0.2} - positions[i];
      const double ds = std::sqrt(dotD(toSpot, toSpot));
      const double cd = dotD(V3{0, -1, 0}, -1.0 * normalized(toSpot));
      const double scale = 1.0 / (std::cos(0.2) - std::cos(0.6));
      const double cone = std::clamp((cd - std::cos(0.6)) * scale, 0.0, 1.0);
      want += brdfCosRef(m, n, v, normalized(toSpot), c) * 60.0 * cone * cone / (ds * ds);
      worst = std::max(worst, std::fabs(got[i * 3 + c] - want) / std::max(want, 1e-3));
    }
  }
  std::printf("punctual lights: worst relative error %.2g\n", worst);
  EXPECT_LT(worst, 2e-4);
}

TEST(ShadingBrdf, ToksvigRoughnessAddsTheNormalsSpread) {
  using L = simd::Lanes<simd::ScalarArch>;
  using F = L::F;
  const F roughness(0.0f, 0.3f, 0.5f, 0.9f);
  const F full = toksvigRoughness<L>(roughness, F(1.0f));
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(full.get(k), roughness.get(k), 1e-6);
  const float lengths[4] = {0.99f, 0.95f, 0.8f, 0.5f};
  const F shorter = toksvigRoughness<L>(roughness, F::load_unaligned(lengths));
  for (int k = 0; k < 4; ++k) {
    const double r = lengths[k], kappa = (3 * r - r * r * r) / (1 - r * r);
    const double a = double(roughness.get(k)) * roughness.get(k);
    const double want = std::pow(std::min(a * a + 2 / kappa, 1.0), 0.25);
    EXPECT_NEAR(shorter.get(k), want, 1e-6);
    EXPECT_GE(shorter.get(k), roughness.get(k));
  }
}

// ------------------------------------------------ furnaces
EnvironmentImage uniformPanorama(double value) {
  return makePanorama(64, 32, [&](V3, double c[3]) { c[0] = c[1] = c[2] = value; });
}

// The directional albedo integral of f cos over a hemisphere grid in (theta, phi).
double albedoRef(const MaterialD& m, double nv, int c) {
  const V3 n{0, 0, 1}, v{std::sqrt(1 - nv * nv), 0, nv};
  constexpr int kTheta = 768, kPhi = 512;
  double sum = 0;
  for (int i = 0; i < kTheta; ++i) {
    const double theta = (i + 0.5) * (kPiD / 2) / kTheta;
    for (int j = 0; j < kPhi; ++j) {
      const double phi = (j + 0.5) * 2 * kPiD / kPhi;
      const V3 l{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
      sum += brdfCosRef(m, n, v, l, c) * std::sin(theta);
    }
  }
  return sum * (kPiD / 2 / kTheta) * (2 * kPiD / kPhi);
}

TEST(ShadingFurnace, MirrorMetalReflectsExactlyOne) {
  const PreparedEnvironment env(uniformPanorama(1.0), {}, executor2());
  const LightingView view = lightingViewOf(&env, {});
  MaterialD m;
  m.roughness = 0;
  std::vector<SurfaceRecord> s;
  for (double nv : {1.0, 0.7, 0.3, 0.1, 0.02})
    for (double az : {0.0, 1.0, 2.5})
      s.push_back(
          recordOf(m, normalized({0.2, 1, -0.4}), viewAt(normalized({0.2, 1, -0.4}), nv, az)));
  const std::vector<float> got = shade(view, s);
  for (float x : got) EXPECT_NEAR(x, 1.0f, 2e-6f);
}

TEST(ShadingFurnace, RoughMetalsAndDielectricsReflectTheirDirectionalAlbedo) {
  const PreparedEnvironment env(uniformPanorama(1.0), {}, executor2());
  const LightingView view = lightingViewOf(&env, {});
  double worst = 0;
  for (double metallic : {1.0, 0.0}) {
    for (double roughness : {0.3, 0.5, 0.75, 1.0}) {
      for (double nv : {0.9, 0.5, 0.2}) {
        MaterialD m;
        m.metallic = metallic, m.roughness = roughness;
        m.baseColor[0] = 1.0, m.baseColor[1] = 0.7, m.baseColor[2] = 0.2;
        const V3 n{0, 1, 0};
        const std::vector<float> got = shade(view, {recordOf(m, n, viewAt(n, nv, 0.7))});
        for (int c = 0; c < 3; ++c) {
          const double want = albedoRef(m, nv, c);
          worst = std::max(worst, std::fabs(got[c] - want));
          EXPECT_NEAR(got[c], want, 4e-3) << "metallic " << metallic << " roughness " << roughness
                                          << " n.v " << nv << " channel " << c;
        }
      }
    }
  }
  std::printf("furnace: worst absolute error %.2g (albedo <= 1)\n", worst);
}

// ------------------------------------------------ the environment term's accuracy
struct Panorama {
  const char* name;
  EnvironmentImage image;
};

std::vector<Panorama> testPanoramas() {
  std::vector<Panorama> out;
  out.push_back({"two-colour split", makePanorama(256, 128, [](V3 d, double c[3]) {
                   const bool sky = d.y > 0;
                   c[0] = sky ? 1.2 : 0.25, c[1] = sky ? 1.1 : 0.3, c[2] = sky ? 1.6 : 0.1;
                 })});
  out.push_back({"sun", makePanorama(256, 128, [](V3 d, double c[3]) {
                   const V3 sun = normalized({0.5, 0.6, -0.6});
                   const double angle = std::acos(std::clamp(dotD(d, sun), -1.0, 1.0));
                   const double disc = angle < 0.12 ? 40.0 : 0.0;
                   c[0] = 0.4 + disc, c[1] = 0.5 + disc, c[2] = 0.7 + 0.9 * disc;
                 })});
  out.push_back({"gradient", makePanorama(256, 128, [](V3 d, double c[3]) {
                   const double u = 0.5 + std::atan2(d.x, -d.z) / (2 * kPiD);
                   c[0] = 0.6 + 0.5 * std::sin(2 * kPiD * u);
                   c[1] = 0.3 + 0.7 * (d.y + 1) / 2;
                   c[2] = 0.2 + 0.8 * std::pow((d.x + 1) / 2, 2.0);
                 })});
  return out;
}

TEST(ShadingEnvironment, CloserToTheIntegralThanSplitSum) {
  constexpr int kGrid = 96;
  const EnvironmentImage white = uniformPanorama(1.0);
  double sumOurs = 0, sumSplit = 0, worstOurs = 0, worstSplit = 0;
  int cases = 0;
  const double roughnesses[] = {0.0, 0.15, 0.3, 0.5, 0.75, 1.0};
  const double nvs[] = {1.0, 0.7, 0.4, 0.2, 0.08};
  double byRoughness[6][2] = {}, byNv[5][2] = {};
  for (const Panorama& p : testPanoramas()) {
    const PreparedEnvironment env(p.image, {}, executor2());
    const LightingView view = lightingViewOf(&env, {});
    double panoramaOurs = 0, panoramaSplit = 0;
    int panoramaCases = 0;
    for (const V3 n : {V3{0, 1, 0}, normalized({0.8, 0.3, -0.5}), normalized({-0.3, -0.4, 0.85})}) {
      for (int ri = 0; ri < 6; ++ri) {
        for (int ni = 0; ni < 5; ++ni) {
          const double roughness = roughnesses[ri], nv = nvs[ni];
          const V3 v = viewAt(n, nv, 0.9);
          const LobeIntegrals exact = integrateLobes(p.image, n, v, roughness, kGrid);
          const LobeIntegrals uniform = integrateLobes(white, n, v, roughness, kGrid);
          for (double metallic : {1.0, 0.0}) {
            MaterialD m;
            m.metallic = metallic, m.roughness = roughness;
            m.baseColor[0] = 0.9, m.baseColor[1] = 0.6, m.baseColor[2] = 0.3;
            const std::vector<float> got = shade(view, {recordOf(m, n, v)});
            double errOurs = 0, errSplit = 0, norm = 0;
            for (int c = 0; c < 3; ++c) {
              const double want = environmentTerm(m, exact, c);
              const double split = splitSumTerm(p.image, m, n, v, exact, uniform, 48, c);
              errOurs += std::pow(got[c] - want, 2), errSplit += std::pow(split - want, 2);
              norm += want * want;
            }
            const double relOurs = std::sqrt(errOurs / norm), relSplit = std::sqrt(errSplit / norm);
            sumOurs += relOurs * relOurs, sumSplit += relSplit * relSplit;
            panoramaOurs += relOurs * relOurs, panoramaSplit += relSplit * relSplit;
            byRoughness[ri][0] += relOurs * relOurs, byRoughness[ri][1] += relSplit * relSplit;
            byNv[ni][0] += relOurs * relOurs, byNv[ni][1] += relSplit * relSplit;
            worstOurs = std::max(worstOurs, relOurs), worstSplit = std::max(worstSplit, relSplit);
            ++cases, ++panoramaCases;
          }
        }
      }
    }
    std::printf("%-16s RMS relative error: ours %.4f, split sum %.4f\n", p.name,
                std::sqrt(panoramaOurs / panoramaCases), std::sqrt(panoramaSplit / panoramaCases));
  }
  for (int ri = 0; ri < 6; ++ri)
    std::printf("roughness %.2f: RMS ours %.4f, split sum %.4f\n", roughnesses[ri],
                std::sqrt(byRoughness[ri][0] / (cases / 6)),
                std::sqrt(byRoughness[ri][1] / (cases / 6)));
  for (int ni = 0; ni < 5; ++ni)
    std::printf("n.v %.2f: RMS ours %.4f, split sum %.4f\n", nvs[ni],
                std::sqrt(byNv[ni][0] / (cases / 5)), std::sqrt(byNv[ni][1] / (cases / 5)));
  const double rmsOurs = std::sqrt(sumOurs / cases), rmsSplit = std::sqrt(sumSplit / cases);
  std::printf(
      "environment term over %d cases: RMS relative error ours %.4f (max %.4f), "
      "split sum %.4f (max %.4f), ratio %.2f\n",
      cases, rmsOurs, worstOurs, rmsSplit, worstSplit, rmsSplit / rmsOurs);
  EXPECT_LT(rmsOurs, 0.5 * rmsSplit);
  EXPECT_LT(worstOurs, 0.3);  // measured 0.265 (split sum: 0.538)
}

// ------------------------------------------------ orientation and rotation
TEST(ShadingEnvironment, ABrightTexelLightsTheMirrorWhereLightingMdSays) {
  const int w = 256, h = 128, bi = 40, bj = 50;
  EnvironmentImage image = makePanorama(w, h, [](V3, double c[3]) { c[0] = c[1] = c[2] = 0.01; });
  for (int k = 0; k < 3; ++k) image.rgb[(std::size_t(bj) * w + bi) * 3 + k] = 1000.0f;
  const V3 texel = directionOfUv((bi + 0.5) / w, (bj + 0.5) / h);
  for (double degrees : {0.0, 90.0}) {
    EnvironmentPlacement placement;
    placement.rotationDegrees = float(degrees);
    const PreparedEnvironment env(image, placement, executor2());
    const LightingView view = lightingViewOf(&env, {});
    // A lookup in d reads the panorama at R_y(-deg) d: the texel shows at R_y(deg) texel.
    const double a = degrees * kPiD / 180;
    const V3 shown{std::cos(a) * texel.x + std::sin(a) * texel.z, texel.y,
                   -std::sin(a) * texel.x + std::cos(a) * texel.z};
    const V3 v{0, 0, 1};
    MaterialD mirror;
    mirror.roughness = 0;
    const std::vector<float> hit = shade(view, {recordOf(mirror, normalized(v + shown), v)});
    EXPECT_GT(hit[0], 100.0f) << degrees;
    if (degrees != 0.0) {
      const std::vector<float> miss = shade(view, {recordOf(mirror, normalized(v + texel), v)});
      EXPECT_LT(miss[0], 0.1f);
    }
    // The background's lookup finds it too, and spreads it over a wide footprint.
    std::vector<BackgroundRay> rays(2);
    for (BackgroundRay& r : rays)
      r.direction[0] = float(shown.x), r.direction[1] = float(shown.y),
      r.direction[2] = float(shown.z);
    rays[1].solidAngle = 0.05f;
    std::vector<float> rgb(6);
    backgroundBatchKernel(Isa::Scalar)(view, rays.data(), 2, rgb.data());
    EXPECT_GT(rgb[0], 100.0f);
    // The texel's energy (1000 x its solid angle) spread over 0.05 sr, roughly.
    const double texelOmega = (2 * kPiD / w) * (kPiD / h) * std::sin(kPiD * (bj + 0.5) / h);
    EXPECT_NEAR(rgb[3], 0.01 + 1000 * texelOmega / 0.05, 0.5 * 1000 * texelOmega / 0.05);
  }
}

// ------------------------------------------------ determinism
TEST(ShadingEnvironment, PreprocessingBitsDoNotDependOnThreads) {
  const EnvironmentImage image = testPanoramas()[1].image;
  Executor one(1);
  const PreparedEnvironment a(image, {33.0f, 1.5f}, one);
  const PreparedEnvironment b(image, {33.0f, 1.5f}, executor2());
  ASSERT_EQ(a.radiance().size(), b.radiance().size());
  EXPECT_EQ(std::memcmp(a.radiance().data(), b.radiance().data(), a.radiance().size() * 4), 0);
  EXPECT_EQ(std::memcmp(a.irradianceTexels().data(), b.irradianceTexels().data(),
                        a.irradianceTexels().size() * 4),
            0);
}

TEST(ShadingEnvironment, LaneCodeIsBitIdenticalOnEveryIsa) {
  const PreparedEnvironment env(testPanoramas()[2].image, {20.0f, 1.0f}, executor2());
  std::vector<PunctualLight> lights(3);
  lights[0].type = PunctualLight::Type::Directional;
  lights[1].position[1] = 2.0f, lights[1].inverseRange4 = 1.0f / 81.0f;
  lights[2].type = PunctualLight::Type::Spot;
  lights[2].position[1] = 3.0f, lights[2].direction[2] = 0.0f, lights[2].direction[1] = -1.0f;
  lights[2].angleScale = 4.0f, lights[2].angleOffset = -2.5f;
  const LightingView view = lightingViewOf(&env, lights);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<SurfaceRecord> surfaces;
  std::vector<BackgroundRay> rays;
  for (int i = 0; i < 3001; ++i) {
    MaterialD m;
    m.metallic = std::fabs(u(rng)), m.roughness = std::fabs(u(rng));
    for (double& c : m.baseColor) c = std::fabs(u(rng));
    const V3 n = normalized({u(rng), u(rng), u(rng)});
    SurfaceRecord s = recordOf(m, n, viewAt(n, 0.01 + 0.99 * std::fabs(u(rng)), 3 * u(rng)));
    s.position[0] = float(u(rng)), s.position[2] = float(u(rng));
    s.occlusion = float(std::fabs(u(rng)));
    s.emission[1] = float(std::fabs(u(rng)));
    surfaces.push_back(s);
    BackgroundRay r;
    r.direction[0] = float(u(rng)), r.direction[1] = float(u(rng)), r.direction[2] = float(u(rng));
    r.solidAngle = float(std::pow(10.0, 3 * u(rng) - 3));
    rays.push_back(r);
  }
  const std::vector<float> scalar = shade(view, surfaces, Isa::Scalar);
  std::vector<float> background(rays.size() * 3), other(rays.size() * 3);
  backgroundBatchKernel(Isa::Scalar)(view, rays.data(), rays.size(), background.data());
  for (float x : scalar) ASSERT_TRUE(std::isfinite(x));
  for (const Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
    if (!isaSupported(isa)) continue;
    const std::vector<float> got = shade(view, surfaces, isa);
    EXPECT_EQ(std::memcmp(got.data(), scalar.data(), got.size() * 4), 0) << isaName(isa);
    backgroundBatchKernel(isa)(view, rays.data(), rays.size(), other.data());
    EXPECT_EQ(std::memcmp(other.data(), background.data(), other.size() * 4), 0) << isaName(isa);
  }
}

}  // namespace
}  // namespace quadra
