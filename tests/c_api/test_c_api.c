/* The C API from a C program (CTest: CApi): an in-memory quad rendered into
 * padded RGBA32F, depth and AOV buffers, checked pixel by pixel against where
 * the quad must be; a glTF file loaded and rendered, unlit and lit (an
 * environment from an array, a name and a file alike); and each misuse
 * returning its status and one-line message while writing nothing.
 *   test_c_api FILE.glb
 * And, for CApiLitEqualsTheCli (lit_equals_cli.sh, which compares OUT.raw
 * with the CLI's EXR), the pbr frame of FILE.glb lit by the W x H texels of
 * ENV.raw (R, G, B floats), its colour then its depth written to OUT.raw:
 *   test_c_api --lit FILE.glb ENV.raw W H OUT.raw */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "quadra/quadra.h"

enum {
  kSize = 40,
  kStride = kSize * 16 + 64,
  kDepthStride = kSize * 4 + 12,
  kAovRow = kSize + 3 /* 4-byte values per AOV row: 3 of padding */
};

static int failures = 0;

#define EXPECT(cond)                                                     \
  do {                                                                   \
    if (!(cond)) {                                                       \
      fprintf(stderr, "%s:%d: failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                        \
    }                                                                    \
  } while (0)

/* The status and the message of one misuse. */
static void expect_error(quadra_status status, quadra_status expected, const char* message) {
  EXPECT(status == expected);
  if (strcmp(quadra_last_error(), message) != 0) {
    fprintf(stderr, "message: '%s'\nexpected: '%s'\n", quadra_last_error(), message);
    ++failures;
  }
}

static float pixels[kSize * kStride / 4 + 16];
static float depth[kSize * kDepthStride / 4];
static uint32_t node_ids[kSize * kAovRow];
static float mask[kSize * kAovRow];

/* quadra_render_with: the node ids (the instance's id on the quad,
 * 0xFFFFFFFF off it, docs/cli.md "AOVs") and the mask (1 on it, 0 off it) at a
 * padded stride, the padding untouched; a short normal target is an error
 * naming it that writes nothing. */
static void aovs_of_the_quad(quadra_renderer* renderer, const quadra_scene* scene,
                             const quadra_target* target, uint32_t instance_id) {
  memset(node_ids, 0xA5, sizeof(node_ids));
  memset(mask, 0xA5, sizeof(mask));
  quadra_aov_targets aovs;
  memset(&aovs, 0, sizeof(aovs));
  aovs.node_id.data = node_ids;
  aovs.node_id.size_bytes = sizeof(node_ids);
  aovs.node_id.row_stride = kAovRow * 4;
  aovs.mask.data = mask;
  aovs.mask.size_bytes = sizeof(mask);
  aovs.mask.row_stride = kAovRow * 4;
  EXPECT(quadra_render_with(renderer, scene, target, NULL, NULL, &aovs) == QUADRA_OK);
  int wrong = 0, padding = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const int inside = x >= 10 && x < 30 && y >= 10 && y < 30;
      wrong += node_ids[y * kAovRow + x] != (inside ? instance_id : 0xFFFFFFFFu);
      wrong += mask[y * kAovRow + x] != (inside ? 1.0f : 0.0f);
    }
    for (int x = kSize; x < kAovRow; ++x) padding += node_ids[y * kAovRow + x] != 0xA5A5A5A5u;
  }
  EXPECT(wrong == 0);
  EXPECT(padding == 0);

  static float normals[kSize * kSize * 3];
  memset(node_ids, 0xA5, sizeof(node_ids));
  aovs.normal.data = normals;
  aovs.normal.size_bytes = 100;
  aovs.normal.row_stride = kSize * 12;
  expect_error(quadra_render_with(renderer, scene, target, NULL, NULL, &aovs),
               QUADRA_INVALID_ARGUMENT,
               "normal AOV target: 40x40 at row stride 480 needs 19200 bytes, the buffer has 100");
  int written = 0;
  for (int i = 0; i < kSize * kAovRow; ++i) written += node_ids[i] != 0xA5A5A5A5u;
  EXPECT(written == 0);
}

/* quadra_render_with's options: a clear colour and 4 samples (the quad's
 * inside keeps its colour, every sample being covered), and each bad option
 * a one-line error. */
static void options_of_the_quad(quadra_renderer* renderer, const quadra_scene* scene,
                                const quadra_target* target, const float base[4]) {
  quadra_render_options options = {QUADRA_SHADING_UNLIT, 4, {0.0f, 0.0f, 0.125f, 1.0f}, 0};
  EXPECT(quadra_render_with(renderer, scene, target, NULL, &options, NULL) == QUADRA_OK);
  const float* corner = (const float*)target->pixels;
  const float* centre = corner + 20 * (target->row_stride / 4) + 20 * 4;
  for (int c = 0; c < 4; ++c) EXPECT(corner[c] == options.clear_color[c] && centre[c] == base[c]);
  options.samples = 3;
  EXPECT(quadra_render_with(renderer, scene, target, NULL, &options, NULL) ==
         QUADRA_INVALID_ARGUMENT);
  EXPECT(strstr(quadra_last_error(), "samples") != NULL);
  options.samples = 1;
  options.shading = (quadra_shading)7;
  expect_error(quadra_render_with(renderer, scene, target, NULL, &options, NULL),
               QUADRA_INVALID_ARGUMENT, "render options: shading 7 is not one of its values");
  options.shading = QUADRA_SHADING_UNLIT;
  options.max_memory = 1000;
  EXPECT(quadra_render_with(renderer, scene, target, NULL, &options, NULL) ==
         QUADRA_INVALID_ARGUMENT);
  EXPECT(strstr(quadra_last_error(), "over the memory budget of 1000 bytes") != NULL);
}

static void in_memory_quad(quadra_renderer* renderer) {
  /* x, y in [-0.5, 0.5] at z = 0, seen orthographically from z = 1 over
   * [-1, 1]^2: pixels 10..29 each way hold it (centres -0.475 .. 0.475). */
  const float positions[] = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0};
  const uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  quadra_scene* scene = NULL;
  EXPECT(quadra_scene_create(&scene) == QUADRA_OK);
  quadra_mesh_data mesh = {0};
  mesh.positions = positions;
  mesh.vertex_count = 4;
  mesh.indices32 = indices;
  mesh.index_count = 6;
  uint32_t mesh_id = 99, material_id = 99, instance_id = 99;
  EXPECT(quadra_scene_add_mesh(scene, &mesh, &mesh_id) == QUADRA_OK);
  quadra_material_data material = {{0.25f, 0.5f, 0.75f, 1.0f}, 0, 0, QUADRA_ALPHA_OPAQUE, 0.5f, 0};
  EXPECT(quadra_scene_add_material(scene, &material, &material_id) == QUADRA_OK);
  EXPECT(quadra_scene_add_instance(scene, mesh_id, material_id, NULL, &instance_id) == QUADRA_OK);
  quadra_camera_data camera = {QUADRA_ORTHOGRAPHIC,
                               0.8f,
                               1.0f,
                               0.5f,
                               2.0f,
                               {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1}};
  EXPECT(quadra_scene_set_camera(scene, &camera) == QUADRA_OK);

  memset(pixels, 0xA5, sizeof(pixels));
  quadra_target target = {pixels, sizeof(pixels), kSize, kSize, kStride, QUADRA_PIXEL_RGBA32F};
  quadra_depth_target depth_target = {depth, sizeof(depth), kDepthStride};
  EXPECT(quadra_render(renderer, scene, &target, &depth_target) == QUADRA_OK);
  int wrong = 0;
  const float base[4] = {0.25f, 0.5f, 0.75f, 1.0f};
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const int inside = x >= 10 && x < 30 && y >= 10 && y < 30;
      const float* p = &pixels[y * (kStride / 4) + x * 4];
      for (int c = 0; c < 4; ++c) wrong += p[c] != (inside ? base[c] : 0.0f);
      const float z = depth[y * (kDepthStride / 4) + x];
      /* (1 - 0.5) / (2 - 0.5) at the quad, 1 (the far plane) elsewhere */
      wrong += inside ? fabsf(z - 1.0f / 3.0f) > 1e-6f : z != 1.0f;
    }
  EXPECT(wrong == 0);
  /* the padding after each row is untouched */
  const unsigned char* bytes = (const unsigned char*)pixels;
  int touched = 0;
  for (int y = 0; y < kSize; ++y)
    for (int i = kSize * 16; i < kStride; ++i) touched += bytes[y * kStride + i] != 0xA5;
  EXPECT(touched == 0);

  /* A draw state: reverse-subtracted (ONE, ONE) from the clear colour 0,
   * unclamped, the quad shows 0 - base; without the state it is base again;
   * a value outside an enum is an error. */
  quadra_draw_state state = {1,
                             1,
                             QUADRA_COMPARE_LESS,
                             QUADRA_CULL_BACK,
                             1,
                             QUADRA_BLEND_REVERSE_SUBTRACT,
                             QUADRA_BLEND_REVERSE_SUBTRACT,
                             QUADRA_FACTOR_ONE,
                             QUADRA_FACTOR_ONE,
                             QUADRA_FACTOR_ONE,
                             QUADRA_FACTOR_ONE};
  EXPECT(quadra_scene_set_draw_state(scene, instance_id, &state) == QUADRA_OK);
  EXPECT(quadra_render(renderer, scene, &target, NULL) == QUADRA_OK);
  const float* centre = &pixels[20 * (kStride / 4) + 20 * 4];
  for (int c = 0; c < 4; ++c) EXPECT(centre[c] == -base[c]);
  EXPECT(quadra_scene_set_draw_state(scene, instance_id, NULL) == QUADRA_OK);
  EXPECT(quadra_render(renderer, scene, &target, NULL) == QUADRA_OK);
  for (int c = 0; c < 4; ++c) EXPECT(centre[c] == base[c]);
  state.cull = (quadra_cull)9;
  expect_error(quadra_scene_set_draw_state(scene, instance_id, &state), QUADRA_INVALID_ARGUMENT,
               "setDrawState: cull 9 is not one of its values");
  /* A value a one-byte C++ enum would wrap into range (257 -> 1) is refused too. */
  state.cull = QUADRA_CULL_NONE;
  state.dst_alpha = (quadra_blend_factor)257;
  expect_error(quadra_scene_set_draw_state(scene, instance_id, &state), QUADRA_INVALID_ARGUMENT,
               "setDrawState: dst_alpha 257 is not one of its values");

  aovs_of_the_quad(renderer, scene, &target, instance_id);
  options_of_the_quad(renderer, scene, &target, base);

  /* misuse */
  unsigned char before[sizeof(pixels)];
  memcpy(before, pixels, sizeof(pixels));
  quadra_target short_target = target;
  short_target.size_bytes = 1000;
  expect_error(quadra_render(renderer, scene, &short_target, NULL), QUADRA_INVALID_ARGUMENT,
               "render target: 40x40 at row stride 704 needs 28096 bytes, the buffer has 1000");
  quadra_target short_stride = target;
  short_stride.row_stride = 100;
  expect_error(quadra_render(renderer, scene, &short_stride, NULL), QUADRA_INVALID_ARGUMENT,
               "render target: row stride 100 bytes is less than a row's 40 x 16 = 640");
  EXPECT(memcmp(before, pixels, sizeof(pixels)) == 0);
  expect_error(quadra_render(NULL, scene, &target, NULL), QUADRA_INVALID_ARGUMENT,
               "quadra_render: an argument is NULL");
  const uint32_t bad_indices[] = {0, 1, 4};
  mesh.indices32 = bad_indices;
  mesh.index_count = 3;
  uint32_t unused = 0;
  expect_error(quadra_scene_add_mesh(scene, &mesh, &unused), QUADRA_INVALID_ARGUMENT,
               "mesh: index 4 (entry 2) is out of range for 4 vertices");
  quadra_texture_data empty = {0, 4, QUADRA_TEXTURE_RGBA8_SRGB, NULL, 0, 0, 0, 0, 0};
  expect_error(quadra_scene_add_texture(scene, &empty, &unused), QUADRA_INVALID_ARGUMENT,
               "texture: 0x4 texels; a texture needs at least one");
  const unsigned char white[4] = {255, 255, 255, 255};
  quadra_texture_data odd_wrap = {1, 1, QUADRA_TEXTURE_RGBA8_SRGB, white, 4, 4, 0, 0, 0};
  odd_wrap.wrap_v = (quadra_wrap)-1;
  expect_error(quadra_scene_add_texture(scene, &odd_wrap, &unused), QUADRA_INVALID_ARGUMENT,
               "texture: wrap_v -1 is not one of its values");
  quadra_camera_data odd_camera = camera;
  odd_camera.projection = (quadra_projection)2;
  expect_error(quadra_scene_set_camera(scene, &odd_camera), QUADRA_INVALID_ARGUMENT,
               "camera: projection 2 is not one of its values");
  quadra_target odd_target = target;
  odd_target.format = (quadra_pixel_format)300;
  expect_error(quadra_render(renderer, scene, &odd_target, NULL), QUADRA_INVALID_ARGUMENT,
               "render target: format 300 is not one of its values");
  float transform[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  transform[12] = NAN;
  expect_error(quadra_scene_set_transform(scene, instance_id, transform), QUADRA_INVALID_ARGUMENT,
               "instance transform: element 12 (column 3, row 0) is NaN");
  expect_error(quadra_scene_set_transform(scene, 5, NULL), QUADRA_INVALID_ARGUMENT,
               "setTransform: handle 5 is not one of this scene's 1");
  quadra_scene_destroy(scene);

  /* Use after destroy: an error naming the call, never freed memory; a
   * second destroy is harmless. */
  expect_error(quadra_scene_set_transform(scene, instance_id, NULL), QUADRA_INVALID_ARGUMENT,
               "quadra_scene_set_transform: the scene handle is not a live one (destroyed, or "
               "not made by quadra)");
  expect_error(quadra_render(renderer, scene, &target, NULL), QUADRA_INVALID_ARGUMENT,
               "quadra_render: the scene handle is not a live one (destroyed, or not made by "
               "quadra)");
  quadra_scene_destroy(scene);
  EXPECT(strstr(quadra_last_error(), "quadra_scene_destroy: the scene handle is not a live one") ==
         quadra_last_error());
  quadra_renderer* gone = NULL;
  EXPECT(quadra_renderer_create(1, &gone) == QUADRA_OK);
  quadra_renderer_destroy(gone);
  quadra_scene* other = NULL;
  EXPECT(quadra_scene_create(&other) == QUADRA_OK);
  expect_error(quadra_render(gone, other, &target, NULL), QUADRA_INVALID_ARGUMENT,
               "quadra_render: the renderer handle is not a live one (destroyed, or not made by "
               "quadra)");
  /* A renderer handle passed as a scene is not a scene. */
  expect_error(quadra_scene_set_camera((quadra_scene*)renderer, &camera), QUADRA_INVALID_ARGUMENT,
               "quadra_scene_set_camera: the scene handle is not a live one (destroyed, or not "
               "made by quadra)");
  quadra_scene_destroy(other);
}

static void gltf_file(quadra_renderer* renderer, const char* path) {
  quadra_scene* scene = NULL;
  EXPECT(quadra_scene_load(path, &scene) == QUADRA_OK);
  if (!scene) return;
  static unsigned char rgba8[kSize * kSize * 4];
  quadra_target target = {rgba8, sizeof(rgba8), kSize, kSize, kSize * 4, QUADRA_PIXEL_RGBA8_SRGB};
  EXPECT(quadra_render(renderer, scene, &target, NULL) == QUADRA_OK);
  int covered = 0;
  for (int i = 0; i < kSize * kSize; ++i) covered += rgba8[i * 4 + 3] != 0;
  EXPECT(covered > kSize * kSize / 10); /* the default camera frames the model */
  /* BoxTextured has no animation: only the rest pose exists. */
  int animations = -1;
  EXPECT(quadra_scene_animation_count(scene, &animations) == QUADRA_OK && animations == 0);
  EXPECT(quadra_scene_set_animation_time(scene, -1, 0.0) == QUADRA_OK);
  expect_error(quadra_scene_set_animation_time(scene, 0, 0.5), QUADRA_INVALID_ARGUMENT,
               "setAnimationTime: animation 0 is not one of the scene's 0 (or -1, the rest pose)");
  quadra_scene_destroy(scene);
  /* Load options: the budget is honoured, a NULL folder is refused. */
  quadra_load_options options = {NULL, 0, 1000, -1};
  quadra_scene* refused = NULL;
  EXPECT(quadra_scene_load_with(path, &options, &refused) == QUADRA_FAILED && refused == NULL);
  EXPECT(strstr(quadra_last_error(), "over the memory budget of 1000 bytes") != NULL);
  const char* folders[] = {"/tmp", NULL};
  options.allowed_paths = folders;
  options.allowed_path_count = 2;
  options.max_memory = 0; /* the default */
  expect_error(quadra_scene_load_with(path, &options, &refused), QUADRA_INVALID_ARGUMENT,
               "quadra_scene_load_with: allowed_paths[1] is NULL");
  options.allowed_path_count = 1;
  EXPECT(quadra_scene_load_with(path, &options, &refused) == QUADRA_OK && refused != NULL);
  quadra_scene_destroy(refused);
  quadra_scene* missing = NULL;
  EXPECT(quadra_scene_load("/nonexistent.glb", &missing) == QUADRA_FAILED);
  EXPECT(missing == NULL && strstr(quadra_last_error(), "/nonexistent.glb") != NULL);
}

enum { kLitWidth = 64, kLitHeight = 48 };
static float lit_color[kLitWidth * kLitHeight * 4];
static float lit_depth[kLitWidth * kLitHeight];
static float lit_other[kLitWidth * kLitHeight * 4];

/* A pbr frame of scene lit by environment (NULL: the default) into
   lit_color and lit_depth, or into `into` alone. */
static quadra_status render_lit(quadra_renderer* renderer, const quadra_scene* scene,
                                const quadra_environment* environment, float* into) {
  quadra_target target = {into ? into : lit_color, sizeof(lit_color),   kLitWidth, kLitHeight,
                          kLitWidth * 16,          QUADRA_PIXEL_RGBA32F};
  quadra_depth_target depth_target = {lit_depth, sizeof(lit_depth), kLitWidth * 4};
  quadra_render_options options = {QUADRA_SHADING_PBR, 1, {0, 0, 0, 0}, 0};
  quadra_lighting lighting = quadra_lighting_defaults();
  lighting.environment = environment;
  return quadra_render_lit(renderer, scene, &target, into ? NULL : &depth_target, &options,
                           &lighting, NULL);
}

/* Environments: one from an array lights as the same texels by name; the
   default is builtin:studio; the texel rule and the misuses. */
static void environments(quadra_renderer* renderer, const char* path) {
  quadra_scene* scene = NULL;
  EXPECT(quadra_scene_load(path, &scene) == QUADRA_OK);
  if (!scene) return;
  quadra_environment* sky = NULL;
  EXPECT(quadra_environment_load("builtin:sky", 0, &sky) == QUADRA_OK);
  int width = 0, height = 0;
  EXPECT(quadra_environment_size(sky, &width, &height) == QUADRA_OK && width * height >= 2);
  const size_t values = (size_t)width * (size_t)height * 3;
  float* texels = malloc(values * sizeof(float));
  EXPECT(texels && quadra_environment_texels(sky, texels, values) == QUADRA_OK);
  quadra_environment* copy = NULL;
  EXPECT(quadra_environment_create(texels, values, width, height, &copy) == QUADRA_OK);
  EXPECT(render_lit(renderer, scene, sky, lit_other) == QUADRA_OK);
  EXPECT(render_lit(renderer, scene, copy, NULL) == QUADRA_OK);
  EXPECT(memcmp(lit_color, lit_other, sizeof(lit_color)) == 0);
  /* No environment is builtin:studio's light, which differs from the sky's. */
  quadra_environment* studio = NULL;
  EXPECT(quadra_environment_load("builtin:studio", 0, &studio) == QUADRA_OK);
  EXPECT(render_lit(renderer, scene, NULL, lit_other) == QUADRA_OK);
  EXPECT(memcmp(lit_color, lit_other, sizeof(lit_color)) != 0);
  EXPECT(render_lit(renderer, scene, studio, NULL) == QUADRA_OK);
  EXPECT(memcmp(lit_color, lit_other, sizeof(lit_color)) == 0);
  /* The texel rule: NaN and negative values become 0. */
  texels[0] = NAN;
  texels[4] = -2.0f;
  quadra_environment* repaired = NULL;
  EXPECT(quadra_environment_create(texels, values, width, height, &repaired) == QUADRA_OK);
  EXPECT(quadra_environment_texels(repaired, texels, values) == QUADRA_OK);
  EXPECT(texels[0] == 0.0f && texels[4] == 0.0f && !signbit(texels[4]));
  /* Misuses: each a status and one line, no handle made. */
  quadra_environment* refused = NULL;
  EXPECT(quadra_environment_create(texels, 0, 0, 0, &refused) == QUADRA_INVALID_ARGUMENT);
  EXPECT(refused == NULL && strstr(quadra_last_error(), "at least 2 texels") != NULL);
  EXPECT(quadra_environment_create(texels, values - 3, width, height, &refused) ==
         QUADRA_INVALID_ARGUMENT);
  EXPECT(refused == NULL && strstr(quadra_last_error(), "texels need") != NULL);
  EXPECT(quadra_environment_load("/nonexistent.exr", 0, &refused) == QUADRA_FAILED);
  EXPECT(refused == NULL && strstr(quadra_last_error(), "/nonexistent.exr") != NULL);
  EXPECT(quadra_environment_texels(sky, texels, values + 1) == QUADRA_INVALID_ARGUMENT);
  quadra_render_options options = {QUADRA_SHADING_PBR, 1, {0, 0, 0, 0}, 0};
  quadra_lighting lighting = quadra_lighting_defaults();
  lighting.tone_map = (quadra_tone_map)9;
  quadra_target target = {lit_color,  sizeof(lit_color), kLitWidth,
                          kLitHeight, kLitWidth * 16,    QUADRA_PIXEL_RGBA32F};
  expect_error(quadra_render_lit(renderer, scene, &target, NULL, &options, &lighting, NULL),
               QUADRA_INVALID_ARGUMENT, "lighting: tone_map 9 is not one of its values");
  free(texels);
  quadra_environment_destroy(repaired);
  quadra_environment_destroy(copy);
  quadra_environment_destroy(studio);
  quadra_environment_destroy(sky);
  quadra_environment_destroy(sky);
  EXPECT(strcmp(quadra_last_error(),
                "quadra_environment_destroy: the environment handle is not a live one "
                "(destroyed, or not made by quadra)") == 0);
  quadra_scene_destroy(scene);
}

/* --lit: the frame of the environment in env_path, for the CLI comparison. */
static int lit_frame(const char* path, const char* env_path, int width, int height,
                     const char* out_path) {
  const size_t values = (size_t)width * (size_t)height * 3;
  float* texels = malloc(values * sizeof(float));
  FILE* in = fopen(env_path, "rb");
  EXPECT(texels && in && fread(texels, sizeof(float), values, in) == values);
  if (in) fclose(in);
  quadra_renderer* renderer = NULL;
  quadra_scene* scene = NULL;
  quadra_environment* environment = NULL;
  EXPECT(quadra_renderer_create(2, &renderer) == QUADRA_OK);
  EXPECT(quadra_scene_load(path, &scene) == QUADRA_OK);
  EXPECT(quadra_environment_create(texels, values, width, height, &environment) == QUADRA_OK);
  EXPECT(render_lit(renderer, scene, environment, NULL) == QUADRA_OK);
  FILE* out = fopen(out_path, "wb");
  EXPECT(out && fwrite(lit_color, sizeof(lit_color), 1, out) == 1 &&
         fwrite(lit_depth, sizeof(lit_depth), 1, out) == 1);
  if (out) fclose(out);
  quadra_environment_destroy(environment);
  quadra_scene_destroy(scene);
  quadra_renderer_destroy(renderer);
  free(texels);
  if (failures != 0) fprintf(stderr, "test_c_api --lit: %d failures\n", failures);
  return failures == 0 ? 0 : 1;
}

int main(int argc, char** argv) {
  if (argc == 7 && strcmp(argv[1], "--lit") == 0)
    return lit_frame(argv[2], argv[3], atoi(argv[4]), atoi(argv[5]), argv[6]);
  if (argc != 2) {
    fprintf(stderr,
            "usage: test_c_api FILE.glb\n"
            "       test_c_api --lit FILE.glb ENV.raw W H OUT.raw\n");
    return 1;
  }
  EXPECT(strcmp(quadra_version(), QUADRA_VERSION_STRING) == 0);
  quadra_renderer* renderer = NULL;
  EXPECT(quadra_renderer_create(2, &renderer) == QUADRA_OK);
  in_memory_quad(renderer);
  gltf_file(renderer, argv[1]);
  environments(renderer, argv[1]);
  quadra_renderer_destroy(renderer);
  quadra_scene_destroy(NULL);
  printf("test_c_api: %d failures\n", failures);
  return failures == 0 ? 0 : 1;
}
