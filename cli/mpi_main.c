/* glint-mpi: glint render on the ranks of an Open MPI job (docs/mpi.md).
 *
 *   mpirun -np N glint-mpi [SCENE] [glint render options]
 *          [--schedule dynamic|static] [--tile N] [--timeout S]
 *
 * One image is cut into tiles, an animation (--frames) into frames; rank 0
 * reads the scene and every file it refers to, once, and broadcasts the
 * bytes (glint_scene_pack), and every rank checks that it renders as the
 * others do (version, backend, maths, and the options that share the work
 * out: fingerprint) before any work starts. The image is
 * bit-identical to glint render's, whatever the ranks, tiles or schedule. */
#include "args.h"
#include "mpi.h"

#include <glint.h>

#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <unistd.h>

static void usage(FILE *f) {
  fputs(
      "Usage: mpirun -np N glint-mpi [SCENE] [options]\n"
      "\n"
      "Renders SCENE as glint render does, on the N ranks of an MPI job: one\n"
      "image in tiles, or with --frames the frames of its animation. Rank 0\n"
      "reads the scene and its meshes and writes every file; all ranks\n"
      "render, rank 0 too. The output is bit-identical to glint render's.\n"
      "\n"
      "Options: those of glint render (glint render --help; -o - and\n"
      "--stats excepted: each rank's part is printed instead), and\n"
      "      --schedule NAME  dynamic (default): units (tiles or frames)\n"
      "                       handed out as ranks finish; static: unit i to\n"
      "                       rank i mod N, the baseline\n"
      "      --tile N         tile side in pixels, a multiple of 16 up to\n"
      "                       4096 (default: 64 for ranks of one thread,\n"
      "                       larger for more, down to 64 for small images);\n"
      "                       one image only (refused with --frames)\n"
      "      --timeout S      a rank that owes work and sends nothing for S\n"
      "                       seconds is taken for hung (default: 120); more\n"
      "                       than one tile or frame takes; and ranks that\n"
      "                       cannot all reach each other within S seconds\n"
      "                       (at least 10) of starting stop the job\n"
      "  -t, --threads N      per rank; 0 (default) shares the CPUs this\n"
      "                       rank may use among the ranks on its host\n"
      "\n"
      "Exit status: 0 on success, 1 out of memory, 2 on bad arguments or\n"
      "input, a failed or silent rank, 130 when stopped (mpirun may report\n"
      "its own: see glint-mpi(1)). A failed job leaves no partial image;\n"
      "frames already written stay, and --resume renders the rest.\n",
      f);
}

void mpi_fail(const mpi_world *w, int status, const char *format, ...) {
  if (w->rank == 0 && w->settle) {
    atomic_store((atomic_int *)&w->ending, 1);
    w->settle(w->settle_context);
  }
  if (w->rank == 0 && w->abandon)
    w->abandon(w->abandon_context);
  char message[1024];
  va_list ap;
  va_start(ap, format);
  vsnprintf(message, sizeof message, format, ap);
  va_end(ap);
  fprintf(stderr, "glint-mpi: %s\n", message);
  fflush(stderr);
  MPI_Abort(w->comm, status);
  exit(status); /* MPI_Abort does not return; this says so to the compiler */
}

void mpi_check(const mpi_world *w, int result, const char *what) {
  if (result == MPI_SUCCESS)
    return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  if (MPI_Error_string(result, text, &length) != MPI_SUCCESS)
    snprintf(text, sizeof text, "MPI error %d", result);
  mpi_fail(w, EXIT_USAGE, "rank %d (%s): %s: %s", w->rank,
           w->hosts ? w->hosts[w->rank] : "?", what, text);
}

/* Every rank's MPI_MESSAGE_CHARS of text, in rank order, on rank 0 (to
 * free); NULL elsewhere. */
static char *gather_texts(const mpi_world *w, const char *mine,
                          const char *what) {
  char *all = NULL;
  if (w->rank == 0 && !(all = calloc((size_t)w->size, MPI_MESSAGE_CHARS)))
    mpi_fail(w, 1, "out of memory");
  mpi_check(w,
            MPI_Gather(mine, MPI_MESSAGE_CHARS, MPI_CHAR, all,
                       MPI_MESSAGE_CHARS, MPI_CHAR, 0, w->comm),
            what);
  return all;
}

int mpi_agree(const mpi_world *w, glint_status st, const char *message) {
  /* a rank's text: its status in the first byte (0: ok), its message */
  char mine[MPI_MESSAGE_CHARS] = {0};
  if (st) {
    mine[0] = (char)st;
    snprintf(mine + 1, sizeof mine - 1, "%s", message ? message : "failed");
  }
  char *all = gather_texts(w, mine, "gathering the ranks' state");
  int first_failed[2] = {-1, 0}; /* the rank, its exit status */
  if (w->rank == 0)
    for (int r = 0; r < w->size && first_failed[0] < 0; r++)
      if (all[(size_t)r * sizeof mine]) {
        first_failed[0] = r;
        first_failed[1] = cli_exit_code((glint_status)all[r * sizeof mine]);
      }
  if (first_failed[0] >= 0) {
    int r = first_failed[0];
    const char *said = all + (size_t)r * sizeof mine + 1;
    if (r == 0)
      fprintf(stderr, "glint-mpi: %s\n", said);
    else
      fprintf(stderr, "glint-mpi: rank %d (%s): %s\n", r, w->hosts[r], said);
  }
  free(all);
  mpi_check(w, MPI_Bcast(first_failed, 2, MPI_INT, 0, w->comm),
            "sharing the ranks' state");
  return first_failed[1];
}

int mpi_copy_tile(void *user, const glint_tile *tile) {
  const mpi_unit_buffer *b = user;
  for (int row = 0; row < tile->height; row++)
    memcpy(b->pixels + 3 * ((size_t)(tile->y - b->y + row) * (size_t)b->width +
                            (size_t)(tile->x - b->x)),
           tile->pixels + (size_t)row * tile->stride,
           3 * sizeof(float) * (size_t)tile->width);
  return 0;
}

int mpi_on_progress(void *user, double fraction) {
  const mpi_world *w = user;
  (void)fraction;
  return cli_stopped() || (w && atomic_load((atomic_int *)&w->ending));
}

double mpi_test_slowdown(int rank) {
  const char *v = getenv("GLINT_MPI_TEST_SLOW");
  while (v && *v) {
    int r, used = 0;
    double factor;
    if (sscanf(v, "%d:%lf%n", &r, &factor, &used) != 2)
      break;
    if (r == rank && factor > 1)
      return factor;
    v += used;
    v += *v == ',';
  }
  return 1;
}

/* Takes glint-mpi's own options out of argv, and leaves glint render's. */
static int parse(int argc, char **argv, mpi_options *o) {
  glint_error err;
  if (glint_isa_cap_check(&err)) { /* as glint render does */
    cli_error("%s", err.message);
    return EXIT_USAGE;
  }
  o->dynamic = 1;
  o->timeout = 120;
  char **rest = malloc((size_t)(argc + 1) * sizeof *rest);
  if (!rest) {
    cli_error("out of memory");
    return EXIT_USAGE;
  }
  int n = 0;
  arg_cursor c = {argc, argv, 0, NULL};
  while (c.i < argc) {
    int r;
    if (arg_is_help(&c)) {
      usage(stdout);
      free(rest);
      return 0;
    }
    if (arg_is(&c, NULL, "--schedule")) {
      const char *v = arg_value(&c, "--schedule");
      if (!v || (strcmp(v, "dynamic") && strcmp(v, "static"))) {
        if (v)
          cli_error("--schedule: '%s' is not dynamic or static", v);
        free(rest);
        return EXIT_USAGE;
      }
      o->dynamic = strcmp(v, "dynamic") == 0;
    } else if ((r = arg_int(&c, NULL, "--tile", GLINT_TILE_SIZE, 4096,
                            &o->tile_size))) {
      if (r == ARG_BAD) {
        free(rest);
        return EXIT_USAGE;
      }
      if (o->tile_size % GLINT_TILE_SIZE) {
        /* glint_render's tiles inside ours: every backend's image is then
         * glint render's (glint.h, GLINT_TILE_SIZE) */
        cli_error("--tile: %d is not a multiple of %d, the renderer's own "
                  "tile",
                  o->tile_size, GLINT_TILE_SIZE);
        free(rest);
        return EXIT_USAGE;
      }
    } else if (arg_is(&c, NULL, "--timeout")) {
      if (parse_double("--timeout", arg_value(&c, "--timeout"), 0.001,
                       &o->timeout)) {
        free(rest);
        return EXIT_USAGE;
      }
    } else {
      rest[n++] = argv[c.i++];
    }
  }
  rest[n] = NULL;
  int status = render_parse(n, rest, &o->render);
  /* render_parse keeps pointers into argv, not into `rest`. */
  free(rest);
  if (status >= 0)
    return status;
  if (o->render.to_stdout) {
    cli_error("-o -: glint-mpi writes files (rank 0 writes them)");
    return EXIT_USAGE;
  }
  if (o->render.stats) {
    cli_error("--stats: glint-mpi prints what each rank rendered instead");
    return EXIT_USAGE;
  }
  if (o->tile_size && o->render.frames) {
    cli_error("--tile: with --frames each rank renders whole frames");
    return EXIT_USAGE;
  }
  o->in_flight = o->render.frames ? 2 : 4;
  return -1;
}

/* Each rank's name for what it renders and how the work is shared; ranks
 * that differ would render different images, or wait for work that never
 * comes (an MPMD launch, `mpirun A : B`, gives each rank its own
 * arguments). What a rank may choose for itself is left out: its threads;
 * and what only rank 0 reads: the output, --resume, --png-compression,
 * --timeout and -q. A scene file is rank 0's, sent to all, so only whether
 * the scene is a file counts. */
static void fingerprint(const mpi_options *o, char *out, size_t size) {
  const render_options *ro = &o->render;
  const glint_render_settings *rs = &ro->settings;
  const char *scene = ro->scene;
  /* a path is rank 0's file, sent to all; a bare name a built-in scene or,
   * where rank 0 finds no such scene, rank 0's file of that name */
  int is_path = strchr(scene, '.') != NULL || strchr(scene, '/') != NULL;
  char size_text[64] = "the scene's size", region[96] = "whole";
  if (rs->width || rs->height)
    snprintf(size_text, sizeof size_text, "%dx%d", rs->width, rs->height);
  if (rs->region_width)
    snprintf(region, sizeof region, "%d,%d,%d,%d", rs->region_x, rs->region_y,
             rs->region_width, rs->region_height);
  char tile[32] = "tiles chosen";
  if (o->tile_size)
    snprintf(tile, sizeof tile, "tile %d", o->tile_size);
  char frames[64] = "a still";
  if (ro->frames)
    snprintf(frames, sizeof frames, "frames %d-%d", ro->first_frame,
             ro->last_frame);
  snprintf(out, size,
           "glint %s, backend %s, %s maths%s, accel %s; %s%.200s, %s, "
           "region %s, %d spp, depth %d, gamma %.17g; %s, %s schedule, %s",
           glint_version(),
           glint_backend_name(glint_backend_resolve(rs->backend)),
           glint_math_name(rs->math), rs->rcp_newton ? "" : ", no Newton step",
           glint_accel_name(rs->accel), is_path ? "a scene file" : "scene ",
           is_path ? "" : scene, size_text, region, rs->spp, rs->max_depth,
           rs->gamma, frames, o->dynamic ? "dynamic" : "static", tile);
}

/* Refuses to start when a rank renders differently from rank 0. */
static int same_renderers(const mpi_world *w, const mpi_options *o) {
  char mine[MPI_MESSAGE_CHARS] = {0};
  fingerprint(o, mine, sizeof mine);
  char *all = gather_texts(w, mine, "gathering the ranks' renderers");
  int same = 1;
  if (w->rank == 0) {
    for (int r = 1; r < w->size; r++)
      same &= strcmp(all, all + (size_t)r * sizeof mine) == 0;
    if (!same) {
      fprintf(stderr,
              "glint-mpi: the ranks would render differently or share the "
              "work differently, so none starts (give every rank the same "
              "glint and arguments):\n");
      for (int r = 0; r < w->size; r++)
        fprintf(stderr, "  rank %d (%s): %s\n", r, w->hosts[r],
                all + (size_t)r * sizeof mine);
    }
  }
  free(all);
  mpi_check(w, MPI_Bcast(&same, 1, MPI_INT, 0, w->comm),
            "sharing the ranks' renderers");
  return same;
}

/* The scene on every rank: rank 0 packs the file and what it refers to,
 * and broadcasts the bytes; a built-in scene is made by name. NULL, with
 * *code the exit status, where a rank failed. */
static glint_scene *share_scene(const mpi_world *w, const mpi_options *o,
                                char *stem, size_t stem_size, int *code) {
  const char *arg = o->render.scene;
  int is_file = w->rank == 0 && cli_scene_is_file(arg); /* rank 0's word */
  mpi_check(w, MPI_Bcast(&is_file, 1, MPI_INT, 0, w->comm),
            "sharing the scene's kind");
  glint_error err = {0};
  glint_scene *scene = NULL;
  glint_status st = GLINT_OK;
  if (!is_file) {
    st = glint_scene_builtin(arg, &scene, &err);
  } else {
    void *packed = NULL;
    size_t size = 0;
    if (w->rank == 0)
      st = glint_scene_pack(arg, &packed, &size, &err);
    uint64_t sent = st ? UINT64_MAX : size;
    mpi_check(w, MPI_Bcast(&sent, 1, MPI_UINT64_T, 0, w->comm),
              "broadcasting the scene");
    if (sent == UINT64_MAX) { /* rank 0 could not read it: it says why */
      *code = mpi_agree(w, st, err.message);
      return NULL;
    }
    size = (size_t)sent;
    if (w->rank != 0 && !(packed = malloc(size ? size : 1)))
      mpi_fail(w, 1, "out of memory for the scene (%zu bytes)", size);
    /* In pieces: MPI counts in ints. */
    for (size_t at = 0; at < size; at += (size_t)1 << 30) {
      size_t piece =
          size - at < ((size_t)1 << 30) ? size - at : (size_t)1 << 30;
      mpi_check(
          w, MPI_Bcast((char *)packed + at, (int)piece, MPI_BYTE, 0, w->comm),
          "broadcasting the scene");
    }
    st = glint_scene_load_packed(packed, size, &scene, &err);
    glint_free(packed);
  }
  if ((*code = mpi_agree(w, st, err.message))) {
    glint_scene_destroy(scene);
    return NULL;
  }
  if (w->rank == 0)
    cli_note_scale(arg, scene);
  cli_scene_stem(arg, stem, stem_size);
  return scene;
}

/* The number of ranks on this rank's host. */
static int ranks_on_host(const mpi_world *w) {
  MPI_Comm host;
  mpi_check(w,
            MPI_Comm_split_type(w->comm, MPI_COMM_TYPE_SHARED, w->rank,
                                MPI_INFO_NULL, &host),
            "finding the ranks on this host");
  int local = 1;
  mpi_check(w, MPI_Comm_size(host, &local), "counting the ranks on this host");
  MPI_Comm_free(&host);
  return local;
}

/* -t 0: the CPUs this rank may use, shared among the ranks on its host
 * (mpirun binds each rank to a core when there are cores enough, and then
 * a rank sees one). */
static int threads_per_rank(int local) {
  int threads = glint_cpu_count() / local;
  return threads < 1 ? 1 : threads;
}

/* What every rank may use and runs, gathered once: returns the most
 * threads of any rank (every rank cuts the image into the same tiles, whose
 * side follows it), and rank 0 prints a note, unless `quiet`, when a rank
 * runs more threads than the CPUs it may use, or when the ranks on a host
 * may use fewer of its CPUs than it has: mpirun binds each rank to one core
 * when it starts 2 or fewer, so that one rank a node renders on one core of
 * each, and says nothing. The first such rank is named. */
static int share_threads(const mpi_world *w, int threads, int local,
                         int quiet) {
  int mine[4] = {glint_cpu_count(), (int)sysconf(_SC_NPROCESSORS_ONLN), local,
                 threads};
  int *all = malloc(sizeof mine * (size_t)w->size);
  if (!all)
    mpi_fail(w, 1, "out of memory");
  mpi_check(w, MPI_Allgather(mine, 4, MPI_INT, all, 4, MPI_INT, w->comm),
            "counting the CPUs");
  int most = 0, noted = quiet || w->rank != 0;
  for (int r = 0; r < w->size; r++) {
    int usable = all[4 * r], online = all[4 * r + 1];
    int ranks = all[4 * r + 2], t = all[4 * r + 3];
    most = t > most ? t : most;
    if (!noted && t > usable) {
      fprintf(stderr,
              "glint-mpi: note: rank %d (%s) runs %d threads on the %d "
              "CPU%s it may use; they will take turns\n",
              r, w->hosts[r], t, usable, usable == 1 ? "" : "s");
      noted = 1;
    } else if (!noted && ranks * usable < online) {
      fprintf(stderr,
              "glint-mpi: note: the %d rank%s on %s may use %d of its %d "
              "CPUs (mpirun binds each rank to a core when it starts 2 or "
              "fewer; mpirun --bind-to none lets them use all)\n",
              ranks, ranks == 1 ? "" : "s", w->hosts[r], ranks * usable,
              online);
      noted = 1;
    }
  }
  free(all);
  return most;
}

/* Parses with rank 0's voice only: the ranks usually parse the same
 * arguments, and one message is enough. Another rank's message, should its
 * own arguments be refused (an MPMD launch), is kept in `message` (its
 * first line, without the "glint-mpi: ") for rank 0 to print. */
static int parse_quietly(const mpi_world *w, int argc, char **argv,
                         mpi_options *o, char *message, size_t size) {
  message[0] = '\0';
  if (w->rank == 0)
    return parse(argc, argv, o);
  fflush(stdout);
  fflush(stderr);
  int saved_out = dup(STDOUT_FILENO), saved_err = dup(STDERR_FILENO);
  FILE *said = tmpfile();
  int quiet = said ? dup(fileno(said)) : open("/dev/null", O_WRONLY);
  if (quiet >= 0) {
    dup2(quiet, STDOUT_FILENO);
    dup2(quiet, STDERR_FILENO);
    close(quiet);
  }
  int status = parse(argc, argv, o);
  fflush(stdout);
  fflush(stderr);
  if (saved_out >= 0) {
    dup2(saved_out, STDOUT_FILENO);
    close(saved_out);
  }
  if (saved_err >= 0) {
    dup2(saved_err, STDERR_FILENO);
    close(saved_err);
  }
  if (said) {
    rewind(said);
    char line[MPI_MESSAGE_CHARS];
    if (status > 0 && fgets(line, sizeof line, said)) {
      line[strcspn(line, "\n")] = '\0';
      const char *text = strncmp(line, "glint-mpi: ", 11) ? line : line + 11;
      snprintf(message, size, "%s", text);
    }
    fclose(said);
  }
  if (status == 0) /* help, printed to no one */
    snprintf(message, size, "its arguments ask for --help");
  else if (status > 0 && !message[0])
    snprintf(message, size, "its arguments are refused");
  return status;
}

/* Every rank's verdict on its arguments, so that none waits in a
 * collective call for a rank that stopped at them: rank 0's own refusal it
 * has printed; another rank's is printed by rank 0, naming the rank. The
 * exit status for all, or -1 to go on. */
static int agree_on_arguments(const mpi_world *w, int status,
                              const char *message) {
  int first = status;
  mpi_check(w, MPI_Bcast(&first, 1, MPI_INT, 0, w->comm),
            "sharing rank 0's arguments");
  if (first >= 0) /* every rank stops, as rank 0 said */
    return first;
  glint_status st = status < 0              ? GLINT_OK
                    : status == EXIT_MEMORY ? GLINT_E_MEMORY
                                            : GLINT_E_ARGUMENT;
  int refused = mpi_agree(w, st, message);
  return refused ? refused : -1;
}

static int run(mpi_world *w, int argc, char **argv) {
  mpi_options o;
  memset(&o, 0, sizeof o);
  char refused[MPI_MESSAGE_CHARS];
  int status = parse_quietly(w, argc, argv, &o, refused, sizeof refused);
  if ((status = agree_on_arguments(w, status, refused)) >= 0)
    return status;
  glint_render_settings *rs = &o.render.settings;
  int local = ranks_on_host(w);
  if (rs->threads == 0)
    rs->threads = threads_per_rank(local);
  o.most_threads = share_threads(w, rs->threads, local, o.render.quiet);
  if (!same_renderers(w, &o))
    return EXIT_USAGE;
  char stem[CLI_STEM_SIZE];
  int code = EXIT_USAGE;
  glint_scene *scene = share_scene(w, &o, stem, sizeof stem, &code);
  if (!scene)
    return code;
  glint_animation animation;
  glint_error err = {0};
  if (!o.render.frames && glint_scene_get_animation(scene, &animation)) {
    glint_scene *still = NULL; /* an animated scene, still: frame one */
    glint_status st = glint_scene_at_time(scene, 0, &still, &err);
    glint_scene_destroy(scene);
    scene = still;
    if ((code = mpi_agree(w, st, err.message)))
      return code;
  }
  glint_world *world = NULL;
  glint_renderer *renderer = NULL;
  glint_status st = glint_world_commit(scene, &world, NULL, &err);
  if (!st)
    st = glint_renderer_create(world, rs, &renderer, &err);
  glint_world_destroy(world);
  if ((code = mpi_agree(w, st, err.message))) {
    glint_renderer_destroy(renderer);
    glint_scene_destroy(scene);
    return code;
  }
  if (w->rank == 0)
    cli_catch_stop_signals();
  status = o.render.frames ? mpi_render_frames(w, &o, scene, renderer, stem)
                           : mpi_render_tiles(w, &o, scene, renderer, stem);
  glint_renderer_destroy(renderer);
  glint_scene_destroy(scene);
  return status;
}

/* Start-up's watchdog: MPI_Init can succeed where messages cannot pass (a
 * rank whose memory limit, ulimit -v, broke Open MPI's shared memory: its
 * warning said so, and then every rank waited for ever). Until each rank
 * has heard from every other, an alarm after --timeout seconds ends the
 * rank with a message, and mpirun the job. */
static char startup_overdue[160];

static void on_startup_overdue(int sig) {
  (void)sig;
  if (write(STDERR_FILENO, startup_overdue, strlen(startup_overdue)) < 0) {
    /* nothing else to try */
  }
  _exit(EXIT_USAGE);
}

/* --timeout's seconds, read before MPI_Init takes its own arguments out
 * (parse() checks the value, and refuses a bad one after start-up), and at
 * least 10: a --timeout of 1 s for hung renders must not stop ranks that
 * take a few seconds to start on a loaded machine. */
static double startup_timeout(int argc, char **argv) {
  double seconds = 120;
  for (int i = 1; i < argc && strcmp(argv[i], "--"); i++) {
    const char *value = strncmp(argv[i], "--timeout=", 10) == 0 ? argv[i] + 10
                        : strcmp(argv[i], "--timeout") == 0 && i + 1 < argc
                            ? argv[i + 1]
                            : NULL;
    char *end;
    double v = value ? strtod(value, &end) : 0;
    if (value && end != value && !*end && v >= 0.001 && v <= 1e6)
      seconds = v;
  }
  return seconds > 10 ? seconds : 10;
}

static void watch_startup(double seconds) {
  snprintf(startup_overdue, sizeof startup_overdue,
           "glint-mpi: the ranks did not all reach each other within %g s of "
           "starting (--timeout; MPI's messages above may say why)\n",
           seconds);
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_startup_overdue;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGALRM, &sa, NULL);
  struct itimerval timer = {
      {0, 0},
      {(time_t)seconds, (suseconds_t)((seconds - (time_t)seconds) * 1e6)}};
  setitimer(ITIMER_REAL, &timer, NULL);
}

static void startup_done(void) {
  struct itimerval off = {{0, 0}, {0, 0}};
  setitimer(ITIMER_REAL, &off, NULL);
  signal(SIGALRM, SIG_DFL);
}

int main(int argc, char **argv) {
  double start = cli_now();
  cli_write_errors_not_signals();
  char stack_problem[128];
  int stack_bad = cli_ensure_stack(stack_problem, sizeof stack_problem);
  /* --help needs no MPI job: outside mpirun it works at once. Inside one
   * (Open MPI or PMIx name the rank) every rank must reach MPI_Init: one
   * that left here held the others there for ever (an MPMD launch giving
   * one rank --help); parse() answers it after. */
  int launched = getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMIX_RANK") ||
                 getenv("PMI_RANK");
  for (int i = 1; !launched && i < argc && strcmp(argv[i], "--"); i++)
    if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
      usage(stdout);
      return 0;
    }
  watch_startup(startup_timeout(argc, argv));
  int provided;
  /* Only the main thread calls MPI; the renderer's threads never do. */
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) !=
      MPI_SUCCESS) {
    fprintf(stderr, "glint-mpi: MPI_Init failed\n");
    return EXIT_USAGE;
  }
  mpi_world w = {.comm = MPI_COMM_WORLD, .size = 1, .started = start};
  /* Errors come back as values, checked by mpi_check, instead of MPI's
   * default of ending the job without a word from glint. */
  MPI_Comm_set_errhandler(w.comm, MPI_ERRORS_RETURN);
  mpi_check(&w, MPI_Comm_rank(w.comm, &w.rank), "MPI_Comm_rank");
  mpi_check(&w, MPI_Comm_size(w.comm, &w.size), "MPI_Comm_size");
  char host[MPI_HOST_CHARS] = {0};
  int length = 0;
  char name[MPI_MAX_PROCESSOR_NAME];
  if (MPI_Get_processor_name(name, &length) == MPI_SUCCESS)
    snprintf(host, sizeof host, "%.*s", length, name);
  if (!(w.hosts = calloc((size_t)w.size, sizeof *w.hosts)))
    mpi_fail(&w, 1, "out of memory");
  mpi_check(&w,
            MPI_Allgather(host, MPI_HOST_CHARS, MPI_CHAR, w.hosts,
                          MPI_HOST_CHARS, MPI_CHAR, w.comm),
            "gathering the host names");
  /* (every rank has heard every other: the host names came, and a barrier
   * passes only once each rank's word has reached all) */
  mpi_check(&w, MPI_Barrier(w.comm), "waiting for every rank");
  startup_done();
  if (stack_bad) /* (said here, where every rank has reached MPI_Init) */
    mpi_fail(&w, EXIT_MEMORY, "rank %d (%s): %s", w.rank, w.hosts[w.rank],
             stack_problem);
  if (provided < MPI_THREAD_FUNNELED)
    mpi_fail(&w, EXIT_USAGE,
             "this MPI cannot run threads beside MPI (MPI_THREAD_FUNNELED)");
  int status = run(&w, argc - 1, argv + 1);
  free(w.hosts);
  MPI_Finalize();
  return status;
}
