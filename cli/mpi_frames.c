/* glint-mpi --frames: the frames of an animation, one unit each, named as
 * glint render --frames names them (cli/animation_frames.c). Rank 0 decides
 * which frames to render (--resume keeps those already written) and writes
 * every file, atomically, as its frame arrives; every rank renders with the
 * camera of the frame's time and, when objects move, commits the world at
 * that time itself. */
#include "mpi.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct frame_job {
  const mpi_world *world;
  const mpi_options *options;
  glint_scene *scene; /* the animation */
  glint_renderer *renderer;
  glint_animation animation;
  frame_files files;
  int moving;
  glint_world *last_world; /* the last frame's, whose BVH the next refits */
  int width, height, origin_x, origin_y; /* the output, in the frame */
  int *frames;                           /* unit u renders frames[u] */
  glint_image_format format;             /* of every frame's file */
  glint_image_writer *writer;            /* the frame being encoded */
} frame_job;

static void frame_name(void *context, int unit, char *name, size_t size) {
  const frame_job *j = context;
  snprintf(name, size, "frame %d", j->frames[unit]);
}

/* The most bytes a frame's file can take: 8-bit RGB, plus what PNG (a
 * filter byte a row, zlib's stored blocks, chunks), BMP (rows padded to 4
 * bytes) or PPM adds, with room to spare. */
static size_t encoded_bound(int width, int height) {
  size_t raw = 3 * (size_t)width * (size_t)height;
  return raw + raw / 64 + 4 * (size_t)height + 4096;
}

static double time_of(const frame_job *j, int frame) {
  return (double)(frame - j->animation.first_frame) / j->animation.fps;
}

/* Rank 0: says that `frame` is written, as glint render --frames does. */
static void frame_written(const frame_job *j, int frame, const char *path,
                          int rank) {
  if (j->options->render.quiet)
    return;
  printf("frame %d (t = %.3f s): %s, rank %d (%s)\n", frame, time_of(j, frame),
         path, rank, j->world->hosts[rank]);
  fflush(stdout);
}

static int open_frame(frame_job *j, int frame, char *path, size_t size,
                      glint_error *error) {
  if (frame_files_path(&j->files, frame, path, size)) {
    snprintf(error->message, sizeof error->message,
             "cannot make the file name or folder of frame %d", frame);
    return -1;
  }
  const glint_render_settings *rs = &j->options->render.settings;
  return glint_image_writer_open(path, j->width, j->height, rs->gamma,
                                 j->options->render.png_compression, &j->writer,
                                 error)
             ? -1
             : 0;
}

/* Rank 0 writes its frames' files itself, encoded as the frame renders;
 * the other ranks encode theirs into memory (the same bytes) and send the
 * file, so that rank 0 only writes and never becomes the job's encoder. */
static int render_frame(void *context, int unit, void *result, size_t *size,
                        glint_error *error) {
  frame_job *j = context;
  int frame = j->frames[unit];
  double time = time_of(j, frame);
  glint_camera camera;
  if (glint_scene_camera_at(j->scene, time, &camera, error) ||
      (j->moving &&
       cli_world_at(j->scene, time, j->renderer, &j->last_world, error)))
    return -1;
  const glint_render_settings *rs = &j->options->render.settings;
  char path[4096];
  if (!result && open_frame(j, frame, path, sizeof path, error))
    return -1;
  if (result && glint_image_writer_open_memory(
                    j->format, j->width, j->height, rs->gamma,
                    j->options->render.png_compression, &j->writer, error))
    return -1;
  cli_tile_sink sink = {j->writer, j->origin_x, j->origin_y, 0, {0}};
  glint_frame_settings settings;
  glint_frame_settings_default(&settings);
  settings.camera = &camera;
  settings.progress = mpi_on_progress;
  settings.progress_user = (void *)j->world;
  settings.tile = cli_tile_to_writer;
  settings.tile_user = &sink;
  glint_status st =
      glint_renderer_render(j->renderer, &settings, NULL, NULL, error);
  j->writer = NULL;
  if (st) {
    glint_image_writer_discard(sink.writer);
    if (sink.failed)
      *error = sink.error;
    return -1;
  }
  if (!result) {
    if (glint_image_writer_finish(sink.writer, error))
      return -1;
    frame_written(j, frame, path, 0);
    return 0;
  }
  void *bytes;
  if (glint_image_writer_finish_memory(sink.writer, &bytes, size, error))
    return -1;
  int fits = *size <= encoded_bound(j->width, j->height);
  if (fits)
    memcpy(result, bytes, *size);
  else
    snprintf(error->message, sizeof error->message,
             "its file took %zu bytes, more than the %zu allowed", *size,
             encoded_bound(j->width, j->height));
  glint_free(bytes);
  return fits ? 0 : -1;
}

static int take_frame(void *context, int unit, int rank, const void *result,
                      size_t size, glint_error *error) {
  frame_job *j = context;
  int frame = j->frames[unit];
  char path[4096];
  if (frame_files_path(&j->files, frame, path, sizeof path)) {
    error->status = GLINT_E_IO; /* rank 0's own */
    snprintf(error->message, sizeof error->message,
             "cannot make the file name or folder of frame %d", frame);
    return -1;
  }
  if (glint_image_write_encoded(path, result, size, error))
    return -1;
  frame_written(j, frame, path, rank);
  return 0;
}

static void abandon(void *context) {
  frame_job *j = context;
  glint_image_writer_discard(j->writer);
  j->writer = NULL;
  frame_files_end(&j->files, 1); /* the folders made still empty go */
}

/* Rank 0: the frames to render, those --resume finds written left out; or
 * after a message the exit status, negated: -EXIT_INTERRUPTED when Ctrl-C
 * stops it (reading the kept frames takes milliseconds each). */
static int plan(frame_job *j, int *kept) {
  const render_options *o = &j->options->render;
  int count = o->last_frame - o->first_frame + 1, n = 0;
  *kept = 0;
  if (!(j->frames = malloc((size_t)count * sizeof *j->frames))) {
    cli_error("out of memory");
    return -EXIT_MEMORY;
  }
  for (int f = o->first_frame; f <= o->last_frame; f++) {
    char path[4096];
    if (cli_stopped()) {
      cli_error("interrupted while looking for the frames written "
                "(--resume); no frame was written");
      return -EXIT_INTERRUPTED;
    }
    if (frame_files_path(&j->files, f, path, sizeof path))
      return -EXIT_USAGE;
    if (o->resume && frame_file_kept(path, f, j->width, j->height, o->quiet)) {
      (*kept)++;
      continue;
    }
    j->frames[n++] = f;
  }
  return n;
}

int mpi_render_frames(const mpi_world *w, const mpi_options *o,
                      glint_scene *scene, glint_renderer *renderer,
                      const char *stem) {
  frame_job j;
  memset(&j, 0, sizeof j);
  j.world = w;
  j.options = o;
  j.scene = scene;
  j.renderer = renderer;
  const glint_render_settings *rs = &o->render.settings;
  frame_size(scene, rs, &j.width, &j.height);
  if (rs->region_width)
    j.origin_x = rs->region_x, j.origin_y = rs->region_y;
  j.moving = glint_scene_has_motion(scene);
  /* Every frame's file has the extension of -o (or of SCENE.png). */
  j.format = glint_image_format_from_path(o->render.output ? o->render.output
                                                           : "x.png");
  /* Every rank checks the animation (they hold the same scene); rank 0
   * alone speaks, makes folders and looks for written frames. */
  int count = -1, kept = 0;
  if (w->rank == 0) {
    int refused =
        frame_files_init(&j.files, scene, &o->render, stem, &j.animation);
    count = refused ? -refused : plan(&j, &kept);
  } else {
    glint_scene_get_animation(scene, &j.animation);
  }
  int header[2] = {count, kept};
  mpi_check(w, MPI_Bcast(header, 2, MPI_INT, 0, w->comm), "sharing the frames");
  count = header[0];
  kept = header[1];
  if (count < 0) {
    free(j.frames);
    if (w->rank == 0)
      frame_files_end(&j.files, 1); /* (none made when the check failed) */
    return -count;                  /* the exit status */
  }
  if (w->rank != 0 && count &&
      !(j.frames = malloc((size_t)count * sizeof *j.frames)))
    mpi_fail(w, 1, "out of memory");
  if (count)
    mpi_check(w, MPI_Bcast(j.frames, count, MPI_INT, 0, w->comm),
              "sharing the frames");
  if (encoded_bound(j.width, j.height) > (size_t)1 << 30)
    mpi_fail(w, EXIT_USAGE,
             "--frames sends each frame's file in one message, at most "
             "1 GiB: %dx%d may be larger (render its frames one by one, in "
             "tiles)",
             j.width, j.height);
  mpi_world *world = (mpi_world *)w;
  world->abandon = abandon;
  world->abandon_context = &j;

  int by_rank[w->size > 0 ? w->size : 1];
  double seconds_by_rank[w->size > 0 ? w->size : 1];
  memset(by_rank, 0, sizeof by_rank);
  memset(seconds_by_rank, 0, sizeof seconds_by_rank);
  mpi_job job = {.world = w,
                 .units = count,
                 .unit_bytes = encoded_bound(j.width, j.height),
                 .dynamic = o->dynamic,
                 .in_flight = o->in_flight,
                 .timeout = o->timeout,
                 .noun = "frame",
                 .stopped_message =
                     "stopped by a signal (Ctrl-C, or mpirun ending the job, "
                     "as it does when a rank dies); the frame being written "
                     "was not, frames written stay, and --resume renders the "
                     "rest",
                 .slow = mpi_test_slowdown(w->rank),
                 .context = &j,
                 .name_of = frame_name,
                 .render = render_frame,
                 .take = take_frame,
                 .units_by_rank = by_rank,
                 .seconds_by_rank = seconds_by_rank};
  double render_start = cli_now();
  mpi_run(&job);
  world->abandon = NULL;
  free(j.frames);
  glint_world_destroy(j.last_world);
  mpi_end_if_silent(&job, "every frame's file");
  if (w->rank == 0)
    frame_files_end(&j.files, 0);
  if (w->rank == 0 && !o->render.quiet) {
    printf("%d frame%s written", count, count == 1 ? "" : "s");
    if (kept)
      printf(", %d kept (--resume)", kept);
    printf(" by %d rank%s, %s schedule: startup %.3f s, rendering and "
           "writing %.3f s\n",
           w->size, w->size == 1 ? "" : "s", o->dynamic ? "dynamic" : "static",
           render_start - w->started, cli_now() - render_start);
    for (int r = 0; r < w->size; r++)
      printf("  rank %d (%s): %d frame%s, %.3f s\n", r, w->hosts[r], by_rank[r],
             by_rank[r] == 1 ? "" : "s", seconds_by_rank[r]);
  }
  return 0;
}
