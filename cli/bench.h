/* Pieces shared by the benchmarks. */
#ifndef GLINT_CLI_BENCH_H
#define GLINT_CLI_BENCH_H

#include <glint.h>

#include <stddef.h>
#include <stdio.h>

double bench_median(const double *values, int count);
int bench_have_program(const char *name);
int bench_run_capture(char *const argv[], char *buf, size_t size);

/* glint bench --spd DIR */
int bench_spd(const char *dir, const glint_render_settings *base,
              const glint_backend *backends, int nbackends, int runs,
              FILE *csv);

/* glint bench --meshes DIR */
int bench_meshes(const char *dir, const glint_render_settings *base,
                 const glint_backend *backends, int nbackends, int runs);

#endif
