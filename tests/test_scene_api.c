/* The library's argument checking: every bad value is refused with
 * GLINT_E_ARGUMENT and a message, and nothing NaN reaches a tracer. */
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef glint_vec3 V;

#define EXPECT_ERR(call, want, text)                                           \
  do {                                                                         \
    glint_error e_;                                                            \
    e_.message[0] = '\0';                                                      \
    glint_status st_ = (call);                                                 \
    assert_int_equal(st_, want);                                               \
    assert_int_equal(e_.status, want);                                         \
    if (!strstr(e_.message, text))                                             \
      fail_msg("message '%s' lacks '%s'", e_.message, text);                   \
  } while (0)

static void primitives_refuse_bad_numbers(void **state) {
  (void)state;
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  V ok = {0, 0, 0}, nan3 = {NAN, 0, 0}, inf3 = {0, INFINITY, 0};
  EXPECT_ERR(glint_scene_add_sphere(s, nan3, 1, m, &e_), GLINT_E_ARGUMENT,
             "finite");
  EXPECT_ERR(glint_scene_add_sphere(s, ok, NAN, m, &e_), GLINT_E_ARGUMENT,
             "finite");
  EXPECT_ERR(glint_scene_add_sphere(s, ok, -1, m, &e_), GLINT_E_ARGUMENT,
             "radius");
  EXPECT_ERR(glint_scene_add_sphere(s, ok, 0, m, &e_), GLINT_E_ARGUMENT,
             "radius");
  EXPECT_ERR(glint_scene_add_sphere(s, ok, 1, m + 1, &e_), GLINT_E_ARGUMENT,
             "material");
  EXPECT_ERR(glint_scene_add_plane(s, (V){0, 0, 0}, ok, m, &e_),
             GLINT_E_ARGUMENT, "normal");
  EXPECT_ERR(glint_scene_add_plane(s, inf3, ok, m, &e_), GLINT_E_ARGUMENT,
             "finite");
  EXPECT_ERR(glint_scene_add_triangle(s, ok, nan3, ok, m, &e_),
             GLINT_E_ARGUMENT, "finite");
  EXPECT_ERR(glint_scene_add_cone(s, ok, 1, ok, 0.5, m, &e_), GLINT_E_ARGUMENT,
             "same point");
  EXPECT_ERR(glint_scene_add_cone(s, ok, 0, (V){0, 1, 0}, 0, m, &e_),
             GLINT_E_ARGUMENT, "radii");
  /* apart, but too little for a direction in double precision */
  EXPECT_ERR(glint_scene_add_cone(s, ok, 1, (V){0, 0, 1e-300}, 1, m, &e_),
             GLINT_E_ARGUMENT, "too close for an axis");
  glint_camera near_cam = {{0, 0, 1e-300}, {0, 0, 0}, {0, 1, 0}, 40};
  EXPECT_ERR(glint_scene_set_camera(s, &near_cam, &e_), GLINT_E_ARGUMENT,
             "too close for a direction");
  EXPECT_ERR(glint_scene_set_camera_orbit(s, (V){1e300, 0, 0}, 1, 0, 360, &e_),
             GLINT_E_ARGUMENT, "magnitude at most 1e15");
  EXPECT_ERR(glint_scene_set_camera_orbit(s, ok, 1, 0, 1e308, &e_),
             GLINT_E_ARGUMENT, "degrees must be finite numbers of magnitude");
  EXPECT_ERR(glint_scene_add_light(s, nan3, (V){1, 1, 1}, &e_),
             GLINT_E_ARGUMENT, "finite");
  EXPECT_ERR(glint_scene_add_light(s, ok, (V){-1, 1, 1}, &e_), GLINT_E_ARGUMENT,
             "negative");
  EXPECT_ERR(glint_scene_set_background(s, nan3, &e_), GLINT_E_ARGUMENT,
             "finite");
  /* Nothing was added by the failed calls. */
  glint_scene_info info;
  glint_scene_get_info(s, &info);
  assert_int_equal(info.objects, 0);
  assert_int_equal(info.spheres + info.planes + info.triangles + info.cones, 0);
  glint_scene_destroy(s);
}

/* The scene's bounds (glint_scene_info): a sphere's centre +- its radius,
 * triangles' vertices, a cone's two ends +- its larger radius; planes are
 * unbounded and left out. */
static void info_bounds_every_shape(void **state) {
  (void)state;
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  glint_scene_info info;
  glint_scene_get_info(s, &info);
  assert_true(info.bounds_min.x == INFINITY && info.bounds_max.z == -INFINITY);
  ASSERT_OK(glint_scene_add_sphere(s, (V){1, 2, 3}, 0.5, m, NULL));
  ASSERT_OK(glint_scene_add_triangle(s, (V){-4, 0, 0}, (V){0, 7, 0},
                                     (V){0, 0, 2}, m, NULL));
  ASSERT_OK(
      glint_scene_add_cone(s, (V){0, 0, -3}, 0.25, (V){0, 0, -1}, 1, m, NULL));
  ASSERT_OK(glint_scene_add_plane(s, (V){0, 1, 0}, (V){0, -100, 0}, m, NULL));
  glint_scene_get_info(s, &info);
  assert_true(info.bounds_min.x == -4 && info.bounds_max.x == 1.5);
  assert_true(info.bounds_min.y == -1 && info.bounds_max.y == 7);
  assert_true(info.bounds_min.z == -4 && info.bounds_max.z == 3.5);
  /* The smallest object: the sphere's radius 0.5 (the cone's larger
   * radius is 1, the triangle's longest side of its box 7); epsilon is
   * 1e-4 of the largest coordinate, the triangle's 7 or the camera's. */
  double epsilon, smallest;
  glint_scene_get_scale(s, &epsilon, &smallest);
  assert_true(smallest == 0.5);
  V from = info.camera.from;
  double largest =
      fmax(7, fmax(fabs(from.x), fmax(fabs(from.y), fabs(from.z))));
  assert_true(fabs(epsilon - 1e-4 * largest) <= 1e-12 * largest);
  /* One far sphere makes it large for everything. */
  ASSERT_OK(glint_scene_add_sphere(s, (V){0, 0, -1e6}, 1, m, NULL));
  glint_scene_get_scale(s, &epsilon, &smallest);
  assert_true(fabs(epsilon - 100.0001) <= 1e-9);
  assert_true(smallest == 0.5);
  /* A cone flat against its radii measures its height, which the float
   * backends cannot trace against radius 2 (they drew it differently). */
  ASSERT_OK(
      glint_scene_add_cone(s, (V){5, 0, 0}, 2, (V){5, 0.001, 0}, 0.5, m, NULL));
  glint_scene_get_scale(s, &epsilon, &smallest);
  assert_true(fabs(smallest - 0.001) <= 1e-15);
  glint_scene_get_scale(NULL, &epsilon, NULL);
  assert_true(epsilon == 0);
  glint_scene_destroy(s);
}

/* NULL where glint.h requires a pointer is refused with the function's
 * name and the argument's (it crashed before: glint_render rendered the
 * whole frame first); the functions that cannot fail answer NULL with
 * nothing. And counts whose products would wrap are refused before use. */
/* A message is one line whatever it quotes: control characters in a file
 * name are shown as '?', and a name longer than the message keeps the
 * message's end, where the problem is said. */
static void messages_are_one_clean_line(void **state) {
  (void)state;
  glint_scene *s = NULL;
  glint_error e;
  assert_int_equal(glint_scene_load("no\033[31m\nsuch.nff", &s, &e),
                   GLINT_E_IO);
  assert_string_equal(e.message, "no?[31m?such.nff: No such file or directory");
  char path[5008];
  for (int i = 0; i < 2500; i++)
    memcpy(path + 2 * i, "./", 2);
  memcpy(path + 5000, "x.nff", 6);
  assert_int_equal(glint_scene_load(path, &s, &e), GLINT_E_IO);
  assert_int_equal(strlen(e.message), sizeof e.message - 1);
  assert_memory_equal(e.message, "././", 4);
  const char *end = "./x.nff: File name too long";
  assert_string_equal(e.message + strlen(e.message) - strlen(end), end);
  assert_non_null(strstr(e.message, "..."));
}

static void null_and_overflowing_arguments_are_refused(void **state) {
  (void)state;
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  glint_scene *out;
  glint_image *im;
  glint_film *film;
  glint_backend b;
  EXPECT_ERR(glint_scene_create(NULL, &e_), GLINT_E_ARGUMENT,
             "glint_scene_create: scene is NULL");
  /* The functions that cannot fail answer NULL with nothing. */
  glint_material_default(NULL);
  glint_render_settings_default(NULL);
  glint_frame_settings_default(NULL);
  glint_transform_identity(NULL);
  glint_camera_key key = {0, {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40}};
  EXPECT_ERR(
      glint_scene_set_camera_keys(NULL, &key, 1, GLINT_INTERPOLATE_LINEAR, &e_),
      GLINT_E_ARGUMENT, "glint_scene_set_camera_keys: scene is NULL");
  EXPECT_ERR(glint_scene_set_animation(s, NULL, &e_), GLINT_E_ARGUMENT,
             "glint_scene_set_animation: animation is NULL");
  /* (it said "mesh: missing arrays") */
  EXPECT_ERR(glint_scene_add_mesh(s, NULL, m, &e_), GLINT_E_ARGUMENT,
             "glint_scene_add_mesh: mesh is NULL");
  EXPECT_ERR(glint_scene_load_memory("{}", 2, NULL, &out, &e_),
             GLINT_E_ARGUMENT, "glint_scene_load_memory: name is NULL");
  EXPECT_ERR(glint_scene_load_packed(NULL, 8, &out, &e_), GLINT_E_ARGUMENT,
             "glint_scene_load_packed: packed is NULL");
  EXPECT_ERR(glint_scene_load_packed(NULL, 0, &out, &e_), GLINT_E_ARGUMENT,
             "glint_scene_load_packed: packed is NULL");
  EXPECT_ERR(glint_scene_load_packed("GLINTPK1", SIZE_MAX, &out, &e_),
             GLINT_E_PARSE, "packed scene: damaged (size)");
  EXPECT_ERR(glint_world_commit_at(NULL, 0, NULL, NULL, NULL, &e_),
             GLINT_E_ARGUMENT, "glint_world_commit_at: scene is NULL");
  EXPECT_ERR(glint_image_write_encoded(NULL, "x", 1, &e_), GLINT_E_ARGUMENT,
             "glint_image_write_encoded: path is NULL");
  EXPECT_ERR(glint_scene_set_camera(s, NULL, &e_), GLINT_E_ARGUMENT,
             "glint_scene_set_camera: camera is NULL");
  EXPECT_ERR(glint_scene_add_material(s, NULL, NULL, &e_), GLINT_E_ARGUMENT,
             "material is NULL");
  EXPECT_ERR(glint_scene_add_sphere(NULL, (V){0, 0, 0}, 1, m, &e_),
             GLINT_E_ARGUMENT, "glint_scene_add_sphere: scene is NULL");
  EXPECT_ERR(glint_scene_builtin(NULL, &out, &e_), GLINT_E_ARGUMENT,
             "name is NULL");
  EXPECT_ERR(glint_scene_camera_at(s, 0, NULL, &e_), GLINT_E_ARGUMENT,
             "camera is NULL");
  EXPECT_ERR(glint_scene_at_time(NULL, 0, &out, &e_), GLINT_E_ARGUMENT,
             "scene is NULL");
  EXPECT_ERR(glint_backend_parse("sse", NULL, &e_), GLINT_E_ARGUMENT,
             "backend is NULL");
  EXPECT_ERR(glint_backend_parse(NULL, &b, &e_), GLINT_E_ARGUMENT,
             "name is NULL");
  EXPECT_ERR(glint_render(s, NULL, NULL, NULL, &e_), GLINT_E_ARGUMENT,
             "glint_render: image is NULL");
  EXPECT_ERR(glint_world_commit(s, NULL, NULL, &e_), GLINT_E_ARGUMENT,
             "world is NULL");
  EXPECT_ERR(glint_image_create(4, 4, NULL, &e_), GLINT_E_ARGUMENT,
             "image is NULL");
  EXPECT_ERR(glint_image_read(NULL, &im, &e_), GLINT_E_ARGUMENT,
             "path is NULL");
  EXPECT_ERR(glint_film_create(4, 4, NULL, &e_), GLINT_E_ARGUMENT,
             "film is NULL");
  ASSERT_OK(glint_film_create(4, 4, &film, NULL));
  EXPECT_ERR(glint_film_to_image(film, 1, NULL, &e_), GLINT_E_ARGUMENT,
             "image is NULL");
  EXPECT_ERR(glint_film_write(film, NULL, &e_), GLINT_E_ARGUMENT,
             "path is NULL");
  glint_film_destroy(film);
  assert_int_equal(glint_image_width(NULL), 0);
  assert_null(glint_image_pixels(NULL));
  assert_int_equal(glint_image_format_from_path(NULL), GLINT_FORMAT_UNKNOWN);
  assert_true(glint_image_psnr(NULL, NULL) < 0);
  assert_int_equal(glint_scene_has_motion(NULL), 0);
  glint_scene_info info;
  glint_scene_get_info(NULL, &info);
  assert_int_equal(info.objects, 0);
  /* 3 * triangle_count wrapped to 2: two indices were checked and the
   * third, out of range, read beyond the positions */
  glint_vec3 pos[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  uint32_t idx[3] = {0, 1, 3};
  glint_mesh mesh = {pos, NULL, 3, idx, SIZE_MAX / 3 + 1};
  EXPECT_ERR(glint_scene_add_mesh(s, &mesh, m, &e_), GLINT_E_ARGUMENT,
             "more than a scene holds");
  glint_scene_destroy(s);
}

/* Default settings at a size, on one backend. */
static glint_render_settings settings_for(glint_backend backend, int width,
                                          int height) {
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.width = width;
  rs.height = height;
  rs.backend = backend;
  return rs;
}

#define SCALED_W 24
#define SCALED_H 16

/* Lights scene s from above and renders it (scalar-double, SCALED_W x
 * SCALED_H); the first of a series (k == 0) is kept in `first`, which must
 * show the plane (not one colour), and every later one must equal it.
 * Destroys s. */
static void renders_as_the_first(glint_scene *s, int k, uint8_t *first) {
  const size_t bytes = SCALED_W * SCALED_H * 3;
  ASSERT_OK(glint_scene_add_light(s, (V){0, 10, 0}, (V){1, 1, 1}, &e_));
  glint_render_settings rs =
      settings_for(GLINT_BACKEND_SCALAR_DOUBLE, SCALED_W, SCALED_H);
  glint_image *img;
  ASSERT_OK(glint_render(s, &rs, &img, NULL, &e_));
  const uint8_t *px = glint_image_pixels_const(img);
  if (k == 0) {
    memcpy(first, px, bytes);
    /* the plane is in view: the image is not one colour */
    assert_true(memcmp(px, px + bytes - 3, 3) != 0);
  } else
    assert_memory_equal(px, first, bytes);
  glint_image_destroy(img);
  glint_scene_destroy(s);
}

/* A plane's normal need not be unit length (glint.h), however short or
 * long: a normal of 1e-200, whose squared length underflows, draws the
 * plane a unit normal draws (it was refused as zero). */
static void plane_normals_of_any_length(void **state) {
  (void)state;
  const double scale[] = {1, 1e-200, 1e15};
  uint8_t first[SCALED_W * SCALED_H * 3];
  for (int k = 0; k < 3; k++) {
    uint32_t m;
    glint_scene *s = scene_with_default_material(&m);
    V n = {0, scale[k], scale[k] * 0.25};
    ASSERT_OK(glint_scene_add_plane(s, n, (V){0, -1, 0}, m, &e_));
    renders_as_the_first(s, k, first);
  }
}

/* A camera's up need not be unit length either: an up of 1e-300, whose
 * cross product with the view direction underflowed, was refused as "zero
 * or parallel"; it draws what a unit up draws, and so does 1e15's. */
static void camera_up_of_any_length(void **state) {
  (void)state;
  const double scale[] = {1, 1e-300, 1e15};
  uint8_t first[SCALED_W * SCALED_H * 3];
  for (int k = 0; k < 3; k++) {
    uint32_t m;
    glint_scene *s = scene_with_default_material(&m);
    glint_camera cam = {
        {0, 0, 5}, {0, 0, 0}, {scale[k] * 0.5, scale[k], 0}, 60};
    ASSERT_OK(glint_scene_set_camera(s, &cam, &e_));
    ASSERT_OK(glint_scene_add_plane(s, (V){0, 1, 0.25}, (V){0, -1, 0}, m, &e_));
    renders_as_the_first(s, k, first);
  }
}

/* GLINT_MAX_COORDINATE: 1e15 and -1e15 are accepted everywhere a scene
 * takes a coordinate or a size, anything beyond is refused with the
 * limit named; and at the limit every backend still draws the image double
 * precision draws: a sphere of radius 1e15 round the camera, seen from
 * inside, lights every pixel (its squared radius, 1e30, is far inside
 * single precision; 1e20's, 1e40, would overflow it and leave the image
 * black in float and white in double, as before the limit). */
static void coordinates_stay_within_the_limit(void **state) {
  (void)state;
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  V ok = {0, 0, 0}, far = {0, 0, 1.0000001e15}, edge = {-1e15, 0, 0};
  const char *limit = "magnitude at most 1e15";
  EXPECT_ERR(glint_scene_add_sphere(s, far, 1, m, &e_), GLINT_E_ARGUMENT,
             limit);
  EXPECT_ERR(glint_scene_add_sphere(s, ok, 1e300, m, &e_), GLINT_E_ARGUMENT,
             limit);
  EXPECT_ERR(glint_scene_add_plane(s, (V){0, 1, 0}, far, m, &e_),
             GLINT_E_ARGUMENT, limit);
  EXPECT_ERR(glint_scene_add_triangle(s, ok, (V){1, 0, 0}, far, m, &e_),
             GLINT_E_ARGUMENT, limit);
  EXPECT_ERR(glint_scene_add_cone(s, ok, 1, far, 0.5, m, &e_), GLINT_E_ARGUMENT,
             limit);
  EXPECT_ERR(glint_scene_add_cone(s, ok, 2e15, (V){0, 1, 0}, 0, m, &e_),
             GLINT_E_ARGUMENT, limit);
  EXPECT_ERR(glint_scene_add_light(s, far, (V){1, 1, 1}, &e_), GLINT_E_ARGUMENT,
             limit);
  glint_camera cam = {{0, 0, -8}, {0, 0, 0}, {0, 1, 0}, 40};
  cam.from = far;
  EXPECT_ERR(glint_scene_set_camera(s, &cam, &e_), GLINT_E_ARGUMENT, limit);
  glint_scene_info info;
  glint_scene_get_info(s, &info);
  assert_int_equal(info.objects, 0);

  ASSERT_OK(glint_scene_add_sphere(s, edge, 1, m, &e_));
  ASSERT_OK(glint_scene_add_sphere(s, ok, 1e15, m, &e_));
  ASSERT_OK(glint_scene_add_light(s, (V){0, 5, -5}, (V){1, 1, 1}, &e_));
  cam.from = (V){0, 0, -8};
  ASSERT_OK(glint_scene_set_camera(s, &cam, &e_));
  for (int be = GLINT_BACKEND_SCALAR_FLOAT; be < GLINT_BACKEND_COUNT; be++) {
    if (backend_missing((glint_backend)be))
      continue;
    glint_render_settings rs = settings_for((glint_backend)be, 16, 12);
    glint_image *im;
    ASSERT_OK(glint_render(s, &rs, &im, NULL, &e_));
    const uint8_t *p = glint_image_pixels_const(im);
    for (int i = 0; i < 16 * 12 * 3; i++)
      if (p[i] == 0)
        fail_msg("%s: pixel %d of the huge sphere is black",
                 glint_backend_name((glint_backend)be), i / 3);
    glint_image_destroy(im);
  }
  glint_scene_destroy(s);
}

static void materials_refuse_bad_values(void **state) {
  (void)state;
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  glint_material mat;
  glint_material_default(&mat);
  mat.kd = -0.5;
  EXPECT_ERR(glint_scene_add_material(s, &mat, NULL, &e_), GLINT_E_ARGUMENT,
             "kd");
  glint_material_default(&mat);
  mat.h = NAN;
  EXPECT_ERR(glint_scene_add_material(s, &mat, NULL, &e_), GLINT_E_ARGUMENT,
             "h");
  glint_material_default(&mat);
  mat.ior = 0;
  EXPECT_ERR(glint_scene_add_material(s, &mat, NULL, &e_), GLINT_E_ARGUMENT,
             "ior");
  glint_material_default(&mat);
  mat.texture = GLINT_TEXTURE_CHECKER_SOLID;
  mat.checker_size = 0;
  EXPECT_ERR(glint_scene_add_material(s, &mat, NULL, &e_), GLINT_E_ARGUMENT,
             "checker size");
  /* GLINT_MAX_COLOR: a light of 1e39 is infinite in float, and times a zero
   * weight NaN (the beams and the scalar tracer drew different images). */
  glint_material_default(&mat);
  mat.kr = GLINT_MAX_COLOR * 10;
  EXPECT_ERR(glint_scene_add_material(s, &mat, NULL, &e_), GLINT_E_ARGUMENT,
             "material kr = 1e+07 must not exceed 1e+06");
  glint_material_default(&mat);
  mat.ior = 1e-30;
  EXPECT_ERR(glint_scene_add_material(s, &mat, NULL, &e_), GLINT_E_ARGUMENT,
             "ior = 1e-30 is outside 1e-06..1e+06");
  glint_material_default(&mat);
  mat.color.y = 1e39;
  EXPECT_ERR(glint_scene_add_material(s, &mat, NULL, &e_), GLINT_E_ARGUMENT,
             "material colour must not exceed 1e+06");
  EXPECT_ERR(glint_scene_add_light(s, (V){0, 5, 0}, (V){1e39, 1, 1}, &e_),
             GLINT_E_ARGUMENT, "light colour must not exceed 1e+06");
  glint_material_default(&mat);
  mat.kr = mat.ks = GLINT_MAX_COLOR; /* the limits themselves are accepted */
  mat.h = 1e30;                      /* (the exponent has none) */
  mat.ior = 1 / GLINT_MAX_COLOR;
  ASSERT_OK(glint_scene_add_material(s, &mat, NULL, &e_));
  ASSERT_OK(
      glint_scene_add_light(s, (V){0, 5, 0}, (V){GLINT_MAX_COLOR, 1, 1}, &e_));
  glint_scene_destroy(s);
}

static void camera_refuses_degenerate_views(void **state) {
  (void)state;
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  glint_camera c = {{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 60};
  EXPECT_ERR(glint_scene_set_camera(s, &c, &e_), GLINT_E_ARGUMENT,
             "same point");
  c.at = (V){0, 5, 0};
  EXPECT_ERR(glint_scene_set_camera(s, &c, &e_), GLINT_E_ARGUMENT, "parallel");
  c.at = (V){0, 0, -1};
  c.fov_x_degrees = 180;
  EXPECT_ERR(glint_scene_set_camera(s, &c, &e_), GLINT_E_ARGUMENT,
             "field of view");
  c.fov_x_degrees = NAN;
  EXPECT_ERR(glint_scene_set_camera(s, &c, &e_), GLINT_E_ARGUMENT, "finite");
  EXPECT_ERR(glint_scene_set_resolution(s, 0, 10, &e_), GLINT_E_ARGUMENT,
             "resolution");
  EXPECT_ERR(glint_scene_set_resolution(s, 10, GLINT_MAX_DIMENSION + 1, &e_),
             GLINT_E_ARGUMENT, "resolution");
  glint_scene_destroy(s);
}

static void render_refuses_bad_settings(void **state) {
  (void)state;
  glint_scene *s;
  ASSERT_OK(glint_scene_builtin("whitted", &s, &e_));
  glint_image *im = NULL;
  glint_render_settings rs;
#define CASE(field, value, text)                                               \
  glint_render_settings_default(&rs);                                          \
  rs.field = value;                                                            \
  EXPECT_ERR(glint_render(s, &rs, &im, NULL, &e_), GLINT_E_ARGUMENT, text);    \
  assert_null(im);
  CASE(max_depth, 0, "depth")
  CASE(max_depth, GLINT_MAX_DEPTH + 1, "depth")
  CASE(spp, 0, "samples")
  CASE(spp, GLINT_MAX_SPP + 1, "samples")
  CASE(width, -3, "width")
  CASE(width, GLINT_MAX_DIMENSION + 1, "width")
  CASE(height, -1, "height")
  CASE(threads, -1, "threads")
  CASE(gamma, 0, "gamma")
  CASE(gamma, NAN, "gamma")
  CASE(gamma, GLINT_MAX_GAMMA * 1.01, "gamma")
  CASE(gamma, GLINT_MIN_GAMMA * 0.99, "gamma")
  CASE(backend, (glint_backend)99, "backend")
  CASE(rcp_newton, 5, "rcp_newton 5 is neither 0 nor 1")
#undef CASE
  /* Without SIMD (GLINT_ISA=none) there is no stream backend: STREAM is
   * refused as glint_backend_supported says, not run as scalar-float; AUTO
   * still renders (with scalar-float). */
  setenv("GLINT_ISA", "none", 1);
  assert_false(glint_backend_supported(GLINT_BACKEND_STREAM));
  glint_render_settings_default(&rs);
  rs.width = 8, rs.height = 6, rs.threads = 1;
  rs.backend = GLINT_BACKEND_STREAM;
  EXPECT_ERR(glint_render(s, &rs, &im, NULL, &e_), GLINT_E_UNSUPPORTED,
             "backend 'stream' is not supported");
  assert_null(im);
  rs.backend = GLINT_BACKEND_AUTO;
  glint_stats st;
  ASSERT_OK(glint_render(s, &rs, &im, &st, &e_));
  assert_int_equal(st.backend, GLINT_BACKEND_SCALAR_FLOAT);
  glint_image_destroy(im);
  unsetenv("GLINT_ISA");
  glint_scene_destroy(s);
}

static void names_parse_and_print(void **state) {
  (void)state;
  glint_backend b;
  ASSERT_OK(glint_backend_parse("scalar-double", &b, &e_));
  assert_int_equal(b, GLINT_BACKEND_SCALAR_DOUBLE);
  assert_string_equal(glint_backend_name(b), "scalar-double");
  EXPECT_ERR(glint_backend_parse("gpu", &b, &e_), GLINT_E_ARGUMENT,
             "unknown backend 'gpu'");
  glint_math m;
  ASSERT_OK(glint_math_parse("taylor", &m, &e_));
  assert_int_equal(m, GLINT_MATH_TAYLOR);
  EXPECT_ERR(glint_math_parse("exactish", &m, &e_), GLINT_E_ARGUMENT,
             "unknown math");
  glint_scene *s = NULL;
  EXPECT_ERR(glint_scene_builtin("cornell", &s, &e_), GLINT_E_ARGUMENT,
             "unknown scene 'cornell'");
  assert_null(s);
  assert_true(glint_backend_supported(GLINT_BACKEND_SCALAR_FLOAT));
  assert_true(glint_backend_supported(GLINT_BACKEND_AUTO));
  assert_int_equal(glint_backend_width(GLINT_BACKEND_SCALAR_DOUBLE), 1);
}

static void builtin_scenes_match_the_spec(void **state) {
  (void)state;
  static const struct {
    const char *name;
    size_t spheres, planes, triangles;
  } want[] = {{"whitted", 1, 1, 0},
              {"giza", 0, 1, 26},
              {"billiard", 10, 1, 0},
              {"phong", 16, 0, 0}};
  assert_int_equal(glint_builtin_scene_count(), 4);
  for (size_t i = 0; i < 4; i++) {
    glint_scene *s;
    assert_string_equal(glint_builtin_scene_name(i), want[i].name);
    ASSERT_OK(glint_scene_builtin(want[i].name, &s, &e_));
    glint_scene_info info;
    glint_scene_get_info(s, &info);
    assert_int_equal(info.spheres, want[i].spheres);
    assert_int_equal(info.planes, want[i].planes);
    assert_int_equal(info.triangles, want[i].triangles);
    assert_int_equal(info.lights, 1);
    assert_int_equal(info.width, 640);
    assert_int_equal(info.height, 480);
    glint_scene_destroy(s);
  }
}

static void mesh_indices_checked(void **state) {
  (void)state;
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  V p[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  uint32_t bad[3] = {0, 1, 3};
  glint_mesh mesh = {p, NULL, 3, bad, 1};
  EXPECT_ERR(glint_scene_add_mesh(s, &mesh, m, &e_), GLINT_E_ARGUMENT,
             "vertex 3");
  uint32_t good[3] = {0, 1, 2};
  mesh.indices = good;
  ASSERT_OK(glint_scene_add_mesh(s, &mesh, m, &e_));
  glint_scene_info info;
  glint_scene_get_info(s, &info);
  assert_int_equal(info.triangles, 1);
  assert_int_equal(info.objects, 1);
  /* NULL arrays: refused where they have elements, an empty mesh taken
   * with NULL arrays as with non-NULL ones */
  glint_mesh no_positions = {NULL, NULL, 3, good, 1};
  EXPECT_ERR(glint_scene_add_mesh(s, &no_positions, m, &e_), GLINT_E_ARGUMENT,
             "mesh: positions is NULL, but vertex_count is 3");
  glint_mesh no_indices = {p, NULL, 3, NULL, 1};
  EXPECT_ERR(glint_scene_add_mesh(s, &no_indices, m, &e_), GLINT_E_ARGUMENT,
             "mesh: indices is NULL, but triangle_count is 1");
  glint_mesh empty_null = {NULL, NULL, 0, NULL, 0};
  glint_mesh empty = {p, NULL, 0, good, 0};
  ASSERT_OK(glint_scene_add_mesh(s, &empty_null, m, &e_));
  ASSERT_OK(glint_scene_add_mesh(s, &empty, m, &e_));
  glint_scene_get_info(s, &info);
  assert_int_equal(info.triangles, 1);
  assert_int_equal(info.objects, 3);
  glint_scene_destroy(s);
}

/* A region is exactly that window of the full frame, on every backend.
 * On Whitted with the fast maths too: a beam's shadow rays through its
 * absorbing glass sphere gave the lanes that crossed no absorber the fast
 * exp's e^0 = 0.978 as well, so a pixel's shadow depended on its packet's
 * other pixels and a region's border pixels differed by up to 2 levels. */
static void region_is_a_window_of_the_frame(void **state) {
  (void)state;
  static const struct {
    const char *scene;
    glint_math math;
  } cases[] = {{"billiard", GLINT_MATH_MINIMAX}, {"whitted", GLINT_MATH_FAST}};
  for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
    glint_scene *s;
    ASSERT_OK(glint_scene_builtin(cases[c].scene, &s, &e_));
    for (int be = GLINT_BACKEND_SCALAR_FLOAT; be <= GLINT_BACKEND_AVX512;
         be++) {
      if (backend_missing((glint_backend)be))
        continue;
      glint_render_settings rs = settings_for((glint_backend)be, 96, 72);
      rs.math = cases[c].math;
      glint_image *full, *part;
      ASSERT_OK(glint_render(s, &rs, &full, NULL, &e_));
      rs.region_x = 13;
      rs.region_y = 7;
      rs.region_width = 41;
      rs.region_height = 30;
      ASSERT_OK(glint_render(s, &rs, &part, NULL, &e_));
      assert_int_equal(glint_image_width(part), 41);
      assert_int_equal(glint_image_height(part), 30);
      const uint8_t *f = glint_image_pixels_const(full);
      const uint8_t *p = glint_image_pixels_const(part);
      for (int y = 0; y < 30; y++)
        assert_memory_equal(p + (size_t)y * 41 * 3,
                            f + ((size_t)(y + 7) * 96 + 13) * 3, 41 * 3);
      rs.region_x = 60; /* 60 + 41 > 96 */
      glint_image *bad = NULL;
      glint_error e;
      assert_int_equal(glint_render(s, &rs, &bad, NULL, &e), GLINT_E_ARGUMENT);
      assert_non_null(strstr(e.message, "region"));
      rs.region_width = 0; /* one side without the other */
      assert_int_equal(glint_render(s, &rs, &bad, NULL, &e), GLINT_E_ARGUMENT);
      assert_non_null(strstr(e.message, "region 0x30: its width and height"));
      rs.region_height = 0; /* a corner without a size */
      assert_int_equal(glint_render(s, &rs, &bad, NULL, &e), GLINT_E_ARGUMENT);
      assert_non_null(strstr(e.message, "region at 60,7 has no size"));
      rs.region_x = rs.region_y = -3;
      assert_int_equal(glint_render(s, &rs, &bad, NULL, &e), GLINT_E_ARGUMENT);
      assert_non_null(strstr(e.message, "region at -3,-3 has no size"));
      glint_image_destroy(full);
      glint_image_destroy(part);
    }
    glint_scene_destroy(s);
  }
}

/* A scene from memory is the scene from its file; the name chooses the
 * format and stands for the file in messages. */
static void scenes_load_from_memory(void **state) {
  (void)state;
  glint_error e;
  glint_scene *from_file, *from_memory;
  char path[512];
  snprintf(path, sizeof path, "%s/scenes/billiard.json", GLINT_SOURCE_DIR);
  FILE *f = fopen(path, "rb");
  assert_non_null(f);
  static char text[1 << 16];
  size_t n = fread(text, 1, sizeof text, f);
  fclose(f);
  assert_true(n > 0 && n < sizeof text);
  ASSERT_OK(glint_scene_load(path, &from_file, &e));
  ASSERT_OK(
      glint_scene_load_memory(text, n, "billiard.json", &from_memory, &e));
  glint_scene_info a, b;
  glint_scene_get_info(from_file, &a);
  glint_scene_get_info(from_memory, &b);
  assert_int_equal(a.spheres, b.spheres);
  assert_int_equal(a.materials, b.materials);
  assert_memory_equal(&a.camera, &b.camera, sizeof a.camera);
  glint_scene_destroy(from_file);
  glint_scene_destroy(from_memory);

  static const char nff[] = "b 0 0 1\nv\nfrom 0 0 -8\nat 0 0 0\nup 0 1 0\n"
                            "angle 45\nhither 1\nresolution 32 24\n"
                            "l 1 1 -5\nf 1 0 0 1 0 0 0 1\ns 0 0 0 1\n";
  ASSERT_OK(
      glint_scene_load_memory(nff, strlen(nff), "ball.nff", &from_memory, &e));
  glint_scene_get_info(from_memory, &b);
  assert_int_equal(b.spheres, 1);
  assert_int_equal(b.width, 32);
  glint_scene_destroy(from_memory);

  assert_int_equal(
      glint_scene_load_memory("s 0 0 0 x\n", 10, "bad.nff", &from_memory, &e),
      GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "bad.nff:1:"));
  assert_int_equal(
      glint_scene_load_memory("{}", 2, "scene.txt", &from_memory, &e),
      GLINT_E_ARGUMENT);
  assert_non_null(
      strstr(e.message,
             "scene.txt: not a scene file (.nff or .json, optionally .gz)"));
  /* A built-in scene's name is not a file: glint_scene_builtin loads it. */
  assert_int_equal(glint_scene_load("whitted", &from_memory, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "whitted: not a scene file"));
  assert_int_equal(glint_scene_load_memory(NULL, 4, "a.json", &from_memory, &e),
                   GLINT_E_ARGUMENT);
  /* NULL is refused whatever the size, as every required pointer is (it
   * was read as an empty file when the size was 0) */
  assert_int_equal(glint_scene_load_memory(NULL, 0, "a.json", &from_memory, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "glint_scene_load_memory: data is NULL"));
  /* empty JSON text is no scene */
  assert_int_equal(
      glint_scene_load_memory("", 0, "empty.json", &from_memory, &e),
      GLINT_E_PARSE);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(primitives_refuse_bad_numbers),
      cmocka_unit_test(info_bounds_every_shape),
      cmocka_unit_test(null_and_overflowing_arguments_are_refused),
      cmocka_unit_test(messages_are_one_clean_line),
      cmocka_unit_test(coordinates_stay_within_the_limit),
      cmocka_unit_test(materials_refuse_bad_values),
      cmocka_unit_test(camera_refuses_degenerate_views),
      cmocka_unit_test(render_refuses_bad_settings),
      cmocka_unit_test(names_parse_and_print),
      cmocka_unit_test(builtin_scenes_match_the_spec),
      cmocka_unit_test(mesh_indices_checked),
      cmocka_unit_test(region_is_a_window_of_the_frame),
      cmocka_unit_test(plane_normals_of_any_length),
      cmocka_unit_test(camera_up_of_any_length),
      cmocka_unit_test(scenes_load_from_memory),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
