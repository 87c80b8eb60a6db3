// The C API (include/quadra/quadra.h) over the public C++ one: handles are
// the C++ objects, every call catches what C++ throws and turns it into a
// status and this thread's last error message.
#include <cstring>
#include <new>
#include <string>

#include "quadra/quadra.h"
#include "quadra/quadra.hpp"

struct quadra_scene {
  quadra::api::Scene scene;
};
struct quadra_renderer {
  quadra::api::Renderer renderer;
};

namespace {

namespace api = quadra::api;

// Per thread, so that concurrent callers each read their own failure.
thread_local std::string lastError;

// Runs body, mapping every exception to a status and a message.
template <typename Body>
quadra_status guarded(Body&& body) {
  try {
    body();
    return QUADRA_OK;
  } catch (const api::Error& error) {
    lastError = error.what();
    return QUADRA_INVALID_ARGUMENT;
  } catch (const std::bad_alloc&) {
    lastError = "out of memory";
    return QUADRA_OUT_OF_MEMORY;
  } catch (const std::exception& error) {
    lastError = error.what();
    return QUADRA_FAILED;
  }
}

quadra_status missing(const char* what) {
  lastError = std::string(what) + " is NULL";
  return QUADRA_INVALID_ARGUMENT;
}

template <typename T>
std::span<const T> span(const T* data, std::size_t count) {
  return data ? std::span<const T>(data, count) : std::span<const T>();
}

api::MeshData meshOf(const quadra_mesh_data& m) {
  if (!m.positions) throw api::Error("mesh: positions is NULL");
  return {.positions = span(m.positions, m.vertex_count * 3),
          .normals = span(m.normals, m.vertex_count * 3),
          .uvs = span(m.uvs, m.vertex_count * 2),
          .colors = span(m.colors, m.vertex_count * 4),
          .indices32 = span(m.indices32, m.index_count),
          .indices16 = span(m.indices16, m.index_count)};
}

api::TextureData textureOf(const quadra_texture_data& t) {
  if (t.format < QUADRA_TEXTURE_RGBA8_SRGB || t.format > QUADRA_TEXTURE_RGBA32F)
    throw api::Error("texture: unknown format " + std::to_string(int(t.format)));
  return {.width = t.width,
          .height = t.height,
          .format = api::TextureFormat(t.format),
          .texels = std::span(static_cast<const std::byte*>(t.texels), t.texels ? t.size_bytes : 0),
          .rowStride = t.row_stride,
          .wrapU = api::Wrap(t.wrap_u),
          .wrapV = api::Wrap(t.wrap_v),
          .filter = api::Filter(t.filter)};
}

api::Matrix4 matrixOf(const float* m) {
  api::Matrix4 out = api::kIdentity;
  if (m) std::memcpy(out.data(), m, sizeof(out));
  return out;
}

}  // namespace

extern "C" {

const char* quadra_version(void) {
  return quadra::version();
}

const char* quadra_last_error(void) {
  return lastError.c_str();
}

quadra_status quadra_scene_create(quadra_scene** out) {
  if (!out) return missing("quadra_scene_create: out");
  return guarded([&] { *out = new quadra_scene{}; });
}

quadra_status quadra_scene_load(const char* path, quadra_scene** out) {
  if (!path) return missing("quadra_scene_load: path");
  if (!out) return missing("quadra_scene_load: out");
  return guarded([&] { *out = new quadra_scene{api::load(path)}; });
}

void quadra_scene_destroy(quadra_scene* scene) {
  delete scene;
}

quadra_status quadra_scene_add_mesh(quadra_scene* scene, const quadra_mesh_data* mesh,
                                    uint32_t* out_mesh) {
  if (!scene || !mesh || !out_mesh) return missing("quadra_scene_add_mesh: an argument");
  return guarded([&] { *out_mesh = scene->scene.addMesh(meshOf(*mesh)).index; });
}

quadra_status quadra_scene_update_mesh(quadra_scene* scene, uint32_t mesh,
                                       const quadra_mesh_data* data) {
  if (!scene || !data) return missing("quadra_scene_update_mesh: an argument");
  return guarded([&] { scene->scene.updateMesh({mesh}, meshOf(*data)); });
}

quadra_status quadra_scene_add_texture(quadra_scene* scene, const quadra_texture_data* texture,
                                       uint32_t* out_texture) {
  if (!scene || !texture || !out_texture) return missing("quadra_scene_add_texture: an argument");
  return guarded([&] { *out_texture = scene->scene.addTexture(textureOf(*texture)).index; });
}

quadra_status quadra_scene_update_texture(quadra_scene* scene, uint32_t texture,
                                          const quadra_texture_data* data) {
  if (!scene || !data) return missing("quadra_scene_update_texture: an argument");
  return guarded([&] { scene->scene.updateTexture({texture}, textureOf(*data)); });
}

quadra_status quadra_scene_add_material(quadra_scene* scene, const quadra_material_data* material,
                                        uint32_t* out_material) {
  if (!scene || !material || !out_material)
    return missing("quadra_scene_add_material: an argument");
  return guarded([&] {
    if (material->alpha_mode < QUADRA_ALPHA_OPAQUE || material->alpha_mode > QUADRA_ALPHA_BLEND)
      throw api::Error("material: unknown alpha mode " + std::to_string(int(material->alpha_mode)));
    api::MaterialData data;
    std::memcpy(data.baseColor.data(), material->base_color, sizeof(material->base_color));
    if (material->has_texture) data.texture = api::TextureHandle{material->texture};
    data.alphaMode = api::AlphaMode(material->alpha_mode);
    data.alphaCutoff = material->alpha_cutoff;
    data.doubleSided = material->double_sided != 0;
    *out_material = scene->scene.addMaterial(data).index;
  });
}

quadra_status quadra_scene_add_instance(quadra_scene* scene, uint32_t mesh, uint32_t material,
                                        const float* transform, uint32_t* out_instance) {
  if (!scene || !out_instance) return missing("quadra_scene_add_instance: an argument");
  return guarded([&] {
    *out_instance = scene->scene.addInstance({mesh}, {material}, matrixOf(transform)).index;
  });
}

quadra_status quadra_scene_set_transform(quadra_scene* scene, uint32_t instance,
                                         const float* transform) {
  if (!scene) return missing("quadra_scene_set_transform: scene");
  return guarded([&] { scene->scene.setTransform({instance}, matrixOf(transform)); });
}

quadra_status quadra_scene_set_camera(quadra_scene* scene, const quadra_camera_data* camera) {
  if (!scene || !camera) return missing("quadra_scene_set_camera: an argument");
  return guarded([&] {
    if (camera->projection != QUADRA_PERSPECTIVE && camera->projection != QUADRA_ORTHOGRAPHIC)
      throw api::Error("camera: unknown projection " + std::to_string(int(camera->projection)));
    scene->scene.setCamera({.projection = api::CameraData::Projection(camera->projection),
                            .yfov = camera->yfov,
                            .ymag = camera->ymag,
                            .znear = camera->znear,
                            .zfar = camera->zfar,
                            .world = matrixOf(camera->world)});
  });
}

quadra_status quadra_renderer_create(int threads, quadra_renderer** out) {
  if (!out) return missing("quadra_renderer_create: out");
  return guarded([&] { *out = new quadra_renderer{api::Renderer({.threads = threads})}; });
}

void quadra_renderer_destroy(quadra_renderer* renderer) {
  delete renderer;
}

quadra_status quadra_render(quadra_renderer* renderer, const quadra_scene* scene,
                            const quadra_target* target, const quadra_depth_target* depth) {
  if (!renderer || !scene || !target) return missing("quadra_render: an argument");
  if (!target->pixels) return missing("render target: pixels");
  if (depth && !depth->depth) return missing("depth target: depth");
  return guarded([&] {
    if (target->format < QUADRA_PIXEL_RGBA8_SRGB || target->format > QUADRA_PIXEL_RGBA32F)
      throw api::Error("render target: unknown pixel format " +
                       std::to_string(int(target->format)));
    const api::Target t{
        .pixels = std::span(static_cast<std::byte*>(target->pixels), target->size_bytes),
        .width = target->width,
        .height = target->height,
        .rowStride = target->row_stride,
        .format = api::PixelFormat(target->format)};
    api::DepthTarget d;
    if (depth)
      d = {.bytes = std::span(reinterpret_cast<std::byte*>(depth->depth), depth->size_bytes),
           .rowStride = depth->row_stride};
    renderer->renderer.render(scene->scene, t, depth ? &d : nullptr);
  });
}

}  // extern "C"
