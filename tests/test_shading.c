/* The shading of single points (docs/specification.md §4) against hand-computed
 * colours. Each case is a 1x1 image with one sample, whose primary ray runs
 * exactly along the camera's view direction, rendered by every backend this CPU
 * supports: all of them must agree with the hand computation to one level. */
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

typedef glint_vec3 V;

static glint_scene *new_scene(V from, V at, V up, V background) {
  glint_scene *s;
  ASSERT_OK(glint_scene_create(&s, &e_));
  glint_camera cam = {from, at, up, 60};
  ASSERT_OK(glint_scene_set_camera(s, &cam, &e_));
  ASSERT_OK(glint_scene_set_background(s, background, &e_));
  return s;
}

static uint32_t material(glint_scene *s, const glint_material *m) {
  uint32_t id;
  ASSERT_OK(glint_scene_add_material(s, m, &id, &e_));
  return id;
}

/* The centre ray alone (a 1x1 image, one sample) through backend `be` at
 * `depth`, on one thread. */
static glint_render_settings centre_ray(int be, int depth) {
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.width = rs.height = 1;
  rs.spp = 1;
  rs.max_depth = depth;
  rs.threads = 1;
  rs.backend = (glint_backend)be;
  return rs;
}

/* Renders the centre ray with every supported backend and checks each
 * channel against round(255 c). */
static void expect_pixel(glint_scene *s, int depth, double r, double g,
                         double b) {
  for (int be = GLINT_BACKEND_SCALAR_FLOAT; be < GLINT_BACKEND_COUNT; be++) {
    if (be == GLINT_BACKEND_STREAM || backend_missing((glint_backend)be))
      continue;
    glint_render_settings rs = centre_ray(be, depth);
    /* The SIMD backends with libm's pow/exp and with the default minimax. */
    for (int m = 0; m < 2; m++) {
      rs.math = m ? GLINT_MATH_MINIMAX : GLINT_MATH_EXACT;
      glint_image *im;
      ASSERT_OK(glint_render(s, &rs, &im, NULL, &e_));
      const uint8_t *p = glint_image_pixels_const(im);
      int want[3] = {expected_byte(r), expected_byte(g), expected_byte(b)};
      for (int c = 0; c < 3; c++)
        if (abs(p[c] - want[c]) > 1)
          fail_msg("backend %s, math %s, channel %d: got %d, want %d (%.5f)",
                   glint_backend_name((glint_backend)be),
                   glint_math_name(rs.math), c, p[c], want[c],
                   c == 0   ? r
                   : c == 1 ? g
                            : b);
      glint_image_destroy(im);
    }
  }
  glint_scene_destroy(s);
}

/* A plane z = 0 facing the camera at (0, 0, 5). */
static glint_scene *wall(const glint_material *m, V ambient) {
  glint_scene *s =
      new_scene((V){0, 0, 5}, (V){0, 0, 0}, (V){0, 1, 0}, (V){0, 0, 0});
  ASSERT_OK(glint_scene_set_ambient(s, ambient, &e_));
  ASSERT_OK(glint_scene_add_plane(s, (V){0, 0, 1}, (V){0, 0, 0}, material(s, m),
                                  &e_));
  return s;
}

/* A matte material: colour (0.8, 0.6, 0.4), ka 0.2, kd 0.5. */
static glint_material matte_material(void) {
  glint_material m;
  glint_material_default(&m);
  m.color = (V){0.8, 0.6, 0.4};
  m.ka = 0.2;
  m.kd = 0.5;
  return m;
}

/* Light straight ahead: N·L = 1. I = C (ka Ia + kd) = C (0.1 + 0.5). */
static void diffuse_only(void **state) {
  (void)state;
  glint_material m = matte_material();
  glint_scene *s = wall(&m, (V){0.5, 0.5, 0.5});
  ASSERT_OK(glint_scene_add_light(s, (V){0, 0, 10}, (V){1, 1, 1}, &e_));
  expect_pixel(s, 5, 0.8 * 0.6, 0.6 * 0.6, 0.4 * 0.6);
}

/* A mesh whose vertex normals are all zero (a file may say `vn 0 0 0`):
 * the interpolated normal cancels, and every backend shades with the
 * triangle's own normal, as diffuse_only's wall (the SIMD backends used
 * to normalise the zero vector and light nothing). */
static void zero_vertex_normals_shade_flat(void **state) {
  (void)state;
  glint_material m = matte_material();
  glint_scene *s =
      new_scene((V){0, 0, 5}, (V){0, 0, 0}, (V){0, 1, 0}, (V){0, 0, 0});
  ASSERT_OK(glint_scene_set_ambient(s, (V){0.5, 0.5, 0.5}, &e_));
  const V positions[3] = {{-2, -1, 0}, {2, -1, 0}, {0, 2, 0}};
  const V normals[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  const uint32_t indices[3] = {0, 1, 2};
  glint_mesh mesh = {positions, normals, 3, indices, 1};
  ASSERT_OK(glint_scene_add_mesh(s, &mesh, material(s, &m), &e_));
  ASSERT_OK(glint_scene_add_light(s, (V){0, 0, 10}, (V){1, 1, 1}, &e_));
  expect_pixel(s, 5, 0.8 * 0.6, 0.6 * 0.6, 0.4 * 0.6);
}

/* The light at (0, 4, 3): L = (0, .8, .6), N·L = .6, R = (0, -.8, .6),
 * V·R = .6, so the highlight is ks .6^h = .5 * .36 = .18 per unit light. */
static glint_material phong_material(void) {
  glint_material m;
  glint_material_default(&m);
  m.color = (V){0.5, 0.5, 0.5};
  m.ka = 0.1;
  m.kd = 0.5;
  m.ks = 0.5;
  m.h = 2;
  return m;
}

static void diffuse_and_highlight(void **state) {
  (void)state;
  glint_material m = phong_material();
  glint_scene *s = wall(&m, (V){1, 1, 1});
  ASSERT_OK(glint_scene_add_light(s, (V){0, 4, 3}, (V){1, 0.5, 0.25}, &e_));
  expect_pixel(s, 5, 0.5 * (0.1 + 0.3 * 1) + 0.18 * 1,
               0.5 * (0.1 + 0.3 * 0.5) + 0.18 * 0.5,
               0.5 * (0.1 + 0.3 * 0.25) + 0.18 * 0.25);
}

/* A light behind the surface contributes nothing, not even a highlight. */
static void light_behind_surface(void **state) {
  (void)state;
  glint_material m = phong_material();
  glint_scene *s = wall(&m, (V){1, 1, 1});
  ASSERT_OK(glint_scene_add_light(s, (V){0, 4, -3}, (V){1, 1, 1}, &e_));
  expect_pixel(s, 5, 0.05, 0.05, 0.05);
}

/* An opaque sphere on the shadow ray (its centre at t = 2.5 along L). */
static void opaque_shadow(void **state) {
  (void)state;
  glint_material m = phong_material(), blocker;
  glint_material_default(&blocker);
  glint_scene *s = wall(&m, (V){1, 1, 1});
  ASSERT_OK(glint_scene_add_light(s, (V){0, 4, 3}, (V){1, 1, 1}, &e_));
  ASSERT_OK(glint_scene_add_sphere(s, (V){0, 2, 1.5}, 0.5,
                                   material(s, &blocker), &e_));
  expect_pixel(s, 5, 0.05, 0.05, 0.05);
}

/* The wall lit from (0, 4, 3) through a glass sphere (kt .8, absorb
 * (.5, 0, .25)) of centre c and radius r, which lets S through per channel:
 * I = C (ka + kd .6 S) + ks .36 S = .05 + .33 S. */
static void expect_through_glass(V c, double r, const double S[3]) {
  glint_material m = phong_material(), glass;
  glint_material_default(&glass);
  glass.kt = 0.8;
  glass.ior = 1.5;
  glass.absorb = (V){0.5, 0, 0.25};
  glint_scene *s = wall(&m, (V){1, 1, 1});
  ASSERT_OK(glint_scene_add_light(s, (V){0, 4, 3}, (V){1, 1, 1}, &e_));
  ASSERT_OK(glint_scene_add_sphere(s, c, r, material(s, &glass), &e_));
  expect_pixel(s, 5, 0.05 + 0.33 * S[0], 0.05 + 0.33 * S[1],
               0.05 + 0.33 * S[2]);
}

/* A glass sphere on the shadow ray, crossed through its centre: two
 * crossings (kt^2) and a chord of 1 (Beer): S = .64 exp(-absorb). */
static void glass_shadow(void **state) {
  (void)state;
  const double S[3] = {0.64 * exp(-0.5), 0.64, 0.64 * exp(-0.25)};
  expect_through_glass((V){0, 2, 1.5}, 0.5, S);
}

/* The light inside a glass sphere of radius 1 around it: the shadow ray
 * enters it 1 before the light and never leaves, one crossing (kt) and a
 * stretch of 1 (Beer): S = .8 exp(-absorb). (The stretch had no exit, and
 * went unabsorbed: S = .8.) */
static void light_inside_glass(void **state) {
  (void)state;
  const double S[3] = {0.8 * exp(-0.5), 0.8, 0.8 * exp(-0.25)};
  expect_through_glass((V){0, 4, 3}, 1, S);
}

/* Glass whose far side lies 0.002 short of the light, seen through as
 * glass_shadow's: kt^2 and a chord of 1. (Shadow rays that ended a
 * thousandth of the way short of the light, 0.005 here, lost its exit and
 * counted one kt and no Beer.) */
static void glass_just_short_of_the_light(void **state) {
  (void)state;
  const double S[3] = {0.64 * exp(-0.5), 0.64, 0.64 * exp(-0.25)};
  const double along = 4.498 / 5; /* the centre, 4.498 along L */
  expect_through_glass((V){0, 4 * along, 3 * along}, 0.5, S);
}

/* A light on a surface: a ceiling plane through the light, whose crossing
 * lies at the shadow ray's very end. Lit as without the ceiling, at every
 * place along it (rounding put the crossing before the light at some and
 * after it at others, and the lit wall was speckled with shadow). */
static void light_on_a_surface(void **state) {
  (void)state;
  for (int k = 0; k < 8; k++) {
    glint_material m = phong_material(), ceiling;
    glint_material_default(&ceiling);
    glint_scene *s = wall(&m, (V){1, 1, 1});
    double y = 4 + 0.37 * k, z = 3 + 0.61 * k;
    ASSERT_OK(glint_scene_add_light(s, (V){0, y, z}, (V){1, 1, 1}, &e_));
    ASSERT_OK(glint_scene_add_plane(s, (V){0, -1, 0}, (V){0, y, 0},
                                    material(s, &ceiling), &e_));
    /* L = (0, y, z)/|.|, N·L = z/|.|, V·R = N·L (V = N): I = .05 + .25 N·L
     * + .5 (N·L)^2 */
    double nl = z / sqrt(y * y + z * z);
    double i = 0.05 + 0.25 * nl + 0.5 * nl * nl;
    expect_pixel(s, 5, i, i, i);
  }
}

/* A mirror reflects the background: kr bg. Depth 1 traces no reflection. */
static glint_scene *mirror(void) {
  glint_material m;
  glint_material_default(&m);
  m.color = (V){0, 0, 0};
  m.ka = m.kd = 0;
  m.kr = 0.4;
  glint_scene *s = wall(&m, (V){1, 1, 1});
  ASSERT_OK(glint_scene_set_background(s, (V){0.2, 0.4, 0.8}, &e_));
  return s;
}

static void reflection_of_background(void **state) {
  (void)state;
  expect_pixel(mirror(), 2, 0.08, 0.16, 0.32);
}

static void depth_one_has_no_reflection(void **state) {
  (void)state;
  expect_pixel(mirror(), 1, 0, 0, 0);
}

/* Straight through the centre of a clear glass ball (ka = kd = ks = kr = 0):
 * in (kt), a chord of 2 (Beer), out (kt): kt^2 exp(-2 absorb) bg. The ray
 * out is level 3: at depth 2 it is not traced and contributes black. */
static glint_scene *glass_ball(void) {
  glint_material g;
  glint_material_default(&g);
  g.ka = g.kd = 0;
  g.kt = 0.9;
  g.ior = 1.5;
  g.absorb = (V){0.2, 0.1, 0};
  glint_scene *s =
      new_scene((V){0, 0, 5}, (V){0, 0, 0}, (V){0, 1, 0}, (V){0.5, 0.5, 0.5});
  ASSERT_OK(glint_scene_add_sphere(s, (V){0, 0, 0}, 1, material(s, &g), &e_));
  return s;
}

static void beer_through_glass(void **state) {
  (void)state;
  expect_pixel(glass_ball(), 3, 0.405 * exp(-0.4), 0.405 * exp(-0.2), 0.405);
}

static void depth_limit_blacks_out(void **state) {
  (void)state;
  expect_pixel(glass_ball(), 2, 0, 0, 0);
}

/* Under a glass ceiling (the plane y = 0, normal +y; kr .25, kt .75) above a
 * floor lit only by ambient light (C = (0, 1, 0), ka = 1), looking up at 60
 * degrees from the normal: beyond the critical angle (41.8), so the ray is
 * totally reflected with weight kr + kt = 1 and sees the floor. Were it
 * refracted, it would give kt bg + kr floor. */
static void total_internal_reflection_weight(void **state) {
  (void)state;
  glint_material ceiling, floor;
  glint_material_default(&ceiling);
  ceiling.ka = ceiling.kd = 0;
  ceiling.kr = 0.25;
  ceiling.kt = 0.75;
  ceiling.ior = 1.5;
  glint_material_default(&floor);
  floor.color = (V){0, 1, 0};
  floor.ka = 1;
  floor.kd = 0;
  glint_scene *s = new_scene((V){0, -1, 0}, (V){sqrt(0.75), -0.5, 0},
                             (V){0, 0, 1}, (V){0, 0, 1});
  ASSERT_OK(glint_scene_add_plane(s, (V){0, 1, 0}, (V){0, 0, 0},
                                  material(s, &ceiling), &e_));
  ASSERT_OK(glint_scene_add_plane(s, (V){0, 1, 0}, (V){0, -100, 0},
                                  material(s, &floor), &e_));
  expect_pixel(s, 5, 0, 1, 0);
}

/* Faint rays end (docs/specification.md §4, Depth): between two parallel
 * mirrors of kr 1/2 (or 1/4) the centre ray bounces forever, the ray of
 * level L weighing kr^(L-1); it is traced while that is at least 2^-24, so
 * up to level 25 (13), whatever the depth limit beyond: 24 (12) secondary
 * rays. Below that the limit decides: depth 10 traces 9. */
static void faint_rays_end(void **state) {
  (void)state;
  static const struct {
    double kr;
    int depth, secondary;
  } cases[] = {{0.5, 64, 24}, {0.5, 26, 24},  {0.5, 25, 24},
               {0.5, 10, 9},  {0.25, 64, 12}, {0.25, 13, 12}};
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    glint_material m;
    glint_material_default(&m);
    m.ka = m.kd = 0;
    m.kr = cases[i].kr;
    glint_scene *s =
        new_scene((V){0, 0, 0.5}, (V){0, 0, 0}, (V){0, 1, 0}, (V){1, 1, 1});
    uint32_t id = material(s, &m);
    ASSERT_OK(glint_scene_add_plane(s, (V){0, 0, 1}, (V){0, 0, 0}, id, &e_));
    ASSERT_OK(glint_scene_add_plane(s, (V){0, 0, -1}, (V){0, 0, 1}, id, &e_));
    for (int be = GLINT_BACKEND_SCALAR_FLOAT; be < GLINT_BACKEND_COUNT; be++) {
      if (be == GLINT_BACKEND_STREAM || backend_missing((glint_backend)be))
        continue;
      glint_render_settings rs = centre_ray(be, cases[i].depth);
      glint_image *im;
      glint_stats st;
      ASSERT_OK(glint_render(s, &rs, &im, &st, &e_));
      if (st.secondary_rays != (uint64_t)cases[i].secondary)
        fail_msg("%s, kr %g, depth %d: %llu secondary rays, want %d",
                 glint_backend_name((glint_backend)be), cases[i].kr,
                 cases[i].depth, (unsigned long long)st.secondary_rays,
                 cases[i].secondary);
      glint_image_destroy(im);
    }
    glint_scene_destroy(s);
  }
}

/* Planar checker (docs/specification.md §8): floor(x) + floor(z) even at (0.5,
 * 0, 0.5), odd at (1.5, 0, 0.5); ambient light only, so I = C exactly. */
static void planar_checker(void **state) {
  (void)state;
  for (int odd = 0; odd < 2; odd++) {
    glint_material m;
    glint_material_default(&m);
    m.texture = GLINT_TEXTURE_CHECKER_PLANAR;
    m.checker_odd = (V){1, 0, 0};
    m.checker_even = (V){1, 1, 0};
    m.checker_size = 1;
    m.ka = 1;
    m.kd = 0;
    double x = odd ? 1.5 : 0.5;
    glint_scene *s =
        new_scene((V){x, 5, 0.5}, (V){x, 0, 0.5}, (V){0, 0, -1}, (V){0, 0, 0});
    ASSERT_OK(glint_scene_add_plane(s, (V){0, 1, 0}, (V){0, 0, 0},
                                    material(s, &m), &e_));
    expect_pixel(s, 1, 1, odd ? 0 : 1, 0);
  }
}

/* Solid checker in sphere-local coordinates: the front point (0, 0, 1) with
 * cells of 0.5 is at cell z = 2 (even); with cells of 0.3 at z = 3 (odd). */
static void solid_checker(void **state) {
  (void)state;
  for (int odd = 0; odd < 2; odd++) {
    glint_material m;
    glint_material_default(&m);
    m.texture = GLINT_TEXTURE_CHECKER_SOLID;
    m.checker_odd = (V){0.9, 0.9, 0.9};
    m.checker_even = (V){0.8, 0.1, 0.1};
    m.checker_size = odd ? 0.3 : 0.5;
    m.ka = 1;
    m.kd = 0;
    glint_scene *s =
        new_scene((V){10, 10, 15}, (V){10, 10, 10}, (V){0, 1, 0}, (V){0, 0, 0});
    ASSERT_OK(
        glint_scene_add_sphere(s, (V){10, 10, 10}, 1, material(s, &m), &e_));
    if (odd)
      expect_pixel(s, 1, 0.9, 0.9, 0.9);
    else
      expect_pixel(s, 1, 0.8, 0.1, 0.1);
  }
}

/* A transparent plane between a wall and its light is crossed once: kt. */
static void glass_plane_shadow(void **state) {
  (void)state;
  glint_material m = phong_material(), glass;
  glint_material_default(&glass);
  glass.ka = glass.kd = 0;
  glass.kt = 0.7;
  glint_scene *s = wall(&m, (V){1, 1, 1});
  ASSERT_OK(glint_scene_add_light(s, (V){0, 4, 3}, (V){1, 1, 1}, &e_));
  /* The plane y = 1 lies between the wall point and the light (at y = 4)
   * and is parallel to the camera ray, which therefore never meets it. */
  ASSERT_OK(glint_scene_add_plane(s, (V){0, 1, 0}, (V){0, 1, 0},
                                  material(s, &glass), &e_));
  expect_pixel(s, 5, 0.05 + 0.33 * 0.7, 0.05 + 0.33 * 0.7, 0.05 + 0.33 * 0.7);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(diffuse_only),
      cmocka_unit_test(zero_vertex_normals_shade_flat),
      cmocka_unit_test(diffuse_and_highlight),
      cmocka_unit_test(light_behind_surface),
      cmocka_unit_test(opaque_shadow),
      cmocka_unit_test(glass_shadow),
      cmocka_unit_test(glass_plane_shadow),
      cmocka_unit_test(reflection_of_background),
      cmocka_unit_test(depth_one_has_no_reflection),
      cmocka_unit_test(beer_through_glass),
      cmocka_unit_test(light_inside_glass),
      cmocka_unit_test(light_on_a_surface),
      cmocka_unit_test(glass_just_short_of_the_light),
      cmocka_unit_test(depth_limit_blacks_out),
      cmocka_unit_test(total_internal_reflection_weight),
      cmocka_unit_test(faint_rays_end),
      cmocka_unit_test(planar_checker),
      cmocka_unit_test(solid_checker),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
