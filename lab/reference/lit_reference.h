// The lit ideal of ../shared/LIGHTING.md ("The ideal image"), in double
// precision: the reference tracer's exact hits, sub-pixel integration and
// level-0 bilinear texture reads (reference_tracer.h), shaded with the glTF
// 2.0 metallic-roughness BRDF (the specification's Appendix B, with
// KHR_materials_ior, _specular, _emissive_strength and _unlit) under the
// equirectangular environment and KHR_lights_punctual lights, no visibility.
//
// The environment term, the integral over the sphere of Lenv(w) f(v, w)
// max(0, n.w), is a Monte Carlo estimate that converges: per hit, samples
// drawn from the environment's luminance (a piecewise-constant density over
// the panorama's texel cells) and from the BRDF (GGX visible normals and the
// cosine lobe, mixed by their weights), combined by the balance heuristic of
// multiple importance sampling; roughness 0 is the mirror direction exactly
// (a delta, added analytically). Points are Owen-scrambled Sobol (0, 2)
// sequences seeded per pixel from LitSettings::seed, a pixel's sub-samples
// taking consecutive blocks of one sequence, so a frame is deterministic and
// the same on any number of threads. Its noise floor is measured by two
// seeds (tests/test_lit_reference.cpp).
//
// Written apart from the engine's shading (engine/shading) so that it can
// measure it: only the environment's data type is shared.
//
// Textures are read as Scene holds them: linear float, the loader having
// decoded the sRGB ones (base colour, emissive, specular colour).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "lab/reference/reference_tracer.h"
#include "scene/scene.h"
#include "shading/environment_image.h"
#include "texture/image.h"

namespace quadra::ref {

// LIGHTING.md "The environment": the panorama's bilinear radiance (u wraps,
// v clamps), turned by --env-rotation and scaled by --env-intensity, and a
// density proportional to its luminance for importance sampling.
class ReferenceEnvironment {
 public:
  // The image must outlive this object; it must have at least one texel.
  explicit ReferenceEnvironment(const EnvironmentImage& image, double rotationDegrees = 0.0,
                                double intensity = 1.0);

  // Radiance arriving from world direction d (any length but 0).
  glm::dvec3 radiance(const glm::dvec3& direction) const;
  // The panorama coordinates (u, v) the direction reads (after the rotation).
  glm::dvec2 panoramaCoordinates(const glm::dvec3& direction) const;
  // The unit world direction that reads panorama coordinates (u, v).
  glm::dvec3 directionOf(const glm::dvec2& uv) const;

  // A unit world direction for a point of [0, 1)^2, drawn with density
  // pdf(direction) per steradian: a texel cell by its share of the luminance
  // (the exact mean of the bilinear radiance over the cell, times its solid
  // angle), then uniformly in solid angle within the cell.
  // uv (when given) receives the sample's panorama coordinates.
  glm::dvec3 sample(const glm::dvec2& point, double& pdf, glm::dvec2* uv = nullptr) const;
  double pdf(const glm::dvec3& direction) const;
  // The same of panorama coordinates (panoramaCoordinates(direction)), for
  // a caller that needs both without computing them twice.
  glm::dvec3 radianceAt(const glm::dvec2& uv) const;
  double pdfAt(const glm::dvec2& uv) const;
  // No radiance anywhere: the environment term is 0 and is not sampled.
  bool black() const { return total_ <= 0.0; }

 private:
  int cellOf(const glm::dvec2& uv, int& row) const;

  const EnvironmentImage& image_;
  double cosRotation_, sinRotation_, intensity_;
  double total_ = 0.0;
  std::vector<double> rowCdf_;                            // height + 1 entries, 0 .. 1
  std::vector<double> cellCdf_;                           // per row, width + 1 entries, 0 .. 1
  std::vector<double> rowProbability_, cellProbability_;  // cellProbability_ within its row
  std::vector<double> cosBoundary_;     // cos(pi j / height), j = 0 .. height: the rows' edges
  std::vector<double> cellSolidAngle_;  // per row
};

// The BRDF's inputs at a point (LIGHTING.md "The material").
struct BrdfParameters {
  glm::dvec3 baseColor{1.0};
  double metallic = 1.0;
  double alpha = 1.0;  // roughness^2
  // The dielectric's Fresnel: f0 = min(((ior - 1) / (ior + 1))^2 x specular
  // colour, 1) x specular, f90 = specular (KHR_materials_ior and _specular;
  // 0.04 and 1 without them).
  glm::dvec3 dielectricF0{0.04};
  double dielectricF90 = 1.0;
};

// The dielectric f0 and f90 of a material's factors with the texture values
// at a point (specularColor: factor x texture rgb; specular: factor x texture a).
void dielectricFresnel(double ior, const glm::dvec3& specularColor, double specular, glm::dvec3& f0,
                       double& f90);

// f(v, l) of Appendix B: mix(f_dielectric, f_metal, metallic) with
// f_metal = F_Schlick(baseColor, 1, h.v) D V, f_dielectric = F D V + (1 -
// max(F)) baseColor / pi, F = F_Schlick(f0, f90, h.v), D GGX, V the
// height-correlated Smith visibility, n.v clamped at 0. n, v, l unit. At
// alpha 0 the specular lobe is a delta and contributes 0 here (see
// mirrorReflectance).
glm::dvec3 evaluateBrdf(const BrdfParameters& m, const glm::dvec3& n, const glm::dvec3& v,
                        const glm::dvec3& l);
// At alpha 0: the factor of Lenv(reflect(-v, n)) the specular delta gives,
// mix(F(f0, f90, n.v), F(baseColor, 1, n.v), metallic); 0 where n.v <= 0.
glm::dvec3 mirrorReflectance(const BrdfParameters& m, const glm::dvec3& n, const glm::dvec3& v);

// Sample counts of the environment term, per sub-pixel hit.
struct EnvironmentSampling {
  int environmentSamples = 16;  // drawn from the environment's luminance
  int brdfSamples = 16;         // drawn from the BRDF (GGX visible normals / cosine)
};

// The environment integral at one point, estimated from block `block` of the
// sequences scrambled by `scramble` (indices block x count .. + count - 1).
glm::dvec3 environmentIntegral(const ReferenceEnvironment& environment, const BrdfParameters& m,
                               const glm::dvec3& n, const glm::dvec3& v,
                               const EnvironmentSampling& sampling, std::uint64_t scramble,
                               std::uint32_t block = 0);

enum class LitBackground : std::uint8_t { Environment, Colour };

// The defaults: 256 rays a pixel, 16 + 16 environment samples a ray (8192 of
// each a pixel); two seeds agree to 60 dB over all pixels, 70 dB over
// interior ones, on metalRoughSpheresScene(3, 3) at 192x144 under
// sunnySkyEnvironment (tests/test_lit_reference.cpp measures a cheaper set).
struct LitSettings {
  int samplesPerAxis = 16;  // S: S x S sub-pixel rays (a scrambled Sobol net over the pixel)
  EnvironmentSampling sampling{16, 16};
  std::uint32_t seed = 1;
  bool lights = true;  // the scene's KHR_lights_punctual lights
  LitBackground background = LitBackground::Environment;
  glm::dvec4 backgroundColour{0.0};  // premultiplied; (0, 0, 0, 0): transparent
};

struct LitFrame {
  Image image;  // premultiplied linear radiance, as the engine's frames
  // Pixels whose 3x3 neighbourhood sees one surface (ReferenceTracer::interiorOf),
  // from the frame's own sub-samples.
  std::vector<std::uint8_t> interior;
};

class LitReference {
 public:
  // The scene (and environment, nullptr: black) must outlive this object.
  LitReference(const Scene& scene, const Camera& camera, int width, int height,
               const ReferenceEnvironment* environment);

  LitFrame render(const LitSettings& settings) const;

  // The radiance leaving the hit toward the ray's origin (LIGHTING.md "The
  // light"; the unlit colour for KHR_materials_unlit). Where LIGHTING.md is
  // silent: a shading normal with n.v below 1e-4 is turned toward v, in the
  // plane of n and v, to n.v = 1e-4; without TANGENT a normal map is not
  // read; B = w N x T in world space (a mirroring instance matrix does not
  // flip it, as the Sample Viewer does). The environment term is estimated
  // from block `block` of the sequences of `scramble`; alpha is the surface's.
  glm::dvec4 hitRadiance(const TracerHit& hit, const Ray& ray, const glm::dvec4& surface,
                         const LitSettings& settings, std::uint64_t scramble,
                         std::uint32_t block) const;

  const ReferenceTracer& tracer() const { return tracer_; }

 private:
  struct PreparedInstance {
    glm::dmat3 normalMatrix{1.0}, tangentMatrix{1.0};  // model to world
    // Posed (morphed, skinned) model-space normals and tangents where the
    // instance deforms; empty: the mesh's own.
    std::vector<glm::dvec3> normals;
    std::vector<glm::dvec4> tangents;
  };
  struct PreparedLight {
    Light::Type type = Light::Type::Point;
    glm::dvec3 position{0.0}, direction{0.0, 0.0, -1.0};  // world; direction: where it shines
    glm::dvec3 intensity{0.0};                            // colour x intensity
    double range = 0.0, angleScale = 0.0, angleOffset = 0.0;
  };

  glm::dvec3 worldDirection(const Ray& ray) const;
  glm::dvec3 punctualLight(const BrdfParameters& m, const glm::dvec3& position, const glm::dvec3& n,
                           const glm::dvec3& v) const;

  const Scene& scene_;
  ReferenceTracer tracer_;
  const ReferenceEnvironment* environment_;
  glm::dmat4 cameraToWorld_{1.0};
  std::vector<PreparedInstance> instances_;
  std::vector<PreparedLight> lights_;
};

}  // namespace quadra::ref
