/* The render driver: validates settings, picks the backend, prepares the
 * scene and hands tiles to worker threads. Tiles are claimed from an atomic
 * counter, so threads balance dynamically; every pixel depends only on its own
 * rays, so the image is bit-identical for every thread count. */
#include "core/cpu.h"
#include "core/error.h"
#include "core/memory.h"
#include "core/timer.h"
#include "image/image.h"
#include "render/backend.h"
#include "scene/scene.h"

#include <math.h>
#include <pthread.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

/* ---- backends ---------------------------------------------------------- */

typedef struct backend_entry {
  const char *name;
  int width;
  const glint_backend_ops *ops; /* NULL: not built into this binary */
  int (*cpu_has)(const glint_cpu_features *f);
} backend_entry;

static int cpu_any(const glint_cpu_features *f) {
  (void)f;
  return 1;
}
static int cpu_sse(const glint_cpu_features *f) { return f->sse41; }
static int cpu_avx2(const glint_cpu_features *f) { return f->avx2; }
static int cpu_avx512(const glint_cpu_features *f) { return f->avx512; }

static const backend_entry backends[GLINT_BACKEND_COUNT] = {
    [GLINT_BACKEND_AUTO] = {"auto", 0, NULL, cpu_any},
    [GLINT_BACKEND_SCALAR_FLOAT] = {"scalar-float", 1, &glint_scalar_ops_float,
                                    cpu_any},
    [GLINT_BACKEND_SCALAR_DOUBLE] = {"scalar-double", 1,
                                     &glint_scalar_ops_double, cpu_any},
    [GLINT_BACKEND_SSE] = {"sse", 4, &glint_beam_ops_sse, cpu_sse},
    [GLINT_BACKEND_AVX2] = {"avx2", 8, &glint_beam_ops_avx2, cpu_avx2},
    [GLINT_BACKEND_AVX512] = {"avx512", 16, &glint_beam_ops_avx512, cpu_avx512},
    [GLINT_BACKEND_STREAM] = {"stream", 0, NULL, cpu_any},
    [GLINT_BACKEND_STREAM_SSE] = {"stream-sse", 4, &glint_stream_ops_sse,
                                  cpu_sse},
    [GLINT_BACKEND_STREAM_AVX2] = {"stream-avx2", 8, &glint_stream_ops_avx2,
                                   cpu_avx2},
    [GLINT_BACKEND_STREAM_AVX512] = {"stream-avx512", 16,
                                     &glint_stream_ops_avx512, cpu_avx512},
};

const glint_backend_ops *glint_backend_ops_of(glint_backend b) {
  return (unsigned)b < GLINT_BACKEND_COUNT ? backends[b].ops : NULL;
}

const char *glint_backend_name(glint_backend b) {
  return (unsigned)b < GLINT_BACKEND_COUNT ? backends[b].name : "unknown";
}

int glint_backend_supported(glint_backend b) {
  if ((unsigned)b >= GLINT_BACKEND_COUNT)
    return 0;
  if (b == GLINT_BACKEND_AUTO || b == GLINT_BACKEND_STREAM)
    return glint_backend_supported(glint_backend_resolve(b));
  glint_cpu_features f;
  glint_cpu_detect(&f);
  return backends[b].ops != NULL && backends[b].cpu_has(&f);
}

glint_backend glint_backend_resolve(glint_backend b) {
  static const glint_backend widest_beam[] = {
      GLINT_BACKEND_AVX512, GLINT_BACKEND_AVX2, GLINT_BACKEND_SSE};
  static const glint_backend widest_stream[] = {GLINT_BACKEND_STREAM_AVX512,
                                                GLINT_BACKEND_STREAM_AVX2,
                                                GLINT_BACKEND_STREAM_SSE};
  const glint_backend *order = NULL;
  if (b == GLINT_BACKEND_AUTO)
    order = widest_beam;
  else if (b == GLINT_BACKEND_STREAM)
    order = widest_stream;
  else
    return b;
  for (int i = 0; i < 3; i++)
    if (glint_backend_supported(order[i]))
      return order[i];
  return GLINT_BACKEND_SCALAR_FLOAT;
}

int glint_backend_width(glint_backend b) {
  b = glint_backend_resolve(b);
  return (unsigned)b < GLINT_BACKEND_COUNT ? backends[b].width : 0;
}

static glint_status parse_name(const char *name, const char *const *names,
                               int count, const char *what, int *out,
                               glint_error *error) {
  for (int i = 0; i < count; i++)
    if (names[i] && strcmp(name, names[i]) == 0) {
      *out = i;
      return GLINT_OK;
    }
  char list[256] = "";
  for (int i = 0; i < count; i++)
    if (names[i]) {
      strncat(list, i ? ", " : "", sizeof list - strlen(list) - 1);
      strncat(list, names[i], sizeof list - strlen(list) - 1);
    }
  return glint_fail(error, GLINT_E_ARGUMENT, "unknown %s '%s' (one of: %s)",
                    what, name, list);
}

glint_status glint_backend_parse(const char *name, glint_backend *b,
                                 glint_error *error) {
  const char *names[GLINT_BACKEND_COUNT];
  for (int i = 0; i < GLINT_BACKEND_COUNT; i++)
    names[i] = backends[i].name;
  int v = 0;
  glint_status st =
      parse_name(name, names, GLINT_BACKEND_COUNT, "backend", &v, error);
  if (st == GLINT_OK)
    *b = (glint_backend)v;
  return st;
}

static const char *const math_names[GLINT_MATH_COUNT] = {"minimax", "fast",
                                                         "taylor", "exact"};

const char *glint_math_name(glint_math m) {
  return (unsigned)m < GLINT_MATH_COUNT ? math_names[m] : "unknown";
}

glint_status glint_math_parse(const char *name, glint_math *m,
                              glint_error *error) {
  int v = 0;
  glint_status st =
      parse_name(name, math_names, GLINT_MATH_COUNT, "math", &v, error);
  if (st == GLINT_OK)
    *m = (glint_math)v;
  return st;
}

static const char *const accel_names[2] = {"bvh", "none"};

const char *glint_accel_name(glint_accel a) {
  return (unsigned)a < 2 ? accel_names[a] : "unknown";
}

glint_status glint_accel_parse(const char *name, glint_accel *a,
                               glint_error *error) {
  int v = 0;
  glint_status st = parse_name(name, accel_names, 2, "acceleration", &v, error);
  if (st == GLINT_OK)
    *a = (glint_accel)v;
  return st;
}

/* ---- settings ---------------------------------------------------------- */

void glint_render_settings_default(glint_render_settings *s) {
  memset(s, 0, sizeof *s);
  s->max_depth = 5;
  s->spp = 5;
  s->backend = GLINT_BACKEND_AUTO;
  s->math = GLINT_MATH_MINIMAX;
  s->rcp_newton = 1;
  s->accel = GLINT_ACCEL_BVH;
  s->gamma = 1;
}

static glint_status validate(const glint_scene *scene,
                             const glint_render_settings *s, int *w, int *h,
                             glint_error *e) {
  *w = s->width ? s->width : scene->width;
  *h = s->height ? s->height : scene->height;
  if (*w < 1 || *w > GLINT_MAX_DIMENSION)
    return glint_fail(e, GLINT_E_ARGUMENT, "width %d is outside 1..%d", *w,
                      GLINT_MAX_DIMENSION);
  if (*h < 1 || *h > GLINT_MAX_DIMENSION)
    return glint_fail(e, GLINT_E_ARGUMENT, "height %d is outside 1..%d", *h,
                      GLINT_MAX_DIMENSION);
  if (s->max_depth < 1 || s->max_depth > GLINT_MAX_DEPTH)
    return glint_fail(e, GLINT_E_ARGUMENT, "depth %d is outside 1..%d",
                      s->max_depth, GLINT_MAX_DEPTH);
  if (s->spp < 1 || s->spp > GLINT_MAX_SPP)
    return glint_fail(e, GLINT_E_ARGUMENT,
                      "samples per pixel %d is outside 1..%d", s->spp,
                      GLINT_MAX_SPP);
  if (s->region_width != 0 || s->region_height != 0) {
    if (s->region_width < 1 || s->region_height < 1 || s->region_x < 0 ||
        s->region_y < 0 || s->region_x > *w - s->region_width ||
        s->region_y > *h - s->region_height)
      return glint_fail(e, GLINT_E_ARGUMENT,
                        "region %d,%d %dx%d is not inside the %dx%d image",
                        s->region_x, s->region_y, s->region_width,
                        s->region_height, *w, *h);
  }
  if (s->threads < 0 || s->threads > GLINT_MAX_THREADS)
    return glint_fail(e, GLINT_E_ARGUMENT, "threads %d is outside 0..%d",
                      s->threads, GLINT_MAX_THREADS);
  if (!(isfinite(s->gamma) && s->gamma > 0))
    return glint_fail(e, GLINT_E_ARGUMENT, "gamma %g must be a number > 0",
                      s->gamma);
  if ((unsigned)s->math >= GLINT_MATH_COUNT)
    return glint_fail(e, GLINT_E_ARGUMENT, "unknown math variant %d",
                      (int)s->math);
  if ((unsigned)s->accel > GLINT_ACCEL_NONE)
    return glint_fail(e, GLINT_E_ARGUMENT, "unknown acceleration %d",
                      (int)s->accel);
  if ((unsigned)s->backend >= GLINT_BACKEND_COUNT)
    return glint_fail(e, GLINT_E_ARGUMENT, "unknown backend %d",
                      (int)s->backend);
  return GLINT_OK;
}

/* ---- workers ----------------------------------------------------------- */

typedef struct render_job {
  const glint_backend_ops *ops;
  const void *prepared;
  glint_image *image;
  int x0, y0, x1, y1; /* the region rendered, in frame pixels */
  int tiles_x, tile_count;
  double inv_gamma;
  atomic_int next_tile;
  atomic_int cancelled;
  pthread_mutex_t progress_lock;
  int tiles_done;
  glint_progress_fn progress;
  void *progress_user;
  int primary_only; /* glint_trace_primary */
} render_job;

typedef struct worker {
  render_job *job;
  void *scratch;
  float *rgb;
  glint_stats stats;
  uint64_t hits; /* primary_only */
} worker;

/* SPEC §4: only the average is clamped to [0, 1], written as round(255 c).
 * Branch-free comparisons (fminf/fmaxf would be library calls), so the loop
 * over a tile vectorises; a NaN, which validated input never produces,
 * fails c > 0 and becomes 0. */
static inline uint8_t to_byte(float c) {
  float v = c > 0.0f ? c : 0.0f;
  v = v < 1.0f ? v : 1.0f;
  return (uint8_t)(int)(255.0f * v + 0.5f);
}

/* Tiny intermediate values (a highlight's power far from its peak, Beer's law
 * over a long path) are denormal numbers, whose arithmetic costs a microcode
 * assist of ~100 cycles on x86. Like most renderers, glint flushes them to
 * zero while it renders (FTZ and DAZ in MXCSR): they are far below one 8-bit
 * level. The caller's mode is restored afterwards. */
static unsigned denormals_off(void) {
#if defined(__SSE__)
  unsigned saved = _mm_getcsr();
  _mm_setcsr(saved | 0x8040); /* FTZ (bit 15) | DAZ (bit 6) */
  return saved;
#else
  return 0;
#endif
}

static void denormals_restore(unsigned saved) {
#if defined(__SSE__)
  _mm_setcsr(saved);
#else
  (void)saved;
#endif
}

static void *worker_main(void *arg) {
  worker *w = arg;
  unsigned csr = denormals_off();
  render_job *job = w->job;
  uint8_t *pixels = glint_image_pixels(job->image);
  int width = glint_image_width(job->image);
  for (;;) {
    if (atomic_load(&job->cancelled))
      break;
    int t = atomic_fetch_add(&job->next_tile, 1);
    if (t >= job->tile_count)
      break;
    tile_rect tile;
    tile.x0 = job->x0 + (t % job->tiles_x) * GLINT_TILE_SIZE;
    tile.y0 = job->y0 + (t / job->tiles_x) * GLINT_TILE_SIZE;
    tile.x1 = tile.x0 + GLINT_TILE_SIZE < job->x1 ? tile.x0 + GLINT_TILE_SIZE
                                                  : job->x1;
    tile.y1 = tile.y0 + GLINT_TILE_SIZE < job->y1 ? tile.y0 + GLINT_TILE_SIZE
                                                  : job->y1;
    if (job->primary_only) {
      w->hits += job->ops->primary_tile(job->prepared, &tile, &w->stats);
      continue;
    }
    job->ops->render_tile(job->prepared, &tile, w->scratch, w->rgb, &w->stats);
    int tw = tile.x1 - tile.x0;
    for (int y = tile.y0; y < tile.y1; y++) {
      float *src = w->rgb + (size_t)(y - tile.y0) * tw * 3;
      uint8_t *dst =
          pixels + ((size_t)(y - job->y0) * width + (tile.x0 - job->x0)) * 3;
      if (job->inv_gamma != 1)
        for (int i = 0; i < tw * 3; i++)
          src[i] = src[i] > 0
                       ? powf(src[i] < 1 ? src[i] : 1.0f, (float)job->inv_gamma)
                       : 0.0f;
      for (int i = 0; i < tw * 3; i++)
        dst[i] = to_byte(src[i]);
    }
    if (job->progress) {
      pthread_mutex_lock(&job->progress_lock);
      job->tiles_done++;
      if (!atomic_load(&job->cancelled) &&
          job->progress(job->progress_user,
                        (double)job->tiles_done / job->tile_count))
        atomic_store(&job->cancelled, 1);
      pthread_mutex_unlock(&job->progress_lock);
    }
  }
  denormals_restore(csr);
  return NULL;
}

static void stats_add(glint_stats *a, const glint_stats *b) {
  a->primary_rays += b->primary_rays;
  a->secondary_rays += b->secondary_rays;
  a->shadow_rays += b->shadow_rays;
  a->reflected_rays += b->reflected_rays;
  a->refracted_rays += b->refracted_rays;
  a->total_internal_reflections += b->total_internal_reflections;
  a->beams += b->beams;
  a->sub_beams += b->sub_beams;
  a->packet_tests += b->packet_tests;
  a->active_lanes += b->active_lanes;
  if (b->generations > a->generations)
    a->generations = b->generations;
  for (int g = 0; g < GLINT_STATS_MAX_GENERATIONS; g++) {
    a->gen_rays[g] += b->gen_rays[g];
    a->gen_packets[g] += b->gen_packets[g];
    a->gen_active_lanes[g] += b->gen_active_lanes[g];
  }
  for (int i = 0; i < 4; i++)
    a->stage_seconds[i] += b->stage_seconds[i];
}

/* glint_render and glint_trace_primary: the same preparation, tiles and
 * threads; primary_only skips shading and leaves *out alone. */
static glint_status run(const glint_scene *scene,
                        const glint_render_settings *settings, int primary_only,
                        glint_image **out, uint64_t *hits,
                        glint_stats *stats_out, glint_error *error) {
  glint_render_settings defaults;
  if (!settings) {
    glint_render_settings_default(&defaults);
    settings = &defaults;
  }
  int width, height;
  glint_status st = validate(scene, settings, &width, &height, error);
  if (st)
    return st;
  glint_backend backend = glint_backend_resolve(settings->backend);
  if (!glint_backend_supported(backend))
    return glint_fail(error, GLINT_E_UNSUPPORTED,
                      "backend '%s' is not supported by this CPU or build",
                      glint_backend_name(backend));
  const glint_backend_ops *ops = backends[backend].ops;

  float(*samples)[2] = malloc(sizeof *samples * (size_t)settings->spp);
  if (!samples)
    return glint_fail(error, GLINT_E_MEMORY, "out of memory");
  glint_sample_offsets(settings->spp, samples);
  glint_frame frame = {width,
                       height,
                       settings->spp,
                       settings->max_depth,
                       settings->math,
                       settings->rcp_newton,
                       settings->accel,
                       glint_scene_epsilon(scene),
                       (const float(*)[2])samples};

  glint_stats stats;
  memset(&stats, 0, sizeof stats);
  stats.backend = backend;
  stats.width = width;
  stats.height = height;
  stats.spp = settings->spp;
  stats.max_depth = settings->max_depth;

  double t0 = glint_now();
  void *prepared = NULL;
  st = ops->prepare(scene, &frame, &prepared, &stats, error);
  stats.prepare_seconds = glint_now() - t0;
  if (st) {
    free(samples);
    return st;
  }

  int rx = 0, ry = 0, rw = width, rh = height;
  if (settings->region_width) {
    rx = settings->region_x, ry = settings->region_y;
    rw = settings->region_width, rh = settings->region_height;
  }
  glint_image *image = NULL;
  if ((st = glint_image_create(rw, rh, &image, error))) {
    ops->release(prepared);
    free(samples);
    return st;
  }

  int tiles_x = (rw + GLINT_TILE_SIZE - 1) / GLINT_TILE_SIZE;
  int tiles_y = (rh + GLINT_TILE_SIZE - 1) / GLINT_TILE_SIZE;
  int threads = settings->threads ? settings->threads : glint_cpu_count();
  if (threads > tiles_x * tiles_y)
    threads = tiles_x * tiles_y;
  stats.threads = threads;

  render_job job;
  job.ops = ops;
  job.prepared = prepared;
  job.image = image;
  job.x0 = rx;
  job.y0 = ry;
  job.x1 = rx + rw;
  job.y1 = ry + rh;
  job.tiles_x = tiles_x;
  job.tile_count = tiles_x * tiles_y;
  job.inv_gamma = 1.0 / settings->gamma;
  atomic_init(&job.next_tile, 0);
  atomic_init(&job.cancelled, 0);
  pthread_mutex_init(&job.progress_lock, NULL);
  job.tiles_done = 0;
  job.progress = settings->progress;
  job.progress_user = settings->progress_user;
  job.primary_only = primary_only;

  worker *workers = calloc((size_t)threads, sizeof *workers);
  pthread_t *tids = calloc((size_t)threads, sizeof *tids);
  size_t scratch = ops->scratch_bytes ? ops->scratch_bytes(prepared) : 0;
  int ok = workers && tids;
  for (int i = 0; ok && i < threads; i++) {
    workers[i].job = &job;
    workers[i].stats = (glint_stats){0};
    workers[i].rgb = glint_aligned_calloc(
        (size_t)GLINT_TILE_SIZE * GLINT_TILE_SIZE * 3, sizeof(float));
    workers[i].scratch = scratch ? glint_aligned_calloc(1, scratch) : NULL;
    ok = workers[i].rgb && (!scratch || workers[i].scratch);
  }

  int started = 0;
  t0 = glint_now();
  if (ok) {
    /* Worker 0 runs on the calling thread. */
    for (int i = 1; i < threads; i++) {
      if (pthread_create(&tids[i], NULL, worker_main, &workers[i]) != 0)
        break; /* the threads that did start take all the tiles */
      started = i;
    }
    worker_main(&workers[0]);
    for (int i = 1; i <= started; i++)
      pthread_join(tids[i], NULL);
  }
  stats.render_seconds = glint_now() - t0;

  uint64_t total_hits = 0;
  for (int i = 0; workers && i < threads; i++) {
    stats_add(&stats, &workers[i].stats);
    total_hits += workers[i].hits;
    glint_aligned_free(workers[i].rgb);
    glint_aligned_free(workers[i].scratch);
  }
  free(workers);
  free(tids);
  pthread_mutex_destroy(&job.progress_lock);
  ops->release(prepared);
  free(samples);

  if (!ok) {
    glint_image_destroy(image);
    return glint_fail(error, GLINT_E_MEMORY,
                      "out of memory allocating per-thread buffers");
  }
  if (atomic_load(&job.cancelled)) {
    glint_image_destroy(image);
    return glint_fail(error, GLINT_E_CANCELLED, "render cancelled");
  }
  if (stats_out)
    *stats_out = stats;
  if (primary_only) {
    glint_image_destroy(image);
    *hits = total_hits;
  } else {
    *out = image;
  }
  return GLINT_OK;
}

glint_status glint_render(const glint_scene *scene,
                          const glint_render_settings *settings,
                          glint_image **out, glint_stats *stats,
                          glint_error *error) {
  return run(scene, settings, 0, out, NULL, stats, error);
}

glint_status glint_trace_primary(const glint_scene *scene,
                                 const glint_render_settings *settings,
                                 uint64_t *hits, glint_stats *stats,
                                 glint_error *error) {
  uint64_t h = 0;
  glint_status st = run(scene, settings, 1, NULL, &h, stats, error);
  if (st == GLINT_OK && hits)
    *hits = h;
  return st;
}
