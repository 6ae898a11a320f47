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

double bench_median(const double *values, int count);
uint64_t bench_rays(const glint_stats *stats);
/* Active lanes over packet tests, as a fraction of the width (1 for the
 * scalar backends). */
double bench_lane_use(const glint_stats *stats, glint_backend backend);
int bench_have_program(const char *name);
int bench_run_capture(char *const argv[], char *buf, size_t size);
void bench_csv_row(FILE *csv, const char *scene, int depth,
                   const bench_column *col, const glint_stats *st,
                   const double *seconds, int runs);

/* The thesis-style tables over scenes x depths x columns. */
int bench_scenes(char **names, int nscenes, const int *depths, int ndepths,
                 const glint_render_settings *base, const bench_column *cols,
                 int ncols, int runs, FILE *csv, const char *plot_dir);

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

/* glint bench --meshes DIR */
int bench_meshes(const char *dir, const glint_render_settings *base,
                 const glint_backend *backends, int nbackends, int runs);

#endif
