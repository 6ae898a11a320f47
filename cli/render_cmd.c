/* glint render [SCENE] [options] */
#include "args.h"
#include "files.h"
#include "cli.h"

#include <glint.h>

#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <time.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/resource.h>
#include <unistd.h>

static void render_usage(FILE *f) {
  fputs(
      "Usage: glint render [SCENE] [options]\n"
      "\n"
      "Renders SCENE: a built-in scene (whitted, giza, billiard, phong; the\n"
      "default is whitted) or a scene file (.nff or .json, optionally .gz).\n"
      "\n"
      "Options:\n"
      "  -o, --output FILE    image to write: .png, .bmp or .ppm (8-bit),\n"
      "                       or the linear floating-point film as .pfm or\n"
      "                       .exr (default: SCENE.png); - writes the\n"
      "                       image to standard output in --format\n"
      "      --format NAME    with -o -: png (default), ppm or bmp\n"
      "  -W, --width N        image width in pixels (default: 640, or the\n"
      "                       scene file's own); the field of view spans\n"
      "                       the width, so -W alone widens or narrows\n"
      "                       the view and changes the aspect ratio\n"
      "  -H, --height N       image height in pixels (default: 480, or the\n"
      "                       scene file's own)\n"
      "  -d, --depth N        recursion depth, 1..64; 1 = local shading with\n"
      "                       shadows (default: 5)\n"
      "  -s, --spp N          samples per pixel, 1..4096 (default: 5)\n"
      "  -b, --backend NAME   auto, scalar-float, scalar-double, sse, avx2,\n"
      "                       avx512, stream, stream-sse, stream-avx2,\n"
      "                       stream-avx512 (default: auto: the widest\n"
      "                       beams or streams the CPU has, streams where\n"
      "                       many mirrors or a deep recursion scatter\n"
      "                       the rays)\n"
      "  -t, --threads N      worker threads; 0 = every CPU this process\n"
      "                       may use (default: 0)\n"
      "      --math NAME      pow/exp in SIMD backends: minimax, fast,\n"
      "                       taylor, exact (default: minimax)\n"
      "      --no-newton      skip the Newton step after rcp (thesis fig. "
      "5.7)\n"
      "      --accel NAME     bvh, bvh2, bvh8 or none (default: bvh: packets\n"
      "                       hand their last few rays a subtree, which they\n"
      "                       walk alone through the 8-wide BVH; bvh2:\n"
      "                       never; bvh8: every ray alone, but in the\n"
      "                       stream backends; none: no BVH)\n"
      "      --gamma G        encode with gamma G, 0.01..100 (default: 1,\n"
      "                       linear); 8-bit outputs only; PNGs record it\n"
      "                       (gAMA)\n"
      "      --png-compression fast|smallest\n"
      "                       fast (default): several times faster to\n"
      "                       write, files 10-90% larger; smallest: zlib's\n"
      "                       best, about 10x slower\n"
      "      --region X,Y,W,H render only this window of the W x H image;\n"
      "                       the output is the cropped window, W x H\n"
      "      --frames A[-B]   the scene's animation, frames A to B (or A\n"
      "                       alone), an 8-bit image each (.png, .bmp or\n"
      "                       .ppm): -o with a printf-style number\n"
      "                       (frame%04d.png), or a number is put before\n"
      "                       the extension (default: SCENE0001.png);\n"
      "                       missing folders of the path are made\n"
      "      --resume         with --frames: keep frames already written\n"
      "  -q, --quiet          no progress bar and no summary line\n"
      "      --stats          detailed statistics after rendering\n"
      "  -h, --help           this help\n"
      "\n"
      "After rendering, one line gives the wall time, the rays traced and the\n"
      "rate. Errors exit with status 2 and write no file; Ctrl-C stops the\n"
      "render (at the next tile, or abandoning it 2 s later), leaves any\n"
      "existing file untouched and exits with 130 (once the render has\n"
      "ended, the image is finished and written, and glint says so, still\n"
      "with 130). Short\n"
      "options take -W 800, -W800 or -W=800; -- ends the options.\n",
      f);
}

/* The signal that asked glint to stop (SIGINT, SIGTERM, SIGHUP), or 0. A
 * handler can only reach variables of static storage; the render sees it
 * through the progress callback and cancels at the next tile. Render
 * threads read it while the handler writes it: a lock-free atomic, which a
 * handler may use (C11 7.14.1.1), where volatile sig_atomic_t is safe only
 * within one thread. */
_Static_assert(ATOMIC_INT_LOCK_FREE == 2, "a lock-free int for the handler");
static atomic_int stop_signal;

/* A tile can take far longer than anyone waits (a deep recursion through
 * glass doubles its rays at every level): STOP_GRACE seconds after the
 * signal, an alarm ends the process from its handler, removing the image
 * file being written (stop_temp, when stop_temp_set) so that nothing is
 * left behind, unless the render has ended and the file is being finished
 * (stop_finishing), which then completes. Only where the command asked
 * for it (stop_watch: glint render; glint-mpi stops its ranks its own way). */
#define STOP_GRACE 2
#define STOP_GRACE_TEXT "2"
static char stop_temp[4096];
static volatile sig_atomic_t stop_watch, stop_temp_set, stop_finishing;

static void on_stop_signal(int sig) {
  if (!stop_signal && stop_watch)
    alarm(STOP_GRACE);
  stop_signal = sig;
}

static void on_stop_overdue(int sig) {
  if (!stop_signal) { /* not glint's alarm: one sent from outside stops */
    on_stop_signal(sig);
    return;
  }
  if (stop_finishing)
    return;
  static const char msg[] = "glint: interrupted; the render did not stop "
                            "within " STOP_GRACE_TEXT " s and was abandoned";
  static const char file_gone[] = ", leaving no partial file\n";
  int wrote = stop_temp_set; /* glint render's file; glint view has none */
  if (stop_temp_set)
    unlink(stop_temp);
  if (write(STDERR_FILENO, msg, sizeof msg - 1) < 0 ||
      write(STDERR_FILENO, wrote ? file_gone : "\n",
            wrote ? sizeof file_gone - 1 : 1) < 0) {
    /* nothing else to try */
  }
  _exit(EXIT_INTERRUPTED);
}

int cli_stopped(void) { return stop_signal != 0; }

static void on_stop_before_catching(int sig) {
  static const char sigint[] = "glint: interrupted (SIGINT)\n",
                    sigterm[] = "glint: interrupted (SIGTERM)\n",
                    sighup[] = "glint: interrupted (SIGHUP)\n";
  const char *msg = sig == SIGINT ? sigint : sig == SIGTERM ? sigterm : sighup;
  if (write(STDERR_FILENO, msg, strlen(msg)) < 0) {
    /* nothing else to try */
  }
  _exit(EXIT_INTERRUPTED);
}

/* Handles the stop signals with `handler`, but leaves one the process was
 * started with ignored (nohup's SIGHUP, the SIGINT of a script's
 * background job) ignored, as a shell does. */
static void handle_stop_signals(void (*handler)(int)) {
  static const int stops[] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  for (size_t i = 0; i < sizeof stops / sizeof *stops; i++) {
    struct sigaction was;
    if (sigaction(stops[i], NULL, &was) == 0 && was.sa_handler == SIG_IGN)
      continue;
    sigaction(stops[i], &sa, NULL);
  }
}

void cli_end_on_stop_signals(void) {
  handle_stop_signals(on_stop_before_catching);
}

void cli_catch_stop_signals(void) {
  handle_stop_signals(on_stop_signal);
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sigemptyset(&sa.sa_mask);
  sa.sa_handler = on_stop_overdue;
  sa.sa_flags = SA_RESTART; /* an image being finished must not see EINTR */
  sigaction(SIGALRM, &sa, NULL);
}

void cli_remove_on_stop(const glint_image_writer *writer) {
  stop_temp_set = 0;
  const char *temp = glint_image_writer_temp_path(writer);
  if (temp && strlen(temp) < sizeof stop_temp) {
    memcpy(stop_temp, temp, strlen(temp) + 1);
    stop_temp_set = 1;
  }
  /* A signal that came before (while the file was being opened) started
   * no grace: start it now, or a render that does not stop never would. */
  int watching = stop_watch;
  stop_watch = 1;
  if (!watching && stop_signal)
    alarm(STOP_GRACE);
}

void cli_stop_finishing(int finishing) {
  stop_finishing = finishing;
  if (!finishing && stop_signal && stop_watch)
    alarm(STOP_GRACE); /* the grace passed while finishing: a new one */
}

typedef struct progress_state {
  int last_percent;
  int show; /* draw a bar (stderr is a terminal and not --quiet) */
} progress_state;

static int on_progress(void *user, double fraction) {
  progress_state *p = user;
  if (stop_signal)
    return 1; /* cancel */
  int percent = (int)(fraction * 100);
  if (p->show && percent != p->last_percent) {
    p->last_percent = percent;
    int filled = percent * 40 / 100;
    fprintf(stderr, "\r[%.*s%*s] %3d%%", filled,
            "########################################", 40 - filled, "",
            percent);
    fflush(stderr);
  }
  return 0;
}

double cli_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double cli_peak_rss_mib(void) {
  struct rusage ru;
  if (getrusage(RUSAGE_SELF, &ru) != 0)
    return 0;
  return (double)ru.ru_maxrss / 1024.0; /* Linux reports KiB */
}

glint_scene *cli_load_scene(const char *arg, char *stem,
                            unsigned long stem_size, int *exit_code) {
  glint_scene *scene = cli_load_animation(arg, stem, stem_size, exit_code);
  glint_animation animation;
  if (!scene || !glint_scene_get_animation(scene, &animation))
    return scene;
  /* An animated scene, still: its first frame. */
  glint_scene *still;
  glint_error err;
  glint_status st = glint_scene_at_time(scene, 0, &still, &err);
  glint_scene_destroy(scene);
  if (st) {
    cli_error("%s: %s", arg, err.message);
    *exit_code = cli_exit_code(st);
    return NULL;
  }
  return still;
}

void cli_note_scale(const char *arg, const glint_scene *scene) {
  double epsilon, smallest;
  glint_scene_get_scale(scene, &epsilon, &smallest);
  if (epsilon >= 0.5 * smallest)
    fprintf(stderr,
            "glint: note: %s: hits nearer than %g to a ray's start are not "
            "seen (1e-4 of the scene's largest coordinate, %g), and its "
            "smallest object measures %g: it and others near that size may "
            "be missing or wrong (keep a scene's extent within about 1e4 "
            "times its smallest object)\n",
            arg, epsilon, epsilon * 1e4, smallest);
}

int cli_scene_is_file(const char *arg) {
  if (strchr(arg, '.') || strchr(arg, '/'))
    return 1;
  for (size_t i = 0; i < glint_builtin_scene_count(); i++)
    if (strcmp(arg, glint_builtin_scene_name(i)) == 0)
      return 0;
  return access(arg, F_OK) == 0;
}

glint_scene *cli_load_animation(const char *arg, char *stem,
                                unsigned long stem_size, int *exit_code) {
  glint_error err;
  glint_scene *scene = NULL;
  if (strcmp(arg, "-") == 0 && access(arg, F_OK) != 0) {
    /* a file's name decides its format, and a JSON scene's meshes lie
     * beside it: a scene is a file or a built-in, never standard input */
    cli_error("-: a scene is a file (.nff or .json, optionally .gz) or a "
              "built-in scene's name, not standard input");
    *exit_code = EXIT_USAGE;
    return NULL;
  }
  int is_file = cli_scene_is_file(arg);
  glint_status st = is_file ? glint_scene_load(arg, &scene, &err)
                            : glint_scene_builtin(arg, &scene, &err);
  if (st) {
    cli_error("%s", err.message);
    *exit_code = cli_exit_code(st);
    return NULL;
  }
  cli_note_scale(arg, scene);
  cli_scene_stem(arg, stem, stem_size);
  return scene;
}

void cli_scene_stem(const char *arg, char *stem, size_t size) {
  const char *base = strrchr(arg, '/');
  base = base ? base + 1 : arg;
  snprintf(stem, size, "%s", base);
  for (int cut = 0; cut < 2; cut++) {
    char *dot = strrchr(stem, '.');
    int gz = dot && strcmp(dot, ".gz") == 0;
    if (dot && dot != stem)
      *dot = '\0';
    if (!gz)
      break;
  }
}

static double mega(uint64_t n) { return (double)n / 1e6; }

/* --stats: the library's figures, and the whole command's stages as the CLI
 * timed them (loading the scene, writing the file, start to end). */
typedef struct command_times {
  double load, write, total;
} command_times;

static void print_stats(FILE *out, const glint_stats *s,
                        const command_times *t) {
  uint64_t rays = s->primary_rays + s->secondary_rays + s->shadow_rays;
  fprintf(out, "  backend            %s, %d thread%s\n",
          glint_backend_name(s->backend), s->threads,
          s->threads == 1 ? "" : "s");
  fprintf(out, "  image              %dx%d, %d spp, depth %d\n", s->width,
          s->height, s->spp, s->max_depth);
  fprintf(out, "  prepare            %.3f s (scene %.2f MiB)\n",
          s->prepare_seconds, (double)s->scene_bytes / 1048576.0);
  if (s->bvh_nodes)
    fprintf(out,
            "  bvh                %llu nodes, %.2f MiB, built in %.1f ms\n",
            (unsigned long long)s->bvh_nodes, (double)s->bvh_bytes / 1048576.0,
            s->bvh_build_seconds * 1e3);
  if (s->wide_nodes)
    fprintf(out,
            "  wide bvh           %llu nodes of 8, %.2f MiB, collapsed in "
            "%.1f ms\n",
            (unsigned long long)s->wide_nodes,
            (double)s->wide_bytes / 1048576.0, s->wide_build_seconds * 1e3);
  else if (s->bvh_nodes)
    fprintf(out, "  wide bvh           none: no walk of this render takes it "
                 "(a beam or scalar backend's with --accel bvh8 would)\n");
  fprintf(out, "  render             %.4f s\n", s->render_seconds);
  fprintf(out, "  load scene         %.4f s\n", t->load);
  /* An 8-bit image file is encoded while the frame renders: this is what
   * writing it costs after the last tile. */
  fprintf(out, "  write image        %.4f s after rendering\n", t->write);
  fprintf(out, "  load to written    %.4f s\n", t->total);
  fprintf(out, "  rays               %llu (%.2f Mrays/s)\n",
          (unsigned long long)rays,
          s->render_seconds > 0 ? mega(rays) / s->render_seconds : 0.0);
  fprintf(out, "    primary          %llu\n",
          (unsigned long long)s->primary_rays);
  fprintf(out, "    reflected        %llu\n",
          (unsigned long long)s->reflected_rays);
  fprintf(out, "    refracted        %llu\n",
          (unsigned long long)s->refracted_rays);
  fprintf(out, "    shadow           %llu\n",
          (unsigned long long)s->shadow_rays);
  fprintf(out, "  total internal reflections %llu\n",
          (unsigned long long)s->total_internal_reflections);
  int width = glint_backend_width(s->backend);
  if (s->beams) {
    fprintf(out, "  beams              %llu, %.2f sub-beams per beam\n",
            (unsigned long long)s->beams,
            (double)s->sub_beams / (double)s->beams);
  }
  if (s->packet_tests && width > 1)
    fprintf(out,
            "  lane utilisation   %.1f%% of %d lanes (%.2f active per packet "
            "test)\n",
            100.0 * (double)s->active_lanes / ((double)s->packet_tests * width),
            width, (double)s->active_lanes / (double)s->packet_tests);
  if (s->alone_walks)
    fprintf(out,
            "  rays alone         %llu subtrees walked by single rays, %.1f "
            "tests each\n",
            (unsigned long long)s->alone_walks,
            (double)s->alone_tests / (double)s->alone_walks);
  if (s->generations) {
    fprintf(out, "  generations        rays        packets   lane use\n");
    for (int g = 0; g < s->generations && g < GLINT_STATS_MAX_GENERATIONS; g++)
      fprintf(out, "    %2d %19llu %14llu %9.1f%%\n", g,
              (unsigned long long)s->gen_rays[g],
              (unsigned long long)s->gen_packets[g],
              s->gen_packets[g] ? 100.0 * (double)s->gen_active_lanes[g] /
                                      ((double)s->gen_packets[g] * width)
                                : 0.0);
    fprintf(out,
            "  stages             generation %.3f s, traversal %.3f s, "
            "shading %.3f s, compaction %.3f s (summed over threads)\n",
            s->stage_seconds[0], s->stage_seconds[1], s->stage_seconds[2],
            s->stage_seconds[3]);
    fprintf(out, "  stream memory      %.2f MiB per thread\n",
            (double)s->stream_bytes_per_thread / 1048576.0);
  }
  fprintf(out, "  peak memory (RSS)  %.1f MiB\n", cli_peak_rss_mib());
}

int cli_is_film_path(const char *path) {
  const char *slash = strrchr(path, '/');
  const char *dot = strrchr(slash ? slash : path, '.');
  return dot && (strcasecmp(dot, ".pfm") == 0 || strcasecmp(dot, ".exr") == 0);
}

glint_status cli_check_output_format(const char *path, const char *scene,
                                     glint_error *err) {
  if (cli_is_film_path(path) ||
      glint_image_format_from_path(path) != GLINT_FORMAT_UNKNOWN) {
    /* Images are written through links: one to the scene, or to a mesh
     * it names, would replace it. */
    char target[PATH_MAX];
    if (scene && same_file(scene, path))
      snprintf(err->message, sizeof err->message,
               "%s: that is the scene file %s", path, scene);
    else if (links_to_input(path, target))
      snprintf(err->message, sizeof err->message,
               "%.400s: a link to %.400s, a scene or mesh file (.nff, "
               ".json, .obj, .ply): the image would replace it",
               path, target);
    else
      return GLINT_OK;
    err->status = GLINT_E_ARGUMENT;
    return GLINT_E_ARGUMENT;
  }
  err->status = GLINT_E_ARGUMENT;
  if (!*path)
    snprintf(err->message, sizeof err->message,
             "the output file name is empty");
  else
    snprintf(err->message, sizeof err->message,
             "%s: unknown output format (use .png, .bmp or .ppm, or .pfm or "
             ".exr for the linear film)",
             path);
  return GLINT_E_ARGUMENT;
}

/* The size of the image or film a render produces: the region's, else the
 * settings', else the scene's. */
static void output_size(const glint_scene *scene,
                        const glint_render_settings *rs, int *w, int *h) {
  glint_scene_info info;
  glint_scene_get_info(scene, &info);
  *w = rs->width ? rs->width : info.width;
  *h = rs->height ? rs->height : info.height;
  if (rs->region_width)
    *w = rs->region_width, *h = rs->region_height;
}

int cli_tile_to_writer(void *user, const glint_tile *tile) {
  cli_tile_sink *sink = user;
  glint_tile t = *tile;
  t.x -= sink->origin_x;
  t.y -= sink->origin_y;
  if (glint_image_writer_put(sink->writer, &t, &sink->error)) {
    sink->failed = 1;
    return 1;
  }
  return 0;
}

/* The frame through a committed world and a renderer: into a film, or
 * with a `sink` tile by tile into its image writer (no film). */
static glint_status render_film(const glint_scene *scene,
                                const glint_render_settings *rs,
                                cli_tile_sink *sink, glint_film **out,
                                glint_stats *stats, glint_error *err) {
  glint_world *world;
  glint_renderer *renderer;
  glint_stats commit;
  glint_status st = glint_world_commit(scene, &world, &commit, err);
  if (st)
    return st;
  st = glint_renderer_create(world, rs, &renderer, err);
  glint_world_destroy(world); /* the renderer holds it */
  if (st)
    return st;
  int w, h;
  output_size(scene, rs, &w, &h);
  glint_frame_settings frame;
  glint_frame_settings_default(&frame);
  if (sink) {
    frame.tile = cli_tile_to_writer;
    frame.tile_user = sink;
  }
  glint_film *film = NULL;
  if (!sink)
    st = glint_film_create(w, h, &film, err);
  if (st == GLINT_OK)
    st = glint_renderer_render(renderer, &frame, film, stats, err);
  glint_renderer_destroy(renderer);
  if (st == GLINT_E_CANCELLED && sink && sink->failed)
    *err = sink->error, st = err->status;
  if (st) {
    glint_film_destroy(film);
    return st;
  }
  stats->prepare_seconds = commit.prepare_seconds;
  *out = film;
  return GLINT_OK;
}

int render_parse(int argc, char **argv, render_options *o) {
  const char *v;
  memset(o, 0, sizeof *o);
  o->png_compression = GLINT_PNG_FAST;
  o->stream_format = GLINT_FORMAT_UNKNOWN; /* --format */
  glint_render_settings_default(&o->settings);
  glint_render_settings *rs = &o->settings;
  arg_cursor c = {argc, argv, 0, NULL};
  while (c.i < argc) {
    if (arg_is_help(&c)) {
      render_usage(stdout);
      return 0;
    }
    int r;
    if ((r = arg_render_setting(&c, rs)) || (r = arg_backend(&c, rs)) ||
        (r = arg_text(&c, "-o", "--output", &o->output)) ||
        (r = arg_int(&c, "-d", "--depth", 1, GLINT_MAX_DEPTH,
                     &rs->max_depth)) ||
        (r = arg_int(&c, "-t", "--threads", 0, GLINT_MAX_THREADS,
                     &rs->threads)) ||
        (r = arg_flag(&c, "-q", "--quiet", &o->quiet)) ||
        (r = arg_flag(&c, NULL, "--resume", &o->resume)) ||
        (r = arg_flag(&c, NULL, "--stats", &o->stats))) {
      if (r == ARG_BAD)
        return EXIT_USAGE;
      continue;
    }
    if (arg_is(&c, NULL, "--frames")) {
      if (!(v = arg_value(&c, "--frames")))
        return EXIT_USAGE;
      /* FIRST or FIRST-LAST, whole numbers 0..GLINT_MAX_FRAME (as in a
       * scene's "frames"), nothing else. */
      char *end;
      long first = -1, last = -1;
      if (v[0] >= '0' && v[0] <= '9') {
        first = last = strtol(v, &end, 10);
        if (*end == '-' && end[1] >= '0' && end[1] <= '9')
          last = strtol(end + 1, &end, 10);
        if (*end)
          first = -1;
      }
      if (first >= 0 && last < first) {
        cli_error("--frames: '%s' runs backwards (FIRST-LAST with LAST at "
                  "least FIRST)",
                  v);
        return EXIT_USAGE;
      }
      if (first < 0 || last > GLINT_MAX_FRAME) {
        cli_error("--frames: '%s' is not a frame or a range FIRST-LAST of "
                  "frames 0..%d",
                  v, GLINT_MAX_FRAME);
        return EXIT_USAGE;
      }
      o->first_frame = (int)first;
      o->last_frame = (int)last;
      o->frames = 1;
    } else if (arg_is(&c, NULL, "--region")) {
      if (!(v = arg_value(&c, "--region")))
        return EXIT_USAGE;
      int r[4];
      if (parse_region("--region", v, r))
        return EXIT_USAGE;
      rs->region_x = r[0], rs->region_y = r[1];
      rs->region_width = r[2], rs->region_height = r[3];
    } else if (arg_is(&c, NULL, "--png-compression")) {
      if (!(v = arg_value(&c, "--png-compression")))
        return EXIT_USAGE;
      o->png_compression_given = 1;
      if (strcmp(v, "fast") == 0)
        o->png_compression = GLINT_PNG_FAST;
      else if (strcmp(v, "smallest") == 0)
        o->png_compression = GLINT_PNG_SMALLEST;
      else {
        cli_error("--png-compression: '%s' is not fast or smallest", v);
        return EXIT_USAGE;
      }
    } else if (arg_is(&c, NULL, "--format")) {
      if (!(v = arg_value(&c, "--format")))
        return EXIT_USAGE;
      char name[8];
      snprintf(name, sizeof name, "x.%s", v);
      o->stream_format = strlen(v) < 4 ? glint_image_format_from_path(name)
                                       : GLINT_FORMAT_UNKNOWN;
      if (o->stream_format == GLINT_FORMAT_UNKNOWN) {
        cli_error("--format: '%s' is not png, bmp or ppm", v);
        return EXIT_USAGE;
      }
    } else if (arg_is(&c, NULL, "--gamma")) {
      if (parse_gamma("--gamma", arg_value(&c, "--gamma"), &rs->gamma))
        return EXIT_USAGE;
    } else if (arg_scene_operand(&c, "render", &o->scene) == ARG_BAD) {
      return EXIT_USAGE;
    }
  }
  if (!o->scene)
    o->scene = "whitted";
  /* -o -: the image onto standard output, in --format (PNG by default);
   * the summary then goes to stderr. */
  o->to_stdout = o->output && strcmp(o->output, "-") == 0;
  if (o->stream_format != GLINT_FORMAT_UNKNOWN && !o->to_stdout) {
    cli_error("--format applies to -o - (standard output); a file's format "
              "is its extension");
    return EXIT_USAGE;
  }
  if (o->to_stdout && o->stream_format == GLINT_FORMAT_UNKNOWN)
    o->stream_format = GLINT_FORMAT_PNG;
  if (o->frames && o->to_stdout) {
    cli_error("--frames writes a file a frame; -o - is one stream");
    return EXIT_USAGE;
  }
  if (o->frames && o->stats) {
    cli_error("--stats applies to one image; --frames prints a line a frame "
              "and a summary");
    return EXIT_USAGE;
  }
  if (o->resume && !o->frames) {
    cli_error("--resume applies to --frames");
    return EXIT_USAGE;
  }
  if (o->png_compression_given &&
      (o->to_stdout ? o->stream_format != GLINT_FORMAT_PNG
                    : o->output && glint_image_format_from_path(o->output) !=
                                       GLINT_FORMAT_PNG)) {
    cli_error("--png-compression applies to PNG images, and %s is not one",
              o->to_stdout ? "the stream" : o->output);
    return EXIT_USAGE;
  }
  return -1;
}

int cmd_render(int argc, char **argv) {
  render_options o;
  int status = render_parse(argc, argv, &o);
  if (status >= 0)
    return status;
  glint_render_settings rs = o.settings;
  const char *scene_arg = o.scene;
  char *output = o.output;
  int quiet = o.quiet, want_stats = o.stats, to_stdout = o.to_stdout;
  glint_png_compression png_compression = o.png_compression;
  glint_image_format stream_format = o.stream_format;
  glint_error err;
  if (to_stdout && cli_stdout_closed()) {
    cli_error("-o -: standard output is closed; redirect it to a file or a "
              "program");
    return EXIT_USAGE;
  }
  if (to_stdout && isatty(STDOUT_FILENO)) {
    cli_error("-o -: standard output is a terminal; redirect it to a file or "
              "a program");
    return EXIT_USAGE;
  }
  FILE *info = to_stdout ? stderr : stdout;
  if (rs.threads > glint_cpu_count())
    fprintf(stderr,
            "glint: note: %d threads on the %d CPUs this process may use; "
            "they will take turns\n",
            rs.threads, glint_cpu_count());

  char stem[CLI_STEM_SIZE], default_output[300];
  command_times times;
  double t0 = cli_now();
  int load_status = EXIT_USAGE;
  glint_scene *scene =
      o.frames ? cli_load_animation(scene_arg, stem, sizeof stem, &load_status)
               : cli_load_scene(scene_arg, stem, sizeof stem, &load_status);
  times.load = cli_now() - t0;
  if (!scene)
    return load_status;
  if (o.frames)
    return render_frames(scene, &o, stem);
  if (!output) {
    snprintf(default_output, sizeof default_output, "%s.png", stem);
    output = default_output;
  }
  /* Refuse a bad output path before a long render, not after. */
  int film_output = !to_stdout && cli_is_film_path(output);
  if (!to_stdout && cli_check_output_format(output, scene_arg, &err)) {
    cli_error("%s", err.message);
    glint_scene_destroy(scene);
    return EXIT_USAGE;
  }
  if (film_output && rs.gamma != 1) {
    cli_error("%s: --gamma applies to 8-bit images; .pfm and .exr are "
              "linear",
              output);
    glint_scene_destroy(scene);
    return EXIT_USAGE;
  }
  /* From here on a stop signal cancels the render and says so: once the
   * image's temporary file exists, glint must remove it. */
  cli_catch_stop_signals();
  /* An image file is encoded while the frame renders (glint_image_writer);
   * opening it checks the path. */
  cli_tile_sink sink = {NULL, rs.region_x, rs.region_y, 0, {0}};
  int out_w, out_h;
  output_size(scene, &rs, &out_w, &out_h);
  glint_status opened =
      to_stdout ? GLINT_OK
      : film_output
          ? glint_film_check_writable(output, &err)
          : glint_image_writer_open(output, out_w, out_h, rs.gamma,
                                    png_compression, &sink.writer, &err);
  if (opened) {
    cli_error("%s", err.message);
    glint_scene_destroy(scene);
    return cli_exit_code(opened);
  }

  cli_remove_on_stop(sink.writer);
  progress_state ps = {-1, !quiet && isatty(STDERR_FILENO)};
  rs.progress = on_progress;
  rs.progress_user = &ps;
  glint_image *image = NULL;
  glint_film *film = NULL;
  glint_stats stats;
  glint_status st = to_stdout
                        ? glint_render(scene, &rs, &image, &stats, &err)
                        : render_film(scene, &rs, sink.writer ? &sink : NULL,
                                      &film, &stats, &err);
  cli_stop_finishing(1);
  if (ps.show)
    fputs("\r\033[K", stderr);
  glint_scene_destroy(scene);
  if (st || stop_signal)
    glint_image_writer_discard(sink.writer);
  if (stop_signal) {
    glint_image_destroy(image);
    glint_film_destroy(film);
    cli_error("interrupted; %s was not written",
              to_stdout ? "the image" : output);
    return EXIT_INTERRUPTED;
  }
  if (st) {
    cli_error("%s", err.message);
    return cli_exit_code(st);
  }

  /* A stop signal from here on lets the file be written whole (the handler
   * only takes note), then says so. */
  double write_start = cli_now();
  st = film_output ? glint_film_write(film, output, &err)
       : to_stdout ? glint_image_write_stream(image, stdout, stream_format,
                                              png_compression, &err)
                   : glint_image_writer_finish(sink.writer, &err);
  times.write = cli_now() - write_start;
  glint_image_destroy(image);
  glint_film_destroy(film);
  if (st) {
    /* The stream's message has no file name to give: the output's named. */
    cli_error("%s%s", to_stdout ? "standard output (-o -): " : "", err.message);
    if (to_stdout) /* said: not again at exit (cli_write_errors_not_signals) */
      clearerr(stdout);
    return cli_exit_code(st);
  }
  if (stop_signal) {
    cli_error("interrupted after %s was written",
              to_stdout ? "the image" : output);
    return EXIT_INTERRUPTED;
  }

  if (!quiet) {
    uint64_t rays =
        stats.primary_rays + stats.secondary_rays + stats.shadow_rays;
    fprintf(info,
            "%s: %dx%d, %s, %.3f s, %.2f M rays (%.2f M primary, %.2f M "
            "secondary, %.2f M shadow), %.2f Mrays/s\n",
            to_stdout ? "(standard output)" : output, out_w, out_h,
            glint_backend_name(stats.backend), stats.render_seconds, mega(rays),
            mega(stats.primary_rays), mega(stats.secondary_rays),
            mega(stats.shadow_rays),
            stats.render_seconds > 0 ? mega(rays) / stats.render_seconds : 0.0);
  }
  if (want_stats) {
    times.total = cli_now() - t0;
    print_stats(info, &stats, &times);
  }
  return 0;
}
