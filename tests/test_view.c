/* glint view's pieces that need no window (cli/view_camera.c,
 * cli/view_font.c, the option parser), against hand-computed values:
 *  - orbiting keeps the point looked at and the distance, 360 degrees come
 *    back, and pitching stops short of the up axis;
 *  - turning keeps the eye; panning and flying move eye and target alike;
 *    dollying scales the distance and never reaches the target;
 *  - the printed camera pastes into a scene file as the same camera;
 *  - every glyph fits its 5x7 cell, letters draw as capitals, unknown
 *    characters as '?';
 *  - the options: defaults, and each error named. */
#include "test_util.h"

#include "cli.h"
#include "view_camera.h"
#include "view_font.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const glint_camera start = {{0, 2, 6}, {0, 1, 0}, {0, 1, 0}, 60};

static double dist(glint_vec3 a, glint_vec3 b) {
  return sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
              (a.z - b.z) * (a.z - b.z));
}

static void assert_vec(glint_vec3 a, glint_vec3 b, double tol) {
  if (dist(a, b) > tol)
    fail_msg("(%g, %g, %g) != (%g, %g, %g)", a.x, a.y, a.z, b.x, b.y, b.z);
}

static void orbit_keeps_target_and_distance(void **state) {
  (void)state;
  glint_camera c = start;
  double d0 = dist(c.from, c.at);
  view_orbit(&c, 90, 0);
  assert_vec(c.at, start.at, 0);
  assert_true(fabs(dist(c.from, c.at) - d0) < 1e-12);
  /* A quarter turn about +y: the eye, 6 in front (+z) of the target's
   * axis, is now beside it on the x axis, at the same height. */
  assert_true(fabs(fabs(c.from.x) - 6) < 1e-12);
  assert_true(fabs(c.from.y - 2) < 1e-12);
  assert_true(fabs(c.from.z) < 1e-12);
  for (int i = 0; i < 3; i++)
    view_orbit(&c, 90, 0);
  assert_vec(c.from, start.from, 1e-12);
  /* Pitching far over the top stops 1 degree short of up. */
  view_orbit(&c, 0, -500);
  double up_angle = acos((c.from.y - c.at.y) / dist(c.from, c.at));
  assert_true(fabs(up_angle - 1.0 * 3.14159265358979323846 / 180) < 1e-9);
  assert_true(fabs(dist(c.from, c.at) - d0) < 1e-12);
}

static void turn_pan_fly_and_dolly(void **state) {
  (void)state;
  glint_camera c = start;
  double d0 = dist(c.from, c.at);
  view_turn(&c, 30, 10);
  assert_vec(c.from, start.from, 0);
  assert_true(fabs(dist(c.from, c.at) - d0) < 1e-12);

  c = start;
  view_pan(&c, 0.5, 0, 4.0 / 3.0);
  /* Half the visible width at the target's distance, to the left (the
   * scene moves with the mouse): d tan(30 deg) . */
  double shift = d0 * tan(30 * 3.14159265358979323846 / 180);
  assert_vec(c.from, (glint_vec3){-shift, 2, 6}, 1e-12);
  assert_vec(c.at, (glint_vec3){-shift, 1, 0}, 1e-12);

  c = start;
  view_fly(&c, 1, 0, 0);
  glint_vec3 dir = {0, -1 / d0, -6 / d0};
  assert_vec(c.from, (glint_vec3){0, 2 + dir.y, 6 + dir.z}, 1e-12);
  assert_vec(c.at, (glint_vec3){0, 1 + dir.y, dir.z}, 1e-12);
  c = start;
  view_fly(&c, 0, 2, 3);
  assert_vec(c.from, (glint_vec3){2, 5, 6}, 1e-12);

  c = start;
  view_dolly(&c, 0.5);
  assert_true(fabs(dist(c.from, c.at) - d0 / 2) < 1e-12);
  assert_vec(c.at, start.at, 0);
  view_dolly(&c, 1e-9);
  assert_true(dist(c.from, c.at) > 0);

  /* No move leaves the range glint renders: scrolled, panned or flown out
   * for long, the camera stops at its last renderable place (it ended the
   * viewer with "coordinates must be finite numbers of magnitude at most
   * 1e15"). */
  c = start;
  for (int i = 0; i < 400; i++)
    view_dolly(&c, 1.25);
  for (int i = 0; i < 400; i++)
    view_pan(&c, 1e3, 1e3, 4.0 / 3.0);
  for (int i = 0; i < 400; i++)
    view_fly(&c, 1e14, 1e14, 1e14);
  const glint_vec3 ends[2] = {c.from, c.at};
  for (int i = 0; i < 2; i++)
    assert_true(fabs(ends[i].x) <= GLINT_MAX_COORDINATE &&
                fabs(ends[i].y) <= GLINT_MAX_COORDINATE &&
                fabs(ends[i].z) <= GLINT_MAX_COORDINATE);
  assert_true(dist(c.from, c.at) > 1e13); /* it did move far */

  /* Nor a camera glint refuses some other way: 20 000 moves of every kind
   * with arguments as large as a script's drags, the camera checked after
   * each (dollied back in from 1e14, from and at rounded into one point or
   * the view onto up, and the viewer ended with "'up' is zero or parallel
   * to the view direction"). */
  c = start;
  uint64_t seed = 1;
  for (int i = 0; i < 20000; i++) {
    seed = seed * 6364136223846793005u + 1442695040888963407u;
    double a = (double)(int32_t)(seed >> 32) / 2147.483648; /* +-1e6 */
    double b = (double)(int32_t)(seed & 0xffffffffu) / 2147.483648;
    switch ((seed >> 29) % 5) {
    case 0: view_orbit(&c, a, b); break;
    case 1: view_turn(&c, a, b); break;
    case 2: view_pan(&c, a / 1e3, b / 1e3, 4.0 / 3.0); break;
    case 3: view_dolly(&c, pow(10, a / 2e5)); break;
    default: view_fly(&c, a * 1e8, b * 1e8, a); break;
    }
    glint_error e;
    if (glint_camera_check(&c, &e) != GLINT_OK)
      fail_msg("move %d: %s", i, e.message);
  }
}

static void camera_json_pastes_into_a_scene(void **state) {
  (void)state;
  glint_camera c = start;
  view_orbit(&c, 37, 12);
  c.fov_x_degrees = 47.5;
  /* and far out, where six digits made from and at one point */
  glint_camera far = {{7.63086016163240e14, -6.389348129689745e14, 1e-300},
                      {7.630860161632403e14, -6.389348129689746e14, 0.1},
                      {0, 1, 0},
                      60};
  const glint_camera *cams[2] = {&c, &far};
  for (int k = 0; k < 2; k++) {
    char json[512], scene_text[1024];
    view_camera_json(cams[k], json, sizeof json);
    snprintf(scene_text, sizeof scene_text, "{%s, \"objects\": []}", json);
    glint_scene *scene;
    ASSERT_OK(glint_scene_load_memory(scene_text, strlen(scene_text),
                                      "pasted.json", &scene, &e_));
    glint_scene_info info;
    glint_scene_get_info(scene, &info);
    assert_vec(info.camera.from, cams[k]->from, 0); /* read back exactly */
    assert_vec(info.camera.at, cams[k]->at, 0);
    assert_true(info.camera.fov_x_degrees == cams[k]->fov_x_degrees);
    glint_scene_destroy(scene);
  }
  char json[512];
  view_camera_json(&start, json, sizeof json); /* in the fewest digits */
  assert_non_null(strstr(json, "\"from\": [0, 2, 6], \"at\": [0, 1, 0]"));
}

/* Draws `text` at scale 1 into a buffer one cell wider and taller than the
 * text needs; returns the count of inked pixels. */
static int ink(const char *text, uint8_t *buf, int w, int h) {
  memset(buf, 0, (size_t)w * h * 3);
  static const uint8_t white[3] = {255, 255, 255};
  view_draw_text(buf, w, h, 0, 0, text, 1, white);
  int n = 0;
  for (int i = 0; i < w * h; i++)
    n += buf[3 * i] != 0;
  return n;
}

static void glyphs_fit_their_cells(void **state) {
  (void)state;
  enum { W = 2 * (VIEW_GLYPH_W + 1), H = VIEW_GLYPH_H + 2 };
  uint8_t buf[W * H * 3], question[W * H * 3];
  ink("?", question, W, H);
  for (int c = 32; c < 127; c++) {
    char text[2] = {(char)c, 0};
    int n = ink(text, buf, W, H);
    /* Nothing outside the first 5x7 cell. */
    for (int y = 0; y < H; y++)
      for (int x = 0; x < W; x++)
        if (buf[3 * (y * W + x)] && (x >= VIEW_GLYPH_W || y >= VIEW_GLYPH_H))
          fail_msg("'%c' inks (%d, %d), outside its cell", c, x, y);
    if (c == ' ')
      assert_int_equal(n, 0);
    else
      assert_true(n > 0);
  }
  uint8_t upper[W * H * 3];
  ink("G", upper, W, H);
  ink("g", buf, W, H);
  assert_memory_equal(buf, upper, sizeof buf);
  ink("~", buf, W, H); /* no glyph */
  assert_memory_equal(buf, question, sizeof buf);
  assert_int_equal(view_text_width("AB", 2), 2 * (VIEW_GLYPH_W + 1) * 2);
  /* '1': a top pixel, a flag of 2, four rows of 1, a foot of 3. */
  assert_int_equal(ink("1", buf, W, H), 1 + 2 + 1 * 4 + 3);
}

static void options(void **state) {
  (void)state;
  view_options o;
  char *none[] = {NULL};
  assert_int_equal(view_parse(0, none, &o), -1);
  assert_string_equal(o.scene, "whitted");
  assert_int_equal(o.settings.spp, 5);
  assert_int_equal(o.benchmark_frames, 0);
  assert_true(o.budget_ms == 40);
  char *args[] = {"giza.json", "-s",   "9",  "-d3", "--benchmark=12",
                  "--budget",  "16.5", "-W", "320", "--gamma",
                  "2.2",       NULL};
  assert_int_equal(view_parse(11, args, &o), -1);
  assert_string_equal(o.scene, "giza.json");
  assert_int_equal(o.settings.spp, 9);
  assert_int_equal(o.settings.max_depth, 3);
  assert_int_equal(o.benchmark_frames, 12);
  assert_true(o.budget_ms == 16.5);
  assert_int_equal(o.settings.width, 320);
  assert_true(o.settings.gamma == 2.2);
  char *bad[][4] = {{"--benchmark", "0", NULL},
                    {"--budget", "0.5", NULL},
                    {"--frobnicate", NULL, NULL},
                    {"-b", "quantum", NULL},
                    {"a.nff", "b.nff", NULL},
                    /* the script was ignored */
                    {"--benchmark=2", "--script", "s.txt", NULL},
                    {"--", "a.nff", "b.nff", NULL}};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    int n = 0;
    while (n < 4 && bad[i][n])
      n++;
    assert_int_equal(view_parse(n, bad[i], &o), 2);
  }
  /* after --, a scene named like an option */
  char *dashed[] = {"--", "-x.nff"};
  assert_int_equal(view_parse(2, dashed, &o), -1);
  assert_string_equal(o.scene, "-x.nff");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(orbit_keeps_target_and_distance),
      cmocka_unit_test(turn_pan_fly_and_dolly),
      cmocka_unit_test(camera_json_pastes_into_a_scene),
      cmocka_unit_test(glyphs_fit_their_cells),
      cmocka_unit_test(options),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
