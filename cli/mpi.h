/* glint-mpi: glint render over Open MPI (docs/mpi.md).
 *
 * The work is cut into units, the tiles of one image or the frames of an
 * animation, and cli/mpi_schedule.c hands them to the ranks; rank 0 renders
 * units too, on a thread beside its master's, and writes every file. */
#ifndef GLINT_CLI_MPI_H
#define GLINT_CLI_MPI_H

#include "args.h"
#include "cli.h"

#include <glint.h>
#include <mpi.h>

#include <stdatomic.h>
#include <stddef.h>

enum { MPI_HOST_CHARS = 256, MPI_MESSAGE_CHARS = 1280 };

typedef struct mpi_world {
  MPI_Comm comm;
  int rank, size;
  char (*hosts)[MPI_HOST_CHARS]; /* every rank's host name */
  /* Rank 0: abandons the output (no partial file) before the job ends on
   * a failure or a stop signal. */
  void (*abandon)(void *context);
  void *abandon_context;
  /* Rank 0 renders its own units on a thread of their own
   * (cli/mpi_schedule.c): when the job ends on a failure, `ending` cancels
   * the unit that thread renders, and settle() waits until it has stopped,
   * before abandon() takes the output away from under it. */
  atomic_int ending;
  void (*settle)(void *context);
  void *settle_context;
  double started; /* cli_now() when the job began, for the summary */
} mpi_world;

/* A glint_tile_fn that copies tiles into a unit's buffer: `pixels` holds
 * the window at frame pixel (x, y), `width` pixels a row. */
typedef struct mpi_unit_buffer {
  float *pixels;
  int x, y, width;
} mpi_unit_buffer;
int mpi_copy_tile(void *user, const glint_tile *tile);

/* A glint_progress_fn, `user` the mpi_world: rank 0 cancels its unit on a
 * stop signal, or when the job ends on a failure. */
int mpi_on_progress(void *user, double fraction);

/* Checks an MPI call's result: on failure prints "glint-mpi: rank R (HOST):
 * WHAT: MPI's message" and ends the job (MPI_Abort). */
void mpi_check(const mpi_world *w, int result, const char *what);

/* Ends the whole job with `status` after rank `w->rank` printed why. */
void mpi_fail(const mpi_world *w, int status, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4), noreturn))
#endif
    ;

/* Collective: whether every rank is ok (st, GLINT_OK where it is). A rank
 * that is not passes its status and message, which rank 0 prints with the
 * rank and host of the first such rank; then every rank returns that
 * rank's exit status (1 out of memory, else 2). 0 when all are ok. */
int mpi_agree(const mpi_world *w, glint_status st, const char *message);

/* The work of one job: `units` units, each a result of at most
 * `unit_bytes` bytes (a tile's linear RGB floats, a frame's encoded file). */
typedef struct mpi_job {
  const mpi_world *world;
  int units;
  size_t unit_bytes;
  int dynamic;      /* hand units out as ranks finish, else unit u to rank
                       u % size (the baseline) */
  int in_flight;    /* units a worker holds at once (dynamic schedule) */
  double timeout;   /* seconds a rank may stay silent while it owes units */
  const char *noun; /* "tile" or "frame", for messages */
  /* Rank 0, after a stop signal: what was lost and what stays. */
  const char *stopped_message;
  double slow; /* test-only: this rank sleeps (slow - 1) x a unit's
                  time after each (GLINT_MPI_TEST_SLOW) */
  void *context;
  /* Unit u's name in messages: "frame 12", "tile 7 at 64,128". */
  void (*name_of)(void *context, int unit, char *name, size_t size);
  /* Renders unit u: on rank 0 straight into the output (`result` NULL),
   * elsewhere into `result` (unit_bytes of room, 8-byte aligned), setting
   * *size. 0, or -1 with *error set. */
  int (*render)(void *context, int unit, void *result, size_t *size,
                glint_error *error);
  /* Rank 0: unit u's result, rendered by rank `rank`. 0, or -1 with *error
   * set (a full disk). */
  int (*take)(void *context, int unit, int rank, const void *result,
              size_t size, glint_error *error);
  /* What each rank did, for the summary (rank 0, `size` entries): units,
   * and seconds spent rendering them. */
  int *units_by_rank;
  double *seconds_by_rank;
  int silent_rank; /* rank 0: see mpi_run */
} mpi_job;

/* Runs the job on every rank; returns once every unit is taken. A failure
 * anywhere (a unit's error, a silent rank of the static schedule, a stop
 * signal) does not return: it prints why and ends the job; but a rank that
 * goes silent in the dynamic schedule (rank 0 renders the units it holds)
 * is noted in silent_rank, so that the output is finished first ... */
void mpi_run(mpi_job *job);
/* ... and then the job ended with a message naming it (rank 0; `written`
 * says what was written). Returns when no rank was silent. */
void mpi_end_if_silent(const mpi_job *job, const char *written);

/* The two kinds of jobs (cli/mpi_tiles.c, cli/mpi_frames.c): each sets up
 * its output on rank 0, runs the job, and finishes the output. They return
 * the exit status. `scene` is the still scene for tiles, the animation for
 * frames. */
typedef struct mpi_options {
  render_options render;
  int dynamic;
  int tile_size;    /* 0: chosen from the image, the ranks and their threads */
  int most_threads; /* the largest number of threads of any rank */
  int in_flight;
  double timeout;
} mpi_options;

int mpi_render_tiles(const mpi_world *w, const mpi_options *o,
                     glint_scene *scene, glint_renderer *renderer,
                     const char *stem);
int mpi_render_frames(const mpi_world *w, const mpi_options *o,
                      glint_scene *scene, glint_renderer *renderer,
                      const char *stem);

/* GLINT_MPI_TEST_SLOW=RANK:FACTOR[,RANK:FACTOR...], for tests and the
 * benchmark only: that rank takes FACTOR times as long per unit (it sleeps
 * the difference). */
double mpi_test_slowdown(int rank);

#endif
