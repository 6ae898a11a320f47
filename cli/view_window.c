/* glint view's window (SDL2): events, camera moves, progressive frames, the
 * on-screen display, reloading, screenshots and the benchmark. See
 * cli/view_cmd.c for what it does and cli/view_camera.c for the moves. */
#include "args.h"
#include "cli.h"
#include "view.h"
#include "view_camera.h"
#include "view_font.h"

#include <glint.h>

#include <SDL.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const double min_scale = 0.125;

typedef struct frame_record {
  double ms;
  uint64_t rays;
} frame_record;

static int backend_cycle(glint_backend current, glint_backend *next) {
  for (int step = 1; step <= GLINT_BACKEND_COUNT; step++) {
    glint_backend b = (glint_backend)((current + step) % GLINT_BACKEND_COUNT);
    if (b != GLINT_BACKEND_AUTO && b != GLINT_BACKEND_STREAM &&
        glint_backend_supported(b)) {
      *next = b;
      return 1;
    }
  }
  return 0;
}

static int file_mtime(const char *path, struct timespec *out) {
  struct stat sb;
  if (stat(path, &sb) != 0)
    return -1;
  *out = sb.st_mtim;
  return 0;
}

/* A renderer for the current scene and settings (backend, maths, threads
 * are fixed for a renderer's life). */
static int make_renderer(viewer *v, glint_error *err) {
  glint_world *world;
  glint_renderer *renderer;
  if (glint_world_commit(v->scene, &world, NULL, err))
    return -1;
  glint_status st = glint_renderer_create(world, &v->rs, &renderer, err);
  glint_world_destroy(world);
  if (st)
    return -1;
  glint_renderer_destroy(v->renderer);
  v->renderer = renderer;
  v->samples = 0;
  return 0;
}

static void free_buffers(viewer *v) {
  glint_film_destroy(v->pass);
  glint_film_destroy(v->sum);
  glint_image_destroy(v->image);
  free(v->screen);
  v->pass = v->sum = NULL;
  v->image = NULL;
  v->screen = NULL;
  if (v->texture)
    SDL_DestroyTexture(v->texture);
  v->texture = NULL;
}

/* Buffers for rendering at rw x rh and showing at the window's size. */
static int size_buffers(viewer *v, int rw, int rh) {
  if (v->pass && rw == v->rw && rh == v->rh && v->texture)
    return 0;
  free_buffers(v);
  glint_error err;
  v->rw = rw;
  v->rh = rh;
  v->samples = 0;
  if (glint_film_create(rw, rh, &v->pass, &err) ||
      glint_film_create(rw, rh, &v->sum, &err) ||
      glint_image_create(rw, rh, &v->image, &err) ||
      !(v->screen = malloc((size_t)v->win_w * v->win_h * 3))) {
    cli_error("view: out of memory for a %dx%d frame", rw, rh);
    return EXIT_MEMORY;
  }
  v->texture =
      SDL_CreateTexture(v->sdl, SDL_PIXELFORMAT_RGB24,
                        SDL_TEXTUREACCESS_STREAMING, v->win_w, v->win_h);
  if (!v->texture) {
    cli_error("view: %s", SDL_GetError());
    return EXIT_USAGE;
  }
  return 0;
}

static double scale_now(const viewer *v) {
  return v->moving ? fmin(v->auto_scale, v->user_scale) : v->user_scale;
}

/* Esc and Ctrl-Q quit (on_key). */
static int is_quit_key(const viewer *v, const SDL_KeyboardEvent *key) {
  SDL_Keycode k = key->keysym.sym;
  int ctrl = (key->keysym.mod & KMOD_CTRL) || v->held[SDL_SCANCODE_LCTRL] ||
             v->held[SDL_SCANCODE_RCTRL];
  return k == SDLK_ESCAPE || (k == SDLK_q && ctrl);
}

/* A pass renders on a thread of its own while this one goes on reading the
 * window's events: a pass can take seconds (a deep recursion through glass,
 * a large window), and a window that ignores its close button and Esc that
 * long is a hung window to its user (events were read between passes
 * only). A request to quit cancels the pass; other input waits for it. */
typedef struct pass_job {
  viewer *v;
  glint_frame_settings frame;
  glint_film *film;
  glint_stats stats;
  glint_error err;
  glint_status status;
  atomic_int quit; /* cancel: the user asked to quit */
  int done;
  pthread_mutex_t lock;
  pthread_cond_t finished;
} pass_job;

/* Cancels the pass on Ctrl-C or SIGTERM (cli_catch_stop_signals), and on a
 * request to quit from the window. */
static int cancel_pass(void *user, double fraction) {
  pass_job *job = user;
  (void)fraction;
  return cli_stopped() || atomic_load(&job->quit);
}

static void render_now(pass_job *job) {
  job->status = glint_renderer_render(job->v->renderer, &job->frame, job->film,
                                      &job->stats, &job->err);
}

static void *render_job(void *arg) {
  pass_job *job = arg;
  render_now(job);
  pthread_mutex_lock(&job->lock);
  job->done = 1;
  pthread_cond_signal(&job->finished);
  pthread_mutex_unlock(&job->lock);
  return NULL;
}

/* Sees each event as SDL_PumpEvents queues it during a pass: a request to
 * quit (the window closed, Esc, Ctrl-Q) cancels the pass, and stays queued
 * for the event loop to act on. (Peeking at the queue instead saw only its
 * first events: behind a held key's repeats, Esc went unseen.) */
static int watch_for_quit(void *user, SDL_Event *ev) {
  pass_job *job = user;
  if (ev->type == SDL_QUIT ||
      (ev->type == SDL_KEYDOWN && is_quit_key(job->v, &ev->key)))
    atomic_store(&job->quit, 1);
  return 1;
}

/* Renders the job's pass, reading the window's events every 10 ms until it
 * ends (on this thread where no other can be started). */
static void render_watching(pass_job *job) {
  pthread_t thread;
  if (pthread_mutex_init(&job->lock, NULL) != 0)
    goto alone;
  if (pthread_cond_init(&job->finished, NULL) != 0) {
    pthread_mutex_destroy(&job->lock);
    goto alone;
  }
  if (pthread_create(&thread, NULL, render_job, job) != 0) {
    pthread_cond_destroy(&job->finished);
    pthread_mutex_destroy(&job->lock);
    goto alone;
  }
  SDL_AddEventWatch(watch_for_quit, job);
  pthread_mutex_lock(&job->lock);
  while (!job->done) {
    struct timespec until;
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_nsec += 10 * 1000 * 1000;
    if (until.tv_nsec >= 1000 * 1000 * 1000)
      until.tv_sec++, until.tv_nsec -= 1000 * 1000 * 1000;
    pthread_cond_timedwait(&job->finished, &job->lock, &until);
    if (job->done || atomic_load(&job->quit))
      continue;
    pthread_mutex_unlock(&job->lock);
    SDL_PumpEvents(); /* on this thread, the window's */
    pthread_mutex_lock(&job->lock);
  }
  pthread_mutex_unlock(&job->lock);
  SDL_DelEventWatch(watch_for_quit, job);
  pthread_join(thread, NULL);
  pthread_cond_destroy(&job->finished);
  pthread_mutex_destroy(&job->lock);
  return;
alone:
  render_now(job);
}

/* One pass: sample 0 while moving (starting over), else the next sample of
 * the pattern, summed in. Returns 0, -1 when it was abandoned because the
 * user asked to quit (the request waits in the event queue), or the exit
 * status of its failure (EXIT_MEMORY where memory ran out). */
static int render_pass(viewer *v) {
  double scale = scale_now(v);
  int rw = (int)(v->win_w * scale + 0.5), rh = (int)(v->win_h * scale + 0.5);
  rw = rw < 1 ? 1 : rw;
  rh = rh < 1 ? 1 : rh;
  int failed = size_buffers(v, rw, rh);
  if (failed)
    return failed;
  if (v->moving)
    v->samples = 0;
  /* The field of view spans the width: rendering the window's aspect at a
   * lower resolution keeps the picture. */
  pass_job job;
  memset(&job, 0, sizeof job);
  job.v = v;
  glint_frame_settings *frame = &job.frame;
  glint_frame_settings_default(frame);
  frame->camera = &v->camera;
  frame->width = rw;
  frame->height = rh;
  frame->spp = v->rs.spp;
  frame->max_depth = v->rs.max_depth;
  frame->sample_first = v->samples;
  frame->sample_count = 1;
  frame->progress = cancel_pass;
  frame->progress_user = &job;
  /* The first sample goes straight into the sum (and is the average); later
   * ones are added to it. */
  job.film = v->samples == 0 ? v->sum : v->pass;
  double t0 = cli_now();
  render_watching(&job);
  const glint_stats st = job.stats;
  glint_error err = job.err;
  if (job.status) {
    if (err.status == GLINT_E_CANCELLED && cli_stopped())
      return EXIT_INTERRUPTED;
    if (err.status == GLINT_E_CANCELLED && atomic_load(&job.quit))
      return -1;
    cli_error("view: %s", err.message);
    return cli_exit_code(err.status);
  }
  size_t n = (size_t)rw * rh * 3;
  float *p = glint_film_pixels(v->pass), *sum = glint_film_pixels(v->sum);
  v->samples++;
  v->frames++;
  if (v->samples > 1) { /* the average goes where the pass was */
    float inv = 1.0f / (float)v->samples;
    for (size_t i = 0; i < n; i++) {
      sum[i] += p[i];
      p[i] = sum[i] * inv;
    }
  }
  glint_film_to_image(v->samples > 1 ? v->pass : v->sum, v->rs.gamma, v->image,
                      &err);
  double ms = (cli_now() - t0) * 1e3;
  v->frame_ms = ms;
  v->rays = st.primary_rays + st.secondary_rays + st.shadow_rays;
  v->mrays = (double)v->rays / (ms * 1e3);
  /* Keep the budget while moving: lower the scale when a frame overran it,
   * and give it back when there is room. */
  if (v->moving && !v->opt->benchmark_frames) {
    if (ms > v->opt->budget_ms)
      v->auto_scale = fmax(min_scale, fmin(v->auto_scale, scale) * 0.75);
    else if (ms < 0.5 * v->opt->budget_ms)
      v->auto_scale = fmin(1.0, v->auto_scale / 0.8);
  }
  return 0;
}

static const char *const math_names[] = {"minimax", "fast", "taylor", "exact"};

/* The rendered image scaled to the window, with the display on top. */
static void present(viewer *v) {
  const uint8_t *src = glint_image_pixels_const(v->image);
  if (v->rw == v->win_w && v->rh == v->win_h) {
    memcpy(v->screen, src, (size_t)v->win_w * v->win_h * 3);
  } else { /* nearest neighbour */
    for (int y = 0; y < v->win_h; y++) {
      const uint8_t *row =
          src + (size_t)((long)y * v->rh / v->win_h) * v->rw * 3;
      uint8_t *out = v->screen + (size_t)y * v->win_w * 3;
      for (int x = 0; x < v->win_w; x++) {
        const uint8_t *px = row + (size_t)((long)x * v->rw / v->win_w) * 3;
        out[3 * x] = px[0];
        out[3 * x + 1] = px[1];
        out[3 * x + 2] = px[2];
      }
    }
  }
  /* Twice the font's size where the help's widest line fits. */
  int text_scale =
      v->win_w >= view_text_width("1-9: DEPTH   B: BACKEND   M: MATHS   [ ]: "
                                  "SCALE  ",
                                  2)
          ? 2
          : 1;
  int line = (VIEW_GLYPH_H + 3) * text_scale;
  static const uint8_t white[3] = {255, 255, 255}, red[3] = {255, 90, 80};
  if (v->osd) {
    char lines[4][sizeof((glint_error *)0)->message + 8];
    int nl = 0;
    double scale = scale_now(v);
    snprintf(lines[nl++], sizeof lines[0], "%s  %dX%d  SCALE %.2f%s", v->stem,
             v->rw, v->rh, scale,
             v->moving && scale < v->user_scale ? " (AUTO)" : "");
    snprintf(lines[nl++], sizeof lines[0], "%.1f FPS  %.1f MS  %.1f MRAYS/S",
             v->fps, v->frame_ms, v->mrays);
    snprintf(lines[nl++], sizeof lines[0], "SPP %d/%d  DEPTH %d  %s  %s",
             v->samples, v->rs.spp, v->rs.max_depth,
             glint_backend_name(
                 glint_backend_choose(v->rs.backend, v->scene, &v->rs)),
             math_names[v->rs.math]);
    if (v->error[0])
      snprintf(lines[nl++], sizeof lines[0], "%s", v->error);
    int width = 0;
    for (int i = 0; i < nl; i++) {
      int w = view_text_width(lines[i], text_scale);
      width = w > width ? w : width;
    }
    view_shade_box(v->screen, v->win_w, v->win_h, 0, 0, width + 8 * text_scale,
                   nl * line + 4 * text_scale);
    for (int i = 0; i < nl; i++)
      view_draw_text(v->screen, v->win_w, v->win_h, 4 * text_scale,
                     4 * text_scale + i * line, lines[i], text_scale,
                     v->error[0] && i == nl - 1 ? red : white);
  }
  if (v->help) {
    static const char *const help[] = {
        "LEFT DRAG: ORBIT   RIGHT DRAG, WHEEL: DOLLY",
        "MIDDLE OR SHIFT+LEFT DRAG: PAN",
        "WASD QE: FLY   ARROWS: TURN   PGUP/PGDN: SPEED",
        "1-9: DEPTH   B: BACKEND   M: MATHS   [ ]: SCALE",
        "R: RESET   F: FULLSCREEN   H: DISPLAY   F1: HELP",
        "P: PRINT CAMERA   SPACE, F12: SCREENSHOT",
        "ESC, CTRL+Q: QUIT"};
    int n = (int)(sizeof help / sizeof help[0]);
    int y0 = v->win_h - n * line - 4 * text_scale;
    view_shade_box(v->screen, v->win_w, v->win_h, 0, y0, v->win_w, v->win_h);
    for (int i = 0; i < n; i++)
      view_draw_text(v->screen, v->win_w, v->win_h, 4 * text_scale,
                     y0 + 2 * text_scale + i * line, help[i], text_scale,
                     white);
  }
  SDL_UpdateTexture(v->texture, NULL, v->screen, v->win_w * 3);
  SDL_RenderClear(v->sdl);
  SDL_RenderCopy(v->sdl, v->texture, NULL, NULL);
  SDL_RenderPresent(v->sdl);
}

/* Reloads the scene file if it changed; on a parse error keeps the scene on
 * screen and says why (on the display and stderr). */
static void reload_if_changed(viewer *v) {
  struct timespec now;
  if (!v->is_file || file_mtime(v->opt->scene, &now) != 0 ||
      (now.tv_sec == v->mtime.tv_sec && now.tv_nsec == v->mtime.tv_nsec))
    return;
  v->mtime = now;
  glint_scene *scene, *still;
  glint_error err;
  if (glint_scene_load(v->opt->scene, &scene, &err) == GLINT_OK) {
    /* An animated scene shows its first frame, as on loading. */
    glint_status st = glint_scene_at_time(scene, 0, &still, &err);
    glint_scene_destroy(scene);
    scene = st ? NULL : still;
  } else {
    scene = NULL;
  }
  if (!scene) {
    snprintf(v->error, sizeof v->error, "%s", err.message);
    fprintf(stderr, "glint: %s (still showing the last good scene)\n",
            err.message);
    v->redraw = 1;
    return;
  }
  glint_scene *old = v->scene;
  v->scene = scene;
  if (make_renderer(v, &err)) {
    v->scene = old;
    glint_scene_destroy(scene);
    snprintf(v->error, sizeof v->error, "%s", err.message);
    fprintf(stderr, "glint: %s\n", err.message);
    return;
  }
  glint_scene_destroy(old);
  glint_scene_info info;
  glint_scene_get_info(v->scene, &info);
  v->home = info.camera;
  v->error[0] = '\0';
  v->samples = 0;
  fprintf(stderr, "glint: reloaded %s\n", v->opt->scene);
}

/* SCENE-NNNN.png, the first name that is not taken (a link to nothing
 * takes its name too: it blocked every screenshot), rendered by
 * glint_render at the window's size with the current camera and
 * settings. */
static void screenshot(viewer *v) {
  char path[400];
  struct stat sb;
  for (int i = 1; i < 100000; i++) {
    snprintf(path, sizeof path, "%s-%04d.png", v->stem, i);
    if (lstat(path, &sb) != 0 && errno == ENOENT)
      break;
  }
  glint_error err;
  glint_render_settings rs = v->rs;
  rs.width = v->win_w;
  rs.height = v->win_h;
  glint_image *image = NULL;
  glint_camera saved;
  glint_scene_info info;
  glint_scene_get_info(v->scene, &info);
  saved = info.camera;
  if (glint_scene_set_camera(v->scene, &v->camera, &err) ||
      glint_render(v->scene, &rs, &image, NULL, &err) ||
      glint_image_write(image, path, &err)) {
    cli_error("screenshot: %s", err.message);
  } else {
    char json[512];
    view_camera_json(&v->camera, json, sizeof json);
    printf("wrote %s (%dx%d, %d spp, depth %d, %s), %s\n", path, rs.width,
           rs.height, rs.spp, rs.max_depth,
           glint_backend_name(glint_backend_choose(rs.backend, v->scene, &rs)),
           json);
    fflush(stdout);
  }
  glint_image_destroy(image);
  glint_scene_set_camera(v->scene, &saved, &err);
}

int view_idle(const viewer *v) {
  return v->samples >= v->rs.spp && !v->moving && v->texture;
}

void view_print_camera(const viewer *v) {
  char json[512];
  view_camera_json(&v->camera, json, sizeof json);
  printf("%s\n", json);
  fflush(stdout);
}

glint_image *view_capture(const viewer *v) {
  glint_image *image;
  glint_error err;
  if (!v->screen || glint_image_create(v->win_w, v->win_h, &image, &err))
    return NULL;
  memcpy(glint_image_pixels(image), v->screen, (size_t)v->win_w * v->win_h * 3);
  return image;
}

static int open_window(viewer *v, int w, int h) {
  v->win_w = w;
  v->win_h = h;
  char title[300];
  snprintf(title, sizeof title, "glint view: %s", v->stem);
  v->window =
      SDL_CreateWindow(title, SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED,
                       w, h, SDL_WINDOW_RESIZABLE);
  if (!v->window)
    return -1;
  v->sdl = SDL_CreateRenderer(v->window, -1, 0);
  if (!v->sdl)
    v->sdl = SDL_CreateRenderer(v->window, -1, SDL_RENDERER_SOFTWARE);
  return v->sdl ? 0 : -1;
}

static int compare_ms(const void *a, const void *b) {
  double x = ((const frame_record *)a)->ms, y = ((const frame_record *)b)->ms;
  return (x > y) - (x < y);
}

/* --benchmark N: the documented orbit, one sample per pixel a frame. */
/* SDL falls back to its invisible "offscreen" driver when no display can be
 * reached, which would leave the user a viewer with no window. So, unless the
 * user names a driver in SDL_VIDEODRIVER, only the drivers that show a window
 * are tried (Wayland only where a compositor can be found), and SDL_Init fails
 * with the reason when none can. A benchmark or a script needs no display:
 * without one it runs on SDL's dummy driver (a script failed there unless
 * SDL_VIDEODRIVER named it). */
static void choose_video_driver(bool headless) {
  const char *named = getenv("SDL_VIDEODRIVER");
  if (named && *named)
    return;
  bool x11 = getenv("DISPLAY") != NULL;
  bool wayland = getenv("WAYLAND_DISPLAY") || getenv("XDG_RUNTIME_DIR");
  if (headless && !x11 && !getenv("WAYLAND_DISPLAY"))
    SDL_SetHint(SDL_HINT_VIDEODRIVER, "dummy");
  else if (!headless)
    SDL_SetHint(SDL_HINT_VIDEODRIVER,
                wayland ? "x11,wayland,KMSDRM" : "x11,KMSDRM");
}

static int run_benchmark(viewer *v) {
  int n = v->opt->benchmark_frames;
  frame_record *frames = calloc((size_t)n, sizeof *frames);
  if (!frames)
    return 1;
  glint_camera start = v->camera;
  double total_ms = 0;
  uint64_t total_rays = 0;
  double t_start = cli_now();
  for (int i = 0; i < n; i++) {
    SDL_Event ev;
    int quit = cli_stopped();
    while (!quit && SDL_PollEvent(&ev)) /* as during a pass */
      quit = ev.type == SDL_QUIT ||
             (ev.type == SDL_KEYDOWN && is_quit_key(v, &ev.key));
    if (quit) {
      free(frames);
      return EXIT_INTERRUPTED;
    }
    v->camera = start;
    view_orbit(&v->camera, 360.0 * i / n, 0);
    v->moving = 1;
    double t0 = cli_now();
    int failed = render_pass(v);
    if (failed) { /* -1: the window asked to quit */
      free(frames);
      return failed < 0 ? EXIT_INTERRUPTED : failed;
    }
    present(v);
    frames[i].ms = (cli_now() - t0) * 1e3;
    frames[i].rays = v->rays;
    total_ms += frames[i].ms;
    total_rays += frames[i].rays;
    v->fps = 1e3 / frames[i].ms;
  }
  double wall = cli_now() - t_start;
  qsort(frames, (size_t)n, sizeof *frames, compare_ms);
  double median = n % 2 ? frames[n / 2].ms
                        : 0.5 * (frames[n / 2 - 1].ms + frames[n / 2].ms);
  int i95 = (int)ceil(0.95 * n) - 1;
  int threads = v->rs.threads ? v->rs.threads : glint_cpu_count();
  printf(
      "%s: %d frames at %dx%d, 1 spp, depth %d, %s, %d thread%s\n", v->stem, n,
      v->rw, v->rh, v->rs.max_depth,
      glint_backend_name(glint_backend_choose(v->rs.backend, v->scene, &v->rs)),
      threads, threads == 1 ? "" : "s");
  printf("frame ms: median %.2f, 95th percentile %.2f; %.1f fps; %.1f "
         "Mrays/s\n",
         median, frames[i95 < 0 ? 0 : i95].ms, n / wall,
         (double)total_rays / (total_ms * 1e3));
  free(frames);
  return 0;
}

/* Keys held down move the camera every frame by their speed x the time. */
static int fly_keys(viewer *v, double dt) {
  const Uint8 *k = v->held;
  int ctrl = k[SDL_SCANCODE_LCTRL] || k[SDL_SCANCODE_RCTRL];
  double distance = 0;
  glint_vec3 d = {v->camera.at.x - v->camera.from.x,
                  v->camera.at.y - v->camera.from.y,
                  v->camera.at.z - v->camera.from.z};
  distance = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  double step = distance * 0.5 * v->speed * dt, turn = 60 * dt;
  double fwd = (k[SDL_SCANCODE_W] - k[SDL_SCANCODE_S]) * step;
  double right = (k[SDL_SCANCODE_D] - k[SDL_SCANCODE_A]) * step;
  double up = (k[SDL_SCANCODE_E] - (k[SDL_SCANCODE_Q] && !ctrl ? 1 : 0)) * step;
  double yaw = (k[SDL_SCANCODE_LEFT] - k[SDL_SCANCODE_RIGHT]) * turn;
  double pitch = (k[SDL_SCANCODE_UP] - k[SDL_SCANCODE_DOWN]) * turn;
  if (fwd == 0 && right == 0 && up == 0 && yaw == 0 && pitch == 0)
    return 0;
  view_fly(&v->camera, fwd, right, up);
  view_turn(&v->camera, yaw, pitch);
  return 1;
}

/* A key press; returns 0 to quit. */
static int on_key(viewer *v, const SDL_KeyboardEvent *key) {
  SDL_Keycode k = key->keysym.sym;
  glint_error err;
  if (is_quit_key(v, key))
    return 0;
  if (k >= SDLK_1 && k <= SDLK_9) {
    v->rs.max_depth = (int)(k - SDLK_0);
    v->samples = 0;
  } else if (k == SDLK_b || k == SDLK_m) {
    glint_render_settings before = v->rs;
    if (k == SDLK_b)
      backend_cycle(glint_backend_choose(v->rs.backend, v->scene, &v->rs),
                    &v->rs.backend);
    else
      v->rs.math = (glint_math)((v->rs.math + 1) % 4);
    if (make_renderer(v, &err)) {
      cli_error("view: %s", err.message);
      v->rs = before;
    }
  } else if (k == SDLK_LEFTBRACKET || k == SDLK_RIGHTBRACKET) {
    double s = v->user_scale * (k == SDLK_LEFTBRACKET ? 0.5 : 2.0);
    v->user_scale = fmax(min_scale, fmin(1.0, s));
    v->auto_scale = v->user_scale;
    v->samples = 0;
  } else if (k == SDLK_h) {
    v->osd = !v->osd;
    v->redraw = 1;
  } else if (k == SDLK_F1) {
    v->help = !v->help;
    v->redraw = 1;
  } else if (k == SDLK_r) {
    v->camera = v->home;
    v->moving = 1;
  } else if (k == SDLK_f) {
    if (SDL_GetWindowFlags(v->window) & SDL_WINDOW_FULLSCREEN_DESKTOP) {
      /* back to the size it had: without a window manager (or with the
       * dummy driver) leaving fullscreen kept the screen's size, and sent
       * no size change, so the view went on rendering at it */
      SDL_SetWindowFullscreen(v->window, 0);
      SDL_SetWindowSize(v->window, v->windowed_w, v->windowed_h);
      view_resize(v, v->windowed_w, v->windowed_h);
    } else {
      v->windowed_w = v->win_w, v->windowed_h = v->win_h;
      SDL_SetWindowFullscreen(v->window, SDL_WINDOW_FULLSCREEN_DESKTOP);
    }
  } else if (k == SDLK_PAGEUP) {
    v->speed *= 2;
  } else if (k == SDLK_PAGEDOWN) {
    v->speed /= 2;
  } else if (k == SDLK_p) {
    view_print_camera(v);
  } else if (k == SDLK_SPACE || k == SDLK_F12) {
    screenshot(v);
  }
  return 1;
}

static void on_mouse_motion(viewer *v, const SDL_MouseMotionEvent *m) {
  if (!m->state)
    return;
  int shift = v->held[SDL_SCANCODE_LSHIFT] || v->held[SDL_SCANCODE_RSHIFT];
  double aspect = (double)v->win_w / v->win_h;
  if ((m->state & SDL_BUTTON_MMASK) || ((m->state & SDL_BUTTON_LMASK) && shift))
    view_pan(&v->camera, (double)m->xrel / v->win_w,
             -(double)m->yrel / v->win_h, aspect);
  else if (m->state & SDL_BUTTON_LMASK)
    view_orbit(&v->camera, 0.3 * m->xrel, 0.3 * m->yrel);
  else if (m->state & SDL_BUTTON_RMASK)
    view_dolly(&v->camera, exp(0.01 * m->yrel));
  else
    return;
  v->moving = 1;
}

void view_resize(viewer *v, int w, int h) {
  if (w < 1 || h < 1 || (w == v->win_w && h == v->win_h))
    return;
  v->win_w = w > GLINT_MAX_DIMENSION ? GLINT_MAX_DIMENSION : w;
  v->win_h = h > GLINT_MAX_DIMENSION ? GLINT_MAX_DIMENSION : h;
  free_buffers(v);
  v->samples = 0;
}

static int run_interactive(viewer *v) {
  double last = cli_now(), last_poll = 0;
  for (;;) {
    if (cli_stopped())
      return EXIT_INTERRUPTED;
    if (v->script) {
      int more = view_script_step(v->script, v);
      if (more < 0)
        return EXIT_USAGE;
      if (more == 0) {
        view_script_free(v->script);
        v->script = NULL;
        /* Without quit the window stays for the user; on a driver that
         * shows none (dummy, offscreen) no one could ever close it */
        const char *driver = SDL_GetCurrentVideoDriver();
        if (driver &&
            (strcmp(driver, "dummy") == 0 || strcmp(driver, "offscreen") == 0))
          return 0;
      }
    }
    SDL_Event ev;
    /* Idle (refined, nothing held): sleep in the event queue, waking a few
     * times a second to look at the scene file (or at the script's clock). */
    int got = view_idle(v) ? SDL_WaitEventTimeout(&ev, v->script ? 5 : 250)
                           : SDL_PollEvent(&ev);
    while (got) {
      switch (ev.type) {
      case SDL_QUIT: return 0;
      case SDL_KEYDOWN:
        v->held[ev.key.keysym.scancode] = 1;
        if (!on_key(v, &ev.key))
          return 0;
        break;
      case SDL_KEYUP: v->held[ev.key.keysym.scancode] = 0; break;
      case SDL_MOUSEMOTION: on_mouse_motion(v, &ev.motion); break;
      case SDL_MOUSEWHEEL:
        view_dolly(&v->camera, pow(0.9, ev.wheel.y));
        v->moving = 1;
        break;
      case SDL_WINDOWEVENT:
        if (ev.window.event == SDL_WINDOWEVENT_SIZE_CHANGED)
          view_resize(v, ev.window.data1, ev.window.data2);
        else if (ev.window.event == SDL_WINDOWEVENT_FOCUS_LOST)
          memset(v->held, 0, sizeof v->held); /* their key-ups go elsewhere */
        else if (ev.window.event == SDL_WINDOWEVENT_EXPOSED && v->image)
          present(v);
        break;
      }
      got = SDL_PollEvent(&ev);
    }
    double now = cli_now();
    if (fly_keys(v, fmin(now - last, 0.1)))
      v->moving = 1;
    last = now;
    if (now - last_poll > 0.25) {
      reload_if_changed(v);
      last_poll = now;
    }
    if (view_idle(v)) {
      if (v->redraw)
        present(v);
      v->redraw = 0;
      continue;
    }
    int was_moving = v->moving;
    int failed = render_pass(v);
    if (failed < 0) /* the quit it was abandoned for is in the queue */
      continue;
    if (failed)
      return failed;
    double end = cli_now();
    v->fps = end > v->last_frame_end ? 1.0 / (end - v->last_frame_end) : 0;
    v->last_frame_end = end;
    present(v);
    /* A frame that moved shows sample 0; refinement starts once a frame
     * passes with nothing moving. */
    if (was_moving) {
      v->moving = 0;
      v->stopped_at = cli_now();
      v->refined_at = 0;
    } else if (v->samples == v->rs.spp && !v->refined_at) {
      v->refined_at = cli_now();
    }
  }
}

int view_run(const view_options *o) {
  viewer v;
  memset(&v, 0, sizeof v);
  v.opt = o;
  v.rs = o->settings;
  v.osd = 1;
  v.speed = 1;
  v.user_scale = v.auto_scale = 1;
  if (o->script_path && !(v.script = view_script_load(o->script_path)))
    return EXIT_USAGE;
  int code = EXIT_USAGE;
  v.scene = cli_load_scene(o->scene, v.stem, sizeof v.stem, &code);
  if (!v.scene) {
    view_script_free(v.script);
    return code;
  }
  v.is_file = cli_scene_is_file(o->scene);
  if (v.is_file)
    file_mtime(o->scene, &v.mtime);
  glint_scene_info info;
  glint_scene_get_info(v.scene, &info);
  v.camera = v.home = info.camera;
  int w = v.rs.width ? v.rs.width : info.width;
  int h = v.rs.height ? v.rs.height : info.height;
  glint_error err;
  if (make_renderer(&v, &err)) {
    cli_error("%s", err.message);
    glint_scene_destroy(v.scene);
    return EXIT_USAGE;
  }
  choose_video_driver(o->benchmark_frames > 0 || o->script_path);
  /* Ctrl-C and SIGTERM cancel the pass being rendered (a pass of a large
   * window takes seconds, and SDL's own handler is looked at between
   * passes only): glint's handlers, installed first, keep SDL's out. */
  cli_catch_stop_signals();
  cli_remove_on_stop(NULL); /* and a pass that will not stop, 2 s later */
  int status = 0;
  if (SDL_Init(SDL_INIT_VIDEO) != 0 || open_window(&v, w, h) != 0) {
    const char *display = getenv("DISPLAY");
    cli_error("view: cannot open a window: %s (DISPLAY is %s%s%s)",
              SDL_GetError(), display ? "'" : "not set", display ? display : "",
              display ? "'" : "");
    status = EXIT_USAGE;
  } else {
    status = o->benchmark_frames ? run_benchmark(&v) : run_interactive(&v);
  }
  if (status == EXIT_INTERRUPTED && cli_stopped())
    cli_error("view: interrupted"); /* as render says (it said nothing) */
  free_buffers(&v);
  if (v.sdl)
    SDL_DestroyRenderer(v.sdl);
  if (v.window)
    SDL_DestroyWindow(v.window);
  SDL_Quit();
  glint_renderer_destroy(v.renderer);
  glint_scene_destroy(v.scene);
  view_script_free(v.script);
  return status;
}
