/* Animation (include/glint.h "Animation", docs/scene-format.md), through the
 * public API, against hand-computed cameras:
 *  - linear keys: halfway between two keys is halfway between them;
 *  - Catmull-Rom keys: through every key, and between them the Hermite cubic
 *    with tangents from the neighbours (one-sided at the ends);
 *  - before the first key and after the last the camera holds still;
 *  - an orbit turns its degrees over the frames, from the +z side;
 *  - the JSON "animation" block sets all of it, and each mistake is named
 *    at its JSON path; a committed world keeps the animation of its copy;
 *  - transforms move spheres, planes, triangles and cones as
 *    translate + pivot + scale R (p - pivot), R = Rz Ry Rx, still or keyed,
 *    and glint_scene_at_time gives the still scene of a time. */
#include "test_util.h"

#include "scene/scene.h" /* to read the moved primitives back */

#include <limits.h>
#include <math.h>
#include <string.h>

static const double pi = 3.14159265358979323846;

static glint_scene *load(const char *json) {
  glint_scene *s;
  ASSERT_OK(glint_scene_load_memory(json, strlen(json), "anim.json", &s, &e_));
  return s;
}

static void near(double got, double want, const char *what) {
  if (fabs(got - want) > 1e-12)
    fail_msg("%s: %.17g, not %.17g", what, got, want);
}

static void at(const glint_scene *s, double t, glint_camera *c) {
  ASSERT_OK(glint_scene_camera_at(s, t, c, &e_));
}

static void linear_keys(void **state) {
  (void)state;
  glint_scene *s =
      load("{\"animation\": {\"fps\": 10, \"frames\": [0, 20], \"camera\": "
           "{\"keys\": [{\"time\": 0, \"from\": [0, 0, 10], \"at\": [0, 0, 0]},"
           " {\"time\": 2, \"from\": [4, 0, 10], \"at\": [0, 2, 0], \"fov\": "
           "40}]}}}");
  glint_camera c;
  at(s, 0.5, &c);
  near(c.from.x, 1, "from.x at 1/4");
  near(c.at.y, 0.5, "at.y at 1/4");
  near(c.fov_x_degrees, 55, "fov at 1/4 (60 to 40)");
  at(s, -3, &c); /* before the first key */
  near(c.from.x, 0, "from.x before the keys");
  at(s, 7, &c); /* after the last */
  near(c.from.x, 4, "from.x after the keys");
  near(c.fov_x_degrees, 40, "fov after the keys");
  glint_animation a;
  assert_int_equal(glint_scene_get_animation(s, &a), 1);
  assert_true(a.fps == 10 && a.first_frame == 0 && a.last_frame == 20);
  glint_scene_destroy(s);
}

static void catmull_rom_keys(void **state) {
  (void)state;
  /* x goes 0, 1, 0 at t = 0, 1, 2: the tangent is 1 at the first key
   * (one-sided) and 0 at the middle one; halfway through the first span the
   * Hermite cubic gives (1/8 - 1/2 + 1/2) * 1 + (-1/4 + 3/4) * 1 = 0.625. */
  glint_scene *s =
      load("{\"animation\": {\"frames\": [0, 48], \"camera\": "
           "{\"interpolation\": \"catmull-rom\", \"keys\": ["
           "{\"time\": 0, \"from\": [0, 0, 10], \"at\": [0, 0, 0]},"
           "{\"time\": 1, \"from\": [1, 0, 10], \"at\": [0, 0, 0]},"
           "{\"time\": 2, \"from\": [0, 0, 10], \"at\": [0, 0, 0]}]}}}");
  glint_camera c;
  at(s, 0.5, &c);
  near(c.from.x, 0.625, "from.x halfway through the first span");
  at(s, 1.5, &c); /* mirror image: 0.625 too */
  near(c.from.x, 0.625, "from.x halfway through the second span");
  for (int k = 0; k <= 2; k++) {
    at(s, k, &c);
    near(c.from.x, k == 1 ? 1 : 0, "from.x at a key");
  }
  glint_animation a;
  assert_int_equal(glint_scene_get_animation(s, &a), 1);
  assert_true(a.fps == 24); /* the default */
  glint_scene_destroy(s);
}

static void orbit(void **state) {
  (void)state;
  glint_scene *s =
      load("{\"camera\": {\"from\": [0, 0, 5], \"at\": [0, 0, 0], \"fov\": 45},"
           "\"animation\": {\"fps\": 24, \"frames\": [1, 48], \"camera\": "
           "{\"orbit\": {\"center\": [1, 2, 3], \"radius\": 6, \"height\": 1.5,"
           " \"degrees\": 360}}}}");
  glint_camera c;
  at(s, 0, &c); /* frame 1: on the +z side */
  near(c.from.x, 1, "from.x at frame 1");
  near(c.from.y, 3.5, "from.y at frame 1");
  near(c.from.z, 9, "from.z at frame 1");
  near(c.at.x, 1, "at.x");
  near(c.fov_x_degrees, 45, "the scene camera's fov");
  /* Frame 13, half a second in: a quarter of the 2 s (48 frames) turn. */
  at(s, 12.0 / 24, &c);
  near(c.from.x, 1 + 6, "from.x a quarter round");
  assert_true(fabs(c.from.z - 3) < 1e-12);
  /* The last frame stops one step short of the whole turn. */
  at(s, 47.0 / 24, &c);
  near(c.from.x, 1 + 6 * sin(2 * pi * 47 / 48), "from.x at the last frame");
  glint_scene_destroy(s);
  /* Frames up to GLINT_MAX_FRAME through the API, as in JSON (the API
   * took INT_MAX, where last - first + 1 overflowed int) */
  s = load("{\"camera\": {\"from\": [0, 0, 5], \"at\": [0, 0, 0]}}");
  glint_animation frames = {1, 0, GLINT_MAX_FRAME};
  ASSERT_OK(glint_scene_set_animation(s, &frames, &e_));
  ASSERT_OK(
      glint_scene_set_camera_orbit(s, (glint_vec3){0, 0, 0}, 6, 0, 360, &e_));
  at(s, (GLINT_MAX_FRAME + 1.0) / 2, &c); /* half-way round: the -z side */
  assert_true(fabs(c.from.z + 6) < 1e-6);
  /* a finite time too far for a finite angle: said so (it blamed the
   * camera's coordinates) */
  ASSERT_OK(
      glint_scene_set_camera_orbit(s, (glint_vec3){0, 0, 0}, 6, 0, 1e15, &e_));
  glint_error e;
  assert_int_equal(glint_scene_camera_at(s, 1e300, &c, &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "time 1e+300 is too far"));
  glint_scene_destroy(s);
}

static void world_keeps_the_animation(void **state) {
  (void)state;
  glint_scene *s =
      load("{\"objects\": [{\"type\": \"sphere\", \"center\": [0, 0, 0], "
           "\"radius\": 1, \"material\": \"default\"}],"
           "\"materials\": {\"default\": {}},"
           "\"animation\": {\"frames\": [0, 3], \"camera\": {\"keys\": ["
           "{\"time\": 0, \"from\": [0, 0, 5], \"at\": [0, 0, 0]}]}}}");
  glint_world *world;
  ASSERT_OK(glint_world_commit(s, &world, NULL, &e_));
  glint_scene_destroy(s); /* the world holds a copy */
  glint_world_destroy(world);
  /* Through the API: keys replace keys, and bad keys are refused. */
  ASSERT_OK(glint_scene_create(&s, &e_));
  glint_camera_key keys[2] = {{0, {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 60}},
                              {0, {{0, 0, 6}, {0, 0, 0}, {0, 1, 0}, 60}}};
  glint_error e;
  assert_int_equal(
      glint_scene_set_camera_keys(s, keys, 2, GLINT_INTERPOLATE_LINEAR, &e),
      GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "does not come after"));
  /* Each message names what is wrong. */
  keys[1].time = NAN;
  assert_int_equal(
      glint_scene_set_camera_keys(s, keys, 2, GLINT_INTERPOLATE_LINEAR, &e),
      GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "key 1's time nan is not a finite number"));
  keys[1].time = 1;
  keys[1].camera.fov_x_degrees = NAN;
  assert_int_equal(
      glint_scene_set_camera_keys(s, keys, 2, GLINT_INTERPOLATE_LINEAR, &e),
      GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "field of view is not a finite number"));
  keys[1].camera.fov_x_degrees = 60;
  assert_int_equal(
      glint_scene_set_camera_keys(s, NULL, 5, GLINT_INTERPOLATE_LINEAR, &e),
      GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "keys is NULL"));
  glint_animation many = {24, 0, INT_MAX};
  assert_int_equal(glint_scene_set_animation(s, &many, &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "frames 0..2147483647 are not a range of "
                                    "frame numbers 0..99999999"));
  glint_animation fast = {1e300, 0, 2};
  assert_int_equal(glint_scene_set_animation(s, &fast, &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "fps 1e+300 is not a number of frames a "
                                    "second from 1e-06 to 1e+06"));
  /* refused when set, not at every frame's camera */
  assert_int_equal(
      glint_scene_set_camera_orbit(s, keys[0].camera.at, 2, 0, 360, &e),
      GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "no animation frames"));
  glint_animation bad = {0, 1, 2};
  assert_int_equal(glint_scene_set_animation(s, &bad, &e), GLINT_E_ARGUMENT);
  glint_animation backwards = {24, 5, 2};
  assert_int_equal(glint_scene_set_animation(s, &backwards, &e),
                   GLINT_E_ARGUMENT);
  glint_scene_destroy(s);
}

static void near_vec(glint_vec3 got, glint_vec3 want, const char *what) {
  if (fabs(got.x - want.x) > 1e-12 || fabs(got.y - want.y) > 1e-12 ||
      fabs(got.z - want.z) > 1e-12)
    fail_msg("%s: (%.17g, %.17g, %.17g), not (%g, %g, %g)", what, got.x, got.y,
             got.z, want.x, want.y, want.z);
}

static void still_transforms(void **state) {
  (void)state;
  glint_scene *s =
      load("{\"materials\": {\"m\": {}}, \"objects\": ["
           /* a quarter turn about z round the origin: x goes to y; scale 2 */
           "{\"type\": \"sphere\", \"center\": [1, 0, 0], \"radius\": 0.5, "
           "\"material\": \"m\", \"transform\": {\"rotate\": [0, 0, 90], "
           "\"scale\": 2}},"
           /* a quarter turn about x round (0, 1, 0): +y normal to +z */
           "{\"type\": \"plane\", \"normal\": [0, 1, 0], \"point\": [0, 1, 0], "
           "\"material\": \"m\", \"transform\": {\"rotate\": [90, 0, 0], "
           "\"pivot\": [0, 1, 0], \"translate\": [0, 0, 3]}},"
           /* about y: z goes to x */
           "{\"type\": \"triangle\", \"vertices\": [[0, 0, 1], [0, 1, 1], "
           "[0, 0, 2]], \"material\": \"m\", \"transform\": {\"rotate\": "
           "[0, 90, 0]}},"
           "{\"type\": \"cone\", \"base\": [0, 0, 0], \"base_radius\": 1, "
           "\"apex\": [0, 2, 0], \"apex_radius\": 0.5, \"material\": \"m\", "
           "\"transform\": {\"translate\": [5, 0, 0], \"scale\": 3}}]}");
  near_vec(s->spheres[0].center, (glint_vec3){0, 2, 0}, "sphere center");
  near(s->spheres[0].radius, 1, "sphere radius");
  near_vec(s->planes[0].normal, (glint_vec3){0, 0, 1}, "plane normal");
  /* The point (0, 1, 0) stays at the pivot, then moves 3 along z. */
  near(s->planes[0].d, -3, "plane d");
  near_vec(s->triangles[0].v[0], (glint_vec3){1, 0, 0}, "vertex 0");
  near_vec(s->triangles[0].v[1], (glint_vec3){1, 1, 0}, "vertex 1");
  near_vec(s->triangles[0].v[2], (glint_vec3){2, 0, 0}, "vertex 2");
  near_vec(s->cones[0].base, (glint_vec3){5, 0, 0}, "cone base");
  near_vec(s->cones[0].apex, (glint_vec3){5, 6, 0}, "cone apex");
  near(s->cones[0].base_radius, 3, "cone base radius");
  assert_int_equal(glint_scene_has_motion(s), 0);
  glint_scene_destroy(s);
}

static void keyed_transforms(void **state) {
  (void)state;
  glint_scene *s =
      load("{\"materials\": {\"m\": {}}, \"objects\": ["
           "{\"type\": \"sphere\", \"center\": [0, 1, 0], \"radius\": 1, "
           "\"material\": \"m\", \"transform\": {\"keys\": [{\"time\": 0}, "
           "{\"time\": 2, \"translate\": [4, 0, 0], \"scale\": 0.5}]}}],"
           "\"animation\": {\"frames\": [0, 48], \"camera\": {\"keys\": ["
           "{\"time\": 0, \"from\": [0, 0, 10], \"at\": [0, 0, 0]},"
           "{\"time\": 2, \"from\": [0, 0, 20], \"at\": [0, 0, 0]}]}}}");
  assert_int_equal(glint_scene_has_motion(s), 1);
  /* As written until a time is asked for. */
  near_vec(s->spheres[0].center, (glint_vec3){0, 1, 0}, "written center");
  glint_scene *still;
  ASSERT_OK(glint_scene_at_time(s, 0.5, &still, &e_));
  /* A quarter of the way: translate (1, 0, 0), scale 0.875 about the
   * origin. */
  near_vec(still->spheres[0].center, (glint_vec3){1, 0.875, 0}, "center");
  near(still->spheres[0].radius, 0.875, "radius");
  near(still->camera.from.z, 12.5, "the camera of that time");
  assert_int_equal(glint_scene_has_motion(still), 0);
  glint_scene_destroy(still);
  /* A motion beyond GLINT_MAX_COORDINATE is refused at that time: the
   * sphere at 1e15 (the largest accepted) moved by 1e14 more. */
  glint_transform_key far[2] = {{0, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, 1}},
                                {1, {{1e14, 0, 0}, {0, 0, 0}, {0, 0, 0}, 1}}};
  glint_scene *t;
  ASSERT_OK(glint_scene_load_memory(
      "{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"sphere\", "
      "\"center\": [1e15, 0, 0], \"radius\": 1, \"material\": \"m\"}]}",
      strlen("{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": "
             "\"sphere\", \"center\": [1e15, 0, 0], \"radius\": 1, "
             "\"material\": \"m\"}]}"),
      "far.json", &t, &e_));
  ASSERT_OK(glint_scene_set_object_motion(t, 0, far, 2,
                                          GLINT_INTERPOLATE_LINEAR, &e_));
  glint_error e0;
  assert_int_equal(glint_scene_at_time(t, 1, &still, &e0), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e0.message, "beyond coordinates of magnitude 1e15"));
  ASSERT_OK(glint_scene_at_time(t, 0, &still, &e_)); /* still inside */
  glint_scene_destroy(still);
  glint_scene_destroy(t);
  ASSERT_OK(glint_scene_at_time(s, 9, &still, &e_)); /* after the last key */
  near_vec(still->spheres[0].center, (glint_vec3){4, 0.5, 0}, "held center");
  glint_scene_destroy(still);
  /* Through the API: a motion for a missing object, a scale not positive. */
  glint_transform_key k = {0, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, 1}};
  glint_error e;
  assert_int_equal(
      glint_scene_set_object_motion(s, 7, &k, 1, GLINT_INTERPOLATE_LINEAR, &e),
      GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "there is no object 7"));
  k.transform.scale = 0;
  assert_int_equal(
      glint_scene_set_object_motion(s, 0, &k, 1, GLINT_INTERPOLATE_LINEAR, &e),
      GLINT_E_ARGUMENT);
  /* Keys beyond the coordinates' range are refused when given, not when a
   * frame is made of them. */
  k.transform.scale = 1e300;
  assert_int_equal(
      glint_scene_set_object_motion(s, 0, &k, 1, GLINT_INTERPOLATE_LINEAR, &e),
      GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "key 0: translate, pivot and scale must "
                                    "be finite numbers of magnitude at most"));
  k.transform.scale = 1;
  k.transform.translate.y = -2e15;
  assert_int_equal(
      glint_scene_set_object_motion(s, 0, &k, 1, GLINT_INTERPOLATE_LINEAR, &e),
      GLINT_E_ARGUMENT);
  glint_scene_destroy(s);
}

/* The world of a frame committed after the last one's (its BVH refitted
 * when objects only moved, built anew when they turned) renders the image
 * a world committed alone renders: 24 spheres (a BVH), one of them moving,
 * and then turning about a point off its centre. */
static void worlds_after_the_last_frame(void **state) {
  (void)state;
  char json[8192];
  int n =
      snprintf(json, sizeof json,
               "{\"image\": {\"width\": 64, \"height\": 48},"
               "\"camera\": {\"from\": [0, 3, 14], \"at\": [0, 1, 0]},"
               "\"lights\": [{\"position\": [5, 9, 9], \"color\": [1, 1, 1]}],"
               "\"materials\": {\"m\": {\"kd\": 0.7, \"ks\": 0.4, \"h\": 20, "
               "\"kr\": 0.3}}, \"objects\": [");
  for (int i = 0; i < 24; i++)
    n += snprintf(json + n, sizeof json - (size_t)n,
                  "{\"type\": \"sphere\", \"center\": [%d, %d, %d], "
                  "\"radius\": 0.45, \"material\": \"m\"%s},",
                  i % 6 - 3, i / 6, -(i % 4),
                  i ? ""
                    : ", \"transform\": {\"keys\": [{\"time\": 0}, "
                      "{\"time\": 1, \"translate\": [2, 1, 1]}, "
                      "{\"time\": 2, \"translate\": [2, 1, 1], \"rotate\": "
                      "[0, 90, 40], \"pivot\": [4, 0, 0]}]}");
  snprintf(json + n - 1, sizeof json - (size_t)n + 1,
           "], \"animation\": {\"fps\": 4, \"frames\": [0, 8]}}");
  glint_scene *s = load(json);
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.threads = 1;
  glint_world *last = NULL;
  for (int f = 0; f <= 8; f++) {
    double t = f / 4.0;
    glint_world *after, *alone;
    ASSERT_OK(glint_world_commit_at(s, t, last, &after, NULL, &e_));
    ASSERT_OK(glint_world_commit_at(s, t, NULL, &alone, NULL, &e_));
    glint_film *films[2];
    glint_world *worlds[2] = {after, alone};
    for (int k = 0; k < 2; k++) {
      glint_renderer *r;
      ASSERT_OK(glint_renderer_create(worlds[k], &rs, &r, &e_));
      ASSERT_OK(glint_film_create(64, 48, &films[k], &e_));
      ASSERT_OK(glint_renderer_render(r, NULL, films[k], NULL, &e_));
      glint_renderer_destroy(r);
    }
    assert_memory_equal(glint_film_pixels(films[0]),
                        glint_film_pixels(films[1]),
                        64 * 48 * 3 * sizeof(float));
    glint_film_destroy(films[0]);
    glint_film_destroy(films[1]);
    glint_world_destroy(alone);
    glint_world_destroy(last);
    last = after;
  }
  glint_world_destroy(last);
  glint_scene_destroy(s);
}

typedef struct bad_case {
  const char *json, *words;
} bad_case;

static void json_mistakes_are_named(void **state) {
  (void)state;
  static const bad_case cases[] = {
      {"{\"animation\": {\"fps\": 0, \"frames\": [0, 1]}}",
       "anim.json: animation.fps: fps 0 is outside 1e-06..1e+06"},
      /* shown with the digits that put it past 1e6 (it read 1e+06) */
      {"{\"animation\": {\"fps\": 1.000001e6, \"frames\": [0, 1]}}",
       "animation.fps: fps 1000001 is outside 1e-06..1e+06"},
      /* frame 1 of it was at an infinite time */
      {"{\"animation\": {\"fps\": 5e-324, \"frames\": [0, 2]}}",
       "animation.fps: fps 4.94065646e-324 is outside 1e-06..1e+06"},
      {"{\"animation\": {\"fps\": 24}}", "animation: missing \"frames\""},
      {"{\"animation\": {\"frames\": [5, 2]}}",
       "animation.frames: the last frame 2 comes before the first 5"},
      {"{\"animation\": {\"frames\": [0.5, 2]}}",
       "animation.frames[0]: expected a whole number"},
      {"{\"animation\": {\"frames\": [1]}}",
       "animation.frames: expected [first, last]"},
      {"{\"animation\": {\"frames\": [0, 9], \"speed\": 2}}",
       "unknown field \"speed\""},
      {"{\"animation\": {\"frames\": [0, 9], \"camera\": {}}}",
       "animation.camera: give either \"keys\" or \"orbit\""},
      {"{\"animation\": {\"frames\": [0, 9], \"camera\": {\"keys\": []}}}",
       "animation.camera.keys: expected at least one key"},
      {"{\"animation\": {\"frames\": [0, 9], \"camera\": {\"keys\": ["
       "{\"time\": 1, \"from\": [0, 0, 5], \"at\": [0, 0, 0]},"
       "{\"time\": 1, \"from\": [0, 0, 6], \"at\": [0, 0, 0]}]}}}",
       "animation.camera.keys[1]: time 1 does not come after"},
      {"{\"animation\": {\"frames\": [0, 9], \"camera\": {\"keys\": ["
       "{\"time\": 0, \"from\": [0, 0, 0], \"at\": [0, 0, 0]}]}}}",
       "animation.camera.keys[0]"},
      {"{\"animation\": {\"frames\": [0, 9], \"camera\": {\"keys\": ["
       "{\"from\": [0, 0, 5], \"at\": [0, 0, 0]}]}}}",
       "animation.camera.keys[0]: missing \"time\""},
      {"{\"animation\": {\"frames\": [0, 9], \"camera\": {\"interpolation\": "
       "\"cubic\", \"keys\": [{\"time\": 0, \"from\": [0, 0, 5], \"at\": "
       "[0, 0, 0]}]}}}",
       "animation.camera.interpolation: expected \"linear\" or "
       "\"catmull-rom\""},
      {"{\"animation\": {\"frames\": [0, 9], \"camera\": {\"orbit\": "
       "{\"center\": [0, 0, 0], \"radius\": 0}}}}",
       "radius positive"},
      {"{\"animation\": {\"frames\": [0, 9], \"camera\": {\"orbit\": "
       "{\"center\": [0, 0, 0], \"radius\": 2}, \"interpolation\": "
       "\"linear\"}}}",
       "\"interpolation\" applies to keys"},
      {"{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"sphere\", "
       "\"center\": [0, 0, 0], \"radius\": 1, \"material\": \"m\", "
       "\"transform\": {\"scale\": 0}}]}",
       "objects[0].transform.scale: the scale 0 is not positive"},
      {"{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"sphere\", "
       "\"center\": [0, 0, 0], \"radius\": 1, \"material\": \"m\", "
       "\"transform\": {\"spin\": 1}}]}",
       "objects[0].transform: unknown field \"spin\""},
      {"{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"sphere\", "
       "\"center\": [0, 0, 0], \"radius\": 1, \"material\": \"m\", "
       "\"transform\": {\"keys\": [{\"time\": 1}, {\"time\": 0}]}}]}",
       "objects[0].transform.keys[1]: time 0 does not come after"},
      {"{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"sphere\", "
       "\"center\": [0, 0, 0], \"radius\": 1, \"material\": \"m\", "
       "\"transform\": {\"keys\": [{\"translate\": [1, 0, 0]}]}}]}",
       "objects[0].transform.keys[0]: missing \"time\""},
      {"{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"sphere\", "
       "\"center\": [0, 0, 0], \"radius\": 1, \"material\": \"m\", "
       "\"transform\": {\"keys\": [{\"time\": 0}], \"rotate\": [1, 0, 0]}}]}",
       "objects[0].transform.rotate: a transform with \"keys\" has its "
       "rotate in each key, not beside them"},
      {"{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"sphere\", "
       "\"center\": [1e14, 0, 0], \"radius\": 1, \"material\": \"m\", "
       "\"transform\": {\"scale\": 100}}]}",
       "objects[0].transform: the transform moves the object beyond "
       "coordinates of magnitude 1e15"},
      /* A pivot cancels out where no rotation or scale acts: 1e300 left
       * the sphere at 1e300 + (3 - 1e300) = 0, and said nothing. */
      {"{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"sphere\", "
       "\"center\": [3, 0, 0], \"radius\": 1, \"material\": \"m\", "
       "\"transform\": {\"pivot\": [1e300, 0, 0]}}]}",
       "objects[0].transform.pivot: must be finite numbers of magnitude at "
       "most 1e15"},
      {"{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"sphere\", "
       "\"center\": [0, 0, 0], \"radius\": 1, \"material\": \"m\", "
       "\"transform\": {\"translate\": [0, 2e15, 0], \"pivot\": [0, -2e15, "
       "0]}}]}",
       "objects[0].transform.translate: must be finite"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    glint_scene *s = NULL;
    glint_error e;
    glint_status st = glint_scene_load_memory(
        cases[i].json, strlen(cases[i].json), "anim.json", &s, &e);
    if (st == GLINT_OK)
      fail_msg("case %zu loaded: %s", i, cases[i].json);
    if (!strstr(e.message, cases[i].words))
      fail_msg("case %zu: '%s' lacks '%s'", i, e.message, cases[i].words);
    assert_null(s);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(linear_keys),
      cmocka_unit_test(catmull_rom_keys),
      cmocka_unit_test(orbit),
      cmocka_unit_test(world_keeps_the_animation),
      cmocka_unit_test(still_transforms),
      cmocka_unit_test(keyed_transforms),
      cmocka_unit_test(worlds_after_the_last_frame),
      cmocka_unit_test(json_mistakes_are_named),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
