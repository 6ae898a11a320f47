/* glint bench --time-to-image: what a user waits for, against the render.
 *
 * For each scene, --runs rounds of: `glint render SCENE -o x.png` as a
 * whole process (this very program, started as a child: loading, the
 * world, rendering, encoding, fsync and rename, process start and exit),
 * the same writing PPM (no compression), and the frame rendered in this
 * process by glint_render (stats.render_seconds, warm, as the other tables
 * measure it). Interleaving the three keeps a noisy machine's drift out of
 * the ratios. It prints the medians and whole/render. */
#include "args.h"
#include "bench.h"
#include "cli.h"

#include <glint.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Seconds one child `glint render` took, or a negative value on failure
 * (with its output on stderr). */
static double time_child(char **argv) {
  static char output[1 << 14];
  double t0 = cli_now();
  int rc = bench_run_capture(argv, output, sizeof output);
  double seconds = cli_now() - t0;
  if (rc != 0) {
    cli_error("'%s render %s' failed:\n%s", argv[0], argv[2], output);
    return -1;
  }
  return seconds;
}

int bench_time_to_image(char **scenes, int nscenes,
                        const glint_render_settings *base, int runs) {
  const char *tmp = getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
  char folder[512], png[600], ppm[600];
  snprintf(folder, sizeof folder, "%s/glint-bench-XXXXXX", tmp);
  if (!mkdtemp(folder)) {
    cli_error("%s: cannot make a folder for the images", folder);
    return EXIT_USAGE;
  }
  snprintf(png, sizeof png, "%s/image.png", folder);
  snprintf(ppm, sizeof ppm, "%s/image.ppm", folder);
  char depth[16], spp[16], threads[16], width[16], height[16];
  snprintf(depth, sizeof depth, "%d", base->max_depth);
  snprintf(spp, sizeof spp, "%d", base->spp);
  snprintf(threads, sizeof threads, "%d", base->threads);
  snprintf(width, sizeof width, "%d", base->width);
  snprintf(height, sizeof height, "%d", base->height);
  glint_backend backend = glint_backend_resolve(base->backend);

  printf("Time to image: `glint render SCENE -o FILE` as a whole process "
         "against its render\n(%s, %d thread%s, depth %d, %d spp; medians of "
         "%d interleaved runs)\n",
         glint_backend_name(backend), base->threads,
         base->threads == 1 ? "" : "s", base->max_depth, base->spp, runs);
  printf("%-22s %10s %10s %10s %10s %10s\n", "scene", "render ms", "PNG ms",
         "PPM ms", "PNG/render", "PPM/render");
  double *times = malloc(sizeof(double) * 3 * (size_t)runs);
  int status = times ? 0 : 1;
  for (int s = 0; s < nscenes && status == 0; s++) {
    char stem[256];
    glint_scene *scene = cli_load_scene(scenes[s], stem, sizeof stem);
    if (!scene) {
      status = EXIT_USAGE;
      break;
    }
    char *argv[] = {"/proc/self/exe",
                    "render",
                    scenes[s],
                    "-b",
                    (char *)glint_backend_name(backend),
                    "-t",
                    threads,
                    "-d",
                    depth,
                    "-s",
                    spp,
                    "-q",
                    "-o",
                    png,
                    base->width ? "-W" : NULL,
                    width,
                    "-H",
                    height,
                    NULL};
    double *render = times, *whole_png = times + runs,
           *whole_ppm = times + 2 * runs;
    /* One untimed round first: page cache, the dynamic loader's. */
    for (int r = -1; r < runs && status == 0; r++) {
      glint_image *image;
      glint_stats st;
      glint_error err;
      if (glint_render(scene, base, &image, &st, &err)) {
        cli_error("%s", err.message);
        status = EXIT_USAGE;
        break;
      }
      glint_image_destroy(image);
      argv[13] = png;
      double t_png = time_child(argv);
      argv[13] = ppm;
      double t_ppm = time_child(argv);
      if (t_png < 0 || t_ppm < 0)
        status = 1;
      else if (r >= 0) {
        render[r] = st.render_seconds;
        whole_png[r] = t_png;
        whole_ppm[r] = t_ppm;
      }
    }
    glint_scene_destroy(scene);
    if (status)
      break;
    double mr = bench_median(render, runs),
           mpng = bench_median(whole_png, runs),
           mppm = bench_median(whole_ppm, runs);
    printf("%-22s %10.2f %10.2f %10.2f %10.2f %10.2f\n", stem, 1e3 * mr,
           1e3 * mpng, 1e3 * mppm, mpng / mr, mppm / mr);
  }
  free(times);
  unlink(png);
  unlink(ppm);
  rmdir(folder);
  return status;
}
