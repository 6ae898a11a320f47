/* glint bench: renders scenes x depths x backends and prints tables shaped
 * like the thesis's A.1–A.3 (seconds per depth and backend), plus Mrays/s.
 * A benchmark, not a test: nothing here passes or fails on speed. */
#include "args.h"
#include "bench.h"
#include "cli.h"

#include <glint.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_ITEMS 64

static void bench_usage(FILE *f) {
  fputs(
      "Usage: glint bench [options]\n"
      "\n"
      "Renders every scene at every depth with every backend, --runs times,\n"
      "and prints the median seconds per depth and backend (the shape of the\n"
      "thesis's tables A.1-A.3), rays per second and SIMD lane utilisation.\n"
      "Runs are interleaved so that all columns come from the same run.\n"
      "\n"
      "Options:\n"
      "  --scenes LIST      built-in scenes or scene files, comma-separated\n"
      "                     (default: whitted,giza,billiard)\n"
      "  --depths LIST      depths, e.g. 1-15 or 1,5,10,15 (default: 1-15)\n"
      "  --backends LIST    backends (default: every one this CPU supports)\n"
      "  --runs N           repetitions; the median is reported (default: 3)\n"
      "  -W, --width N      (default: 640)\n"
      "  -H, --height N     (default: 480)\n"
      "  -s, --spp N        samples per pixel (default: 5)\n"
      "  -t, --threads N    worker threads (default: 1)\n"
      "      --math NAME    minimax, fast, taylor, exact (default: minimax)\n"
      "      --accel NAME   bvh or none (default: bvh)\n"
      "      --csv FILE     also write every measurement as CSV\n"
      "      --spd DIR      instead: the SPD scenes in DIR (balls-s4, gears-s4,\n"
      "                     mount-s6, rings-s4, teapot-s4, tetra-s6, tree-s4)\n"
      "                     at 512x512, 1 spp, depth 5, against Tachyon when\n"
      "                     it is installed\n"
      "      --meshes DIR   instead: primary-ray throughput on DIR/bunny.obj\n"
      "                     and DIR/dragon_vrip_res2.ply.gz (1024x1024), with\n"
      "                     Embree 3 on the same rays when glint-embree-bench\n"
      "                     was built\n"
      "      --plot DIR     also plot seconds against depth per scene into\n"
      "                     DIR/SCENE.png (needs gnuplot)\n"
      "  -h, --help         this help\n",
      f);
}

typedef struct cell {
  double *seconds;   /* one per run */
  glint_stats stats; /* of the last run: counts are identical run to run */
} cell;

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

double bench_median(const double *v, int n) {
  double tmp[256];
  memcpy(tmp, v, sizeof *v * (size_t)n);
  qsort(tmp, (size_t)n, sizeof *tmp, cmp_double);
  return n % 2 ? tmp[n / 2] : 0.5 * (tmp[n / 2 - 1] + tmp[n / 2]);
}

static uint64_t total_rays(const glint_stats *s) {
  return s->primary_rays + s->secondary_rays + s->shadow_rays;
}

/* "1-15" or "1,5,10,15" (or a mix). */
static int parse_depths(char *text, int *depths) {
  char *items[MAX_ITEMS];
  int n = split_list(text, items, MAX_ITEMS), count = 0;
  if (n <= 0) {
    cli_error("--depths: give a list such as 1-15 or 1,5,10,15");
    return -1;
  }
  for (int i = 0; i < n; i++) {
    int lo, hi;
    char *dash = strchr(items[i], '-');
    if (dash) {
      *dash = '\0';
      if (parse_int("--depths", items[i], 1, GLINT_MAX_DEPTH, &lo) ||
          parse_int("--depths", dash + 1, 1, GLINT_MAX_DEPTH, &hi))
        return -1;
    } else {
      if (parse_int("--depths", items[i], 1, GLINT_MAX_DEPTH, &lo))
        return -1;
      hi = lo;
    }
    for (int d = lo; d <= hi; d++) {
      if (count == MAX_ITEMS) {
        cli_error("--depths: at most %d depths", MAX_ITEMS);
        return -1;
      }
      depths[count++] = d;
    }
  }
  if (count == 0) {
    cli_error("--depths: the list is empty");
    return -1;
  }
  return count;
}

/* --plot needs gnuplot and a folder to write into; checked before the
 * (long) measurements rather than after. */
static int check_plot_dir(const char *dir) {
  if (system("command -v gnuplot >/dev/null 2>&1") != 0) {
    cli_error("--plot needs gnuplot (Debian package gnuplot-nox)");
    return -1;
  }
  struct stat sb;
  if (stat(dir, &sb) != 0 && mkdir(dir, 0777) != 0) {
    cli_error("--plot: cannot create the folder %s", dir);
    return -1;
  }
  if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
    cli_error("--plot: %s is not a folder", dir);
    return -1;
  }
  return 0;
}

/* Seconds against depth, one line per backend, like the thesis's figures
 * 5.4-5.6: DIR/SCENE.dat (the data), DIR/SCENE.gp (the script) and
 * DIR/SCENE.png (the plot). */
static int plot_scene(const char *dir, const char *scene, const int *depths,
                      int ndepths, const glint_backend *backends,
                      int nbackends, const double *medians) {
  char path[8192];
  snprintf(path, sizeof path, "%s/%s.dat", dir, scene);
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  fprintf(f, "# depth");
  for (int b = 0; b < nbackends; b++)
    fprintf(f, " %s", glint_backend_name(backends[b]));
  fprintf(f, "\n");
  for (int d = 0; d < ndepths; d++) {
    fprintf(f, "%d", depths[d]);
    for (int b = 0; b < nbackends; b++)
      fprintf(f, " %.6f", medians[d * nbackends + b]);
    fprintf(f, "\n");
  }
  if (fclose(f) != 0)
    return -1;
  snprintf(path, sizeof path, "%s/%s.gp", dir, scene);
  if (!(f = fopen(path, "w")))
    return -1;
  fprintf(f,
          "set terminal pngcairo size 800,500 font 'sans,11'\n"
          "set output '%s/%s.png'\n"
          "set title 'Scene \"%s\": render time against recursion depth "
          "(640x480, 5 spp, one thread)'\n"
          "set xlabel 'recursion depth'\nset ylabel 'seconds'\n"
          "set key top left\nset grid\nset xtics 1\n"
          "plot ",
          dir, scene, scene);
  for (int b = 0; b < nbackends; b++)
    fprintf(f, "%s'%s/%s.dat' using 1:%d with linespoints lw 2 title '%s'",
            b ? ", " : "", dir, scene, b + 2, glint_backend_name(backends[b]));
  fprintf(f, "\n");
  if (fclose(f) != 0)
    return -1;
  char cmd[16384];
  snprintf(cmd, sizeof cmd, "gnuplot '%s/%s.gp'", dir, scene);
  return system(cmd) == 0 ? 0 : -1;
}

int cmd_bench(int argc, char **argv) {
  char default_scenes[] = "whitted,giza,billiard", default_depths[] = "1-15";
  char *scene_list = default_scenes, *depth_list = default_depths;
  char *backend_list = NULL;
  const char *csv_path = NULL, *plot_dir = NULL, *spd_dir = NULL,
             *mesh_dir = NULL, *v;
  int runs = 3, width_given = 0, height_given = 0;
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.width = 640;
  rs.height = 480;
  rs.threads = 1;
  glint_error err;
  arg_cursor c = {argc, argv, 0, NULL};
  while (c.i < argc) {
    const char *a = argv[c.i];
    if (arg_is(&c, "-h", "--help")) {
      bench_usage(stdout);
      return 0;
    } else if (arg_is(&c, NULL, "--scenes")) {
      if (!(scene_list = (char *)arg_value(&c, "--scenes")))
        return EXIT_USAGE;
    } else if (arg_is(&c, NULL, "--depths")) {
      if (!(depth_list = (char *)arg_value(&c, "--depths")))
        return EXIT_USAGE;
    } else if (arg_is(&c, NULL, "--backends")) {
      if (!(backend_list = (char *)arg_value(&c, "--backends")))
        return EXIT_USAGE;
    } else if (arg_is(&c, NULL, "--runs")) {
      if (parse_int("--runs", arg_value(&c, "--runs"), 1, 255, &runs))
        return EXIT_USAGE;
        } else if (arg_is(&c, "-W", "--width")) {
      if (parse_int("--width", arg_value(&c, "--width"), 1,
                    GLINT_MAX_DIMENSION, &rs.width))
        return EXIT_USAGE;
      width_given = 1;
    } else if (arg_is(&c, "-H", "--height")) {
      if (parse_int("--height", arg_value(&c, "--height"), 1,
                    GLINT_MAX_DIMENSION, &rs.height))
        return EXIT_USAGE;
      height_given = 1;
    } else if (arg_is(&c, "-s", "--spp")) {
      if (parse_int("--spp", arg_value(&c, "--spp"), 1, GLINT_MAX_SPP, &rs.spp))
        return EXIT_USAGE;
    } else if (arg_is(&c, "-t", "--threads")) {
      if (parse_int("--threads", arg_value(&c, "--threads"), 0,
                    GLINT_MAX_THREADS, &rs.threads))
        return EXIT_USAGE;
    } else if (arg_is(&c, NULL, "--math")) {
      if (!(v = arg_value(&c, "--math")))
        return EXIT_USAGE;
      if (glint_math_parse(v, &rs.math, &err)) {
        cli_error("--math: %s", err.message);
        return EXIT_USAGE;
      }
    } else if (arg_is(&c, NULL, "--accel")) {
      if (!(v = arg_value(&c, "--accel")))
        return EXIT_USAGE;
      if (glint_accel_parse(v, &rs.accel, &err)) {
        cli_error("--accel: %s", err.message);
        return EXIT_USAGE;
      }
    } else if (arg_is(&c, NULL, "--csv")) {
      if (!(csv_path = arg_value(&c, "--csv")))
        return EXIT_USAGE;
    } else if (arg_is(&c, NULL, "--meshes")) {
      if (!(mesh_dir = arg_value(&c, "--meshes")))
        return EXIT_USAGE;
    } else if (arg_is(&c, NULL, "--spd")) {
      if (!(spd_dir = arg_value(&c, "--spd")))
        return EXIT_USAGE;
    } else if (arg_is(&c, NULL, "--plot")) {
      if (!(plot_dir = arg_value(&c, "--plot")))
        return EXIT_USAGE;
    } else {
      cli_error("unknown option '%s' (see glint bench --help)", a);
      return EXIT_USAGE;
    }
  }

  int depths[MAX_ITEMS];
  int ndepths = parse_depths(depth_list, depths);
  if (ndepths < 0)
    return EXIT_USAGE;
  if (plot_dir && check_plot_dir(plot_dir))
    return EXIT_USAGE;

  glint_backend backends[GLINT_BACKEND_COUNT];
  int nbackends = 0;
  if (backend_list) {
    char *items[MAX_ITEMS];
    int n = split_list(backend_list, items, MAX_ITEMS);
    for (int i = 0; i < n; i++) {
      glint_backend b;
      if (glint_backend_parse(items[i], &b, &err)) {
        cli_error("--backends: %s", err.message);
        return EXIT_USAGE;
      }
      if (!glint_backend_supported(b)) {
        cli_error("backend '%s' is not supported on this CPU", items[i]);
        return EXIT_USAGE;
      }
      if (nbackends < GLINT_BACKEND_COUNT)
        backends[nbackends++] = glint_backend_resolve(b);
    }
    if (nbackends == 0) {
      cli_error("--backends: the list is empty");
      return EXIT_USAGE;
    }
  } else {
    for (int b = 0; b < GLINT_BACKEND_COUNT; b++)
      if (b != GLINT_BACKEND_AUTO && b != GLINT_BACKEND_STREAM &&
          glint_backend_supported((glint_backend)b))
        backends[nbackends++] = (glint_backend)b;
  }

  if (mesh_dir) {
    glint_render_settings mr = rs;
    mr.width = width_given ? rs.width : 0;
    mr.height = height_given ? rs.height : 0;
    return bench_meshes(mesh_dir, &mr, backends, nbackends, runs);
  }
  if (spd_dir) {
    FILE *csv = NULL;
    if (csv_path && !(csv = fopen(csv_path, "w"))) {
      cli_error("%s: cannot write the CSV file", csv_path);
      return EXIT_USAGE;
    }
    if (csv)
      fprintf(csv, "scene,depth,backend,width,height,spp,threads,runs,"
                   "median_s,min_s,max_s,rays,primary,secondary,shadow,"
                   "mrays_per_s,lane_utilisation,sub_beams_per_beam\n");
    int st = bench_spd(spd_dir, &rs, backends, nbackends, runs, csv);
    if (csv && fclose(csv) != 0 && !st) {
      cli_error("%s: writing the CSV file failed", csv_path);
      st = EXIT_USAGE;
    }
    return st;
  }

  char *scene_names[MAX_ITEMS];
  int nscenes = split_list(scene_list, scene_names, MAX_ITEMS);
  if (nscenes <= 0) {
    cli_error("--scenes: give at least one scene");
    return EXIT_USAGE;
  }
  glint_scene *scenes[MAX_ITEMS];
  char stems[MAX_ITEMS][64];
  for (int i = 0; i < nscenes; i++) {
    scenes[i] = cli_load_scene(scene_names[i], stems[i], sizeof stems[i]);
    if (!scenes[i]) {
      for (int k = 0; k < i; k++)
        glint_scene_destroy(scenes[k]);
      return EXIT_USAGE;
    }
  }

  FILE *csv = NULL;
  if (csv_path && !(csv = fopen(csv_path, "w"))) {
    cli_error("%s: cannot write the CSV file", csv_path);
    for (int i = 0; i < nscenes; i++)
      glint_scene_destroy(scenes[i]);
    return EXIT_USAGE;
  }

  size_t ncells = (size_t)nscenes * ndepths * nbackends;
  cell *cells = calloc(ncells, sizeof *cells);
  double *times = calloc(ncells * (size_t)runs, sizeof *times);
  if (!cells || !times) {
    cli_error("out of memory");
    return 1;
  }
  for (size_t i = 0; i < ncells; i++)
    cells[i].seconds = times + i * (size_t)runs;
#define CELL(s, d, b) cells[((size_t)(s)*ndepths + (d)) * nbackends + (b)]

  int tty = isatty(STDERR_FILENO);
  size_t done = 0, total = ncells * (size_t)runs;
  int status = 0;
  for (int r = 0; r < runs && !status; r++)
    for (int s = 0; s < nscenes && !status; s++)
      for (int d = 0; d < ndepths && !status; d++)
        for (int b = 0; b < nbackends && !status; b++) {
          rs.max_depth = depths[d];
          rs.backend = backends[b];
          glint_image *image;
          glint_stats st;
          if (tty) {
            fprintf(stderr, "\r[%zu/%zu] %s depth %d %s\033[K", done + 1, total,
                    stems[s], depths[d], glint_backend_name(backends[b]));
            fflush(stderr);
          }
          if (glint_render(scenes[s], &rs, &image, &st, &err)) {
            cli_error("%s: %s", stems[s], err.message);
            status = EXIT_USAGE;
            break;
          }
          glint_image_destroy(image);
          CELL(s, d, b).seconds[r] = st.render_seconds;
          CELL(s, d, b).stats = st;
          done++;
        }
  if (tty)
    fputs("\r\033[K", stderr);

  if (!status) {
    printf("glint %s bench: %dx%d, %d spp, %d thread%s, math %s, accel %s, "
           "median of %d run%s\n",
           glint_version(), rs.width, rs.height, rs.spp, rs.threads,
           rs.threads == 1 ? "" : "s", glint_math_name(rs.math),
           glint_accel_name(rs.accel), runs, runs == 1 ? "" : "s");
    for (int s = 0; s < nscenes; s++) {
      printf("\nScene \"%s\": seconds\n%5s", stems[s], "depth");
      for (int b = 0; b < nbackends; b++)
        printf(" %14s", glint_backend_name(backends[b]));
      printf("\n");
      for (int d = 0; d < ndepths; d++) {
        printf("%5d", depths[d]);
        for (int b = 0; b < nbackends; b++)
          printf(" %14.4f", bench_median(CELL(s, d, b).seconds, runs));
        printf("\n");
      }
      printf("Scene \"%s\": Mrays/s\n%5s", stems[s], "depth");
      for (int b = 0; b < nbackends; b++)
        printf(" %14s", glint_backend_name(backends[b]));
      printf("\n");
      for (int d = 0; d < ndepths; d++) {
        printf("%5d", depths[d]);
        for (int b = 0; b < nbackends; b++) {
          cell *cl = &CELL(s, d, b);
          double t = bench_median(cl->seconds, runs);
          printf(" %14.2f",
                 t > 0 ? (double)total_rays(&cl->stats) / t / 1e6 : 0.0);
        }
        printf("\n");
      }
      int ref = -1;
      for (int b = 0; b < nbackends; b++)
        if (backends[b] == GLINT_BACKEND_SCALAR_FLOAT)
          ref = b;
      if (ref >= 0 && nbackends > 1) {
        printf("Scene \"%s\": speed-up over scalar-float\n%5s", stems[s],
               "depth");
        for (int b = 0; b < nbackends; b++)
          printf(" %14s", glint_backend_name(backends[b]));
        printf("\n");
        for (int d = 0; d < ndepths; d++) {
          printf("%5d", depths[d]);
          double base = bench_median(CELL(s, d, ref).seconds, runs);
          for (int b = 0; b < nbackends; b++) {
            double t = bench_median(CELL(s, d, b).seconds, runs);
            printf(" %13.2fx", t > 0 ? base / t : 0.0);
          }
          printf("\n");
        }
      }
      int any_packet = 0;
      for (int b = 0; b < nbackends; b++)
        any_packet |= glint_backend_width(backends[b]) > 1;
      if (any_packet) {
        printf("Scene \"%s\": SIMD lane utilisation\n%5s", stems[s], "depth");
        for (int b = 0; b < nbackends; b++)
          if (glint_backend_width(backends[b]) > 1)
            printf(" %14s", glint_backend_name(backends[b]));
        printf("\n");
        for (int d = 0; d < ndepths; d++) {
          printf("%5d", depths[d]);
          for (int b = 0; b < nbackends; b++) {
            int w = glint_backend_width(backends[b]);
            if (w <= 1)
              continue;
            const glint_stats *st = &CELL(s, d, b).stats;
            printf(" %13.1f%%", st->packet_tests
                                    ? 100.0 * (double)st->active_lanes /
                                          ((double)st->packet_tests * w)
                                    : 0.0);
          }
          printf("\n");
        }
      }
    }
    for (int sc = 0; plot_dir && sc < nscenes && !status; sc++) {
      double med[MAX_ITEMS * GLINT_BACKEND_COUNT];
      for (int d = 0; d < ndepths; d++)
        for (int b = 0; b < nbackends; b++)
          med[d * nbackends + b] = bench_median(CELL(sc, d, b).seconds, runs);
      if (plot_scene(plot_dir, stems[sc], depths, ndepths, backends,
                     nbackends, med)) {
        cli_error("--plot: gnuplot could not draw %s/%s.png", plot_dir,
                  stems[sc]);
        status = EXIT_USAGE;
      }
    }
    if (csv) {
      fprintf(csv, "scene,depth,backend,width,height,spp,threads,runs,"
                   "median_s,min_s,max_s,rays,primary,secondary,shadow,"
                   "mrays_per_s,lane_utilisation,sub_beams_per_beam\n");
      for (int s = 0; s < nscenes; s++)
        for (int d = 0; d < ndepths; d++)
          for (int b = 0; b < nbackends; b++) {
            cell *cl = &CELL(s, d, b);
            const glint_stats *st = &cl->stats;
            double med = bench_median(cl->seconds, runs), lo = cl->seconds[0],
                   hi = cl->seconds[0];
            for (int r = 1; r < runs; r++) {
              lo = fmin(lo, cl->seconds[r]);
              hi = fmax(hi, cl->seconds[r]);
            }
            int w = glint_backend_width(backends[b]);
            fprintf(
                csv,
                "%s,%d,%s,%d,%d,%d,%d,%d,%.6f,%.6f,%.6f,%llu,%llu,%llu,"
                "%llu,%.3f,%.4f,%.3f\n",
                stems[s], depths[d], glint_backend_name(backends[b]), st->width,
                st->height, st->spp, st->threads, runs, med, lo, hi,
                (unsigned long long)total_rays(st),
                (unsigned long long)st->primary_rays,
                (unsigned long long)st->secondary_rays,
                (unsigned long long)st->shadow_rays,
                med > 0 ? (double)total_rays(st) / med / 1e6 : 0.0,
                w > 1 && st->packet_tests
                    ? (double)st->active_lanes / ((double)st->packet_tests * w)
                    : 1.0,
                st->beams ? (double)st->sub_beams / (double)st->beams : 0.0);
          }
    }
  }
  if (csv && fclose(csv) != 0 && !status) {
    cli_error("%s: writing the CSV file failed", csv_path);
    status = EXIT_USAGE;
  }
  free(cells);
  free(times);
  for (int i = 0; i < nscenes; i++)
    glint_scene_destroy(scenes[i]);
  return status;
}
