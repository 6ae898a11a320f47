/* libFuzzer target: the command line's parsers (cli/cli.h) on arbitrary
 * arguments. The input is split at NUL bytes into at most 64 arguments; the
 * first names the command (render, view, bench or compare; anything else
 * is given to all four). Parsers read no file and start nothing, so any
 * arguments are safe to try. Whatever a parser accepts must be settings in
 * their documented ranges, which the library's own check then takes or refuses
 * with a message. Build and run with scripts/fuzz.sh. */
#include "bench.h"
#include "cli.h"

#include "render/renderer.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_ARGS = 64 };

static void check_settings(const glint_render_settings *s) {
  if (s->max_depth < 1 || s->max_depth > GLINT_MAX_DEPTH || s->spp < 1 ||
      s->spp > GLINT_MAX_SPP || s->width < 0 ||
      s->width > GLINT_MAX_DIMENSION || s->height < 0 ||
      s->height > GLINT_MAX_DIMENSION || s->threads < 0 ||
      s->threads > GLINT_MAX_THREADS || !(s->gamma > 0) || !isfinite(s->gamma))
    abort();
  glint_error e;
  e.message[0] = '\0';
  if (gli_render_settings_check(s, 640, 480, &e) != GLINT_OK &&
      e.message[0] == '\0')
    abort(); /* a refusal without a message */
}

static void parse_render(int argc, char **argv) {
  render_options o;
  if (render_parse(argc, argv, &o) < 0) {
    if (!o.scene || (o.to_stdout && o.stream_format == GLINT_FORMAT_UNKNOWN))
      abort();
    check_settings(&o.settings);
  }
}

static void parse_bench(int argc, char **argv) {
  bench_options o;
  if (bench_parse(argc, argv, &o) < 0) {
    if (o.nscenes < 1 || o.ndepths < 1 || o.nthreads < 1 || o.ncols < 1 ||
        o.runs < 1)
      abort();
    for (int c = 0; c < o.ncols; c++)
      if (!glint_backend_supported(o.cols[c].backend))
        abort();
    check_settings(&o.settings);
  }
}

static void parse_view(int argc, char **argv) {
  view_options o;
  if (view_parse(argc, argv, &o) < 0) {
    if (!o.scene || o.benchmark_frames < 0 || !(o.budget_ms >= 1))
      abort();
    check_settings(&o.settings);
  }
}

static void parse_compare(int argc, char **argv) {
  compare_options o;
  if (compare_parse(argc, argv, &o) < 0 && (!o.files[0] || !o.files[1]))
    abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  /* Our own copy, NUL-terminated: parsers may split arguments in place. */
  char *text = malloc(size + 1);
  if (!text)
    return 0;
  memcpy(text, data, size);
  text[size] = '\0';
  char *argv[MAX_ARGS + 1];
  int argc = 0;
  for (size_t i = 0; i <= size && argc < MAX_ARGS;) {
    argv[argc++] = text + i;
    i += strlen(text + i) + 1;
  }
  argv[argc] = NULL;
  /* Parsers modify what they split; give each its own copy. */
  char *copy = malloc(size + 1);
  char *args[MAX_ARGS + 1];
  if (copy) {
    void (*parsers[4])(int, char **) = {parse_render, parse_view, parse_bench,
                                        parse_compare};
    const char *names[4] = {"render", "view", "bench", "compare"};
    int chosen = -1;
    for (int p = 0; p < 4; p++)
      if (strcmp(argv[0], names[p]) == 0)
        chosen = p;
    for (int p = 0; p < 4; p++) {
      if (chosen >= 0 && p != chosen)
        continue;
      memcpy(copy, text, size + 1);
      for (int a = 0; a <= argc; a++)
        args[a] = argv[a] ? copy + (argv[a] - text) : NULL;
      /* With a command name first, its arguments follow it. */
      int skip = chosen >= 0;
      parsers[p](argc - skip, args + skip);
    }
  }
  free(copy);
  free(text);
  return 0;
}
