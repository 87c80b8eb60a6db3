// The public Scene (include/quadra/scene.hpp): validates the embedder's
// arrays and turns them into the engine's Scene records, and quadra::api::load.
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

#include "api/public_scene.h"
#include "api/renderer.h"
#include "core/error.h"
#include "quadra/tbb.hpp"
#include "scene/gltf_loader.h"
#include "texture/image.h"
#include "texture/texel_format.h"

namespace quadra::api {

namespace {

// The attribute array `name`, `components` floats per vertex, as a vector of
// T (glm vectors): empty stays empty; any other length but V x components is
// an Error, so nothing reads past the embedder's array.
template <typename T>
std::vector<T> attribute(std::span<const float> values, std::size_t vertices, int components,
                         const char* name) {
  if (values.empty()) return {};
  if (values.size() != vertices * components)
    throw Error("mesh: " + std::string(name) + " hold " + std::to_string(values.size()) +
                " floats, " + std::to_string(vertices) + " vertices need " +
                std::to_string(vertices * components));
  std::vector<T> out(vertices);
  std::memcpy(out.data(), values.data(), values.size() * sizeof(float));
  return out;
}

template <typename Index>
std::vector<std::uint32_t> checkedIndices(std::span<const Index> indices, std::size_t vertices) {
  if (indices.size() % 3 != 0)
    throw Error("mesh: " + std::to_string(indices.size()) +
                " indices are not a whole number of triangles");
  std::vector<std::uint32_t> out(indices.begin(), indices.end());
  for (std::size_t i = 0; i < out.size(); ++i)
    if (out[i] >= vertices)
      throw Error("mesh: index " + std::to_string(out[i]) + " (entry " + std::to_string(i) +
                  ") is out of range for " + std::to_string(vertices) + " vertices");
  return out;
}

// The geometry of `data` as an engine mesh (material unset).
quadra::Mesh meshOf(const MeshData& data) {
  if (data.positions.size() % 3 != 0)
    throw Error("mesh: positions hold " + std::to_string(data.positions.size()) +
                " floats, not 3 per vertex");
  const std::size_t vertices = data.positions.size() / 3;
  if (data.indices32.empty() == data.indices16.empty())
    throw Error(data.indices32.empty() ? "mesh: no indices (give indices32 or indices16)"
                                       : "mesh: both indices32 and indices16 given");
  for (const float p : data.positions)
    if (!std::isfinite(p)) throw Error("mesh: a position is NaN or infinite");
  quadra::Mesh mesh;
  mesh.positions = attribute<glm::vec3>(data.positions, vertices, 3, "positions");
  mesh.normals = attribute<glm::vec3>(data.normals, vertices, 3, "normals");
  mesh.texcoords[0] = attribute<glm::vec2>(data.uvs, vertices, 2, "uvs");
  mesh.colors = attribute<glm::vec4>(data.colors, vertices, 4, "colors");
  mesh.indices = data.indices32.empty() ? checkedIndices(data.indices16, vertices)
                                        : checkedIndices(data.indices32, vertices);
  return mesh;
}

TexelFormat texelFormatOf(TextureFormat format) {
  switch (format) {
    case TextureFormat::Rgba8Srgb:
      return TexelFormat::Rgba8Srgb;
    case TextureFormat::Rgba8Unorm:
      return TexelFormat::Rgba8Unorm;
    case TextureFormat::Rgba16F:
      return TexelFormat::Rgba16F;
    case TextureFormat::Rgba32F:
      return TexelFormat::Rgba32F;
  }
  throw Error("texture: unknown format");
}

WrapMode wrapOf(Wrap wrap) {
  return wrap == Wrap::Repeat           ? WrapMode::Repeat
         : wrap == Wrap::MirroredRepeat ? WrapMode::MirroredRepeat
                                        : WrapMode::ClampToEdge;
}

// The texels decoded by the engine's own decoder for their format, and
// stored in that format again, so the texture samples the embedder's exact
// values (every format's decode-encode round trip is the identity).
std::shared_ptr<const Texture> textureOf(const TextureData& data) {
  if (data.width <= 0 || data.height <= 0)
    throw Error("texture: " + std::to_string(data.width) + "x" + std::to_string(data.height) +
                " texels; a texture needs at least one");
  if (std::int64_t(data.width) * data.height > kMaxImagePixels)
    throw Error("texture: " + std::to_string(data.width) + "x" + std::to_string(data.height) +
                " texels is over the limit of " + std::to_string(kMaxImagePixels));
  const TexelFormat format = texelFormatOf(data.format);
  const std::size_t rowBytes = std::size_t(data.width) * bytesPerTexel(format);
  const std::size_t stride = data.rowStride == 0 ? rowBytes : data.rowStride;
  if (stride < rowBytes)
    throw Error("texture: row stride " + std::to_string(stride) + " bytes is less than a row's " +
                std::to_string(rowBytes));
  const std::size_t needed = stride * (std::size_t(data.height) - 1) + rowBytes;
  if (data.texels.size() < needed)
    throw Error("texture: " + std::to_string(data.width) + "x" + std::to_string(data.height) +
                " texels need " + std::to_string(needed) + " bytes, the array has " +
                std::to_string(data.texels.size()));
  auto image = std::make_shared<Image>(data.width, data.height);
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(data.texels.data());
  for (int y = 0; y < data.height; ++y)
    for (int x = 0; x < data.width; ++x)
      decodeTexel(format, bytes + y * stride + std::size_t(x) * bytesPerTexel(format),
                  image->texel(x, y));
  SamplerState sampler;
  sampler.wrapU = wrapOf(data.wrapU);
  sampler.wrapV = wrapOf(data.wrapV);
  sampler.magLinear = data.filter != Filter::Nearest;
  sampler.minFilter = data.filter == Filter::Nearest     ? quadra::Filter::Nearest
                      : data.filter == Filter::Bilinear  ? quadra::Filter::Bilinear
                      : data.filter == Filter::Trilinear ? quadra::Filter::Trilinear
                                                         : quadra::Filter::Anisotropic;
  try {
    return std::make_shared<const Texture>(std::move(image), sampler, format);
  } catch (const quadra::Error& error) {
    throw Error(error.what());
  }
}

glm::mat4 matrixOf(const Matrix4& m, const char* what) {
  for (std::size_t i = 0; i < m.size(); ++i)
    if (!std::isfinite(m[i]))
      throw Error(std::string(what) + ": element " + std::to_string(i) + " (column " +
                  std::to_string(i / 4) + ", row " + std::to_string(i % 4) + ") is " +
                  (std::isnan(m[i]) ? "NaN" : "infinite"));
  glm::mat4 out;
  std::memcpy(&out[0][0], m.data(), sizeof(out));
  return out;
}

template <typename Handle>
std::size_t checkedIndex(Handle handle, std::size_t count, const char* what) {
  if (handle.index >= count)
    throw Error(std::string(what) + ": handle " + std::to_string(handle.index) +
                " is not one of this scene's " + std::to_string(count));
  return handle.index;
}

}  // namespace

Matrix4 lookAt(const std::array<float, 3>& eye, const std::array<float, 3>& target,
               const std::array<float, 3>& up) {
  const glm::mat4 world = lookAtWorld({eye[0], eye[1], eye[2]}, {target[0], target[1], target[2]},
                                      {up[0], up[1], up[2]});
  Matrix4 out;
  std::memcpy(out.data(), &world[0][0], sizeof(out));
  return out;
}

Scene::Scene() : impl_(std::make_unique<Impl>()) {
  impl_->scene.name = "in-memory scene";
}
Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

MeshHandle Scene::addMesh(const MeshData& data) {
  quadra::Mesh mesh = meshOf(data);
  impl_->scene.meshes.push_back(std::move(mesh));
  impl_->derived.push_back({int(impl_->scene.meshes.size() - 1)});
  impl_->drawn.push_back(false);
  return {std::uint32_t(impl_->derived.size() - 1)};
}

void Scene::updateMesh(MeshHandle handle, const MeshData& data) {
  const std::size_t index = checkedIndex(handle, impl_->derived.size(), "updateMesh");
  const quadra::Mesh geometry = meshOf(data);
  for (const int engineMesh : impl_->derived[index]) {
    quadra::Mesh& mesh = impl_->scene.meshes[engineMesh];
    const int material = mesh.material;
    mesh = geometry;
    mesh.material = material;
  }
}

TextureHandle Scene::addTexture(const TextureData& data) {
  impl_->scene.textures.push_back(textureOf(data));
  return {std::uint32_t(impl_->scene.textures.size() - 1)};
}

void Scene::updateTexture(TextureHandle handle, const TextureData& data) {
  const std::size_t index = checkedIndex(handle, impl_->scene.textures.size(), "updateTexture");
  impl_->scene.textures[index] = textureOf(data);
}

MaterialHandle Scene::addMaterial(const MaterialData& data) {
  quadra::Material material;
  for (int c = 0; c < 4; ++c) {
    if (!std::isfinite(data.baseColor[c]))
      throw Error("material: base colour component " + std::to_string(c) + " is not finite");
    material.baseColorFactor[c] = data.baseColor[c];
  }
  if (data.texture)
    material.baseColorTexture =
        int(checkedIndex(*data.texture, impl_->scene.textures.size(), "material texture"));
  material.alphaMode = data.alphaMode == AlphaMode::Opaque ? quadra::AlphaMode::Opaque
                       : data.alphaMode == AlphaMode::Mask ? quadra::AlphaMode::Mask
                                                           : quadra::AlphaMode::Blend;
  if (!std::isfinite(data.alphaCutoff)) throw Error("material: alpha cutoff is not finite");
  material.alphaCutoff = data.alphaCutoff;
  material.doubleSided = data.doubleSided;
  impl_->scene.materials.push_back(material);
  return {std::uint32_t(impl_->scene.materials.size() - 1)};
}

InstanceHandle Scene::addInstance(MeshHandle meshHandle, MaterialHandle materialHandle,
                                  const Matrix4& transform) {
  const std::size_t mesh = checkedIndex(meshHandle, impl_->derived.size(), "addInstance mesh");
  const int material =
      int(checkedIndex(materialHandle, impl_->scene.materials.size(), "addInstance material"));
  const glm::mat4 world = matrixOf(transform, "instance transform");
  std::vector<int>& derived = impl_->derived[mesh];
  int engineMesh = -1;
  if (!impl_->drawn[mesh]) {
    engineMesh = derived[0];
    impl_->scene.meshes[engineMesh].material = material;
    impl_->drawn[mesh] = true;
  } else {
    for (const int candidate : derived)
      if (impl_->scene.meshes[candidate].material == material) engineMesh = candidate;
    if (engineMesh < 0) {  // a new material for this mesh: a copy of its geometry
      quadra::Mesh copy = impl_->scene.meshes[derived[0]];
      copy.material = material;
      impl_->scene.meshes.push_back(std::move(copy));
      engineMesh = int(impl_->scene.meshes.size() - 1);
      derived.push_back(engineMesh);
    }
  }
  quadra::Instance instance;
  instance.mesh = engineMesh;
  instance.world = world;
  impl_->scene.instances.push_back(std::move(instance));
  return {std::uint32_t(impl_->scene.instances.size() - 1)};
}

void Scene::setTransform(InstanceHandle handle, const Matrix4& transform) {
  const std::size_t index = checkedIndex(handle, impl_->scene.instances.size(), "setTransform");
  impl_->scene.instances[index].world = matrixOf(transform, "instance transform");
}

void Scene::setDrawState(InstanceHandle handle, const std::optional<DrawStateData>& data) {
  const std::size_t index = checkedIndex(handle, impl_->scene.instances.size(), "setDrawState");
  std::optional<quadra::DrawState> state;
  if (data) {
    // An enum value cast from a number outside it would index past the
    // kernels' tables.
    const auto check = [](int value, int last, const char* what) {
      if (value < 0 || value > last)
        throw Error("setDrawState: " + std::string(what) + " " + std::to_string(value) +
                    " is not one of its values");
    };
    const BlendData& b = data->blend;
    check(int(data->depthCompare), int(CompareFunction::Always), "depthCompare");
    check(int(data->cull), int(CullMode::Front), "cull");
    check(int(b.colorEquation), int(BlendEquation::Max), "blend.colorEquation");
    check(int(b.alphaEquation), int(BlendEquation::Max), "blend.alphaEquation");
    for (const auto& [factor, name] :
         {std::pair{b.srcColor, "blend.srcColor"}, std::pair{b.dstColor, "blend.dstColor"},
          std::pair{b.srcAlpha, "blend.srcAlpha"}, std::pair{b.dstAlpha, "blend.dstAlpha"}})
      check(int(factor), int(BlendFactor::OneMinusDstAlpha), name);
    // The public enums list the engine's in the same order (static_asserts
    // below), so each converts by value.
    state.emplace();
    state->depthTest = data->depthTest;
    state->depthWrite = data->depthWrite;
    state->depthCompare = quadra::CompareFunction(data->depthCompare);
    state->cull = quadra::CullMode(data->cull);
    const BlendData& blend = data->blend;
    state->blend = {blend.enabled,
                    quadra::BlendEquation(blend.colorEquation),
                    quadra::BlendEquation(blend.alphaEquation),
                    quadra::BlendFactor(blend.srcColor),
                    quadra::BlendFactor(blend.dstColor),
                    quadra::BlendFactor(blend.srcAlpha),
                    quadra::BlendFactor(blend.dstAlpha)};
  }
  impl_->scene.instances[index].drawState = state;
}

static_assert(int(CompareFunction::Never) == int(quadra::CompareFunction::Never) &&
              int(CompareFunction::Less) == int(quadra::CompareFunction::Less) &&
              int(CompareFunction::Equal) == int(quadra::CompareFunction::Equal) &&
              int(CompareFunction::LessEqual) == int(quadra::CompareFunction::LessEqual) &&
              int(CompareFunction::Greater) == int(quadra::CompareFunction::Greater) &&
              int(CompareFunction::NotEqual) == int(quadra::CompareFunction::NotEqual) &&
              int(CompareFunction::GreaterEqual) == int(quadra::CompareFunction::GreaterEqual) &&
              int(CompareFunction::Always) == int(quadra::CompareFunction::Always));
static_assert(int(CullMode::None) == int(quadra::CullMode::None) &&
              int(CullMode::Back) == int(quadra::CullMode::Back) &&
              int(CullMode::Front) == int(quadra::CullMode::Front));
static_assert(int(BlendEquation::Add) == int(quadra::BlendEquation::Add) &&
              int(BlendEquation::Subtract) == int(quadra::BlendEquation::Subtract) &&
              int(BlendEquation::ReverseSubtract) == int(quadra::BlendEquation::ReverseSubtract) &&
              int(BlendEquation::Min) == int(quadra::BlendEquation::Min) &&
              int(BlendEquation::Max) == int(quadra::BlendEquation::Max));
static_assert(int(BlendFactor::Zero) == int(quadra::BlendFactor::Zero) &&
              int(BlendFactor::One) == int(quadra::BlendFactor::One) &&
              int(BlendFactor::SrcColor) == int(quadra::BlendFactor::SrcColor) &&
              int(BlendFactor::OneMinusSrcColor) == int(quadra::BlendFactor::OneMinusSrcColor) &&
              int(BlendFactor::DstColor) == int(quadra::BlendFactor::DstColor) &&
              int(BlendFactor::OneMinusDstColor) == int(quadra::BlendFactor::OneMinusDstColor) &&
              int(BlendFactor::SrcAlpha) == int(quadra::BlendFactor::SrcAlpha) &&
              int(BlendFactor::OneMinusSrcAlpha) == int(quadra::BlendFactor::OneMinusSrcAlpha) &&
              int(BlendFactor::DstAlpha) == int(quadra::BlendFactor::DstAlpha) &&
              int(BlendFactor::OneMinusDstAlpha) == int(quadra::BlendFactor::OneMinusDstAlpha));

void Scene::setCamera(const CameraData& data) {
  quadra::Camera camera;
  camera.type = data.projection == CameraData::Projection::Perspective
                    ? quadra::Camera::Type::Perspective
                    : quadra::Camera::Type::Orthographic;
  const bool perspective = camera.type == quadra::Camera::Type::Perspective;
  if (perspective && !(data.yfov > 0.0f && data.yfov < 3.14159f))
    throw Error("camera: yfov " + std::to_string(data.yfov) + " is not in (0, pi) radians");
  if (!perspective && !(data.ymag > 0.0f && std::isfinite(data.ymag)))
    throw Error("camera: ymag " + std::to_string(data.ymag) + " is not positive");
  if (!(data.znear > 0.0f && std::isfinite(data.znear)))
    throw Error("camera: znear " + std::to_string(data.znear) + " is not positive");
  if (!std::isfinite(data.zfar) || (data.zfar != 0.0f && data.zfar <= data.znear) ||
      (!perspective && data.zfar == 0.0f))
    throw Error("camera: zfar " + std::to_string(data.zfar) + " is not beyond znear" +
                (perspective ? " (or 0 for infinite)" : ""));
  camera.yfov = data.yfov;
  camera.xmag = camera.ymag = data.ymag;
  camera.znear = data.znear;
  camera.zfar = data.zfar;
  camera.world = matrixOf(data.world, "camera world");
  impl_->camera = camera;
}

std::size_t Scene::meshCount() const {
  return impl_->derived.size();
}
std::size_t Scene::instanceCount() const {
  return impl_->scene.instances.size();
}

namespace {
std::size_t checkedAnimation(int animation, const quadra::Scene& scene, const char* call,
                             bool restAllowed) {
  const int count = int(scene.animations.size());
  if (animation < (restAllowed ? -1 : 0) || animation >= count)
    throw Error(std::string(call) + ": animation " + std::to_string(animation) +
                " is not one of the scene's " + std::to_string(count) +
                (restAllowed ? " (or -1, the rest pose)" : ""));
  return std::size_t(animation);
}
}  // namespace

int Scene::animationCount() const {
  return int(impl_->scene.animations.size());
}
std::string Scene::animationName(int animation) const {
  return impl_->scene.animations[checkedAnimation(animation, impl_->scene, "animationName", false)]
      .name;
}
double Scene::animationDuration(int animation) const {
  return quadra::animationDuration(impl_->scene.animations[checkedAnimation(
      animation, impl_->scene, "animationDuration", false)]);
}

void Scene::setAnimationTime(int animation, double seconds) {
  checkedAnimation(animation, impl_->scene, "setAnimationTime", true);
  if (!std::isfinite(seconds))
    throw Error("setAnimationTime: seconds " + std::to_string(seconds) + " is not finite");
  Impl& impl = *impl_;
  // Framed before the first pose moves anything, as the CLI frames a sequence.
  if (!impl.camera && impl.scene.cameras.empty()) impl.camera = defaultCamera(impl.scene);
  poseNodes(impl.scene, animation, seconds, impl.pose);
  placeOnNodes(impl.scene, impl.pose);
}

namespace {
Scene loadWith(const std::string& path, const LoadOptions& options, TaskArena* arena) {
  if (options.scene < -1)
    throw Error(path + ": scene " + std::to_string(options.scene) +
                " is not a scene index (or -1, the file's default)");
  quadra::LoadOptions engine;
  engine.allowedPaths = options.allowedPaths;
  engine.maxMemory = options.maxMemory;
  engine.sceneIndex = options.scene;
  engine.arena = arena;
  Scene scene;
  try {
    detail::SceneAccess::mutableOf(scene).scene = loadGltf(path, engine);
  } catch (const quadra::Error& error) {  // the engine's, as the public type
    throw Error(error.what());
  } catch (const std::logic_error& error) {  // a failed internal check (core/error.h)
    throw Error(std::string("quadra: ") + error.what());
  }
  return scene;
}
}  // namespace
static_assert(kDefaultMaxMemory == quadra::kDefaultMaxMemory, "the CLI's default budget");

Scene load(const std::string& path, const LoadOptions& options) {
  return loadWith(path, options, nullptr);
}

Scene loadIn(const std::string& path, tbb::task_arena& arena, const LoadOptions& options) {
  return loadWith(path, options, &arena);
}

}  // namespace quadra::api
