/* glint bench --view N: glint view's benchmark (its documented orbit, N
 * frames) on each scene, each in a process of its own as a user runs it,
 * without a display when there is none. */
#include "args.h"
#include "bench.h"
#include "cli.h"

#include <glint.h>

#include <stdio.h>
#include <string.h>

int bench_view(char **scenes, int nscenes, const glint_render_settings *base,
               int frames) {
  char nframes[16], depth[16], threads[16], width[16], height[16];
  snprintf(nframes, sizeof nframes, "%d", frames);
  snprintf(depth, sizeof depth, "%d", base->max_depth);
  snprintf(threads, sizeof threads, "%d", base->threads);
  char *more[BENCH_CHILD_ARGS];
  bench_child_args(base, width, height, more);
  static char output[1 << 14];
  int status = 0;
  for (int s = 0; s < nscenes; s++) {
    /* The scene after "--": a name starting with '-' is a scene (it was
     * taken as an option of glint view: --scenes --help printed its help) */
    char *argv[16 + BENCH_CHILD_ARGS] = {
        "/proc/self/exe",
        "view",
        "--benchmark",
        nframes,
        "-b",
        (char *)glint_backend_name(base->backend),
        "-d",
        depth,
        "-t",
        threads};
    int n = 10;
    for (int k = 0; k < BENCH_CHILD_ARGS && more[k]; k++)
      argv[n++] = more[k];
    argv[n++] = "--";
    argv[n++] = scenes[s];
    argv[n] = NULL;
    int rc = bench_run_capture(argv, output, sizeof output);
    if (rc != 0) {
      cli_error("'glint view %s --benchmark %d' failed:\n%s", scenes[s], frames,
                output);
      status = rc == EXIT_USAGE ? EXIT_USAGE : 1;
      continue;
    }
    fputs(output, stdout);
  }
  return status;
}
