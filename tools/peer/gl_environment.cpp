// The Sample Viewer's environment preparation, pass by pass, in OpenGL on
// llvmpipe (see gl_environment.h). The method is the Sample Viewer's
// (ibl_sampler.js, ibl_filtering.frag: Hammersley points, GGX and cosine
// importance sampling, each sample read from the source cube's mip level
// that covers its share of the sphere, Křivánek & Colbert 2008); the GLSL is
// the peer's own.
#define GL_GLEXT_PROTOTYPES 1
#include "gl_environment.h"

#include <GL/glext.h>

#include <string>

#include "core/error.h"
#include "gl_program.h"

namespace quadra {

namespace {

// One triangle over the whole viewport, from gl_VertexID alone.
constexpr const char* kFullscreenVertex = R"(
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

// The direction of the cube texel under the fragment: OpenGL's cube map
// table (the 4.5 specification's 8.13) solved for the direction, with (s, t)
// from the window position (row 0 of a face is t near 0).
constexpr const char* kCubeDirection = R"(
const float kPi = 3.14159265358979;
uniform int face;
uniform float faceSize;
vec3 cubeDirection() {
  vec2 st = gl_FragCoord.xy / faceSize * 2.0 - 1.0;
  float s = st.x, t = st.y;
  vec3 d;
  if (face == 0) d = vec3(1.0, -t, -s);
  else if (face == 1) d = vec3(-1.0, -t, s);
  else if (face == 2) d = vec3(s, 1.0, t);
  else if (face == 3) d = vec3(s, -1.0, -t);
  else if (face == 4) d = vec3(s, -t, 1.0);
  else d = vec3(-s, -t, -1.0);
  return normalize(d);
}
// Hammersley point i of n: (i / n, the bit-reversed i as a fraction).
vec2 hammersley(int i, int n) {
  return vec2(float(i) / float(n), float(bitfieldReverse(uint(i))) * 2.3283064365386963e-10);
}
// cos(theta) of a GGX half vector for the point's second coordinate
// (Walter et al. 2007, eq. 35 and 36, with alpha2 = alpha^2).
float ggxCosTheta(float x, float alpha2) {
  return sqrt((1.0 - x) / (1.0 + (alpha2 - 1.0) * x));
}
)";

// LIGHTING.md's mapping: u = 0.5 + atan2(x, -z) / 2 pi, v = acos(y) / pi,
// bilinear, wrapping in u and clamping in v (the sampler's state).
constexpr const char* kPanoramaToCube = R"(
uniform sampler2D panorama;
layout(location = 0) out vec4 color;
void main() {
  vec3 d = cubeDirection();
  vec2 uv = vec2(0.5 + atan(d.x, -d.z) / (2.0 * kPi), acos(clamp(d.y, -1.0, 1.0)) / kPi);
  color = vec4(textureLod(panorama, uv, 0.0).rgb, 1.0);
}
)";

// The prefiltered radiance around each texel's direction n (taken as the
// view and the normal, v = n): GGX-distributed half vectors, each reflected
// sample weighted by n.l; or, with `lambertian`, cosine-distributed samples
// averaged (the irradiance / pi). Each sample reads the source's mip level
// whose texels are its share of the sphere, 1 / (count pdf); roughness 0
// reads level 0 (every sample would be n itself, so one lookup is the same).
constexpr const char* kFilter = R"(
uniform samplerCube source;
uniform float sourceSize;
uniform float roughness;
uniform int sampleCount;
uniform bool lambertian;
layout(location = 0) out vec4 color;
void main() {
  vec3 n = cubeDirection();
  if (!lambertian && roughness == 0.0) {
    color = vec4(textureLod(source, n, 0.0).rgb, 1.0);
    return;
  }
  vec3 up = abs(n.y) < 0.9999999 ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, sign(n.y));
  vec3 t = normalize(cross(up, n));
  vec3 b = cross(n, t);
  float alpha = roughness * roughness;
  float alpha2 = alpha * alpha;
  // lod = log4(sample's solid angle / texel's) = 0.5 log2(6 size^2 / (count pdf)).
  float texelsPerUnitPdf = 6.0 * sourceSize * sourceSize / float(sampleCount);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (int i = 0; i < sampleCount; ++i) {
    vec2 x = hammersley(i, sampleCount);
    float cosTheta, pdf;
    if (lambertian) {
      cosTheta = sqrt(1.0 - x.y);
      pdf = cosTheta / kPi;
    } else {
      cosTheta = ggxCosTheta(x.y, alpha2);
      float d = cosTheta * cosTheta * (alpha2 - 1.0) + 1.0;
      pdf = alpha2 / (kPi * d * d) / 4.0;  // D(h) (n.h) / (4 v.h), v = n
    }
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    float phi = 2.0 * kPi * x.x;
    vec3 h = normalize(t * (sinTheta * cos(phi)) + b * (sinTheta * sin(phi)) + n * cosTheta);
    float lod = 0.5 * log2(texelsPerUnitPdf / pdf);
    if (lambertian) {
      sum += textureLod(source, h, lod).rgb;
      weight += 1.0;
    } else {
      vec3 l = 2.0 * dot(n, h) * h - n;
      float nl = dot(n, l);
      if (nl > 0.0) {
        sum += textureLod(source, l, lod).rgb * nl;
        weight += nl;
      }
    }
  }
  color = vec4(sum / max(weight, 1e-30), 1.0);
}
)";

// The split sum's second factor (Karis 2013): for n.v and roughness, the
// integral of the GGX BRDF x n.l under uniform white light split as
// f0 x scale + bias, scale weighting (1 - Fc) and bias Fc, Fc = (1 - v.h)^5;
// GGX samples, each weighted by V (height-correlated Smith) x 4 (v.h) (n.l) / (n.h).
constexpr const char* kLut = R"(
uniform float lutSize;
uniform int sampleCount;
layout(location = 0) out vec4 color;
void main() {
  vec2 st = gl_FragCoord.xy / lutSize;
  float nv = st.x, alpha = st.y * st.y, alpha2 = alpha * alpha;
  vec3 v = vec3(sqrt(1.0 - nv * nv), 0.0, nv);
  float scale = 0.0, bias = 0.0;
  for (int i = 0; i < sampleCount; ++i) {
    vec2 x = hammersley(i, sampleCount);
    float cosTheta = ggxCosTheta(x.y, alpha2);
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    float phi = 2.0 * kPi * x.x;
    vec3 h = vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
    float vh = dot(v, h);
    vec3 l = 2.0 * vh * h - v;
    float nl = clamp(l.z, 0.0, 1.0), nh = clamp(h.z, 0.0, 1.0);
    vh = clamp(vh, 0.0, 1.0);
    if (nl > 0.0) {
      float vis = 0.5 / (nl * sqrt(nv * nv * (1.0 - alpha2) + alpha2) +
                         nv * sqrt(nl * nl * (1.0 - alpha2) + alpha2));
      float g = vis * vh * nl / nh;
      float fc = pow(1.0 - vh, 5.0);
      scale += (1.0 - fc) * g;
      bias += fc * g;
    }
  }
  color = vec4(4.0 * scale / float(sampleCount), 4.0 * bias / float(sampleCount), 0.0, 1.0);
}
)";

constexpr const char* kPrelude = "#version 450 core\n";

GLuint makeCube(int levels, int size) {
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_CUBE_MAP, id);
  glTexStorage2D(GL_TEXTURE_CUBE_MAP, levels, GL_RGBA32F, size, size);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER,
                  levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_CUBE_MAP, axis, GL_CLAMP_TO_EDGE);
  return id;
}

// Draws `program` into the six faces of `cube`'s `level` (size >> level).
void drawFaces(GLuint program, GLuint cube, int level, int size) {
  const int n = size >> level;
  glUseProgram(program);
  glUniform1f(glGetUniformLocation(program, "faceSize"), float(n));
  glViewport(0, 0, n, n);
  for (int face = 0; face < 6; ++face) {
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                           GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), cube, level);
    glUniform1i(glGetUniformLocation(program, "face"), face);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
}

}  // namespace

GlEnvironment::GlEnvironment(const EnvironmentImage& image, int cubeSize, int lutSize) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (image.width > maxSize || image.height > maxSize)
    throw Error(image.name + ": " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + " is larger than llvmpipe's textures (" +
                std::to_string(maxSize) + " texels a side)");
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  // WebGL 2, the Sample Viewer's API, always filters across cube faces.
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  GLuint vertexArray = 0, framebuffer = 0;
  glGenVertexArrays(1, &vertexArray);
  glBindVertexArray(vertexArray);
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);

  GLuint panorama = 0;
  glGenTextures(1, &panorama);
  glBindTexture(GL_TEXTURE_2D, panorama);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, image.width, image.height, 0, GL_RGB, GL_FLOAT,
               image.rgb.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  throwOnGlError("uploading the panorama");

  const GLuint toCube = linkProgram(kPrelude, kFullscreenVertex,
                                    (std::string(kCubeDirection) + kPanoramaToCube).c_str());
  const GLuint filter =
      linkProgram(kPrelude, kFullscreenVertex, (std::string(kCubeDirection) + kFilter).c_str());
  const GLuint table =
      linkProgram(kPrelude, kFullscreenVertex, (std::string(kCubeDirection) + kLut).c_str());

  // The source cube: the panorama at each texel's centre, and its mip chain.
  int sourceLevels = 1;
  while ((cubeSize >> sourceLevels) > 0) ++sourceLevels;
  const GLuint source = makeCube(sourceLevels, cubeSize);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, panorama);
  glUseProgram(toCube);
  glUniform1i(glGetUniformLocation(toCube, "panorama"), 0);
  drawFaces(toCube, source, 0, cubeSize);
  glBindTexture(GL_TEXTURE_CUBE_MAP, source);
  glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
  throwOnGlError("rendering the panorama into a cube map");

  // The specular levels and the irradiance, each read from the source cube.
  specular_ = makeCube(kSpecularLevels, cubeSize);
  irradiance_ = makeCube(1, cubeSize);
  glBindTexture(GL_TEXTURE_CUBE_MAP, source);
  glUseProgram(filter);
  glUniform1i(glGetUniformLocation(filter, "source"), 0);
  glUniform1f(glGetUniformLocation(filter, "sourceSize"), float(cubeSize));
  glUniform1i(glGetUniformLocation(filter, "lambertian"), 0);
  glUniform1i(glGetUniformLocation(filter, "sampleCount"), kSpecularSamples);
  for (int level = 0; level < kSpecularLevels; ++level) {
    glUseProgram(filter);
    glUniform1f(glGetUniformLocation(filter, "roughness"),
                float(level) / float(kSpecularLevels - 1));
    drawFaces(filter, specular_, level, cubeSize);
  }
  glUseProgram(filter);
  glUniform1i(glGetUniformLocation(filter, "lambertian"), 1);
  glUniform1f(glGetUniformLocation(filter, "roughness"), 0.0f);
  glUniform1i(glGetUniformLocation(filter, "sampleCount"), kLambertianSamples);
  drawFaces(filter, irradiance_, 0, cubeSize);
  throwOnGlError("prefiltering the environment");

  // The GGX table.
  glGenTextures(1, &lut_);
  glBindTexture(GL_TEXTURE_2D, lut_);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RG32F, lutSize, lutSize);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, lut_, 0);
  glUseProgram(table);
  glUniform1f(glGetUniformLocation(table, "lutSize"), float(lutSize));
  glUniform1i(glGetUniformLocation(table, "sampleCount"), kLutSamples);
  glViewport(0, 0, lutSize, lutSize);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glFinish();
  throwOnGlError("computing the GGX table");

  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteVertexArrays(1, &vertexArray);
  for (GLuint program : {toCube, filter, table}) glDeleteProgram(program);
  // The panorama and the source cube are only the passes' input.
  glDeleteTextures(1, &panorama);
  glDeleteTextures(1, &source);
}

GlEnvironment::~GlEnvironment() {
  for (GLuint id : {specular_, irradiance_, lut_}) glDeleteTextures(1, &id);
}

}  // namespace quadra
