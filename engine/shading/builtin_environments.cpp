// The built-in environments, each an analytic function of the direction
// evaluated in double precision at every texel centre (LIGHTING.md's mapping)
// and rounded to float once. Only + - * / and sqrt are used, with sine and
// cosine as written-out series, so the texels are the same bits on every
// machine and libm (glibc picks FMA variants of sin and cos by CPU).
#include "shading/builtin_environments.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace quadra {

namespace {

struct EnvSinCos {
  double s, c;
};

// sin(pi t) and cos(pi t) for |t| <= 2: t reduced exactly to r in [-1/4,
// 1/4] plus a quarter turn count (t - n/2 is exact by Sterbenz's lemma), then
// the Taylor series of sin and cos at pi r to x^17 and x^18, whose first
// omitted terms are below 1e-19 for |x| <= pi/4.
EnvSinCos envSinCosPi(double t) {
  const double n = std::floor(2.0 * t + 0.5);
  const double x = 3.14159265358979323846 * (t - 0.5 * n);
  const double x2 = x * x;
  double s = 1.0, c = 1.0;
  for (int k = 17; k >= 3; k -= 2) s = 1.0 - x2 / double(k * (k - 1)) * s;
  for (int k = 18; k >= 2; k -= 2) c = 1.0 - x2 / double(k * (k - 1)) * c;
  s *= x;
  switch (int(n) & 3) {
    case 0:
      return {s, c};
    case 1:
      return {c, -s};
    case 2:
      return {-s, -c};
    default:
      return {-c, s};
  }
}

struct EnvDirection {
  double x, y, z;
};

EnvDirection envNormalized(double x, double y, double z) {
  const double length = std::sqrt(x * x + y * y + z * z);
  return {x / length, y / length, z / length};
}

double envDot(const EnvDirection& a, const EnvDirection& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

double envSmoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

struct EnvRgb {
  double r, g, b;
};

using EnvRadianceFn = EnvRgb (*)(const EnvDirection&);

// Texel (i, j)'s centre is at u = (i + 0.5) / W, v = (j + 0.5) / H, the
// direction of theta = pi v from +Y and phi = pi (2u - 1) from -Z toward +X.
EnvironmentImage realizeEnvironment(std::string_view name, int width, int height,
                                    EnvRadianceFn radiance) {
  EnvironmentImage image;
  image.name = "builtin:" + std::string(name);
  image.width = width;
  image.height = height;
  image.rgb.resize(image.texelCount() * 3);
  std::vector<EnvSinCos> columns(static_cast<std::size_t>(width));
  for (int i = 0; i < width; ++i)
    columns[std::size_t(i)] = envSinCosPi(2.0 * ((i + 0.5) / width) - 1.0);
  for (int j = 0; j < height; ++j) {
    const EnvSinCos theta = envSinCosPi((j + 0.5) / height);
    float* row = image.rgb.data() + std::size_t(j) * std::size_t(width) * 3;
    for (int i = 0; i < width; ++i) {
      const EnvSinCos& phi = columns[std::size_t(i)];
      const EnvRgb l = radiance({theta.s * phi.s, theta.c, -theta.s * phi.c});
      row[3 * i] = float(l.r);
      row[3 * i + 1] = float(l.g);
      row[3 * i + 2] = float(l.b);
    }
  }
  return image;
}

// builtin:studio: a grey ground (0.12) below a sky brightening from 0.5 at
// the horizon to 0.8 at the zenith, joined over y in [-0.1, 0.1], and two
// broad soft lights: a key of 6 up front left (cone 10 to 20 degrees) and a
// rim of 3 behind right (8 to 18 degrees). Neutral grey throughout.
EnvRgb studioRadiance(const EnvDirection& d) {
  static const EnvDirection key = envNormalized(-1.0, 1.0, 1.0);
  static const EnvDirection rim = envNormalized(1.0, 0.5, -1.0);
  const double ground = 0.12, sky = 0.5 + 0.3 * d.y;
  const double l = ground + (sky - ground) * envSmoothstep(-0.1, 0.1, d.y) +
                   6.0 * envSmoothstep(0.94, 0.985, envDot(d, key)) +
                   3.0 * envSmoothstep(0.95, 0.99, envDot(d, rim));
  return {l, l, l};
}

// builtin:sky: a blue sky, lighter toward the horizon, over a dark ground,
// and a sun of radiance (15000, 13500, 11250) 16 degrees high, a disc of
// 0.8 to 1.2 degrees' radius (a soft rim of about one texel).
EnvRgb skyRadiance(const EnvDirection& d) {
  static const EnvDirection sun = envNormalized(0.25, 0.3, -1.0);
  const EnvRgb horizon{0.85, 0.9, 1.0}, zenith{0.15, 0.3, 0.75}, ground{0.1, 0.09, 0.08};
  const double up = 1.0 - std::max(d.y, 0.0);
  const double a = 1.0 - up * up * up;  // 0 at the horizon, 1 at the zenith
  const double h = envSmoothstep(-0.02, 0.02, d.y);
  const double s = envSmoothstep(0.99978, 0.9999, envDot(d, sun));
  const auto channel = [&](double hz, double ze, double gr, double sunValue) {
    const double skyValue = hz + (ze - hz) * a;
    return gr + (skyValue - gr) * h + sunValue * s;
  };
  return {channel(horizon.r, zenith.r, ground.r, 15000.0),
          channel(horizon.g, zenith.g, ground.g, 13500.0),
          channel(horizon.b, zenith.b, ground.b, 11250.0)};
}

// builtin:white: radiance 1 everywhere (the furnace test's environment).
EnvRgb whiteRadiance(const EnvDirection&) {
  return {1.0, 1.0, 1.0};
}

struct BuiltinEnvironment {
  const char* name;
  int width, height;
  EnvRadianceFn radiance;
};

// studio and sky at 1024x512 (a texel is 0.35 degrees: the lights' soft
// edges span tens of texels, the sun's rim about one); white needs no detail.
constexpr BuiltinEnvironment kBuiltinEnvironments[] = {
    {"studio", 1024, 512, studioRadiance},
    {"sky", 1024, 512, skyRadiance},
    {"white", 64, 32, whiteRadiance},
};

}  // namespace

const std::vector<std::string>& builtinEnvironmentNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const BuiltinEnvironment& b : kBuiltinEnvironments) out.emplace_back(b.name);
    return out;
  }();
  return names;
}

EnvironmentImage builtinEnvironment(std::string_view name) {
  for (const BuiltinEnvironment& b : kBuiltinEnvironments)
    if (name == b.name) return realizeEnvironment(name, b.width, b.height, b.radiance);
  std::string list;
  for (const std::string& known : builtinEnvironmentNames())
    list += (list.empty() ? "" : ", ") + known;
  throw makeError("builtin:" + std::string(name), "unknown built-in environment (" + list + ")");
}

}  // namespace quadra
