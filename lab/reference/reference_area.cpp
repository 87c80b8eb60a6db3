// ReferenceTracer::renderArea: the box-filtered frame integrated over each
// pixel's area where the visible surfaces allow it (the header says when),
// for frames whose point-sampled reference does not converge: a minified
// texture seen by N x N point samples converges only as fast as the samples
// resolve its texels, and at the horizon of builtin:checker-plane a pixel
// spans ~10^5 texel rows. Tests: tests/test_reference_area.cpp.
//
// Why it is exact: for a planar triangle the window-to-texel map is
// projective, S(X) = N(X) / D(X) with N and D affine in the window point X
// (the ray's barycentric weights are linear in its direction, or in its
// origin for an orthographic camera). On a line D = constant (a line of
// constant depth) the map is affine, so the texture's integral along a chord
// of the polygon is a segment integral of the bilinear reconstruction
// (BilinearIntegral, exact). Across those lines the chord integral L(p) is
// analytic between the positions where a polygon edge, which carries the
// chord's ends, crosses a texel line, or where a vertex starts or ends an
// edge; Gauss-Legendre between those breakpoints is exact to rounding when L is
// a low-degree polynomial there and converges fast otherwise (a chord that is
// not along a texel axis also kinks where it passes a texel corner; two node
// counts agreeing is the evidence, which quadra report samples prints).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <map>
#include <memory>

#include "core/error.h"
#include "lab/reference/bilinear_integral.h"
#include "lab/reference/reference_tracer.h"

namespace quadra::ref {

namespace {

// A convex polygon: a triangle clipped by six planes (near, far, the
// view's sides) and then by up to thirteen lines (a cell's four, another such
// polygon's nine) has at most 3 + 6 + 4 + 9 vertices.
struct Polygon {
  std::array<glm::dvec2, 24> v;
  int n = 0;
};

// Keeps a*x + b*y + c >= 0. Each crossing is interpolated from the vertex
// nearer the line, so a far vertex does not spoil the near one's precision.
Polygon clipped(const Polygon& in, double a, double b, double c) {
  Polygon out;
  for (int i = 0; i < in.n; ++i) {
    const glm::dvec2 p = in.v[std::size_t(i)], q = in.v[std::size_t((i + 1) % in.n)];
    const double dp = a * p.x + b * p.y + c, dq = a * q.x + b * q.y + c;
    if (dp >= 0.0) out.v[std::size_t(out.n++)] = p;
    if ((dp >= 0.0) != (dq >= 0.0)) {
      const glm::dvec2 crossing = std::fabs(dp) <= std::fabs(dq) ? p + (dp / (dp - dq)) * (q - p)
                                                                 : q + (dq / (dq - dp)) * (p - q);
      out.v[std::size_t(out.n++)] = crossing;
    }
  }
  return out;
}

double signedArea(const Polygon& p) {
  double twice = 0.0;
  for (int i = 0; i < p.n; ++i) {
    const glm::dvec2 a = p.v[std::size_t(i)], b = p.v[std::size_t((i + 1) % p.n)];
    twice += a.x * b.y - a.y * b.x;
  }
  return 0.5 * twice;
}

Polygon clippedToRect(Polygon p, const glm::dvec2& lo, const glm::dvec2& hi) {
  p = clipped(p, 1.0, 0.0, -lo.x);
  p = clipped(p, -1.0, 0.0, hi.x);
  p = clipped(p, 0.0, 1.0, -lo.y);
  return clipped(p, 0.0, -1.0, hi.y);
}

// The part of a inside the convex polygon b.
Polygon intersection(Polygon a, const Polygon& b) {
  const double orientation = signedArea(b) >= 0.0 ? 1.0 : -1.0;
  for (int i = 0; i < b.n && a.n > 0; ++i) {
    const glm::dvec2 p = b.v[std::size_t(i)], q = b.v[std::size_t((i + 1) % b.n)];
    // Inside: cross(q - p, X - p) has the polygon's orientation.
    const double ea = -(q.y - p.y) * orientation, eb = (q.x - p.x) * orientation;
    a = clipped(a, ea, eb, -(ea * p.x + eb * p.y));
  }
  return a;
}

// Gauss-Legendre nodes and weights on [-1, 1].
struct GaussRule {
  int n;
  double x[5], w[5];
};
constexpr GaussRule kGauss[5] = {
    {1, {0.0}, {2.0}},
    {2, {-0.5773502691896257, 0.5773502691896257}, {1.0, 1.0}},
    {3,
     {-0.7745966692414834, 0.0, 0.7745966692414834},
     {0.5555555555555556, 0.8888888888888888, 0.5555555555555556}},
    {4,
     {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526},
     {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538}},
    {5,
     {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640},
     {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
      0.2369268850561891}},
};

// Texel coordinates beyond this make a triangle point-sampled: a double then
// holds them to 2^-12 texel, and the tables' period reduction stays exact.
constexpr double kMaxTexelCoordinate = 1099511627776.0;  // 2^40
// View-space coordinates beyond this make a triangle point-sampled (below).
constexpr double kMaxViewCoordinate = 1e12;
// Quadrature intervals one cell may take before it is point-sampled instead
// (a pixel at the horizon of builtin:checker-plane takes ~2.4e5).
constexpr double kMaxBreakpoints = 1 << 22;
// Texture tables larger than this are not built; their triangles are
// point-sampled (a 1024^2 repeating texture takes 200 MB).
constexpr std::size_t kMaxTableBytes = std::size_t(512) << 20;

// An affine function of the window point.
struct Affine {
  double x = 0.0, y = 0.0, c = 0.0;
  double at(const glm::dvec2& p) const { return x * p.x + y * p.y + c; }
};

}  // namespace

// One frame's integration state: the texture tables, and per pixel the
// candidates the screen grid lists there.
struct ReferenceTracer::AreaFrame {
  const ReferenceTracer& tracer;
  AreaSettings settings;
  std::map<const Texture*, std::unique_ptr<BilinearIntegral>> tables;
  mutable std::atomic<std::int64_t> exactCells{0}, sampledCells{0}, intervals{0};
  // Exact area in cells of the deepest level.
  mutable std::atomic<std::int64_t> exactUnits{0};

  // A triangle as the pixel's cells see it.
  struct Candidate {
    Polygon screen;           // in window space, clipped to the near and far planes
    glm::dvec2 lo, hi;        // its bounds
    bool finite = false;      // every corner finite: the polygon can be clipped
    bool integrable = false;  // false: cells holding it are point-sampled
    Affine s, t, d;           // texel coordinates = (s, t) / d
    const BilinearIntegral* texture = nullptr;  // nullptr: the colour is constant
    glm::dvec4 factor{1.0};
  };

  AreaFrame(const ReferenceTracer& t, const AreaSettings& s) : tracer(t), settings(s) {
    for (const PreparedInstance& instance : tracer.instances_) {
      const Material* material = instance.material;
      if (!material || material->baseColorTexture < 0) continue;
      const Texture* texture = tracer.scene_.textures.at(material->baseColorTexture).get();
      if (tables.count(texture) || !materialIntegrable(instance)) continue;
      const Image& image = texture->image();
      if (BilinearIntegral::bytesFor(image.width, image.height, texture->sampler()) >
          kMaxTableBytes) {
        tables[texture] = nullptr;
        continue;
      }
      tables[texture] = std::make_unique<BilinearIntegral>(image, texture->sampler());
    }
  }

  // Colour = factor x texture, opaque: linear in the texture, so its area
  // integral is the texture's.
  static bool materialIntegrable(const PreparedInstance& instance) {
    if (!instance.mesh->colors.empty()) return false;
    const Material* material = instance.material;
    if (!material) return true;
    if (material->alphaMode != AlphaMode::Opaque) return false;
    return material->baseColorTexture < 0 || !textureAlphaOf(*material).premultiplied();
  }

  // The triangle's window-space polygon, clipped in view space to the range
  // of distances a hit must lie in; false when it has no area to offer (culled,
  // edge-on, degenerate, wholly outside that range).
  bool makeCandidate(std::size_t index, std::size_t triangle, Candidate& out) const {
    const PreparedInstance& instance = tracer.instances_[index];
    if (instance.degenerate[triangle]) return false;
    const std::uint32_t* corner = &instance.mesh->indices[triangle * 3];
    // Sutherland-Hodgman in view space against -z >= znear and -z <= zfar.
    // A corner beyond 1e12 (huge-1e30's fan and wall) leaves neither the
    // clipped polygon nor the affine weights (sums of products as large as
    // its square) digits for the pixels near the eye: such a triangle is
    // taken as present wherever the screen grid lists it, and point-sampled.
    for (int k = 0; k < 3; ++k)
      if (!glm::all(glm::lessThan(glm::abs(instance.viewPositions[corner[k]]),
                                  glm::dvec3(kMaxViewCoordinate)))) {
        out.finite = out.integrable = false;
        out.lo = glm::dvec2(-HUGE_VAL);
        out.hi = glm::dvec2(HUGE_VAL);
        return true;
      }
    std::array<glm::dvec3, 12> poly{}, next{};
    int n = 3;
    for (int k = 0; k < 3; ++k) poly[std::size_t(k)] = instance.viewPositions[corner[k]];
    // Keeps distance(v) >= 0, distance affine in v; each crossing from the
    // vertex nearer the plane, so a far vertex costs no precision.
    const auto clipBy = [&](const auto& distance) {
      int m = 0;
      for (int i = 0; i < n; ++i) {
        const glm::dvec3 p = poly[std::size_t(i)], q = poly[std::size_t((i + 1) % n)];
        const double dp = distance(p), dq = distance(q);
        if (dp >= 0.0) next[std::size_t(m++)] = p;
        if ((dp >= 0.0) != (dq >= 0.0))
          next[std::size_t(m++)] = std::fabs(dp) <= std::fabs(dq) ? p + (dp / (dp - dq)) * (q - p)
                                                                  : q + (dq / (dq - dp)) * (p - q);
      }
      n = m;
      poly = next;
    };
    clipBy([&](const glm::dvec3& v) { return -v.z - tracer.znear_; });
    if (std::isfinite(tracer.zfar_))
      clipBy([&](const glm::dvec3& v) { return tracer.zfar_ + v.z; });
    // And to the view beyond the window by a pixel, before projecting: a
    // corner projected 1e30 pixels away would leave the clipped polygon
    // nothing of its precision (builtin:huge-1e30).
    const bool orthographic = tracer.camera_.type == Camera::Type::Orthographic;
    const double f = 1.0 / std::tan(double(tracer.camera_.yfov) / 2.0);
    const double xLo = -1.0 - 2.0 / tracer.width_, xHi = 1.0 + 2.0 / tracer.width_;
    const double yLo = -1.0 - 2.0 / tracer.height_, yHi = 1.0 + 2.0 / tracer.height_;
    // NDC x = v.x * sx / depth, depth = -v.z (perspective) or 1.
    const double sx =
        orthographic ? 1.0 / (double(tracer.camera_.ymag) * tracer.aspect_) : f / tracer.aspect_;
    const double sy = orthographic ? 1.0 / double(tracer.camera_.ymag) : f;
    const auto depth = [&](const glm::dvec3& v) { return orthographic ? 1.0 : -v.z; };
    if (n >= 3) clipBy([&](const glm::dvec3& v) { return v.x * sx - xLo * depth(v); });
    if (n >= 3) clipBy([&](const glm::dvec3& v) { return xHi * depth(v) - v.x * sx; });
    if (n >= 3) clipBy([&](const glm::dvec3& v) { return v.y * sy - yLo * depth(v); });
    if (n >= 3) clipBy([&](const glm::dvec3& v) { return yHi * depth(v) - v.y * sy; });
    if (n < 3) return false;
    out.screen.n = n;
    out.lo = glm::dvec2(HUGE_VAL);
    out.hi = -out.lo;
    bool finite = true;
    for (int i = 0; i < n; ++i) {
      const glm::dvec3 v = poly[std::size_t(i)];
      const double xNdc = orthographic ? v.x / (double(tracer.camera_.ymag) * tracer.aspect_)
                                       : v.x / -v.z * f / tracer.aspect_;
      const double yNdc = orthographic ? v.y / double(tracer.camera_.ymag) : v.y / -v.z * f;
      const glm::dvec2 w((xNdc + 1.0) * 0.5 * tracer.width_, (1.0 - yNdc) * 0.5 * tracer.height_);
      finite = finite && std::isfinite(w.x) && std::isfinite(w.y);
      out.screen.v[std::size_t(i)] = w;
      out.lo = glm::min(out.lo, w);
      out.hi = glm::max(out.hi, w);
    }
    // Barycentric weights as affine functions of the window point, from
    // three rays (exact up to rounding: they are linear in the ray).
    const auto weightsAt = [&](const glm::dvec2& window) {
      return tracer.planeWeights(instance, triangle, tracer.primaryRay(window));
    };
    const glm::dvec2 origin(0.0), ex(tracer.width_, 0.0), ey(0.0, tracer.height_);
    const glm::dvec3 w0 = weightsAt(origin), wx = (weightsAt(ex) - w0) / double(tracer.width_),
                     wy = (weightsAt(ey) - w0) / double(tracer.height_);
    out.d = {wx.x + wx.y + wx.z, wy.x + wy.y + wy.z, w0.x + w0.y + w0.z};
    // Culling as testTriangle does it: the sign of the weights' sum where the
    // polygon is (constant there: the sum is zero only on the horizon).
    glm::dvec2 centroid(0.0);
    for (int i = 0; i < n; ++i) centroid += out.screen.v[std::size_t(i)];
    centroid /= double(n);
    const double sum = out.d.at(centroid);
    out.finite = finite;
    if (finite && sum == 0.0) return false;
    const bool front = (sum < 0.0) != instance.mirrored;
    if (finite && instance.cullBack && !front) return false;
    out.integrable = finite && materialIntegrable(instance);
    out.texture = nullptr;
    out.factor =
        instance.material ? glm::dvec4(instance.material->baseColorFactor) : glm::dvec4(1.0);
    if (!out.integrable || !instance.material || instance.material->baseColorTexture < 0)
      return true;
    const Material& material = *instance.material;
    const Texture* texture = tracer.scene_.textures.at(material.baseColorTexture).get();
    out.texture = tables.at(texture).get();
    if (!out.texture) {
      out.integrable = false;
      return true;
    }
    const Mesh& mesh = *instance.mesh;
    const std::vector<glm::vec2>& uvs = mesh.texcoords[material.baseColorTexCoord];
    const Image& image = texture->image();
    glm::dvec3 s(0.0), t(0.0);
    for (int k = 0; k < 3; ++k) {
      TracerHit at;
      at.instance = int(index);
      at.triangle = int(triangle);
      at.bary = glm::dvec3(0.0);
      at.bary[k] = 1.0;
      const glm::dvec2 uv = uvs.empty()
                                ? glm::dvec2(0.0)
                                : transformed(material.baseColorTransform,
                                              tracer.texCoord(at, material.baseColorTexCoord));
      s[k] = uv.x * image.width - 0.5;
      t[k] = uv.y * image.height - 0.5;
    }
    out.s = {glm::dot(wx, s), glm::dot(wy, s), glm::dot(w0, s)};
    out.t = {glm::dot(wx, t), glm::dot(wy, t), glm::dot(w0, t)};
    return true;
  }

  static glm::dvec2 texelAt(const Candidate& c, const glm::dvec2& window) {
    const double d = c.d.at(window);
    return {c.s.at(window) / d, c.t.at(window) / d};
  }

  // Breakpoints of the chord integral on the polygon (see the file comment),
  // as positions p along the depth gradient; false when there would be more
  // than the budget or the texel coordinates are too large.
  bool breakpoints(const Polygon& poly, const Candidate& c, const glm::dvec2& origin,
                   const glm::dvec2& pAxis, std::vector<double>& out) const {
    out.clear();
    double budget = kMaxBreakpoints;
    for (int i = 0; i < poly.n; ++i) {
      const glm::dvec2 a = poly.v[std::size_t(i)], b = poly.v[std::size_t((i + 1) % poly.n)];
      const double pa = glm::dot(a - origin, pAxis), pb = glm::dot(b - origin, pAxis);
      out.push_back(pa);
      if (pa == pb) continue;
      const double da = c.d.at(a), db = c.d.at(b);
      for (const Affine* numerator : {&c.s, &c.t}) {
        const double na = numerator->at(a), nb = numerator->at(b);
        const double va = na / da, vb = nb / db;
        if (!(std::fabs(va) <= kMaxTexelCoordinate && std::fabs(vb) <= kMaxTexelCoordinate))
          return false;
        const double kLo = std::floor(std::min(va, vb)) + 1.0,
                     kHi = std::ceil(std::max(va, vb)) - 1.0;
        budget -= std::max(0.0, kHi - kLo + 1.0);
        if (budget < 0.0) return false;
        // s = k where (na + l (nb - na)) = k (da + l (db - da)).
        for (double k = kLo; k <= kHi; k += 1.0) {
          const double l = (k * da - na) / ((nb - na) - k * (db - da));
          if (l > 0.0 && l < 1.0) out.push_back(pa + l * (pb - pa));
        }
      }
    }
    std::sort(out.begin(), out.end());
    // Crossings of one texel line by two edges at nearly one p (a chord
    // along a texel axis meets it at both ends at once) count once: a kink
    // within 1e-4 of an interval from its end moves a Gauss rule's result by
    // ~1e-8 of the interval's.
    std::size_t kept = 1;
    for (std::size_t i = 1; i < out.size(); ++i) {
      const double next = i + 1 < out.size() ? out[i + 1] : out[i];
      if (i + 1 < out.size() && out[i] - out[kept - 1] < 1e-4 * (next - out[kept - 1])) continue;
      out[kept++] = out[i];
    }
    out.resize(std::min(kept, out.size()));
    return true;
  }

  // The integral over the polygon of the candidate's texture (rgba), or
  // nothing when it cannot be integrated (then the cell is sampled).
  bool integrateTexture(const Polygon& poly, const Candidate& c, std::vector<double>& scratch,
                        glm::dvec4& result) const {
    const glm::dvec2 gradient(c.d.x, c.d.y);
    const double length = glm::length(gradient);
    const glm::dvec2 pAxis = length > 0.0 ? gradient / length : glm::dvec2(0.0, 1.0);
    const glm::dvec2 qAxis(-pAxis.y, pAxis.x);
    const glm::dvec2 origin = poly.v[0];
    if (!breakpoints(poly, c, origin, pAxis, scratch)) return false;
    std::array<double, 24> p{}, q{};
    for (int i = 0; i < poly.n; ++i) {
      p[std::size_t(i)] = glm::dot(poly.v[std::size_t(i)] - origin, pAxis);
      q[std::size_t(i)] = glm::dot(poly.v[std::size_t(i)] - origin, qAxis);
    }
    // The texture integrated along the polygon's chord at p (a line of
    // constant depth), in window units.
    const auto chord = [&](double at) {
      double q0 = HUGE_VAL, q1 = -HUGE_VAL;
      for (int i = 0; i < poly.n; ++i) {
        const std::size_t j = std::size_t((i + 1) % poly.n);
        const double pa = p[std::size_t(i)], pb = p[j];
        if (pa == pb || at < std::min(pa, pb) || at > std::max(pa, pb)) continue;
        const double qq = q[std::size_t(i)] + (at - pa) / (pb - pa) * (q[j] - q[std::size_t(i)]);
        q0 = std::min(q0, qq);
        q1 = std::max(q1, qq);
      }
      if (!(q1 > q0)) return glm::dvec4(0.0);
      const glm::dvec2 base = origin + at * pAxis;
      const glm::dvec2 a = texelAt(c, base + q0 * qAxis), b = texelAt(c, base + q1 * qAxis);
      return (q1 - q0) * c.texture->segmentMean(a, b);
    };
    const GaussRule& rule = kGauss[settings.gaussNodes - 1];
    glm::dvec4 sum(0.0);
    std::int64_t count = 0;
    for (std::size_t i = 0; i + 1 < scratch.size(); ++i) {
      const double a = scratch[i], b = scratch[i + 1];
      if (!(b > a)) continue;
      const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
      glm::dvec4 interval(0.0);
      for (int k = 0; k < rule.n; ++k) interval += rule.w[k] * chord(mid + half * rule.x[k]);
      sum += half * interval;
      ++count;
    }
    intervals.fetch_add(count, std::memory_order_relaxed);
    result = sum;
    return true;
  }

  // Premultiplied RGBA integrated over the cell [lo, lo + size]^2, or sampled.
  glm::dvec4 cell(const glm::dvec2& lo, double size, int depth,
                  const std::vector<const Candidate*>& parent, std::vector<double>& scratch,
                  std::vector<TracerHit>& hits) const {
    const glm::dvec2 hi = lo + size;
    std::vector<const Candidate*> present;
    std::vector<Polygon> parts;
    bool integrable = true;
    for (const Candidate* c : parent) {
      if (c->hi.x <= lo.x || c->lo.x >= hi.x || c->hi.y <= lo.y || c->lo.y >= hi.y) continue;
      if (!c->finite) {
        // Its polygon cannot be clipped reliably: count it as here.
        present.push_back(c);
        parts.push_back({});
        integrable = false;
        continue;
      }
      const Polygon part = clippedToRect(c->screen, lo, hi);
      if (part.n < 3 || std::fabs(signedArea(part)) <= 1e-12 * size * size) continue;
      integrable = integrable && c->integrable;
      present.push_back(c);
      parts.push_back(part);
    }
    // Overlapping polygons need depth order: not integrated here.
    for (std::size_t i = 0; integrable && i < parts.size(); ++i)
      for (std::size_t j = i + 1; integrable && j < parts.size(); ++j)
        if (std::fabs(signedArea(intersection(parts[i], parts[j]))) > 1e-9 * size * size)
          integrable = false;
    if (integrable) {
      glm::dvec4 sum(0.0);
      for (std::size_t i = 0; integrable && i < parts.size(); ++i) {
        const Candidate& c = *present[i];
        const double area = std::fabs(signedArea(parts[i]));
        glm::dvec4 texture(1.0);
        if (c.texture) {
          integrable = integrateTexture(parts[i], c, scratch, texture);
          texture /= area;
        }
        sum += glm::dvec4(glm::dvec3(c.factor) * glm::dvec3(texture), 1.0) * area;
      }
      if (integrable) {
        exactCells.fetch_add(1, std::memory_order_relaxed);
        exactUnits.fetch_add(std::int64_t(1) << (2 * (settings.maxDepth - depth)),
                             std::memory_order_relaxed);
        return sum;
      }
    }
    const int raysPerAxis = settings.samplesPerAxis >> depth;
    if (depth < settings.maxDepth && raysPerAxis >= 2 && raysPerAxis % 2 == 0) {
      glm::dvec4 sum(0.0);
      const double half = 0.5 * size;
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i)
          sum += cell(lo + glm::dvec2(i * half, j * half), half, depth + 1, present, scratch, hits);
      return sum;
    }
    // The S x S grid's rays that fall in this cell.
    sampledCells.fetch_add(1, std::memory_order_relaxed);
    glm::dvec4 sum(0.0);
    const double step = size / raysPerAxis;
    for (int j = 0; j < raysPerAxis; ++j)
      for (int i = 0; i < raysPerAxis; ++i)
        sum += tracer.shade(lo + glm::dvec2((i + 0.5) * step, (j + 0.5) * step), hits);
    return sum * (size * size / (double(raysPerAxis) * raysPerAxis));
  }

  glm::dvec4 pixel(int x, int y, std::vector<Candidate>& candidates, std::vector<double>& scratch,
                   std::vector<TracerHit>& hits) const {
    candidates.clear();
    const auto consider = [&](const TriangleRef& ref) {
      Candidate c;
      if (makeCandidate(ref.instance, ref.triangle, c)) candidates.push_back(c);
    };
    if (tracer.search_ == TracerSearch::ScreenGrid) {
      const ScreenGrid& grid = tracer.grid_;
      // Cells are whole powers of two pixels: the pixel lies in one.
      const int column = std::min(x / grid.cellSize, grid.columns - 1);
      const int row = std::min(y / grid.cellSize, grid.rows - 1);
      const std::size_t index = std::size_t(row * grid.columns + column);
      for (std::uint32_t e = grid.cellStart[index]; e < grid.cellStart[index + 1]; ++e)
        consider(grid.entries[e]);
      for (const TriangleRef& ref : grid.everywhere) consider(ref);
    } else {
      for (std::size_t i = 0; i < tracer.instances_.size(); ++i)
        for (std::size_t t = 0; t * 3 < tracer.instances_[i].mesh->indices.size(); ++t)
          consider({std::uint32_t(i), std::uint32_t(t)});
    }
    std::vector<const Candidate*> all;
    for (const Candidate& c : candidates) all.push_back(&c);
    return cell(glm::dvec2(x, y), 1.0, 0, all, scratch, hits);
  }
};

Image ReferenceTracer::renderArea(const AreaSettings& settings, AreaStats* stats) const {
  QUADRA_CHECK(settings.samplesPerAxis > 0);
  QUADRA_CHECK(settings.gaussNodes >= 1 && settings.gaussNodes <= 5);
  QUADRA_CHECK(settings.maxDepth >= 0);
  const AreaFrame frame(*this, settings);
  Image image(width_, height_);
  tbb::parallel_for(tbb::blocked_range<int>(0, height_, 1),
                    [&](const tbb::blocked_range<int>& rows) {
                      std::vector<AreaFrame::Candidate> candidates;
                      std::vector<double> scratch;
                      std::vector<TracerHit> hits;
                      for (int y = rows.begin(); y < rows.end(); ++y)
                        for (int x = 0; x < width_; ++x) {
                          const glm::dvec4 value = frame.pixel(x, y, candidates, scratch, hits);
                          float* out = image.texel(x, y);
                          for (int c = 0; c < 4; ++c) out[c] = float(value[c]);
                        }
                    });
  if (stats) {
    stats->exactCells = frame.exactCells.load();
    stats->sampledCells = frame.sampledCells.load();
    stats->intervals = frame.intervals.load();
    stats->exactArea =
        double(frame.exactUnits.load()) /
        (double(width_) * height_ * double(std::int64_t(1) << (2 * settings.maxDepth)));
  }
  return image;
}

}  // namespace quadra::ref
