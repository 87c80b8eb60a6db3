// The peer's image-based lighting: an equirectangular panorama prepared in
// OpenGL the way the Khronos glTF Sample Viewer prepares its environment
// (split sum, Karis 2013): the panorama rendered into a cube map, the cube
// prefiltered by GGX importance sampling into one mip level per roughness, a
// Lambertian (cosine-weighted) irradiance cube, and the 2-D GGX table of
// (n.v, roughness) -> (scale, bias) of f0. Each pass draws into the cube
// faces (or the table) with a fragment shader of its own; the lit shading of
// gl_scene_renderer.cpp then reads one prefiltered lookup, one irradiance
// lookup and one table lookup per pixel. docs/lighting.md "The llvmpipe
// peer" has the parameters and their source.
#pragma once

#include <GL/gl.h>

#include "shading/environment_image.h"

namespace quadra {

class GlEnvironment {
 public:
  // The Sample Viewer's parameters (its ibl_sampler.js).
  static constexpr int kCubeSize = 256;            // every cube's level 0 face
  static constexpr int kSpecularLevels = 5;        // log2(256) + 1 - 4 (lowest mip 4)
  static constexpr int kSpecularSamples = 1024;    // GGX samples per texel
  static constexpr int kLambertianSamples = 2048;  // cosine samples per texel
  static constexpr int kLutSize = 1024;            // the table's side
  static constexpr int kLutSamples = 512;          // GGX samples per table entry

  // Runs every pass (and waits for them: glFinish), leaving depth test,
  // culling and blending off and the default framebuffer bound. cubeSize (a
  // power of two, 16 to 1024) and lutSize (16 to 4096) may be smaller than
  // the Sample Viewer's for quick tests: the cubes keep kSpecularLevels
  // levels, so the LOD per roughness stays the Sample Viewer's, and the
  // sample counts stay. Throws Error on any OpenGL failure or a panorama
  // larger than GL allows.
  explicit GlEnvironment(const EnvironmentImage& panorama, int cubeSize = kCubeSize,
                         int lutSize = kLutSize);
  ~GlEnvironment();
  GlEnvironment(const GlEnvironment&) = delete;
  GlEnvironment& operator=(const GlEnvironment&) = delete;

  // Level l holds roughness l / (kSpecularLevels - 1), so a lookup's LOD is
  // roughness x (kSpecularLevels - 1).
  GLuint specularCube() const { return specular_; }
  GLuint irradianceCube() const { return irradiance_; }
  GLuint lut() const { return lut_; }

 private:
  GLuint specular_ = 0, irradiance_ = 0, lut_ = 0;
};

}  // namespace quadra
