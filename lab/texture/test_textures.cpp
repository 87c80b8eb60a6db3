// Generated test textures for the texture error report and tests.
#include "lab/texture/test_textures.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace quadra {

namespace {

// A stateless hash of (seed, lattice point, channel) → [0, 1): no generator
// state to thread through, and the same value on every platform.
double latticeValue(std::uint64_t seed, std::uint64_t x, std::uint64_t y, std::uint64_t channel) {
  std::uint64_t z = seed ^ (x * 0x9E3779B97F4A7C15ull) ^ (y * 0xC2B2AE3D27D4EB4Full) ^
                    (channel * 0x165667B19E3779F9ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return double(z >> 11) * 0x1p-53;
}

void checkSize(int width, int height) {
  QUADRA_CHECK(width > 0 && height > 0);
}

}  // namespace

Image makeCheckerTexture(int width, int height, int cellTexels) {
  checkSize(width, height);
  QUADRA_CHECK(cellTexels > 0);
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float value = float(((x / cellTexels) + (y / cellTexels) + 1) % 2);
      float* t = image.texel(x, y);
      t[0] = t[1] = t[2] = value;
      t[3] = 1.0f;
    }
  return image;
}

Image makeZonePlateTexture(int width, int height) {
  checkSize(width, height);
  Image image(width, height);
  const double size = std::max(width, height);
  const double pi = 3.14159265358979323846;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double dx = x + 0.5 - 0.5 * width, dy = y + 0.5 - 0.5 * height;
      const float value = float(0.5 + 0.5 * std::cos(pi * (dx * dx + dy * dy) / size));
      float* t = image.texel(x, y);
      t[0] = t[1] = t[2] = value;
      t[3] = 1.0f;
    }
  return image;
}

Image makeValueNoiseTexture(int width, int height, std::uint64_t seed) {
  checkSize(width, height);
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* t = image.texel(x, y);
      for (int c = 0; c < 3; ++c) t[c] = float(latticeValue(seed, x, y, c));
      t[3] = 1.0f;
    }
  return image;
}

Image makeSmoothNoiseTexture(int width, int height, std::uint64_t seed) {
  checkSize(width, height);
  Image image(width, height);
  std::vector<double> sum(std::size_t(width) * height * 3, 0.0);
  double totalAmplitude = 0.0;
  double amplitude = 1.0;
  for (int period = std::max(8, std::max(width, height) / 4); period >= 8; period /= 2) {
    // Lattice cells per side, rounded so the noise tiles with the texture.
    const int cellsX = std::max(1, (width + period / 2) / period);
    const int cellsY = std::max(1, (height + period / 2) / period);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const double gx = (x + 0.5) * cellsX / width, gy = (y + 0.5) * cellsY / height;
        const int ix = int(std::floor(gx)), iy = int(std::floor(gy));
        const auto smooth = [](double t) { return t * t * (3.0 - 2.0 * t); };
        const double sx = smooth(gx - ix), sy = smooth(gy - iy);
        for (int c = 0; c < 3; ++c) {
          const auto at = [&](int lx, int ly) {
            return latticeValue(seed + std::uint64_t(period), std::uint64_t(lx % cellsX),
                                std::uint64_t(ly % cellsY), std::uint64_t(c));
          };
          const double top = at(ix, iy) + (at(ix + 1, iy) - at(ix, iy)) * sx;
          const double bottom = at(ix, iy + 1) + (at(ix + 1, iy + 1) - at(ix, iy + 1)) * sx;
          sum[(std::size_t(y) * width + x) * 3 + c] += amplitude * (top + (bottom - top) * sy);
        }
      }
    totalAmplitude += amplitude;
    amplitude *= 0.5;
  }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* t = image.texel(x, y);
      for (int c = 0; c < 3; ++c)
        t[c] = float(sum[(std::size_t(y) * width + x) * 3 + c] / totalAmplitude);
      t[3] = 1.0f;
    }
  return image;
}

}  // namespace quadra
