/* examples/triangle.cpp through the C API (<quadra/quadra.h> only): the same
 * vertex-coloured triangle rendered into the program's own 8-bit sRGB
 * buffer; prints its centre pixel. Every call returns a status; on failure
 * quadra_last_error() is the one-line message. */
#include <stdint.h>
#include <stdio.h>

#include <quadra/quadra.h>

enum { kWidth = 640, kHeight = 360 };

static int ok(quadra_status status) {
  if (status != QUADRA_OK) fprintf(stderr, "%s\n", quadra_last_error());
  return status == QUADRA_OK;
}

int main(void) {
  static const float positions[] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
  static const float colors[] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1}; /* linear RGBA */
  static const uint32_t indices[] = {0, 1, 2};
  static uint8_t pixels[kWidth * kHeight * 4]; /* the program's own buffer */

  quadra_mesh_data mesh = {0};
  mesh.positions = positions;
  mesh.colors = colors;
  mesh.vertex_count = 3;
  mesh.indices32 = indices;
  mesh.index_count = 3;
  quadra_material_data material = {{1, 1, 1, 1}, 0, 0, QUADRA_ALPHA_OPAQUE, 0.5f, 0};
  /* Column-major camera-to-world: at (0, 0, 3), looking down -z. */
  quadra_camera_data camera = {QUADRA_PERSPECTIVE,
                               0.8f,
                               1.0f,
                               0.1f,
                               0.0f, /* zfar 0: infinite */
                               {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 3, 1}};
  quadra_target target = {pixels, sizeof pixels, kWidth, kHeight, kWidth * 4,
                          QUADRA_PIXEL_RGBA8_SRGB};

  quadra_scene* scene = NULL;
  quadra_renderer* renderer = NULL;
  uint32_t mesh_id, material_id, instance_id;
  const int rendered = ok(quadra_scene_create(&scene)) &&
                       ok(quadra_scene_add_mesh(scene, &mesh, &mesh_id)) &&
                       ok(quadra_scene_add_material(scene, &material, &material_id)) &&
                       ok(quadra_scene_add_instance(scene, mesh_id, material_id, NULL,
                                                    &instance_id)) && /* identity */
                       ok(quadra_scene_set_camera(scene, &camera)) &&
                       ok(quadra_renderer_create(2, &renderer)) &&
                       ok(quadra_render(renderer, scene, &target, NULL));
  quadra_renderer_destroy(renderer); /* both accept NULL */
  quadra_scene_destroy(scene);
  if (!rendered) return 1;
  const uint8_t* centre = &pixels[(180 * kWidth + 320) * 4];
  printf("quadra %s: centre pixel %d %d %d %d\n", quadra_version(), centre[0], centre[1],
         centre[2], centre[3]);
  return centre[3] == 255 ? 0 : 1;
}
