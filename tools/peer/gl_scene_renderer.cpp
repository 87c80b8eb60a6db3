// Uploading a Scene to OpenGL and drawing it as quadra does (see
// gl_scene_renderer.h).
#define GL_GLEXT_PROTOTYPES 1
#include "gl_scene_renderer.h"

#include <GL/glext.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_inverse.hpp>

#include "api/camera.h"
#include "api/renderer.h"
#include "core/error.h"
#include "gl_environment.h"
#include "gl_program.h"
#include "osmesa_context.h"
#include "scene/deformation.h"
#include "texture/image.h"
#include "texture/mip_chain.h"

namespace quadra {

bool peerSupportsFilter(Filter filter) {
  return filter == Filter::Nearest || filter == Filter::Bilinear || filter == Filter::NearestMip ||
         filter == Filter::Trilinear || filter == Filter::Anisotropic;
}

namespace {

// One shader pair per state a draw can have, specialized by #define (as
// quadra specializes its tile kernels), so that neither renderer interpolates
// or tests what a draw does not use.
constexpr const char* kVertexShader = R"(
layout(location = 0) in vec3 position;
uniform mat4 clipFromModel;
#ifdef TEXTURED
layout(location = 1) in vec2 texcoord;
uniform mat3x2 uvTransform;  // the material's texture transform (scene.h)
out vec2 uv;
#endif
#ifdef VERTEX_COLOR
layout(location = 2) in vec4 color;
out vec4 vertexColor;
#endif
void main() {
  gl_Position = clipFromModel * vec4(position, 1.0);
#ifdef TEXTURED
  uv = uvTransform * vec3(texcoord, 1.0);
#endif
#ifdef VERTEX_COLOR
  vertexColor = color;
#endif
}
)";

constexpr const char* kFragmentShader = R"(
uniform vec4 baseColor;
uniform float alphaCutoff;
#ifdef TEXTURED
uniform sampler2D baseColorTexture;
uniform bool premultipliedTexture;
in vec2 uv;
#endif
#ifdef VERTEX_COLOR
in vec4 vertexColor;
#endif
layout(location = 0) out vec4 fragColor;
void main() {
  vec4 c = baseColor;
#ifdef TEXTURED
  vec4 texel = texture(baseColorTexture, uv);
  // quadra's shadeColor: straight colour back from premultiplied levels.
  if (premultipliedTexture) texel.rgb = texel.a > 0.0 ? texel.rgb / texel.a : vec3(0.0);
  c *= texel;
#endif
#ifdef VERTEX_COLOR
  c *= vertexColor;
#endif
#ifdef ALPHA_MASK
  if (c.a < alphaCutoff) discard;
#endif
#ifndef ALPHA_BLEND
  c.a = 1.0;
#endif
  fragColor = c;
}
)";

// Pbr: every attribute a lit draw may read (arrays a mesh lacks read GL's
// constant default instead), in world space for the light.
constexpr const char* kLitVertexShader = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec2 texcoord0;
layout(location = 2) in vec4 color;
layout(location = 3) in vec3 normal;
layout(location = 4) in vec4 tangent;
layout(location = 5) in vec2 texcoord1;
uniform mat4 clipFromModel;
uniform mat4 worldFromModel;
uniform mat3 normalFromModel;
out vec3 worldPosition;
out vec3 worldNormal;
out vec4 worldTangent;
out vec2 uv0;
out vec2 uv1;
out vec4 vertexColor;
void main() {
  gl_Position = clipFromModel * vec4(position, 1.0);
  worldPosition = (worldFromModel * vec4(position, 1.0)).xyz;
  worldNormal = normalFromModel * normal;
  // A mirroring world matrix does not flip w (docs/lighting.md).
  worldTangent = vec4(mat3(worldFromModel) * tangent.xyz, tangent.w);
  uv0 = texcoord0;
  uv1 = texcoord1;
  vertexColor = color;
}
)";

// The tone maps of engine/io/tone_map.cpp, for 8-bit pbr frames (TONE_MAP 0:
// a clamp, 1: Khronos PBR Neutral, 2: ACES, Hill's fit).
constexpr const char* kToneMap = R"(
vec3 toneMap(vec3 c) {
  c = max(c, vec3(0.0));
#if TONE_MAP == 1
  float x = min(c.r, min(c.g, c.b));
  float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  c -= offset;
  float peak = max(c.r, max(c.g, c.b));
  const float start = 0.76, d = 0.24;
  if (peak >= start) {
    float newPeak = 1.0 - d * d / (peak + d - start);
    c *= newPeak / peak;
    float g = 1.0 - 1.0 / (0.15 * (peak - newPeak) + 1.0);
    c = mix(c, vec3(newPeak), g);
  }
#elif TONE_MAP == 2
  // GLSL matrices are given column by column: these are the rows of
  // tone_map.cpp's kIn and kOut.
  const mat3 toFit = transpose(mat3(0.59719, 0.35458, 0.04823, 0.07600, 0.90834, 0.01566,
                                    0.02840, 0.13383, 0.83777));
  const mat3 fromFit = transpose(mat3(1.60475, -0.53108, -0.07367, -0.10208, 1.10813, -0.00605,
                                      -0.00327, -0.07276, 1.07602));
  vec3 v = toFit * c;
  vec3 a = v * (v + 0.0245786) - 0.000090537;
  vec3 b = v * (0.983729 * v + 0.4329510) + 0.238081;
  c = fromFit * (a / b);
#endif
  return clamp(c, 0.0, 1.0);
}
)";

// The lit fragment: LIGHTING.md's material, lit as the Khronos glTF Sample
// Viewer lights it. Environment (split sum): the prefiltered radiance at
// the reflected direction, level roughness x (levels - 1); the irradiance
// at n; the GGX table at (n.v, roughness) gives the lobe's albedo with the
// Sample Viewer's roughness-dependent Fresnel (Fdez-Agüera 2019),
// k_S = f0 + (max(1 - roughness, f0) - f0) (1 - n.v)^5, albedo = weight
// (k_S scale + bias); dielectric = mix(diffuse, specular, its albedo),
// metal = specular x its albedo (f0 = baseColor), mixed by metallic, x
// occlusion. Lights: the same mix of the Appendix B BRDF terms, with the
// specification's falloff, range window and cone. No shadows.
constexpr const char* kLitFragmentShader = R"(
const float kPi = 3.14159265358979;
in vec3 worldPosition;
in vec3 worldNormal;
in vec4 worldTangent;
in vec2 uv0;
in vec2 uv1;
in vec4 vertexColor;
uniform sampler2D baseColorTexture;
uniform sampler2D metallicRoughnessTexture;
uniform sampler2D normalTexture;
uniform sampler2D occlusionTexture;
uniform sampler2D emissiveTexture;
uniform sampler2D specularTexture;
uniform sampler2D specularColorTexture;
uniform mat3x2 uvTransform[7];
uniform int uvSet[7];
uniform vec4 baseColor;
uniform float alphaCutoff;
uniform bool premultipliedTexture;
uniform vec2 metallicRoughness;
uniform float normalScale;
uniform float occlusionStrength;
uniform vec3 emission;
uniform float dielectricF0;
uniform float specularFactor;
uniform vec3 specularColorFactor;
uniform vec3 eye;
uniform float exposureScale;
uniform mat3 environmentRotation;
uniform float environmentScale;
uniform samplerCube specularCube;
uniform samplerCube irradianceCube;
uniform sampler2D ggxTable;
uniform float specularMaxLod;
#define MAX_LIGHTS 16
uniform int lightCount;
uniform vec3 lightPosition[MAX_LIGHTS];
uniform vec3 lightDirection[MAX_LIGHTS];
uniform vec3 lightRadiance[MAX_LIGHTS];
uniform vec4 lightShape[MAX_LIGHTS];  // type, 1 / range^4, cone scale, cone offset
layout(location = 0) out vec4 fragColor;

vec2 uvOf(int i) {
  return uvTransform[i] * vec3(uvSet[i] == 0 ? uv0 : uv1, 1.0);
}

vec3 albedo(vec3 f0, float weight, float roughness, float nv, vec2 table) {
  vec3 ks = f0 + (max(vec3(1.0 - roughness), f0) - f0) * pow(1.0 - nv, 5.0);
  return weight * (ks * table.x + table.y);
}

vec3 shade(vec3 base) {
  vec3 v = normalize(eye - worldPosition);
  float metallic = metallicRoughness.x, roughness = metallicRoughness.y;
#ifdef METALLIC_ROUGHNESS_TEXTURE
  vec4 mr = texture(metallicRoughnessTexture, uvOf(1));
  metallic *= mr.b;
  roughness *= mr.g;
#endif
  metallic = clamp(metallic, 0.0, 1.0);
  roughness = clamp(roughness, 0.0, 1.0);
#ifdef NORMALS
  vec3 n = normalize(worldNormal);
#ifdef NORMAL_TEXTURE
  vec3 t = normalize(worldTangent.xyz);
  vec3 b = (worldTangent.w < 0.0 ? -1.0 : 1.0) * cross(n, t);
#endif
  // Double-sided back faces turn N, T and B toward the viewer.
  if (!gl_FrontFacing) {
    n = -n;
#ifdef NORMAL_TEXTURE
    t = -t;
    b = -b;
#endif
  }
#ifdef NORMAL_TEXTURE
  vec3 tn = texture(normalTexture, uvOf(2)).rgb * 2.0 - 1.0;
  tn = normalize(tn * vec3(normalScale, normalScale, 1.0));
  n = normalize(t * tn.x + b * tn.y + n * tn.z);
#endif
#else
  // No NORMAL: the triangle's own plane, facing the viewer.
  vec3 n = normalize(cross(dFdx(worldPosition), dFdy(worldPosition)));
  if (dot(n, v) < 0.0) n = -n;
#endif
  float nv = clamp(dot(n, v), 0.0, 1.0);
  float weight = specularFactor;
#ifdef SPECULAR_TEXTURE
  weight *= texture(specularTexture, uvOf(5)).a;
#endif
  vec3 specularColor = specularColorFactor;
#ifdef SPECULAR_COLOR_TEXTURE
  specularColor *= texture(specularColorTexture, uvOf(6)).rgb;
#endif
  vec3 f0 = min(vec3(dielectricF0) * specularColor, vec3(1.0));

  vec3 color = emission;
#ifdef EMISSIVE_TEXTURE
  color *= texture(emissiveTexture, uvOf(4)).rgb;
#endif

  vec3 r = 2.0 * dot(n, v) * n - v;
  vec3 specularLight =
      textureLod(specularCube, environmentRotation * r, roughness * specularMaxLod).rgb;
  vec3 diffuseLight = texture(irradianceCube, environmentRotation * n).rgb;
  vec2 table = texture(ggxTable, vec2(nv, roughness)).rg;
  vec3 dielectric = mix(diffuseLight * base, specularLight, albedo(f0, weight, roughness, nv, table));
  vec3 metal = specularLight * albedo(base, 1.0, roughness, nv, table);
  float occlusion = 1.0;
#ifdef OCCLUSION_TEXTURE
  occlusion = 1.0 + occlusionStrength * (texture(occlusionTexture, uvOf(3)).r - 1.0);
#endif
  color += occlusion * environmentScale * mix(dielectric, metal, metallic);

  // A mirror's narrow lobe keeps a finite value under a point light.
  float alpha = max(roughness * roughness, 1.0 / 1024.0);
  float alpha2 = alpha * alpha;
  for (int i = 0; i < lightCount; ++i) {
    vec4 shape = lightShape[i];
    vec3 l = -lightDirection[i];
    float falloff = 1.0;
    if (shape.x != 0.0) {
      vec3 toLight = lightPosition[i] - worldPosition;
      float d2 = max(dot(toLight, toLight), 1e-20);
      l = toLight * inversesqrt(d2);
      falloff = clamp(1.0 - d2 * d2 * shape.y, 0.0, 1.0) / d2;
      if (shape.x == 2.0) {
        float cone = clamp(-dot(l, lightDirection[i]) * shape.z + shape.w, 0.0, 1.0);
        falloff *= cone * cone;
      }
    }
    float nl = dot(n, l), nvl = dot(n, v);
    if (nl <= 0.0 || nvl <= 0.0) continue;
    vec3 h = normalize(l + v);
    float nh = clamp(dot(n, h), 0.0, 1.0), vh = clamp(dot(v, h), 0.0, 1.0);
    float d = nh * nh * (alpha2 - 1.0) + 1.0;
    float specular = alpha2 / (kPi * d * d) * 0.5 /
                     (nl * sqrt(nvl * nvl * (1.0 - alpha2) + alpha2) +
                      nvl * sqrt(nl * nl * (1.0 - alpha2) + alpha2));
    float w = pow(1.0 - vh, 5.0);
    vec3 lightDielectric = mix(base / kPi, vec3(specular), f0 * weight + (weight - f0 * weight) * w);
    vec3 lightMetal = (base + (1.0 - base) * w) * specular;
    color += lightRadiance[i] * (falloff * nl) * mix(lightDielectric, lightMetal, metallic);
  }
  return color;
}

void main() {
  vec4 c = baseColor;
#ifdef BASE_COLOR_TEXTURE
  vec4 texel = texture(baseColorTexture, uvOf(0));
  if (premultipliedTexture) texel.rgb = texel.a > 0.0 ? texel.rgb / texel.a : vec3(0.0);
  c *= texel;
#endif
#ifdef VERTEX_COLOR
  c *= vertexColor;
#endif
#ifdef ALPHA_MASK
  if (c.a < alphaCutoff) discard;
#endif
#ifdef UNLIT
  vec3 radiance = c.rgb;
#else
  vec3 radiance = shade(c.rgb);
#endif
  radiance *= exposureScale;
#ifdef TONE_MAP
  radiance = toneMap(radiance);
#endif
#ifndef ALPHA_BLEND
  c.a = 1.0;
#endif
  fragColor = vec4(radiance, c.a);
}
)";

// The background: the environment through each pixel, as the Sample Viewer
// draws it, the prefiltered cube's level 0 (roughness 0: the cube itself) in
// the direction of the pixel centre's ray (two points on it unprojected).
constexpr const char* kBackgroundVertexShader = R"(
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

constexpr const char* kBackgroundFragmentShader = R"(
uniform mat4 worldFromClip;
uniform vec2 viewportSize;
uniform mat3 environmentRotation;
uniform float environmentScale;
uniform float exposureScale;
uniform samplerCube specularCube;
layout(location = 0) out vec4 fragColor;
void main() {
  // Window row 0 is the top (glClipControl GL_UPPER_LEFT).
  vec2 ndc = vec2(gl_FragCoord.x / viewportSize.x * 2.0 - 1.0,
                  1.0 - gl_FragCoord.y / viewportSize.y * 2.0);
  vec4 nearPoint = worldFromClip * vec4(ndc, 0.0, 1.0);
  vec4 fartherPoint = worldFromClip * vec4(ndc, 0.5, 1.0);
  vec3 d = normalize(fartherPoint.xyz / fartherPoint.w - nearPoint.xyz / nearPoint.w);
  vec3 radiance = textureLod(specularCube, environmentRotation * d, 0.0).rgb *
                  (environmentScale * exposureScale);
#ifdef TONE_MAP
  radiance = toneMap(radiance);
#endif
  fragColor = vec4(radiance, 1.0);
}
)";

// The most punctual lights the lit shader takes (its MAX_LIGHTS).
constexpr std::size_t kMaxLights = 16;

// The environment's rotation as a lookup applies it: world direction d reads
// the panorama at R_y(-degrees) d (LIGHTING.md).
glm::mat3 environmentRotation(float degrees) {
  const double angle = double(degrees) * 3.14159265358979323846 / 180.0;
  const float c = float(std::cos(angle)), s = float(std::sin(angle));
  // Columns: the images of x, y, z.
  return glm::mat3(glm::vec3(c, 0.0f, s), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(-s, 0.0f, c));
}

GLint glWrap(WrapMode wrap) {
  switch (wrap) {
    case WrapMode::Repeat:
      return GL_REPEAT;
    case WrapMode::MirroredRepeat:
      return GL_MIRRORED_REPEAT;
    case WrapMode::ClampToEdge:
      return GL_CLAMP_TO_EDGE;
    case WrapMode::ClampToBorder:
      return GL_CLAMP_TO_BORDER;
  }
  return GL_REPEAT;
}

// quadra's nearest-mip is bilinear within the nearest level, unless the
// sampler asks for the nearest texel within levels (SamplerState::minLinear).
GLint glMinFilter(Filter filter, bool minLinear) {
  switch (filter) {
    case Filter::Nearest:
      return GL_NEAREST;
    case Filter::Bilinear:
      return GL_LINEAR;
    case Filter::NearestMip:
      return minLinear ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
    case Filter::Trilinear:
      return minLinear ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
    case Filter::Anisotropic:
      return GL_LINEAR_MIPMAP_LINEAR;
    default:
      throw Error(std::string("--filter ") + filterName(filter) + ": llvmpipe has no such filter");
  }
}

struct GlTexelFormat {
  GLint internalFormat;
  GLenum type;
};

// quadra's storage formats (texture/texel_format.h) in GL: the same bytes,
// encoded by quadra's own encodeTexel.
GlTexelFormat glTexelFormat(TexelFormat format) {
  switch (format) {
    case TexelFormat::Rgba32F:
      return {GL_RGBA32F, GL_FLOAT};
    case TexelFormat::Rgba16F:
      return {GL_RGBA16F, GL_HALF_FLOAT};
    case TexelFormat::Rgba8Unorm:
      return {GL_RGBA8, GL_UNSIGNED_BYTE};
    case TexelFormat::Rgba8Srgb:
      return {GL_SRGB8_ALPHA8, GL_UNSIGNED_BYTE};
  }
  return {GL_RGBA32F, GL_FLOAT};
}

}  // namespace

void GlSceneRenderer::makeFramebuffer(GLenum colorFormat, int samples, GLuint& framebuffer,
                                      GLuint& color, GLuint& depth) const {
  // Samples 1 is glRenderbufferStorage's single-sample storage as well.
  const auto storage = [&](GLuint buffer, GLenum format) {
    glBindRenderbuffer(GL_RENDERBUFFER, buffer);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, format,
                                     settings_.width, settings_.height);
  };
  glGenRenderbuffers(1, &color);
  storage(color, colorFormat);
  glGenRenderbuffers(1, &depth);
  storage(depth, GL_DEPTH_COMPONENT32F);
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("llvmpipe: the colour + DEPTH32F framebuffer at " + std::to_string(samples) +
                " samples is incomplete");
  // GL may give more samples than asked (llvmpipe has 1 and 4): the frame
  // would then not be the one quadra draws at that count.
  GLint given = 0;
  glBindRenderbuffer(GL_RENDERBUFFER, color);
  glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &given);
  if (std::max(given, 1) != samples)
    throw Error("--samples " + std::to_string(samples) + ": llvmpipe gives " +
                std::to_string(given) + " samples per pixel for that request");
}

GlSceneRenderer::GlSceneRenderer(const OsMesaContext& context, const Scene& scene,
                                 const PeerSettings& settings)
    : scene_(scene), settings_(settings) {
  // Clip depth [0, 1] as quadra's projection makes it, and window row 0 at
  // the top, so that glReadPixels returns rows in quadra's order. GL then
  // also inverts its facing test, so CCW stays front-facing as in glTF.
  const auto clipControl =
      reinterpret_cast<PFNGLCLIPCONTROLPROC>(context.procAddress("glClipControl"));
  if (!clipControl) throw Error("llvmpipe: glClipControl is missing (OpenGL 4.5)");
  clipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);

  const bool lit = settings.shading == Shading::Pbr;
  if (lit) {
    if (!settings.environment)
      throw Error("llvmpipe: pbr shading needs an environment (PeerSettings::environment)");
    // Prepared once, before the first frame, as a real-time viewer does on
    // loading an environment; the frames' times do not include it.
    const auto started = std::chrono::steady_clock::now();
    environment_ =
        std::make_unique<GlEnvironment>(*settings.environment, settings.iblSize, settings.lutSize);
    prepareMs_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started)
            .count();
    if (settings.punctualLights)
      for (const Light& light : scene.lights) lights_.push_back(punctualLightOf(light));
    if (lights_.size() > kMaxLights)
      throw Error(scene.name + ": " + std::to_string(lights_.size()) +
                  " punctual lights; the llvmpipe peer's shader takes at most " +
                  std::to_string(kMaxLights) + " (--lights off draws without them)");
  }

  const bool floatColor = settings.framebuffer == PeerFramebuffer::Rgba32F;
  const GLenum colorFormat = floatColor ? GL_RGBA32F : GL_SRGB8_ALPHA8;
  if (settings.samples > 1) {
    GLint maxSamples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    if (settings.samples > maxSamples)
      throw Error("--samples " + std::to_string(settings.samples) + ": llvmpipe has at most " +
                  std::to_string(maxSamples) + " samples per pixel (GL_MAX_SAMPLES)");
  }
  makeFramebuffer(colorFormat, settings.samples, framebuffer_, colorBuffer_, depthBuffer_);
  if (settings.samples > 1)
    makeFramebuffer(colorFormat, 1, resolveFramebuffer_, resolveColor_, resolveDepth_);
  if (!floatColor) glEnable(GL_FRAMEBUFFER_SRGB);
  throwOnGlError("making the framebuffer");

  const float exposureScale = std::exp2(settings.exposure);
  static const Material kDefaultMaterial;
  meshes_.resize(scene.meshes.size());
  std::vector<bool> uploaded(scene.meshes.size(), false);
  for (const Instance& instance : scene.instances) {
    const std::size_t m = std::size_t(instance.mesh);
    const Mesh& mesh = scene.meshes.at(m);
    const Material& material =
        mesh.material >= 0 ? scene.materials.at(std::size_t(mesh.material)) : kDefaultMaterial;
    // The draw state as engine/api/renderer.cpp makeDraw sets it.
    const int texcoordSet = std::clamp(material.baseColorTexCoord, 0, 1);
    const bool textured = material.baseColorTexture >= 0 && !mesh.texcoords[texcoordSet].empty();
    const bool vertexColor = !mesh.colors.empty();
    DrawState draw;
    std::string defines;
    if (lit) draw = litDrawState(mesh, material, instance, defines);
    if (const VertexDeformer deformer(mesh, instance); deformer.active()) {
      Vertices posed;
      std::vector<glm::vec3> positions(mesh.positions.size()), normals;
      std::vector<glm::vec4> tangents;
      if (lit && !mesh.normals.empty()) normals.resize(positions.size());
      if (lit && !mesh.tangents.empty()) tangents.resize(positions.size());
      for (std::size_t i = 0; i < positions.size(); ++i) {
        const glm::mat4 skin = deformer.skinMatrix(i);
        positions[i] = deformer.position(i, skin);
        if (!normals.empty()) normals[i] = deformer.normal(i, skin);
        if (!tangents.empty()) tangents[i] = deformer.tangent(i, skin);
      }
      uploadMesh(mesh, {positions, normals, tangents}, texcoordSet, vertexColor, lit,
                 posedMeshes_.emplace_back());
      draw.mesh = &posedMeshes_.back();
    } else {
      if (!uploaded[m]) {
        uploadMesh(mesh, {mesh.positions, mesh.normals, mesh.tangents}, texcoordSet, vertexColor,
                   lit, meshes_[m]);
        uploaded[m] = true;
      }
      draw.mesh = &meshes_[m];
    }
    if (lit) {
      draw.program = &litProgramFor(defines);
    } else {
      draw.program = &programFor(textured, vertexColor, material.alphaMode);
      if (textured) {
        const Texture& texture = scene.textures.at(std::size_t(material.baseColorTexture))
                                     ->forAlpha(textureAlphaOf(material));
        draw.texture = textureFor(texture);
        draw.premultipliedTexture = texture.alpha().premultiplied();
        draw.uvTransform = material.baseColorTransform.matrix();
      }
      // quadra's unlit colour is the radiance it shows, x 2^exposure too.
      draw.baseColor = glm::vec4(glm::vec3(material.baseColorFactor) * exposureScale,
                                 material.baseColorFactor.a);
    }
    draw.alphaCutoff = material.alphaCutoff;
    draw.cull = !material.doubleSided;
    draw.frontClockwise = glm::determinant(glm::mat3(instance.world)) < 0.0f;
    draw.blend = material.alphaMode == AlphaMode::Blend;
    draws_.push_back(draw);
  }
  throwOnGlError("uploading meshes and textures");

  if (lit) {
    std::string prelude = "#version 450 core\n";
    if (!floatColor)
      prelude += "#define TONE_MAP " +
                 std::to_string(int(settings.toneMap == ToneMap::PbrNeutral ? 1
                                    : settings.toneMap == ToneMap::Aces     ? 2
                                                                            : 0)) +
                 "\n" + kToneMap;
    backgroundProgram_ = linkProgram(prelude, kBackgroundVertexShader, kBackgroundFragmentShader);
    glGenVertexArrays(1, &emptyVertexArray_);
    glUseProgram(backgroundProgram_);
    glUniform1i(glGetUniformLocation(backgroundProgram_, "specularCube"), 7);
    // Every lit program reads the prepared environment from units 7-9.
    glActiveTexture(GL_TEXTURE7);
    glBindTexture(GL_TEXTURE_CUBE_MAP, environment_->specularCube());
    glActiveTexture(GL_TEXTURE8);
    glBindTexture(GL_TEXTURE_CUBE_MAP, environment_->irradianceCube());
    glActiveTexture(GL_TEXTURE9);
    glBindTexture(GL_TEXTURE_2D, environment_->lut());
    glActiveTexture(GL_TEXTURE0);
    throwOnGlError("compiling the background");
  }

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glCullFace(GL_BACK);
  // quadra's "over": colour = src * a + dst * (1 - a) with the shaded
  // (straight) colour as src, alpha = a + dst_a * (1 - a): premultiplied out.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glViewport(0, 0, settings.width, settings.height);
  // What no surface covers: quadra's clear colour (x 2^exposure), or for
  // pbr's environment and transparent backgrounds nothing (the environment
  // is drawn over it).
  glm::vec4 clear = settings.clearColor;
  if (lit && settings.background != Background::Color) clear = glm::vec4(0.0f);
  clear = glm::vec4(glm::vec3(clear) * exposureScale, clear.a);
  if (lit && !floatColor) {
    float mapped[3];
    ToneMapping{settings.toneMap, 0.0f}.apply(&clear[0], mapped);
    clear = glm::vec4(mapped[0], mapped[1], mapped[2], clear.a);
  }
  glClearColor(clear.r, clear.g, clear.b, clear.a);
  glClearDepth(1.0);
}

GlSceneRenderer::~GlSceneRenderer() {
  const auto release = [](const MeshBuffers& mesh) {
    glDeleteVertexArrays(1, &mesh.vertexArray);
    glDeleteBuffers(7, mesh.buffers);
  };
  for (const MeshBuffers& mesh : meshes_) release(mesh);
  for (const MeshBuffers& mesh : posedMeshes_) release(mesh);
  for (const auto& [texture, id] : textures_) glDeleteTextures(1, &id);
  for (const auto& [variant, program] : programs_) glDeleteProgram(program.id);
  if (backgroundProgram_ != 0) glDeleteProgram(backgroundProgram_);
  if (emptyVertexArray_ != 0) glDeleteVertexArrays(1, &emptyVertexArray_);
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteRenderbuffers(1, &colorBuffer_);
  glDeleteRenderbuffers(1, &depthBuffer_);
  if (resolveFramebuffer_ != 0) {
    glDeleteFramebuffers(1, &resolveFramebuffer_);
    glDeleteRenderbuffers(1, &resolveColor_);
    glDeleteRenderbuffers(1, &resolveDepth_);
  }
}

const GlSceneRenderer::Program& GlSceneRenderer::programFor(bool textured, bool vertexColor,
                                                            AlphaMode alphaMode) {
  const std::string variant =
      "unlit " + std::to_string(int(textured) | int(vertexColor) << 1 | int(alphaMode) << 2);
  if (const auto found = programs_.find(variant); found != programs_.end()) return found->second;
  std::string defines = "#version 330 core\n";
  if (textured) defines += "#define TEXTURED\n";
  if (vertexColor) defines += "#define VERTEX_COLOR\n";
  if (alphaMode == AlphaMode::Mask) defines += "#define ALPHA_MASK\n";
  if (alphaMode == AlphaMode::Blend) defines += "#define ALPHA_BLEND\n";
  Program program;
  program.id = linkProgram(defines, kVertexShader, kFragmentShader);
  program.clipFromModel = glGetUniformLocation(program.id, "clipFromModel");
  program.baseColor = glGetUniformLocation(program.id, "baseColor");
  program.alphaCutoff = glGetUniformLocation(program.id, "alphaCutoff");
  program.premultipliedTexture = glGetUniformLocation(program.id, "premultipliedTexture");
  program.uvTransform = glGetUniformLocation(program.id, "uvTransform");
  glUseProgram(program.id);
  glUniform1i(glGetUniformLocation(program.id, "baseColorTexture"), 0);
  return programs_.emplace(variant, program).first->second;
}

const GlSceneRenderer::Program& GlSceneRenderer::litProgramFor(const std::string& defines) {
  const std::string variant = "pbr\n" + defines;
  if (const auto found = programs_.find(variant); found != programs_.end()) return found->second;
  std::string prelude = "#version 450 core\n" + defines;
  if (settings_.framebuffer == PeerFramebuffer::Srgba8)
    prelude += "#define TONE_MAP " +
               std::to_string(settings_.toneMap == ToneMap::PbrNeutral ? 1
                              : settings_.toneMap == ToneMap::Aces     ? 2
                                                                       : 0) +
               "\n" + kToneMap;
  Program program;
  program.id = linkProgram(prelude, kLitVertexShader, kLitFragmentShader);
  const auto at = [&](const char* name) { return glGetUniformLocation(program.id, name); };
  program.clipFromModel = at("clipFromModel");
  program.baseColor = at("baseColor");
  program.alphaCutoff = at("alphaCutoff");
  program.premultipliedTexture = at("premultipliedTexture");
  program.uvTransform = at("uvTransform");
  program.worldFromModel = at("worldFromModel");
  program.normalFromModel = at("normalFromModel");
  program.uvSet = at("uvSet");
  program.metallicRoughness = at("metallicRoughness");
  program.normalScale = at("normalScale");
  program.occlusionStrength = at("occlusionStrength");
  program.emission = at("emission");
  program.dielectricF0 = at("dielectricF0");
  program.specularFactor = at("specularFactor");
  program.specularColorFactor = at("specularColorFactor");
  glUseProgram(program.id);
  const char* samplers[kLitTextures] = {
      "baseColorTexture", "metallicRoughnessTexture", "normalTexture",       "occlusionTexture",
      "emissiveTexture",  "specularTexture",          "specularColorTexture"};
  for (int unit = 0; unit < kLitTextures; ++unit) glUniform1i(at(samplers[unit]), unit);
  glUniform1i(at("specularCube"), 7);
  glUniform1i(at("irradianceCube"), 8);
  glUniform1i(at("ggxTable"), 9);
  glUniform1f(at("specularMaxLod"), float(GlEnvironment::kSpecularLevels - 1));
  return programs_.emplace(variant, program).first->second;
}

GlSceneRenderer::DrawState GlSceneRenderer::litDrawState(const Mesh& mesh, const Material& material,
                                                         const Instance& instance,
                                                         std::string& defines) {
  DrawState draw;
  draw.worldFromModel = instance.world;
  draw.normalFromModel = glm::inverseTranspose(glm::mat3(instance.world));
  // Each texture through its own set and transform; one whose set the mesh
  // lacks is not read (as quadra's renderer.cpp materialShading decides),
  // nor a normal map without tangents.
  const auto texture = [&](LitTexture slot, const MaterialTexture& from, const TextureAlpha& alpha,
                           const char* define) {
    const int set = std::clamp(from.texCoord, 0, 1);
    if (!from.present() || mesh.texcoords[set].empty()) return;
    const Texture& t = scene_.textures.at(std::size_t(from.texture))->forAlpha(alpha);
    draw.litTextures[slot] = textureFor(t);
    draw.uvSet[slot] = set;
    draw.uvTransforms[slot] = from.transform.matrix();
    if (slot == kBaseColor) draw.premultipliedTexture = t.alpha().premultiplied();
    defines += std::string("#define ") + define + "\n";
  };
  if (material.unlit) {
    defines += "#define UNLIT\n";
  } else {
    texture(kMetallicRoughness, material.metallicRoughness, {}, "METALLIC_ROUGHNESS_TEXTURE");
    if (!mesh.normals.empty()) {
      defines += "#define NORMALS\n";
      if (!mesh.tangents.empty()) texture(kNormal, material.normal, {}, "NORMAL_TEXTURE");
    }
    texture(kOcclusion, material.occlusion, {}, "OCCLUSION_TEXTURE");
    texture(kEmissive, material.emissive, {}, "EMISSIVE_TEXTURE");
    texture(kSpecular, material.specular, {}, "SPECULAR_TEXTURE");
    texture(kSpecularColor, material.specularColor, {}, "SPECULAR_COLOR_TEXTURE");
  }
  texture(kBaseColor,
          {material.baseColorTexture, material.baseColorTexCoord, material.baseColorTransform},
          textureAlphaOf(material), "BASE_COLOR_TEXTURE");
  if (!mesh.colors.empty()) defines += "#define VERTEX_COLOR\n";
  if (material.alphaMode == AlphaMode::Mask) defines += "#define ALPHA_MASK\n";
  if (material.alphaMode == AlphaMode::Blend) defines += "#define ALPHA_BLEND\n";
  draw.baseColor = material.baseColorFactor;
  draw.metallicRoughness = {material.metallicFactor, material.roughnessFactor};
  draw.normalScale = material.normalScale;
  draw.occlusionStrength = material.occlusionStrength;
  draw.emission = material.emissiveFactor * material.emissiveStrength;
  // KHR_materials_ior: f0 = ((ior - 1) / (ior + 1))^2.
  const float r = (material.ior - 1.0f) / (material.ior + 1.0f);
  draw.dielectricF0 = r * r;
  draw.specularFactor = material.specularFactor;
  draw.specularColorFactor = material.specularColorFactor;
  return draw;
}

void GlSceneRenderer::uploadMesh(const Mesh& mesh, const Vertices& vertices, int texcoordSet,
                                 bool vertexColor, bool lit, MeshBuffers& out) {
  glGenVertexArrays(1, &out.vertexArray);
  glBindVertexArray(out.vertexArray);
  glGenBuffers(7, out.buffers);
  const auto attribute = [&](int slot, GLint components, GLsizeiptr bytes, const void* data) {
    glBindBuffer(GL_ARRAY_BUFFER, out.buffers[slot]);
    glBufferData(GL_ARRAY_BUFFER, bytes, data, GL_STATIC_DRAW);
    glVertexAttribPointer(GLuint(slot), components, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(GLuint(slot));
  };
  attribute(0, 3, GLsizeiptr(vertices.positions.size_bytes()), vertices.positions.data());
  const std::vector<glm::vec2>& texcoords = mesh.texcoords[lit ? 0 : texcoordSet];
  if (!texcoords.empty())
    attribute(1, 2, GLsizeiptr(texcoords.size() * sizeof(glm::vec2)), texcoords.data());
  if (vertexColor)
    attribute(2, 4, GLsizeiptr(mesh.colors.size() * sizeof(glm::vec4)), mesh.colors.data());
  if (lit && !vertices.normals.empty())
    attribute(3, 3, GLsizeiptr(vertices.normals.size_bytes()), vertices.normals.data());
  if (lit && !vertices.tangents.empty())
    attribute(4, 4, GLsizeiptr(vertices.tangents.size_bytes()), vertices.tangents.data());
  if (lit && !mesh.texcoords[1].empty())
    attribute(5, 2, GLsizeiptr(mesh.texcoords[1].size() * sizeof(glm::vec2)),
              mesh.texcoords[1].data());
  // Buffer 6 holds the indices (slot 3 is the normals' attribute).
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, out.buffers[6]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STATIC_DRAW);
  out.indexCount = GLsizei(mesh.indices.size());
  glBindVertexArray(0);
}

GLuint GlSceneRenderer::textureFor(const Texture& texture) {
  auto [slot, added] = textures_.try_emplace(&texture, 0);
  if (added) slot->second = uploadTexture(texture);
  return slot->second;
}

GLuint GlSceneRenderer::uploadTexture(const Texture& texture) {
  const TexelFormat storage = settings_.textureFormat.value_or(texture.storage());
  const GlTexelFormat format = glTexelFormat(storage);
  const auto upload = [&](int level, const Image& image) {
    const std::size_t texels = std::size_t(image.width) * std::size_t(image.height);
    const int bytes = bytesPerTexel(storage);
    std::vector<std::uint8_t> encoded(texels * std::size_t(bytes));
    for (std::size_t i = 0; i < texels; ++i)
      encodeTexel(storage, &image.rgba[4 * i], &encoded[i * std::size_t(bytes)]);
    glTexImage2D(GL_TEXTURE_2D, level, format.internalFormat, image.width, image.height, 0, GL_RGBA,
                 format.type, encoded.data());
  };

  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  upload(0, texture.filteredLevel0());

  // The filter as quadra resolves it (texture/texture_sampler.cpp makeTextureView).
  const SamplerState& sampler = texture.sampler();
  const Filter filter = settings_.filter.value_or(sampler.minFilter);
  const bool magLinear = settings_.filter ? filter != Filter::Nearest : sampler.magLinear;
  const bool minLinear = settings_.filter ? true : sampler.minLinear;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, glWrap(sampler.wrapU));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, glWrap(sampler.wrapV));
  glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, sampler.borderColor);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, glMinFilter(filter, minLinear));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, magLinear ? GL_LINEAR : GL_NEAREST);
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_LOD_BIAS, settings_.lodBias);
  if (filter == Filter::Anisotropic)
    glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY, float(settings_.maxAniso));
  // A texture whose alpha is read has quadra's own levels (premultiplied, and
  // for alpha tests coverage-preserving); GL would build straight ones.
  if (needsMips(filter) && texture.alpha().premultiplied()) {
    const MipChain& mips = texture.mips();
    for (int level = 1; level < mips.levelCount(); ++level) upload(level, mips.level(level));
  } else if (needsMips(filter)) {
    glGenerateMipmap(GL_TEXTURE_2D);
  }
  return id;
}

void GlSceneRenderer::draw(const DrawState& state, const glm::mat4& clipFromModel) const {
  const Program& program = *state.program;
  glUseProgram(program.id);
  glUniformMatrix4fv(program.clipFromModel, 1, GL_FALSE, &clipFromModel[0][0]);
  glUniform4fv(program.baseColor, 1, &state.baseColor[0]);
  glUniform1f(program.alphaCutoff, state.alphaCutoff);
  glUniform1i(program.premultipliedTexture, state.premultipliedTexture ? 1 : 0);
  if (settings_.shading == Shading::Pbr) {
    glUniformMatrix3x2fv(program.uvTransform, kLitTextures, GL_FALSE, &state.uvTransforms[0][0][0]);
    glUniform1iv(program.uvSet, kLitTextures, state.uvSet);
    glUniformMatrix4fv(program.worldFromModel, 1, GL_FALSE, &state.worldFromModel[0][0]);
    glUniformMatrix3fv(program.normalFromModel, 1, GL_FALSE, &state.normalFromModel[0][0]);
    glUniform2fv(program.metallicRoughness, 1, &state.metallicRoughness[0]);
    glUniform1f(program.normalScale, state.normalScale);
    glUniform1f(program.occlusionStrength, state.occlusionStrength);
    glUniform3fv(program.emission, 1, &state.emission[0]);
    glUniform1f(program.dielectricF0, state.dielectricF0);
    glUniform1f(program.specularFactor, state.specularFactor);
    glUniform3fv(program.specularColorFactor, 1, &state.specularColorFactor[0]);
    for (int unit = 0; unit < kLitTextures; ++unit) {
      if (state.litTextures[unit] == 0) continue;
      glActiveTexture(GLenum(GL_TEXTURE0 + unit));
      glBindTexture(GL_TEXTURE_2D, state.litTextures[unit]);
    }
    glActiveTexture(GL_TEXTURE0);
  } else {
    if (program.uvTransform >= 0)
      glUniformMatrix3x2fv(program.uvTransform, 1, GL_FALSE, &state.uvTransform[0][0]);
    if (state.texture) glBindTexture(GL_TEXTURE_2D, state.texture);
  }
  if (state.cull)
    glEnable(GL_CULL_FACE);
  else
    glDisable(GL_CULL_FACE);
  glFrontFace(state.frontClockwise ? GL_CW : GL_CCW);
  if (state.blend)
    glEnable(GL_BLEND);
  else
    glDisable(GL_BLEND);
  glDepthMask(state.blend ? GL_FALSE : GL_TRUE);
  glBindVertexArray(state.mesh->vertexArray);
  glDrawElements(GL_TRIANGLES, state.mesh->indexCount, GL_UNSIGNED_INT, nullptr);
}

void GlSceneRenderer::setLitFrameUniforms(const glm::vec3& eye) const {
  const glm::mat3 rotation = environmentRotation(settings_.environmentRotation);
  const float exposureScale = std::exp2(settings_.exposure);
  const int count = int(lights_.size());
  const std::size_t n = lights_.size();
  std::vector<glm::vec3> position(n), direction(n), radiance(n);
  std::vector<glm::vec4> shape(n);
  for (int i = 0; i < count; ++i) {
    const PunctualLight& l = lights_[std::size_t(i)];
    position[std::size_t(i)] = {l.position[0], l.position[1], l.position[2]};
    direction[std::size_t(i)] = {l.direction[0], l.direction[1], l.direction[2]};
    radiance[std::size_t(i)] = {l.radiance[0], l.radiance[1], l.radiance[2]};
    shape[std::size_t(i)] = {float(int(l.type)), l.inverseRange4, l.angleScale, l.angleOffset};
  }
  for (const auto& [variant, program] : programs_) {
    glUseProgram(program.id);
    const auto at = [&](const char* name) { return glGetUniformLocation(program.id, name); };
    glUniform3fv(at("eye"), 1, &eye[0]);
    glUniform1f(at("exposureScale"), exposureScale);
    glUniformMatrix3fv(at("environmentRotation"), 1, GL_FALSE, &rotation[0][0]);
    glUniform1f(at("environmentScale"), settings_.environmentIntensity);
    glUniform1i(at("lightCount"), count);
    if (count > 0) {
      glUniform3fv(at("lightPosition"), count, &position[0][0]);
      glUniform3fv(at("lightDirection"), count, &direction[0][0]);
      glUniform3fv(at("lightRadiance"), count, &radiance[0][0]);
      glUniform4fv(at("lightShape"), count, &shape[0][0]);
    }
  }
}

void GlSceneRenderer::drawBackground(const glm::mat4& clipFromWorld) const {
  const glm::mat4 worldFromClip = glm::inverse(clipFromWorld);
  const glm::mat3 rotation = environmentRotation(settings_.environmentRotation);
  const auto at = [&](const char* name) { return glGetUniformLocation(backgroundProgram_, name); };
  glUseProgram(backgroundProgram_);
  glUniformMatrix4fv(at("worldFromClip"), 1, GL_FALSE, &worldFromClip[0][0]);
  glUniform2f(at("viewportSize"), float(settings_.width), float(settings_.height));
  glUniformMatrix3fv(at("environmentRotation"), 1, GL_FALSE, &rotation[0][0]);
  glUniform1f(at("environmentScale"), settings_.environmentIntensity);
  glUniform1f(at("exposureScale"), std::exp2(settings_.exposure));
  // Behind everything: no depth test or write, so the surfaces draw over it.
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glBindVertexArray(emptyVertexArray_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glEnable(GL_DEPTH_TEST);
}

void GlSceneRenderer::render(const Camera& camera) {
  const glm::mat4 view = viewMatrix(camera);
  const glm::mat4 projection = projectionMatrix(camera, double(settings_.width) / settings_.height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glDepthMask(GL_TRUE);  // glClear honours the depth mask
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (settings_.shading == Shading::Pbr) {
    setLitFrameUniforms(glm::vec3(glm::inverse(view)[3]));
    if (settings_.background == Background::Environment) drawBackground(projection * view);
  }
  for (const std::size_t i : instanceDrawOrder(scene_, view))
    draw(draws_[i], projection * (view * scene_.instances[i].world));
  if (settings_.samples > 1) {
    // The resolve is part of the frame's time, as quadra's is.
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFramebuffer_);
    glBlitFramebuffer(
        0, 0, settings_.width, settings_.height, 0, 0, settings_.width, settings_.height,
        GL_COLOR_BUFFER_BIT | (settings_.frameDepth ? GL_DEPTH_BUFFER_BIT : 0), GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resolveFramebuffer_);
  }
  glFinish();
  const std::size_t values = std::size_t(settings_.width) * std::size_t(settings_.height) * 4;
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  if (settings_.framebuffer == PeerFramebuffer::Rgba32F) {
    colorFloat_.resize(values);
    glReadPixels(0, 0, settings_.width, settings_.height, GL_RGBA, GL_FLOAT, colorFloat_.data());
  } else {
    colorBytes_.resize(values);
    glReadPixels(0, 0, settings_.width, settings_.height, GL_RGBA, GL_UNSIGNED_BYTE,
                 colorBytes_.data());
  }
  if (settings_.frameDepth) {
    depth_.resize(values / 4);
    glReadPixels(0, 0, settings_.width, settings_.height, GL_DEPTH_COMPONENT, GL_FLOAT,
                 depth_.data());
  }
}

void GlSceneRenderer::lastFrame(Frame& frame) const {
  frame.width = settings_.width;
  frame.height = settings_.height;
  if (settings_.framebuffer == PeerFramebuffer::Rgba32F) {
    frame.rgba = colorFloat_;
  } else {
    frame.rgba.resize(colorBytes_.size());
    for (std::size_t i = 0; i < colorBytes_.size(); ++i)
      frame.rgba[i] =
          i % 4 == 3 ? float(colorBytes_[i]) * kUnorm8Scale : srgb8ToLinear(colorBytes_[i]);
  }
  frame.depth = depth_;
  throwOnGlError("reading the frame back");
}

}  // namespace quadra
