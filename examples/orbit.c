/* Many frames of one scene through the public API alone: the scene is
 * committed once into a world, one renderer keeps its threads between
 * frames, and each frame moves the camera a step around the point looked
 * at. A tile callback counts the tiles as they finish (a window would draw
 * them); the last frame is converted to 8 bits and written.
 *
 *   orbit [SCENE] [FRAMES] [OUTPUT]    (defaults: whitted, 36, orbit.png)
 */
#include <glint.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(const glint_error *err) {
  fprintf(stderr, "orbit: %s\n", err->message);
  return 1;
}

/* The camera turned by `degrees` about the vertical axis through the point
 * it looks at. */
static glint_camera orbit(const glint_camera *c, double degrees) {
  double a = degrees * 3.14159265358979323846 / 180.0;
  double dx = c->from.x - c->at.x, dz = c->from.z - c->at.z;
  glint_camera moved = *c;
  moved.from.x = c->at.x + dx * cos(a) - dz * sin(a);
  moved.from.z = c->at.z + dx * sin(a) + dz * cos(a);
  return moved;
}

static int count_tile(void *user, const glint_tile *tile) {
  (void)tile;
  ++*(long *)user;
  return 0; /* non-zero would cancel the frame */
}

int main(int argc, char **argv) {
  const char *name = argc > 1 ? argv[1] : "whitted";
  int frames = argc > 2 ? atoi(argv[2]) : 36;
  const char *output = argc > 3 ? argv[3] : "orbit.png";
  if (frames < 1) {
    fprintf(stderr, "orbit: FRAMES must be a whole number >= 1\n");
    return 2;
  }
  glint_error err;
  glint_scene *scene;
  /* A name with a '.' or a '/' is a scene file, anything else built in. */
  glint_status st = strpbrk(name, "./")
                        ? glint_scene_load(name, &scene, &err)
                        : glint_scene_builtin(name, &scene, &err);
  if (st)
    return fail(&err);
  glint_scene_info info;
  glint_scene_get_info(scene, &info);

  glint_render_settings settings;
  glint_render_settings_default(&settings);
  settings.spp = 1;
  glint_world *world = NULL;
  glint_renderer *renderer = NULL;
  glint_film *film = NULL;
  glint_image *image = NULL;
  st = glint_world_commit(scene, &world, NULL, &err);
  glint_scene_destroy(scene); /* the world keeps its own copy */
  if (st || glint_renderer_create(world, &settings, &renderer, &err) ||
      glint_film_create(info.width, info.height, &film, &err) ||
      glint_image_create(info.width, info.height, &image, &err)) {
    glint_film_destroy(film);
    glint_world_destroy(world);
    glint_renderer_destroy(renderer);
    return fail(&err);
  }
  glint_world_destroy(world); /* the renderer holds its own reference */

  long tiles = 0;
  glint_frame_settings frame;
  glint_frame_settings_default(&frame);
  frame.tile = count_tile;
  frame.tile_user = &tiles;
  for (int i = 0; i < frames && st == GLINT_OK; i++) {
    glint_camera camera = orbit(&info.camera, 360.0 * i / frames);
    frame.camera = &camera;
    st = glint_renderer_render(renderer, &frame, film, NULL, &err);
  }
  if (st == GLINT_OK &&
      (st = glint_film_to_image(film, 1.0, image, &err)) == GLINT_OK)
    st = glint_image_write(image, output, &err);
  glint_image_destroy(image);
  glint_film_destroy(film);
  glint_renderer_destroy(renderer);
  if (st)
    return fail(&err);
  printf("%s: %d frames of %dx%d, %ld tiles\n", output, frames, info.width,
         info.height, tiles);
  return 0;
}
