/* Pieces shared by the benchmarks (cli/bench_*.c). */
#ifndef GLINT_CLI_BENCH_H
#define GLINT_CLI_BENCH_H

#include <glint.h>

#include <stddef.h>
#include <stdio.h>

/* One column of a benchmark table: a backend at a thread count. */
typedef struct bench_column {
  glint_backend backend;
  int threads;
  char name[40];
} bench_column;

/* What glint bench was asked for (bench_parse; see cli.h). Lists are
 * split and checked: backends this CPU has, depths and thread counts in
 * range; one column per backend and thread count. */
#define BENCH_MAX_ITEMS 64
typedef struct bench_options {
  char *scenes[BENCH_MAX_ITEMS];
  int nscenes;
  char default_scenes[32];
  int depths[BENCH_MAX_ITEMS], ndepths, depths_given;
  int threads[BENCH_MAX_ITEMS], nthreads;
  glint_backend backends[GLINT_BACKEND_COUNT];
  int nbackends, backends_given;
  bench_column cols[GLINT_BACKEND_COUNT * BENCH_MAX_ITEMS];
  int ncols;
  char *csv_path, *plot_dir, *spd_dir, *mesh_dir;
  int runs, frames, time_to_image, view_frames;
  int runs_given, scenes_given, threads_given;
  glint_render_settings settings;
} bench_options;
int bench_parse(int argc, char **argv, bench_options *options);

double bench_median(const double *values, int count);
uint64_t bench_rays(const glint_stats *stats);
/* Active lanes over packet tests, as a fraction of the width (1 for the
 * scalar backends). */
double bench_lane_use(const glint_stats *stats, glint_backend backend);
int bench_have_program(const char *name);
/* The settings of a child glint's command line that `rs` holds besides
 * its backend, depth, spp and threads: -W and -H, each only where `rs` sets
 * it (one alone was passed as 0, or dropped), --math, --accel and
 * --no-newton (they were dropped, and --time-to-image compared a render
 * with --accel none against a child's with the BVH): out[0..8],
 * NULL-padded; the numbers are written into width and height. */
enum { BENCH_CHILD_ARGS = 9 };
void bench_child_args(const glint_render_settings *rs, char width[16],
                      char height[16], char *out[BENCH_CHILD_ARGS]);
/* Whether `path` is one of the SPD scenes that --spd DIR reads. */
int bench_spd_scene_at(const char *dir, const char *path);
int bench_run_capture(char *const argv[], char *buf, size_t size);
void bench_csv_row(FILE *csv, const char *scene, int depth,
                   const bench_column *col, const glint_stats *st,
                   const double *seconds, int runs);

/* One scene's world and a renderer per column of a benchmark table, each
 * kept across the table's runs and depths (cli/bench_renderers.c says
 * why). open prints its error; render returns glint's. */
typedef struct bench_renderers {
  const glint_scene *scene;
  glint_world *world;
  /* per column and backend (an auto column's choices), each made at its
   * first frame */
  glint_renderer **renderers;
  glint_film *film;
  int ncols, deepest;
} bench_renderers;
/* Commits `scene` (named `name` in an error, which sets *status). */
int bench_renderers_open(bench_renderers *renderers, const glint_scene *scene,
                         const char *name, int ncols, int deepest, int *status);
/* One frame of `settings` (backend, threads, size, depth and spp) with
 * column `col`'s renderer for the backend that renders it, made from the
 * settings when the column has none. */
glint_status bench_renderers_render(bench_renderers *renderers, int col,
                                    const glint_render_settings *settings,
                                    glint_stats *stats, glint_error *error);
void bench_renderers_close(bench_renderers *renderers);
/* The end of the run of columns from `first` on that share its thread count
 * (the columns come thread count by thread count): the columns whose
 * renderers a table keeps at once. */
int bench_thread_group_end(const bench_column *cols, int ncols, int first);

/* The thesis-style tables over scenes x depths x columns (csv: --csv's
 * text, written at the end to csv_path; plot_dir: --plot's). */
int bench_scenes(char **names, int nscenes, const int *depths, int ndepths,
                 const glint_render_settings *base, const bench_column *cols,
                 int ncols, int runs, FILE *csv, const char *csv_path,
                 const char *plot_dir);

/* glint bench --spd DIR */
int bench_spd(const char *dir, const glint_render_settings *base,
              const bench_column *cols, int ncols, int runs, FILE *csv);

/* glint bench --frames N: N frames of one scene with the camera moving,
 * through one renderer and through N glint_render calls. */
int bench_frames(const char *scene, const glint_render_settings *base,
                 int frames);

/* glint bench --time-to-image: each scene written by `glint render` as a
 * whole process, against its render time. */
int bench_time_to_image(char **scenes, int nscenes,
                        const glint_render_settings *base, int runs);

/* glint bench --view N: glint view --benchmark N on each scene. */
int bench_view(char **scenes, int nscenes, const glint_render_settings *base,
               int frames);

/* glint bench --meshes DIR */
int bench_meshes(const char *dir, const glint_render_settings *base,
                 const glint_backend *backends, int nbackends, int runs);

#endif
