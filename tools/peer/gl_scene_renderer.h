// quadra's unlit frame drawn with OpenGL 4.5 on llvmpipe: the peer's
// counterpart of Renderer::render, so that the two are timed on the same
// work. The same camera (api/camera.h matrices, clip depth [0, 1] through
// glClipControl), the same draws in the same order (instanceDrawOrder), the
// same shading: baseColorFactor x baseColorTexture (decoded to linear before
// filtering) x COLOR_0; OPAQUE writes alpha 1, MASK discards below the
// cutoff, BLEND composites premultiplied "over" without writing depth; single
// sided materials cull back faces, mirrored instances flip the winding. Each
// texture is filtered as its glTF sampler says (or as --filter says), with
// GL's own mip chain, into a float RGBA + 32-bit float depth framebuffer.
#pragma once

#include <GL/gl.h>

#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "io/frame.h"
#include "scene/scene.h"
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
};

// The filters llvmpipe has: nearest, bilinear, nearest-mip, trilinear, aniso.
bool peerSupportsFilter(Filter filter);

class GlSceneRenderer {
 public:
  // Uploads the scene's meshes and textures (with their mip chains) and
  // compiles the shaders it needs; `scene` must outlive the renderer.
  // Throws Error on any OpenGL failure.
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

 private:
  struct Program {
    GLuint id = 0;
    GLint clipFromModel = -1, baseColor = -1, alphaCutoff = -1, premultipliedTexture = -1,
          uvTransform = -1;
  };
  struct MeshBuffers {
    GLuint vertexArray = 0;
    GLuint buffers[4] = {};  // positions, texture coordinates, colours, indices
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
  };

  const Program& programFor(bool textured, bool vertexColor, AlphaMode alphaMode);
  // positions: the mesh's own, or an instance's posed ones.
  void uploadMesh(const Mesh& mesh, std::span<const glm::vec3> positions, int texcoordSet,
                  bool vertexColor, MeshBuffers& out);
  GLuint uploadTexture(const Texture& texture);
  // A colour + DEPTH32F framebuffer of the frame's size at `samples` per pixel.
  void makeFramebuffer(GLenum colorFormat, int samples, GLuint& framebuffer, GLuint& color,
                       GLuint& depth) const;
  void draw(const DrawState& state, const glm::mat4& clipFromModel) const;

  const Scene& scene_;
  PeerSettings settings_;
  GLuint framebuffer_ = 0, colorBuffer_ = 0, depthBuffer_ = 0;
  // With samples > 1: the single-sample framebuffer the frame resolves into.
  GLuint resolveFramebuffer_ = 0, resolveColor_ = 0, resolveDepth_ = 0;
  std::map<int, Program> programs_;
  std::vector<MeshBuffers> meshes_;  // one per scene mesh
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
};

}  // namespace quadra
