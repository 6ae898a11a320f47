/* Renderers: a world bound to one backend, a pool of worker threads and
 * their scratch memory, rendering frames. Everything a frame needs is made
 * when the renderer is created (or, for a deeper frame than any before, when
 * that frame starts), so a frame that only moves the camera costs its
 * rendering alone.
 *
 * Tiles are claimed from an atomic counter, so threads balance dynamically;
 * every pixel depends only on its own rays, so a frame is bit-identical for
 * every thread count. */
#include "render/renderer.h"

#include "core/error.h"
#include "core/memory.h"
#include "core/timer.h"
#include "image/image.h"
#include "render/backend.h"
#include "render/thread_pool.h"
#include "render/world.h"
#include "scene/scene.h"

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

/* One worker's own memory, a cache line apart from the next worker's. */
typedef struct render_worker {
  _Alignas(GLI_ALIGN) glint_stats stats;
  uint64_t hits;
  float *rgb;    /* one tile of linear RGB */
  void *scratch; /* the backend's, for frames up to scratch_depth (NULL:
                    not made yet, see prepare_workers) */
} render_worker;

/* The frame being rendered, shared by the workers. */
typedef struct frame_job {
  frame_params params;
  int x0, y0, x1, y1; /* the region rendered, in frame pixels */
  int tiles_x, tile_count;
  frame_output *out;
  const gli_byte_encoding *encoding; /* of out->image */
  glint_progress_fn progress;
  void *progress_user;
  glint_tile_fn tile;
  void *tile_user;
  atomic_int next_tile;
  atomic_int cancelled;
  pthread_mutex_t report_lock; /* callbacks never run two at once */
  int tiles_done;
} frame_job;

struct glint_renderer {
  glint_world *world;
  glint_render_settings settings; /* the defaults of each frame */
  glint_backend backend;
  const gli_backend_ops *ops;
  const data_ops *layout;
  gli_bvh no_bvh; /* what --accel none traverses: nothing */
  void *view;
  thread_pool *pool;
  int workers;
  render_worker *worker;
  int scratch_depth; /* the deepest frame the scratch holds */
  float (*samples)[2];
  int samples_spp; /* the count `samples` holds offsets for */
  /* The 8-bit encoding of the last frame with an image (gamma 0, none,
   * after calloc), kept while frames keep their gamma. */
  gli_byte_encoding encoding;
  frame_job job;
  /* Set while a frame renders or the world changes: a call that overlaps
   * one (from another thread, or from a tile callback) is refused rather
   * than left to hang on the pool or overwrite the frame's job. */
  atomic_int busy;
};

/* Claims the renderer for one call, or says why it cannot. */
static glint_status claim(glint_renderer *r, const char *what, glint_error *e) {
  if (atomic_exchange(&r->busy, 1))
    return gli_fail(e, GLINT_E_ARGUMENT,
                    "%s: the renderer is busy with another call (calls on "
                    "one renderer must not overlap; a tile or progress "
                    "callback must not call its own renderer)",
                    what);
  return GLINT_OK;
}

static glint_status release(glint_renderer *r, glint_status st) {
  atomic_store(&r->busy, 0);
  return st;
}

/* ---- validation ---------------------------------------------------------- */

/* What every frame is checked against: the size, depth, samples and region
 * that glint_render_settings and glint_frame_settings share. */
static glint_status frame_check(int w, int h, int depth, int spp, int rx,
                                int ry, int rw, int rh, glint_error *e) {
  if (w < 1 || w > GLINT_MAX_DIMENSION)
    return gli_fail(e, GLINT_E_ARGUMENT, "width %d is outside 1..%d", w,
                    GLINT_MAX_DIMENSION);
  if (h < 1 || h > GLINT_MAX_DIMENSION)
    return gli_fail(e, GLINT_E_ARGUMENT, "height %d is outside 1..%d", h,
                    GLINT_MAX_DIMENSION);
  if (depth < 1 || depth > GLINT_MAX_DEPTH)
    return gli_fail(e, GLINT_E_ARGUMENT, "depth %d is outside 1..%d", depth,
                    GLINT_MAX_DEPTH);
  if (spp < 1 || spp > GLINT_MAX_SPP)
    return gli_fail(e, GLINT_E_ARGUMENT,
                    "samples per pixel %d is outside 1..%d", spp,
                    GLINT_MAX_SPP);
  if (rw == 0 && rh == 0) { /* the whole frame: nothing else may be said */
    if (rx != 0 || ry != 0)
      return gli_fail(e, GLINT_E_ARGUMENT,
                      "region at %d,%d has no size (its width and height "
                      "are 0; all four 0 render the whole image)",
                      rx, ry);
    return GLINT_OK;
  }
  if (rw < 1 || rh < 1)
    return gli_fail(e, GLINT_E_ARGUMENT,
                    "region %dx%d: its width and height must both be at "
                    "least 1 (both 0, and its corner 0,0, render the whole "
                    "image)",
                    rw, rh);
  if (rx < 0 || ry < 0 || rx > w - rw || ry > h - rh)
    return gli_fail(e, GLINT_E_ARGUMENT,
                    "region %d,%d %dx%d is not inside the %dx%d image", rx, ry,
                    rw, rh, w, h);
  return GLINT_OK;
}

glint_status gli_render_settings_check(const glint_render_settings *s,
                                       int scene_width, int scene_height,
                                       glint_error *e) {
  glint_status st = frame_check(s->width ? s->width : scene_width,
                                s->height ? s->height : scene_height,
                                s->max_depth, s->spp, s->region_x, s->region_y,
                                s->region_width, s->region_height, e);
  if (st)
    return st;
  if (s->threads < 0 || s->threads > GLINT_MAX_THREADS)
    return gli_fail(e, GLINT_E_ARGUMENT, "threads %d is outside 0..%d",
                    s->threads, GLINT_MAX_THREADS);
  if (gli_gamma_check(s->gamma, e))
    return GLINT_E_ARGUMENT;
  if ((unsigned)s->math >= GLINT_MATH_COUNT)
    return gli_fail(e, GLINT_E_ARGUMENT, "unknown math variant %d",
                    (int)s->math);
  if (s->rcp_newton != 0 && s->rcp_newton != 1)
    return gli_fail(e, GLINT_E_ARGUMENT, "rcp_newton %d is neither 0 nor 1",
                    s->rcp_newton);
  if ((unsigned)s->accel >= GLINT_ACCEL_COUNT)
    return gli_fail(e, GLINT_E_ARGUMENT, "unknown acceleration %d",
                    (int)s->accel);
  if ((unsigned)s->backend >= GLINT_BACKEND_COUNT)
    return gli_fail(e, GLINT_E_ARGUMENT, "unknown backend %d", (int)s->backend);
  return GLINT_OK;
}

/* ---- creation ------------------------------------------------------------ */

/* How the renderer's layout walks the BVH: a backend whose rays never walk
 * alone walks the binary tree, and needs no leaf blocks. */
static glint_accel walk_of(const glint_renderer *r) {
  return !r->ops->walks_alone && r->settings.accel != GLINT_ACCEL_NONE
             ? GLINT_ACCEL_BVH2
             : r->settings.accel;
}

/* The buffers of the first `count` workers, those a frame of `count` tiles
 * or more sets to work: each one's tile of pixels and, where `scratch`, the
 * backend's scratch for frames up to `depth` (the stream backends' buffers
 * grow with the depth; the beams need none). Made when a frame first needs
 * them and kept for the frames after, so that memory follows the threads
 * that work, not the threads there are: every thread's ray streams made at
 * once took 1.9 GB for a 16x16 image with 1 024 threads. */
static glint_status prepare_workers(glint_renderer *r, int count, int depth,
                                    int scratch, glint_error *error) {
  if (scratch && r->ops->scratch_bytes && depth > r->scratch_depth) {
    for (int i = 0; i < r->workers; i++) {
      gli_aligned_free(r->worker[i].scratch);
      r->worker[i].scratch = NULL;
    }
    r->scratch_depth = depth;
  }
  size_t bytes = scratch && r->ops->scratch_bytes
                     ? r->ops->scratch_bytes(r->scratch_depth)
                     : 0;
  for (int i = 0; i < count; i++) {
    render_worker *w = &r->worker[i];
    if (!w->rgb &&
        !(w->rgb = gli_aligned_calloc((size_t)GLI_TILE_SIZE * GLI_TILE_SIZE * 3,
                                      sizeof(float))))
      return gli_fail(error, GLINT_E_MEMORY,
                      "out of memory for %d threads' buffers", count);
    if (bytes && !w->scratch && !(w->scratch = gli_aligned_calloc(1, bytes)))
      return gli_fail(error, GLINT_E_MEMORY,
                      "out of memory for %d threads' ray streams", count);
  }
  return GLINT_OK;
}

/* The tiles of a frame of w x h pixels. */
static int tiles_of(int w, int h) {
  return ((w + GLI_TILE_SIZE - 1) / GLI_TILE_SIZE) *
         ((h + GLI_TILE_SIZE - 1) / GLI_TILE_SIZE);
}

glint_status glint_renderer_create(glint_world *world,
                                   const glint_render_settings *settings,
                                   glint_renderer **out, glint_error *error) {
  GLI_NOT_NULL(world, "world", error);
  GLI_NOT_NULL(out, "renderer", error);
  glint_render_settings defaults;
  if (!settings) {
    glint_render_settings_default(&defaults);
    settings = &defaults;
  }
  glint_status st = gli_render_settings_check(settings, world->scene->width,
                                              world->scene->height, error);
  if (st)
    return st;
  glint_backend backend =
      glint_backend_choose(settings->backend, world->scene, settings);
  /* STREAM resolves to scalar-float where there is no stream backend: that
   * stand-in is refused, as glint_backend_supported(STREAM) says. */
  glint_backend missing =
      !glint_backend_supported(settings->backend) ? settings->backend : backend;
  if (!glint_backend_supported(missing))
    return gli_fail(error, GLINT_E_UNSUPPORTED,
                    "backend '%s' is not supported by this CPU or build",
                    glint_backend_name(missing));

  glint_renderer *r = calloc(1, sizeof *r);
  if (!r)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  gli_world_retain(world);
  r->world = world;
  r->settings = *settings;
  r->backend = backend;
  r->ops = gli_backend_ops_of(backend);
  r->layout = gli_data_ops_of(r->ops->data);
  pthread_mutex_init(&r->job.report_lock, NULL);

  const void *data = NULL;
  const gli_bvh *bvh = &r->no_bvh;
  if ((st = gli_world_data(world, r->ops->data, &data, error)) ||
      (settings->accel != GLINT_ACCEL_NONE &&
       (st = gli_world_bvh(world, walk_of(r) == GLINT_ACCEL_BVH8, &bvh,
                           error))) ||
      (st = r->layout->bind(data, bvh, walk_of(r), &r->view, error))) {
    glint_renderer_destroy(r);
    return st;
  }

  int threads = settings->threads ? settings->threads : glint_cpu_count();
  if ((st = gli_thread_pool_create(threads, &r->pool, error))) {
    glint_renderer_destroy(r);
    return st;
  }
  r->workers = gli_thread_pool_size(r->pool);
  r->worker = gli_aligned_calloc((size_t)r->workers, sizeof *r->worker);
  r->samples = malloc(sizeof *r->samples * GLINT_MAX_SPP);
  if (!r->worker || !r->samples) {
    glint_renderer_destroy(r);
    return gli_fail(error, GLINT_E_MEMORY,
                    "out of memory for %d threads' buffers", threads);
  }
  /* The workers a frame of the settings' own size sets to work, so that
   * memory it cannot have is refused here, before any frame. */
  int tiles =
      settings->region_width
          ? tiles_of(settings->region_width, settings->region_height)
          : tiles_of(settings->width ? settings->width : world->scene->width,
                     settings->height ? settings->height
                                      : world->scene->height);
  if ((st = prepare_workers(r, r->workers < tiles ? r->workers : tiles,
                            settings->max_depth, 1, error))) {
    glint_renderer_destroy(r);
    return st;
  }
  *out = r;
  return GLINT_OK;
}

static glint_status set_world(glint_renderer *r, glint_world *world,
                              glint_error *error) {
  const void *data = NULL;
  const gli_bvh *bvh = &r->no_bvh;
  void *view = NULL;
  glint_status st;
  if ((st = gli_world_data(world, r->ops->data, &data, error)) ||
      (r->settings.accel != GLINT_ACCEL_NONE &&
       (st = gli_world_bvh(world, walk_of(r) == GLINT_ACCEL_BVH8, &bvh,
                           error))) ||
      (st = r->layout->bind(data, bvh, walk_of(r), &view, error)))
    return st;
  if (r->view)
    r->layout->unbind(r->view);
  r->view = view;
  gli_world_retain(world);
  gli_world_release(r->world);
  r->world = world;
  return GLINT_OK;
}

glint_status glint_renderer_set_world(glint_renderer *r, glint_world *world,
                                      glint_error *error) {
  GLI_NOT_NULL(r, "renderer", error);
  GLI_NOT_NULL(world, "world", error);
  glint_status st = claim(r, "glint_renderer_set_world", error);
  return st ? st : release(r, set_world(r, world, error));
}

void glint_renderer_destroy(glint_renderer *r) {
  if (!r)
    return;
  gli_thread_pool_destroy(r->pool);
  for (int i = 0; r->worker && i < r->workers; i++) {
    gli_aligned_free(r->worker[i].rgb);
    gli_aligned_free(r->worker[i].scratch);
  }
  gli_aligned_free(r->worker);
  free(r->samples);
  if (r->view)
    r->layout->unbind(r->view);
  pthread_mutex_destroy(&r->job.report_lock);
  gli_world_release(r->world);
  free(r);
}

void glint_frame_settings_default(glint_frame_settings *frame) {
  if (frame)
    memset(frame, 0, sizeof *frame);
}

/* ---- the workers --------------------------------------------------------- */

/* Tiny intermediate values (a highlight's power far from its peak, Beer's law
 * over a long path) are denormal numbers, whose arithmetic costs a microcode
 * assist of ~100 cycles on x86. Like most renderers, glint flushes them to
 * zero while it renders (FTZ and DAZ in MXCSR): they are far below one 8-bit
 * level. Each worker restores its thread's mode after the frame. */
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

/* Copies a finished tile into the film and the 8-bit image. */
/* A tile's values made finite before anyone sees them: within the limits
 * of glint.h a pixel can still overflow single precision (kr = kt = 1e6
 * for five bounces), and a film of infinities, or of NaN where one met a
 * zero weight, poisons whatever reads it (.pfm, .exr, a compositor). The
 * largest float stands for an overflow, 0 for NaN. */
static void keep_finite(float *rgb, size_t n) {
  /* First whether any value is infinite or NaN (exponent bits all set): a
   * loop the compiler vectorises, so that finite tiles, nearly all, cost
   * about a tenth of what testing and fixing each value in one loop did
   * (2% of a small render). */
  uint32_t any = 0;
  for (size_t i = 0; i < n; i++) {
    uint32_t bits;
    memcpy(&bits, &rgb[i], sizeof bits);
    any |= (bits & 0x7f800000u) == 0x7f800000u;
  }
  if (!any)
    return;
  for (size_t i = 0; i < n; i++)
    if (!(rgb[i] <= FLT_MAX))
      rgb[i] = rgb[i] > 0 ? FLT_MAX : 0;
}

static void store_tile(const frame_job *job, const tile_rect *t,
                       const float *rgb) {
  size_t tw = (size_t)(t->x1 - t->x0);
  for (int y = t->y0; y < t->y1; y++) {
    const float *src = rgb + (size_t)(y - t->y0) * tw * 3;
    size_t row = (size_t)(y - job->y0), col = (size_t)(t->x0 - job->x0);
    if (job->out->film) {
      glint_film *f = job->out->film;
      memcpy(f->rgb + (row * (size_t)f->width + col) * 3, src,
             tw * 3 * sizeof *src);
    }
    if (job->out->image) {
      glint_image *im = job->out->image;
      gli_byte_encode(job->encoding, src,
                      im->rgb + (row * (size_t)im->width + col) * 3, tw * 3);
    }
  }
}

/* Hands the tile to the caller's callbacks, one at a time: its pixels in
 * the film, or without a film the worker's own copy (`rgb`). */
static void report_tile(frame_job *job, const tile_rect *t, const float *rgb) {
  if (!job->progress && !job->tile)
    return;
  pthread_mutex_lock(&job->report_lock);
  job->tiles_done++;
  if (!atomic_load(&job->cancelled)) {
    int cancel = 0;
    if (job->tile) {
      glint_film *f = job->out->film;
      glint_tile tile = {t->x0,         t->y0, t->x1 - t->x0,
                         t->y1 - t->y0, rgb,   (size_t)(t->x1 - t->x0) * 3};
      if (f) {
        tile.stride = (size_t)f->width * 3;
        tile.pixels = f->rgb + ((size_t)(t->y0 - job->y0) * (size_t)f->width +
                                (size_t)(t->x0 - job->x0)) *
                                   3;
      }
      cancel = job->tile(job->tile_user, &tile);
    }
    if (!cancel && job->progress)
      cancel = job->progress(job->progress_user,
                             (double)job->tiles_done / job->tile_count);
    if (cancel)
      atomic_store(&job->cancelled, 1);
  }
  pthread_mutex_unlock(&job->report_lock);
}

static void work(void *arg, int index) {
  glint_renderer *r = arg;
  frame_job *job = &r->job;
  render_worker *w = &r->worker[index];
  unsigned csr = denormals_off();
  while (!atomic_load(&job->cancelled)) {
    int i = atomic_fetch_add(&job->next_tile, 1);
    if (i >= job->tile_count)
      break;
    tile_rect t;
    t.x0 = job->x0 + (i % job->tiles_x) * GLI_TILE_SIZE;
    t.y0 = job->y0 + (i / job->tiles_x) * GLI_TILE_SIZE;
    t.x1 = t.x0 + GLI_TILE_SIZE < job->x1 ? t.x0 + GLI_TILE_SIZE : job->x1;
    t.y1 = t.y0 + GLI_TILE_SIZE < job->y1 ? t.y0 + GLI_TILE_SIZE : job->y1;
    if (job->out->primary_only) {
      w->hits += r->ops->primary_tile(r->view, &job->params, &t, &w->stats);
      continue;
    }
    r->ops->render_tile(r->view, &job->params, &t, w->scratch, w->rgb,
                        &w->stats);
    keep_finite(w->rgb, (size_t)(t.x1 - t.x0) * (size_t)(t.y1 - t.y0) * 3);
    store_tile(job, &t, w->rgb);
    report_tile(job, &t, w->rgb);
  }
  denormals_restore(csr);
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
  a->alone_walks += b->alone_walks;
  a->alone_tests += b->alone_tests;
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

/* ---- frames -------------------------------------------------------------- */

static int pick(int frame_value, int renderer_value) {
  return frame_value ? frame_value : renderer_value;
}

static glint_status render_frame(glint_renderer *r,
                                 const glint_frame_settings *frame,
                                 frame_output *out, glint_stats *stats_out,
                                 glint_error *error) {
  glint_frame_settings none;
  if (!frame) {
    glint_frame_settings_default(&none);
    frame = &none;
  }
  const glint_render_settings *s = &r->settings;
  const glint_scene *scene = r->world->scene;
  int width = pick(frame->width, pick(s->width, scene->width));
  int height = pick(frame->height, pick(s->height, scene->height));
  int depth = pick(frame->max_depth, s->max_depth);
  int spp = pick(frame->spp, s->spp);
  int own_region = frame->region_width || frame->region_height ||
                   frame->region_x || frame->region_y;
  int rx = own_region ? frame->region_x : s->region_x;
  int ry = own_region ? frame->region_y : s->region_y;
  int rw = own_region ? frame->region_width : s->region_width;
  int rh = own_region ? frame->region_height : s->region_height;
  glint_status st =
      frame_check(width, height, depth, spp, rx, ry, rw, rh, error);
  if (st)
    return st;
  int first = frame->sample_first, count = frame->sample_count;
  if (first < 0 || first >= spp)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "sample_first %d is not among the %d samples of the "
                    "pattern (0..%d)",
                    first, spp, spp - 1);
  if (count < 0 || count > spp - first)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "sample_count %d is not 0..%d: the pattern has %d "
                    "samples, and %d of them from sample_first %d",
                    count, spp - first, spp, spp - first, first);
  if (count == 0)
    count = spp - first;
  if (!rw)
    rx = 0, ry = 0, rw = width, rh = height;
  const glint_camera *camera = frame->camera ? frame->camera : &scene->camera;
  if (frame->camera && (st = gli_camera_check(camera, error)))
    return st;
  if (out->film && (out->film->width != rw || out->film->height != rh))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "a %dx%d film cannot hold a %dx%d frame", out->film->width,
                    out->film->height, rw, rh);
  int tiles = tiles_of(rw, rh);
  int workers = r->workers < tiles ? r->workers : tiles;
  if ((st = prepare_workers(r, workers, depth, !out->primary_only, error)))
    return st;
  if (spp != r->samples_spp) {
    gli_sample_offsets(spp, r->samples);
    r->samples_spp = spp;
  }

  frame_job *job = &r->job;
  gli_camera_basis_init(&job->params.camera, camera, width, height);
  /* The epsilon of the frame's camera: the world's was of its own (a camera
   * committed far away made one so large that whole spheres were lost
   * from a near one, and one committed near left acne on a far view). */
  r->layout->set_epsilon(r->view,
                         gli_epsilon_at(r->world->extent, camera->from));
  job->params.spp = count;
  job->params.max_depth = depth;
  job->params.math = s->math;
  job->params.rcp_newton = s->rcp_newton;
  job->params.samples = (const float(*)[2])r->samples + first;
  job->x0 = rx;
  job->y0 = ry;
  job->x1 = rx + rw;
  job->y1 = ry + rh;
  job->tiles_x = (rw + GLI_TILE_SIZE - 1) / GLI_TILE_SIZE;
  job->tile_count = tiles;
  job->out = out;
  if (out->image && r->encoding.gamma != out->gamma)
    gli_byte_encoding_init(&r->encoding, out->gamma);
  job->encoding = &r->encoding;
  job->progress = frame->progress ? frame->progress : s->progress;
  job->progress_user =
      frame->progress ? frame->progress_user : s->progress_user;
  job->tile = frame->tile;
  job->tile_user = frame->tile_user;
  atomic_store(&job->next_tile, 0);
  atomic_store(&job->cancelled, 0);
  job->tiles_done = 0;

  for (int i = 0; i < workers; i++) {
    memset(&r->worker[i].stats, 0, sizeof r->worker[i].stats);
    r->worker[i].hits = 0;
  }
  double t0 = gli_now();
  gli_thread_pool_run(r->pool, workers, work, r);
  double seconds = gli_now() - t0;

  glint_stats stats;
  memset(&stats, 0, sizeof stats);
  out->hits = 0;
  for (int i = 0; i < workers; i++) {
    stats_add(&stats, &r->worker[i].stats);
    out->hits += r->worker[i].hits;
  }
  if (atomic_load(&job->cancelled))
    return gli_fail(error, GLINT_E_CANCELLED, "render cancelled");
  if (stats_out) {
    gli_world_stats(r->world, &stats);
    stats.prepare_seconds = 0; /* a frame prepares nothing */
    stats.backend = r->backend;
    stats.width = width;
    stats.height = height;
    stats.spp = spp;
    stats.max_depth = depth;
    stats.threads = workers;
    stats.render_seconds = seconds;
    stats.stream_bytes_per_thread =
        r->ops->scratch_bytes ? r->ops->scratch_bytes(depth) : 0;
    *stats_out = stats;
  }
  return GLINT_OK;
}

glint_status gli_renderer_render(glint_renderer *r,
                                 const glint_frame_settings *frame,
                                 frame_output *out, glint_stats *stats_out,
                                 glint_error *error) {
  glint_status st = claim(r, "glint_renderer_render", error);
  return st ? st : release(r, render_frame(r, frame, out, stats_out, error));
}

glint_status glint_renderer_render(glint_renderer *r,
                                   const glint_frame_settings *frame,
                                   glint_film *film, glint_stats *stats,
                                   glint_error *error) {
  GLI_NOT_NULL(r, "renderer", error);
  if (!film && !(frame && frame->tile))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "no film to render into and no tile callback");
  frame_output out = {film, NULL, 1, 0, 0};
  return gli_renderer_render(r, frame, &out, stats, error);
}
