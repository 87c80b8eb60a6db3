// The lit ideal (lit_reference.h; self-tests in tests/test_lit_reference.cpp).
#include "lab/reference/lit_reference.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "lab/reference/reference_raster.h"

namespace quadra::ref {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMinimumNDotV = 1e-4;  // see hitRadiance

double luminance(const glm::dvec3& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

double maxComponent(const glm::dvec3& c) {
  return std::max({c.r, c.g, c.b});
}

// ---- sequences ----------------------------------------------------------------------

// The splitmix64 finalizer: a 64-bit hash whose bits all depend on every input bit.
std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

std::uint64_t hashCombine(std::uint64_t a, std::uint64_t b) {
  return mix64(a ^ mix64(b + 0x9e3779b97f4a7c15ull));
}

std::uint32_t reverseBits(std::uint32_t x) {
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
}

// The first two dimensions of Sobol's sequence as 32-bit binary fractions:
// the van der Corput sequence and the one of the Pascal matrix mod 2
// (direction numbers v_{k+1} = v_k xor v_k / 2), together a (0, 2)-sequence:
// every aligned block of 2^m points is a (0, m, 2)-net.
std::uint32_t sobolFirst(std::uint32_t index) {
  return reverseBits(index);
}

std::uint32_t sobolSecond(std::uint32_t index) {
  std::uint32_t v = 1u << 31, result = 0;
  for (; index != 0; index >>= 1, v ^= v >> 1)
    if (index & 1u) result ^= v;
  return result;
}

// Owen's nested uniform scrambling in Burley's hashed form (2020, after Laine
// and Karras): each binary digit flipped by a hash of the digits above it,
// which keeps the nets' stratification and makes every point uniform.
std::uint32_t owenScramble(std::uint32_t fraction, std::uint32_t seed) {
  std::uint32_t x = reverseBits(fraction);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return reverseBits(x);
}

double unitOf(std::uint32_t bits) {
  return double(bits) * 0x1p-32;  // [0, 1)
}

glm::dvec2 sobolPoint(std::uint32_t index, std::uint64_t scramble) {
  return {unitOf(owenScramble(sobolFirst(index), std::uint32_t(scramble))),
          unitOf(owenScramble(sobolSecond(index), std::uint32_t(scramble >> 32)))};
}

// ---- the BRDF ------------------------------------------------------------------------

// An orthonormal basis (t, b, n) around unit n (Duff et al. 2017).
void basisAround(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

// GGX's normal distribution at half vector h (unit), from 1 - (n.h)^2 taken
// as |n x h|^2 so that a sharp lobe keeps its digits near its peak.
double ggxD(double alpha, const glm::dvec3& n, const glm::dvec3& h) {
  const double cosine = glm::dot(n, h);
  if (!(cosine > 0.0)) return 0.0;
  const glm::dvec3 sine = glm::cross(n, h);
  const double a2 = alpha * alpha;
  const double denominator = glm::dot(sine, sine) + cosine * cosine * a2;
  return a2 / (kPi * denominator * denominator);
}

// The height-correlated Smith visibility G / (4 n.l n.v).
double smithV(double alpha, double nDotL, double nDotV) {
  const double a2 = alpha * alpha;
  const double ggxV = nDotL * std::sqrt(nDotV * nDotV * (1.0 - a2) + a2);
  const double ggxL = nDotV * std::sqrt(nDotL * nDotL * (1.0 - a2) + a2);
  const double sum = ggxV + ggxL;
  return sum > 0.0 ? 0.5 / sum : 0.0;
}

glm::dvec3 schlick(const glm::dvec3& f0, double f90, double cosine) {
  const double m = std::clamp(1.0 - cosine, 0.0, 1.0);
  const double m2 = m * m;
  return f0 + (f90 - f0) * (m2 * m2 * m);
}

// The density per steradian of l from sampling GGX's visible normals for v
// and reflecting v about them: G1(v) D(h) / (4 n.v).
double ggxPdf(double alpha, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l) {
  const double nDotV = glm::dot(n, v);
  const glm::dvec3 sum = v + l;
  const double length = glm::length(sum);
  if (!(nDotV > 0.0) || !(length > 0.0)) return 0.0;
  const double d = ggxD(alpha, n, sum / length);
  return d / (2.0 * (nDotV + std::sqrt(alpha * alpha + (1.0 - alpha * alpha) * nDotV * nDotV)));
}

// A visible normal of GGX for local view direction v (z up, v.z > 0), from
// a point of [0, 1)^2 (Heitz 2018, "Sampling the GGX Distribution of Visible
// Normals").
glm::dvec3 sampleVisibleNormal(const glm::dvec3& v, double alpha, const glm::dvec2& point) {
  const glm::dvec3 vh = glm::normalize(glm::dvec3(alpha * v.x, alpha * v.y, v.z));
  const double lengthSquared = vh.x * vh.x + vh.y * vh.y;
  const glm::dvec3 t1 = lengthSquared > 0.0
                            ? glm::dvec3(-vh.y, vh.x, 0.0) / std::sqrt(lengthSquared)
                            : glm::dvec3(1.0, 0.0, 0.0);
  const glm::dvec3 t2 = glm::cross(vh, t1);
  const double r = std::sqrt(point.x), phi = 2.0 * kPi * point.y;
  const double p1 = r * std::cos(phi);
  const double s = 0.5 * (1.0 + vh.z);
  const double p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * r * std::sin(phi);
  const glm::dvec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(glm::dvec3(alpha * nh.x, alpha * nh.y, std::max(0.0, nh.z)));
}

}  // namespace

// ---- the environment ------------------------------------------------------------------

ReferenceEnvironment::ReferenceEnvironment(const EnvironmentImage& image, double rotationDegrees,
                                           double intensity)
    : image_(image),
      cosRotation_(std::cos(rotationDegrees * kPi / 180.0)),
      sinRotation_(std::sin(rotationDegrees * kPi / 180.0)),
      intensity_(intensity) {
  const int w = image.width, h = image.height;
  QUADRA_CHECK(w > 0 && h > 0 && image.rgb.size() == image.texelCount() * 3);
  // Each cell's weight: the exact mean of the bilinear radiance over it (the
  // hat functions give its own texel 3/4 and each neighbour 1/8 per axis; u
  // wraps, v clamps), as luminance, times the cell's solid angle. Positive
  // wherever the radiance is, so the density covers the integrand.
  const double hat[3] = {0.125, 0.75, 0.125};
  std::vector<double> weights(std::size_t(w) * std::size_t(h));
  rowProbability_.assign(std::size_t(h), 0.0);
  for (int j = 0; j <= h; ++j) cosBoundary_.push_back(std::cos(kPi * j / h));
  for (int j = 0; j < h; ++j)
    cellSolidAngle_.push_back(2.0 * kPi / w *
                              (cosBoundary_[std::size_t(j)] - cosBoundary_[std::size_t(j) + 1]));
  for (int j = 0; j < h; ++j) {
    const double solidAngle = cellSolidAngle_[std::size_t(j)];
    for (int i = 0; i < w; ++i) {
      glm::dvec3 mean(0.0);
      for (int b = -1; b <= 1; ++b)
        for (int a = -1; a <= 1; ++a) {
          const int x = int(wrapTexel(i + a, w, WrapMode::Repeat));
          const int y = int(wrapTexel(j + b, h, WrapMode::ClampToEdge));
          const float* t = image.texel(x, y);
          mean += hat[a + 1] * hat[b + 1] * glm::dvec3(t[0], t[1], t[2]);
        }
      const double weight = luminance(mean) * solidAngle;
      weights[std::size_t(j) * std::size_t(w) + std::size_t(i)] = weight;
      rowProbability_[std::size_t(j)] += weight;
    }
    total_ += rowProbability_[std::size_t(j)];
  }
  if (total_ <= 0.0) return;
  rowCdf_.assign(std::size_t(h) + 1, 0.0);
  cellCdf_.assign((std::size_t(w) + 1) * std::size_t(h), 0.0);
  cellProbability_.assign(weights.size(), 0.0);
  for (int j = 0; j < h; ++j) {
    const double row = rowProbability_[std::size_t(j)];
    double* cdf = &cellCdf_[std::size_t(j) * (std::size_t(w) + 1)];
    for (int i = 0; i < w; ++i) {
      const double p =
          row > 0.0 ? weights[std::size_t(j) * std::size_t(w) + std::size_t(i)] / row : 1.0 / w;
      cellProbability_[std::size_t(j) * std::size_t(w) + std::size_t(i)] = p;
      cdf[i + 1] = cdf[i] + p;
    }
    cdf[w] = 1.0;
    rowProbability_[std::size_t(j)] = row / total_;
    rowCdf_[std::size_t(j) + 1] = rowCdf_[std::size_t(j)] + rowProbability_[std::size_t(j)];
  }
  rowCdf_[std::size_t(h)] = 1.0;
}

glm::dvec2 ReferenceEnvironment::panoramaCoordinates(const glm::dvec3& d) const {
  // The panorama is read at R_y(-rotation) d.
  const double x = cosRotation_ * d.x - sinRotation_ * d.z;
  const double z = sinRotation_ * d.x + cosRotation_ * d.z;
  const double y = d.y / glm::length(d);
  return {0.5 + std::atan2(x, -z) / (2.0 * kPi), std::acos(std::clamp(y, -1.0, 1.0)) / kPi};
}

glm::dvec3 ReferenceEnvironment::directionOf(const glm::dvec2& uv) const {
  const double phi = 2.0 * kPi * (uv.x - 0.5), theta = kPi * uv.y;
  const double x = std::sin(theta) * std::sin(phi), z = -std::sin(theta) * std::cos(phi);
  // R_y(rotation) of the panorama's direction.
  return {cosRotation_ * x + sinRotation_ * z, std::cos(theta),
          -sinRotation_ * x + cosRotation_ * z};
}

glm::dvec3 ReferenceEnvironment::radiance(const glm::dvec3& direction) const {
  return radianceAt(panoramaCoordinates(direction));
}

glm::dvec3 ReferenceEnvironment::radianceAt(const glm::dvec2& uv) const {
  const int w = image_.width, h = image_.height;
  const double x = uv.x * w - 0.5, y = uv.y * h - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  // u wraps, v clamps. A direction's coordinates lie in [0, 1], where
  // columns -1 and w are the only ones to wrap; others take the general rule.
  const auto column = [w](double i) {
    if (i >= -1.0 && i <= w) {
      const int c = int(i);
      return c < 0 ? c + w : (c >= w ? c - w : c);
    }
    return int(wrapTexel(std::int64_t(i), w, WrapMode::Repeat));
  };
  const auto row = [h](double j) { return int(std::clamp(j, 0.0, double(h - 1))); };
  const int i0 = column(x0), i1 = column(x0 + 1), j0 = row(y0), j1 = row(y0 + 1);
  const auto texel = [&](int i, int j) {
    const float* t = image_.texel(i, j);
    return glm::dvec3(t[0], t[1], t[2]);
  };
  const glm::dvec3 top = (1 - fx) * texel(i0, j0) + fx * texel(i1, j0);
  const glm::dvec3 bottom = (1 - fx) * texel(i0, j1) + fx * texel(i1, j1);
  return intensity_ * ((1 - fy) * top + fy * bottom);
}

int ReferenceEnvironment::cellOf(const glm::dvec2& uv, int& row) const {
  const int w = image_.width, h = image_.height;
  row = std::clamp(int(std::floor(uv.y * h)), 0, h - 1);
  return int(wrapTexel(std::int64_t(std::floor(uv.x * w)), w, WrapMode::Repeat));
}

double ReferenceEnvironment::pdf(const glm::dvec3& direction) const {
  return pdfAt(panoramaCoordinates(direction));
}

double ReferenceEnvironment::pdfAt(const glm::dvec2& uv) const {
  if (black()) return 0.0;
  int j = 0;
  const int i = cellOf(uv, j);
  const int w = image_.width;
  return rowProbability_[std::size_t(j)] *
         cellProbability_[std::size_t(j) * std::size_t(w) + std::size_t(i)] /
         cellSolidAngle_[std::size_t(j)];
}

glm::dvec3 ReferenceEnvironment::sample(const glm::dvec2& point, double& pdf,
                                        glm::dvec2* uv) const {
  QUADRA_CHECK(!black());
  const int w = image_.width, h = image_.height;
  // The first entry with cdf > point: its interval has a positive share.
  const auto pick = [](const double* cdf, int count, double at, double& fraction) {
    const int k =
        std::clamp(int(std::upper_bound(cdf + 1, cdf + count + 1, at) - (cdf + 1)), 0, count - 1);
    fraction = std::clamp((at - cdf[k]) / (cdf[k + 1] - cdf[k]), 0.0, 1.0);
    return k;
  };
  double fy = 0.0, fx = 0.0;
  const int j = pick(rowCdf_.data(), h, point.y, fy);
  const int i = pick(&cellCdf_[std::size_t(j) * (std::size_t(w) + 1)], w, point.x, fx);
  const double cosTop = cosBoundary_[std::size_t(j)];
  const double cosBottom = cosBoundary_[std::size_t(j) + 1];
  const double cosTheta = cosTop - fy * (cosTop - cosBottom);
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  const double u = (i + fx) / w;
  if (uv) *uv = {u, std::acos(std::clamp(cosTheta, -1.0, 1.0)) / kPi};
  const double phi = 2.0 * kPi * (u - 0.5);
  const double x = sinTheta * std::sin(phi), z = -sinTheta * std::cos(phi);
  pdf = rowProbability_[std::size_t(j)] *
        cellProbability_[std::size_t(j) * std::size_t(w) + std::size_t(i)] /
        cellSolidAngle_[std::size_t(j)];
  return {cosRotation_ * x + sinRotation_ * z, cosTheta, -sinRotation_ * x + cosRotation_ * z};
}

// ---- the BRDF ------------------------------------------------------------------------

void dielectricFresnel(double ior, const glm::dvec3& specularColor, double specular, glm::dvec3& f0,
                       double& f90) {
  const double r = (ior - 1.0) / (ior + 1.0);
  f0 = glm::min(r * r * specularColor, glm::dvec3(1.0)) * specular;
  f90 = specular;
}

glm::dvec3 evaluateBrdf(const BrdfParameters& m, const glm::dvec3& n, const glm::dvec3& v,
                        const glm::dvec3& l) {
  const double nDotL = glm::dot(n, l);
  if (!(nDotL > 0.0)) return glm::dvec3(0.0);
  const double nDotV = std::max(glm::dot(n, v), 0.0);
  const glm::dvec3 sum = v + l;
  const double length = glm::length(sum);
  if (!(length > 0.0)) return glm::dvec3(0.0);
  const glm::dvec3 h = sum / length;
  const double vDotH = std::clamp(glm::dot(v, h), 0.0, 1.0);
  const double specular = m.alpha > 0.0 ? ggxD(m.alpha, n, h) * smithV(m.alpha, nDotL, nDotV) : 0.0;
  const glm::dvec3 fDielectric = schlick(m.dielectricF0, m.dielectricF90, vDotH);
  const glm::dvec3 fMetal = schlick(m.baseColor, 1.0, vDotH);
  const glm::dvec3 dielectric =
      fDielectric * specular + (1.0 - maxComponent(fDielectric)) * m.baseColor / kPi;
  const glm::dvec3 metal = fMetal * specular;
  return (1.0 - m.metallic) * dielectric + m.metallic * metal;
}

glm::dvec3 mirrorReflectance(const BrdfParameters& m, const glm::dvec3& n, const glm::dvec3& v) {
  const double nDotV = glm::dot(n, v);
  if (!(nDotV > 0.0)) return glm::dvec3(0.0);
  return (1.0 - m.metallic) * schlick(m.dielectricF0, m.dielectricF90, nDotV) +
         m.metallic * schlick(m.baseColor, 1.0, nDotV);
}

glm::dvec3 environmentIntegral(const ReferenceEnvironment& environment, const BrdfParameters& m,
                               const glm::dvec3& n, const glm::dvec3& v,
                               const EnvironmentSampling& sampling, std::uint64_t scramble,
                               std::uint32_t block) {
  glm::dvec3 result(0.0);
  if (environment.black()) return result;
  const double nDotV = glm::dot(n, v);
  const bool delta = m.alpha == 0.0;
  if (delta && nDotV > 0.0)
    result += mirrorReflectance(m, n, v) * environment.radiance(2.0 * nDotV * n - v);
  // How the BRDF's samples divide between its lobes: by their reflectance
  // at n.v, roughly; any division is unbiased (the environment's samples
  // cover every direction with radiance).
  const double specularWeight =
      delta || !(nDotV > 0.0)
          ? 0.0
          : luminance((1.0 - m.metallic) * schlick(m.dielectricF0, m.dielectricF90, nDotV) +
                      m.metallic * schlick(m.baseColor, 1.0, nDotV));
  const double diffuseWeight =
      (1.0 - m.metallic) * luminance(m.baseColor) * (1.0 - maxComponent(m.dielectricF0));
  if (!(specularWeight + diffuseWeight > 0.0)) return result;
  double specularShare = specularWeight / (specularWeight + diffuseWeight);
  if (specularWeight > 0.0 && diffuseWeight > 0.0)
    specularShare = std::clamp(specularShare, 0.1, 0.9);
  const double environmentCount = sampling.environmentSamples;
  const double brdfCount = sampling.brdfSamples;
  if (environmentCount + brdfCount <= 0.0) return result;
  glm::dvec3 t, b;
  basisAround(n, t, b);
  const glm::dvec3 localV(glm::dot(v, t), glm::dot(v, b), nDotV);
  const auto brdfPdf = [&](const glm::dvec3& l) {
    double p = (1.0 - specularShare) * std::max(0.0, glm::dot(n, l)) / kPi;
    if (specularShare > 0.0) p += specularShare * ggxPdf(m.alpha, n, v, l);
    return p;
  };
  // The balance heuristic over both strategies' sample counts: each sample
  // weighs f L cos / (n_env p_env + n_brdf p_brdf).
  const auto add = [&](const glm::dvec3& l, const glm::dvec2& uv, double environmentPdf,
                       double brdfPdfAtL) {
    const double cosine = glm::dot(n, l);
    if (!(cosine > 0.0)) return;
    const double combined = environmentCount * environmentPdf + brdfCount * brdfPdfAtL;
    if (!(combined > 0.0)) return;
    const glm::dvec3 f = evaluateBrdf(m, n, v, l);
    if (f == glm::dvec3(0.0)) return;
    result += f * environment.radianceAt(uv) * (cosine / combined);
  };
  const std::uint64_t environmentScramble = hashCombine(scramble, 1);
  const std::uint64_t brdfScramble = hashCombine(scramble, 2);
  for (int k = 0; k < sampling.environmentSamples; ++k) {
    const std::uint32_t index =
        block * std::uint32_t(sampling.environmentSamples) + std::uint32_t(k);
    double environmentPdf = 0.0;
    glm::dvec2 uv;
    const glm::dvec3 l =
        environment.sample(sobolPoint(index, environmentScramble), environmentPdf, &uv);
    if (environmentPdf > 0.0 && glm::dot(n, l) > 0.0) add(l, uv, environmentPdf, brdfPdf(l));
  }
  for (int k = 0; k < sampling.brdfSamples; ++k) {
    const std::uint32_t index = block * std::uint32_t(sampling.brdfSamples) + std::uint32_t(k);
    glm::dvec2 point = sobolPoint(index, brdfScramble);
    constexpr double kBelowOne = 1.0 - 0x1p-53;
    glm::dvec3 local;
    if (point.x < specularShare) {
      point.x = std::min(point.x / specularShare, kBelowOne);
      const glm::dvec3 h = sampleVisibleNormal(localV, m.alpha, point);
      local = 2.0 * glm::dot(localV, h) * h - localV;
    } else {
      point.x = std::min((point.x - specularShare) / (1.0 - specularShare), kBelowOne);
      const double r = std::sqrt(point.x), phi = 2.0 * kPi * point.y;
      local = {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - point.x))};
    }
    const glm::dvec3 l = glm::normalize(local.x * t + local.y * b + local.z * n);
    if (!(glm::dot(n, l) > 0.0)) continue;
    const glm::dvec2 uv = environment.panoramaCoordinates(l);
    add(l, uv, environment.pdfAt(uv), brdfPdf(l));
  }
  return result;
}

// ---- the frame ----------------------------------------------------------------------

LitReference::LitReference(const Scene& scene, const Camera& camera, int width, int height,
                           const ReferenceEnvironment* environment)
    : scene_(scene),
      tracer_(scene, camera, width, height),
      environment_(environment),
      cameraToWorld_(glm::inverse(referenceViewMatrix(camera))) {
  for (const Instance& instance : scene.instances) {
    const Mesh& mesh = scene.meshes.at(std::size_t(instance.mesh));
    PreparedInstance prepared;
    const glm::dmat3 linear(glm::dmat4(instance.world));
    prepared.tangentMatrix = linear;
    prepared.normalMatrix = glm::transpose(glm::inverse(linear));
    const bool morphed = !instance.morphWeights.empty() && !mesh.targets.empty();
    const bool skinned = !instance.jointMatrices.empty() && !mesh.joints[0].empty();
    if (morphed || skinned) {
      // Posed as the tracer poses positions (glTF 2.0 §3.7.2.2, §3.7.3):
      // target deltas by weight, then each influence's joint matrix by
      // weight (its inverse transpose for normals).
      prepared.normals.assign(mesh.normals.begin(), mesh.normals.end());
      for (const glm::vec4& t : mesh.tangents) prepared.tangents.push_back(glm::dvec4(t));
      if (morphed)
        for (std::size_t t = 0; t < mesh.targets.size(); ++t) {
          const double weight = instance.morphWeights.at(t);
          const MorphTarget& target = mesh.targets[t];
          for (std::size_t v = 0; v < target.normals.size() && v < prepared.normals.size(); ++v)
            prepared.normals[v] += weight * glm::dvec3(target.normals[v]);
          for (std::size_t v = 0; v < target.tangents.size() && v < prepared.tangents.size(); ++v)
            prepared.tangents[v] += glm::dvec4(weight * glm::dvec3(target.tangents[v]), 0.0);
        }
      if (skinned) {
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
          glm::dvec3 normal(0.0), tangent(0.0);
          for (int set = 0; set < 2; ++set) {
            if (mesh.joints[set].empty()) continue;
            for (int k = 0; k < 4; ++k) {
              const double weight = mesh.weights[set][v][k];
              if (weight == 0.0) continue;
              const glm::dmat3 joint(glm::dmat4(instance.jointMatrices.at(mesh.joints[set][v][k])));
              if (!prepared.normals.empty())
                normal += weight * (glm::transpose(glm::inverse(joint)) * prepared.normals[v]);
              if (!prepared.tangents.empty())
                tangent += weight * (joint * glm::dvec3(prepared.tangents[v]));
            }
          }
          if (!prepared.normals.empty()) prepared.normals[v] = normal;
          if (!prepared.tangents.empty())
            prepared.tangents[v] = glm::dvec4(tangent, prepared.tangents[v].w);
        }
      }
    }
    instances_.push_back(std::move(prepared));
  }
  for (const Light& light : scene.lights) {
    PreparedLight prepared;
    const glm::dmat4 world(light.world);
    prepared.type = light.type;
    prepared.position = glm::dvec3(world[3]);
    prepared.direction = glm::normalize(glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0));
    prepared.intensity = glm::dvec3(light.color) * double(light.intensity);
    prepared.range = light.range;
    // KHR_lights_punctual's cone: the square of a ramp in the cosine from the
    // outer angle to the inner one, as the specification's reference code.
    const double cosOuter = std::cos(double(light.outerConeAngle));
    prepared.angleScale = 1.0 / std::max(0.001, std::cos(double(light.innerConeAngle)) - cosOuter);
    prepared.angleOffset = -cosOuter * prepared.angleScale;
    lights_.push_back(prepared);
  }
}

glm::dvec3 LitReference::worldDirection(const Ray& ray) const {
  return glm::normalize(glm::dmat3(cameraToWorld_) * ray.direction);
}

glm::dvec3 LitReference::punctualLight(const BrdfParameters& m, const glm::dvec3& position,
                                       const glm::dvec3& n, const glm::dvec3& v) const {
  glm::dvec3 sum(0.0);
  for (const PreparedLight& light : lights_) {
    glm::dvec3 l = -light.direction;
    double attenuation = 1.0;
    if (light.type != Light::Type::Directional) {
      const glm::dvec3 toLight = light.position - position;
      const double distanceSquared = glm::dot(toLight, toLight);
      if (!(distanceSquared > 0.0)) continue;
      const double distance = std::sqrt(distanceSquared);
      l = toLight / distance;
      attenuation = 1.0 / distanceSquared;
      if (light.range > 0.0) {
        const double ratio = distance / light.range;
        attenuation *= std::clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
      }
      if (light.type == Light::Type::Spot) {
        const double ramp = std::clamp(
            glm::dot(light.direction, -l) * light.angleScale + light.angleOffset, 0.0, 1.0);
        attenuation *= ramp * ramp;
      }
    }
    const double nDotL = glm::dot(n, l);
    if (!(nDotL > 0.0) || attenuation == 0.0) continue;
    sum += evaluateBrdf(m, n, v, l) * nDotL * attenuation * light.intensity;
  }
  return sum;
}

glm::dvec4 LitReference::hitRadiance(const TracerHit& hit, const Ray& ray,
                                     const glm::dvec4& surface, const LitSettings& settings,
                                     std::uint64_t scramble, std::uint32_t block) const {
  static const Material kDefaultMaterial;  // glTF's: white, metallic 1, roughness 1
  const Material* found = tracer_.materialOf(hit);
  const Material& material = found ? *found : kDefaultMaterial;
  if (material.unlit) return surface;
  const Instance& instance = scene_.instances[std::size_t(hit.instance)];
  const Mesh& mesh = scene_.meshes[std::size_t(instance.mesh)];
  const PreparedInstance& prepared = instances_[std::size_t(hit.instance)];
  const std::uint32_t* corner = &mesh.indices[std::size_t(hit.triangle) * 3];

  const glm::dvec3 viewPosition = ray.origin + hit.viewDistance * ray.direction;
  const glm::dvec3 position(cameraToWorld_ * glm::dvec4(viewPosition, 1.0));
  const glm::dvec3 v = -worldDirection(ray);
  const bool front = tracer_.frontFacing(hit, ray);
  // The triangle's own normal, toward the viewer (the front side's when
  // front-facing, the flipped one on a double-sided back face).
  const std::array<glm::dvec3, 3> c = tracer_.viewCorners(hit);
  glm::dvec3 geometric =
      glm::normalize(glm::dmat3(cameraToWorld_) * glm::cross(c[1] - c[0], c[2] - c[0]));
  if (glm::dot(geometric, v) < 0.0) geometric = -geometric;

  // The front side's frame; flipped as a whole on back faces below.
  glm::dvec3 normal = front ? geometric : -geometric;
  const bool hasNormals = !mesh.normals.empty();
  if (hasNormals) {
    glm::dvec3 sum(0.0);
    for (int k = 0; k < 3; ++k)
      sum += hit.bary[k] * (prepared.normals.empty() ? glm::dvec3(mesh.normals[corner[k]])
                                                     : prepared.normals[corner[k]]);
    const glm::dvec3 world = prepared.normalMatrix * sum;
    if (glm::length(world) > 0.0) normal = glm::normalize(world);
  }
  const auto read = [&](const MaterialTexture& texture) {
    const Texture& t = *scene_.textures.at(std::size_t(texture.texture));
    const glm::dvec2 uv = transformed(texture.transform, tracer_.texCoord(hit, texture.texCoord));
    return sampleBilinear(t.image(), t.sampler(), uv);
  };
  if (material.normal.present() && !mesh.tangents.empty()) {
    glm::dvec4 sum(0.0);
    for (int k = 0; k < 3; ++k)
      sum += hit.bary[k] * (prepared.tangents.empty() ? glm::dvec4(mesh.tangents[corner[k]])
                                                      : prepared.tangents[corner[k]]);
    const glm::dvec3 world = prepared.tangentMatrix * glm::dvec3(sum);
    if (glm::length(world) > 0.0) {
      const glm::dvec3 tangent = glm::normalize(world);
      const glm::dvec3 bitangent = (sum.w < 0.0 ? -1.0 : 1.0) * glm::cross(normal, tangent);
      const glm::dvec3 texel(read(material.normal));
      const double scale = material.normalScale;
      const glm::dvec3 local = glm::normalize((2.0 * texel - 1.0) * glm::dvec3(scale, scale, 1.0));
      const glm::dvec3 mapped = local.x * tangent + local.y * bitangent + local.z * normal;
      if (glm::length(mapped) > 0.0) normal = glm::normalize(mapped);
    }
  }
  if (!front) normal = -normal;
  // An interpolated or mapped normal may face away from the viewer (near
  // silhouettes of smooth-shaded meshes, under steep normal maps), where the
  // BRDF is undefined and a mirror would read below its own horizon. The
  // reference turns it toward v in the plane of n and v until n.v = 1e-4:
  // grazing, its mirror direction continues the view ray, as a true
  // silhouette's does.
  if (const double nDotV = glm::dot(normal, v); nDotV < kMinimumNDotV) {
    const glm::dvec3 across = normal - nDotV * v;
    const double length = glm::length(across);
    normal = length > 0.0 ? across / length * std::sqrt(1.0 - kMinimumNDotV * kMinimumNDotV) +
                                kMinimumNDotV * v
                          : v;
  }

  BrdfParameters m;
  m.baseColor = glm::dvec3(surface);
  double metallic = material.metallicFactor, roughness = material.roughnessFactor;
  if (material.metallicRoughness.present()) {
    const glm::dvec4 texel = read(material.metallicRoughness);
    metallic *= texel.b;
    roughness *= texel.g;
  }
  m.metallic = std::clamp(metallic, 0.0, 1.0);
  roughness = std::clamp(roughness, 0.0, 1.0);
  m.alpha = roughness * roughness;
  glm::dvec3 specularColor(material.specularColorFactor);
  double specular = material.specularFactor;
  if (material.specularColor.present()) specularColor *= glm::dvec3(read(material.specularColor));
  if (material.specular.present()) specular *= read(material.specular).a;
  dielectricFresnel(material.ior, specularColor, specular, m.dielectricF0, m.dielectricF90);

  glm::dvec3 radiance(0.0);
  if (environment_) {
    double occlusion = 1.0;
    if (material.occlusion.present())
      occlusion = 1.0 + double(material.occlusionStrength) * (read(material.occlusion).r - 1.0);
    radiance += occlusion * environmentIntegral(*environment_, m, normal, v, settings.sampling,
                                                scramble, block);
  }
  if (settings.lights) radiance += punctualLight(m, position, normal, v);
  glm::dvec3 emission = glm::dvec3(material.emissiveFactor) * double(material.emissiveStrength);
  if (material.emissive.present() && emission != glm::dvec3(0.0))
    emission *= glm::dvec3(read(material.emissive));
  radiance += emission;
  return {radiance, surface.a};
}

LitFrame LitReference::render(const LitSettings& settings) const {
  QUADRA_CHECK(settings.samplesPerAxis > 0 && settings.sampling.environmentSamples >= 0 &&
               settings.sampling.brdfSamples >= 0);
  const int s = settings.samplesPerAxis;
  const int width = tracer_.width(), height = tracer_.height();
  std::vector<int> surfaces(std::size_t(width) * std::size_t(height), -1);
  LitFrame frame;
  frame.image = tracer_.integrate(s * s, [&](int x, int y, int k, std::vector<TracerHit>& scratch) {
    // Everything random about a pixel follows from the seed and its position.
    // Its sub-samples are the first S^2 points of a scrambled (0, 2)-sequence
    // over its square: stratified along every elementary interval (S^2 rows,
    // S^2 columns, S x S squares, ...), which edges of any slope, silhouettes
    // and the horizon seen in a mirror resolve better than jittered strata.
    const std::uint64_t pixel =
        hashCombine(hashCombine(settings.seed, std::uint64_t(x)), std::uint64_t(y));
    const glm::dvec2 window =
        glm::dvec2(x, y) + sobolPoint(std::uint32_t(k), hashCombine(pixel, 3));
    int surface = -1;
    glm::dvec4 colour = tracer_.shadeWith(
        window, scratch,
        [&](const TracerHit& hit, const Ray& ray, const glm::dvec4& surfaceColour) {
          return hitRadiance(hit, ray, surfaceColour, settings, pixel, std::uint32_t(k));
        },
        &surface);
    int& seen = surfaces[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    if (k == 0) seen = surface;
    if (seen != surface) seen = ReferenceTracer::kMixedSurface;
    if (colour.a < 1.0) {
      glm::dvec4 background = settings.backgroundColour;
      if (settings.background == LitBackground::Environment)
        background =
            environment_
                ? glm::dvec4(environment_->radiance(worldDirection(tracer_.primaryRay(window))),
                             1.0)
                : glm::dvec4(0.0, 0.0, 0.0, 1.0);
      colour += (1.0 - colour.a) * background;
    }
    return colour;
  });
  frame.interior = ReferenceTracer::interiorOf(surfaces, width, height);
  return frame;
}

}  // namespace quadra::ref
