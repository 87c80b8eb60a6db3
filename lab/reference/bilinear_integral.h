// Exact integrals of a texture's level-0 bilinear reconstruction along
// straight segments of texel space, for the area-integrating reference
// (ReferenceTracer::renderArea). The function integrated is the one
// sampleBilinear() point-samples: texel space x = u*W - 0.5, y = v*H - 0.5,
// texel (i, j) at the integer point (i, j), bilinear in between, wrapped per
// the sampler (border colour outside for ClampToBorder).
//
// How: along a texel row the reconstruction is a piecewise linear function
// r_j(x); a segment that stays between rows j and j+1 sees
// (1 - fy) r_j + fy r_{j+1} with fy affine in x, so its integral needs only
// the row's prefix integrals of r_j and of x * r_j, tabulated once per row
// (and per column, for segments steeper than 45 degrees). A segment costs one
// piece per row it crosses, not per texel: a chord across a minified ground
// plane that spans thousands of texels along a row is a few table lookups.
// Everything is double; the tables hold one period of a repeating line, and
// a segment is moved by whole periods before it is looked up, so the sums stay
// as small as one period's.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "texture/image.h"
#include "texture/sampler_state.h"

namespace quadra::ref {

class BilinearIntegral {
 public:
  BilinearIntegral(const Image& image, const SamplerState& sampler);

  // The mean of the reconstruction along the segment from a to b (texel
  // space), by length; the value at a when the two are equal.
  glm::dvec4 segmentMean(const glm::dvec2& a, const glm::dvec2& b) const;

  // The tables' size for an image, to refuse ones too large to tabulate.
  static std::size_t bytesFor(int width, int height, const SamplerState& sampler);

 private:
  // One row (or column) of the reconstruction as a function of the position
  // x along it: linear between the integer points, wrapped.
  struct Line {
    // Periodic lines (repeat, mirror, and the constant border line) hold one
    // period [0, period]; clamped ones [-1, n] with constants beyond.
    int period = 0;  // 0: not periodic
    double lo = 0.0, hi = 0.0;
    glm::dvec4 below{0.0}, above{0.0};  // the constant values beyond [lo, hi]
    std::vector<glm::dvec4> value;      // at lo, lo + 1, ..., hi
    std::vector<glm::dvec4> sum0;       // integral of r from lo to each point
    std::vector<glm::dvec4> sum1;       // integral of x * r from lo to each point
  };

  static Line makeLine(const std::vector<glm::dvec4>& texels, WrapMode mode,
                       const glm::dvec4& border);
  // Integral of (alpha + beta * (x - x0)) * r(x) over [x0, x1], x0 <= x1.
  static glm::dvec4 integrate(const Line& line, double x0, double x1, double alpha, double beta);
  // Integral of (1 - fy) r_a + fy r_b over [x0, x1], fy = fy0 + m (x - x0):
  // a segment between the lines a and b.
  static glm::dvec4 integratePair(const Line& a, const Line& b, double x0, double x1, double fy0,
                                  double m);
  // Antiderivatives of r and x * r, in one frame of reference per line.
  static void antiderivatives(const Line& line, double x, glm::dvec4& f0, glm::dvec4& f1);

  static glm::dvec4 lineValue(const Line& line, double x);
  const Line& lineAt(int axis, double index) const;
  glm::dvec4 pointValue(const glm::dvec2& at) const;

  WrapMode wrap_[2];
  int size_[2];
  std::vector<Line> lines_[2];  // [0]: rows (x varies), [1]: columns (y varies)
  Line border_;                 // a row or column wholly outside a bordered image
};

}  // namespace quadra::ref
