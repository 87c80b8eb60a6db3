// quadra's frame drawn with OpenGL 4.5 on llvmpipe: the peer's counterpart
// of Renderer::render, so that the two are timed on the same work. The same
// camera (api/camera.h matrices, clip depth [0, 1] through glClipControl),
// the same draws in the same order (instanceDrawOrder). Unlit, the same
// shading: baseColorFactor x baseColorTexture (decoded to linear before
// filtering) x COLOR_0; OPAQUE writes alpha 1, MASK discards below the
// cutoff, BLEND composites premultiplied "over" without writing depth; single
// sided materials cull back faces, mirrored instances flip the winding. Each
// texture is filtered as its glTF sampler says (or as --filter says), with
// GL's own mip chain, into a float RGBA + 32-bit float depth framebuffer.
// Pbr: glTF's metallic-roughness material (LIGHTING.md) lit as the Khronos
// glTF Sample Viewer lights it, split-sum image-based lighting from
// gl_environment.h plus the KHR_lights_punctual lights, no shadows.
#pragma once

#include <GL/gl.h>

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "api/renderer.h"
#include "gl_environment.h"
#include "io/frame.h"
#include "io/tone_map.h"
#include "scene/scene.h"
#include "shading/environment_image.h"
#include "shading/lighting.h"
#include "texture/sampler_state.h"
#include "texture/texel_format.h"

namespace quadra {

class OsMesaContext;

// The colour buffer llvmpipe draws into. Rgba32F holds what quadra's Frame
// holds (premultiplied linear float), so the two images compare exactly;
// Srgba8 is llvmpipe's cheapest target (4 bytes a pixel, blending in linear
// through GL_FRAMEBUFFER_SRGB), for measuring what the float target costs it.
enum class PeerFramebuffer : std::uint8_t { Rgba32F, Srgba8 };

struct PeerSettings {
  int width = 1920;
  int height = 1080;
  std::optional<Filter> filter;  // unset: each texture's glTF sampler decides
  int maxAniso = 16;
  float lodBias = 0.0f;
  // Unset: as quadra stores it by default (quadra's loader's choice).
  std::optional<TexelFormat> textureFormat;
  PeerFramebuffer framebuffer = PeerFramebuffer::Rgba32F;
  // Read depth back with every frame too, as quadra resolves it with every
  // frame whose output has a Z channel (RenderSettings::frameDepth).
  bool frameDepth = false;
  // Multisampling (MSAA) as a GL application has it, to set beside quadra's
  // --samples: above 1, coverage and depth per sample in a multisampled
  // framebuffer, shaded once per pixel and triangle, and resolved by
  // glBlitFramebuffer (colour: the samples' mean; depth: the
  // implementation's choice of a sample) before the read-back.
  int samples = 1;
  // Unlit or Pbr. Pbr reads the rest, each as RenderSettings means it:
  // the environment (required; it must outlive the renderer), its rotation
  // and intensity, the background, the punctual lights and the exposure
  // (the frame holds radiance x 2^exposure, as for unlit frames). An Srgba8
  // pbr frame is tone mapped by `toneMap` in the shader, then sRGB encoded.
  Shading shading = Shading::Unlit;
  const EnvironmentImage* environment = nullptr;
  float environmentRotation = 0.0f;
  float environmentIntensity = 1.0f;
  Background background = Background::Environment;
  glm::vec4 clearColor{0.0f};
  bool punctualLights = true;
  float exposure = 0.0f;
  ToneMap toneMap = ToneMap::PbrNeutral;
  // The prepared environment's cube face and GGX table sizes (GlEnvironment).
  int iblSize = GlEnvironment::kCubeSize;
  int lutSize = GlEnvironment::kLutSize;
};

// The filters llvmpipe has: nearest, bilinear, nearest-mip, trilinear, aniso.
bool peerSupportsFilter(Filter filter);

class GlSceneRenderer {
 public:
  // Uploads the scene's meshes and textures (with their mip chains) and
  // compiles the shaders it needs, and for pbr prepares the environment
  // (timed: prepareMs); `scene` must outlive the renderer. Throws Error on
  // any OpenGL failure.
  GlSceneRenderer(const OsMesaContext& context, const Scene& scene, const PeerSettings& settings);
  ~GlSceneRenderer();
  GlSceneRenderer(const GlSceneRenderer&) = delete;
  GlSceneRenderer& operator=(const GlSceneRenderer&) = delete;

  // Draws one frame and reads its colour (and with frameDepth its depth) back
  // into memory, so it returns once llvmpipe has finished the frame
  // (quadra's frame time also ends with the frame in memory).
  void render(const Camera& camera);
  // The last frame as quadra's Frame holds it: premultiplied linear RGBA
  // float and, with frameDepth, window depth in [0, 1]; row 0 at the top.
  void lastFrame(Frame& frame) const;
  // The environment's preparation (gl_environment.h, until llvmpipe has
  // finished it), in milliseconds; 0 for unlit frames.
  double prepareMs() const { return prepareMs_; }

 private:
  // The material textures a pbr draw reads, in their texture units.
  enum LitTexture {
    kBaseColor,
    kMetallicRoughness,
    kNormal,
    kOcclusion,
    kEmissive,
    kSpecular,
    kSpecularColor,
    kLitTextures
  };
  struct Program {
    GLuint id = 0;
    GLint clipFromModel = -1, baseColor = -1, alphaCutoff = -1, premultipliedTexture = -1,
          uvTransform = -1;
    // Pbr's own.
    GLint worldFromModel = -1, normalFromModel = -1, uvSet = -1, metallicRoughness = -1,
          normalScale = -1, occlusionStrength = -1, emission = -1, dielectricF0 = -1,
          specularFactor = -1, specularColorFactor = -1;
  };
  struct MeshBuffers {
    GLuint vertexArray = 0;
    // Attributes 0-5: positions, texture coordinates (unlit: the base
    // colour's set; pbr: TEXCOORD_0), colours, normals, tangents,
    // TEXCOORD_1; then the indices.
    GLuint buffers[7] = {};
    GLsizei indexCount = 0;
  };
  struct DrawState {
    const MeshBuffers* mesh = nullptr;
    const Program* program = nullptr;
    GLuint texture = 0;                 // 0: untextured
    bool premultipliedTexture = false;  // its levels hold rgb·a, as quadra's (texture/texture.h)
    glm::mat3x2 uvTransform{1.0f};
    glm::vec4 baseColor{1.0f};
    float alphaCutoff = 0.5f;
    bool cull = true, frontClockwise = false, blend = false;
    // Pbr's own: every material texture (0: none) with its set and
    // transform, and the material's factors.
    GLuint litTextures[kLitTextures] = {};
    GLint uvSet[kLitTextures] = {};
    glm::mat3x2 uvTransforms[kLitTextures];
    glm::mat4 worldFromModel{1.0f};
    glm::mat3 normalFromModel{1.0f};
    glm::vec2 metallicRoughness{1.0f};
    float normalScale = 1.0f, occlusionStrength = 1.0f;
    glm::vec3 emission{0.0f};
    float dielectricF0 = 0.04f, specularFactor = 1.0f;
    glm::vec3 specularColorFactor{1.0f};
  };
  // The vertices a draw reads: the mesh's own or an instance's posed ones.
  struct Vertices {
    std::span<const glm::vec3> positions, normals;
    std::span<const glm::vec4> tangents;
  };

  const Program& programFor(bool textured, bool vertexColor, AlphaMode alphaMode);
  // `defines`: the pbr variant (which textures and attributes it reads).
  const Program& litProgramFor(const std::string& defines);
  // Unlit: the texcoordSet's coordinates; pbr (lit): both sets, normals and tangents.
  void uploadMesh(const Mesh& mesh, const Vertices& vertices, int texcoordSet, bool vertexColor,
                  bool lit, MeshBuffers& out);
  GLuint uploadTexture(const Texture& texture);
  GLuint textureFor(const Texture& texture);
  DrawState litDrawState(const Mesh& mesh, const Material& material, const Instance& instance,
                         std::string& defines);
  void drawBackground(const glm::mat4& clipFromWorld) const;
  // A colour + DEPTH32F framebuffer of the frame's size at `samples` per pixel.
  void makeFramebuffer(GLenum colorFormat, int samples, GLuint& framebuffer, GLuint& color,
                       GLuint& depth) const;
  void draw(const DrawState& state, const glm::mat4& clipFromModel) const;
  // The pbr frame's uniforms (camera, light) on every lit program.
  void setLitFrameUniforms(const glm::vec3& eye) const;

  const Scene& scene_;
  PeerSettings settings_;
  GLuint framebuffer_ = 0, colorBuffer_ = 0, depthBuffer_ = 0;
  // With samples > 1: the single-sample framebuffer the frame resolves into.
  GLuint resolveFramebuffer_ = 0, resolveColor_ = 0, resolveDepth_ = 0;
  std::map<std::string, Program> programs_;  // by variant
  std::vector<MeshBuffers> meshes_;          // one per scene mesh
  // One per skinned or morphed instance, its vertices posed as quadra's
  // vertex stage poses them (scene/deformation.h); a deque, so that the
  // draws' pointers stay valid as it grows.
  std::deque<MeshBuffers> posedMeshes_;
  // One per texture variant the materials read (Texture::forAlpha).
  std::map<const Texture*, GLuint> textures_;
  std::vector<DrawState> draws_;          // one per scene instance
  std::vector<float> colorFloat_;         // the last frame read back, Rgba32F
  std::vector<std::uint8_t> colorBytes_;  // the last frame read back, Srgba8
  std::vector<float> depth_;              // the last frame's depth, with frameDepth
  // Pbr: the prepared environment, the background's program, the scene's
  // lights as the engine records them, and the time the preparation took.
  std::unique_ptr<GlEnvironment> environment_;
  GLuint backgroundProgram_ = 0, emptyVertexArray_ = 0;
  std::vector<PunctualLight> lights_;
  double prepareMs_ = 0.0;
};

}  // namespace quadra
