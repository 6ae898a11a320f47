/* glint bench --frames N: what a frame costs beyond its rendering.
 *
 * The same N frames (the scene's camera orbiting its look-at point by one
 * degree a frame) are rendered twice, interleaved frame by frame so that
 * both see the same machine: through one world and one renderer
 * (glint_renderer_render into a film), and through one glint_render call
 * each (which commits the scene, starts threads and converts to 8 bits
 * every time). For each path it prints the median wall time of a frame and
 * the median time its threads spent rendering tiles (stats.render_seconds);
 * the renderer's overhead is the difference, as a share of the latter. */
#include "args.h"
#include "bench.h"
#include "cli.h"

#include <glint.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static glint_camera orbit(const glint_camera *c, int frame) {
  double a = frame * 3.14159265358979323846 / 180.0;
  double dx = c->from.x - c->at.x, dz = c->from.z - c->at.z;
  glint_camera moved = *c;
  moved.from.x = c->at.x + dx * cos(a) - dz * sin(a);
  moved.from.z = c->at.z + dx * sin(a) + dz * cos(a);
  return moved;
}

typedef struct frame_times {
  double *wall, *render;
} frame_times;

int bench_frames(const char *scene_name, const glint_render_settings *base,
                 int frames) {
  char stem[CLI_STEM_SIZE];
  int code = EXIT_USAGE;
  glint_scene *scene = cli_load_scene(scene_name, stem, sizeof stem, &code);
  if (!scene)
    return code;
  glint_render_settings rs = *base;
  glint_scene_info info;
  glint_scene_get_info(scene, &info);
  int width = rs.width ? rs.width : info.width;
  int height = rs.height ? rs.height : info.height;
  glint_error err;
  glint_world *world = NULL;
  glint_renderer *renderer = NULL;
  glint_film *film = NULL;
  frame_times paths[2];
  for (int p = 0; p < 2; p++) {
    paths[p].wall = calloc((size_t)frames, sizeof(double));
    paths[p].render = calloc((size_t)frames, sizeof(double));
  }
  int status = 1;
  if (!paths[0].wall || !paths[0].render || !paths[1].wall ||
      !paths[1].render) {
    cli_error("out of memory");
    goto done;
  }
  if (glint_world_commit(scene, &world, NULL, &err) ||
      glint_renderer_create(world, &rs, &renderer, &err) ||
      glint_film_create(width, height, &film, &err)) {
    cli_error("%s", err.message);
    status = cli_exit_code(err.status);
    goto done;
  }
  glint_stats st;
  /* A warm-up frame each way: page faults and caches, not per-frame cost. */
  for (int f = -1; f < frames; f++) {
    glint_camera cam = orbit(&info.camera, f);
    glint_frame_settings fs;
    glint_frame_settings_default(&fs);
    fs.camera = &cam;
    double t0 = cli_now();
    if (glint_renderer_render(renderer, &fs, film, &st, &err)) {
      cli_error("%s", err.message);
      goto done;
    }
    double t1 = cli_now();
    if (f >= 0) {
      paths[0].wall[f] = t1 - t0;
      paths[0].render[f] = st.render_seconds;
    }
    glint_image *image;
    t0 = cli_now();
    if (glint_scene_set_camera(scene, &cam, &err) ||
        glint_render(scene, &rs, &image, &st, &err)) {
      cli_error("%s", err.message);
      goto done;
    }
    t1 = cli_now();
    glint_image_destroy(image);
    if (f >= 0) {
      paths[1].wall[f] = t1 - t0;
      paths[1].render[f] = st.render_seconds;
    }
  }
  static const char *const names[2] = {"one renderer", "glint_render"};
  printf("%d frames of %s at %dx%d, %d spp, depth %d, %s, %d thread%s, the "
         "camera orbiting (medians)\n",
         frames, stem, width, height, rs.spp, rs.max_depth,
         glint_backend_name(st.backend), st.threads,
         st.threads == 1 ? "" : "s");
  printf("%-14s %12s %12s %12s %9s\n", "path", "frame ms", "render ms",
         "overhead ms", "overhead");
  for (int p = 0; p < 2; p++) {
    double wall = bench_median(paths[p].wall, frames);
    double render = bench_median(paths[p].render, frames);
    printf("%-14s %12.3f %12.3f %12.3f %8.1f%%\n", names[p], 1e3 * wall,
           1e3 * render, 1e3 * (wall - render), 100 * (wall - render) / render);
  }
  status = 0;
done:
  for (int p = 0; p < 2; p++) {
    free(paths[p].wall);
    free(paths[p].render);
  }
  glint_film_destroy(film);
  glint_renderer_destroy(renderer);
  glint_world_destroy(world);
  glint_scene_destroy(scene);
  return status;
}
