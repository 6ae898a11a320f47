/* The NFF reader: every entity of NFF.TXT, the SPD suite's primitive
 * counts, and every kind of malformed input reported as FILE:LINE. */
#include "test_util.h"

#include "scene/polygon.h"
#include "scene/scene.h"
#include "shared.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static char dir[64];

static int setup(void **state) {
  (void)state;
  strcpy(dir, "/tmp/glint-test-nff-XXXXXX");
  return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  return system(cmd) == 0 ? 0 : -1;
}

static const char *write_file(const char *name, const char *text) {
  static char path[256];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  fputs(text, f);
  fclose(f);
  return path;
}

#define VIEW                                                                   \
  "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\n"                \
  "resolution 64 48\n"

static void every_entity(void **state) {
  (void)state;
  const char *p = write_file(
      "all.nff",
      "# a comment line\n" VIEW "b 0.1 0.2 0.3 # background\n"
      "l 1 2 3\nl 4 5 6 0.5 0.25 1\nl 7 8 9\n"
      "f 1 0.5 0.25 0.8 0.3 20 0.6 1.5\n"
      "s 0 0 0 1\n"
      "s 3 0 0 -0.5\n" /* negative: inside visible, read as 0.5 */
      "c 0 0 0 1 0 2 0 0.5\n"
      "c\n1 1 1 -0.2\n1 3 1 -0.2\n"
      "p 3\n0 0 0\n1 0 0\n0 1 0\n"
      "p 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
      "p 6\n0 0 0\n4 0 0\n4 4 0\n3 4 0\n3 1 0\n0 1 0\n" /* concave L */
      "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 1 1\n");
  glint_scene *s;
  ASSERT_OK(glint_scene_load(p, &s, &e_));
  glint_scene_info info;
  glint_scene_get_info(s, &info);
  assert_int_equal(info.width, 64);
  assert_int_equal(info.height, 48);
  assert_int_equal(info.spheres, 2);
  assert_int_equal(info.cones, 2);
  /* p 3: 1, p 4: 2, concave hexagon: 4 (ear clipping), pp 3: 1 */
  assert_int_equal(info.triangles, 1 + 2 + 4 + 1);
  assert_int_equal(info.objects, 2 + 2 + 4);
  assert_int_equal(info.lights, 3);
  assert_int_equal(info.materials, 1);
  /* Background, light intensity 1/sqrt(3) for uncoloured lights. */
  assert_true(fabs(info.background.z - 0.3) < 1e-12);
  assert_true(fabs(s->lights[0].color.x - 1 / sqrt(3.0)) < 1e-12);
  assert_true(fabs(s->lights[1].color.y - 0.25) < 1e-12);
  /* The field of view: NFF's angle spans the outer pixel centres. */
  double want = 2 * atan(tan(45 * 3.14159265358979323846 / 360) * 64.0 / 63.0) *
                180 / 3.14159265358979323846;
  assert_true(fabs(info.camera.fov_x_degrees - want) < 1e-9);
  /* Material mapping: kd = Kd, ks = kr = Ks, h = Shine, kt = T, ka = 0.1. */
  const glint_material *m = &s->materials[0];
  assert_true(m->kd == 0.8 && m->ks == 0.3 && m->kr == 0.3 && m->h == 20 &&
              m->kt == 0.6 && m->ior == 1.5 && m->ka == 0.1);
  assert_true(s->spheres[1].radius == 0.5);
  assert_true(s->cones[1].base_radius == 0.2);
  /* pp keeps its normals (normalised). */
  const gli_triangle_prim *t = &s->triangles[s->triangle_count - 1];
  assert_true(t->normals != GLI_NO_NORMALS);
  assert_true(fabs(s->tri_normals[t->normals + 2].y - sqrt(0.5)) < 1e-12);
  /* The concave polygon's triangles cover its area (4 + 3*... = 7): the
   * L-shape 4x1 + 1x3 has area 7. */
  double area = 0;
  for (size_t i = 3; i < 7; i++) {
    const gli_triangle_prim *q = &s->triangles[i];
    double ax = q->v[1].x - q->v[0].x, ay = q->v[1].y - q->v[0].y;
    double bx = q->v[2].x - q->v[0].x, by = q->v[2].y - q->v[0].y;
    area += 0.5 * (ax * by - ay * bx);
  }
  assert_true(fabs(area - 7) < 1e-9);
  glint_scene_destroy(s);
}

#define EXPECT_FAIL(name, text, want_status, want)                             \
  do {                                                                         \
    const char *p_ = write_file(name, text);                                   \
    glint_scene *s_ = NULL;                                                    \
    glint_error e_;                                                            \
    glint_status st_ = glint_scene_load(p_, &s_, &e_);                         \
    assert_int_equal(st_, want_status);                                        \
    assert_null(s_);                                                           \
    if (!strstr(e_.message, want))                                             \
      fail_msg("message '%s' lacks '%s'", e_.message, want);                   \
    if (!strstr(e_.message, name))                                             \
      fail_msg("message '%s' lacks the file name", e_.message);                \
  } while (0)

static void malformed_files(void **state) {
  (void)state;
  EXPECT_FAIL(
      "num.nff", VIEW "f 1 1 1 1 0 1 0 1\ns 0 0 zero 1\n", GLINT_E_PARSE,
      "num.nff:9: expected a number for the sphere's centre, found 'zero'");
  EXPECT_FAIL("nan.nff", VIEW "f 1 1 1 1 0 1 0 1\ns 0 0 0 nan\n", GLINT_E_PARSE,
              "nan.nff:9: the sphere's radius is 'nan', not a finite number");
  /* Finite but beyond GLINT_MAX_COORDINATE: its square overflows floats. */
  EXPECT_FAIL("huge.nff", VIEW "f 1 1 1 1 0 1 0 1\ns 0 0 0 1e39\n",
              GLINT_E_PARSE,
              "huge.nff:9: sphere: centre and radius must be finite numbers of "
              "magnitude at most 1e15");
  EXPECT_FAIL("bright.nff", VIEW "l 0 5 0 1e39 1 1\n", GLINT_E_PARSE,
              "bright.nff:8: light colour must not exceed 1e+06");
  EXPECT_FAIL("inf.nff", VIEW "b 1 inf 0\n", GLINT_E_PARSE,
              "inf.nff:8: the background colour is 'inf', not a finite number");
  /* one view and one background a file (a second replaced the first) */
  EXPECT_FAIL("twoviews.nff", VIEW VIEW, GLINT_E_PARSE,
              "twoviews.nff:8: a second view (the first is on line 1)");
  EXPECT_FAIL("twob.nff", VIEW "b 0 0 0\nb 1 1 1\n", GLINT_E_PARSE,
              "twob.nff:9: a second background colour (the first is on line "
              "8)");
  EXPECT_FAIL("unknown.nff", VIEW "torus 0 0 0 1 2\n", GLINT_E_PARSE,
              "unknown.nff:8: unknown entity 'torus'");
  /* A line a number short: said at that line, not at the next entity's
   * (it said "short.nff:10: ... found 's'"). */
  EXPECT_FAIL("short.nff", VIEW "f 1 1 1 1 0 1 0 1\ns 0 0 0\ns 1 1 1 1\n",
              GLINT_E_PARSE,
              "short.nff:9: expected a number for the sphere's radius, found "
              "the end of the line (line 10 begins 's')");
  /* A number too many (it said "unknown entity '2'"), on the entity's line
   * and on a line of its own. */
  EXPECT_FAIL("extra.nff", VIEW "f 1 1 1 1 0 1 0 1\ns 0 0 0 1 2\n",
              GLINT_E_PARSE,
              "extra.nff:9: unexpected '2': more numbers on the line than its "
              "entity takes");
  EXPECT_FAIL("stray.nff",
              VIEW "f 1 1 1 1 0 1 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n1 1 1\n",
              GLINT_E_PARSE,
              "stray.nff:13: expected an entity (v, b, l, f, s, c, p or pp), "
              "found the number '1'");
  /* the angle's own line, not the view's (it said line 1) */
  EXPECT_FAIL("angle.nff",
              "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 180\nhither 0.01\n"
              "resolution 64 48\n",
              GLINT_E_PARSE,
              "angle.nff:5: view angle 180 is not between 0 and 180");
  /* (it said "field of view 0", a value not in the file) */
  EXPECT_FAIL("tiny.nff",
              "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 4.9e-324\n"
              "hither 0.01\nresolution 64 48\n",
              GLINT_E_PARSE,
              "tiny.nff:5: view angle 4.94066e-324 is too small to make a "
              "view of");
  /* at the last line (it said the line after it, which is not there) */
  EXPECT_FAIL("trunc.nff", VIEW "f 1 1 1 1 0 1 0 1\np 4\n0 0 0\n1 0 0\n1 1 0\n",
              GLINT_E_PARSE,
              "trunc.nff:12: the file ends where a polygon vertex was expected "
              "(vertex 4 of 4");
  EXPECT_FAIL("res-eof.nff",
              "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\n"
              "resolution 64\n",
              GLINT_E_PARSE,
              "res-eof.nff:7: the file ends where the vertical resolution was "
              "expected");
  /* a view cut short after a whole line: at that line (it said the next) */
  EXPECT_FAIL("view-eof.nff", "v\nfrom 0 0 1\n", GLINT_E_PARSE,
              "view-eof.nff:2: the file ends where 'at' was expected");
  EXPECT_FAIL("count.nff", VIEW "f 1 1 1 1 0 1 0 1\np 2\n0 0 0\n1 0 0\n",
              GLINT_E_PARSE, "count.nff:9: the vertex count is 2, outside 3..");
  EXPECT_FAIL("nomat.nff", VIEW "s 0 0 0 1\n", GLINT_E_PARSE,
              "nomat.nff:8: 's' before any 'f' material line");
  EXPECT_FAIL("view.nff", "v\nfrom 0 0 10\nat 0 0 0\nangle 45\n", GLINT_E_PARSE,
              "view.nff:4: expected 'up', found 'angle'");
  EXPECT_FAIL("res.nff",
              "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither "
              "1\nresolution 0 10\n",
              GLINT_E_PARSE, "res.nff:7: the horizontal resolution is 0");
  EXPECT_FAIL("field.nff", VIEW "f 1 1 1 1 0 1 0\n", GLINT_E_PARSE,
              "field.nff:8: the file ends where the material's index of "
              "refraction was expected");
  EXPECT_FAIL("radius.nff", VIEW "f 1 1 1 1 0 1 0 1\ns 0 0 0 0\n",
              GLINT_E_PARSE, "radius.nff:9: sphere: radius 0 must be > 0");
  EXPECT_FAIL("cone.nff", VIEW "f 1 1 1 1 0 1 0 1\nc\n0 0 0 1\n0 1 0 -1\n",
              GLINT_E_PARSE,
              "cone.nff:9: the cone's radii 1 and -1 have different signs");
  EXPECT_FAIL(
      "camera.nff",
      "v\nfrom 0 0 0\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n",
      GLINT_E_PARSE,
      "camera.nff:3: camera: 'from' and 'at' are the same point");
  /* The camera's errors at the value's own line (they all said line 1, the
   * 'v'). */
  EXPECT_FAIL("far.nff",
              "v\nfrom 0 0 1e16\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\n"
              "resolution 8 8\n",
              GLINT_E_PARSE, "far.nff:2: camera: coordinates must be finite");
  EXPECT_FAIL("up.nff",
              "v\nfrom 0 0 1\nat 0 0 0\nup 0 0 0\nangle 45\nhither 1\n"
              "resolution 8 8\n",
              GLINT_E_PARSE, "up.nff:4: camera: 'up' is zero");
  /* A whole number short, as a number short is (it said line 8, 'found
   * 'b''). */
  EXPECT_FAIL("res-short.nff",
              "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\n"
              "resolution 64\nb 0 0 0\n",
              GLINT_E_PARSE,
              "res-short.nff:7: expected a whole number for the vertical "
              "resolution, found the end of the line (line 8 begins 'b')");
  /* A polygon's vertex line with a number too many or too few is named,
   * though the error shows later (they named the line where it did). */
  EXPECT_FAIL("vlong.nff",
              VIEW "f 1 1 1 1 0 1 0 1\np 3\n0 0 0\n1 0 0 7\n0 1 0\n"
                   "s 0 0 0 1\n",
              GLINT_E_PARSE,
              "vlong.nff:11: more numbers on the line than a polygon vertex "
              "takes (vertex 2 of 3 of the polygon on line 9)");
  EXPECT_FAIL("vshort.nff",
              VIEW "f 1 1 1 1 0 1 0 1\np 3\n0 0 0\n1 0\n0 1 0\n"
                   "s 0 0 0 1\n",
              GLINT_E_PARSE,
              "vshort.nff:11: fewer numbers on the line than a polygon vertex "
              "takes (vertex 2 of 3 of the polygon on line 9)");
  EXPECT_FAIL("pplong.nff",
              VIEW "f 1 1 1 1 0 1 0 1\npp 3\n0 0 0 0 0 1\n1 0 0 0 0 1 5\n"
                   "0 1 0 0 0 1\ns 0 0 0 1\n",
              GLINT_E_PARSE,
              "pplong.nff:11: more numbers on the line than a patch vertex "
              "takes (vertex 2 of 3 of the patch on line 9)");
  /* A vertex out of range at its line (it said the polygon's). */
  EXPECT_FAIL("vfar.nff",
              VIEW "f 1 1 1 1 0 1 0 1\np 3\n0 0 0\n1e40 0 0\n0 1 0\n",
              GLINT_E_PARSE,
              "vfar.nff:11: p vertex 2 of 3 (of line 9): coordinates must be "
              "finite");
  /* ...but a number that is not finite is its own error, said as such. */
  EXPECT_FAIL("vnan.nff",
              VIEW "f 1 1 1 1 0 1 0 1\np 4\n0 0 0 1\n0 0 0 1\n0\n5 nan 0\n",
              GLINT_E_PARSE,
              "vnan.nff:13: a polygon vertex is 'nan', not a finite number");
  /* Vertices over lines in another layout that reads whole: accepted. */
  {
    const char *p =
        write_file("layout.nff", VIEW "f 1 1 1 1 0 1 0 1\np 3\n0 0 0 1\n0 0 "
                                      "0 1\n0\ns 0 0 0 1\n");
    glint_scene *s = NULL;
    ASSERT_OK(glint_scene_load(p, &s, &e_));
    assert_int_equal(s->triangle_count, 1);
    assert_int_equal(s->sphere_count, 1);
    glint_scene_destroy(s);
  }
  EXPECT_FAIL("glass.nff", VIEW "f 1 1 1 1 0 1 0.5 0\n", GLINT_E_PARSE,
              "glass.nff:8: material ior = 0 must be a finite number > 0");
  /* ior 0 stands for 'none' where nothing is transmitted (the SPD writes
   * it), a negative one never (it read as 1). */
  EXPECT_FAIL("opaque.nff", VIEW "f 1 1 1 1 0 1 0 -5\n", GLINT_E_PARSE,
              "opaque.nff:8: material ior = -5 must be a finite number > 0");
  EXPECT_FAIL("patch.nff",
              VIEW "f 1 1 1 1 0 1 0 1\npp 3\n0 0 0 0 0 1e20\n1 0 0 0 0 1\n"
                   "0 1 0 0 0 1\n",
              GLINT_E_PARSE, "patch.nff:9: vertex normals must be finite");
  /* A missing file, and a binary one. */
  glint_scene *s = NULL;
  glint_error e;
  char missing[256];
  snprintf(missing, sizeof missing, "%s/none.nff", dir);
  assert_int_equal(glint_scene_load(missing, &s, &e), GLINT_E_IO);
  assert_non_null(strstr(e.message, "none.nff: No such file"));
  char bin[256];
  snprintf(bin, sizeof bin, "%s/bin.nff", dir);
  FILE *f = fopen(bin, "wb");
  fwrite("s\0\1\2", 1, 4, f);
  fclose(f);
  assert_int_equal(glint_scene_load(bin, &s, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "binary data"));
}

#define EXPECT_FAIL_FILE(name, want_status, want)                              \
  do {                                                                         \
    char p_[256];                                                              \
    snprintf(p_, sizeof p_, "%s/%s", dir, name);                               \
    glint_scene *s_ = NULL;                                                    \
    glint_error e_;                                                            \
    assert_int_equal(glint_scene_load(p_, &s_, &e_), want_status);             \
    assert_null(s_);                                                           \
    if (!strstr(e_.message, want))                                             \
      fail_msg("message '%s' lacks '%s'", e_.message, want);                   \
  } while (0)

/* Large polygons load in time proportional to their size and inward
 * corners, not to its square: a "pac-man" of 200 000 vertices with one
 * inward corner (the fuzzer's find: quadratic ear clipping took minutes),
 * a comb with 2 000 teeth, both covering exactly their area; a comb of
 * 20 000 teeth is refused with FILE:LINE rather than left to run for long. */
/* A scene of `copies` copies of the polygon pt[0..n). */
static const char *polygons_file(const char *name, const double (*pt)[2],
                                 size_t n, int copies) {
  static char path[256];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  fputs(VIEW "f 1 0 0 1 0 1 0 1\n", f);
  for (int c = 0; c < copies; c++) {
    fprintf(f, "p %zu\n", n);
    for (size_t i = 0; i < n; i++)
      fprintf(f, "%.17g %.17g 0\n", pt[i][0], pt[i][1]);
  }
  fclose(f);
  return path;
}

static const char *polygon_file(const char *name, const double (*pt)[2],
                                size_t n) {
  return polygons_file(name, pt, n, 1);
}

static double shoelace(const double (*pt)[2], size_t n) {
  double a = 0;
  for (size_t i = 0; i < n; i++) {
    const double *p = pt[i], *q = pt[(i + 1) % n];
    a += 0.5 * (p[0] * q[1] - q[0] * p[1]);
  }
  return a;
}

static void expect_cover(const char *path, const double (*pt)[2], size_t n) {
  glint_scene *s;
  ASSERT_OK(glint_scene_load(path, &s, &e_));
  assert_int_equal(s->triangle_count, n - 2);
  double area = 0;
  for (size_t i = 0; i < s->triangle_count; i++) {
    const gli_triangle_prim *q = &s->triangles[i];
    double ax = q->v[1].x - q->v[0].x, ay = q->v[1].y - q->v[0].y;
    double bx = q->v[2].x - q->v[0].x, by = q->v[2].y - q->v[0].y;
    double a = 0.5 * (ax * by - ay * bx);
    if (a < -1e-9) /* every triangle keeps the orientation */
      fail_msg("%s: triangle %zu has area %g: (%g %g) (%g %g) (%g %g)", path, i,
               a, q->v[0].x, q->v[0].y, q->v[1].x, q->v[1].y, q->v[2].x,
               q->v[2].y);
    area += a;
  }
  double want = shoelace(pt, n);
  if (fabs(area - want) > 1e-9 * want)
    fail_msg("%s: triangles cover %.12g, the polygon %.12g", path, area, want);
  glint_scene_destroy(s);
}

/* A comb: a bar along y in [-1, 0] with `teeth` spikes to y = 10. */
static size_t comb(double (*pt)[2], size_t teeth) {
  size_t n = 0;
  pt[n][0] = 0, pt[n++][1] = -1;
  pt[n][0] = 2.0 * (double)teeth, pt[n++][1] = -1;
  for (size_t i = teeth; i > 0; i--) {
    pt[n][0] = 2.0 * (double)i, pt[n++][1] = 0;
    pt[n][0] = 2.0 * (double)i - 1, pt[n++][1] = 10;
  }
  pt[n][0] = 0, pt[n++][1] = 0;
  return n;
}

static void large_polygons(void **state) {
  (void)state;
  enum { PACMAN = 200000, TEETH = 20000 };
  double(*pt)[2] =
      malloc(sizeof *pt * (PACMAN > 2 * TEETH + 3 ? PACMAN : 2 * TEETH + 3));
  assert_non_null(pt);
  /* A 300-degree arc and the centre last: its only inward corner. */
  for (size_t i = 0; i + 1 < PACMAN; i++) {
    double a =
        (30.0 + 300.0 * (double)i / (PACMAN - 2)) * 3.14159265358979 / 180;
    pt[i][0] = cos(a), pt[i][1] = sin(a);
  }
  pt[PACMAN - 1][0] = pt[PACMAN - 1][1] = 0;
  expect_cover(polygon_file("pacman.nff", (const double(*)[2])pt, PACMAN),
               (const double(*)[2])pt, PACMAN);
  size_t n = comb(pt, 2000);
  expect_cover(polygon_file("comb.nff", (const double(*)[2])pt, n),
               (const double(*)[2])pt, n);
  /* A square of 4 x 10 000 vertices along its edges: convex, though every
   * vertex but the corners turns not at all (it was refused as having too
   * many inward corners). */
  n = 0;
  for (int side = 0; side < 4; side++)
    for (int i = 0; i < 10000; i++) {
      const double corner[4][2] = {{0, 0}, {1e4, 0}, {1e4, 1e4}, {0, 1e4}};
      const double step[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
      pt[n][0] = corner[side][0] + i * step[side][0];
      pt[n++][1] = corner[side][1] + i * step[side][1];
    }
  expect_cover(polygon_file("square.nff", (const double(*)[2])pt, n),
               (const double(*)[2])pt, n);
  n = comb(pt, TEETH);
  polygon_file("bigcomb.nff", (const double(*)[2])pt, n);
  EXPECT_FAIL_FILE("bigcomb.nff", GLINT_E_PARSE,
                   "bigcomb.nff:9: p: the polygon of 40003 vertices has too "
                   "many inward corners to triangulate (the concave polygons "
                   "of a scene get 2^28 ear-clipping tests in all)");
  /* The limit is the scene's, not each polygon's: ten copies of a comb
   * that takes a quarter of a second each are refused after about eight
   * (they took 2.5 s, a thousand of them would take minutes). */
  n = comb(pt, 5000);
  polygons_file("combs.nff", (const double(*)[2])pt, n, 10);
  free(pt);
  EXPECT_FAIL_FILE("combs.nff", GLINT_E_PARSE,
                   "p: the polygon of 10003 vertices has too many inward "
                   "corners to triangulate");
}

/* Every SPD scene loads with the primitive counts its file holds (p: one
 * object each; sphereflake etc. at the given sizes). */
static void spd_counts_shared(void **state) {
  (void)state;
  static const struct {
    const char *name;
    size_t spheres, cones, polygons, lights;
  } want[] = {{"balls-s4", 7381, 0, 1, 3},      {"gears-s4", 0, 0, 9345, 5},
              {"mount-s6", 4, 0, 8192, 1},      {"rings-s4", 900, 900, 1, 3},
              {"teapot-s4", 0, 0, 16 + 992, 2}, {"tetra-s6", 0, 0, 4096, 1},
              {"tree-s4", 31, 31, 1, 7}};
  for (size_t i = 0; i < sizeof want / sizeof *want; i++) {
    char sub[64];
    snprintf(sub, sizeof sub, "scenes/spd/%s.nff", want[i].name);
    glint_scene *s;
    ASSERT_OK(glint_scene_load(shared_path(sub), &s, &e_));
    glint_scene_info info;
    glint_scene_get_info(s, &info);
    assert_int_equal(info.spheres, want[i].spheres);
    assert_int_equal(info.cones, want[i].cones);
    assert_int_equal(info.objects,
                     want[i].spheres + want[i].cones + want[i].polygons);
    assert_int_equal(info.lights, want[i].lights);
    assert_int_equal(info.width, 512);
    assert_int_equal(info.height, 512);
    printf("%-10s %6zu spheres %5zu cones %6zu triangles %5zu objects\n",
           want[i].name, info.spheres, info.cones, info.triangles,
           info.objects);
    glint_scene_destroy(s);
  }
}

/* An emit that fails at triangle `fail_at` with GLINT_E_MEMORY (the scene's
 * push out of memory), counting the triangles it is given. */
typedef struct failing_emit {
  int calls, fail_at;
} failing_emit;

static int emit_until(void *user, size_t a, size_t b, size_t c) {
  (void)a, (void)b, (void)c;
  failing_emit *f = user;
  return ++f->calls == f->fail_at ? GLINT_E_MEMORY : 0;
}

/* The emit's own status comes back from every path of the triangulation:
 * a quad's two triangles (it became 1, and an NFF reader out of memory
 * exited 2, not 1), a convex polygon's bisection, a concave one's ears. */
static void emit_failures_keep_their_status(void **state) {
  (void)state;
  const glint_vec3 quad[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const glint_vec3 hexagon[6] = {{2, 0, 0},  {1, 1.7, 0},   {-1, 1.7, 0},
                                 {-2, 0, 0}, {-1, -1.7, 0}, {1, -1.7, 0}};
  const glint_vec3 arrow[5] = {
      {0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {1, 1, 0}, {0.2, 1, 0}};
  struct {
    const glint_vec3 *v;
    size_t n;
  } shapes[] = {{quad, 4}, {hexagon, 6}, {arrow, 5}};
  for (size_t s = 0; s < 3; s++)
    for (int at = 1; at <= (int)shapes[s].n - 2; at++) {
      failing_emit f = {0, at};
      size_t tests = GLI_SCENE_EAR_TESTS;
      assert_int_equal(
          gli_triangulate(shapes[s].v, shapes[s].n, emit_until, &f, &tests),
          GLINT_E_MEMORY);
      assert_int_equal(f.calls, at); /* stopped there */
    }
}

/* tests/polygon_reference.c: gli_triangulate without the grid. */
int reference_triangulate(const glint_vec3 *v, size_t n, gli_polygon_emit emit,
                          void *user, size_t *tests_left);

typedef struct cuts {
  size_t (*t)[3], count, room;
} cuts;

static int note_cut(void *user, size_t a, size_t b, size_t c) {
  cuts *k = user;
  if (k->count == k->room) {
    k->room = k->room ? 2 * k->room : 64;
    k->t = realloc(k->t, k->room * sizeof *k->t);
    assert_non_null(k->t);
  }
  k->t[k->count][0] = a, k->t[k->count][1] = b, k->t[k->count++][2] = c;
  return 0;
}

/* The grid of inward corners (scene/polygon.c) reads, for each ear, the
 * corners near its triangle rather than the whole list: the same ears are
 * cut, in the same order, as by the list alone, for polygons of 40 to
 * 4 000 corners, stars and combs, in planes at every angle and far from
 * the origin, and the same refusal where the tests run out. */
static void the_grid_cuts_as_the_list(void **state) {
  (void)state;
  unsigned seed = 12345;
  for (int k = 0; k < 60; k++) {
    size_t n = (size_t)(40 << (k % 7));
    if (n > 4000)
      n = 4000;
    glint_vec3 *v = malloc(n * sizeof *v);
    assert_non_null(v);
    double ax = 0.37 * k, ay = 0.61 * k, shift = k % 5 == 4 ? 1e6 : 0;
    for (size_t i = 0; i < n; i++) {
      seed = seed * 1103515245u + 12345u;
      double t = 6.283185307179586 * (double)i / (double)n;
      double r = k % 3 == 0   ? (i % 2 ? 1.0 : 0.55) /* teeth */
                 : k % 3 == 1 ? 0.3 + 0.7 * (seed >> 8) / 16777216.0
                              : (i % 8 < 4 ? 1.0 : 0.9); /* comb-like */
      double x = 3 * r * cos(t), y = 3 * r * sin(t), z = 0;
      double y1 = y * cos(ax) - z * sin(ax), z1 = y * sin(ax) + z * cos(ax);
      double x2 = x * cos(ay) + z1 * sin(ay), z2 = -x * sin(ay) + z1 * cos(ay);
      v[i] = (glint_vec3){x2 + shift, y1, z2};
    }
    cuts grid = {NULL, 0, 0}, list = {NULL, 0, 0};
    size_t tests_grid = GLI_SCENE_EAR_TESTS, tests_list = GLI_SCENE_EAR_TESTS;
    int rg = gli_triangulate(v, n, note_cut, &grid, &tests_grid);
    int rl = reference_triangulate(v, n, note_cut, &list, &tests_list);
    assert_int_equal(rg, rl);
    assert_int_equal(tests_grid, tests_list);
    assert_int_equal(grid.count, list.count);
    if (grid.count)
      assert_memory_equal(grid.t, list.t, grid.count * sizeof *grid.t);
    /* and where the tests run out: refused alike */
    size_t few_grid = 1000, few_list = 1000;
    grid.count = list.count = 0;
    assert_int_equal(gli_triangulate(v, n, note_cut, &grid, &few_grid),
                     reference_triangulate(v, n, note_cut, &list, &few_list));
    free(grid.t);
    free(list.t);
    free(v);
  }
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(the_grid_cuts_as_the_list),
      cmocka_unit_test(every_entity),
      cmocka_unit_test(malformed_files),
      cmocka_unit_test(large_polygons),
      cmocka_unit_test(emit_failures_keep_their_status),
      cmocka_unit_test(spd_counts_shared),
  };
  return glint_run_tests(tests, argc, argv, setup, teardown);
}
