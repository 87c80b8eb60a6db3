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
struct quadra_environment {
  quadra::api::Environment environment;
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

quadra_status missing(const std::string& what) {
  lastError = what + " is NULL";
  return QUADRA_INVALID_ARGUMENT;
}

// A C caller can store any int in an enum field, but C++ must not read a
// value outside its enum's range (undefined behaviour), so the field is read
// as the int C stored and checked before it becomes the C++ enum; a value the
// narrower C++ enum would wrap into range is refused too.
template <typename ApiEnum, typename CEnum>
ApiEnum enumField(const CEnum& field, CEnum last, const char* context, const char* name) {
  static_assert(sizeof(CEnum) == sizeof(int), "C enums are stored as int");
  int value;
  std::memcpy(&value, &field, sizeof value);
  if (value < 0 || value > int(last))
    throw api::Error(std::string(context) + ": " + name + " " + std::to_string(value) +
                     " is not one of its values");
  return ApiEnum(value);
}

// enumField converts by value: each C enum lists its C++ enum's values in the
// same order, ending at the same last one.
static_assert(int(QUADRA_TEXTURE_RGBA32F) == int(api::TextureFormat::Rgba32F) &&
              int(QUADRA_WRAP_CLAMP_TO_EDGE) == int(api::Wrap::ClampToEdge) &&
              int(QUADRA_FILTER_ANISOTROPIC) == int(api::Filter::Anisotropic) &&
              int(QUADRA_ALPHA_BLEND) == int(api::AlphaMode::Blend) &&
              int(QUADRA_COMPARE_ALWAYS) == int(api::CompareFunction::Always) &&
              int(QUADRA_CULL_FRONT) == int(api::CullMode::Front) &&
              int(QUADRA_BLEND_MAX) == int(api::BlendEquation::Max) &&
              int(QUADRA_FACTOR_ONE_MINUS_DST_ALPHA) == int(api::BlendFactor::OneMinusDstAlpha) &&
              int(QUADRA_ORTHOGRAPHIC) == int(api::CameraData::Projection::Orthographic) &&
              int(QUADRA_PIXEL_RGBA32F) == int(api::PixelFormat::Rgba32F) &&
              int(QUADRA_SHADING_PBR) == int(api::Shading::Pbr) &&
              int(QUADRA_BACKGROUND_TRANSPARENT) == int(api::Background::Transparent));

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
    return std::is_same_v<T, quadra_scene> ? 1 : std::is_same_v<T, quadra_renderer> ? 2 : 3;
  }
  template <typename T>
  static std::string notLive(const char* call) {
    const char* kind = std::is_same_v<T, quadra_scene>      ? "scene"
                       : std::is_same_v<T, quadra_renderer> ? "renderer"
                                                            : "environment";
    return std::string(call) + ": the " + kind +
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
  return {
      .width = t.width,
      .height = t.height,
      .format =
          enumField<api::TextureFormat>(t.format, QUADRA_TEXTURE_RGBA32F, "texture", "format"),
      .texels = std::span(static_cast<const std::byte*>(t.texels), t.texels ? t.size_bytes : 0),
      .rowStride = t.row_stride,
      .wrapU = enumField<api::Wrap>(t.wrap_u, QUADRA_WRAP_CLAMP_TO_EDGE, "texture", "wrap_u"),
      .wrapV = enumField<api::Wrap>(t.wrap_v, QUADRA_WRAP_CLAMP_TO_EDGE, "texture", "wrap_v"),
      .filter = enumField<api::Filter>(t.filter, QUADRA_FILTER_ANISOTROPIC, "texture", "filter")};
}

api::Matrix4 matrixOf(const float* m) {
  api::Matrix4 out = api::kIdentity;
  if (m) std::memcpy(out.data(), m, sizeof(out));
  return out;
}

// A C AOV target as the C++ one; a NULL data pointer stays null bytes (not
// asked for), whatever size it states.
template <typename CTarget>
api::AovTarget aovTarget(const CTarget& target) {
  if (!target.data) return {};
  return {.bytes = std::span(reinterpret_cast<std::byte*>(target.data), target.size_bytes),
          .rowStride = target.row_stride};
}

// A C lighting as the C++ options' members of those names.
void applyLighting(const quadra_lighting& l, const char* call, api::RenderOptions& o) {
  if (l.environment) o.environment = liveHandles().get(l.environment, call).environment;
  o.environmentRotation = l.environment_rotation;
  o.environmentIntensity = l.environment_intensity;
  o.punctualLights = l.punctual_lights != 0;
  o.background = enumField<api::Background>(l.background, QUADRA_BACKGROUND_TRANSPARENT, "lighting",
                                            "background");
  o.exposure = l.exposure;
  // The C enum's 0 is the default, which C++ states by leaving toneMap unset.
  const auto toneMap =
      enumField<quadra_tone_map>(l.tone_map, QUADRA_TONE_MAP_NONE, "lighting", "tone_map");
  if (toneMap != QUADRA_TONE_MAP_DEFAULT) o.toneMap = api::ToneMap(int(toneMap) - 1);
}
static_assert(int(QUADRA_TONE_MAP_NONE) - 1 == int(api::ToneMap::None) &&
              int(QUADRA_TONE_MAP_PBR_NEUTRAL) - 1 == int(api::ToneMap::PbrNeutral));

// quadra_render, quadra_render_with and quadra_render_lit, named `call` in
// their messages.
quadra_status render(const char* call, quadra_renderer* renderer, const quadra_scene* scene,
                     const quadra_target* target, const quadra_depth_target* depth,
                     const quadra_render_options* options, const quadra_lighting* lighting,
                     const quadra_aov_targets* aovs) {
  if (!renderer || !scene || !target) return missing(std::string(call) + ": an argument");
  if (!target->pixels) return missing("render target: pixels");
  if (depth && !depth->depth) return missing("depth target: depth");
  return guarded([&] {
    const api::Target t{
        .pixels = std::span(static_cast<std::byte*>(target->pixels), target->size_bytes),
        .width = target->width,
        .height = target->height,
        .rowStride = target->row_stride,
        .format = enumField<api::PixelFormat>(target->format, QUADRA_PIXEL_RGBA32F, "render target",
                                              "format")};
    api::DepthTarget d;
    if (depth)
      d = {.bytes = std::span(reinterpret_cast<std::byte*>(depth->depth), depth->size_bytes),
           .rowStride = depth->row_stride};
    api::AovTargets a;
    if (aovs)
      a = {.normal = aovTarget(aovs->normal),
           .position = aovTarget(aovs->position),
           .uv = aovTarget(aovs->uv),
           .mask = aovTarget(aovs->mask),
           .primitiveId = aovTarget(aovs->primitive_id),
           .nodeId = aovTarget(aovs->node_id),
           .materialId = aovTarget(aovs->material_id)};
    api::RenderOptions o;
    if (options) {
      o.shading = enumField<api::Shading>(options->shading, QUADRA_SHADING_PBR, "render options",
                                          "shading");
      o.samples = options->samples;
      std::memcpy(o.clearColor.data(), options->clear_color, sizeof(options->clear_color));
      if (options->max_memory != 0) o.maxMemory = options->max_memory;
    }
    if (lighting) applyLighting(*lighting, call, o);
    liveHandles()
        .get(renderer, call)
        .renderer.render(liveHandles().get(scene, call).scene, t, depth ? &d : nullptr, o,
                         aovs ? &a : nullptr);
  });
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

namespace {
// Whatever the loader refuses is the file's failure (QUADRA_FAILED), not a
// bad argument of the call.
// options: NULL for the defaults, else checked for NULL folders already.
quadra_status loadScene(const char* path, const quadra_load_options* options, quadra_scene** out) {
  const quadra_status status = guarded([&] {
    api::LoadOptions loadOptions;
    if (options) {
      loadOptions.allowedPaths.assign(options->allowed_paths,
                                      options->allowed_paths + options->allowed_path_count);
      if (options->max_memory != 0) loadOptions.maxMemory = options->max_memory;
      loadOptions.scene = options->scene;
    }
    *out = liveHandles().add(
        std::make_unique<quadra_scene>(quadra_scene{api::load(path, loadOptions)}));
  });
  return status == QUADRA_INVALID_ARGUMENT ? QUADRA_FAILED : status;
}
}  // namespace

quadra_status quadra_scene_load(const char* path, quadra_scene** out) {
  if (!path) return missing("quadra_scene_load: path");
  if (!out) return missing("quadra_scene_load: out");
  return loadScene(path, nullptr, out);
}

quadra_status quadra_scene_load_with(const char* path, const quadra_load_options* options,
                                     quadra_scene** out) {
  if (!path || !options || !out) return missing("quadra_scene_load_with: an argument");
  if (options->allowed_path_count != 0 && !options->allowed_paths)
    return missing("quadra_scene_load_with: allowed_paths");
  for (std::size_t i = 0; i < options->allowed_path_count; ++i)
    if (!options->allowed_paths[i]) {
      lastError = "quadra_scene_load_with: allowed_paths[" + std::to_string(i) + "] is NULL";
      return QUADRA_INVALID_ARGUMENT;
    }
  return loadScene(path, options, out);
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
    api::MaterialData data;
    std::memcpy(data.baseColor.data(), material->base_color, sizeof(material->base_color));
    if (material->has_texture) data.texture = api::TextureHandle{material->texture};
    data.alphaMode = enumField<api::AlphaMode>(material->alpha_mode, QUADRA_ALPHA_BLEND, "material",
                                               "alpha_mode");
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
      const char* context = "setDrawState";
      const auto equation = [&](const quadra_blend_equation& field, const char* name) {
        return enumField<api::BlendEquation>(field, QUADRA_BLEND_MAX, context, name);
      };
      const auto factor = [&](const quadra_blend_factor& field, const char* name) {
        return enumField<api::BlendFactor>(field, QUADRA_FACTOR_ONE_MINUS_DST_ALPHA, context, name);
      };
      data = api::DrawStateData{
          .depthTest = state->depth_test != 0,
          .depthWrite = state->depth_write != 0,
          .depthCompare = enumField<api::CompareFunction>(
              state->depth_compare, QUADRA_COMPARE_ALWAYS, context, "depth_compare"),
          .cull = enumField<api::CullMode>(state->cull, QUADRA_CULL_FRONT, context, "cull"),
          .blend = {.enabled = state->blend_enabled != 0,
                    .colorEquation = equation(state->color_equation, "color_equation"),
                    .alphaEquation = equation(state->alpha_equation, "alpha_equation"),
                    .srcColor = factor(state->src_color, "src_color"),
                    .dstColor = factor(state->dst_color, "dst_color"),
                    .srcAlpha = factor(state->src_alpha, "src_alpha"),
                    .dstAlpha = factor(state->dst_alpha, "dst_alpha")}};
    }
    liveHandles().get(scene, "quadra_scene_set_draw_state").scene.setDrawState({instance}, data);
  });
}

quadra_status quadra_scene_set_camera(quadra_scene* scene, const quadra_camera_data* camera) {
  if (!scene || !camera) return missing("quadra_scene_set_camera: an argument");
  return guarded([&] {
    liveHandles()
        .get(scene, "quadra_scene_set_camera")
        .scene.setCamera({.projection = enumField<api::CameraData::Projection>(
                              camera->projection, QUADRA_ORTHOGRAPHIC, "camera", "projection"),
                          .yfov = camera->yfov,
                          .ymag = camera->ymag,
                          .znear = camera->znear,
                          .zfar = camera->zfar,
                          .world = matrixOf(camera->world)});
  });
}

quadra_status quadra_scene_animation_count(const quadra_scene* scene, int* out_count) {
  if (!scene || !out_count) return missing("quadra_scene_animation_count: an argument");
  return guarded([&] {
    *out_count = liveHandles().get(scene, "quadra_scene_animation_count").scene.animationCount();
  });
}

quadra_status quadra_scene_set_animation_time(quadra_scene* scene, int animation, double seconds) {
  if (!scene) return missing("quadra_scene_set_animation_time: scene");
  return guarded([&] {
    liveHandles()
        .get(scene, "quadra_scene_set_animation_time")
        .scene.setAnimationTime(animation, seconds);
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
  return render("quadra_render", renderer, scene, target, depth, nullptr, nullptr, nullptr);
}

quadra_status quadra_render_with(quadra_renderer* renderer, const quadra_scene* scene,
                                 const quadra_target* target, const quadra_depth_target* depth,
                                 const quadra_render_options* options,
                                 const quadra_aov_targets* aovs) {
  return render("quadra_render_with", renderer, scene, target, depth, options, nullptr, aovs);
}

quadra_lighting quadra_lighting_defaults(void) {
  const api::RenderOptions o;
  return {.environment = nullptr,
          .environment_rotation = o.environmentRotation,
          .environment_intensity = o.environmentIntensity,
          .punctual_lights = o.punctualLights ? 1 : 0,
          .background = QUADRA_BACKGROUND_ENVIRONMENT,
          .exposure = o.exposure,
          .tone_map = QUADRA_TONE_MAP_DEFAULT};
}

quadra_status quadra_render_lit(quadra_renderer* renderer, const quadra_scene* scene,
                                const quadra_target* target, const quadra_depth_target* depth,
                                const quadra_render_options* options,
                                const quadra_lighting* lighting, const quadra_aov_targets* aovs) {
  return render("quadra_render_lit", renderer, scene, target, depth, options, lighting, aovs);
}

quadra_status quadra_environment_create(const float* rgb, size_t value_count, int width, int height,
                                        quadra_environment** out) {
  if (!rgb || !out) return missing("quadra_environment_create: an argument");
  return guarded([&] {
    *out = liveHandles().add(std::make_unique<quadra_environment>(quadra_environment{
        api::Environment::fromTexels(std::span(rgb, value_count), width, height)}));
  });
}

quadra_status quadra_environment_load(const char* source, uint64_t max_memory,
                                      quadra_environment** out) {
  if (!source || !out) return missing("quadra_environment_load: an argument");
  const quadra_status status = guarded([&] {
    *out = liveHandles().add(std::make_unique<quadra_environment>(quadra_environment{
        api::Environment::load(source, max_memory != 0 ? max_memory : api::kDefaultMaxMemory)}));
  });
  // A source that cannot be read is a failed load, as quadra_scene_load's.
  return status == QUADRA_INVALID_ARGUMENT ? QUADRA_FAILED : status;
}

void quadra_environment_destroy(quadra_environment* environment) {
  if (environment) liveHandles().remove(environment, "quadra_environment_destroy");
}

quadra_status quadra_environment_size(const quadra_environment* environment, int* out_width,
                                      int* out_height) {
  if (!environment || !out_width || !out_height)
    return missing("quadra_environment_size: an argument");
  return guarded([&] {
    const api::Environment& e =
        liveHandles().get(environment, "quadra_environment_size").environment;
    *out_width = e.width();
    *out_height = e.height();
  });
}

quadra_status quadra_environment_texels(const quadra_environment* environment, float* out,
                                        size_t value_count) {
  if (!environment || !out) return missing("quadra_environment_texels: an argument");
  return guarded([&] {
    const std::span<const float> texels =
        liveHandles().get(environment, "quadra_environment_texels").environment.texels();
    if (value_count != texels.size())
      throw api::Error("quadra_environment_texels: value_count " + std::to_string(value_count) +
                       " is not the environment's " + std::to_string(texels.size()));
    std::memcpy(out, texels.data(), texels.size() * sizeof(float));
  });
}

}  // extern "C"
