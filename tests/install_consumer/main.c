/* The C embedder: main.cpp's quad through the C API (quadra/quadra.h only),
 * rendered into its own padded buffers and written as main.cpp writes it,
 * for read_reference to compare with the CLI's EXR.
 *   consumer_c OUT.raw */
#include <stdio.h>
#include <string.h>

#include <quadra/quadra.h>

enum { kWidth = 64, kHeight = 48, kStride = 1024, kDepthStride = 300 };

static const float kPositions[] = {-0.7f, -0.6f, 0, 0.8f, -0.7f, 0, 0.6f, 0.7f, 0, -0.8f, 0.5f, 0};
static const float kColors[] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 0.5f};
static const uint16_t kIndices[] = {0, 1, 2, 0, 2, 3};
static float pixels[kStride / 4 * kHeight], depth[kDepthStride / 4 * kHeight];

static int check(quadra_status status, const char* what) {
  if (status != QUADRA_OK) fprintf(stderr, "consumer_c: %s: %s\n", what, quadra_last_error());
  return status == QUADRA_OK;
}

int main(int argc, char** argv) {
  if (argc != 2) return fprintf(stderr, "usage: consumer_c OUT.raw\n"), 1;
  quadra_scene* scene = NULL;
  quadra_renderer* renderer = NULL;
  quadra_mesh_data mesh = {0};
  mesh.positions = kPositions;
  mesh.colors = kColors;
  mesh.vertex_count = 4;
  mesh.indices16 = kIndices;
  mesh.index_count = 6;
  const quadra_material_data material = {{0.9f, 0.8f, 1.0f, 1.0f}, 0,    0,
                                         QUADRA_ALPHA_OPAQUE,      0.5f, 1};
  const quadra_camera_data camera = {QUADRA_ORTHOGRAPHIC,
                                     0.8f,
                                     1.0f,
                                     0.5f,
                                     2.0f,
                                     {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1}};
  quadra_target target = {pixels, sizeof(pixels), kWidth, kHeight, kStride, QUADRA_PIXEL_RGBA32F};
  quadra_depth_target depth_target = {depth, sizeof(depth), kDepthStride};
  uint32_t mesh_id, material_id, instance_id;
  int ok = check(quadra_scene_create(&scene), "scene") &&
           check(quadra_scene_add_mesh(scene, &mesh, &mesh_id), "mesh") &&
           check(quadra_scene_add_material(scene, &material, &material_id), "material") &&
           check(quadra_scene_add_instance(scene, mesh_id, material_id, NULL, &instance_id),
                 "instance") &&
           check(quadra_scene_set_camera(scene, &camera), "camera") &&
           check(quadra_renderer_create(2, &renderer), "renderer") &&
           check(quadra_render(renderer, scene, &target, &depth_target), "render");
  quadra_renderer_destroy(renderer);
  quadra_scene_destroy(scene);
  if (!ok) return 1;
  FILE* out = fopen(argv[1], "wb");
  if (!out) return 1;
  for (int y = 0; y < kHeight; ++y) fwrite(&pixels[y * kStride / 4], 16, kWidth, out);
  for (int y = 0; y < kHeight; ++y) fwrite(&depth[y * kDepthStride / 4], 4, kWidth, out);
  ok = fclose(out) == 0;
  printf("consumer_c: quadra %s (headers %s), rendered %dx%d\n", quadra_version(),
         QUADRA_VERSION_STRING, kWidth, kHeight);
  return ok && strcmp(quadra_version(), QUADRA_VERSION_STRING) == 0 ? 0 : 1;
}
