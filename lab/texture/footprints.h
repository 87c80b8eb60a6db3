// A seeded set of lookup footprints for measuring texture filters against the
// ground truth: magnification (1/8 texel per pixel) to minification (512
// texels per pixel), anisotropy 1..64, every orientation (including sheared
// Jacobians), positions in the interior, near the texture's edges and across
// wrap seams. Stratified over the buckets so every bucket is covered.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "lab/texture/ground_truth.h"
#include "texture/texture_sampler.h"

namespace quadra {

// Scale = the footprint's major axis (the Jacobian's larger singular value) in
// level-0 texels per pixel; bucket b covers [1/8 * 4^b, 1/8 * 4^(b+1)), the last
// one closed at 512.
constexpr int kScaleBuckets = 6;
// Anisotropy = major / minor singular value; bucket b covers [2^b, 2^(b+1)),
// the last one closed at 64.
constexpr int kAnisoBuckets = 6;

std::string scaleBucketName(int bucket);  // e.g. "1/8-1/2", "128-512"
std::string anisoBucketName(int bucket);  // e.g. "1-2", "32-64"
double scaleBucketLow(int bucket);        // texels per pixel
double anisoBucketLow(int bucket);

struct FootprintSetOptions {
  std::size_t count = 4096;
  std::uint64_t seed = 1;
  int textureWidth = 256;  // footprints are drawn in texels, stored normalized
  int textureHeight = 256;
};

// Structure of arrays in float (what the engine's samplers read); the ground
// truth reads the same float values widened to double.
struct FootprintSet {
  std::vector<float> u, v, dudx, dvdx, dudy, dvdy;
  std::vector<float> scale, anisotropy;  // texels per pixel (major axis), major/minor
  std::vector<int> scaleBucket, anisoBucket;

  std::size_t size() const { return u.size(); }
  LookupBatch batch() const;
  Footprint footprint(std::size_t i) const;
  std::vector<Footprint> footprints() const;
  // The footprints at `indices`, in that order (e.g. one bucket of the set).
  FootprintSet subset(const std::vector<std::size_t>& indices) const;
};

// Deterministic for a given options value (own generator, no std distributions).
FootprintSet makeFootprintSet(const FootprintSetOptions& options);

// A footprint of the given major axis (texels per pixel), anisotropy, texel-space
// orientation of the major axis and screen-space rotation (radians), centred at
// (u, v). The screen rotation makes the Jacobian's columns differ from its
// singular vectors, i.e. sheared footprints.
Footprint makeFootprint(double u, double v, double majorTexels, double anisotropy,
                        double textureAngle, double screenAngle, int width, int height);

}  // namespace quadra
