// The seeded footprint set: buckets, stratification and the Jacobian built
// from its singular value decomposition.
#include "lab/texture/footprints.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace quadra {

namespace {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64: a tiny generator whose output is the same on every platform and
// standard library (std distributions are not), so a seed names one set.
class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t state_;
};

std::string fraction(double x) {
  if (x >= 1.0) return std::to_string(int(std::lround(x)));
  return "1/" + std::to_string(int(std::lround(1.0 / x)));
}

}  // namespace

double scaleBucketLow(int bucket) {
  return 0.125 * std::pow(4.0, bucket);
}
double anisoBucketLow(int bucket) {
  return std::pow(2.0, bucket);
}

std::string scaleBucketName(int bucket) {
  return fraction(scaleBucketLow(bucket)) + "-" + fraction(scaleBucketLow(bucket + 1));
}
std::string anisoBucketName(int bucket) {
  return fraction(anisoBucketLow(bucket)) + "-" + fraction(anisoBucketLow(bucket + 1));
}

Footprint makeFootprint(double u, double v, double majorTexels, double anisotropy,
                        double textureAngle, double screenAngle, int width, int height) {
  // J = R(textureAngle) * diag(major, minor) * R(screenAngle)^T, in texels per pixel.
  const double minor = majorTexels / anisotropy;
  const double ct = std::cos(textureAngle), st = std::sin(textureAngle);
  const double cs = std::cos(screenAngle), ss = std::sin(screenAngle);
  const double a = majorTexels, b = minor;
  const double j00 = ct * a * cs + (-st) * b * (-ss);  // row u, column x
  const double j01 = ct * a * ss + (-st) * b * cs;     // row u, column y
  const double j10 = st * a * cs + ct * b * (-ss);     // row v, column x
  const double j11 = st * a * ss + ct * b * cs;        // row v, column y
  Footprint f;
  f.u = u;
  f.v = v;
  f.dudx = j00 / width;
  f.dudy = j01 / width;
  f.dvdx = j10 / height;
  f.dvdy = j11 / height;
  return f;
}

LookupBatch FootprintSet::batch() const {
  return {u.data(), v.data(), dudx.data(), dvdx.data(), dudy.data(), dvdy.data(), u.size()};
}

Footprint FootprintSet::footprint(std::size_t i) const {
  return {double(u[i]),    double(v[i]),    double(dudx[i]),
          double(dvdx[i]), double(dudy[i]), double(dvdy[i])};
}

std::vector<Footprint> FootprintSet::footprints() const {
  std::vector<Footprint> all(size());
  for (std::size_t i = 0; i < size(); ++i) all[i] = footprint(i);
  return all;
}

FootprintSet FootprintSet::subset(const std::vector<std::size_t>& indices) const {
  FootprintSet out;
  for (const std::size_t i : indices) {
    QUADRA_CHECK_OP(i, <, size());
    out.u.push_back(u[i]);
    out.v.push_back(v[i]);
    out.dudx.push_back(dudx[i]);
    out.dvdx.push_back(dvdx[i]);
    out.dudy.push_back(dudy[i]);
    out.dvdy.push_back(dvdy[i]);
    out.scale.push_back(scale[i]);
    out.anisotropy.push_back(anisotropy[i]);
    out.scaleBucket.push_back(scaleBucket[i]);
    out.anisoBucket.push_back(anisoBucket[i]);
  }
  return out;
}

FootprintSet makeFootprintSet(const FootprintSetOptions& options) {
  QUADRA_CHECK(options.textureWidth > 0 && options.textureHeight > 0);
  SeededRandom random(options.seed);
  FootprintSet set;
  const std::size_t n = options.count;
  for (auto* column :
       {&set.u, &set.v, &set.dudx, &set.dvdx, &set.dudy, &set.dvdy, &set.scale, &set.anisotropy})
    column->reserve(n);
  const double w = options.textureWidth, h = options.textureHeight;
  for (std::size_t i = 0; i < n; ++i) {
    // Stratified: footprint i lands in scale bucket i mod 6 and anisotropy
    // bucket (i / 6) mod 6, log-uniform inside the bucket.
    const int scaleBucket = int(i % kScaleBuckets);
    const int anisoBucket = int((i / kScaleBuckets) % kAnisoBuckets);
    const double major = scaleBucketLow(scaleBucket) * std::pow(4.0, random.uniform());
    const double aniso = anisoBucketLow(anisoBucket) * std::pow(2.0, random.uniform());
    const double textureAngle = random.uniform(0.0, kPi);
    const double screenAngle = random.uniform(0.0, 2.0 * kPi);
    double u = random.uniform(), v = random.uniform();
    // Positions: 40% interior, 40% on or across an edge / wrap seam (within
    // the footprint's reach of u or v = 0 or 1), 20% shifted by whole periods.
    const double place = random.uniform();
    if (place < 0.4) {
      const double reach = random.uniform(-1.0, 1.0) * (0.5 * major + 2.0);
      const double edge = random.uniform() < 0.5 ? 0.0 : 1.0;
      if (random.uniform() < 0.5)
        u = edge + reach / w;
      else
        v = edge + reach / h;
    } else if (place < 0.6) {
      u += std::floor(random.uniform(-3.0, 4.0));
      v += std::floor(random.uniform(-3.0, 4.0));
    }
    const Footprint f = makeFootprint(u, v, major, aniso, textureAngle, screenAngle,
                                      options.textureWidth, options.textureHeight);
    set.u.push_back(float(f.u));
    set.v.push_back(float(f.v));
    set.dudx.push_back(float(f.dudx));
    set.dvdx.push_back(float(f.dvdx));
    set.dudy.push_back(float(f.dudy));
    set.dvdy.push_back(float(f.dvdy));
    set.scale.push_back(float(major));
    set.anisotropy.push_back(float(aniso));
    set.scaleBucket.push_back(scaleBucket);
    set.anisoBucket.push_back(anisoBucket);
  }
  return set;
}

}  // namespace quadra
