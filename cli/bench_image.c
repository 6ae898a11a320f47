/* glint bench --time-to-image: what a user waits for, against the render.
 *
 * For each scene, --runs rounds of: `glint render SCENE -o x.png` as a
 * whole process (this very program, started as a child: loading, the
 * world, rendering, encoding, fsync and rename, process start and exit),
 * the same writing PPM (no compression), and the frame rendered in this
 * process by glint_render (stats.render_seconds, warm, as the other tables
 * measure it). Interleaving them keeps a noisy machine's drift out of the
 * ratios. It prints the medians, whole/render, and whole against the render
 * time the PNG process reported itself (cold: its first frame). */
#include "args.h"
#include "bench.h"
#include "cli.h"

#include <glint.h>

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Seconds one child `glint render ... --stats` of `scene` took, or a
 * negative value on failure (with its output on stderr, and *code the exit
 * status for it: a child's usage error is 2, as bench_view's, any other
 * failure 1); *render: the render time it reported itself. */
static double time_child(char **argv, const char *scene, double *render,
                         int *code) {
  static char output[1 << 14];
  double t0 = cli_now();
  int rc = bench_run_capture(argv, output, sizeof output);
  double seconds = cli_now() - t0;
  const char *line = strstr(output, "\n  render ");
  if (rc != 0 || !line || sscanf(line, " render %lf", render) != 1) {
    if (!cli_stopped()) /* a Ctrl-C stopped it too: the caller says so */
      cli_error("'glint render %s' failed:\n%s", scene, output);
    *code = rc == EXIT_USAGE ? EXIT_USAGE : 1;
    return -1;
  }
  return seconds;
}

int bench_time_to_image(char **scenes, int nscenes,
                        const glint_render_settings *base, int runs) {
  /* Ctrl-C ends the runs and still removes the folder (it was left), even
   * as the folder is being made. */
  cli_catch_stop_signals();
  /* (an empty TMPDIR is unset, as mktemp takes it; it made "/glint-...") */
  const char *tmp = getenv("TMPDIR");
  if (!tmp || !*tmp)
    tmp = "/tmp";
  char folder[PATH_MAX], png[PATH_MAX + 16], ppm[PATH_MAX + 16];
  int fits = snprintf(folder, sizeof folder, "%s/glint-bench-XXXXXX", tmp) <
             (int)sizeof folder;
  if (!fits || !mkdtemp(folder)) {
    cli_error("%s%s: cannot make a folder there for the images: %s",
              tmp == getenv("TMPDIR") ? "TMPDIR " : "", tmp,
              strerror(fits ? errno : ENAMETOOLONG));
    return EXIT_USAGE;
  }
  snprintf(png, sizeof png, "%s/image.png", folder);
  snprintf(ppm, sizeof ppm, "%s/image.ppm", folder);
  char depth[16], spp[16], threads[16], width[16], height[16];
  snprintf(depth, sizeof depth, "%d", base->max_depth);
  snprintf(spp, sizeof spp, "%d", base->spp);
  snprintf(threads, sizeof threads, "%d", base->threads);
  char *more[BENCH_CHILD_ARGS];
  bench_child_args(base, width, height, more);
  /* (auto stays auto: each scene's process chooses as glint_render does) */
  glint_backend backend = base->backend;

  printf("Time to image: `glint render SCENE -o FILE` as a whole process "
         "against its render\n(%s, %d thread%s, depth %d, %d spp, %s maths%s, "
         "accel %s; medians of %d interleaved runs; render: warm, in this "
         "process; own: what the PNG process reported)\n",
         glint_backend_name(backend), base->threads,
         base->threads == 1 ? "" : "s", base->max_depth, base->spp,
         glint_math_name(base->math), base->rcp_newton ? "" : " (no Newton)",
         glint_accel_name(base->accel), runs);
  printf("%-16s %9s %9s %9s %9s %10s %10s %8s\n", "scene", "render ms",
         "own ms", "PNG ms", "PPM ms", "PNG/render", "PPM/render", "PNG/own");
  enum { RENDER, OWN, PNG, PPM, SERIES };
  double *times = malloc(sizeof(double) * SERIES * (size_t)runs);
  int status = times ? 0 : 1;
  for (int s = 0; s < nscenes && status == 0; s++) {
    char stem[CLI_STEM_SIZE];
    int code = EXIT_USAGE;
    glint_scene *scene = cli_load_scene(scenes[s], stem, sizeof stem, &code);
    if (!scene) {
      status = code;
      break;
    }
    /* The scene after "--": a name that starts with '-' is still a scene
     * (-dash.json was read as -d ash.json). */
    char *argv[16 + BENCH_CHILD_ARGS] = {"/proc/self/exe",
                                         "render",
                                         "-b",
                                         (char *)glint_backend_name(backend),
                                         "-t",
                                         threads,
                                         "-d",
                                         depth,
                                         "-s",
                                         spp,
                                         "--stats",
                                         "-o",
                                         png};
    enum { OUTPUT = 12 };
    int n = OUTPUT + 1;
    for (int k = 0; k < BENCH_CHILD_ARGS && more[k]; k++)
      argv[n++] = more[k];
    argv[n++] = "--";
    argv[n++] = scenes[s];
    argv[n] = NULL;
    /* One untimed round first: page cache, the dynamic loader's. */
    for (int r = -1; r < runs && status == 0 && !cli_stopped(); r++) {
      glint_image *image;
      glint_stats st;
      glint_error err;
      if (glint_render(scene, base, &image, &st, &err)) {
        cli_error("%s", err.message);
        status = cli_exit_code(err.status);
        break;
      }
      glint_image_destroy(image);
      if (cli_stopped())
        break;
      double own, own_ppm;
      argv[OUTPUT] = png;
      double t_png = time_child(argv, scenes[s], &own, &status);
      argv[OUTPUT] = ppm;
      double t_ppm =
          t_png < 0 ? -1 : time_child(argv, scenes[s], &own_ppm, &status);
      if (t_png >= 0 && t_ppm >= 0 && r >= 0) {
        times[RENDER * runs + r] = st.render_seconds;
        times[OWN * runs + r] = own;
        times[PNG * runs + r] = t_png;
        times[PPM * runs + r] = t_ppm;
      }
    }
    glint_scene_destroy(scene);
    if (cli_stopped()) {
      cli_error("interrupted: %s and the scenes after it not measured", stem);
      status = EXIT_INTERRUPTED;
    }
    if (status)
      break;
    double m[SERIES];
    for (int i = 0; i < SERIES; i++)
      m[i] = bench_median(times + i * runs, runs);
    printf("%-16s %9.2f %9.2f %9.2f %9.2f %10.2f %10.2f %8.2f\n", stem,
           1e3 * m[RENDER], 1e3 * m[OWN], 1e3 * m[PNG], 1e3 * m[PPM],
           m[PNG] / m[RENDER], m[PPM] / m[RENDER], m[PNG] / m[OWN]);
  }
  free(times);
  unlink(png);
  unlink(ppm);
  rmdir(folder);
  return status;
}
