/* Worlds, renderers and films (include/glint.h, "Worlds and renderers"),
 * through the public API alone:
 *  - a frame through a renderer is the image glint_render makes, for every
 *    backend this CPU has, and for a moved camera, a region, other depths
 *    and sample counts;
 *  - a committed world does not change when its scene is edited or
 *    destroyed, and outlives glint_world_destroy while a renderer holds it;
 *  - the tile callback hands over every pixel exactly once, with the film's
 *    final values, and cancels the frame when it asks to;
 *  - two renderers of one world render at the same time on two threads;
 *  - a thread with a small stack renders as deep as the renderer goes;
 *  - memory follows the threads a frame sets to work, not the threads;
 *  - each bad argument is refused with a message. */
#include "test_util.h"

#include <limits.h>
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define W 96
#define H 72

static glint_scene *whitted(void) {
  glint_scene *s;
  ASSERT_OK(glint_scene_builtin("whitted", &s, &e_));
  return s;
}

static glint_render_settings settings_for(glint_backend b) {
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.width = W;
  rs.height = H;
  rs.backend = b;
  rs.threads = 2;
  return rs;
}

/* The film converted as glint_render converts it (gamma 1). */
static void assert_film_is_image(const glint_film *film, glint_image *image) {
  glint_image *converted;
  ASSERT_OK(glint_image_create(glint_film_width(film), glint_film_height(film),
                               &converted, &e_));
  ASSERT_OK(glint_film_to_image(film, 1, converted, &e_));
  assert_int_equal(glint_image_width(converted), glint_image_width(image));
  assert_int_equal(glint_image_height(converted), glint_image_height(image));
  size_t n = (size_t)glint_image_width(image) * glint_image_height(image) * 3;
  assert_memory_equal(glint_image_pixels(converted), glint_image_pixels(image),
                      n);
  glint_image_destroy(converted);
}

/* A camera orbiting the scene's own, a little further each frame. */
static glint_camera orbit(const glint_camera *c, int frame) {
  glint_camera moved = *c;
  double a = 0.05 * frame, dx = c->from.x - c->at.x, dz = c->from.z - c->at.z;
  moved.from.x = c->at.x + dx * cos(a) - dz * sin(a);
  moved.from.z = c->at.z + dx * sin(a) + dz * cos(a);
  return moved;
}

static void frames_equal_glint_render(void **state) {
  (void)state;
  glint_scene *scene = whitted();
  glint_scene_info info;
  glint_scene_get_info(scene, &info);
  for (int b = GLINT_BACKEND_SCALAR_FLOAT; b < GLINT_BACKEND_COUNT; b++) {
    if (b == GLINT_BACKEND_STREAM || backend_missing(b))
      continue;
    glint_render_settings rs = settings_for(b);
    glint_world *world;
    glint_renderer *renderer;
    glint_film *film;
    ASSERT_OK(glint_world_commit(scene, &world, NULL, &e_));
    ASSERT_OK(glint_renderer_create(world, &rs, &renderer, &e_));
    ASSERT_OK(glint_film_create(W, H, &film, &e_));
    /* Frames with the camera moving, the depth and samples changing. */
    for (int f = 0; f < 4; f++) {
      glint_camera cam = orbit(&info.camera, f);
      glint_frame_settings fs;
      glint_frame_settings_default(&fs);
      fs.camera = &cam;
      fs.max_depth = 1 + 3 * f;
      fs.spp = f % 2 ? 1 : 5;
      ASSERT_OK(glint_renderer_render(renderer, &fs, film, NULL, &e_));
      glint_scene *moved = whitted();
      ASSERT_OK(glint_scene_set_camera(moved, &cam, &e_));
      glint_render_settings one = rs;
      one.max_depth = fs.max_depth;
      one.spp = fs.spp;
      glint_image *image;
      ASSERT_OK(glint_render(moved, &one, &image, NULL, &e_));
      assert_film_is_image(film, image);
      glint_image_destroy(image);
      glint_scene_destroy(moved);
    }
    /* A region of the frame: the same pixels, cropped. (In 8 bits: the
     * beams group a region's pixels into packets differently from the
     * whole frame's, which may change a float's last bit.) */
    glint_film *part;
    ASSERT_OK(glint_film_create(20, 10, &part, &e_));
    glint_frame_settings fs;
    glint_frame_settings_default(&fs);
    fs.region_x = 33, fs.region_y = 17, fs.region_width = 20,
    fs.region_height = 10;
    ASSERT_OK(glint_renderer_render(renderer, &fs, part, NULL, &e_));
    rs.region_x = 33, rs.region_y = 17, rs.region_width = 20,
    rs.region_height = 10;
    glint_image *cropped;
    ASSERT_OK(glint_render(scene, &rs, &cropped, NULL, &e_));
    assert_film_is_image(part, cropped);
    glint_image_destroy(cropped);
    glint_film_destroy(part);
    glint_film_destroy(film);
    glint_renderer_destroy(renderer);
    glint_world_destroy(world);
  }
  glint_scene_destroy(scene);
}

/* A frame's own camera gets its own epsilon (docs/specification.md §3: it
 * scales with the camera's distance as well as the scene's): a world
 * committed with the camera far away, rendered from near, lost both
 * spheres to the far camera's epsilon, and one committed near, rendered
 * from far, showed acne. Each frame equals glint_render of the scene with
 * that camera, for every backend, whichever camera the world had. */
static void frame_cameras_have_their_own_epsilon(void **state) {
  (void)state;
  glint_scene *scene = whitted();
  glint_scene_info info;
  glint_scene_get_info(scene, &info);
  glint_camera cams[3] = {info.camera, info.camera, info.camera};
  cams[1].from.z = 1e5; /* the same look, from far */
  /* the near view from 1e4 away, zoomed in to the same picture */
  cams[2].from = (glint_vec3){0, 1241.6, 9922.8};
  cams[2].fov_x_degrees = 0.04;
  for (int b = GLINT_BACKEND_SCALAR_FLOAT; b < GLINT_BACKEND_COUNT; b++) {
    if (b == GLINT_BACKEND_STREAM || backend_missing(b))
      continue;
    glint_render_settings rs = settings_for(b);
    rs.spp = 1;
    for (int committed = 0; committed < 2; committed++) {
      glint_scene *at = whitted();
      ASSERT_OK(glint_scene_set_camera(at, &cams[committed], &e_));
      glint_world *world;
      glint_renderer *renderer;
      glint_film *film;
      ASSERT_OK(glint_world_commit(at, &world, NULL, &e_));
      ASSERT_OK(glint_renderer_create(world, &rs, &renderer, &e_));
      ASSERT_OK(glint_film_create(W, H, &film, &e_));
      for (int c = 0; c < 3; c++) {
        glint_frame_settings fs;
        glint_frame_settings_default(&fs);
        fs.camera = &cams[c];
        ASSERT_OK(glint_renderer_render(renderer, &fs, film, NULL, &e_));
        ASSERT_OK(glint_scene_set_camera(at, &cams[c], &e_));
        glint_image *image;
        ASSERT_OK(glint_render(at, &rs, &image, NULL, &e_));
        assert_film_is_image(film, image);
        glint_image_destroy(image);
      }
      glint_film_destroy(film);
      glint_renderer_destroy(renderer);
      glint_world_destroy(world);
      glint_scene_destroy(at);
    }
  }
  glint_scene_destroy(scene);
}

/* Materials within glint.h's limits can still overflow single precision
 * (kr = kt = 1e6, two nested spheres, five bounces: about 1e30 a bounce);
 * every backend's film stays finite, an overflow held at FLT_MAX (or, in the
 * streams, at 2^64 times what a hit brings). */
static void films_stay_finite(void **state) {
  (void)state;
  glint_scene *s;
  ASSERT_OK(glint_scene_create(&s, &e_));
  glint_material m;
  glint_material_default(&m);
  m.ks = 0;
  m.kr = m.kt = 1e6;
  m.ior = 1.5;
  uint32_t id;
  ASSERT_OK(glint_scene_add_material(s, &m, &id, &e_));
  ASSERT_OK(glint_scene_set_ambient(s, (glint_vec3){0.1, 0.1, 0.1}, &e_));
  ASSERT_OK(glint_scene_add_light(s, (glint_vec3){3, 5, 5},
                                  (glint_vec3){1, 1, 1}, &e_));
  ASSERT_OK(glint_scene_add_sphere(s, (glint_vec3){0, 0, 0}, 2, id, &e_));
  ASSERT_OK(glint_scene_add_sphere(s, (glint_vec3){0, 0, 0}, 1, id, &e_));
  for (int b = GLINT_BACKEND_SCALAR_FLOAT; b < GLINT_BACKEND_COUNT; b++) {
    if (b == GLINT_BACKEND_STREAM || backend_missing(b))
      continue;
    glint_render_settings rs = settings_for(b);
    rs.max_depth = 5;
    glint_world *world;
    glint_renderer *renderer;
    glint_film *film;
    ASSERT_OK(glint_world_commit(s, &world, NULL, &e_));
    ASSERT_OK(glint_renderer_create(world, &rs, &renderer, &e_));
    ASSERT_OK(glint_film_create(W, H, &film, &e_));
    ASSERT_OK(glint_renderer_render(renderer, NULL, film, NULL, &e_));
    const float *px = glint_film_pixels_const(film);
    int overflowed = 0;
    for (int i = 0; i < W * H * 3; i++) {
      if (!isfinite(px[i]))
        fail_msg("%s: film value %d is %g", glint_backend_name(b), i, px[i]);
      /* held at FLT_MAX; the streams, whose weights are held at 2^64
       * (render/frame.h), add 2^64 times what a hit brings instead */
      overflowed += px[i] >= 0x1p64f;
    }
    assert_true(overflowed > 0); /* the case this test is about */
    glint_film_destroy(film);
    glint_renderer_destroy(renderer);
    glint_world_destroy(world);
  }
  glint_scene_destroy(s);
}

/* Editing or destroying the scene after the commit changes nothing; the
 * world outlives glint_world_destroy while its renderer holds it. */
static void worlds_are_independent_of_their_scene(void **state) {
  (void)state;
  glint_scene *scene = whitted();
  glint_render_settings rs = settings_for(GLINT_BACKEND_AUTO);
  glint_image *before;
  ASSERT_OK(glint_render(scene, &rs, &before, NULL, &e_));
  glint_world *world;
  glint_stats stats;
  ASSERT_OK(glint_world_commit(scene, &world, &stats, &e_));
  assert_true(stats.scene_bytes > 0);
  glint_renderer *renderer;
  ASSERT_OK(glint_renderer_create(world, &rs, &renderer, &e_));
  glint_world_destroy(world);
  ASSERT_OK(glint_scene_set_background(scene, (glint_vec3){1, 0, 1}, &e_));
  ASSERT_OK(glint_scene_add_light(scene, (glint_vec3){0, 5, 0},
                                  (glint_vec3){1, 1, 1}, &e_));
  glint_scene_destroy(scene);
  glint_film *film;
  ASSERT_OK(glint_film_create(W, H, &film, &e_));
  ASSERT_OK(glint_renderer_render(renderer, NULL, film, &stats, &e_));
  assert_film_is_image(film, before);
  assert_int_equal(stats.width, W);
  assert_int_equal(stats.primary_rays, (uint64_t)W * H * 5);
  assert_true(stats.prepare_seconds == 0);
  glint_film_destroy(film);
  glint_image_destroy(before);
  glint_renderer_destroy(renderer);
}

typedef struct tile_log {
  glint_film *film;
  int *covered; /* per pixel: how many tiles held it */
  float *copy;  /* the pixels as the callback saw them */
  int tiles, cancel_after;
} tile_log;

static int on_tile(void *user, const glint_tile *t) {
  tile_log *log = user;
  for (int y = 0; y < t->height; y++)
    for (int x = 0; x < t->width; x++) {
      size_t i = (size_t)(t->y + y) * W + (size_t)(t->x + x);
      log->covered[i]++;
      memcpy(log->copy + i * 3, t->pixels + (size_t)y * t->stride + x * 3,
             3 * sizeof(float));
    }
  log->tiles++;
  return log->cancel_after && log->tiles >= log->cancel_after;
}

static void tiles_cover_the_frame_once(void **state) {
  (void)state;
  glint_scene *scene = whitted();
  glint_world *world;
  glint_renderer *renderer;
  ASSERT_OK(glint_world_commit(scene, &world, NULL, &e_));
  glint_scene_destroy(scene);
  glint_render_settings rs = settings_for(GLINT_BACKEND_AUTO);
  ASSERT_OK(glint_renderer_create(world, &rs, &renderer, &e_));
  glint_world_destroy(world);
  tile_log log = {0};
  ASSERT_OK(glint_film_create(W, H, &log.film, &e_));
  log.covered = calloc(W * H, sizeof *log.covered);
  log.copy = calloc(W * H * 3, sizeof *log.copy);
  glint_frame_settings fs;
  glint_frame_settings_default(&fs);
  fs.tile = on_tile;
  fs.tile_user = &log;
  ASSERT_OK(glint_renderer_render(renderer, &fs, log.film, NULL, &e_));
  for (int i = 0; i < W * H; i++)
    assert_int_equal(log.covered[i], 1);
  assert_memory_equal(log.copy, glint_film_pixels(log.film),
                      W * H * 3 * sizeof(float));
  assert_int_equal(log.tiles, 6 * 5); /* 16x16 tiles */

  /* Cancelling from the callback. */
  memset(log.covered, 0, W * H * sizeof *log.covered);
  log.tiles = 0;
  log.cancel_after = 3;
  glint_error e;
  assert_int_equal(glint_renderer_render(renderer, &fs, log.film, NULL, &e),
                   GLINT_E_CANCELLED);
  assert_int_equal(log.tiles, 3);
  /* ...and the renderer renders the next frame whole. */
  log.cancel_after = 0;
  log.tiles = 0;
  ASSERT_OK(glint_renderer_render(renderer, &fs, log.film, NULL, &e_));
  assert_int_equal(log.tiles, 30);
  free(log.covered);
  free(log.copy);
  glint_film_destroy(log.film);
  glint_renderer_destroy(renderer);
}

typedef struct parallel_job {
  glint_world *world;
  glint_film *film;
  glint_status status;
} parallel_job;

static void *render_on_thread(void *arg) {
  parallel_job *job = arg;
  glint_render_settings rs = settings_for(GLINT_BACKEND_AUTO);
  glint_renderer *renderer;
  glint_error e;
  job->status = glint_renderer_create(job->world, &rs, &renderer, &e);
  for (int f = 0; job->status == GLINT_OK && f < 3; f++)
    job->status = glint_renderer_render(renderer, NULL, job->film, NULL, &e);
  glint_renderer_destroy(renderer);
  return NULL;
}

static void renderers_share_a_world(void **state) {
  (void)state;
  glint_scene *scene = whitted();
  glint_world *world;
  ASSERT_OK(glint_world_commit(scene, &world, NULL, &e_));
  parallel_job jobs[2];
  pthread_t threads[2];
  for (int i = 0; i < 2; i++) {
    jobs[i].world = world;
    ASSERT_OK(glint_film_create(W, H, &jobs[i].film, &e_));
    assert_int_equal(
        pthread_create(&threads[i], NULL, render_on_thread, &jobs[i]), 0);
  }
  for (int i = 0; i < 2; i++) {
    pthread_join(threads[i], NULL);
    assert_int_equal(jobs[i].status, GLINT_OK);
  }
  assert_memory_equal(glint_film_pixels(jobs[0].film),
                      glint_film_pixels(jobs[1].film),
                      W * H * 3 * sizeof(float));
  glint_render_settings rs = settings_for(GLINT_BACKEND_AUTO);
  glint_image *image;
  ASSERT_OK(glint_render(scene, &rs, &image, NULL, &e_));
  assert_film_is_image(jobs[0].film, image);
  glint_image_destroy(image);
  for (int i = 0; i < 2; i++)
    glint_film_destroy(jobs[i].film);
  glint_world_destroy(world);
  glint_scene_destroy(scene);
}

static void expect_error(glint_status got, glint_status want,
                         const glint_error *e, const char *words) {
  assert_int_equal(got, want);
  if (!strstr(e->message, words))
    fail_msg("message '%s' does not say '%s'", e->message, words);
}

static void bad_arguments_are_refused(void **state) {
  (void)state;
  glint_scene *scene = whitted();
  glint_world *world;
  glint_renderer *renderer;
  glint_film *film, *small;
  glint_error e;
  expect_error(glint_world_commit(NULL, &world, NULL, &e), GLINT_E_ARGUMENT, &e,
               "glint_world_commit: scene is NULL");
  expect_error(glint_world_commit(scene, NULL, NULL, &e), GLINT_E_ARGUMENT, &e,
               "glint_world_commit: world is NULL");
  ASSERT_OK(glint_world_commit(scene, &world, NULL, &e_));
  glint_render_settings rs = settings_for(GLINT_BACKEND_AUTO);
  rs.max_depth = 0;
  expect_error(glint_renderer_create(world, &rs, &renderer, &e),
               GLINT_E_ARGUMENT, &e, "depth 0");
  rs = settings_for(GLINT_BACKEND_AUTO);
  expect_error(glint_renderer_create(NULL, &rs, &renderer, &e),
               GLINT_E_ARGUMENT, &e, "glint_renderer_create: world is NULL");
  ASSERT_OK(glint_renderer_create(world, &rs, &renderer, &e_));
  ASSERT_OK(glint_film_create(W, H, &film, &e_));
  ASSERT_OK(glint_film_create(W / 2, H, &small, &e_));
  expect_error(glint_renderer_render(renderer, NULL, small, NULL, &e),
               GLINT_E_ARGUMENT, &e, "film");
  expect_error(glint_renderer_render(renderer, NULL, NULL, NULL, &e),
               GLINT_E_ARGUMENT, &e, "film");
  glint_frame_settings fs;
  glint_frame_settings_default(&fs);
  fs.spp = GLINT_MAX_SPP + 1;
  expect_error(glint_renderer_render(renderer, &fs, film, NULL, &e),
               GLINT_E_ARGUMENT, &e, "samples per pixel");
  /* sample ranges: each bound named, no int overflow in the message */
  glint_frame_settings_default(&fs);
  fs.spp = 5, fs.sample_first = 2, fs.sample_count = INT_MAX;
  expect_error(glint_renderer_render(renderer, &fs, film, NULL, &e),
               GLINT_E_ARGUMENT, &e,
               "sample_count 2147483647 is not 0..3: the pattern has 5 "
               "samples, and 3 of them from sample_first 2");
  fs.sample_count = -1;
  expect_error(glint_renderer_render(renderer, &fs, film, NULL, &e),
               GLINT_E_ARGUMENT, &e, "sample_count -1");
  fs.sample_first = 5, fs.sample_count = 0;
  expect_error(glint_renderer_render(renderer, &fs, film, NULL, &e),
               GLINT_E_ARGUMENT, &e, "sample_first 5");
  glint_frame_settings_default(&fs);
  fs.region_x = W - 4, fs.region_width = 8, fs.region_height = 8;
  expect_error(glint_renderer_render(renderer, &fs, film, NULL, &e),
               GLINT_E_ARGUMENT, &e, "region");
  /* A corner without a size, or one side without the other: named, not
   * ignored (x 5 with width 0 rendered the whole frame) nor called outside
   * the image (0,0 0x5 was "not inside the image") */
  glint_frame_settings_default(&fs);
  fs.region_x = 5;
  expect_error(glint_renderer_render(renderer, &fs, film, NULL, &e),
               GLINT_E_ARGUMENT, &e, "region at 5,0 has no size");
  glint_frame_settings_default(&fs);
  fs.region_height = 5;
  expect_error(glint_renderer_render(renderer, &fs, film, NULL, &e),
               GLINT_E_ARGUMENT, &e,
               "region 0x5: its width and height must both be at least 1");
  glint_scene_info info;
  glint_scene_get_info(scene, &info);
  glint_camera cam = info.camera;
  cam.up = (glint_vec3){cam.at.x - cam.from.x, cam.at.y - cam.from.y,
                        cam.at.z - cam.from.z};
  glint_frame_settings_default(&fs);
  fs.camera = &cam;
  expect_error(glint_renderer_render(renderer, &fs, film, NULL, &e),
               GLINT_E_ARGUMENT, &e, "parallel");
  cam = info.camera;
  cam.fov_x_degrees = 0.0 / 0.0;
  expect_error(glint_renderer_render(renderer, &fs, film, NULL, &e),
               GLINT_E_ARGUMENT, &e, "finite");
  expect_error(glint_film_create(0, 5, &small, &e), GLINT_E_ARGUMENT, &e,
               "film size");
  /* After all that, a good frame still renders. */
  ASSERT_OK(glint_renderer_render(renderer, NULL, film, NULL, &e_));
  glint_film_destroy(film);
  glint_film_destroy(small);
  glint_renderer_destroy(renderer);
  glint_world_destroy(world);
  glint_scene_destroy(scene);
}

/* A scene of n mirror spheres in a row, and a matte floor. */
static glint_scene *mirrors(int n, int matte_spheres) {
  glint_scene *s;
  ASSERT_OK(glint_scene_create(&s, &e_));
  glint_material mirror, matte;
  glint_material_default(&mirror);
  glint_material_default(&matte);
  mirror.kr = 0.8;
  uint32_t m, f;
  ASSERT_OK(glint_scene_add_material(s, &mirror, &m, &e_));
  ASSERT_OK(glint_scene_add_material(s, &matte, &f, &e_));
  ASSERT_OK(glint_scene_add_plane(s, (glint_vec3){0, 1, 0},
                                  (glint_vec3){0, 0, 0}, f, &e_));
  for (int i = 0; i < n; i++)
    ASSERT_OK(glint_scene_add_sphere(s, (glint_vec3){i, 1, 0}, 0.4, m, &e_));
  for (int i = 0; i < matte_spheres; i++)
    ASSERT_OK(glint_scene_add_sphere(s, (glint_vec3){i, 2, 0}, 0.4, f, &e_));
  return s;
}

/* GLINT_BACKEND_AUTO (src/render/backend_choice.c): the widest beams unless
 * rays scatter: 64 specular primitives from depth 2, 4 from depth 5, but
 * only from depth 10 where they are under 1/16 of the primitives other
 * than planes; and a renderer runs what glint_backend_choose says. Other
 * backends pass as glint_backend_resolve gives them. */
static void auto_picks_streams_where_rays_scatter(void **state) {
  (void)state;
  glint_backend beams = glint_backend_resolve(GLINT_BACKEND_AUTO);
  glint_backend streams = glint_backend_resolve(GLINT_BACKEND_STREAM);
  static const struct {
    int spheres, matte, depth, stream;
  } cases[] = {{64, 0, 2, 1},   {64, 0, 1, 0},   {63, 0, 4, 0},
               {63, 0, 5, 1},   {4, 0, 5, 1},    {3, 0, 15, 0},
               {0, 0, 15, 0},   {200, 0, 5, 1},  {4, 60, 5, 1},
               {4, 61, 5, 0},   {4, 61, 9, 0},   {4, 61, 10, 1},
               {64, 960, 2, 1}, {64, 961, 2, 0}, {64, 961, 10, 1}};
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    glint_scene *s = mirrors(cases[i].spheres, cases[i].matte);
    glint_render_settings rs;
    glint_render_settings_default(&rs);
    rs.max_depth = cases[i].depth;
    rs.width = rs.height = 8;
    rs.spp = 1;
    rs.threads = 1;
    glint_backend want = cases[i].stream ? streams : beams;
    assert_int_equal(glint_backend_choose(GLINT_BACKEND_AUTO, s, &rs), want);
    assert_int_equal(glint_backend_choose(GLINT_BACKEND_SCALAR_FLOAT, s, &rs),
                     GLINT_BACKEND_SCALAR_FLOAT);
    glint_image *im;
    glint_stats st;
    ASSERT_OK(glint_render(s, &rs, &im, &st, &e_));
    assert_int_equal(st.backend, want);
    glint_image_destroy(im);
    glint_scene_destroy(s);
  }
  /* The thesis's scenes: beams for Whitted at any depth, streams for
   * Billiard from depth 5. */
  glint_scene *w, *b;
  ASSERT_OK(glint_scene_builtin("whitted", &w, &e_));
  ASSERT_OK(glint_scene_builtin("billiard", &b, &e_));
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.max_depth = 15;
  assert_int_equal(glint_backend_choose(GLINT_BACKEND_AUTO, w, &rs), beams);
  assert_int_equal(glint_backend_choose(GLINT_BACKEND_AUTO, b, &rs), streams);
  rs.max_depth = 4;
  assert_int_equal(glint_backend_choose(GLINT_BACKEND_AUTO, b, &rs), beams);
  glint_scene_destroy(w);
  glint_scene_destroy(b);
}

/* glint_render from a thread with a 64 KiB stack, in every backend at the
 * deepest depth: the tracers' recursion runs on the renderer's own threads
 * (the AVX-512 beams at depth 64 need about 512 KiB; while the calling
 * thread worked as one of them, this crashed). */
typedef struct small_stack_render {
  glint_scene *scene;
  glint_backend backend;
  glint_status status;
  glint_image *image;
} small_stack_render;

static void *render_on_a_small_stack(void *p) {
  small_stack_render *r = p;
  glint_render_settings rs = settings_for(r->backend);
  rs.width = 32;
  rs.height = 24;
  rs.max_depth = 64;
  rs.threads = 1;
  glint_error e;
  r->status = glint_render(r->scene, &rs, &r->image, NULL, &e);
  return NULL;
}

static void a_small_thread_renders_deep(void **state) {
  (void)state;
  glint_scene *s;
  ASSERT_OK(glint_scene_builtin("billiard", &s, &e_));
  for (int b = GLINT_BACKEND_SCALAR_FLOAT; b <= GLINT_BACKEND_STREAM_AVX512;
       b++) {
    if (!glint_backend_supported((glint_backend)b))
      continue;
    small_stack_render r = {s, (glint_backend)b, GLINT_E_ARGUMENT, NULL};
    pthread_attr_t attr;
    pthread_t thread;
    assert_int_equal(pthread_attr_init(&attr), 0);
    assert_int_equal(pthread_attr_setstacksize(&attr, (size_t)64 << 10), 0);
    assert_int_equal(
        pthread_create(&thread, &attr, render_on_a_small_stack, &r), 0);
    pthread_join(thread, NULL);
    pthread_attr_destroy(&attr);
    assert_int_equal(r.status, GLINT_OK);
    glint_image_destroy(r.image);
  }
  glint_scene_destroy(s);
}

/* The process's resident memory, in bytes (/proc/self/statm's second
 * field), or -1 where it cannot be read. */
static long long resident_bytes(void) {
  FILE *f = fopen("/proc/self/statm", "r");
  long long pages = -1, size;
  if (f && fscanf(f, "%lld %lld", &size, &pages) != 2)
    pages = -1;
  if (f)
    fclose(f);
  return pages < 0 ? -1 : pages * sysconf(_SC_PAGESIZE);
}

/* A renderer's workers get their buffers when a frame first sets them to
 * work: a renderer of 256 threads rendering a 16x16 frame (one tile) holds
 * one thread's ray streams (2 MiB more resident), where every thread's,
 * made at once, took 460 MiB (1.9 GB with 1 024 threads). A larger frame
 * later makes the buffers of the threads it needs, and renders what two
 * threads render. */
static void memory_follows_the_threads_that_work(void **state) {
  (void)state;
  if (backend_missing(GLINT_BACKEND_STREAM))
    return;
  long long before = resident_bytes();
  if (before < 0) {
    printf("SKIPPED: no /proc/self/statm\n");
    return;
  }
  glint_scene *scene = whitted();
  glint_render_settings rs = settings_for(GLINT_BACKEND_STREAM);
  rs.width = rs.height = 16;
  rs.spp = 1;
  rs.threads = 256;
  glint_world *world;
  glint_renderer *renderer;
  glint_film *small, *large;
  glint_stats st;
  ASSERT_OK(glint_world_commit(scene, &world, NULL, &e_));
  ASSERT_OK(glint_renderer_create(world, &rs, &renderer, &e_));
  ASSERT_OK(glint_film_create(16, 16, &small, &e_));
  ASSERT_OK(glint_renderer_render(renderer, NULL, small, &st, &e_));
  long long grown = resident_bytes() - before;
  printf("256 threads, one 16x16 tile: %.1f MiB more resident "
         "(%.1f MiB of ray streams a thread)\n",
         (double)grown / 1048576.0,
         (double)st.stream_bytes_per_thread / 1048576.0);
  assert_int_equal(st.threads, 1);
  assert_true(grown < 16 * (long long)st.stream_bytes_per_thread);
  glint_frame_settings fs;
  glint_frame_settings_default(&fs);
  fs.width = W, fs.height = H;
  ASSERT_OK(glint_film_create(W, H, &large, &e_));
  ASSERT_OK(glint_renderer_render(renderer, &fs, large, &st, &e_));
  int tiles = ((W + GLINT_TILE_SIZE - 1) / GLINT_TILE_SIZE) *
              ((H + GLINT_TILE_SIZE - 1) / GLINT_TILE_SIZE);
  assert_int_equal(st.threads, tiles < 256 ? tiles : 256);
  rs.width = W, rs.height = H, rs.threads = 2;
  glint_image *image;
  ASSERT_OK(glint_render(scene, &rs, &image, NULL, &e_));
  assert_film_is_image(large, image);
  glint_image_destroy(image);
  glint_film_destroy(large);
  glint_film_destroy(small);
  glint_renderer_destroy(renderer);
  glint_world_destroy(world);
  glint_scene_destroy(scene);
}

/* Calls that overlap on one renderer are refused, not left to hang on its
 * threads or to overwrite the frame being rendered: from the frame's own
 * tile callback, and from a second thread. */
typedef struct reentry {
  glint_renderer *renderer;
  glint_world *world;
  glint_film *other;
  glint_status render, set_world;
  char message[sizeof((glint_error *)0)->message];
} reentry;

static int reenter(void *user, const glint_tile *t) {
  (void)t;
  reentry *r = user;
  glint_error e;
  glint_frame_settings small;
  glint_frame_settings_default(&small);
  small.width = small.height = 8;
  r->render = glint_renderer_render(r->renderer, &small, r->other, NULL, &e);
  snprintf(r->message, sizeof r->message, "%s", e.message);
  r->set_world = glint_renderer_set_world(r->renderer, r->world, &e);
  return 0;
}

typedef struct shared_renderer {
  glint_renderer *renderer;
  glint_film *film;
  int rendered, refused, other;
} shared_renderer;

static void *render_shared(void *arg) {
  shared_renderer *job = arg;
  glint_error e;
  for (int f = 0; f < 20; f++) {
    glint_status st =
        glint_renderer_render(job->renderer, NULL, job->film, NULL, &e);
    if (st == GLINT_OK && glint_film_pixels(job->film))
      job->rendered++;
    else if (st == GLINT_E_ARGUMENT && strstr(e.message, "busy"))
      job->refused++;
    else
      job->other++;
  }
  return NULL;
}

static void overlapping_calls_are_refused(void **state) {
  (void)state;
  glint_scene *scene = whitted();
  glint_world *world;
  ASSERT_OK(glint_world_commit(scene, &world, NULL, &e_));
  glint_render_settings rs = settings_for(GLINT_BACKEND_AUTO);
  glint_image *want;
  ASSERT_OK(glint_render(scene, &rs, &want, NULL, &e_));
  glint_renderer *renderer;
  ASSERT_OK(glint_renderer_create(world, &rs, &renderer, &e_));

  reentry r = {renderer, world, NULL, GLINT_OK, GLINT_OK, ""};
  glint_film *film;
  ASSERT_OK(glint_film_create(W, H, &film, &e_));
  ASSERT_OK(glint_film_create(8, 8, &r.other, &e_));
  glint_frame_settings fs;
  glint_frame_settings_default(&fs);
  fs.tile = reenter;
  fs.tile_user = &r;
  ASSERT_OK(glint_renderer_render(renderer, &fs, film, NULL, &e_));
  assert_int_equal(r.render, GLINT_E_ARGUMENT);
  assert_non_null(strstr(r.message, "glint_renderer_render: the renderer is "
                                    "busy with another call"));
  assert_int_equal(r.set_world, GLINT_E_ARGUMENT);
  assert_film_is_image(film, want); /* the frame is whole */
  ASSERT_OK(glint_renderer_render(renderer, NULL, film, NULL, &e_));

  /* Two threads on one renderer: each call renders its frame whole or is
   * refused; none hangs. */
  shared_renderer jobs[2];
  pthread_t threads[2];
  for (int i = 0; i < 2; i++) {
    jobs[i] = (shared_renderer){renderer, NULL, 0, 0, 0};
    ASSERT_OK(glint_film_create(W, H, &jobs[i].film, &e_));
    assert_int_equal(pthread_create(&threads[i], NULL, render_shared, &jobs[i]),
                     0);
  }
  for (int i = 0; i < 2; i++) {
    pthread_join(threads[i], NULL);
    assert_int_equal(jobs[i].other, 0);
    assert_int_equal(jobs[i].rendered + jobs[i].refused, 20);
    if (jobs[i].rendered)
      assert_film_is_image(jobs[i].film, want);
    glint_film_destroy(jobs[i].film);
  }
  assert_true(jobs[0].rendered + jobs[1].rendered > 0);
  glint_film_destroy(r.other);
  glint_film_destroy(film);
  glint_image_destroy(want);
  glint_renderer_destroy(renderer);
  glint_world_destroy(world);
  glint_scene_destroy(scene);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(frames_equal_glint_render),
      cmocka_unit_test(frame_cameras_have_their_own_epsilon),
      cmocka_unit_test(films_stay_finite),
      cmocka_unit_test(worlds_are_independent_of_their_scene),
      cmocka_unit_test(tiles_cover_the_frame_once),
      cmocka_unit_test(renderers_share_a_world),
      cmocka_unit_test(overlapping_calls_are_refused),
      cmocka_unit_test(bad_arguments_are_refused),
      cmocka_unit_test(auto_picks_streams_where_rays_scatter),
      cmocka_unit_test(a_small_thread_renders_deep),
      cmocka_unit_test(memory_follows_the_threads_that_work),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
