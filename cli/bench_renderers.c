/* The renderers a benchmark table times: one scene's world, committed once,
 * and a renderer per column, made at the column's first frame and kept for
 * every later run and depth, as an application that renders many frames
 * keeps one (glint view, animations, glint-mpi).
 *
 * Timing a glint_render call per run instead measured, besides the render,
 * glibc returning the last call's scratch memory to the system and the
 * next call faulting it in again: the renderer, its threads and their
 * buffers were made and freed every call, and a worker thread allocates
 * from a malloc arena of its own, which glibc trims. Whitted at 640x480,
 * depth 5, 1 spp, two threads: the AVX-512 beams took 0.0037 s a frame
 * between stream-avx512 frames and 0.0015 s alone, the stream renderer
 * faulting in about 1 000 pages a call. A one-shot render's whole cost
 * (loading, committing, writing the file) is what --time-to-image
 * measures.
 *
 * A column of auto renders each depth with the backend glint render would
 * choose for it (glint_backend_choose weighs the depth), so it may keep a
 * renderer for each backend it chose. The tables open one set of renderers
 * per scene and thread count, so that their threads and stream buffers
 * stay what one thread count's columns need. */
#include "args.h"
#include "bench.h"

#include <stdlib.h>

int bench_renderers_open(bench_renderers *b, const glint_scene *scene,
                         const char *name, int ncols, int deepest,
                         int *status) {
  glint_error err;
  glint_status st;
  b->scene = scene;
  b->ncols = ncols;
  b->deepest = deepest;
  b->film = NULL;
  b->renderers =
      calloc((size_t)ncols * GLINT_BACKEND_COUNT, sizeof *b->renderers);
  if (!b->renderers) {
    cli_error("out of memory");
    *status = EXIT_MEMORY;
    return -1;
  }
  if ((st = glint_world_commit(scene, &b->world, NULL, &err))) {
    cli_error("%s: %s", name, err.message);
    free(b->renderers);
    *status = cli_exit_code(st);
    return -1;
  }
  return 0;
}

static void bench_renderers_drop(bench_renderers *b) {
  for (size_t k = 0; k < (size_t)b->ncols * GLINT_BACKEND_COUNT; k++) {
    glint_renderer_destroy(b->renderers[k]);
    b->renderers[k] = NULL;
  }
}

glint_status bench_renderers_render(bench_renderers *b, int col,
                                    const glint_render_settings *rs,
                                    glint_stats *stats, glint_error *err) {
  glint_status st;
  glint_backend backend = glint_backend_choose(rs->backend, b->scene, rs);
  glint_renderer **renderer =
      &b->renderers[(size_t)col * GLINT_BACKEND_COUNT + backend];
  if (!*renderer) {
    /* Made for the deepest frame of the table, so that no later frame
     * grows the stream buffers inside its timed render. */
    glint_render_settings made = *rs;
    made.backend = backend;
    made.max_depth = b->deepest;
    st = glint_renderer_create(b->world, &made, renderer, err);
    if (st == GLINT_E_MEMORY) {
      /* Too little memory for every column's renderer at once (an
       * address-space limit, many threads): the others go, each made again
       * when its column comes round, as one glint_render a frame was. */
      bench_renderers_drop(b);
      st = glint_renderer_create(b->world, &made, renderer, err);
    }
    if (st)
      return st;
  }
  glint_scene_info info;
  glint_world_get_info(b->world, &info);
  int w = rs->width ? rs->width : info.width;
  int h = rs->height ? rs->height : info.height;
  if (b->film &&
      (glint_film_width(b->film) != w || glint_film_height(b->film) != h)) {
    glint_film_destroy(b->film);
    b->film = NULL;
  }
  if (!b->film && (st = glint_film_create(w, h, &b->film, err)))
    return st;
  glint_frame_settings frame;
  glint_frame_settings_default(&frame);
  frame.width = w;
  frame.height = h;
  frame.max_depth = rs->max_depth;
  frame.spp = rs->spp;
  return glint_renderer_render(*renderer, &frame, b->film, stats, err);
}

void bench_renderers_close(bench_renderers *b) {
  bench_renderers_drop(b);
  free(b->renderers);
  glint_film_destroy(b->film);
  glint_world_destroy(b->world);
}

int bench_thread_group_end(const bench_column *cols, int ncols, int first) {
  int end = first + 1;
  while (end < ncols && cols[end].threads == cols[first].threads)
    end++;
  return end;
}
