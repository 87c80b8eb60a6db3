// Uploading a Scene to OpenGL and drawing it as quadra does (see
// gl_scene_renderer.h).
#define GL_GLEXT_PROTOTYPES 1
#include "gl_scene_renderer.h"

#include <GL/glext.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "api/camera.h"
#include "api/renderer.h"
#include "core/error.h"
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

void throwOnGlError(const char* what) {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", unsigned(error));
  throw Error(std::string("llvmpipe: OpenGL error ") + code + " while " + what);
}

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

GLuint compileShader(GLenum stage, const std::string& defines, const char* body) {
  const std::string source = "#version 330 core\n" + defines + body;
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[512] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    std::string line(log);
    std::replace(line.begin(), line.end(), '\n', ' ');
    throw Error("llvmpipe: shader does not compile: " + line);
  }
  return shader;
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
    if (const VertexDeformer deformer(mesh, instance); deformer.active()) {
      std::vector<glm::vec3> posed(mesh.positions.size());
      for (std::size_t i = 0; i < posed.size(); ++i)
        posed[i] = deformer.position(i, deformer.skinMatrix(i));
      uploadMesh(mesh, posed, texcoordSet, vertexColor, posedMeshes_.emplace_back());
      draw.mesh = &posedMeshes_.back();
    } else {
      if (!uploaded[m]) {
        uploadMesh(mesh, mesh.positions, texcoordSet, vertexColor, meshes_[m]);
        uploaded[m] = true;
      }
      draw.mesh = &meshes_[m];
    }
    draw.program = &programFor(textured, vertexColor, material.alphaMode);
    if (textured) {
      const Texture& texture = scene.textures.at(std::size_t(material.baseColorTexture))
                                   ->forAlpha(textureAlphaOf(material));
      auto [slot, added] = textures_.try_emplace(&texture, 0);
      if (added) slot->second = uploadTexture(texture);
      draw.texture = slot->second;
      draw.premultipliedTexture = texture.alpha().premultiplied();
      draw.uvTransform = material.baseColorTransform.matrix();
    }
    draw.baseColor = material.baseColorFactor;
    draw.alphaCutoff = material.alphaCutoff;
    draw.cull = !material.doubleSided;
    draw.frontClockwise = glm::determinant(glm::mat3(instance.world)) < 0.0f;
    draw.blend = material.alphaMode == AlphaMode::Blend;
    draws_.push_back(draw);
  }
  throwOnGlError("uploading meshes and textures");

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glCullFace(GL_BACK);
  // quadra's "over": colour = src * a + dst * (1 - a) with the shaded
  // (straight) colour as src, alpha = a + dst_a * (1 - a): premultiplied out.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glViewport(0, 0, settings.width, settings.height);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClearDepth(1.0);
}

GlSceneRenderer::~GlSceneRenderer() {
  const auto release = [](const MeshBuffers& mesh) {
    glDeleteVertexArrays(1, &mesh.vertexArray);
    glDeleteBuffers(4, mesh.buffers);
  };
  for (const MeshBuffers& mesh : meshes_) release(mesh);
  for (const MeshBuffers& mesh : posedMeshes_) release(mesh);
  for (const auto& [texture, id] : textures_) glDeleteTextures(1, &id);
  for (const auto& [variant, program] : programs_) glDeleteProgram(program.id);
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
  const int variant = int(textured) | int(vertexColor) << 1 | int(alphaMode) << 2;
  if (const auto found = programs_.find(variant); found != programs_.end()) return found->second;
  std::string defines;
  if (textured) defines += "#define TEXTURED\n";
  if (vertexColor) defines += "#define VERTEX_COLOR\n";
  if (alphaMode == AlphaMode::Mask) defines += "#define ALPHA_MASK\n";
  if (alphaMode == AlphaMode::Blend) defines += "#define ALPHA_BLEND\n";
  const GLuint vertex = compileShader(GL_VERTEX_SHADER, defines, kVertexShader);
  const GLuint fragment = compileShader(GL_FRAGMENT_SHADER, defines, kFragmentShader);
  Program program;
  program.id = glCreateProgram();
  glAttachShader(program.id, vertex);
  glAttachShader(program.id, fragment);
  glLinkProgram(program.id);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program.id, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) throw Error("llvmpipe: shader program does not link");
  program.clipFromModel = glGetUniformLocation(program.id, "clipFromModel");
  program.baseColor = glGetUniformLocation(program.id, "baseColor");
  program.alphaCutoff = glGetUniformLocation(program.id, "alphaCutoff");
  program.premultipliedTexture = glGetUniformLocation(program.id, "premultipliedTexture");
  program.uvTransform = glGetUniformLocation(program.id, "uvTransform");
  glUseProgram(program.id);
  glUniform1i(glGetUniformLocation(program.id, "baseColorTexture"), 0);
  return programs_.emplace(variant, program).first->second;
}

void GlSceneRenderer::uploadMesh(const Mesh& mesh, std::span<const glm::vec3> positions,
                                 int texcoordSet, bool vertexColor, MeshBuffers& out) {
  glGenVertexArrays(1, &out.vertexArray);
  glBindVertexArray(out.vertexArray);
  glGenBuffers(4, out.buffers);
  const auto attribute = [&](int slot, GLint components, GLsizeiptr bytes, const void* data) {
    glBindBuffer(GL_ARRAY_BUFFER, out.buffers[slot]);
    glBufferData(GL_ARRAY_BUFFER, bytes, data, GL_STATIC_DRAW);
    glVertexAttribPointer(GLuint(slot), components, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(GLuint(slot));
  };
  attribute(0, 3, GLsizeiptr(positions.size() * sizeof(glm::vec3)), positions.data());
  const std::vector<glm::vec2>& texcoords = mesh.texcoords[texcoordSet];
  if (!texcoords.empty())
    attribute(1, 2, GLsizeiptr(texcoords.size() * sizeof(glm::vec2)), texcoords.data());
  if (vertexColor)
    attribute(2, 4, GLsizeiptr(mesh.colors.size() * sizeof(glm::vec4)), mesh.colors.data());
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, out.buffers[3]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STATIC_DRAW);
  out.indexCount = GLsizei(mesh.indices.size());
  glBindVertexArray(0);
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
  glUseProgram(state.program->id);
  glUniformMatrix4fv(state.program->clipFromModel, 1, GL_FALSE, &clipFromModel[0][0]);
  glUniform4fv(state.program->baseColor, 1, &state.baseColor[0]);
  glUniform1f(state.program->alphaCutoff, state.alphaCutoff);
  glUniform1i(state.program->premultipliedTexture, state.premultipliedTexture ? 1 : 0);
  if (state.program->uvTransform >= 0)
    glUniformMatrix3x2fv(state.program->uvTransform, 1, GL_FALSE, &state.uvTransform[0][0]);
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
  if (state.texture) glBindTexture(GL_TEXTURE_2D, state.texture);
  glBindVertexArray(state.mesh->vertexArray);
  glDrawElements(GL_TRIANGLES, state.mesh->indexCount, GL_UNSIGNED_INT, nullptr);
}

void GlSceneRenderer::render(const Camera& camera) {
  const glm::mat4 view = viewMatrix(camera);
  const glm::mat4 projection = projectionMatrix(camera, double(settings_.width) / settings_.height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glDepthMask(GL_TRUE);  // glClear honours the depth mask
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
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
