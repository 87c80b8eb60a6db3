// The frame reference of DESIGN.md ("Accuracy"): a brute-force double-precision
// ray caster. Each pixel averages S x S stratified subsamples (a box filter);
// each subsample's primary ray takes its exact nearest triangle hit, whose
// barycentrics give the attributes; colour is baseColorFactor x level-0
// bilinear texture (at the coordinates after the material's texture
// transform) x COLOR_0 (unlit only), with OPAQUE / MASK handled per the
// spec and BLEND composited back to front over the nearest opaque hit.
//
// Which triangles a primary ray is tested against: by default those whose
// window-space bounds hold the ray's window point (a screen grid built once),
// which finds exactly the hits an exhaustive search finds, in the same order,
// and makes a frame cost per pixel what its few nearby triangles cost, not
// the whole scene (dense-mesh's 2M triangles: days exhaustively, 11 s so at
// 480x270 with 16 x 16 rays per pixel on two threads).
//
// BLEND caveat: the reference sorts every hit by distance, exactly; a
// rasterizer orders whole draws at best. They agree when blended surfaces do
// not interpenetrate and no blended draw overlaps itself on screen. Coplanar
// hits of one instance at one distance (a ray through a shared edge) count once.
//
// Skinned and morphed instances are traced at their posed positions (the
// scene's posed weights and joint matrices, applied in double).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "texture/image.h"
#include "texture/sampler_state.h"

namespace quadra::ref {

struct Ray {
  glm::dvec3 origin;     // view space
  glm::dvec3 direction;  // view space, z = -1 (so t is the view distance gained)
};

struct TracerHit {
  int instance = 0;
  int triangle = 0;         // index within the instance's mesh
  double viewDistance = 0;  // -z of the hit in view space
  glm::dvec3 bary{0.0};     // weights of the triangle's vertices, in index order
};

// Texel index → index inside [0, n) under the wrap mode, or -1 for the border colour.
std::int64_t wrapTexel(std::int64_t i, std::int64_t n, WrapMode mode);

// Level-0 bilinear lookup in double, per the texel convention (lookup at u reads
// texel-space x = u*W - 0.5; row 0 is v = 0) and the sampler's wrap modes.
glm::dvec4 sampleBilinear(const Image& image, const SamplerState& sampler, const glm::dvec2& uv);
// The lookup of a texture whose alpha is read (texture/texture.h TextureAlpha):
// the bilinear average of rgb times alpha (the border colour likewise), then
// divided by the averaged alpha; (0, 0, 0, 0) where that alpha is 0. `image`
// is straight (Texture::image()); premultiplying happens here, in double.
glm::dvec4 sampleBilinearPremultiplied(const Image& image, const SamplerState& sampler,
                                       const glm::dvec2& uv);

// KHR_texture_transform applied to texture coordinates, in double.
glm::dvec2 transformed(const TextureTransform& transform, glm::dvec2 uv);

// How shade(), nearestHit() and render() find the triangles a primary ray
// may hit. Both give bit-identical frames; Exhaustive is the plain loop the
// screen grid is tested against.
enum class TracerSearch : std::uint8_t { ScreenGrid, Exhaustive };

class ReferenceTracer {
 public:
  // The scene must outlive the tracer.
  ReferenceTracer(const Scene& scene, const Camera& camera, int width, int height,
                  TracerSearch search = TracerSearch::ScreenGrid);

  // The primary ray through a window-space point (pixels, y down).
  Ray primaryRay(const glm::dvec2& window) const;

  // Every hit of the ray that survives culling and lies between the near and
  // far planes, nearest first (ties in scene order). Tests every triangle.
  void allHits(const Ray& ray, std::vector<TracerHit>& out) const;
  std::optional<TracerHit> nearestHit(const glm::dvec2& window) const;

  // TEXCOORD_n interpolated at the hit; (0, 0) when the mesh has no such set.
  glm::dvec2 texCoord(const TracerHit& hit, int set) const;
  // TEXCOORD_n where `ray` meets the plane of the hit's triangle, inside the
  // triangle or not: the exact value at a neighbouring point, e.g. for finite
  // differences across a pixel or a pixel centre beside the triangle.
  glm::dvec2 planeTexCoord(const TracerHit& hit, const Ray& ray, int set) const;
  // baseColorFactor x texture x COLOR_0 at the hit, straight (not premultiplied).
  glm::dvec4 surfaceColour(const TracerHit& hit) const;

  // Premultiplied RGBA seen along the ray through a window point. scratch is
  // reused between calls to avoid allocation.
  glm::dvec4 shade(const glm::dvec2& window, std::vector<TracerHit>& scratch) const;

  // shade() with each hit's straight RGBA given by colour(hit, ray, its
  // surfaceColour()) in place of surfaceColour(), called only for hits that
  // count (MASK's test and the alpha kept or made 1 are as in shade(), on
  // surfaceColour's alpha): the lit reference's colours composited alike.
  // `surface` (when given) receives the instance of the first hit that
  // counts, -1 where there is none.
  using HitColour =
      std::function<glm::dvec4(const TracerHit& hit, const Ray& ray, const glm::dvec4& surface)>;
  glm::dvec4 shadeWith(const glm::dvec2& window, std::vector<TracerHit>& scratch,
                       const HitColour& colour, int* surface = nullptr) const;
  // The instance the ray through a window point sees first (as shadeWith's
  // `surface`), -1 for none.
  int visibleSurface(const glm::dvec2& window, std::vector<TracerHit>& scratch) const;

  // The whole frame: samplesPerAxis^2 stratified subsamples per pixel, box
  // filtered; premultiplied linear RGBA. Rows run in parallel.
  Image render(int samplesPerAxis) const;

  // The pixel integration every render uses: each pixel (x, y) the mean of
  // sample(x, y, k, scratch) over k in [0, samplesPerPixel), summed in k
  // order, so the frame is the same whatever the thread count. Rows run in
  // parallel (oneTBB); sample must be safe to call from several threads.
  using PixelSample =
      std::function<glm::dvec4(int x, int y, int k, std::vector<TracerHit>& scratch)>;
  Image integrate(int samplesPerPixel, const PixelSample& sample) const;
  // Sub-sample k (row-major) of pixel (x, y)'s samplesPerAxis^2 strata, at
  // `within` ([0, 1)^2, 0.5: the stratum's centre) inside its stratum.
  static glm::dvec2 stratumPoint(int x, int y, int k, int samplesPerAxis, const glm::dvec2& within);

  // Pixels whose 3x3 neighbourhood sees one surface (LIGHTING.md "Scoring"):
  // 1 where every sub-sample of the pixel and of its neighbours inside the
  // frame sees the same instance first (visibleSurface), or all see nothing.
  // A surface is an instance: an instance's silhouette over itself counts as
  // interior. Row-major, width x height.
  std::vector<std::uint8_t> interiorMask(int samplesPerAxis) const;
  // The same from each pixel's surface: an instance when all its sub-samples
  // saw that one, -1 when all saw none, kMixedSurface otherwise.
  static constexpr int kMixedSurface = -2;
  static std::vector<std::uint8_t> interiorOf(const std::vector<int>& pixelSurfaces, int width,
                                              int height);

  // The hit triangle's corners in view space, as posed, in index order.
  std::array<glm::dvec3, 3> viewCorners(const TracerHit& hit) const;
  // Whether the ray sees the hit triangle's front side (counter-clockwise,
  // as the instance's matrix turns it): what single-sided materials keep and
  // double-sided ones shade with their normals flipped when false.
  bool frontFacing(const TracerHit& hit, const Ray& ray) const;
  // The hit instance's material; nullptr: the glTF default material.
  const Material* materialOf(const TracerHit& hit) const;
  const Scene& scene() const { return scene_; }
  const Camera& camera() const { return camera_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // Each pixel the mean of its rays through the given points (offsets in
  // pixels from its centre, y down): what a sampler with exact hits and
  // point lookups at those positions would resolve to, e.g. the engine's
  // N-sample pattern (window/sample_pattern.h).
  Image renderPoints(const std::vector<glm::dvec2>& offsets) const;

  // The same box-filtered frame, integrated over each pixel's area where
  // that can be done exactly (reference_area.cpp), point-sampled elsewhere.
  // A cell (the pixel, or a quarter of it, down to maxDepth splits) whose
  // visible triangles do not overlap on screen is the sum of their exact
  // integrals over their parts of it: the triangle's screen polygon (near and
  // far planes clipped in view space, then clipped to the cell), on which the
  // level-0 bilinear texture is integrated along lines of constant depth
  // (where the perspective map is affine, BilinearIntegral) and across them by
  // Gauss-Legendre quadrature between every crossing of a texel line by the
  // polygon's edges. Triangles that cannot be integrated so (MASK or BLEND
  // materials, vertex colours, textures whose alpha is read, texture
  // coordinates beyond 2^40 texels, a corner beyond 1e12 in view space, a
  // texture whose tables would pass 512 MB) make their cells split, and the
  // cells of the last level that still hold them take the S x S grid's rays
  // there.
  struct AreaSettings {
    int samplesPerAxis = 16;  // S: the rays of a point-sampled pixel, per axis
    int gaussNodes = 3;       // per interval between breakpoints, 1-5
    int maxDepth = 2;         // splits of a pixel into quarters (while S allows)
  };
  struct AreaStats {
    std::int64_t exactCells = 0, sampledCells = 0;  // leaves of the pixels' cell trees
    double exactArea = 0.0;      // the frame's share integrated exactly (the rest took rays)
    std::int64_t intervals = 0;  // quadrature intervals integrated
  };
  Image renderArea(const AreaSettings& settings, AreaStats* stats = nullptr) const;

 private:
  struct PreparedInstance {
    const Mesh* mesh = nullptr;
    const Material* material = nullptr;  // nullptr: the glTF default material
    std::vector<glm::dvec3> viewPositions;
    glm::dvec3 boundsLo{0.0}, boundsHi{0.0};
    bool cullBack = true;   // single-sided: draw only front faces
    bool mirrored = false;  // negative determinant: front faces are clockwise
    // Corners exactly collinear in the mesh: no area, so no hit. Along the
    // line through them the inside test sees three weights of rounding noise
    // and would otherwise take any ray on that line, far beyond the corners.
    std::vector<bool> degenerate;
  };

  // One triangle of one instance; the grid's cells list them in scene order.
  struct TriangleRef {
    std::uint32_t instance = 0, triangle = 0;
  };
  // Triangles by the window-space cells their projected bounds overlap
  // (cell c's are entries[cellStart[c] .. cellStart[c + 1])), plus those
  // that have no projected bounds (a vertex at or behind the eye, or not
  // finite), which every ray is tested against.
  struct ScreenGrid {
    int cellSize = 1;  // pixels per cell side
    int columns = 0, rows = 0;
    std::vector<std::uint32_t> cellStart;
    std::vector<TriangleRef> entries;
    std::vector<TriangleRef> everywhere;
  };

  // Model-space positions of the instance's mesh, morphed and skinned in
  // double from the posed instance's weights and joint matrices (glTF 2.0
  // §3.7.2.2, §3.7.3: each influence's joint transform weighted, not the
  // engine's blended matrix); the stored positions when nothing deforms it.
  // Texture coordinates and colours are read as stored (morph targets that
  // move them are not modelled here).
  static std::vector<glm::dvec3> posedPositions(const Mesh& mesh, const Instance& instance);
  void buildScreenGrid();
  // allHits for the primary ray through a window point, by the grid where
  // the point lies on the screen.
  void hitsAt(const glm::dvec2& window, std::vector<TracerHit>& out) const;
  // Appends the triangle's hit, if the ray has one that counts.
  void testTriangle(std::size_t index, std::size_t triangle, const Ray& ray,
                    std::vector<TracerHit>& out) const;
  bool rayMayHit(const PreparedInstance& instance, const Ray& ray) const;
  // Barycentric weights, unnormalized, of where the ray meets the triangle's
  // plane: all of one sign inside the triangle; their sum is
  // dot(direction, e1 x e2).
  glm::dvec3 planeWeights(const PreparedInstance& instance, std::size_t triangle,
                          const Ray& ray) const;

  struct AreaFrame;  // reference_area.cpp

  const Scene& scene_;
  Camera camera_;
  int width_;
  int height_;
  double aspect_;
  std::vector<PreparedInstance> instances_;
  double znear_ = 0.0, zfar_ = 0.0;  // the range of view distances a hit must lie in
  TracerSearch search_;
  ScreenGrid grid_;
};

}  // namespace quadra::ref
