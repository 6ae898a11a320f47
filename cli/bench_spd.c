/* glint bench --spd DIR: the Standard Procedural Databases against Tachyon.
 * Each scene renders at the file's own resolution (512x512), 1 sample per
 * pixel, depth 5, with every backend asked for; when Debian's tachyon is
 * installed, it renders the same file in the same run,
 *   tachyon FILE -numthreads T -raydepth 5 -shade_phong
 * and its own "Ray Tracing Time" is compared with glint's render time
 * (both exclude parsing and acceleration-structure building). */
#include "args.h"
#include "files.h"
#include "bench.h"
#include "cli.h"

#include <glint.h>

#include <fcntl.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

static const char *const spd_scenes[] = {"balls-s4", "gears-s4",  "mount-s6",
                                         "rings-s4", "teapot-s4", "tetra-s6",
                                         "tree-s4"};
#define SPD_COUNT (sizeof spd_scenes / sizeof *spd_scenes)

int bench_spd_scene_at(const char *dir, const char *path) {
  for (size_t i = 0; i < SPD_COUNT; i++) {
    char scene[4096];
    snprintf(scene, sizeof scene, "%s/%s.nff", dir, spd_scenes[i]);
    if (same_file(scene, path))
      return 1;
  }
  return 0;
}

int bench_have_program(const char *name) {
  char cmd[256];
  snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", name);
  return system(cmd) == 0;
}

/* Runs argv, capturing stdout and stderr into buf; returns the exit status
 * or -1. */
int bench_run_capture(char *const argv[], char *buf, size_t size) {
  int fds[2];
  if (pipe(fds) != 0)
    return -1;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
  posix_spawn_file_actions_adddup2(&fa, fds[1], 2);
  posix_spawn_file_actions_addclose(&fa, fds[0]);
  pid_t pid;
  int rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  close(fds[1]);
  size_t n = 0;
  if (rc == 0) {
    ssize_t r;
    while ((r = read(fds[0], buf + n, size - 1 - n)) > 0)
      if ((n += (size_t)r) >= size - 1)
        break;
  }
  buf[n] = '\0';
  close(fds[0]);
  if (rc != 0)
    return -1;
  int status;
  if (waitpid(pid, &status, 0) < 0)
    return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* Tachyon's reported ray tracing time for one file, or a negative value. */
static double tachyon_seconds(const char *file, int threads, const char *out) {
  char nthreads[16];
  snprintf(nthreads, sizeof nthreads, "%d", threads);
  char *argv[] = {"tachyon",   (char *)file, "-numthreads",  nthreads,
                  "-raydepth", "5",          "-shade_phong", "-o",
                  (char *)out, NULL};
  static char buf[1 << 16];
  if (bench_run_capture(argv, buf, sizeof buf) != 0)
    return -1;
  const char *p = strstr(buf, "Ray Tracing Time:");
  double t;
  if (!p || sscanf(p, "Ray Tracing Time: %lf", &t) != 1)
    return -1;
  return t;
}

int bench_spd(const char *dir, const glint_render_settings *base,
              const bench_column *cols, int ncols, int runs, FILE *csv) {
  glint_scene *scenes[SPD_COUNT];
  char paths[SPD_COUNT][4096];
  for (size_t i = 0; i < SPD_COUNT; i++) {
    snprintf(paths[i], sizeof paths[i], "%s/%s.nff", dir, spd_scenes[i]);
    glint_error err;
    if (glint_scene_load(paths[i], &scenes[i], &err)) {
      cli_error("--spd: %s", err.message);
      for (size_t k = 0; k < i; k++)
        glint_scene_destroy(scenes[k]);
      return cli_exit_code(err.status);
    }
  }
  int tachyon = bench_have_program("tachyon");
  char out[] = "/tmp/glint-bench-tachyon-XXXXXX";
  int fd = tachyon ? mkstemp(out) : -1;
  if (fd >= 0)
    close(fd);
  else
    tachyon = 0;

  /* Tachyon once per distinct thread count, as an extra column each, run
   * beside the first column of that count (-t 0 and -t 2 are one count on
   * two CPUs). */
  int tthreads[16], tfirst[16], ntt = 0;
  for (int c = 0; c < ncols; c++) {
    int t = cols[c].threads ? cols[c].threads : glint_cpu_count(), seen = 0;
    for (int k = 0; k < ntt; k++)
      seen |= tthreads[k] == t;
    if (!seen && ntt < 16) {
      tthreads[ntt] = t;
      tfirst[ntt++] = c;
    }
  }
  size_t cells = SPD_COUNT * (size_t)(ncols + ntt);
  double *times = calloc(cells * (size_t)runs, sizeof *times);
  glint_stats *stats = calloc(cells, sizeof *stats);
  if (!times || !stats) {
    cli_error("out of memory");
    return 1;
  }
#define T(s, b, r) times[(((size_t)(s) * (ncols + ntt)) + (b)) * runs + (r)]
#define ST(s, b) stats[(size_t)(s) * (ncols + ntt) + (b)]
  glint_render_settings rs = *base;
  rs.width = rs.height = 0; /* the files' own */
  rs.spp = 1;
  rs.max_depth = 5;
  int status = 0, tty = isatty(STDERR_FILENO);
  /* Scene by scene and thread count by thread count, each column's
   * renderer kept for all its runs, Tachyon at the same thread count
   * interleaved with them; run -1 warms up, untimed (see bench_cmd.c). */
  for (size_t s = 0; s < SPD_COUNT && !status; s++)
    for (int c0 = 0, c1; c0 < ncols && !status; c0 = c1) {
      c1 = bench_thread_group_end(cols, ncols, c0);
      int k = -1; /* Tachyon's column run with this group, if any */
      for (int j = 0; tachyon && j < ntt; j++)
        if (tfirst[j] >= c0 && tfirst[j] < c1)
          k = j;
      bench_renderers br;
      if (bench_renderers_open(&br, scenes[s], spd_scenes[s], ncols,
                               rs.max_depth, &status))
        break;
      for (int r = -1; r < runs && !status; r++) {
        for (int b = c0; b < c1; b++) {
          if (tty)
            fprintf(stderr, "\r[run %d/%d] %s %s\033[K", r + 1, runs,
                    spd_scenes[s], cols[b].name);
          rs.backend = cols[b].backend;
          rs.threads = cols[b].threads;
          glint_error err;
          glint_status st =
              bench_renderers_render(&br, b, &rs, &ST(s, b), &err);
          if (st) {
            cli_error("%s: %s", spd_scenes[s], err.message);
            status = cli_exit_code(st);
            break;
          }
          if (r >= 0)
            T(s, b, r) = ST(s, b).render_seconds;
        }
        if (k >= 0 && r >= 0 && !status) {
          int t = tthreads[k];
          if (tty)
            fprintf(stderr, "\r[run %d/%d] %s tachyon %d thread%s\033[K", r + 1,
                    runs, spd_scenes[s], t, t == 1 ? "" : "s");
          T(s, ncols + k, r) = tachyon_seconds(paths[s], t, out);
        }
      }
      bench_renderers_close(&br);
    }
  if (tty)
    fputs("\r\033[K", stderr);
  if (tachyon)
    unlink(out);

  if (!status) {
    printf("glint %s bench --spd: the files' own 512x512, 1 spp, depth 5, "
           "median of %d run%s (seconds)\n",
           glint_version(), runs, runs == 1 ? "" : "s");
    if (!tachyon)
      printf("(tachyon is not installed: Debian package tachyon-bin-nox)\n");
    printf("%-10s", "scene");
    for (int b = 0; b < ncols; b++)
      printf(" %14s", cols[b].name);
    for (int k = 0; tachyon && k < ntt; k++) {
      char name[32];
      snprintf(name, sizeof name, "tachyon/%dt", tthreads[k]);
      printf(" %12s %9s", name, "speed-up");
    }
    printf(" %10s\n", "Mrays/s");
    for (size_t s = 0; s < SPD_COUNT; s++) {
      printf("%-10s", spd_scenes[s]);
      double best = INFINITY;
      int best_b = 0;
      for (int b = 0; b < ncols; b++) {
        double m = bench_median(&T(s, b, 0), runs);
        printf(" %14.4f", m);
        if (m < best)
          best = m, best_b = b;
      }
      for (int k = 0; tachyon && k < ntt; k++) {
        /* glint's best column at the same thread count */
        double tm = bench_median(&T(s, ncols + k, 0), runs), g = INFINITY;
        for (int b = 0; b < ncols; b++) {
          int t = cols[b].threads ? cols[b].threads : glint_cpu_count();
          if (t == tthreads[k])
            g = fmin(g, bench_median(&T(s, b, 0), runs));
        }
        if (tm > 0)
          printf(" %12.4f %8.1fx", tm, tm / g);
        else
          printf(" %12s %9s", "failed", "-");
      }
      double rays = (double)bench_rays(&ST(s, best_b));
      printf(" %10.2f\n", best > 0 ? rays / best / 1e6 : 0.0);
      for (int b = 0; csv && b < ncols; b++)
        bench_csv_row(csv, spd_scenes[s], 5, &cols[b], &ST(s, b), &T(s, b, 0),
                      runs);
      for (int k = 0; csv && tachyon && k < ntt; k++)
        fprintf(csv,
                "%s,5,tachyon,512,512,1,%d,%d,%.6f,,,,,,,,,,,,,,,tachyon/%dt\n",
                spd_scenes[s], tthreads[k], runs,
                bench_median(&T(s, ncols + k, 0), runs), tthreads[k]);
    }
  }
  free(times);
  free(stats);
  for (size_t s = 0; s < SPD_COUNT; s++)
    glint_scene_destroy(scenes[s]);
  return status;
}
