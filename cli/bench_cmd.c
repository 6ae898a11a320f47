#define _DEFAULT_SOURCE /* realpath */
/* glint bench: renders scenes x depths x backends (x thread counts) and
 * prints tables shaped like the thesis's A.1–A.3 (seconds per depth and
 * backend), with Mrays/s, speed-ups, SIMD lane utilisation, the stream
 * backends' stages and, for several thread counts, the scaling. A benchmark,
 * not a test: nothing here passes or fails on speed. */
#include "args.h"
#include "bench.h"
#include "cli.h"
#include "files.h"

#include <glint.h>

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_ITEMS BENCH_MAX_ITEMS

static void bench_usage(FILE *f) {
  fputs(
      "Usage: glint bench [options]\n"
      "\n"
      "Renders every scene at every depth with every backend, --runs times,\n"
      "and prints the median seconds per depth and backend (the shape of the\n"
      "thesis's tables A.1-A.3), rays per second, speed-ups over\n"
      "scalar-float, SIMD lane utilisation and the stream backends' stages.\n"
      "Each scene is committed once and each column keeps one renderer\n"
      "(auto: one per backend it picks) for all its frames, as an\n"
      "application rendering many frames does (--time-to-image measures a\n"
      "whole glint render process). A scene's columns of one thread count\n"
      "are run together, their runs interleaved, after one untimed\n"
      "warm-up frame of each column.\n"
      "\n"
      "Options:\n"
      "  --scenes LIST      built-in scenes or scene files, comma-separated\n"
      "                     (default: whitted,giza,billiard)\n"
      "  --depths LIST      depths, e.g. 1-15 or 1,5,10,15 (default: 1-15)\n"
      "  --backends LIST    backends (default: every one this CPU supports);\n"
      "                     auto renders each scene and depth with what\n"
      "                     glint render would choose for it\n"
      "  --runs N           repetitions; the median is reported (default: 3)\n"
      "  -W, --width N      (default: the scene's own; 640 for built-ins)\n"
      "  -H, --height N     (default: the scene's own; 480 for built-ins)\n"
      "  -s, --spp N        samples per pixel (default: 5)\n"
      "  -t, --threads LIST worker threads, e.g. 1 or 1,2 for a scaling\n"
      "                     table; 0 = all cores (default: 1)\n"
      "      --math NAME    minimax, fast, taylor, exact (default: minimax)\n"
      "      --no-newton    skip the Newton step after rcp\n"
      "      --accel NAME   bvh, bvh2, bvh8, none (default: bvh)\n"
      "      --csv FILE     also write every measurement as CSV (once\n"
      "                     every run has ended; on an error or Ctrl-C an\n"
      "                     existing FILE stays as it was); this table and\n"
      "                     --spd's only\n"
      "      --plot DIR     also plot seconds against depth per scene into\n"
      "                     DIR/SCENE.png, with its data and gnuplot script\n"
      "                     (DIR/SCENE.dat, DIR/SCENE.gp; needs gnuplot);\n"
      "                     this table only\n"
      "      --spd DIR      instead: the SPD scenes in DIR (balls-s4, "
      "gears-s4,\n"
      "                     mount-s6, rings-s4, teapot-s4, tetra-s6, tree-s4)\n"
      "                     at 512x512, 1 spp, depth 5, against Tachyon when\n"
      "                     it is installed\n"
      "      --frames N     instead: N frames of one scene with the\n"
      "                     camera orbiting, through one renderer and\n"
      "                     through N glint_render calls: the cost of a\n"
      "                     frame beyond its rendering (first depth,\n"
      "                     thread count and backend of the lists;\n"
      "                     depth 5 unless --depths is given)\n"
      "      --time-to-image\n"
      "                     instead: each scene written by glint render\n"
      "                     as a whole process (PNG and PPM), against its\n"
      "                     render time (first depth, thread count and\n"
      "                     backend, as for --frames)\n"
      "      --view N       instead: glint view --benchmark N on each scene\n"
      "                     (first depth, thread count and backend)\n"
      "      --meshes DIR   instead: primary-ray throughput on DIR/bunny.obj\n"
      "                     and DIR/dragon_vrip_res2.ply.gz (1024x1024, one\n"
      "                     thread), with Embree 3 on the same rays when\n"
      "                     glint-embree-bench was built\n"
      "  -h, --help         this help\n"
      "\n"
      "An option the chosen benchmark does not use is refused.\n",
      f);
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

double bench_median(const double *v, int n) {
  /* n is up to --frames' 100000: the sorted copy is the heap's. */
  double *tmp = malloc(sizeof *v * (size_t)n);
  if (!tmp || n <= 0) {
    free(tmp);
    return NAN;
  }
  memcpy(tmp, v, sizeof *v * (size_t)n);
  qsort(tmp, (size_t)n, sizeof *tmp, cmp_double);
  double median = n % 2 ? tmp[n / 2] : 0.5 * (tmp[n / 2 - 1] + tmp[n / 2]);
  free(tmp);
  return median;
}

void bench_child_args(const glint_render_settings *rs, char width[16],
                      char height[16], char *out[BENCH_CHILD_ARGS]) {
  int k = 0;
  for (int i = 0; i < BENCH_CHILD_ARGS; i++)
    out[i] = NULL;
  snprintf(width, 16, "%d", rs->width);
  snprintf(height, 16, "%d", rs->height);
  if (rs->width)
    out[k++] = "-W", out[k++] = width;
  if (rs->height)
    out[k++] = "-H", out[k++] = height;
  out[k++] = "--math", out[k++] = (char *)glint_math_name(rs->math);
  out[k++] = "--accel", out[k++] = (char *)glint_accel_name(rs->accel);
  if (!rs->rcp_newton)
    out[k++] = "--no-newton";
}

uint64_t bench_rays(const glint_stats *s) {
  return s->primary_rays + s->secondary_rays + s->shadow_rays;
}

double bench_lane_use(const glint_stats *s, glint_backend b) {
  int w = glint_backend_width(b);
  return w > 1 && s->packet_tests
             ? (double)s->active_lanes / ((double)s->packet_tests * w)
             : 1.0;
}

/* "1-15" or "1,5,10,15" (or a mix), each in [lo, hi] and once (a value
 * twice made two columns or rows alike, and a speed-up table against the
 * wrong one); `example` is such a list for the option. */
static int parse_range_list(const char *option, const char *example, char *text,
                            long lo, long hi, int *out) {
  char *items[MAX_ITEMS];
  int n = split_list(text, items, MAX_ITEMS), count = 0;
  if (n <= 0) {
    cli_error("%s: give a list such as %s", option, example);
    return -1;
  }
  for (int i = 0; i < n; i++) {
    int a, b;
    /* not a leading minus sign (nor past an empty item's end) */
    char *dash = items[i][0] ? strchr(items[i] + 1, '-') : NULL;
    if (dash && strchr(dash + 1, '-')) {
      cli_error("%s: '%s' is not a value or a range A-B", option, items[i]);
      return -1;
    }
    if (dash) {
      *dash = '\0';
      if (parse_int(option, items[i], lo, hi, &a) ||
          parse_int(option, dash + 1, lo, hi, &b))
        return -1;
      if (a > b) {
        cli_error("%s: the range %d-%d runs backwards (write %d-%d)", option, a,
                  b, b, a);
        return -1;
      }
    } else {
      if (parse_int(option, items[i], lo, hi, &a))
        return -1;
      b = a;
    }
    for (int d = a; d <= b; d++) {
      if (count == MAX_ITEMS) {
        cli_error("%s: at most %d values", option, MAX_ITEMS);
        return -1;
      }
      for (int k = 0; k < count; k++)
        if (out[k] == d) {
          cli_error("%s: %d is in the list twice", option, d);
          return -1;
        }
      out[count++] = d;
    }
  }
  if (count == 0) {
    cli_error("%s: the list is empty", option);
    return -1;
  }
  return count;
}

/* Whether gnuplot can be given `name`: its strings hold no line break
 * (the plot failed after the whole benchmark). */
static int plot_name_ok(const char *what, const char *name) {
  if (!strpbrk(name, "\n\r"))
    return 1;
  cli_error("--plot: %s has a line break, which gnuplot cannot take", what);
  return 0;
}

/* --plot needs gnuplot and a folder to write into; checked before the
 * (long) measurements rather than after. A missing folder is made once
 * the scenes have loaded (make_plot_dir): here, only its parent is looked
 * at (a run refused for a scene left the folder made). */
static int check_plot_dir(const char *dir) {
  if (!bench_have_program("gnuplot")) {
    cli_error("--plot needs gnuplot (Debian package gnuplot-nox)");
    return -1;
  }
  if (!plot_name_ok("the folder's name", dir))
    return -1;
  struct stat sb;
  if (stat(dir, &sb) == 0) {
    if (!S_ISDIR(sb.st_mode)) {
      cli_error("--plot: %s is not a folder", dir);
      return -1;
    }
    if (access(dir, W_OK | X_OK) != 0) {
      cli_error("--plot: cannot write in the folder %s: %s", dir,
                strerror(errno));
      return -1;
    }
    return 0;
  }
  int err = errno;
  if (lstat(dir, &sb) == 0) { /* a link to nothing */
    cli_error("--plot: %s is a link to nothing, not a folder", dir);
    return -1;
  }
  char parent[PATH_MAX]; /* the folder it would be made in */
  snprintf(parent, sizeof parent, "%s", dir);
  size_t n = strlen(parent);
  while (n > 1 && parent[n - 1] == '/') /* plots/ */
    parent[--n] = '\0';
  char *slash = strrchr(parent, '/');
  if (!slash)
    strcpy(parent, ".");
  else if (slash == parent)
    parent[1] = '\0';
  else
    *slash = '\0';
  if (err == ENOENT && access(parent, W_OK | X_OK) == 0)
    return 0;
  cli_error("--plot: cannot create the folder %s: %s", dir,
            strerror(err == ENOENT ? errno : err));
  return -1;
}

/* Makes --plot's folder if it is missing; *made says whether it was. */
static int make_plot_dir(const char *dir, int *made) {
  *made = 0;
  struct stat sb;
  if (mkdir(dir, 0777) == 0)
    *made = 1;
  else if (errno != EEXIST) {
    cli_error("--plot: cannot create the folder %s: %s", dir, strerror(errno));
    return -1;
  } else if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
    cli_error("--plot: %s is not a folder", dir); /* made meanwhile */
    return -1;
  }
  return 0;
}

/* Text inside a gnuplot single-quoted string, where a quote is written
 * twice. */
static void put_gnuplot_text(FILE *f, const char *text) {
  for (const char *p = text; *p; p++)
    if (*p == '\'')
      fputs("''", f);
    else
      fputc(*p, f);
}

/* DIR/SCENE.SUFFIX as a gnuplot string. */
static void put_gnuplot_path(FILE *f, const char *dir, const char *scene,
                             const char *suffix) {
  fputc('\'', f);
  put_gnuplot_text(f, dir);
  fputc('/', f);
  put_gnuplot_text(f, scene);
  fprintf(f, ".%s'", suffix);
}

/* Writes `size` bytes of text to `path` whole, or leaves what was there;
 * 0, or -1 after a message naming the file and the error. */
static int write_whole(const char *path, const char *text, size_t size) {
  int saved = replace_whole(path, text, size);
  if (saved)
    cli_error("--plot: %s: writing failed: %s", path, strerror(saved));
  return saved ? -1 : 0;
}

/* Whether the file at `path` is a PNG from its signature to its IEND
 * chunk, as a whole one ends. */
static int png_is_whole(const char *path) {
  static const unsigned char signature[8] = {0x89, 'P',  'N',  'G',
                                             '\r', '\n', 0x1a, '\n'};
  static const unsigned char iend[12] = {0,   0,   0,    0,    'I',  'E',
                                         'N', 'D', 0xae, 0x42, 0x60, 0x82};
  unsigned char head[8], tail[12];
  FILE *f = fopen(path, "rb");
  int whole = f && fread(head, 1, 8, f) == 8 && fseek(f, -12, SEEK_END) == 0 &&
              fread(tail, 1, 12, f) == 12 && !memcmp(head, signature, 8) &&
              !memcmp(tail, iend, 12);
  if (f)
    fclose(f);
  return whole;
}

/* The gnuplot script of the plot of `scene`, drawing into `output`. */
static char *plot_script(const char *dir, const char *scene, const char *output,
                         const bench_column *cols, int ncols,
                         const glint_stats *st, size_t *size) {
  char *text = NULL;
  FILE *f = open_memstream(&text, size);
  if (!f)
    return NULL;
  /* Names go into gnuplot's single-quoted strings, quotes doubled; and
   * gnuplot runs without a shell, so no name is ever a command. */
  fprintf(f, "set terminal pngcairo size 800,500 font 'sans,11'\n"
             "set output '");
  put_gnuplot_text(f, output);
  fprintf(f, "'\nset title 'Scene \"");
  put_gnuplot_text(f, scene);
  fprintf(f,
          "\": render time against recursion depth (%dx%d, %d spp)'\n"
          "set xlabel 'recursion depth'\nset ylabel 'seconds'\n"
          "set key top left\nset grid\nset xtics 1\n"
          "plot ",
          st->width, st->height, st->spp);
  for (int c = 0; c < ncols; c++) {
    fprintf(f, "%s", c ? ", " : "");
    put_gnuplot_path(f, dir, scene, "dat");
    fprintf(f, " using 1:%d with linespoints lw 2 title '%s'", c + 2,
            cols[c].name);
  }
  fprintf(f, "\n");
  if (fclose(f) != 0) {
    free(text);
    return NULL;
  }
  return text;
}

/* Seconds against depth, one line per column, like the thesis's figures
 * 5.4-5.6: DIR/SCENE.dat (the data), DIR/SCENE.gp (the script) and
 * DIR/SCENE.png (the plot). Each is written whole or not at all: gnuplot
 * draws into a file beside the plot, which takes the plot's place once it
 * reads as a whole PNG (gnuplot exits 0 when its output cannot be written:
 * on a full disk a good plot was replaced by a truncated one). 0, or -1
 * after a message. */
static int plot_scene(const char *dir, const char *scene, const int *depths,
                      int ndepths, const bench_column *cols, int ncols,
                      const double *medians, const glint_stats *st) {
  char path[PATH_MAX], png[PATH_MAX];
  if (snprintf(path, sizeof path, "%s/%s.dat", dir, scene) >=
          (int)sizeof path ||
      snprintf(png, sizeof png, "%s/%s.png", dir, scene) >= (int)sizeof png) {
    cli_error("--plot: %s/%s.png: %s", dir, scene, strerror(ENAMETOOLONG));
    return -1;
  }
  char *text = NULL;
  size_t size = 0;
  FILE *f = open_memstream(&text, &size);
  if (!f) {
    cli_error("--plot: out of memory");
    return -1;
  }
  fprintf(f, "# depth");
  for (int c = 0; c < ncols; c++)
    fprintf(f, " %s", cols[c].name);
  fprintf(f, "\n");
  for (int d = 0; d < ndepths; d++) {
    fprintf(f, "%d", depths[d]);
    for (int c = 0; c < ncols; c++)
      fprintf(f, " %.6f", medians[d * ncols + c]);
    fprintf(f, "\n");
  }
  int failed = fclose(f) != 0;
  if (failed)
    cli_error("--plot: out of memory");
  failed = failed || write_whole(path, text, size);
  free(text);
  text = NULL;
  /* the script kept (drawing into SCENE.png), and the one run */
  if (snprintf(path, sizeof path, "%s/%s.gp", dir, scene) >= (int)sizeof path) {
    cli_error("--plot: %s/%s.gp: %s", dir, scene, strerror(ENAMETOOLONG));
    failed = 1;
  }
  char *kept = NULL;
  if (!failed) {
    kept = plot_script(dir, scene, png, cols, ncols, st, &size);
    if (!kept)
      cli_error("--plot: out of memory");
    failed = !kept || write_whole(path, kept, size);
  }
  free(kept);
  if (failed)
    return -1;
  file_replacement plot, run;
  int saved = replace_begin(&plot, png);
  if (saved) {
    cli_error("--plot: %s: writing failed: %s", png, strerror(saved));
    return -1;
  }
  int drawn = 0;
  saved = replace_begin(&run, path);
  if (saved) {
    cli_error("--plot: %s: writing failed: %s", path, strerror(saved));
  } else {
    char *script = plot_script(dir, scene, plot.temp, cols, ncols, st, &size);
    saved = script ? replace_write(&run, script, size) : ENOMEM;
    free(script);
    if (saved) {
      cli_error("--plot: %s: writing failed: %s", path, strerror(saved));
    } else {
      char *argv[] = {"gnuplot", run.temp, NULL};
      char output[4096]; /* gnuplot's words: what it drew is checked */
      drawn = bench_run_capture(argv, output, sizeof output) == 0;
      if (!drawn)
        cli_error("--plot: gnuplot could not draw %s", png);
      else if (!(drawn = png_is_whole(plot.temp)))
        cli_error("--plot: gnuplot could not write %s whole (is the disk "
                  "full?)",
                  png);
    }
    replace_end(&run, 0); /* the script run goes */
  }
  int ended = replace_end(&plot, drawn);
  if (drawn && ended)
    cli_error("--plot: %s: writing failed: %s", png, strerror(ended));
  return drawn && !ended ? 0 : -1;
}

static void print_header(const char *title, const char *scene,
                         const bench_column *cols, int ncols, int packets) {
  printf("Scene \"%s\": %s\n%5s", scene, title, "depth");
  for (int c = 0; c < ncols; c++)
    if (!packets || glint_backend_width(cols[c].backend) > 1)
      printf(" %14s", cols[c].name);
  printf("\n");
}

int bench_parse(int argc, char **argv, bench_options *o) {
  char depth_list_default[] = "1-15", threads_default[] = "1";
  char *depth_list = NULL, *backend_list = NULL, *thread_list = NULL;
  memset(o, 0, sizeof *o);
  /* The scene names point into the list, split in place: the default's
   * copy lives in the options. */
  snprintf(o->default_scenes, sizeof o->default_scenes, "%s",
           "whitted,giza,billiard");
  char *scene_list = o->default_scenes;
  o->runs = 0; /* 3 unless given */
  glint_render_settings *rs = &o->settings;
  glint_render_settings_default(rs);
  rs->width = rs->height = 0; /* 0: not given */
  glint_error err;
  arg_cursor c = {argc, argv, 0, NULL};
  while (c.i < argc) {
    const char *a = argv[c.i];
    if (arg_is_help(&c)) {
      bench_usage(stdout);
      return 0;
    }
    int r;
    if ((r = arg_render_setting(&c, rs)) ||
        (r = arg_text(&c, NULL, "--scenes", &scene_list)) ||
        (r = arg_text(&c, NULL, "--depths", &depth_list)) ||
        (r = arg_text(&c, NULL, "--backends", &backend_list)) ||
        (r = arg_int(&c, NULL, "--runs", 1, 255, &o->runs)) ||
        (r = arg_text(&c, "-t", "--threads", &thread_list)) ||
        (r = arg_text(&c, NULL, "--csv", &o->csv_path)) ||
        (r = arg_text(&c, NULL, "--plot", &o->plot_dir)) ||
        (r = arg_text(&c, NULL, "--spd", &o->spd_dir)) ||
        (r = arg_text(&c, NULL, "--meshes", &o->mesh_dir)) ||
        (r = arg_int(&c, NULL, "--frames", 1, 100000, &o->frames)) ||
        (r = arg_flag(&c, NULL, "--time-to-image", &o->time_to_image)) ||
        (r = arg_int(&c, NULL, "--view", 1, 1000000, &o->view_frames))) {
      if (r == ARG_BAD)
        return EXIT_USAGE;
      continue;
    }
    if (a[0] != '-' || a[1] == '\0')
      cli_error("unexpected argument '%s': glint bench takes options only "
                "(see glint bench --help)",
                a);
    else
      arg_unknown(a, "bench");
    return EXIT_USAGE;
  }

  o->runs_given = o->runs != 0;
  o->runs = o->runs ? o->runs : 3;
  o->scenes_given = scene_list != o->default_scenes;
  o->threads_given = thread_list != NULL;
  /* An empty name would read as the root folder ("/balls-s4.nff") or the
   * current one. */
  const char *named[] = {"--spd", o->spd_dir,  "--meshes", o->mesh_dir,
                         "--csv", o->csv_path, "--plot",   o->plot_dir};
  for (int i = 0; i < 8; i += 2)
    if (named[i + 1] && !*named[i + 1]) {
      cli_error("%s: the name is empty", named[i]);
      return EXIT_USAGE;
    }
  o->depths_given = depth_list != NULL;
  o->ndepths = parse_range_list("--depths", "1-15 or 1,5,10,15",
                                depth_list ? depth_list : depth_list_default, 1,
                                GLINT_MAX_DEPTH, o->depths);
  if (o->ndepths < 0)
    return EXIT_USAGE;
  o->nthreads = parse_range_list("--threads", "1 or 1,2",
                                 thread_list ? thread_list : threads_default, 0,
                                 GLINT_MAX_THREADS, o->threads);
  if (o->nthreads < 0)
    return EXIT_USAGE;
  /* 0 is every CPU: -t 0,2 on two CPUs made two columns alike */
  for (int i = 0; i < o->nthreads; i++)
    for (int j = 0; j < o->nthreads; j++)
      if (o->threads[i] == 0 && o->threads[j] == glint_cpu_count()) {
        cli_error("--threads: 0 (every CPU this process may use) and %d are "
                  "one thread count here",
                  o->threads[j]);
        return EXIT_USAGE;
      }
  o->nscenes = split_list(scene_list, o->scenes, MAX_ITEMS);
  if (o->nscenes <= 0) {
    cli_error("--scenes: give at least one scene");
    return EXIT_USAGE;
  }
  for (int i = 0; i < o->nscenes; i++)
    if (!*o->scenes[i]) { /* "whitted,,giza" or "," */
      cli_error("--scenes: an empty name in the list (a comma at either end, "
                "or two together)");
      return EXIT_USAGE;
    }
  /* A scene's name labels its rows, lines and plot files: two of one name
   * could not be told apart (the second's plot replaced the first's). */
  for (int i = 1; i < o->nscenes; i++)
    for (int j = 0; j < i; j++) {
      char a[CLI_STEM_SIZE], b[CLI_STEM_SIZE];
      cli_scene_stem(o->scenes[i], a, sizeof a);
      cli_scene_stem(o->scenes[j], b, sizeof b);
      if (strcmp(a, b) == 0) {
        cli_error("--scenes: two scenes named '%s' (%s and %s): their results "
                  "could not be told apart",
                  a, o->scenes[j], o->scenes[i]);
        return EXIT_USAGE;
      }
    }

  o->backends_given = backend_list != NULL;
  if (backend_list) {
    char *items[MAX_ITEMS];
    const char *given[GLINT_BACKEND_COUNT]; /* as named, by o->backends */
    int n = split_list(backend_list, items, MAX_ITEMS);
    for (int i = 0; i < n; i++) {
      glint_backend b;
      if (!*items[i]) { /* as --scenes says it ("unknown backend ''") */
        cli_error("--backends: an empty name in the list (a comma at either "
                  "end, or two together)");
        return EXIT_USAGE;
      }
      if (glint_backend_parse(items[i], &b, &err)) {
        cli_error("--backends: %s", err.message);
        return EXIT_USAGE;
      }
      if (!glint_backend_supported(b)) {
        cli_unsupported_backend(items[i]);
        return EXIT_USAGE;
      }
      /* auto stays auto: each scene and depth renders with what glint
       * render would choose for them (glint_backend_choose) */
      glint_backend run =
          b == GLINT_BACKEND_AUTO ? b : glint_backend_resolve(b);
      for (int k = 0; k < o->nbackends; k++)
        if (o->backends[k] == run) {
          if (strcmp(given[k], items[i]) == 0)
            cli_error("--backends: %s is in the list twice", items[i]);
          else
            cli_error("--backends: %s and %s are one backend here (%s)",
                      given[k], items[i], glint_backend_name(run));
          return EXIT_USAGE;
        }
      given[o->nbackends] = items[i];
      o->backends[o->nbackends++] = run;
    }
    if (o->nbackends <= 0) {
      cli_error("--backends: the list is empty");
      return EXIT_USAGE;
    }
  } else {
    for (int b = 0; b < GLINT_BACKEND_COUNT; b++)
      if (b != GLINT_BACKEND_AUTO && b != GLINT_BACKEND_STREAM &&
          glint_backend_supported((glint_backend)b))
        o->backends[o->nbackends++] = (glint_backend)b;
  }

  /* Columns: every backend at every thread count. */
  for (int t = 0; t < o->nthreads; t++)
    for (int b = 0;
         b < o->nbackends && o->ncols < GLINT_BACKEND_COUNT * BENCH_MAX_ITEMS;
         b++) {
      bench_column *col = &o->cols[o->ncols++];
      col->backend = o->backends[b];
      col->threads = o->threads[t];
      if (o->nthreads > 1)
        snprintf(col->name, sizeof col->name, "%s/%dt",
                 glint_backend_name(o->backends[b]), o->threads[t]);
      else
        snprintf(col->name, sizeof col->name, "%s",
                 glint_backend_name(o->backends[b]));
    }
  return -1;
}

/* ---- the CSV file -------------------------------------------------------
 * The rows are gathered in memory and the file is written only when the
 * benchmark has run to its end, through a temporary file beside it renamed
 * over it: a bad scene, a failed render or Ctrl-C leaves an existing file
 * as it was, and no half-written one. */

/* Whether the CSV can be written (checked before anything is measured) and
 * is none of the files the benchmark reads: its scenes (`scenes`, or the
 * SPD scenes of spd_dir), and the meshes they name, whose names the check
 * goes by (an existing scene or mesh file is never replaced by a CSV). */
static int check_csv_path(const char *path, char **scenes, int nscenes,
                          const char *spd_dir) {
  if (strcmp(path, "-") == 0) { /* -o - is standard output; this is not */
    cli_error("--csv: '-' would be a file of that name; the table is on "
              "standard output already (name a file, or ./- for that one)");
    return -1;
  }
  struct stat csv_sb;
  if (stat(path, &csv_sb) == 0) {
    if (S_ISDIR(csv_sb.st_mode)) {
      cli_error("--csv: %s is a folder", path);
      return -1;
    }
    /* The rename would put a file in the place of a device or a pipe (of
     * /dev/full through a link to it), as the images' writer refuses to */
    if (!S_ISREG(csv_sb.st_mode)) {
      cli_error("--csv: %s: not a regular file", path);
      return -1;
    }
    int scene = spd_dir && bench_spd_scene_at(spd_dir, path);
    for (int i = 0; i < nscenes && !scene; i++)
      scene = same_file(scenes[i], path);
    if (scene) {
      cli_error("--csv: %s is a scene of this benchmark", path);
      return -1;
    }
    char target[PATH_MAX];
    if (named_as_input(path) ||
        (realpath(path, target) && named_as_input(target))) {
      cli_error("--csv: %s is a scene or mesh file (.nff, .json, .obj, .ply): "
                "the CSV would replace it",
                path);
      return -1;
    }
  }
  char temp[PATH_MAX + 32];
  int fd = create_beside(path, temp, sizeof temp);
  if (fd < 0) {
    cli_error("--csv: %s: cannot write here: %s", path, strerror(errno));
    return -1;
  }
  close(fd);
  unlink(temp);
  return 0;
}

/* Writes the CSV's `size` bytes to `path` whole, or not at all. Stop
 * signals wait until the file is in place. */
static int write_csv(const char *path, const char *text, size_t size) {
  int saved = replace_whole(path, text, size);
  if (saved) {
    cli_error("%s: writing the CSV file failed: %s", path, strerror(saved));
    return -1;
  }
  return 0;
}

/* A benchmark that fixes what it renders refuses the options it would not
 * use, rather than ignore them (--spd rendered its 512x512 at depth 5
 * whatever -W or --depths said). */
static int unused_options(const bench_options *o) {
  glint_render_settings defaults;
  glint_render_settings_default(&defaults);
  const glint_render_settings *rs = &o->settings;
  const char *option = NULL, *mode = NULL, *why = NULL;
  if (o->spd_dir || o->mesh_dir) {
    option = rs->width                                  ? "-W"
             : rs->height                               ? "-H"
             : rs->spp != defaults.spp                  ? "-s"
             : o->depths_given                          ? "--depths"
             : o->scenes_given                          ? "--scenes"
             : o->mesh_dir && o->threads_given          ? "-t"
             : o->mesh_dir && rs->math != defaults.math ? "--math"
                                                        : NULL;
    mode = o->spd_dir ? "--spd" : "--meshes";
    why = o->spd_dir ? "renders the SPD files' own size, 1 spp, depth 5"
                     : "traces 1024x1024 primary rays on one thread, "
                       "shading none";
  } else if (o->view_frames || o->frames) {
    /* (--frames with no --scenes: the default list's first, Whitted) */
    option = o->runs_given                                    ? "--runs"
             : o->view_frames && rs->spp != defaults.spp      ? "-s"
             : o->frames && o->scenes_given && o->nscenes > 1 ? "a second scene"
                                                              : NULL;
    mode = o->view_frames ? "--view" : "--frames";
    why = o->view_frames ? "renders its frames once a scene, at 1 spp"
                         : "renders its frames once, of one scene";
  }
  if (!option)
    return 0;
  cli_error("%s %s: %s is not used", mode, why, option);
  return 1;
}

int cmd_bench(int argc, char **argv) {
  bench_options o;
  int status = bench_parse(argc, argv, &o);
  if (status >= 0)
    return status;
  glint_render_settings rs = o.settings;
  int modes = (o.frames > 0) + o.time_to_image + (o.view_frames > 0) +
              (o.mesh_dir != NULL) + (o.spd_dir != NULL);
  if (modes > 1) {
    cli_error("--frames, --time-to-image, --view, --meshes and --spd are "
              "benchmarks of their own: choose one");
    return EXIT_USAGE;
  }
  /* Only the scene benchmark (and --spd, for --csv) writes them: given to
   * another they were ignored, an empty --plot folder made. */
  int csv_ignored = o.csv_path && modes && !o.spd_dir;
  if (csv_ignored || (o.plot_dir && modes)) {
    cli_error("%s is written by the scene benchmark%s only",
              csv_ignored ? "--csv" : "--plot",
              csv_ignored ? " and --spd" : "");
    return EXIT_USAGE;
  }
  if (o.plot_dir && check_plot_dir(o.plot_dir))
    return EXIT_USAGE;
  if (unused_options(&o))
    return EXIT_USAGE;
  if (o.mesh_dir)
    return bench_meshes(o.mesh_dir, &rs, o.backends, o.nbackends, o.runs);
  if (o.frames || o.time_to_image || o.view_frames) {
    /* One configuration: the first of each list; the render's own depth
     * when none is given. */
    if (o.depths_given)
      rs.max_depth = o.depths[0];
    rs.threads = o.threads[0];
    rs.backend = o.backends_given ? o.backends[0] : GLINT_BACKEND_AUTO;
    if (o.view_frames)
      return bench_view(o.scenes, o.nscenes, &rs, o.view_frames);
    return o.frames ? bench_frames(o.scenes[0], &rs, o.frames)
                    : bench_time_to_image(o.scenes, o.nscenes, &rs, o.runs);
  }

  FILE *csv = NULL;
  char *csv_text = NULL;
  size_t csv_size = 0;
  if (o.csv_path) {
    if (check_csv_path(o.csv_path, o.scenes, o.spd_dir ? 0 : o.nscenes,
                       o.spd_dir))
      return EXIT_USAGE;
    if (!(csv = open_memstream(&csv_text, &csv_size))) {
      cli_error("out of memory");
      return EXIT_MEMORY;
    }
  }
  if (csv)
    fprintf(csv, "scene,depth,backend,width,height,spp,threads,runs,"
                 "median_s,min_s,max_s,rays,primary,secondary,shadow,"
                 "mrays_per_s,lane_utilisation,sub_beams_per_beam,"
                 "generate_s,traverse_s,shade_s,compact_s,"
                 "generation_lane_use,column\n");
  if (o.spd_dir)
    status = bench_spd(o.spd_dir, &rs, o.cols, o.ncols, o.runs, csv);
  else
    status = bench_scenes(o.scenes, o.nscenes, o.depths, o.ndepths, &rs, o.cols,
                          o.ncols, o.runs, csv, o.csv_path, o.plot_dir);
  if (csv && fclose(csv) != 0 && !status) {
    cli_error("out of memory");
    status = EXIT_MEMORY;
  }
  if (csv && !status && write_csv(o.csv_path, csv_text, csv_size))
    status = EXIT_USAGE;
  free(csv_text);
  return status;
}

void bench_csv_row(FILE *csv, const char *scene, int depth,
                   const bench_column *col, const glint_stats *st,
                   const double *seconds, int runs) {
  double med = bench_median(seconds, runs), lo = seconds[0], hi = seconds[0];
  for (int r = 1; r < runs; r++) {
    lo = fmin(lo, seconds[r]);
    hi = fmax(hi, seconds[r]);
  }
  /* what rendered: an auto column's choice for this scene and depth */
  int w = glint_backend_width(st->backend);
  fprintf(csv,
          "%s,%d,%s,%d,%d,%d,%d,%d,%.6f,%.6f,%.6f,%llu,%llu,%llu,%llu,"
          "%.3f,%.4f,%.3f,%.6f,%.6f,%.6f,%.6f,",
          scene, depth, glint_backend_name(st->backend), st->width, st->height,
          st->spp, st->threads, runs, med, lo, hi,
          (unsigned long long)bench_rays(st),
          (unsigned long long)st->primary_rays,
          (unsigned long long)st->secondary_rays,
          (unsigned long long)st->shadow_rays,
          med > 0 ? (double)bench_rays(st) / med / 1e6 : 0.0,
          bench_lane_use(st, st->backend),
          st->beams ? (double)st->sub_beams / (double)st->beams : 0.0,
          st->stage_seconds[0], st->stage_seconds[1], st->stage_seconds[2],
          st->stage_seconds[3]);
  for (int g = 0; g < st->generations && g < GLINT_STATS_MAX_GENERATIONS; g++)
    fprintf(csv, "%s%.4f", g ? ";" : "",
            st->gen_packets[g] ? (double)st->gen_active_lanes[g] /
                                     ((double)st->gen_packets[g] * w)
                               : 0.0);
  /* the column asked for: auto's rows name the backend that rendered */
  fprintf(csv, ",%s\n", col->name);
}

/* Whether --plot's files for `stem` can be written: each is absent or a
 * regular file (gnuplot waited for ever on a pipe there, and a device
 * took its plot without a word), and none is, or leads through a link to,
 * a scene or mesh file (a link there turned a scene into a PNG), a scene
 * of this benchmark, or --csv's file (`csv`, or NULL). */
static int check_plot_files(const char *dir, const char *stem, char **scenes,
                            int nscenes, const char *csv) {
  static const char *const suffixes[] = {"dat", "gp", "png"};
  if (!plot_name_ok("a scene's name", stem))
    return -1;
  char *csv_file = csv ? written_file(csv) : NULL;
  int refused = 0;
  for (int k = 0; k < 3 && !refused; k++) {
    char path[8192], target[PATH_MAX];
    refused = 1;
    if (snprintf(path, sizeof path, "%s/%s.%s", dir, stem, suffixes[k]) >=
        (int)sizeof path) {
      cli_error("--plot: %s/%s.%s: the name is too long", dir, stem,
                suffixes[k]);
      break;
    }
    struct stat sb;
    char *file = written_file(path);
    int scene = 0;
    for (int i = 0; i < nscenes && !scene; i++)
      scene = same_file(scenes[i], path);
    if (stat(path, &sb) == 0 && !S_ISREG(sb.st_mode))
      cli_error("--plot: %s: not a regular file", path);
    else if (scene)
      cli_error("--plot: %s is a scene of this benchmark", path);
    else if (links_to_input(path, target))
      cli_error("--plot: %s: a link to %s, a scene or mesh file (.nff, .json, "
                ".obj, .ply): the plot would replace it",
                path, target);
    else if (file && csv_file && strcmp(file, csv_file) == 0)
      cli_error("--plot: %s is --csv's file too", path);
    else
      refused = 0;
    free(file);
  }
  free(csv_file);
  return refused ? -1 : 0;
}

int bench_scenes(char **names, int nscenes, const int *depths, int ndepths,
                 const glint_render_settings *base, const bench_column *cols,
                 int ncols, int runs, FILE *csv, const char *csv_path,
                 const char *plot_dir) {
  glint_scene *scenes[MAX_ITEMS];
  char stems[MAX_ITEMS][CLI_STEM_SIZE];
  for (int i = 0; i < nscenes; i++) {
    int code = EXIT_USAGE;
    scenes[i] = cli_load_scene(names[i], stems[i], sizeof stems[i], &code);
    if (scenes[i] && plot_dir &&
        check_plot_files(plot_dir, stems[i], names, nscenes, csv_path)) {
      glint_scene_destroy(scenes[i]);
      scenes[i] = NULL;
    }
    if (!scenes[i]) {
      for (int k = 0; k < i; k++)
        glint_scene_destroy(scenes[k]);
      return code;
    }
  }
  size_t ncells = (size_t)nscenes * ndepths * ncols;
  glint_stats *stats = calloc(ncells, sizeof *stats);
  double *times = calloc(ncells * (size_t)runs, sizeof *times);
  int made_plot_dir = 0, failed = 0;
  if (!stats || !times) {
    cli_error("out of memory");
    failed = 1;
  } else if (plot_dir && make_plot_dir(plot_dir, &made_plot_dir)) {
    failed = EXIT_USAGE;
  }
  if (failed) {
    free(stats);
    free(times);
    for (int i = 0; i < nscenes; i++)
      glint_scene_destroy(scenes[i]);
    return failed;
  }
#define IDX(s, d, c) (((size_t)(s)*ndepths + (d)) * ncols + (c))
#define SECONDS(s, d, c) (times + IDX(s, d, c) * runs)
  glint_render_settings rs = *base;
  int tty = isatty(STDERR_FILENO), status = 0;
  size_t done = 0, total = ncells * (size_t)runs;
  int deepest = depths[0];
  for (int d = 1; d < ndepths; d++)
    deepest = depths[d] > deepest ? depths[d] : deepest;
  /* Scene by scene, and within a scene thread count by thread count (the
   * columns come in that order), each column's renderer kept for all its
   * runs and depths (cli/bench_renderers.c); a group's runs are
   * interleaved. Only one group's renderers live at once: their threads and
   * stream buffers grow with the columns. Run -1 warms up, untimed: each
   * column once at the first depth (page faults in fresh scratch memory,
   * cold caches, the clock ramping up would otherwise land on the first
   * row). */
  for (int s = 0; s < nscenes && !status; s++)
    for (int c0 = 0, c1; c0 < ncols && !status; c0 = c1) {
      c1 = bench_thread_group_end(cols, ncols, c0);
      bench_renderers br;
      if (bench_renderers_open(&br, scenes[s], stems[s], ncols, deepest,
                               &status))
        break;
      for (int r = -1; r < runs && !status; r++)
        for (int d = 0; d < (r < 0 ? 1 : ndepths) && !status; d++)
          for (int c = c0; c < c1 && !status; c++) {
            rs.max_depth = depths[d];
            rs.backend = cols[c].backend;
            rs.threads = cols[c].threads;
            if (tty && r < 0) {
              fprintf(stderr, "\r[warm-up] %s %s\033[K", stems[s],
                      cols[c].name);
              fflush(stderr);
            } else if (tty) {
              fprintf(stderr, "\r[%zu/%zu] %s depth %d %s\033[K", ++done, total,
                      stems[s], depths[d], cols[c].name);
              fflush(stderr);
            }
            glint_error err;
            glint_status st =
                bench_renderers_render(&br, c, &rs, &stats[IDX(s, d, c)], &err);
            if (st) {
              cli_error("%s: %s", stems[s], err.message);
              status = cli_exit_code(st);
              break;
            }
            if (r >= 0)
              SECONDS(s, d, c)[r] = stats[IDX(s, d, c)].render_seconds;
          }
      bench_renderers_close(&br);
    }
  if (tty)
    fputs("\r\033[K", stderr);

  for (int s = 0; s < nscenes && !status; s++) {
    if (s == 0)
      printf("glint %s bench: %d spp, math %s, accel %s, median of %d run%s\n",
             glint_version(), rs.spp, glint_math_name(rs.math),
             glint_accel_name(rs.accel), runs, runs == 1 ? "" : "s");
    printf("\n%s at %dx%d\n", stems[s], stats[IDX(s, 0, 0)].width,
           stats[IDX(s, 0, 0)].height);
    print_header("seconds", stems[s], cols, ncols, 0);
    for (int d = 0; d < ndepths; d++) {
      printf("%5d", depths[d]);
      for (int c = 0; c < ncols; c++)
        printf(" %14.4f", bench_median(SECONDS(s, d, c), runs));
      printf("\n");
    }
    print_header("Mrays/s", stems[s], cols, ncols, 0);
    for (int d = 0; d < ndepths; d++) {
      printf("%5d", depths[d]);
      for (int c = 0; c < ncols; c++) {
        double t = bench_median(SECONDS(s, d, c), runs);
        printf(" %14.2f",
               t > 0 ? (double)bench_rays(&stats[IDX(s, d, c)]) / t / 1e6
                     : 0.0);
      }
      printf("\n");
    }
    /* Speed-up over scalar-float at the same thread count. */
    int any_ref = 0;
    for (int c = 0; c < ncols; c++)
      any_ref |= cols[c].backend == GLINT_BACKEND_SCALAR_FLOAT;
    if (any_ref && ncols > 1) {
      print_header("speed-up over scalar-float", stems[s], cols, ncols, 0);
      for (int d = 0; d < ndepths; d++) {
        printf("%5d", depths[d]);
        for (int c = 0; c < ncols; c++) {
          int ref = -1;
          for (int k = 0; k < ncols; k++)
            if (cols[k].backend == GLINT_BACKEND_SCALAR_FLOAT &&
                cols[k].threads == cols[c].threads)
              ref = k;
          double t = bench_median(SECONDS(s, d, c), runs);
          if (ref < 0 || t <= 0)
            printf(" %14s", "-");
          else
            printf(" %13.2fx", bench_median(SECONDS(s, d, ref), runs) / t);
        }
        printf("\n");
      }
    }
    /* Thread scaling: the first thread count against each other one. */
    if (ncols > 1 && cols[ncols - 1].threads != cols[0].threads) {
      print_header("thread scaling (time at the first thread count / time)",
                   stems[s], cols, ncols, 0);
      for (int d = 0; d < ndepths; d++) {
        printf("%5d", depths[d]);
        for (int c = 0; c < ncols; c++) {
          int base_c = -1;
          for (int k = 0; k < ncols && base_c < 0; k++)
            if (cols[k].backend == cols[c].backend)
              base_c = k;
          double t = bench_median(SECONDS(s, d, c), runs);
          printf(" %13.2fx",
                 t > 0 ? bench_median(SECONDS(s, d, base_c), runs) / t : 0.0);
        }
        printf("\n");
      }
    }
    int any_packet = 0;
    for (int c = 0; c < ncols; c++)
      any_packet |= glint_backend_width(cols[c].backend) > 1;
    if (any_packet) {
      print_header("SIMD lane utilisation", stems[s], cols, ncols, 1);
      for (int d = 0; d < ndepths; d++) {
        printf("%5d", depths[d]);
        for (int c = 0; c < ncols; c++)
          if (glint_backend_width(cols[c].backend) > 1)
            printf(" %13.1f%%",
                   100.0 * bench_lane_use(&stats[IDX(s, d, c)],
                                          stats[IDX(s, d, c)].backend));
        printf("\n");
      }
    }
    /* Stream backends: where the time goes, and how full each generation's
     * packets are (issue 5). */
    for (int c = 0; c < ncols; c++) {
      int streams = 0;
      for (int d = 0; d < ndepths; d++)
        streams |= stats[IDX(s, d, c)].backend >= GLINT_BACKEND_STREAM_SSE;
      if (!streams)
        continue;
      printf("Scene \"%s\", %s: seconds per stage (summed over threads) and "
             "lane use per generation\n%5s %9s %9s %9s %9s   generations 0, "
             "1, 2, ...\n",
             stems[s], cols[c].name, "depth", "generate", "traverse", "shade",
             "compact");
      for (int d = 0; d < ndepths; d++) {
        const glint_stats *st = &stats[IDX(s, d, c)];
        if (st->backend < GLINT_BACKEND_STREAM_SSE) {
          printf("%5d  (%s)\n", depths[d], glint_backend_name(st->backend));
          continue;
        }
        int w = glint_backend_width(st->backend);
        printf("%5d %9.4f %9.4f %9.4f %9.4f  ", depths[d], st->stage_seconds[0],
               st->stage_seconds[1], st->stage_seconds[2],
               st->stage_seconds[3]);
        for (int g = 0; g < st->generations && g < GLINT_STATS_MAX_GENERATIONS;
             g++)
          printf(" %3.0f%%", st->gen_packets[g]
                                 ? 100.0 * (double)st->gen_active_lanes[g] /
                                       ((double)st->gen_packets[g] * w)
                                 : 0.0);
        printf("\n");
      }
    }
  }
  double *med =
      plot_dir ? malloc(sizeof *med * (size_t)(ndepths * ncols)) : NULL;
  for (int s = 0; med && s < nscenes && !status; s++) {
    for (int d = 0; d < ndepths; d++)
      for (int c = 0; c < ncols; c++)
        med[d * ncols + c] = bench_median(SECONDS(s, d, c), runs);
    if (plot_scene(plot_dir, stems[s], depths, ndepths, cols, ncols, med,
                   &stats[IDX(s, 0, 0)]))
      status = EXIT_USAGE;
  }
  if (plot_dir && !med) {
    cli_error("--plot: out of memory");
    status = EXIT_MEMORY;
  }
  free(med);
  for (int s = 0; csv && s < nscenes && !status; s++)
    for (int d = 0; d < ndepths; d++)
      for (int c = 0; c < ncols; c++)
        bench_csv_row(csv, stems[s], depths[d], &cols[c], &stats[IDX(s, d, c)],
                      SECONDS(s, d, c), runs);
  free(stats);
  free(times);
  for (int i = 0; i < nscenes; i++)
    glint_scene_destroy(scenes[i]);
  if (status && made_plot_dir)
    rmdir(plot_dir); /* (one holding plots stays) */
  return status;
#undef IDX
#undef SECONDS
}
