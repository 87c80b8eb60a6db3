// The area-integrating reference (ReferenceTracer::renderArea) and its
// segment integrals (lab/reference/bilinear_integral.h) against answers
// found another way: dense quadrature of the point lookup, hat-function
// sums, the closed-form average of a linear texture on a perspective floor,
// exact pixel areas under an edge, and the point-sampled tracer itself where
// that converges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "lab/image/image_difference.h"
#include "lab/reference/bilinear_integral.h"
#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"

namespace quadra::ref {

namespace {

// Texels in [0, 1], alpha too, in steps of 1/999.
Image noiseImage(int width, int height, unsigned seed) {
  std::minstd_rand rng(seed);
  Image image(width, height);
  std::generate(image.rgba.begin(), image.rgba.end(),
                [&rng] { return float(rng() % 1000) / 999.0f; });
  return image;
}

// The point lookup of texel-space position p.
glm::dvec4 lookup(const Image& image, const SamplerState& sampler, const glm::dvec2& p) {
  return sampleBilinear(image, sampler, {(p.x + 0.5) / image.width, (p.y + 0.5) / image.height});
}

double maxAbs(const glm::dvec4& v) {
  return std::max({std::fabs(v.r), std::fabs(v.g), std::fabs(v.b), std::fabs(v.a)});
}

}  // namespace

// Random segments, short and long, steep and shallow, in every wrap mode,
// against the midpoint rule over 2^18 point lookups (its error is below
// (slope jump) h^2 / 8 per texel line crossed: < 1e-8 here).
TEST(BilinearIntegral, SegmentMeanIsTheMeanOfThePointLookups) {
  const Image image = noiseImage(7, 5, 3);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> position(-30.0, 30.0), length(0.2, 40.0),
      angle(0.0, 6.283185307179586);
  for (const WrapMode mode : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge,
                              WrapMode::ClampToBorder}) {
    SamplerState sampler;
    sampler.wrapU = mode;
    sampler.wrapV = mode == WrapMode::Repeat ? WrapMode::ClampToBorder : WrapMode::Repeat;
    sampler.borderColor[0] = 0.3f;
    sampler.borderColor[3] = 0.9f;
    const BilinearIntegral integral(image, sampler);
    for (int trial = 0; trial < 12; ++trial) {
      const glm::dvec2 a(position(rng), position(rng));
      const double l = length(rng), phi = trial == 0   ? 0.0
                                          : trial == 1 ? 1.5707963267948966
                                                       : angle(rng);
      const glm::dvec2 b = a + l * glm::dvec2(std::cos(phi), std::sin(phi));
      constexpr int kPoints = 1 << 18;
      glm::dvec4 sum(0.0);
      for (int i = 0; i < kPoints; ++i)
        sum += lookup(image, sampler, a + (b - a) * ((i + 0.5) / kPoints));
      const glm::dvec4 expected = sum / double(kPoints);
      EXPECT_LT(maxAbs(integral.segmentMean(a, b) - expected), 1e-7)
          << wrapName(mode) << " from " << a.x << "," << a.y << " to " << b.x << "," << b.y;
    }
    // A point is its lookup.
    const glm::dvec2 p(2.3, -1.7);
    EXPECT_LT(maxAbs(integral.segmentMean(p, p) - lookup(image, sampler, p)), 1e-12);
  }
}

// A row segment a million texels out and thousands long (a chord across a
// minified plane) is the hat-weighted sum of its texels: the tables' period
// reduction loses nothing that far out.
TEST(BilinearIntegral, LongRowSegmentFarOutIsTheHatWeightedSum) {
  const Image image = noiseImage(13, 4, 5);
  const SamplerState sampler;  // repeat
  const BilinearIntegral integral(image, sampler);
  const double x0 = 1.0e6 + 0.37, x1 = x0 + 4321.9, y = 2.25;
  // The integral of the hat max(0, 1 - |t|) from -inf to t.
  const auto hatUpTo = [](double t) {
    return t <= -1.0  ? 0.0
           : t <= 0.0 ? 0.5 * (t + 1) * (t + 1)
           : t <= 1.0 ? 1.0 - 0.5 * (1 - t) * (1 - t)
                      : 1.0;
  };
  glm::dvec4 expected(0.0);
  for (auto i = std::int64_t(std::floor(x0)) - 1; i <= std::int64_t(std::ceil(x1)) + 1; ++i) {
    const double w = hatUpTo(x1 - double(i)) - hatUpTo(x0 - double(i));
    const int column = int(wrapTexel(i, image.width, WrapMode::Repeat));
    for (int row = 2; row <= 3; ++row) {
      const float* t = image.texel(column, row);
      expected += w * (row == 2 ? 0.75 : 0.25) * glm::dvec4(t[0], t[1], t[2], t[3]);
    }
  }
  expected /= (x1 - x0);
  EXPECT_LT(maxAbs(integral.segmentMean({x0, y}, {x1, y}) - expected), 1e-11);
}

namespace {

// A perspective camera at the origin looking down -Z over a floor at y = -1
// from z = -1 to z = -100, wide beyond the view, whose texture is linear in
// both texel coordinates where the view sees it: texel (i, j) = a + b i + c j.
struct Floor {
  Scene scene;
  Camera camera;
  static constexpr double kU0 = 0.5, kKu = 0.45 / 120.0;  // u = kU0 + kKu x
  static constexpr double kV0 = 0.01, kKv = 0.97 / 99.0;  // v = kV0 + kKv (-z - 1)
  static constexpr int kSize = 64;
  glm::dvec4 a{0.1, 0.2, 0.05, 1.0}, b{0.01, 0.0, -0.004, 0.0}, c{0.004, 0.011, 0.0, 0.0};

  Floor() {
    camera.yfov = float(60.0 * 3.141592653589793 / 180.0);
    camera.znear = 0.1f;
    Image texture(kSize, kSize);
    for (int j = 0; j < kSize; ++j)
      for (int i = 0; i < kSize; ++i) {
        const glm::dvec4 value = a + b * double(i) + c * double(j);
        for (int k = 0; k < 4; ++k) texture.texel(i, j)[k] = float(value[k]);
      }
    // Read back as stored, so the closed form uses the float texels' line.
    SamplerState sampler;
    sampler.wrapU = sampler.wrapV = WrapMode::ClampToEdge;
    Mesh mesh;
    const float xs[4] = {-500, 500, 500, -500}, zs[4] = {-1, -1, -100, -100};
    for (int k = 0; k < 4; ++k) {
      mesh.positions.push_back({xs[k], -1.0f, zs[k]});
      mesh.texcoords[0].push_back(
          {float(kU0 + kKu * xs[k]), float(kV0 + kKv * (-double(zs[k]) - 1.0))});
    }
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.material = 0;
    Material material;
    material.baseColorTexture = 0;
    material.doubleSided = true;
    scene.meshes.push_back(mesh);
    scene.materials.push_back(material);
    scene.textures.push_back(
        std::make_shared<Texture>(std::make_shared<Image>(std::move(texture)), sampler));
    scene.instances.push_back(Instance{});
  }
};

}  // namespace

// The floor's texel coordinates are projective in the window point; their
// box average over a pixel has a closed form (a log across rows, the centre
// across columns), and a linear texture's average is its value there.
TEST(ReferenceArea, LinearTextureOnAPerspectiveFloorIsTheClosedForm) {
  const Floor floor;
  const int width = 64, height = 36;
  const ReferenceTracer tracer(floor.scene, floor.camera, width, height);
  ReferenceTracer::AreaStats stats;
  const Image image = tracer.renderArea({.samplesPerAxis = 16, .gaussNodes = 3}, &stats);
  const double f = 1.0 / std::tan(3.141592653589793 / 6.0), aspect = double(width) / height;
  // Window y where the far edge (z = -100) lies: yn = -f / 100.
  const double farEdgeY = 0.5 * height * (1.0 + f / 100.0);
  int checked = 0;
  for (int y = int(std::ceil(farEdgeY)); y < height; ++y) {
    // yn = 1 - 2 y / H < 0; the mean of 1 / yn over the row of pixels.
    const auto yn = [&](double wy) { return 1.0 - 2.0 * wy / height; };
    const double meanInverse =
        -0.5 * height * (std::log(std::fabs(yn(y + 1.0))) - std::log(std::fabs(yn(y))));
    for (int x = 0; x < width; ++x) {
      const double xn = 2.0 * (x + 0.5) / width - 1.0;
      // Hit: X = -xn aspect / yn, -Z = -f / yn.
      const double u = Floor::kU0 - Floor::kKu * aspect * xn * meanInverse;
      const double v = Floor::kV0 + Floor::kKv * (-f * meanInverse - 1.0);
      const double s = u * Floor::kSize - 0.5, t = v * Floor::kSize - 0.5;
      ASSERT_TRUE(s > 0.0 && s < Floor::kSize - 1 && t > 0.0 && t < Floor::kSize - 1);
      const glm::dvec4 expected = floor.a + floor.b * s + floor.c * t;
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(image.texel(x, y)[k], expected[k], 2e-7) << x << "," << y << " channel " << k;
      ASSERT_NEAR(image.texel(x, y)[3], 1.0, 1e-7);
      ++checked;
    }
  }
  EXPECT_GT(checked, 800);
  EXPECT_EQ(stats.sampledCells, 0);
  // The point-sampled frame misses the same answer by far more: the test can tell.
  const Image sampled = tracer.render(4);
  double worst = 0.0;
  for (int y = int(std::ceil(farEdgeY)); y < height; ++y)
    for (int x = 0; x < width; ++x)
      worst = std::max(worst, double(std::fabs(sampled.texel(x, y)[1] - image.texel(x, y)[1])));
  EXPECT_GT(worst, 1e-5);
}

// An untextured triangle with a corner in the view: each pixel's alpha is
// the exact area of its square inside the triangle, here found scanline by
// scanline (each edge's half-plane cuts a row to an interval) rather than by
// clipping polygons as renderArea does.
TEST(ReferenceArea, CoverageIsTheExactPixelArea) {
  Scene scene;
  Mesh mesh;
  const glm::dvec3 corners[3] = {{-0.31, -0.17, -2}, {5, 9, -2}, {7, -6, -2}};
  for (const glm::dvec3& p : corners) mesh.positions.push_back(glm::vec3(p));
  mesh.indices = {0, 1, 2};
  mesh.material = 0;
  scene.meshes.push_back(mesh);
  Material material;
  material.doubleSided = true;
  scene.materials.push_back(material);
  scene.instances.push_back(Instance{});
  Camera camera;
  camera.yfov = 1.0f;
  const int width = 24, height = 16;
  const ReferenceTracer tracer(scene, camera, width, height);
  ReferenceTracer::AreaStats stats;
  const Image image = tracer.renderArea({.samplesPerAxis = 16}, &stats);
  const double f = 1.0 / std::tan(0.5), aspect = double(width) / height;
  glm::dvec2 w[3];
  for (int k = 0; k < 3; ++k) {
    // The positions as stored (float), projected.
    const glm::dvec3 p(mesh.positions[std::size_t(k)]);
    w[k] = {(f / aspect * p.x / -p.z + 1.0) * width / 2, (1.0 - f * p.y / -p.z) * height / 2};
  }
  // Row wy inside the triangle: x in [lo, hi], from each edge's half-plane
  // (the side its opposite corner lies on).
  const auto rowInterval = [&](double wy, double& lo, double& hi) {
    lo = -HUGE_VAL;
    hi = HUGE_VAL;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec2 p = w[k], q = w[(k + 1) % 3], o = w[(k + 2) % 3];
      const double a = -(q.y - p.y), b = q.x - p.x;  // side(X) = a (X - p).x + b (X - p).y
      const double sign = a * (o.x - p.x) + b * (o.y - p.y) > 0 ? 1.0 : -1.0;
      const double sa = sign * a, rest = sign * b * (wy - p.y);  // sa (x - p.x) + rest >= 0
      if (sa == 0.0) {
        if (rest < 0.0) hi = -HUGE_VAL;
      } else if (sa > 0.0) {
        lo = std::max(lo, p.x - rest / sa);
      } else {
        hi = std::min(hi, p.x - rest / sa);
      }
    }
  };
  int partial = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      constexpr int kRows = 4096;
      double area = 0.0;
      for (int r = 0; r < kRows; ++r) {
        double lo, hi;
        rowInterval(y + (r + 0.5) / kRows, lo, hi);
        area += std::max(0.0, std::min(hi, x + 1.0) - std::max(lo, double(x))) / kRows;
      }
      partial += area > 0.01 && area < 0.99;
      // The covered width is piecewise linear in wy: the midpoint rule is
      // exact but for the rows holding a kink (a corner, or an edge leaving
      // the square), a few of 1/4096 each.
      ASSERT_NEAR(image.texel(x, y)[3], area, 2e-6) << x << "," << y;
    }
  EXPECT_GT(partial, 20);
  EXPECT_EQ(stats.sampledCells, 0);
}

// checker-plane's horizon: two quadrature settings agree far beyond the
// criterion (the breakpoints make each interval's integrand smooth), and
// where the checker is magnified (the lower rows) the point-sampled frame,
// which converges there, agrees too.
TEST(ReferenceArea, CheckerPlaneConvergesAndMatchesDenseRaysWhereThoseConverge) {
  const Scene scene = makeBuiltinScene("checker-plane");
  // Small: a pixel column costs the texel rows its pixels cross between the
  // eye and the plane's far edge (~1.2e5 here at any width), ~1.5 s a node.
  const int width = 32, height = 18;
  const ReferenceTracer tracer(scene, scene.cameras.at(0), width, height);
  ReferenceTracer::AreaStats stats;
  const Image fine = tracer.renderArea({.samplesPerAxis = 16, .gaussNodes = 3}, &stats);
  const Image coarse = tracer.renderArea({.samplesPerAxis = 8, .gaussNodes = 1});
  EXPECT_GT(imageDifference(coarse, fine).psnr, 70.0);
  EXPECT_EQ(stats.sampledCells, 0);
  EXPECT_EQ(stats.exactArea, 1.0);
  EXPECT_GT(stats.intervals, 1000000);
  const Image rays = tracer.render(64);
  double worst = 0.0;
  for (int y = height - 4; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, double(std::fabs(rays.texel(x, y)[k] - fine.texel(x, y)[k])));
  EXPECT_LT(worst, 2e-3);
}

// Where surfaces overlap on screen (blended layers, occluders) the cells
// split and the last level takes the point-sampled rays: such a frame stays
// the point-sampled one but for its exactly integrated cells.
TEST(ReferenceArea, OverlappingSurfacesFallBackToTheRays) {
  // The share integrated exactly: alpha-quads' background outside its five
  // blended quads (measured 0.108 at 96x54), showcase's all but its
  // silhouettes, blended glass, masked panel and vertex-coloured ball.
  for (const auto& [name, exactAtLeast] : {std::pair{"alpha-quads", 0.05}, {"showcase", 0.5}}) {
    const Scene scene = makeBuiltinScene(name);
    const int width = 96, height = 54;
    const ReferenceTracer tracer(scene, scene.cameras.at(0), width, height);
    ReferenceTracer::AreaStats stats;
    const Image area = tracer.renderArea({.samplesPerAxis = 16}, &stats);
    EXPECT_GT(stats.sampledCells, 0) << name;
    EXPECT_GT(stats.exactCells, 0) << name;
    EXPECT_GT(stats.exactArea, exactAtLeast) << name;
    EXPECT_LT(stats.exactArea, 1.0) << name;
    EXPECT_GT(imageDifference(area, tracer.render(16)).psnr, 40.0) << name;
  }
}

// Corners 1e30 away (huge-1e30's fan and wall) leave no digits for a
// clipped polygon near the eye: those triangles take the rays, so the frame
// is the point-sampled one (before, cells they crossed came out empty: 9.3
// dB); at 1e6 (huge-1e6) the polygons hold and agree with the rays.
TEST(ReferenceArea, HugeCoordinatesTakeTheRaysWhereTheyCannotBeClipped) {
  const int width = 64, height = 36;
  for (const auto& [name, exact] : {std::pair{"huge-1e30", false}, {"huge-1e6", true}}) {
    const Scene scene = makeBuiltinScene(name);
    const ReferenceTracer tracer(scene, scene.cameras.at(0), width, height);
    ReferenceTracer::AreaStats stats;
    const Image area = tracer.renderArea({.samplesPerAxis = 16}, &stats);
    const Image rays = tracer.render(16);
    if (!exact) {
      EXPECT_EQ(area.rgba, rays.rgba) << name;
      EXPECT_EQ(stats.exactArea, 0.0) << name;
    } else {
      EXPECT_GT(stats.exactArea, 0.5) << name;
      EXPECT_GT(imageDifference(area, rays).psnr, 45.0) << name;
    }
  }
}

}  // namespace quadra::ref
