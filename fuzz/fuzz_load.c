/* libFuzzer target: one file format's reader on arbitrary bytes, and the
 * renderer on whatever it loads. FUZZ_FILE_NAME (set by CMakeLists.txt)
 * names the input like a file, and so chooses the reader:
 *   scene.nff, scene.json        glint_scene_load_memory
 *   scene.pack                   glint_scene_load_packed (what glint-mpi's
 *                                ranks receive), the block's CRC-32 made
 *                                right for the mutated bytes but one time in
 *                                eight, so that mutations reach the parser
 *   mesh.obj, mesh.ply           the mesh readers, from memory
 *   mesh.ply.gz                  a temporary file: zlib and its size caps
 * A scene that loads is rendered 8x8 (smaller for scenes of many lights
 * and planes) by the scalar reference and by the widest SIMD backend: whatever
 * a reader accepts, the renderer must take; an animated one also with its
 * camera at a few frames' times. Build and run with scripts/fuzz.sh. */
/* mkstemps is a BSD/GNU extension */
#define _DEFAULT_SOURCE
#include <glint.h>

#include "scene/mesh.h"
#include "scene/scene.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#ifndef FUZZ_FILE_NAME
#error "define FUZZ_FILE_NAME, e.g. \"scene.nff\""
#endif

static int ends_with(const char *s, const char *end) {
  size_t n = strlen(s), e = strlen(end);
  return n >= e && strcmp(s + n - e, end) == 0;
}

/* A scene around a mesh: a camera looking at its bounds, a light, one
 * material. NULL when the mesh does not load (or the camera cannot see
 * it: an empty or degenerate mesh). */
static glint_scene *mesh_scene(const uint8_t *data, size_t size) {
  glint_scene *s;
  glint_error e;
  uint32_t material;
  glint_material m;
  glint_material_default(&m);
  m.kr = 0.3;
  m.kt = 0.5;
  m.ior = 1.3;
  if (glint_scene_create(&s, &e) ||
      glint_scene_add_material(s, &m, &material, &e) ||
      glint_scene_add_light(s, (glint_vec3){3, 5, 7}, (glint_vec3){1, 1, 1},
                            &e)) {
    glint_scene_destroy(s);
    return NULL;
  }
  glint_status st;
  if (ends_with(FUZZ_FILE_NAME, ".gz")) {
    char path[] = "/tmp/glint-fuzz-XXXXXX.ply.gz";
    int fd = mkstemps(path, 7);
    if (fd < 0)
      abort();
    if (write(fd, data, size) != (ssize_t)size)
      abort();
    close(fd);
    st = glint_scene_add_mesh_file(s, path, 1, (glint_vec3){0, 0, 0}, material,
                                   &e);
    unlink(path);
  } else {
    char *text = malloc(size + 1);
    if (!text)
      abort();
    memcpy(text, data, size);
    text[size] = '\0';
    st = gli_scene_add_mesh_data(s, FUZZ_FILE_NAME, text, size, 1,
                                 (glint_vec3){0, 0, 0}, material, &e);
    free(text);
  }
  glint_scene_info info;
  glint_scene_get_info(s, &info);
  if (st || info.triangles == 0) {
    glint_scene_destroy(s);
    return NULL;
  }
  glint_vec3 lo = info.bounds_min, hi = info.bounds_max;
  glint_vec3 at = {(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
  double extent = (hi.x - lo.x) + (hi.y - lo.y) + (hi.z - lo.z) + 1;
  glint_camera cam = {{at.x, at.y, at.z + 2 * extent}, at, {0, 1, 0}, 60};
  if (glint_scene_set_camera(s, &cam, &e)) {
    glint_scene_destroy(s);
    return NULL;
  }
  return s;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  glint_scene *scene = NULL;
  glint_error e;
  if (ends_with(FUZZ_FILE_NAME, ".nff") || ends_with(FUZZ_FILE_NAME, ".json")) {
    if (glint_scene_load_memory(data, size, FUZZ_FILE_NAME, &scene, &e))
      return 0;
  } else if (ends_with(FUZZ_FILE_NAME, ".pack")) {
    uint8_t *block = malloc(size ? size : 1);
    if (!block)
      return 0;
    if (size)
      memcpy(block, data, size);
    /* The block's last 4 bytes: zlib's CRC-32 of the rest (src/scene/pack.c).
     * The mutated last byte decides (the first is the magic's 'G'). */
    if (size >= 4 && data[size - 1] % 8 != 7) {
      uint32_t crc = (uint32_t)crc32_z(0, block, size - 4);
      for (int i = 0; i < 4; i++)
        block[size - 4 + (size_t)i] = (uint8_t)(crc >> (8 * i));
    }
    glint_status st = glint_scene_load_packed(block, size, &scene, &e);
    free(block);
    if (st)
      return 0;
  } else if (!(scene = mesh_scene(data, size))) {
    return 0;
  }
  /* The render's work grows as pixels x lights x planes (planes lie
   * outside the BVH): at 8x8 a scene of 762 lights took 1.6 s under the
   * sanitizers, which libFuzzer calls a hang although the renderer did
   * exactly the work asked (0.12 s in a release build). The image shrinks
   * so that pixels x (lights + 1) x (planes + 1) stays within 4096. */
  double cost =
      (double)(scene->light_count + 1) * (double)(scene->plane_count + 1);
  int side = 8;
  while (side > 1 && side * side * cost > 4096)
    side--;
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.width = rs.height = side;
  rs.spp = 1;
  rs.max_depth = 3;
  rs.threads = 1;
  const glint_backend backends[] = {GLINT_BACKEND_SCALAR_FLOAT,
                                    GLINT_BACKEND_AUTO, GLINT_BACKEND_STREAM};
  for (size_t i = 0; i < sizeof backends / sizeof *backends; i++) {
    glint_image *image = NULL;
    rs.backend = backends[i];
    if (glint_render(scene, &rs, &image, NULL, &e) == GLINT_OK)
      glint_image_destroy(image);
  }
  /* An animated scene: its camera at the frames' times and between them,
   * and one frame rendered with it. */
  glint_animation anim;
  if (glint_scene_get_animation(scene, &anim)) {
    glint_camera camera;
    for (int f = anim.first_frame;
         f <= anim.last_frame && f < anim.first_frame + 4; f++)
      glint_scene_camera_at(scene, (f - anim.first_frame + 0.5) / anim.fps,
                            &camera, &e);
    if (glint_scene_camera_at(scene, 1 / anim.fps, &camera, &e) == GLINT_OK &&
        glint_scene_set_camera(scene, &camera, &e) == GLINT_OK) {
      glint_image *image = NULL;
      rs.backend = GLINT_BACKEND_AUTO;
      if (glint_render(scene, &rs, &image, NULL, &e) == GLINT_OK)
        glint_image_destroy(image);
    }
  }
  glint_scene_destroy(scene);
  return 0;
}
