/* Animation (include/glint.h "Animation", docs/scene-format.md), through the
 * public API, against hand-computed cameras:
 *  - linear keys: halfway between two keys is halfway between them;
 *  - Catmull-Rom keys: through every key, and between them the Hermite cubic
 *    with tangents from the neighbours (one-sided at the ends);
 *  - before the first key and after the last the camera holds still;
 *  - an orbit turns its degrees over the frames, from the +z side;
 *  - the JSON "animation" block sets all of it, and each mistake is named
 *    at its JSON path; a committed world keeps the animation of its copy. */
#include "test_util.h"

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
  ASSERT_OK(glint_scene_set_camera_orbit(s, keys[0].camera.at, 2, 0, 360, &e_));
  glint_camera c;
  assert_int_equal(glint_scene_camera_at(s, 0, &c, &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "no animation frames"));
  glint_animation bad = {0, 1, 2};
  assert_int_equal(glint_scene_set_animation(s, &bad, &e), GLINT_E_ARGUMENT);
  glint_animation backwards = {24, 5, 2};
  assert_int_equal(glint_scene_set_animation(s, &backwards, &e),
                   GLINT_E_ARGUMENT);
  glint_scene_destroy(s);
}

typedef struct bad_case {
  const char *json, *words;
} bad_case;

static void json_mistakes_are_named(void **state) {
  (void)state;
  static const bad_case cases[] = {
      {"{\"animation\": {\"fps\": 0, \"frames\": [0, 1]}}",
       "anim.json: animation.fps: fps 0 is not in (0, 1e6]"},
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
      cmocka_unit_test(json_mistakes_are_named),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
