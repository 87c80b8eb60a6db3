// The C API (include/quadra/quadra.h) over the public C++ one: handles name
// the C++ objects in a table of live ones, and every call catches what C++
// throws and turns it into a status and this thread's last error message.
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <type_traits>
#include <unordered_map>

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

// The live objects behind the handles. A C caller can pass a handle it has
// destroyed; a handle is a number that is never handed out again (not the
// object's address, which a later object could reuse), so such a call finds
// nothing and is an error instead of a use of freed memory. This table is
// the C layer's only process-wide state (C gives no context to hang it on);
// the objects themselves are as thread-safe as the C++ ones, and destroying
// one while another thread uses it stays the caller's race.
class LiveHandles {
 public:
  template <typename T>
  T* add(std::unique_ptr<T> object) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const std::uintptr_t id = next_++;
    T* handle = reinterpret_cast<T*>(id);
    objects_.emplace(id, Entry{std::move(object), kindOf<T>()});
    return handle;
  }
  // The object `handle` names, or an Error naming the call.
  template <typename T>
  T& get(const T* handle, const char* call) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = objects_.find(reinterpret_cast<std::uintptr_t>(handle));
    if (it == objects_.end() || it->second.kind != kindOf<T>()) throw api::Error(notLive<T>(call));
    return *static_cast<T*>(it->second.object.get());
  }
  // Destroys the object; when nothing live has that handle (destroyed
  // twice, or made up) only sets the thread's last error.
  template <typename T>
  void remove(const T* handle, const char* call) {
    std::shared_ptr<void> dying;  // destroyed after the lock is released
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = objects_.find(reinterpret_cast<std::uintptr_t>(handle));
    if (it == objects_.end() || it->second.kind != kindOf<T>()) {
      lastError = notLive<T>(call);
      return;
    }
    dying = std::move(it->second.object);
    objects_.erase(it);
  }

 private:
  struct Entry {
    std::shared_ptr<void> object;
    int kind;
  };
  template <typename T>
  static int kindOf() {
    return std::is_same_v<T, quadra_scene> ? 1 : 2;
  }
  template <typename T>
  static std::string notLive(const char* call) {
    return std::string(call) + ": the " + (std::is_same_v<T, quadra_scene> ? "scene" : "renderer") +
           " handle is not a live one (destroyed, or not made by quadra)";
  }
  mutable std::mutex mutex_;
  std::uintptr_t next_ = 0x51ad0001;  // odd, and far from small indices
  std::unordered_map<std::uintptr_t, Entry> objects_;
};

LiveHandles& liveHandles() {
  static LiveHandles handles;
  return handles;
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
  return guarded([&] { *out = liveHandles().add(std::make_unique<quadra_scene>()); });
}

quadra_status quadra_scene_load(const char* path, quadra_scene** out) {
  if (!path) return missing("quadra_scene_load: path");
  if (!out) return missing("quadra_scene_load: out");
  return guarded([&] {
    *out = liveHandles().add(std::make_unique<quadra_scene>(quadra_scene{api::load(path)}));
  });
}

void quadra_scene_destroy(quadra_scene* scene) {
  if (scene) liveHandles().remove(scene, "quadra_scene_destroy");
}

quadra_status quadra_scene_add_mesh(quadra_scene* scene, const quadra_mesh_data* mesh,
                                    uint32_t* out_mesh) {
  if (!scene || !mesh || !out_mesh) return missing("quadra_scene_add_mesh: an argument");
  return guarded([&] {
    *out_mesh =
        liveHandles().get(scene, "quadra_scene_add_mesh").scene.addMesh(meshOf(*mesh)).index;
  });
}

quadra_status quadra_scene_update_mesh(quadra_scene* scene, uint32_t mesh,
                                       const quadra_mesh_data* data) {
  if (!scene || !data) return missing("quadra_scene_update_mesh: an argument");
  return guarded([&] {
    liveHandles().get(scene, "quadra_scene_update_mesh").scene.updateMesh({mesh}, meshOf(*data));
  });
}

quadra_status quadra_scene_add_texture(quadra_scene* scene, const quadra_texture_data* texture,
                                       uint32_t* out_texture) {
  if (!scene || !texture || !out_texture) return missing("quadra_scene_add_texture: an argument");
  return guarded([&] {
    *out_texture = liveHandles()
                       .get(scene, "quadra_scene_add_texture")
                       .scene.addTexture(textureOf(*texture))
                       .index;
  });
}

quadra_status quadra_scene_update_texture(quadra_scene* scene, uint32_t texture,
                                          const quadra_texture_data* data) {
  if (!scene || !data) return missing("quadra_scene_update_texture: an argument");
  return guarded([&] {
    liveHandles()
        .get(scene, "quadra_scene_update_texture")
        .scene.updateTexture({texture}, textureOf(*data));
  });
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
    *out_material =
        liveHandles().get(scene, "quadra_scene_add_material").scene.addMaterial(data).index;
  });
}

quadra_status quadra_scene_add_instance(quadra_scene* scene, uint32_t mesh, uint32_t material,
                                        const float* transform, uint32_t* out_instance) {
  if (!scene || !out_instance) return missing("quadra_scene_add_instance: an argument");
  return guarded([&] {
    *out_instance = liveHandles()
                        .get(scene, "quadra_scene_add_instance")
                        .scene.addInstance({mesh}, {material}, matrixOf(transform))
                        .index;
  });
}

quadra_status quadra_scene_set_transform(quadra_scene* scene, uint32_t instance,
                                         const float* transform) {
  if (!scene) return missing("quadra_scene_set_transform: scene");
  return guarded([&] {
    liveHandles()
        .get(scene, "quadra_scene_set_transform")
        .scene.setTransform({instance}, matrixOf(transform));
  });
}

quadra_status quadra_scene_set_draw_state(quadra_scene* scene, uint32_t instance,
                                          const quadra_draw_state* state) {
  if (!scene) return missing("quadra_scene_set_draw_state: scene");
  return guarded([&] {
    std::optional<api::DrawStateData> data;
    if (state) {
      // Values outside an enum are the C++ call's one-line errors.
      data =
          api::DrawStateData{.depthTest = state->depth_test != 0,
                             .depthWrite = state->depth_write != 0,
                             .depthCompare = api::CompareFunction(state->depth_compare),
                             .cull = api::CullMode(state->cull),
                             .blend = {.enabled = state->blend_enabled != 0,
                                       .colorEquation = api::BlendEquation(state->color_equation),
                                       .alphaEquation = api::BlendEquation(state->alpha_equation),
                                       .srcColor = api::BlendFactor(state->src_color),
                                       .dstColor = api::BlendFactor(state->dst_color),
                                       .srcAlpha = api::BlendFactor(state->src_alpha),
                                       .dstAlpha = api::BlendFactor(state->dst_alpha)}};
    }
    liveHandles().get(scene, "quadra_scene_set_draw_state").scene.setDrawState({instance}, data);
  });
}

quadra_status quadra_scene_set_camera(quadra_scene* scene, const quadra_camera_data* camera) {
  if (!scene || !camera) return missing("quadra_scene_set_camera: an argument");
  return guarded([&] {
    if (camera->projection != QUADRA_PERSPECTIVE && camera->projection != QUADRA_ORTHOGRAPHIC)
      throw api::Error("camera: unknown projection " + std::to_string(int(camera->projection)));
    liveHandles()
        .get(scene, "quadra_scene_set_camera")
        .scene.setCamera({.projection = api::CameraData::Projection(camera->projection),
                          .yfov = camera->yfov,
                          .ymag = camera->ymag,
                          .znear = camera->znear,
                          .zfar = camera->zfar,
                          .world = matrixOf(camera->world)});
  });
}

quadra_status quadra_renderer_create(int threads, quadra_renderer** out) {
  if (!out) return missing("quadra_renderer_create: out");
  return guarded([&] {
    *out = liveHandles().add(
        std::make_unique<quadra_renderer>(quadra_renderer{api::Renderer({.threads = threads})}));
  });
}

void quadra_renderer_destroy(quadra_renderer* renderer) {
  if (renderer) liveHandles().remove(renderer, "quadra_renderer_destroy");
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
    liveHandles()
        .get(renderer, "quadra_render")
        .renderer.render(liveHandles().get(scene, "quadra_render").scene, t, depth ? &d : nullptr);
  });
}

}  // extern "C"
