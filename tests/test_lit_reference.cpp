// Self-tests of the lit ideal (lab/reference/lit_reference.h) against
// closed forms and independent quadratures: white furnaces, a Lambertian
// plane under a panorama split at the horizon, the panorama's orientation
// and rotation, punctual lights by hand, the noise floor between two seeds,
// and the same bits on one thread and two.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "lab/image/lit_score.h"
#include "lab/reference/lit_reference.h"
#include "lab/scene/lit_scenes.h"

namespace quadra::ref {

namespace {

constexpr double kPi = std::numbers::pi;

// The height-correlated Smith visibility, written out as in Appendix B.
double visibility(double alpha, double nl, double nv) {
  const double a2 = alpha * alpha;
  return 0.5 / (nl * std::sqrt(nv * nv * (1 - a2) + a2) + nv * std::sqrt(nl * nl * (1 - a2) + a2));
}

double ggx(double alpha, double nh) {
  const double a2 = alpha * alpha;
  const double d = nh * nh * (a2 - 1) + 1;
  return a2 / (kPi * d * d);
}

// The directional albedo of a white GGX metal, int D V (n.l) dl over the
// hemisphere, by the midpoint rule over the NDF's own parameterization
// (theta_h = atan(alpha sqrt(s / (1 - s))), phi = 2 pi t, where D (n.h) dh =
// ds dt) and l = reflect(v, h), dl = 4 (v.h) dh.
double metalAlbedo(double alpha, double nDotV) {
  const glm::dvec3 v(std::sqrt(1 - nDotV * nDotV), 0, nDotV);
  constexpr int kSteps = 1000;
  double sum = 0;
  for (int a = 0; a < kSteps; ++a) {
    const double s = (a + 0.5) / kSteps;
    const double theta = std::atan(alpha * std::sqrt(s / (1 - s)));
    for (int b = 0; b < kSteps; ++b) {
      const double phi = 2 * kPi * (b + 0.5) / kSteps;
      const glm::dvec3 h(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                         std::cos(theta));
      const double vh = glm::dot(v, h);
      if (vh <= 0) continue;
      const glm::dvec3 l = 2 * vh * h - v;
      if (l.z <= 0) continue;
      sum += visibility(alpha, l.z, nDotV) * l.z * 4 * vh / h.z;
    }
  }
  return sum / (double(kSteps) * kSteps);
}

BrdfParameters metal(double roughness) {
  BrdfParameters m;
  m.baseColor = glm::dvec3(1.0);
  m.metallic = 1.0;
  m.alpha = roughness * roughness;
  return m;
}

// The mean of `blocks` blocks of the estimate: the pixel-sized sample count.
glm::dvec3 integral(const ReferenceEnvironment& environment, const BrdfParameters& m,
                    const glm::dvec3& n, const glm::dvec3& v, int samples, int blocks = 16) {
  glm::dvec3 sum(0.0);
  for (int b = 0; b < blocks; ++b)
    sum += environmentIntegral(environment, m, n, v, {samples, samples}, 12345, std::uint32_t(b));
  return sum / double(blocks);
}

glm::dvec3 unitAt(double degrees) {  // in the x-z plane, from +z toward +x
  const double r = degrees * kPi / 180;
  return {std::sin(r), 0, std::cos(r)};
}

TEST(LitReference, FurnaceMirrorMetalIsExactlyOne) {
  const EnvironmentImage white = uniformEnvironment(glm::vec3(1.0f));
  const ReferenceEnvironment environment(white);
  for (const double angle : {0.0, 30.0, 60.0, 85.0}) {
    const glm::dvec3 got =
        environmentIntegral(environment, metal(0.0), {0, 0, 1}, unitAt(angle), {16, 16}, 1);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], 1.0, 1e-12) << angle;
  }
  // The whole frame: spheres of white mirror metal inside the white furnace
  // are invisible (their roughness is 0, metallic 1).
  Scene scene = metalRoughSpheresScene(1, 1, glm::vec3(1.0f));
  scene.materials[0].roughnessFactor = 0.0f;
  const LitReference reference(scene, scene.cameras[0], 24, 16, &environment);
  LitSettings settings;
  settings.samplesPerAxis = 2;
  settings.sampling = {4, 4};
  const LitFrame frame = reference.render(settings);
  int covered = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 24; ++x) {
      for (int c = 0; c < 4; ++c) ASSERT_NEAR(frame.image.texel(x, y)[c], 1.0f, 1e-6f) << x << y;
      covered += frame.interior[std::size_t(y * 24 + x)] == 0 ? 0 : 1;
    }
  EXPECT_GT(covered, 0);
}

TEST(LitReference, FurnaceRoughMetalIsItsDirectionalAlbedo) {
  const EnvironmentImage white = uniformEnvironment(glm::vec3(1.0f), 16, 8);
  const ReferenceEnvironment environment(white);
  for (const double roughness : {0.3, 0.6, 1.0})
    for (const double angle : {0.0, 45.0, 75.0}) {
      const double expected = metalAlbedo(roughness * roughness, std::cos(angle * kPi / 180));
      const glm::dvec3 got = integral(environment, metal(roughness), {0, 0, 1}, unitAt(angle), 64);
      EXPECT_NEAR(got.r, expected, 2e-3 * expected) << roughness << " " << angle;
      EXPECT_LT(expected, 1.0 + 1e-6);
    }
}

// The irradiance int L(w) max(0, n.w) dw of a panorama whose rows are each
// constant, L a function of v = theta / pi interpolated linearly between row
// centres (clamped beyond the first and last), by the midpoint rule.
double irradiance(const std::vector<double>& rows, const glm::dvec3& n) {
  const int h = int(rows.size());
  const auto radiance = [&](double theta) {
    const double y = theta / kPi * h - 0.5;
    const int j = int(std::floor(y));
    const double f = y - j;
    const auto row = [&](int k) { return rows[std::size_t(std::clamp(k, 0, h - 1))]; };
    return (1 - f) * row(j) + f * row(j + 1);
  };
  constexpr int kTheta = 2000, kPhi = 1000;
  double sum = 0;
  for (int a = 0; a < kTheta; ++a) {
    const double theta = kPi * (a + 0.5) / kTheta;
    const double l = radiance(theta);
    for (int b = 0; b < kPhi; ++b) {
      const double phi = 2 * kPi * (b + 0.5) / kPhi;
      const glm::dvec3 w(std::sin(theta) * std::sin(phi), std::cos(theta),
                         std::sin(theta) * std::cos(phi));
      sum += l * std::max(0.0, glm::dot(n, w)) * std::sin(theta);
    }
  }
  return sum * (kPi / kTheta) * (2 * kPi / kPhi);
}

TEST(LitReference, DiffuseDielectricUnderSplitSkyIsLambert) {
  // With KHR_materials_specular's weight 0 the dielectric is Lambertian:
  // radiance = baseColor / pi x irradiance.
  constexpr int kHeight = 16;
  const EnvironmentImage split = splitEnvironment(glm::vec3(1.0f), glm::vec3(0.25f), 32, kHeight);
  const ReferenceEnvironment environment(split);
  std::vector<double> rows(kHeight, 0.25);
  for (int j = 0; j < kHeight / 2; ++j) rows[std::size_t(j)] = 1.0;
  BrdfParameters m;
  m.baseColor = {0.8, 0.6, 0.4};
  m.metallic = 0.0;
  m.alpha = 0.25;
  dielectricFresnel(1.5, glm::dvec3(1.0), 0.0, m.dielectricF0, m.dielectricF90);
  for (const double tilt : {0.0, 45.0, 90.0, 150.0}) {
    const double r = tilt * kPi / 180;
    const glm::dvec3 n(std::sin(r), std::cos(r), 0.0);  // tilted from +Y toward +X
    const glm::dvec3 v = glm::normalize(n + glm::dvec3(0.0, 0.0, 0.5));
    const double e = irradiance(rows, n);
    const glm::dvec3 got = integral(environment, m, n, v, 64);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(got[c], m.baseColor[c] / kPi * e, 1e-3 * m.baseColor[c] / kPi * e) << tilt;
  }
  // Facing straight up, the sharp-horizon figure: pi (sky) to a few parts
  // in a thousand (the texel band at the horizon blends the halves).
  EXPECT_NEAR(irradiance(rows, {0, 1, 0}), kPi, 0.02);
}

// LIGHTING.md's mapping inverted by hand: the direction of panorama (u, v).
glm::dvec3 directionOfTexel(double u, double v) {
  const double phi = 2 * kPi * (u - 0.5), theta = kPi * v;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

EnvironmentImage oneBrightTexel(int w, int h, int i, int j) {
  EnvironmentImage image = uniformEnvironment(glm::vec3(0.0f), w, h);
  for (int c = 0; c < 3; ++c)
    image.rgb[3 * (std::size_t(j) * std::size_t(w) + std::size_t(i)) + std::size_t(c)] = 1000.0f;
  return image;
}

TEST(LitReference, PanoramaOrientationAndRotation) {
  constexpr int kW = 64, kH = 32, kI = 40, kJ = 10;
  const EnvironmentImage image = oneBrightTexel(kW, kH, kI, kJ);
  const glm::dvec3 d = directionOfTexel((kI + 0.5) / kW, (kJ + 0.5) / kH);
  const ReferenceEnvironment plain(image);
  EXPECT_NEAR(plain.radiance(d).r, 1000.0, 1e-9);
  EXPECT_NEAR(plain.radiance(directionOfTexel((kI + 1.5) / kW, (kJ + 0.5) / kH)).r, 0.0, 1e-9);
  // -Z is the panorama's centre column (u = 0.5, between texels W/2 - 1 and
  // W/2), +Y its top row.
  const EnvironmentImage centre = oneBrightTexel(kW, kH, kW / 2, kH / 4);
  const double theta = kPi * (kH / 4 + 0.5) / kH;
  const ReferenceEnvironment centred(centre);
  EXPECT_NEAR(centred.radiance({0.0, std::cos(theta), -std::sin(theta)}).r, 500.0, 1e-9);
  EXPECT_EQ(centred.radiance({0.0, std::cos(theta), std::sin(theta)}).r, 0.0);
  EXPECT_EQ(centred.radiance({0.0, -std::cos(theta), -std::sin(theta)}).r, 0.0);
  // Turned 90 degrees about +Y: a lookup in d reads the panorama at
  // R_y(-90) d, so the texel is now seen at R_y(90) d = (d.z, d.y, -d.x).
  const ReferenceEnvironment turned(image, 90.0, 2.0);
  const glm::dvec3 moved(d.z, d.y, -d.x);
  EXPECT_NEAR(turned.radiance(moved).r, 2000.0, 1e-6);
  EXPECT_NEAR(turned.radiance(d).r, 0.0, 1e-9);
  // Sampling by luminance finds only the texel's 3x3 cells, with the
  // density the sample reports.
  for (int k = 0; k < 64; ++k) {
    double pdf = 0;
    const glm::dvec3 s = turned.sample({(k + 0.5) / 64, std::fmod(0.37 * k, 1.0)}, pdf);
    EXPECT_NEAR(pdf, turned.pdf(s), 1e-9 * pdf);
    EXPECT_GT(glm::dot(s, moved), std::cos(3.0 * kPi / kH));
  }
}

// A camera at `eye` looking along `direction` (not vertical).
Camera cameraLooking(const glm::vec3& eye, const glm::vec3& direction, float yfov) {
  Camera camera;
  camera.yfov = yfov;
  camera.znear = 0.01f;
  camera.world = glm::inverse(glm::lookAt(eye, eye + direction, glm::vec3(0.0f, 1.0f, 0.0f)));
  return camera;
}

// The brightest pixel of a frame.
glm::ivec2 brightest(const Image& image) {
  glm::ivec2 best(0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.texel(x, y)[0] > image.texel(best.x, best.y)[0]) best = {x, y};
  return best;
}

TEST(LitReference, BrightTexelSeenWhereTheMappingPutsIt) {
  constexpr int kW = 256, kH = 128, kI = 150, kJ = 40;  // above the horizon
  const EnvironmentImage image = oneBrightTexel(kW, kH, kI, kJ);
  const glm::dvec3 d = directionOfTexel((kI + 0.5) / kW, (kJ + 0.5) / kH);
  constexpr int kSize = 33;
  LitSettings settings;
  settings.samplesPerAxis = 3;
  settings.sampling = {4, 4};
  Scene empty;
  // Straight at it, as background.
  {
    const ReferenceEnvironment environment(image);
    const LitReference reference(empty, cameraLooking({0, 0, 0}, glm::vec3(d), 0.3f), kSize, kSize,
                                 &environment);
    EXPECT_EQ(brightest(reference.render(settings).image), glm::ivec2(kSize / 2));
  }
  // In a mirror: the floor y = -1 of white metal, roughness 0, seen along
  // d mirrored in it.
  Material mirror;
  mirror.roughnessFactor = 0.0f;
  const Scene floor = [&] {
    Scene s = litPlaneScene(mirror, 100.0f);
    s.instances[0].world = glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0));
    return s;
  }();
  const glm::vec3 down(float(d.x), -float(d.y), float(d.z));
  const ReferenceEnvironment environment(image);
  const LitReference reference(floor, cameraLooking({0, 0, 0}, down, 0.3f), kSize, kSize,
                               &environment);
  const Image seen = reference.render(settings).image;
  EXPECT_EQ(brightest(seen), glm::ivec2(kSize / 2));
  EXPECT_GT(seen.texel(kSize / 2, kSize / 2)[0], 10.0f);
  // Turned 90 degrees, the texel leaves the mirror's centre and appears
  // where the reflection of R_y(90) d is.
  const ReferenceEnvironment turned(image, 90.0);
  const LitReference away(floor, cameraLooking({0, 0, 0}, down, 0.3f), kSize, kSize, &turned);
  EXPECT_LT(away.render(settings).image.texel(kSize / 2, kSize / 2)[0], 1e-3f);
  const glm::vec3 movedDown(float(d.z), -float(d.y), -float(d.x));
  const LitReference there(floor, cameraLooking({0, 0, 0}, movedDown, 0.3f), kSize, kSize, &turned);
  EXPECT_EQ(brightest(there.render(settings).image), glm::ivec2(kSize / 2));
}

// An orthographic camera above the plane y = 0 looking down, seeing
// |x|, |z| <= 2: pixel (px, py) of a size x size frame sees world
// (x, z) = (-2 + 4 (px + 0.5) / size, -2 + 4 (py + 0.5) / size).
Camera topDown() {
  Camera camera;
  camera.type = Camera::Type::Orthographic;
  camera.xmag = camera.ymag = 2.0f;
  camera.znear = 0.5f;
  camera.zfar = 10.0f;
  // Looking down -Y with +Z toward the image's bottom: x right, z down.
  camera.world = glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, -1, 0), glm::vec4(0, 1, 0, 0),
                           glm::vec4(0, 5, 0, 1));
  return camera;
}

glm::dvec3 pixelWorld(int px, int py, int size) {
  return {-2.0 + 4.0 * (px + 0.5) / size, 0.0, -2.0 + 4.0 * (py + 0.5) / size};
}

TEST(LitReference, PointLightOnAPlaneByHand) {
  constexpr int kSize = 128;
  Material material;
  material.baseColorFactor = {0.5f, 0.4f, 0.3f, 1.0f};
  material.metallicFactor = 0.0f;
  material.roughnessFactor = 0.6f;
  Scene scene = litPlaneScene(material, 4.0f);
  Light light;
  light.type = Light::Type::Point;
  light.intensity = 3.0f;
  light.color = {1.0f, 0.5f, 0.25f};
  light.world = glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 1.0f, -0.2f));
  scene.lights.push_back(light);
  const LitReference reference(scene, topDown(), kSize, kSize, nullptr);
  LitSettings settings;
  settings.samplesPerAxis = 4;
  const Image image = reference.render(settings).image;
  const glm::dvec3 lightAt(0.3, 1.0, -0.2), v(0, 1, 0), n(0, 1, 0);
  const double alpha = 0.36;
  for (const glm::ivec2 p :
       {glm::ivec2(64, 64), glm::ivec2(70, 59), glm::ivec2(20, 100), glm::ivec2(110, 10)}) {
    const glm::dvec3 at = pixelWorld(p.x, p.y, kSize);
    const glm::dvec3 toLight = lightAt - at;
    const double d2 = glm::dot(toLight, toLight);
    const glm::dvec3 l = toLight / std::sqrt(d2);
    const glm::dvec3 h = glm::normalize(l + v);
    const double fresnel = 0.04 + 0.96 * std::pow(1 - glm::dot(v, h), 5);
    const double specular = fresnel * ggx(alpha, h.y) * visibility(alpha, l.y, 1.0);
    for (int c = 0; c < 3; ++c) {
      const double base = material.baseColorFactor[c];
      const double f = (1 - fresnel) * base / kPi + specular;
      const double expected = f * glm::dot(n, l) * 3.0 * light.color[c] / d2;
      EXPECT_NEAR(image.texel(p.x, p.y)[c], expected, 2e-3 * expected) << p.x << "," << p.y;
    }
  }
}

TEST(LitReference, SpotConeEdge) {
  constexpr int kSize = 128;
  Material lambert;
  lambert.metallicFactor = 0.0f;
  lambert.specularFactor = 0.0f;  // KHR_materials_specular 0: f = baseColor / pi
  Scene scene = litPlaneScene(lambert, 4.0f);
  Light spot;
  spot.type = Light::Type::Spot;
  spot.intensity = 10.0f;
  spot.innerConeAngle = 0.3f;
  spot.outerConeAngle = 0.6f;
  spot.range = 0.0f;
  // At (0, 1, 0), -Z turned to -Y.
  spot.world = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)), -float(kPi) / 2,
                           glm::vec3(1, 0, 0));
  scene.lights.push_back(spot);
  const LitReference reference(scene, topDown(), kSize, kSize, nullptr);
  LitSettings settings;
  settings.samplesPerAxis = 16;
  const Image image = reference.render(settings).image;
  const double cosInner = std::cos(0.3), cosOuter = std::cos(0.6);
  // The closed form at a point of the plane, and its mean over a pixel
  // (the midpoint rule on 16 x 16 points: the cone's ramp is curved enough
  // that a pixel's mean is not its centre's value).
  const auto radiance = [&](double x, double z) {
    const double d2 = x * x + z * z + 1.0;
    const double cosAngle = 1.0 / std::sqrt(d2);  // from the spot's axis, and n.l too
    const double t = std::clamp((cosAngle - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
    return 10.0 / kPi * cosAngle / d2 * t * t;
  };
  const auto pixelMean = [&](int px, int py) {
    double sum = 0;
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i)
        sum += radiance(-2.0 + 4.0 * (px + (i + 0.5) / 16) / kSize,
                        -2.0 + 4.0 * (py + (j + 0.5) / 16) / kSize);
    return sum / 256;
  };
  int inside = 0, outside = 0, ramp = 0;
  for (int py = 0; py < kSize; ++py)
    for (int px = 0; px < kSize; ++px) {
      const glm::dvec3 at = pixelWorld(px, py, kSize);
      const double angle = std::atan(std::sqrt(at.x * at.x + at.z * at.z));
      const double got = image.texel(px, py)[0];
      const double expected = pixelMean(px, py);
      EXPECT_NEAR(got, expected, 3e-3 * expected + 1e-4) << px << "," << py;
      // The cone's edges pass through pixels; those clear of them by more
      // than a pixel's span of angle are wholly lit or dark.
      if (angle < 0.3 - 0.03) ++inside;
      if (angle > 0.6 + 0.03) {
        EXPECT_EQ(got, 0.0) << px << "," << py;
        ++outside;
      }
      if (angle > 0.3 + 0.03 && angle < 0.6 - 0.03) ++ramp;
    }
  EXPECT_GT(inside, 100);
  EXPECT_GT(outside, 100);
  EXPECT_GT(ramp, 100);
}

TEST(LitReference, DirectionalLightAndEmissionAndOcclusion) {
  // A Lambertian plane under a directional light of E lux at 60 degrees,
  // plus its emission; an occlusion of 0 at strength 1 removes the white
  // environment's share, which the plane's irradiance pi would have added.
  Material material;
  material.metallicFactor = 0.0f;
  material.specularFactor = 0.0f;
  material.baseColorFactor = {0.5f, 0.5f, 0.5f, 1.0f};
  material.emissiveFactor = {0.1f, 0.2f, 0.3f};
  material.emissiveStrength = 2.0f;
  Scene scene = litPlaneScene(material, 4.0f);
  auto occlusion = std::make_shared<Image>(1, 1);
  occlusion->rgba = {0.0f, 0.0f, 0.0f, 1.0f};
  scene.textures.push_back(std::make_shared<Texture>(occlusion, SamplerState{}));
  Light sun;
  sun.type = Light::Type::Directional;
  sun.intensity = 4.0f;
  sun.world = glm::rotate(glm::mat4(1.0f), -float(kPi) / 3, glm::vec3(1, 0, 0));  // 60 deg down
  scene.lights.push_back(sun);
  const EnvironmentImage white = uniformEnvironment(glm::vec3(1.0f));
  const ReferenceEnvironment environment(white);
  LitSettings settings;
  settings.samplesPerAxis = 2;
  settings.sampling = {16, 16};
  const double cosine = std::sin(kPi / 3);
  {
    const LitReference reference(scene, topDown(), 8, 8, &environment);
    const Image image = reference.render(settings).image;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(image.texel(3, 5)[c],
                  0.5 / kPi * (4.0 * cosine + kPi) + 2.0 * material.emissiveFactor[c], 2e-3);
  }
  scene.materials[0].occlusion.texture = 0;
  const LitReference reference(scene, topDown(), 8, 8, &environment);
  const Image image = reference.render(settings).image;
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(image.texel(3, 5)[c], 0.5 / kPi * 4.0 * cosine + 2.0 * material.emissiveFactor[c],
                1e-6);
}

// A camera at (0, 5, 0) looking down (as topDown), or at (0, -5, 0) looking up.
Camera orthographicAlongY(bool fromBelow) {
  Camera camera = topDown();
  if (fromBelow)
    camera.world = glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, -1, 0, 0),
                             glm::vec4(0, -5, 0, 1));
  return camera;
}

TEST(LitReference, NormalMapTiltsTheFrameAndBackFacesFlipIt) {
  // A Lambertian double-sided plane (N = +Y, TANGENT +X with w = +-1, so
  // B = w N x T = -w Z) whose normal map holds one texel: n_t tilted by 30
  // degrees toward T or toward B. Lit by a directional light alone, its
  // radiance is baseColor / pi x E x max(0, n.l) for n = T n_t.x + B n_t.y +
  // N n_t.z, flipped with N, T and B seen from below.
  const double tilt = 30.0 * kPi / 180;
  struct Case {
    glm::dvec3 local;  // n_t
    float w;
    bool fromBelow;
    glm::dvec3 expectedNormal;
  };
  const double s = std::sin(tilt), c = std::cos(tilt);
  const Case cases[] = {
      {{s, 0, c}, 1.0f, false, {s, c, 0}},   {{0, s, c}, 1.0f, false, {0, c, -s}},
      {{0, s, c}, -1.0f, false, {0, c, s}},  {{s, 0, c}, 1.0f, true, {-s, -c, 0}},
      {{0, s, c}, -1.0f, true, {0, -c, -s}},
  };
  for (const Case& test : cases) {
    Material material;
    material.metallicFactor = 0.0f;
    material.specularFactor = 0.0f;
    material.doubleSided = true;
    material.normal.texture = 0;
    Scene scene = litPlaneScene(material, 4.0f);
    scene.meshes[0].tangents.assign(4, glm::vec4(1, 0, 0, test.w));
    auto texel = std::make_shared<Image>(1, 1);
    for (int k = 0; k < 3; ++k) texel->rgba[std::size_t(k)] = float((test.local[k] + 1.0) / 2.0);
    texel->rgba[3] = 1.0f;
    scene.textures.push_back(std::make_shared<Texture>(texel, SamplerState{}));
    // Light arriving along -l for l in each of a few directions.
    for (const glm::dvec3 toLight : {glm::dvec3(0.5, 1, 0.2), glm::dvec3(-0.3, 1, -0.6),
                                     glm::dvec3(0.4, -1, 0.3), glm::dvec3(0.1, -1, -0.5)}) {
      const glm::dvec3 l = glm::normalize(toLight);
      Light sun;
      sun.type = Light::Type::Directional;
      sun.intensity = 2.0f;
      // The node's -Z turned onto -l: its rotation's columns, Z = l.
      const glm::dvec3 z = l, x = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), z)),
                       y = glm::cross(z, x);
      sun.world = glm::mat4(glm::vec4(glm::vec3(x), 0), glm::vec4(glm::vec3(y), 0),
                            glm::vec4(glm::vec3(z), 0), glm::vec4(0, 0, 0, 1));
      scene.lights = {sun};
      const LitReference reference(scene, orthographicAlongY(test.fromBelow), 4, 4, nullptr);
      LitSettings settings;
      settings.samplesPerAxis = 1;
      const Image image = reference.render(settings).image;
      const glm::dvec3 n = glm::normalize(test.expectedNormal);
      const double expected = 1.0 / kPi * 2.0 * std::max(0.0, glm::dot(n, l));
      EXPECT_NEAR(image.texel(1, 2)[0], expected, 1e-5)
          << "w " << test.w << (test.fromBelow ? " below" : " above") << " l " << l.x << "," << l.y
          << "," << l.z;
    }
  }
}

TEST(LitReference, IorSpecularAndUnlit) {
  // KHR_materials_ior and _specular: f0 = min(((ior - 1) / (ior + 1))^2 x
  // specularColor, 1) x specular, f90 = specular.
  glm::dvec3 f0;
  double f90 = 0;
  dielectricFresnel(2.0, glm::dvec3(1.0, 0.5, 20.0), 0.5, f0, f90);
  EXPECT_NEAR(f0.r, 0.5 / 9, 1e-15);
  EXPECT_NEAR(f0.g, 0.25 / 9, 1e-15);
  EXPECT_NEAR(f0.b, 0.5, 1e-15);  // clamped to 1 before the weight
  EXPECT_EQ(f90, 0.5);
  // A dielectric mirror seen head-on reflects f0 of the environment; at
  // grazing angles f90.
  BrdfParameters m;
  m.metallic = 0.0;
  m.alpha = 0.0;
  m.dielectricF0 = f0;
  m.dielectricF90 = f90;
  EXPECT_NEAR(mirrorReflectance(m, {0, 0, 1}, {0, 0, 1}).g, f0.g, 1e-15);
  EXPECT_NEAR(mirrorReflectance(m, {0, 0, 1}, glm::normalize(glm::dvec3(1, 0, 1e-9))).g, 0.5, 1e-8);
  // KHR_materials_unlit shows the base colour whatever the light.
  Material unlit;
  unlit.unlit = true;
  unlit.baseColorFactor = {0.2f, 0.4f, 0.6f, 1.0f};
  unlit.emissiveFactor = {1.0f, 1.0f, 1.0f};
  const Scene scene = litPlaneScene(unlit, 4.0f);
  const EnvironmentImage bright = uniformEnvironment(glm::vec3(5.0f));
  const ReferenceEnvironment environment(bright);
  LitSettings settings;
  settings.samplesPerAxis = 1;
  const Image image = LitReference(scene, topDown(), 4, 4, &environment).render(settings).image;
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(image.texel(2, 2)[c], unlit.baseColorFactor[c]);
}

LitFrame renderSpheres(const LitSettings& settings, int width, int height) {
  static const EnvironmentImage sky = sunnySkyEnvironment(256, 128);
  static const ReferenceEnvironment environment(sky);
  static const Scene scene = metalRoughSpheresScene(3, 3, glm::vec3(0.9f, 0.7f, 0.5f));
  const LitReference reference(scene, scene.cameras[0], width, height, &environment);
  return reference.render(settings);
}

TEST(LitReference, NoiseFloorBetweenTwoSeeds) {
  // Pixel integration and environment samples both change with the seed;
  // what two seeds disagree on bounds the ideal's own error.
  LitSettings settings;
  settings.samplesPerAxis = 8;
  settings.sampling = {16, 16};
  const auto start = std::chrono::steady_clock::now();
  const LitFrame a = renderSpheres(settings, 96, 72);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  settings.seed = 2;
  const LitFrame b = renderSpheres(settings, 96, 72);
  const LitScore score = scoreLitFrame(a.image, b.image, a.interior);
  std::printf(
      "[ 96x72, %d^2 rays, %d + %d env samples per ray: %.2f s ] seeds 1 vs 2: "
      "%.2f dB all, %.2f dB interior (%zu px)\n",
      settings.samplesPerAxis, settings.sampling.environmentSamples, settings.sampling.brdfSamples,
      seconds, score.all.psnr, score.interior.psnr, score.interiorPixels);
  EXPECT_GT(score.interior.psnr, 55.0);
  EXPECT_GT(score.all.psnr, 45.0);
  EXPECT_GT(score.interiorPixels, 1000u);
}

TEST(LitReference, SameBitsOnOneThreadAndTwo) {
  LitSettings settings;
  settings.samplesPerAxis = 2;
  settings.sampling = {8, 8};
  LitFrame one, two;
  tbb::task_arena(1).execute([&] { one = renderSpheres(settings, 48, 36); });
  tbb::task_arena(2).execute([&] { two = renderSpheres(settings, 48, 36); });
  ASSERT_EQ(one.image.rgba.size(), two.image.rgba.size());
  EXPECT_EQ(std::memcmp(one.image.rgba.data(), two.image.rgba.data(),
                        one.image.rgba.size() * sizeof(float)),
            0);
  EXPECT_EQ(one.interior, two.interior);
}

TEST(LitScore, PbrNeutralAndSrgb) {
  // Below the compression threshold the tone map only offsets: x - f with
  // f = 0.04 once the smallest component passes 0.08.
  const glm::dvec3 grey = pbrNeutral(glm::dvec3(0.5));
  EXPECT_NEAR(grey.r, 0.46, 1e-15);
  EXPECT_NEAR(pbrNeutral(glm::dvec3(0.04)).g, 0.04 - (0.04 - 0.04 * 0.04 * 6.25), 1e-15);
  // Highlights compress toward 1 and desaturate.
  const glm::dvec3 bright = pbrNeutral({50.0, 10.0, 1.0});
  EXPECT_LT(bright.r, 1.0);
  EXPECT_GT(bright.r, 0.98);
  EXPECT_GT(bright.b / bright.r, 1.0 / 50.0);
  EXPECT_NEAR(srgbEncode(1.0), 1.0, 1e-15);
  EXPECT_NEAR(srgbEncode(0.002), 0.02584, 1e-12);
  EXPECT_NEAR(srgbEncode(0.5), 0.735356983, 1e-9);
}

TEST(LitScore, InteriorPsnrLeavesEdgesOut) {
  Image a(4, 1), b(4, 1);
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 4; ++c) a.texel(x, 0)[c] = b.texel(x, 0)[c] = 0.25f;
  b.texel(0, 0)[1] = 0.75f;  // an edge pixel differs
  const std::vector<std::uint8_t> interior = {0, 1, 1, 1};
  EXPECT_TRUE(std::isinf(imageDifference(a, b, interior).psnr));
  EXPECT_NEAR(imageDifference(a, b).psnr, -10 * std::log10(0.25 / 12), 1e-9);
}

TEST(LitReference, InteriorMaskFollowsSilhouettes) {
  const Scene scene = metalRoughSpheresScene(1, 1, glm::vec3(1.0f));
  const ReferenceTracer tracer(scene, scene.cameras[0], 32, 32);
  const std::vector<std::uint8_t> mask = tracer.interiorMask(3);
  EXPECT_EQ(mask[16 * 32 + 16], 1);  // the sphere's middle
  EXPECT_EQ(mask[0], 1);             // the corner: background only
  // Along the middle row, from the background into the sphere, the mask
  // drops to 0 around the silhouette and rises again.
  int zeros = 0;
  for (int x = 0; x < 16; ++x) zeros += mask[16 * 32 + std::size_t(x)] == 0;
  EXPECT_GE(zeros, 2);
  EXPECT_LE(zeros, 4);
}

}  // namespace

}  // namespace quadra::ref
