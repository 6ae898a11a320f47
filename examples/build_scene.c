/* A scene built in code and written as a PNG: a checkered floor, a glass
 * sphere, a mirror sphere, a solid-checkered cone and a small mesh (a
 * pyramid given as arrays), under two lights.
 *
 *   build_scene [OUTPUT]    (default: build_scene.png)
 */
#include <glint.h>

#include <stdio.h>

/* Every glint call reports failure the same way: a status and a message. */
#define TRY(call)                                                              \
  do {                                                                         \
    if ((call) != GLINT_OK) {                                                  \
      fprintf(stderr, "build_scene: %s\n", err.message);                       \
      glint_scene_destroy(scene);                                              \
      return 1;                                                                \
    }                                                                          \
  } while (0)

int main(int argc, char **argv) {
  const char *output = argc > 1 ? argv[1] : "build_scene.png";
  glint_error err;
  glint_scene *scene = NULL;
  TRY(glint_scene_create(&scene, &err));

  glint_camera camera = {{0, 3, 9}, {0, 1, 0}, {0, 1, 0}, 55};
  TRY(glint_scene_set_camera(scene, &camera, &err));
  TRY(glint_scene_set_resolution(scene, 640, 400, &err));
  TRY(glint_scene_set_background(scene, (glint_vec3){0.25, 0.45, 0.85}, &err));
  TRY(glint_scene_add_light(scene, (glint_vec3){-5, 10, 8},
                            (glint_vec3){1, 1, 1}, &err));
  TRY(glint_scene_add_light(scene, (glint_vec3){6, 4, 6},
                            (glint_vec3){0.3, 0.3, 0.35}, &err));

  /* Materials start from glint_material_default (white matte) and change
   * what they need: docs/specification.md section 4 gives the model. */
  glint_material floor, glass, mirror, checker, clay;
  glint_material_default(&floor);
  floor.texture = GLINT_TEXTURE_CHECKER_PLANAR;
  floor.checker_odd = (glint_vec3){0.9, 0.9, 0.9};
  floor.checker_even = (glint_vec3){0.2, 0.2, 0.2};
  floor.checker_size = 1;
  glint_material_default(&glass);
  glass.ka = 0.01, glass.kd = 0.01, glass.ks = 0.9, glass.h = 80;
  glass.kr = 0.1, glass.kt = 0.9, glass.ior = 1.5;
  glass.absorb = (glint_vec3){0.1, 0.025, 0}; /* Beer's law: a blue tint */
  glint_material_default(&mirror);
  mirror.color = (glint_vec3){0.8, 0.8, 0.8};
  mirror.kd = 0.2, mirror.ks = 0.8, mirror.h = 200, mirror.kr = 0.8;
  glint_material_default(&checker);
  checker.texture = GLINT_TEXTURE_CHECKER_SOLID;
  checker.checker_odd = (glint_vec3){0.9, 0.2, 0.1};
  checker.checker_even = (glint_vec3){0.9, 0.8, 0.2};
  checker.checker_size = 0.25;
  glint_material_default(&clay);
  clay.color = (glint_vec3){0.8, 0.45, 0.3};
  uint32_t m_floor, m_glass, m_mirror, m_checker, m_clay;
  TRY(glint_scene_add_material(scene, &floor, &m_floor, &err));
  TRY(glint_scene_add_material(scene, &glass, &m_glass, &err));
  TRY(glint_scene_add_material(scene, &mirror, &m_mirror, &err));
  TRY(glint_scene_add_material(scene, &checker, &m_checker, &err));
  TRY(glint_scene_add_material(scene, &clay, &m_clay, &err));

  TRY(glint_scene_add_plane(scene, (glint_vec3){0, 1, 0}, (glint_vec3){0, 0, 0},
                            m_floor, &err));
  TRY(glint_scene_add_sphere(scene, (glint_vec3){0.4, 1.2, 1.5}, 1.2, m_glass,
                             &err));
  TRY(glint_scene_add_sphere(scene, (glint_vec3){-2.5, 1, -1}, 1, m_mirror,
                             &err));
  TRY(glint_scene_add_cone(scene, (glint_vec3){2.8, 0, -0.5}, 0.8,
                           (glint_vec3){2.8, 2.2, -0.5}, 0, m_checker, &err));

  /* A mesh from arrays: a square pyramid, counter-clockwise from outside. */
  const glint_vec3 corners[] = {
      {-1, 0, -4}, {1, 0, -4}, {1, 0, -2}, {-1, 0, -2}, {0, 1.6, -3}};
  const uint32_t faces[] = {0, 4, 1, 1, 4, 2, 2, 4, 3, 3, 4, 0};
  glint_mesh pyramid = {corners, NULL, 5, faces, 4};
  TRY(glint_scene_add_mesh(scene, &pyramid, m_clay, &err));

  glint_render_settings settings;
  glint_render_settings_default(&settings); /* 5 spp, depth 5, every core */
  settings.gamma = 2.2;
  glint_image *image = NULL;
  TRY(glint_render(scene, &settings, &image, NULL, &err));
  glint_status st = glint_image_write(image, output, &err);
  glint_image_destroy(image);
  TRY(st);
  glint_scene_destroy(scene);
  printf("%s\n", output);
  return 0;
}
