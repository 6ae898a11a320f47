/* glint-mpi without --frames: one image, in square tiles (the last row and
 * column cut to the image), rank 0 writing each tile into the output as it
 * arrives (glint_image_writer encodes while the rest renders; a .pfm or
 * .exr film is filled and written at the end). */
#include "mpi.h"

#include <pthread.h>
#include <stdio.h>
#include <string.h>

typedef struct tile_job {
  const mpi_world *world;
  glint_renderer *renderer;
  int frame_width, frame_height; /* the frame the tiles are windows of */
  int origin_x, origin_y;        /* the output's corner in the frame */
  int width, height;             /* the output's */
  int side, columns;
  /* rank 0's output: an 8-bit image, or a film; its own tiles (from the
   * thread that renders them) and the workers' (from the main thread) go
   * in one at a time */
  cli_tile_sink sink;
  glint_film *film;
  pthread_mutex_t output_lock;
} tile_job;

/* The default tile side. A rank renders a tile with all its threads, in
 * glint's own tiles of GLINT_TILE_SIZE pixels, taken by its threads as they
 * finish: with at least 16 of those a thread, a tile's last ones keep few
 * threads waiting (at 16 threads, 64-pixel tiles gave each thread one, and
 * one rank rendered 4K Billiard 2.4x slower than glint render; 256 pixels
 * gave 1.05x). Smaller again, down to 64, while the image has fewer than 8
 * tiles a rank, so that the dynamic schedule can still even out the ranks. */
static int default_side(int most_threads, int width, int height, int ranks) {
  int side = 64;
  while (side < 4096 && (side / GLINT_TILE_SIZE) * (side / GLINT_TILE_SIZE) <
                            16 * most_threads)
    side += GLINT_TILE_SIZE;
  while (side > 64 &&
         ((width + side - 1) / side) * ((height + side - 1) / side) < 8 * ranks)
    side -= GLINT_TILE_SIZE;
  return side;
}

/* Unit u's window of the output. */
static void tile_rect(const tile_job *t, int unit, int *x, int *y, int *w,
                      int *h) {
  *x = (unit % t->columns) * t->side;
  *y = (unit / t->columns) * t->side;
  *w = t->width - *x < t->side ? t->width - *x : t->side;
  *h = t->height - *y < t->side ? t->height - *y : t->side;
}

static void tile_name(void *context, int unit, char *name, size_t size) {
  int x, y, w, h;
  tile_rect(context, unit, &x, &y, &w, &h);
  snprintf(name, size, "tile %d at %d,%d", unit, x, y);
}

/* Into rank 0's output: a tile of frame pixels. */
static int put_tile_locked(tile_job *t, const glint_tile *tile) {
  if (t->sink.writer)
    return cli_tile_to_writer(&t->sink, tile);
  float *film = glint_film_pixels(t->film);
  for (int row = 0; row < tile->height; row++)
    memcpy(film +
               3 * ((size_t)(tile->y - t->origin_y + row) * (size_t)t->width +
                    (size_t)(tile->x - t->origin_x)),
           tile->pixels + (size_t)row * tile->stride,
           3 * sizeof(float) * (size_t)tile->width);
  return 0;
}

static int put_tile(void *user, const glint_tile *tile) {
  tile_job *t = user;
  pthread_mutex_lock(&t->output_lock);
  int r = put_tile_locked(t, tile);
  pthread_mutex_unlock(&t->output_lock);
  return r;
}

static int render_tile(void *context, int unit, void *result, size_t *size,
                       glint_error *error) {
  tile_job *t = context;
  int x, y, w, h;
  tile_rect(t, unit, &x, &y, &w, &h);
  float *pixels = result;
  *size = 3 * sizeof(float) * (size_t)w * (size_t)h;
  mpi_unit_buffer buffer = {pixels, t->origin_x + x, t->origin_y + y, w};
  glint_frame_settings frame;
  glint_frame_settings_default(&frame);
  frame.width = t->frame_width;
  frame.height = t->frame_height;
  frame.region_x = t->origin_x + x;
  frame.region_y = t->origin_y + y;
  frame.region_width = w;
  frame.region_height = h;
  frame.progress = mpi_on_progress;
  frame.progress_user = (void *)t->world;
  frame.tile = pixels ? mpi_copy_tile : put_tile;
  frame.tile_user = pixels ? (void *)&buffer : (void *)t;
  glint_status st =
      glint_renderer_render(t->renderer, &frame, NULL, NULL, error);
  pthread_mutex_lock(&t->output_lock);
  if (st == GLINT_E_CANCELLED && t->sink.failed)
    *error = t->sink.error;
  pthread_mutex_unlock(&t->output_lock);
  return st ? -1 : 0;
}

static int take_tile(void *context, int unit, int rank, const void *result,
                     size_t size, glint_error *error) {
  (void)rank;
  tile_job *t = context;
  int x, y, w, h;
  tile_rect(t, unit, &x, &y, &w, &h);
  const float *pixels = result;
  if (size != 3 * sizeof(float) * (size_t)w * (size_t)h) {
    error->status = GLINT_E_PARSE; /* the worker's */
    snprintf(error->message, sizeof error->message,
             "%zu bytes, not the tile's %dx%d pixels", size, w, h);
    return -1;
  }
  glint_tile tile = {t->origin_x + x, t->origin_y + y, w, h,
                     pixels,          3 * (size_t)w};
  pthread_mutex_lock(&t->output_lock);
  int r = put_tile_locked(t, &tile);
  if (r)
    *error = t->sink.error;
  pthread_mutex_unlock(&t->output_lock);
  return r ? -1 : 0;
}

static void abandon(void *context) {
  tile_job *t = context;
  glint_image_writer_discard(t->sink.writer);
  t->sink.writer = NULL;
}

int mpi_render_tiles(const mpi_world *w, const mpi_options *o,
                     glint_scene *scene, glint_renderer *renderer,
                     const char *stem) {
  const glint_render_settings *rs = &o->render.settings;
  glint_scene_info info;
  glint_scene_get_info(scene, &info);
  tile_job t;
  memset(&t, 0, sizeof t);
  t.world = w;
  t.renderer = renderer;
  t.frame_width = rs->width ? rs->width : info.width;
  t.frame_height = rs->height ? rs->height : info.height;
  t.width = t.frame_width;
  t.height = t.frame_height;
  if (rs->region_width) {
    t.origin_x = rs->region_x, t.origin_y = rs->region_y;
    t.width = rs->region_width, t.height = rs->region_height;
  }
  t.side = o->tile_size
               ? o->tile_size
               : default_side(o->most_threads, t.width, t.height, w->size);
  t.columns = (t.width + t.side - 1) / t.side;
  int rows = (t.height + t.side - 1) / t.side;
  t.sink.origin_x = t.origin_x;
  t.sink.origin_y = t.origin_y;

  /* Rank 0 opens the output before anyone renders: a path that takes no
   * file fails now, not after the render. */
  char default_output[300];
  const char *output = o->render.output;
  if (!output) {
    snprintf(default_output, sizeof default_output, "%s.png", stem);
    output = default_output;
  }
  int film_output = cli_is_film_path(output);
  glint_error err = {0};
  glint_status st = GLINT_OK;
  if (w->rank == 0) {
    if (cli_check_output_format(output, o->render.scene, &err))
      st = GLINT_E_ARGUMENT;
    else if (film_output && rs->gamma != 1)
      st = GLINT_E_ARGUMENT,
      snprintf(err.message, sizeof err.message,
               "%s: --gamma applies to 8-bit images; .pfm and .exr are "
               "linear",
               output);
    else if (film_output)
      st = glint_film_check_writable(output, &err);
    else
      st = glint_image_writer_open(output, t.width, t.height, rs->gamma,
                                   o->render.png_compression, &t.sink.writer,
                                   &err);
    if (!st && film_output)
      st = glint_film_create(t.width, t.height, &t.film, &err);
  }
  /* The tile's region must lie in the frame; the renderer says so once. */
  int refused = mpi_agree(w, st, err.message);
  if (refused) {
    glint_image_writer_discard(t.sink.writer);
    glint_film_destroy(t.film);
    return refused;
  }
  pthread_mutex_init(&t.output_lock, NULL);
  mpi_world *world = (mpi_world *)w;
  world->abandon = abandon;
  world->abandon_context = &t;

  char stopped[480];
  snprintf(stopped, sizeof stopped,
           "stopped by a signal (Ctrl-C, or mpirun ending the job, as it does "
           "when a rank dies); %s was not written",
           output);
  int by_rank[w->size > 0 ? w->size : 1];
  double seconds_by_rank[w->size > 0 ? w->size : 1];
  memset(by_rank, 0, sizeof by_rank);
  memset(seconds_by_rank, 0, sizeof seconds_by_rank);
  mpi_job job = {.world = w,
                 .units = t.columns * rows,
                 .unit_bytes =
                     3 * sizeof(float) * (size_t)t.side * (size_t)t.side,
                 .dynamic = o->dynamic,
                 .in_flight = o->in_flight,
                 .timeout = o->timeout,
                 .noun = "tile",
                 .stopped_message = stopped,
                 .slow = mpi_test_slowdown(w->rank),
                 .context = &t,
                 .name_of = tile_name,
                 .render = render_tile,
                 .take = take_tile,
                 .units_by_rank = by_rank,
                 .seconds_by_rank = seconds_by_rank};
  double render_start = cli_now();
  mpi_run(&job);
  double render_end = cli_now();
  pthread_mutex_destroy(&t.output_lock);
  if (w->rank != 0)
    return 0;
  st = film_output ? glint_film_write(t.film, output, &err)
                   : glint_image_writer_finish(t.sink.writer, &err);
  t.sink.writer = NULL;
  world->abandon = NULL;
  glint_film_destroy(t.film);
  if (st) {
    cli_error("%s", err.message);
    return cli_exit_code(st);
  }
  mpi_end_if_silent(&job, output);
  if (!o->render.quiet) {
    printf("%s: %dx%d, %s, %d rank%s, %s schedule, %d tile%s of %d pixels: "
           "startup %.3f s, rendering %.3f s, writing %.3f s\n",
           output, t.width, t.height,
           glint_backend_name(glint_backend_choose(rs->backend, scene, rs)),
           w->size, w->size == 1 ? "" : "s", o->dynamic ? "dynamic" : "static",
           job.units, job.units == 1 ? "" : "s", t.side,
           render_start - w->started, render_end - render_start,
           cli_now() - render_end);
    for (int r = 0; r < w->size; r++)
      printf("  rank %d (%s): %d tile%s, %.3f s\n", r, w->hosts[r], by_rank[r],
             by_rank[r] == 1 ? "" : "s", seconds_by_rank[r]);
  }
  return 0;
}
