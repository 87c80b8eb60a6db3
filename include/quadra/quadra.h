/* quadra's C API: opaque handles, status codes and a message getter, no C++
 * types, so any language with a C FFI can bind it. It is a thin layer over
 * the C++ API (quadra/quadra.hpp), with the same validation and messages.
 *
 * Errors: every function returning quadra_status returns QUADRA_OK or an
 * error code, and then quadra_last_error() gives the one-line message of
 * the calling thread's last failure (valid until its next failing call).
 * Ownership: *_create and quadra_scene_load hand out handles the caller
 * releases with the matching *_destroy (NULL is accepted and ignored).
 * Handles are never reused: one used after its destroy (or made up, or of
 * the other kind) is QUADRA_INVALID_ARGUMENT with a message naming the call,
 * and a second destroy only sets that message. Data passed in is copied.
 * Threads: as in C++; a scene may be rendered by several renderers at once,
 * a renderer renders one frame at a time. */
#ifndef QUADRA_QUADRA_H
#define QUADRA_QUADRA_H

#include <stddef.h>
#include <stdint.h>

#include "quadra/export.h"
#include "quadra/version.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum quadra_status {
  QUADRA_OK = 0,
  QUADRA_INVALID_ARGUMENT = 1, /* a NULL handle or pointer, data that fails validation, or a
                                  frame over its memory budget */
  QUADRA_FAILED = 2,           /* a load that failed (the file, the sandbox, its budget) */
  QUADRA_OUT_OF_MEMORY = 3
} quadra_status;

typedef struct quadra_scene quadra_scene;
typedef struct quadra_renderer quadra_renderer;
typedef struct quadra_environment quadra_environment;

/* The library's version, "MAJOR.MINOR.PATCH". */
QUADRA_API const char* quadra_version(void);
/* The calling thread's last error message; "" when none. */
QUADRA_API const char* quadra_last_error(void);

/* Counts are the caller's statement of each array's length: positions,
 * normals (optional) and colors (optional) hold vertex_count x 3, 3 and 4
 * floats, uvs (optional) vertex_count x 2; exactly one of indices32 and
 * indices16 holds index_count entries, each < vertex_count. */
typedef struct quadra_mesh_data {
  const float* positions;
  const float* normals;
  const float* uvs;
  const float* colors;
  size_t vertex_count;
  const uint32_t* indices32;
  const uint16_t* indices16;
  size_t index_count;
} quadra_mesh_data;

typedef enum quadra_texture_format {
  QUADRA_TEXTURE_RGBA8_SRGB = 0,
  QUADRA_TEXTURE_RGBA8_UNORM = 1,
  QUADRA_TEXTURE_RGBA16F = 2,
  QUADRA_TEXTURE_RGBA32F = 3
} quadra_texture_format;
typedef enum quadra_wrap {
  QUADRA_WRAP_REPEAT = 0,
  QUADRA_WRAP_MIRRORED_REPEAT = 1,
  QUADRA_WRAP_CLAMP_TO_EDGE = 2
} quadra_wrap;
typedef enum quadra_filter {
  QUADRA_FILTER_NEAREST = 0,
  QUADRA_FILTER_BILINEAR = 1,
  QUADRA_FILTER_TRILINEAR = 2,
  QUADRA_FILTER_ANISOTROPIC = 3
} quadra_filter;

/* texels: size_bytes bytes, rows row_stride apart (0: tightly packed). */
typedef struct quadra_texture_data {
  int width;
  int height;
  quadra_texture_format format;
  const void* texels;
  size_t size_bytes;
  size_t row_stride;
  quadra_wrap wrap_u;
  quadra_wrap wrap_v;
  quadra_filter filter;
} quadra_texture_data;

typedef enum quadra_alpha_mode {
  QUADRA_ALPHA_OPAQUE = 0,
  QUADRA_ALPHA_MASK = 1,
  QUADRA_ALPHA_BLEND = 2
} quadra_alpha_mode;

typedef struct quadra_material_data {
  float base_color[4]; /* linear, straight */
  int has_texture;     /* nonzero: texture is read at the mesh's uvs */
  uint32_t texture;
  quadra_alpha_mode alpha_mode;
  float alpha_cutoff;
  int double_sided;
} quadra_material_data;

/* Per-draw state, as quadra::api::DrawStateData (quadra/scene.hpp); the
   enums' values are the C++ enumerators' in declaration order. */
typedef enum quadra_compare {
  QUADRA_COMPARE_NEVER = 0,
  QUADRA_COMPARE_LESS = 1,
  QUADRA_COMPARE_EQUAL = 2,
  QUADRA_COMPARE_LEQUAL = 3,
  QUADRA_COMPARE_GREATER = 4,
  QUADRA_COMPARE_NOTEQUAL = 5,
  QUADRA_COMPARE_GEQUAL = 6,
  QUADRA_COMPARE_ALWAYS = 7
} quadra_compare;
typedef enum quadra_cull {
  QUADRA_CULL_NONE = 0,
  QUADRA_CULL_BACK = 1,
  QUADRA_CULL_FRONT = 2
} quadra_cull;
typedef enum quadra_blend_equation {
  QUADRA_BLEND_ADD = 0,
  QUADRA_BLEND_SUBTRACT = 1,
  QUADRA_BLEND_REVERSE_SUBTRACT = 2,
  QUADRA_BLEND_MIN = 3,
  QUADRA_BLEND_MAX = 4
} quadra_blend_equation;
typedef enum quadra_blend_factor {
  QUADRA_FACTOR_ZERO = 0,
  QUADRA_FACTOR_ONE = 1,
  QUADRA_FACTOR_SRC_COLOR = 2,
  QUADRA_FACTOR_ONE_MINUS_SRC_COLOR = 3,
  QUADRA_FACTOR_DST_COLOR = 4,
  QUADRA_FACTOR_ONE_MINUS_DST_COLOR = 5,
  QUADRA_FACTOR_SRC_ALPHA = 6,
  QUADRA_FACTOR_ONE_MINUS_SRC_ALPHA = 7,
  QUADRA_FACTOR_DST_ALPHA = 8,
  QUADRA_FACTOR_ONE_MINUS_DST_ALPHA = 9
} quadra_blend_factor;
typedef struct quadra_draw_state {
  int depth_test;
  int depth_write;
  quadra_compare depth_compare;
  quadra_cull cull;
  int blend_enabled;
  quadra_blend_equation color_equation;
  quadra_blend_equation alpha_equation;
  quadra_blend_factor src_color;
  quadra_blend_factor dst_color;
  quadra_blend_factor src_alpha;
  quadra_blend_factor dst_alpha;
} quadra_draw_state;

typedef enum quadra_projection {
  QUADRA_PERSPECTIVE = 0,
  QUADRA_ORTHOGRAPHIC = 1
} quadra_projection;

/* As quadra::api::CameraData; world is column-major camera-to-world. */
typedef struct quadra_camera_data {
  quadra_projection projection;
  float yfov;
  float ymag;
  float znear;
  float zfar;
  float world[16];
} quadra_camera_data;

typedef enum quadra_pixel_format {
  QUADRA_PIXEL_RGBA8_SRGB = 0,
  QUADRA_PIXEL_RGBA16F = 1,
  QUADRA_PIXEL_RGBA32F = 2
} quadra_pixel_format;

/* The embedder's buffer of size_bytes bytes; rules as quadra::api::Target. */
typedef struct quadra_target {
  void* pixels;
  size_t size_bytes;
  int width;
  int height;
  size_t row_stride;
  quadra_pixel_format format;
} quadra_target;
typedef struct quadra_depth_target {
  float* depth;
  size_t size_bytes;
  size_t row_stride;
} quadra_depth_target;

/* The AOV targets, as quadra::api::AovTargets (quadra/renderer.hpp): each a
 * plane of the embedder's own memory with the rules of the depth target, the
 * AOV defined as the CLI's --aov channel of that name (docs/cli.md "AOVs").
 * A NULL pointer: that AOV is not asked for, and not computed. */
typedef struct quadra_aov_float_target {
  float* data; /* channels floats per pixel */
  size_t size_bytes;
  size_t row_stride;
} quadra_aov_float_target;
typedef struct quadra_aov_id_target {
  uint32_t* data; /* 1 per pixel */
  size_t size_bytes;
  size_t row_stride;
} quadra_aov_id_target;
typedef struct quadra_aov_targets {
  quadra_aov_float_target normal;    /* 3 channels: N.X N.Y N.Z */
  quadra_aov_float_target position;  /* 3: P.X P.Y P.Z */
  quadra_aov_float_target uv;        /* 2: uv.U uv.V */
  quadra_aov_float_target mask;      /* 1: mask */
  quadra_aov_id_target primitive_id; /* id.primitive */
  quadra_aov_id_target node_id;      /* id.node; a scene built in code: the instance's id */
  quadra_aov_id_target material_id;  /* id.material; built in code: the material's id */
} quadra_aov_targets;

QUADRA_API quadra_status quadra_scene_create(quadra_scene** out);
QUADRA_API quadra_status quadra_scene_load(const char* path, quadra_scene** out);
/* As quadra::api::LoadOptions: folders the file may also read, the bytes
   its load may allocate (0: the default, 8 GiB), the glTF scene (-1: the
   file's default). */
typedef struct quadra_load_options {
  const char* const* allowed_paths;
  size_t allowed_path_count;
  uint64_t max_memory;
  int scene;
} quadra_load_options;
QUADRA_API quadra_status quadra_scene_load_with(const char* path,
                                                const quadra_load_options* options,
                                                quadra_scene** out);
QUADRA_API void quadra_scene_destroy(quadra_scene* scene);
QUADRA_API quadra_status quadra_scene_add_mesh(quadra_scene* scene, const quadra_mesh_data* mesh,
                                               uint32_t* out_mesh);
QUADRA_API quadra_status quadra_scene_update_mesh(quadra_scene* scene, uint32_t mesh,
                                                  const quadra_mesh_data* data);
QUADRA_API quadra_status quadra_scene_add_texture(quadra_scene* scene,
                                                  const quadra_texture_data* texture,
                                                  uint32_t* out_texture);
QUADRA_API quadra_status quadra_scene_update_texture(quadra_scene* scene, uint32_t texture,
                                                     const quadra_texture_data* data);
QUADRA_API quadra_status quadra_scene_add_material(quadra_scene* scene,
                                                   const quadra_material_data* material,
                                                   uint32_t* out_material);
/* transform: 16 floats, column-major; NULL: the identity. */
QUADRA_API quadra_status quadra_scene_add_instance(quadra_scene* scene, uint32_t mesh,
                                                   uint32_t material, const float* transform,
                                                   uint32_t* out_instance);
QUADRA_API quadra_status quadra_scene_set_transform(quadra_scene* scene, uint32_t instance,
                                                    const float* transform);
/* state NULL: the instance goes back to its material's state. */
QUADRA_API quadra_status quadra_scene_set_draw_state(quadra_scene* scene, uint32_t instance,
                                                     const quadra_draw_state* state);
QUADRA_API quadra_status quadra_scene_set_camera(quadra_scene* scene,
                                                 const quadra_camera_data* camera);
/* A loaded scene's glTF animations, and its pose `seconds` into one of them
   (-1: the rest pose), as quadra::api::Scene::setAnimationTime. */
QUADRA_API quadra_status quadra_scene_animation_count(const quadra_scene* scene, int* out_count);
QUADRA_API quadra_status quadra_scene_set_animation_time(quadra_scene* scene, int animation,
                                                         double seconds);

/* threads <= 0: all cores. */
QUADRA_API quadra_status quadra_renderer_create(int threads, quadra_renderer** out);
QUADRA_API void quadra_renderer_destroy(quadra_renderer* renderer);
/* depth may be NULL. Unlit shading, 1 sample, transparent black clear. */
QUADRA_API quadra_status quadra_render(quadra_renderer* renderer, const quadra_scene* scene,
                                       const quadra_target* target,
                                       const quadra_depth_target* depth);
/* As quadra::api::RenderOptions. PBR: glTF's metallic-roughness material
   under an environment, lit by quadra_render_lit's lighting (quadra_render_with
   lights it with the defaults of quadra_lighting_defaults). */
typedef enum quadra_shading {
  QUADRA_SHADING_UNLIT = 0,
  QUADRA_SHADING_LIT = 1,
  QUADRA_SHADING_PBR = 2
} quadra_shading;
typedef struct quadra_render_options {
  quadra_shading shading;
  int samples;          /* per pixel: 1, 2, 4, 8 or 16 */
  float clear_color[4]; /* premultiplied linear */
  uint64_t max_memory;  /* bytes a frame may hold; 0: the default, 8 GiB */
} quadra_render_options;
/* quadra_render with options (NULL: quadra_render's) and the AOVs whose
   targets aovs gives (NULL: none). */
QUADRA_API quadra_status quadra_render_with(quadra_renderer* renderer, const quadra_scene* scene,
                                            const quadra_target* target,
                                            const quadra_depth_target* depth,
                                            const quadra_render_options* options,
                                            const quadra_aov_targets* aovs);

/* Environments, as quadra::api::Environment (quadra/environment.hpp): the
 * light of QUADRA_SHADING_PBR, an equirectangular panorama of linear RGB
 * radiance (docs/lighting.md "Environments"). Immutable once made; a
 * renderer keeps its preparation of one while frames ask for the same
 * handle, and may keep lighting with it after quadra_environment_destroy
 * (the texels are shared). */
/* width x height texels of R, G, B floats, value_count = width x height x 3
   of them, row 0 the top (+Y), the centre column facing -Z; copied, then
   checked and repaired as the CLI's --env (at least 2 texels, at most 2^28;
   NaN and negative values become 0, values above 2^32 become 2^32). */
QUADRA_API quadra_status quadra_environment_create(const float* rgb, size_t value_count, int width,
                                                   int height, quadra_environment** out);
/* "builtin:NAME" or a .hdr or .exr file, as --env; its allocations charged
   to max_memory (0: the default, 8 GiB). A file that fails is QUADRA_FAILED. */
QUADRA_API quadra_status quadra_environment_load(const char* source, uint64_t max_memory,
                                                 quadra_environment** out);
QUADRA_API void quadra_environment_destroy(quadra_environment* environment);
QUADRA_API quadra_status quadra_environment_size(const quadra_environment* environment,
                                                 int* out_width, int* out_height);
/* The texels as quadra lights with them (the rule applied) into out, which
   holds value_count = width x height x 3 floats. */
QUADRA_API quadra_status quadra_environment_texels(const quadra_environment* environment,
                                                   float* out, size_t value_count);

/* The light and output of a PBR frame, as quadra::api::RenderOptions's
   members of those names (each the CLI's render option in the comment). */
typedef enum quadra_background {
  QUADRA_BACKGROUND_ENVIRONMENT = 0, /* --background env */
  QUADRA_BACKGROUND_COLOR = 1,       /* the clear colour's r, g, b, made opaque */
  QUADRA_BACKGROUND_TRANSPARENT = 2
} quadra_background;
typedef enum quadra_tone_map {
  QUADRA_TONE_MAP_DEFAULT = 0, /* PBR_NEUTRAL for PBR shading, NONE for the others */
  QUADRA_TONE_MAP_PBR_NEUTRAL = 1,
  QUADRA_TONE_MAP_ACES = 2,
  QUADRA_TONE_MAP_NONE = 3 /* a clamp */
} quadra_tone_map;
typedef struct quadra_lighting {
  const quadra_environment* environment; /* --env; NULL: builtin:studio */
  float environment_rotation;            /* --env-rotation, degrees */
  float environment_intensity;           /* --env-intensity */
  int punctual_lights;                   /* --lights: nonzero on */
  quadra_background background;          /* --background */
  float exposure;                        /* --exposure EV, every shading */
  quadra_tone_map tone_map;              /* --tonemap, for QUADRA_PIXEL_RGBA8_SRGB targets */
} quadra_lighting;
/* The defaults: builtin:studio, rotation 0, intensity 1, lights on, the
   environment as background, exposure 0, the default tone map. */
QUADRA_API quadra_lighting quadra_lighting_defaults(void);
/* quadra_render_with with lighting (NULL: quadra_lighting_defaults()). */
QUADRA_API quadra_status quadra_render_lit(quadra_renderer* renderer, const quadra_scene* scene,
                                           const quadra_target* target,
                                           const quadra_depth_target* depth,
                                           const quadra_render_options* options,
                                           const quadra_lighting* lighting,
                                           const quadra_aov_targets* aovs);

#ifdef __cplusplus
}
#endif

#endif /* QUADRA_QUADRA_H */
