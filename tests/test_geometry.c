/* Every intersection case of docs/specification.md §3 and the optics of
 * eq. 2.11–2.13, against hand-computed values. Compiled once per precision. */
#include "test_util.h"

#include "geometry/intersect.h"
#include "math/optics.h"

#if defined(GLINT_REAL_FLOAT)
#define TOL 1e-5
#else
#define TOL 1e-12
#endif
#define EPS ((real)1e-4)
#define BIG ((real)1e30)

static void near(double got, double want) {
  if (fabs(got - want) > TOL * fmax(1, fabs(want)))
    fail_msg("got %.9g, want %.9g", got, want);
}

static void near3(vec3 got, double x, double y, double z) {
  near(got.x, x);
  near(got.y, y);
  near(got.z, z);
}

static const vec3 C = {0, 0, -5};
#define R2 ((real)1)

static void sphere_from_outside(void **state) {
  (void)state;
  real t;
  int inside = -1;
  assert_true(
      sphere_hit(C, R2, v3(0, 0, 0), v3(0, 0, -1), EPS, BIG, &t, &inside));
  near(t, 4);
  assert_int_equal(inside, 0);
  /* Off-centre: x = 0.6 gives a half chord of 0.8. */
  assert_true(sphere_hit(C, R2, v3((real)0.6, 0, 0), v3(0, 0, -1), EPS, BIG, &t,
                         &inside));
  near(t, 4.2);
}

static void sphere_from_inside(void **state) {
  (void)state;
  real t;
  int inside = 0;
  assert_true(
      sphere_hit(C, R2, v3(0, 0, -5), v3(0, 0, -1), EPS, BIG, &t, &inside));
  near(t, 1);
  assert_int_equal(inside, 1);
  /* Half-way to the rim, looking sideways: sqrt(1 - 0.25). */
  assert_true(sphere_hit(C, R2, v3(0, 0, (real)-5.5), v3(0, 1, 0), EPS, BIG, &t,
                         &inside));
  near(t, sqrt(0.75));
  assert_int_equal(inside, 1);
}

static void sphere_behind_origin(void **state) {
  (void)state;
  real t;
  int inside;
  assert_false(
      sphere_hit(C, R2, v3(0, 0, 0), v3(0, 0, 1), EPS, BIG, &t, &inside));
}

static void sphere_tangent(void **state) {
  (void)state;
  real t;
  int inside = -1;
  assert_true(
      sphere_hit(C, R2, v3(1, 0, 0), v3(0, 0, -1), EPS, BIG, &t, &inside));
  near(t, 5);
  assert_int_equal(inside, 0);
}

static void sphere_miss(void **state) {
  (void)state;
  real t;
  int inside;
  assert_false(sphere_hit(C, R2, v3((real)1.01, 0, 0), v3(0, 0, -1), EPS, BIG,
                          &t, &inside));
  assert_false(
      sphere_hit(C, R2, v3(0, 0, 0), v3(0, 1, 0), EPS, BIG, &t, &inside));
}

static void sphere_respects_tmax(void **state) {
  (void)state;
  real t;
  int inside;
  assert_false(
      sphere_hit(C, R2, v3(0, 0, 0), v3(0, 0, -1), EPS, 3, &t, &inside));
}

/* A secondary ray leaving the surface must not hit it again at t ~ 0. */
static void sphere_secondary_rays(void **state) {
  (void)state;
  real t;
  int inside = -1;
  /* Reflected outward from the front point (0, 0, -4): misses. */
  assert_false(
      sphere_hit(C, R2, v3(0, 0, -4), v3(0, 0, 1), EPS, BIG, &t, &inside));
  /* Refracted inward: the far side, from inside. */
  assert_true(
      sphere_hit(C, R2, v3(0, 0, -4), v3(0, 0, -1), EPS, BIG, &t, &inside));
  near(t, 2);
  assert_int_equal(inside, 1);
}

static const vec3 UP = {0, 1, 0};

static void plane_hits(void **state) {
  (void)state;
  real t;
  assert_true(plane_hit(UP, 0, v3(0, 1, 0), v3(0, -1, 0), EPS, BIG, &t));
  near(t, 1);
  real s = (real)(1 / sqrt(2.0));
  assert_true(plane_hit(UP, 0, v3(0, 1, 0), v3(s, -s, 0), EPS, BIG, &t));
  near(t, sqrt(2.0));
  /* From the back side (d = -n·P = 2 for the plane y = -2... here y = 0). */
  assert_true(plane_hit(UP, 0, v3(0, -2, 0), v3(0, 1, 0), EPS, BIG, &t));
  near(t, 2);
  /* d != 0: the plane y = 3 is n·X - 3 = 0. */
  assert_true(plane_hit(UP, -3, v3(0, 0, 0), v3(0, 1, 0), EPS, BIG, &t));
  near(t, 3);
}

static void plane_parallel_and_behind(void **state) {
  (void)state;
  real t;
  assert_false(plane_hit(UP, 0, v3(0, 1, 0), v3(1, 0, 0), EPS, BIG, &t));
  assert_false(plane_hit(UP, 0, v3(0, 0, 0), v3(1, 0, 0), EPS, BIG, &t));
  assert_false(plane_hit(UP, 0, v3(0, 1, 0), v3(0, 1, 0), EPS, BIG, &t));
  assert_false(plane_hit(UP, 0, v3(0, 1, 0), v3(0, -1, 0), EPS, (real)0.5, &t));
}

/* triangle_hit for the triangle A, A + e1, A + e2, with its edges and
 * moments about the origin as the scene conversion computes them. */
static int tri_hit(vec3 a, vec3 e1, vec3 e2, vec3 o, vec3 d, real tmin,
                   real tmax, real *t, real *u, real *v) {
  vec3 p[3] = {a, v3_add(a, e1), v3_add(a, e2)};
  vec3 edge[3], moment[3];
  for (int k = 0; k < 3; k++) {
    edge[k] = v3_sub(p[(k + 1) % 3], p[k]);
    moment[k] = v3_cross(p[k], p[(k + 1) % 3]);
  }
  vec3 l = triangle_ray_moment(v3(0, 0, 0), o, d);
  return triangle_hit(a, edge, moment, v3_cross(e1, e2), o, d, l, tmin, tmax, t,
                      u, v);
}

/* The triangle (0,0,0) (1,0,0) (0,1,0), rays straight down -z from z = 1. */
static const vec3 TA = {0, 0, 0}, TE1 = {1, 0, 0}, TE2 = {0, 1, 0};

static int tri(real x, real y, real *t, real *u, real *v) {
  return tri_hit(TA, TE1, TE2, v3(x, y, 1), v3(0, 0, -1), EPS, BIG, t, u, v);
}

static void triangle_inside(void **state) {
  (void)state;
  real t, u, v;
  assert_true(tri((real)0.25, (real)0.25, &t, &u, &v));
  near(t, 1);
  near(u, 0.25);
  near(v, 0.25);
  /* From below (the back side) too. */
  assert_true(tri_hit(TA, TE1, TE2, v3((real)0.2, (real)0.3, -2), v3(0, 0, 1),
                      EPS, BIG, &t, &u, &v));
  near(t, 2);
}

static void triangle_edges_and_vertices(void **state) {
  (void)state;
  real t, u, v;
  assert_true(tri((real)0.5, 0, &t, &u, &v)); /* edge AB: v = 0 */
  near(v, 0);
  assert_true(tri(0, (real)0.5, &t, &u, &v));         /* edge AC: u = 0 */
  assert_true(tri((real)0.5, (real)0.5, &t, &u, &v)); /* edge BC: u + v = 1 */
  near(u + v, 1);
  assert_true(tri(0, 0, &t, &u, &v)); /* vertex A */
  assert_true(tri(1, 0, &t, &u, &v)); /* vertex B */
  near(u, 1);
  assert_true(tri(0, 1, &t, &u, &v)); /* vertex C */
  near(v, 1);
}

static void triangle_outside(void **state) {
  (void)state;
  real t, u, v;
  assert_false(tri((real)0.6, (real)0.6, &t, &u, &v));
  assert_false(tri((real)-0.01, (real)0.5, &t, &u, &v));
  assert_false(tri((real)0.5, (real)-0.01, &t, &u, &v));
  assert_false(tri(2, 2, &t, &u, &v));
  /* Behind the origin and parallel to the plane. */
  assert_false(tri_hit(TA, TE1, TE2, v3((real)0.2, (real)0.2, 1), v3(0, 0, 1),
                       EPS, BIG, &t, &u, &v));
  assert_false(tri_hit(TA, TE1, TE2, v3(-1, (real)0.2, 0), v3(1, 0, 0), EPS,
                       BIG, &t, &u, &v));
}

static void triangle_degenerate(void **state) {
  (void)state;
  real t, u, v;
  /* Collinear vertices: e2 = 2 e1. */
  assert_false(tri_hit(TA, v3(1, 0, 0), v3(2, 0, 0), v3((real)0.5, 0, 1),
                       v3(0, 0, -1), EPS, BIG, &t, &u, &v));
  /* All three vertices the same. */
  assert_false(tri_hit(TA, v3(0, 0, 0), v3(0, 0, 0), v3(0, 0, 1), v3(0, 0, -1),
                       EPS, BIG, &t, &u, &v));
}

static void reflection(void **state) {
  (void)state;
  real s = (real)(1 / sqrt(2.0));
  near3(reflect_dir(v3(s, -s, 0), UP), 1 / sqrt(2.0), 1 / sqrt(2.0), 0);
  near3(reflect_dir(v3(0, -1, 0), UP), 0, 1, 0);
}

static void refraction(void **state) {
  (void)state;
  real s = (real)(1 / sqrt(2.0));
  vec3 t;
  /* 45 degrees into glass (eta = 1/1.5): sin = 0.4714, cos = 0.8819. */
  assert_true(refract_dir(v3(s, -s, 0), UP, (real)(1 / 1.5), &t));
  near3(t, sqrt(0.5) / 1.5, -sqrt(1 - 0.5 / 2.25), 0);
  /* Normal incidence passes straight through. */
  assert_true(refract_dir(v3(0, -1, 0), UP, (real)(1 / 1.5), &t));
  near3(t, 0, -1, 0);
  /* Leaving glass at 30 degrees (below the critical 41.8): sin = 0.75. */
  assert_true(
      refract_dir(v3((real)0.5, -(real)sqrt(0.75), 0), UP, (real)1.5, &t));
  near3(t, 0.75, -sqrt(1 - 0.5625), 0);
}

static void total_internal_reflection(void **state) {
  (void)state;
  vec3 t;
  /* Leaving glass at 60 degrees: 1.5 sin 60 = 1.30 > 1. */
  assert_false(
      refract_dir(v3((real)sqrt(0.75), (real)-0.5, 0), UP, (real)1.5, &t));
  /* Just below the critical angle it still refracts. */
  real sc = (real)(1 / 1.5 - 1e-3);
  assert_true(
      refract_dir(v3(sc, -(real)sqrt(1 - sc * sc), 0), UP, (real)1.5, &t));
}

static void beer_attenuation(void **state) {
  (void)state;
  near3(beer(v3((real)0.1, (real)0.5, 0), 2), exp(-0.2), exp(-1.0), 1);
  near3(beer(v3(1, 2, 3), 0), 1, 1, 1);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(sphere_from_outside),
      cmocka_unit_test(sphere_from_inside),
      cmocka_unit_test(sphere_behind_origin),
      cmocka_unit_test(sphere_tangent),
      cmocka_unit_test(sphere_miss),
      cmocka_unit_test(sphere_respects_tmax),
      cmocka_unit_test(sphere_secondary_rays),
      cmocka_unit_test(plane_hits),
      cmocka_unit_test(plane_parallel_and_behind),
      cmocka_unit_test(triangle_inside),
      cmocka_unit_test(triangle_edges_and_vertices),
      cmocka_unit_test(triangle_outside),
      cmocka_unit_test(triangle_degenerate),
      cmocka_unit_test(reflection),
      cmocka_unit_test(refraction),
      cmocka_unit_test(total_internal_reflection),
      cmocka_unit_test(beer_attenuation),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
