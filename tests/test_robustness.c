/* Numerically fragile geometry, on scenes the thesis never rendered:
 *  - a cylinder of radius 0.01 seen from 8 units away: every backend agrees
 *    with scalar-double (before the cone roots were solved from the ray's
 *    point nearest the axis, every float backend lost the squared distance
 *    to the axis to cancellation: 23.6 dB for scalar-float, 24.2 dB and
 *    about 6000 wrong pixels for the SIMD backends; now 78.6-80.7 dB);
 *  - triangles of edges 2e13 and 2e15 render in every float backend as in
 *    scalar-double (their plane test overflowed floats);
 *  - closed meshes are watertight: rays aimed exactly at the edges and
 *    vertices that triangles share never pass between them;
 *  - rays that cross a bounding box for a few 1e-6, far from the
 *    coordinates' zero, are not culled by the slab tests' rounding.
 *  - rays that skim a cone, passing its axis at 0.99 of its radius there,
 *    are not culled by the test of the cone's reach (its widest radius).
 * A backend this CPU lacks is reported as skipped. */
#define GLINT_REAL_FLOAT
#include "test_util.h"

#include "render/scalar_scene.h"
#include "scene/mesh.h"
#include "test_views.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const glint_backend float_backends[] = {
    GLINT_BACKEND_SCALAR_FLOAT, GLINT_BACKEND_SSE,
    GLINT_BACKEND_AVX2,         GLINT_BACKEND_AVX512,
    GLINT_BACKEND_STREAM_SSE,   GLINT_BACKEND_STREAM_AVX2,
    GLINT_BACKEND_STREAM_AVX512};
#define BACKEND_COUNT (sizeof float_backends / sizeof *float_backends)

static glint_scene *scene_from_text(const char *text, const char *ext) {
  char path[256];
  snprintf(path, sizeof path, "%s/glint-robust-%d%s",
           getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid(), ext);
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fputs(text, f);
  fclose(f);
  glint_scene *s;
  ASSERT_OK(glint_scene_load(path, &s, &e_));
  unlink(path);
  return s;
}

static glint_image *render(const glint_scene *s, glint_backend b, int depth) {
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.backend = b;
  rs.max_depth = depth;
  glint_image *im;
  ASSERT_OK(glint_render(s, &rs, &im, NULL, &e_));
  return im;
}

/* Pixels whose channels differ by more than 8 levels. */
static int wrong_pixels(const glint_image *a, const glint_image *b) {
  const uint8_t *p = glint_image_pixels_const(a),
                *q = glint_image_pixels_const(b);
  int n = 0, count = glint_image_width(a) * glint_image_height(a);
  for (int i = 0; i < count; i++)
    for (int c = 0; c < 3; c++)
      if (abs(p[3 * i + c] - q[3 * i + c]) > 8) {
        n++;
        break;
      }
  return n;
}

/* Renders s with scalar-double and every float backend this CPU has (the
 * others reported skipped): each within min_psnr of it, and no pixel off
 * by more than 8 levels. */
static void float_backends_agree(const glint_scene *s, double min_psnr) {
  glint_image *ref = render(s, GLINT_BACKEND_SCALAR_DOUBLE, 1);
  for (size_t k = 0; k < BACKEND_COUNT; k++) {
    glint_backend b = float_backends[k];
    if (!glint_backend_supported(b)) {
      printf("%-14s SKIPPED (not on this CPU)\n", glint_backend_name(b));
      continue;
    }
    glint_image *im = render(s, b, 1);
    double psnr = glint_image_psnr(ref, im);
    int wrong = wrong_pixels(ref, im);
    printf("%-14s %.2f dB, %d wrong pixels\n", glint_backend_name(b), psnr,
           wrong);
    if (psnr < min_psnr || wrong > 0)
      fail_msg("%s: %.2f dB, %d pixels off by more than 8 levels",
               glint_backend_name(b), psnr, wrong);
    glint_image_destroy(im);
  }
  glint_image_destroy(ref);
}

static void thin_cylinder(void **state) {
  (void)state;
  glint_scene *s = scene_from_text(
      "b 0 0 0\nv\nfrom 0 0 -8\nat 0 0 0\nup 0 1 0\nangle 0.5\n"
      "hither 0.001\nresolution 256 256\nl -10 3 -20\nf 1 1 1 1 0 1 0 1\n"
      "c -0.03 -0.005 0.02 0.01 0.03 0.005 -0.02 0.01\n",
      ".nff");
  float_backends_agree(s, 75);
  glint_scene_destroy(s);
}

/* A triangle of edges 2e13, seen from 3e12 away, and one of edges 2e15
 * from 3e14 (coordinates up to GLINT_MAX_COORDINATE are accepted): the
 * float backends vanished them, N·(A - O) in the plane test overflowing
 * floats (about 1e39 and 1e45), and rendered the background (3.2 dB). */
static void huge_triangles(void **state) {
  (void)state;
  static const char *const scales[] = {"13", "15"};
  for (int i = 0; i < 2; i++) {
    char text[512];
    int near = i == 0 ? 12 : 14;
    snprintf(text, sizeof text,
             "b 0.2 0.3 0.4\nv\nfrom 0 0 3e%d\nat 0 0 0\nup 0 1 0\n"
             "angle 45\nhither 1\nresolution 64 48\nl 0 0 9e%d\n"
             "f 1 1 1 1 0 1 0 1\np 3\n-1e%s -1e%s 0\n1e%s -1e%s 0\n0 1e%s 0\n",
             near, near, scales[i], scales[i], scales[i], scales[i], scales[i]);
    glint_scene *s = scene_from_text(text, ".nff");
    printf("edges 2e%s:\n", scales[i]);
    float_backends_agree(s, 60);
    glint_scene_destroy(s);
  }
}

/* ---- long numbers ----------------------------------------------------------
 */

/* Numbers longer than 127 characters were cut to 127 and read wrongly (a
 * valid one misread, an invalid one accepted); they are read whole now. */
static void long_numbers_are_read_whole(void **state) {
  (void)state;
  char text[1024], digits[260];
  memset(digits, '0', 250);
  digits[250] = '\0';
  /* 0.000...0005 (250 zeros): a valid, tiny, finite number. */
  snprintf(text, sizeof text,
           "b 0.%s5 0 0\nv\nfrom 0 0 -8\nat 0 0 0\nup 0 1 0\nangle 40\n"
           "hither 0.001\nresolution 4 4\n",
           digits);
  glint_scene *s = scene_from_text(text, ".nff");
  glint_scene_info info;
  glint_scene_get_info(s, &info);
  assert_true(info.background.x > 0 && info.background.x < 1e-249);
  glint_scene_destroy(s);
  /* 1000...0 with a letter after the 127th character: not a number. */
  snprintf(text, sizeof text,
           "b 1%sx 0 0\nv\nfrom 0 0 -8\nat 0 0 0\nup 0 1 0\nangle 40\n"
           "hither 0.001\nresolution 4 4\n",
           digits);
  char path[256];
  snprintf(path, sizeof path, "%s/glint-long-%d.nff",
           getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid());
  FILE *f = fopen(path, "w");
  fputs(text, f);
  fclose(f);
  glint_error e;
  assert_int_equal(glint_scene_load(path, &s, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, ":1: expected a number"));
  assert_non_null(strstr(e.message, "..."));
  unlink(path);
}

/* ---- watertight meshes --------------------------------------------------- */

#define CX 31.3
#define CY -17.7
#define CZ 21.1
#define RADIUS 0.37

typedef struct mesh_build {
  glint_vec3 positions[2562];
  uint32_t indices[3 * 5120];
  size_t vertices, triangles;
} mesh_build;

/* The midpoint of edge (a, b) on the unit sphere, made once per edge so
 * that both triangles share the vertex. A linear search: small meshes. */
static uint32_t midpoint(mesh_build *m, uint32_t a, uint32_t b,
                         uint32_t (*cache)[3], size_t *cached) {
  uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
  for (size_t i = 0; i < *cached; i++)
    if (cache[i][0] == lo && cache[i][1] == hi)
      return cache[i][2];
  glint_vec3 p = m->positions[a], q = m->positions[b];
  glint_vec3 c = {(p.x + q.x) / 2, (p.y + q.y) / 2, (p.z + q.z) / 2};
  double l = sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
  m->positions[m->vertices] = (glint_vec3){c.x / l, c.y / l, c.z / l};
  cache[*cached][0] = lo, cache[*cached][1] = hi,
  cache[*cached][2] = (uint32_t)m->vertices;
  (*cached)++;
  return (uint32_t)m->vertices++;
}

/* A closed icosphere of 5120 small triangles, far from the origin (where a
 * float keeps fewer bits of a triangle's size) and scaled to coordinates
 * whose float roundings differ from edge to edge. */
static void icosphere(mesh_build *m) {
  const double t = (1 + sqrt(5.0)) / 2;
  const double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                           {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                           {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  static const uint32_t f[20][3] = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  m->vertices = 12;
  for (int i = 0; i < 12; i++) {
    double l = sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    m->positions[i] = (glint_vec3){v[i][0] / l, v[i][1] / l, v[i][2] / l};
  }
  memcpy(m->indices, f, sizeof f);
  m->triangles = 20;
  static uint32_t cache[7680][3];
  for (int level = 0; level < 4; level++) {
    size_t cached = 0, n = m->triangles;
    uint32_t next[3 * 5120];
    for (size_t i = 0; i < n; i++) {
      uint32_t a = m->indices[3 * i], b = m->indices[3 * i + 1],
               c = m->indices[3 * i + 2];
      uint32_t ab = midpoint(m, a, b, cache, &cached),
               bc = midpoint(m, b, c, cache, &cached),
               ca = midpoint(m, c, a, cache, &cached);
      const uint32_t four[12] = {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca};
      memcpy(next + 12 * i, four, sizeof four);
    }
    m->triangles = 4 * n;
    memcpy(m->indices, next, m->triangles * 3 * sizeof *next);
  }
  for (size_t i = 0; i < m->vertices; i++) {
    glint_vec3 *p = &m->positions[i];
    *p = (glint_vec3){CX + RADIUS * p->x, CY + RADIUS * p->y,
                      CZ + RADIUS * p->z};
  }
}

/* The packet kernels' nearest-hit entry points, for a view of a scene
 * (tests/test_views.h). */
static const struct {
  glint_backend backend;
  int width;
  void (*nearest)(const void *, const float *, const float *, int, float *,
                  int *);
} packets[] = {{GLINT_BACKEND_SSE, 4, gli_beam_nearest_hit_sse},
               {GLINT_BACKEND_AVX2, 8, gli_beam_nearest_hit_avx2},
               {GLINT_BACKEND_AVX512, 16, gli_beam_nearest_hit_avx512}};

/* How many of `lanes` rays (o, d: lanes x, then y, then z) packet kernel p
 * finds no hit for, traced as packets of its width. */
static int packet_misses(const void *view, int p, const float *o,
                         const float *d, int lanes) {
  int w = packets[p].width, misses = 0;
  for (int base = 0; base < lanes; base += w) {
    float po[48], pd[48], t[16];
    int obj[16];
    for (int i = 0; i < w; i++)
      for (int c = 0; c < 3; c++) {
        po[c * w + i] = o[c * lanes + base + i];
        pd[c * w + i] = d[c * lanes + base + i];
      }
    packets[p].nearest(view, po, pd, (1 << w) - 1, t, obj);
    for (int i = 0; i < w; i++)
      misses += obj[i] < 0;
  }
  return misses;
}

/* Adds to misses[0] the rays scalar-float misses, to misses[1 + p] those
 * packet kernel p misses (where views[p] is open). */
static void count_misses(const scene_r *ref, void *const views[3],
                         const float *o, const float *d, int lanes,
                         int misses[4]) {
  for (int i = 0; i < lanes; i++) {
    hit_r h;
    vec3 org = v3(o[i], o[lanes + i], o[2 * lanes + i]);
    vec3 dir = v3(d[i], d[lanes + i], d[2 * lanes + i]);
    misses[0] += !gli_scalar_nearest_hit_float(ref, &org, &dir, REAL_MAX, &h);
  }
  for (int p = 0; p < 3; p++)
    if (views[p])
      misses[1 + p] += packet_misses(views[p], p, o, d, lanes);
}

/* Makes `lanes` rays (o, d: lanes x, then y, then z) for a test. */
typedef void (*ray_maker)(void *ctx, unsigned long long *seed, float *o,
                          float *d, int lanes);

/* Traces `rays` rays that make aims at scene s through every walk of
 * accels, with scalar-float and each packet kernel this CPU has (the
 * others reported skipped): none may miss. */
static void every_walk_hits(const glint_scene *s, const glint_accel *accels,
                            int accel_count, int rays, ray_maker make,
                            void *ctx, const char *what) {
  for (int ai = 0; ai < accel_count; ai++) {
    test_view pv[3], scalar;
    void *views[3] = {NULL, NULL, NULL};
    for (int p = 0; p < 3; p++)
      if (glint_backend_supported(packets[p].backend))
        views[p] =
            test_view_open(s, gli_backend_ops_of(packets[p].backend)->data,
                           accels[ai], &pv[p]);
    const scene_r *ref =
        test_view_open(s, DATA_SCALAR_FLOAT, accels[ai], &scalar);
    unsigned long long seed = 7 + (unsigned long long)ai;
    int misses[4] = {0}, lanes = 16;
    for (int r = 0; r < rays; r += lanes) {
      float o[3 * 16], d[3 * 16];
      make(ctx, &seed, o, d, lanes);
      count_misses(ref, views, o, d, lanes, misses);
    }
    test_view_close(&scalar);
    for (int p = 0; p < 3; p++)
      if (views[p])
        test_view_close(&pv[p]);
    for (int p = 0; p < 4; p++) {
      const char *name =
          p == 0 ? "scalar-float" : glint_backend_name(packets[p - 1].backend);
      if (p > 0 && !views[p - 1])
        printf("%-12s SKIPPED (not on this CPU)\n", name);
      else
        printf("%-12s %s: %d of %d %s missed\n", name,
               glint_accel_name(accels[ai]), misses[p], rays, what);
    }
    for (int p = 0; p < 4; p++)
      assert_int_equal(misses[p], 0);
  }
}

#define EDGE_RAYS 200000

/* Rays from outside aimed exactly at an edge two triangles share (or at a
 * vertex, one ray in five): they must hit the closed mesh. */
static void edge_rays(void *ctx, unsigned long long *seed, float *o, float *d,
                      int lanes) {
  const mesh_build *m = ctx;
  for (int i = 0; i < lanes; i++) {
    size_t tri = (size_t)(uniform(seed) * (double)m->triangles);
    int k = (int)(uniform(seed) * 3);
    glint_vec3 a = m->positions[m->indices[3 * tri + (size_t)k]],
               b = m->positions[m->indices[3 * tri + (size_t)(k + 1) % 3]];
    double f = uniform(seed) < 0.2 ? 0 : uniform(seed);
    double target[3] = {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y),
                        a.z + f * (b.z - a.z)};
    /* From outside, facing the target's faces: not a grazing ray along
     * the silhouette, which may rightly pass the solid by. */
    double from[3], dir[3], l;
    double out[3] = {target[0] - CX, target[1] - CY, target[2] - CZ};
    do {
      double z = 2 * uniform(seed) - 1, phi = 6.283185307 * uniform(seed);
      double dist = 2 + 30 * uniform(seed);
      from[0] = CX + dist * sqrt(1 - z * z) * cos(phi);
      from[1] = CY + dist * sqrt(1 - z * z) * sin(phi);
      from[2] = CZ + dist * z;
      for (int c = 0; c < 3; c++)
        dir[c] = target[c] - from[c];
      l = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    } while ((dir[0] * out[0] + dir[1] * out[1] + dir[2] * out[2]) / l >
             -0.3 * RADIUS);
    for (int c = 0; c < 3; c++) {
      o[c * lanes + i] = (float)from[c];
      d[c * lanes + i] = (float)(dir[c] / l);
    }
  }
}

static void meshes_are_watertight(void **state) {
  (void)state;
  static mesh_build m;
  icosphere(&m);
  uint32_t id;
  glint_scene *s = scene_with_default_material(&id);
  glint_mesh mesh = {m.positions, NULL, m.vertices, m.indices, m.triangles};
  ASSERT_OK(glint_scene_add_mesh(s, &mesh, id, &e_));
  /* Every walk: brute force, the hybrid, the binary tree alone and every ray
   * alone through the wide tree. */
  static const glint_accel accels[4] = {GLINT_ACCEL_NONE, GLINT_ACCEL_BVH,
                                        GLINT_ACCEL_BVH2, GLINT_ACCEL_BVH8};
  every_walk_hits(s, accels, 4, 200000, edge_rays, &m, "edge and vertex rays");
  glint_scene_destroy(s);
}

/* Rays through a triangle next to its vertex A, the corner of its bounding
 * box (A is the lowest in x and in y), entering the box through the face x
 * = A.x and leaving through y = A.y a few 1e-6 later: far from the
 * coordinates' zero (1000), so that O/D carries an ulp (6e-5/|D|) far
 * larger than that stretch. A slab test computing B/D - O/D in one fma
 * without moving O outwards culls about half of them (the box is missed,
 * the triangle with it); every walk must hit. */
static void corner_rays(void *ctx, unsigned long long *seed, float *o, float *d,
                        int lanes) {
  const glint_vec3 *tri = ctx, a = tri[0];
  for (int i = 0; i < lanes; i++) {
    /* P = A + f1 (B - A) + f2 (C - A), 1e-6 to 1e-5 from each edge
     * at A, inside the triangle */
    double f1 = 2e-6 + 2e-5 * uniform(seed), f2 = 2e-6 + 2e-5 * uniform(seed);
    double target[3] = {a.x + f1 * (tri[1].x - a.x) + f2 * (tri[2].x - a.x),
                        a.y + f1 * (tri[1].y - a.y) + f2 * (tri[2].y - a.y),
                        a.z + f1 * (tri[1].z - a.z) + f2 * (tri[2].z - a.z)};
    /* +x and -y, and +z: at least 30 degrees from the triangle's
     * plane (normal (1, -1, 1)); from 0.2 to 1.2 away, beyond the
     * scene's epsilon (1e-4 of its coordinates: 0.1) */
    double dir[3] = {0.2 + uniform(seed), -0.2 - uniform(seed),
                     0.5 + uniform(seed)};
    double l = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double dist = 0.2 + uniform(seed);
    float from[3];
    for (int c = 0; c < 3; c++)
      from[c] = (float)(target[c] - dist * dir[c] / l);
    /* aimed from the rounded origin, so the ray passes within 1e-7 */
    double aim[3], al = 0;
    for (int c = 0; c < 3; c++)
      aim[c] = target[c] - from[c], al += aim[c] * aim[c];
    for (int c = 0; c < 3; c++) {
      o[c * lanes + i] = from[c];
      d[c * lanes + i] = (float)(aim[c] / sqrt(al));
    }
  }
}

static void rays_grazing_a_box_corner_hit(void **state) {
  (void)state;
  const glint_vec3 a = {1000.25, 1000.5, 1000.75};
  const glint_vec3 tri[3] = {a,
                             {a.x + 0.5, a.y + 0.25, a.z - 0.25},
                             {a.x + 0.125, a.y + 0.5, a.z + 0.375}};
  /* 63 copies 2 and more away in +x and +y, out of the rays' reach, so
   * that the scene has a tree whose boxes all have their corner at A */
  static glint_vec3 positions[3 * 64];
  static uint32_t indices[3 * 64];
  for (int k = 0; k < 64; k++)
    for (int c = 0; c < 3; c++) {
      double shift_x = k ? 2 + 0.75 * (k % 8) : 0,
             shift_y = k ? 2 + 0.75 * (k / 8) : 0;
      positions[3 * k + c] =
          (glint_vec3){tri[c].x + shift_x, tri[c].y + shift_y, tri[c].z};
      indices[3 * k + c] = (uint32_t)(3 * k + c);
    }
  uint32_t id;
  glint_scene *s = scene_with_default_material(&id);
  glint_mesh mesh = {positions, NULL, 3 * 64, indices, 64};
  ASSERT_OK(glint_scene_add_mesh(s, &mesh, id, &e_));
  static const glint_accel accels[3] = {GLINT_ACCEL_BVH, GLINT_ACCEL_BVH2,
                                        GLINT_ACCEL_BVH8};
  every_walk_hits(s, accels, 3, 20000, corner_rays, (void *)tri, "corner rays");
  glint_scene_destroy(s);
}

/* Cones of every shape the reach test (cone_reach_lanes) must keep: a thin
 * cylinder, a cone widening towards its apex and one narrowing, their axes
 * in all directions. */
typedef struct skim_cone {
  double base[3], axis[3], height, rb, rt;
} skim_cone;

static const skim_cone skim_cones[3] = {
    {{3.1, -2.2, 5.3}, {0.36, 0.48, 0.8}, 1.5, 0.01, 0.01},
    {{-4.7, 1.9, 6.1}, {-0.6, 0.0, 0.8}, 1.2, 0.02, 0.08},
    {{0.4, 6.3, -3.9}, {0.0, -0.8, 0.6}, 2.0, 0.08, 0.02}};

/* Rays skimming a cone: their line passes the axis at height h (a quarter to
 * three quarters up) at 0.99 of the radius there, tilted up to 30 degrees
 * along the axis, from 2 to 32 away. */
static void skimming_rays(void *ctx, unsigned long long *seed, float *o,
                          float *d, int lanes) {
  (void)ctx;
  for (int i = 0; i < lanes; i++) {
    const skim_cone *c = &skim_cones[(int)(uniform(seed) * 3)];
    const double *a = c->axis;
    /* p: a unit vector across the axis, q = a x p */
    double r[3] = {uniform(seed) - 0.5, uniform(seed) - 0.5,
                   uniform(seed) - 0.5};
    double ra = r[0] * a[0] + r[1] * a[1] + r[2] * a[2], p[3], pl = 0;
    for (int k = 0; k < 3; k++)
      p[k] = r[k] - ra * a[k], pl += p[k] * p[k];
    for (int k = 0; k < 3; k++)
      p[k] /= sqrt(pl);
    double q[3] = {a[1] * p[2] - a[2] * p[1], a[2] * p[0] - a[0] * p[2],
                   a[0] * p[1] - a[1] * p[0]};
    double f = 0.25 + 0.5 * uniform(seed), h = f * c->height;
    double rho = 0.99 * (c->rb + f * (c->rt - c->rb));
    double tilt = (uniform(seed) - 0.5) * 1.0471975512,
           dist = 2 + 30 * uniform(seed);
    double target[3], from[3], aim[3], al = 0;
    for (int k = 0; k < 3; k++) {
      target[k] = c->base[k] + h * a[k] + rho * p[k];
      double dk = cos(tilt) * q[k] + sin(tilt) * a[k];
      from[k] = (double)(float)(target[k] - dist * dk);
    }
    /* aimed from the rounded origin: the line passes the axis no farther
     * than at the target */
    for (int k = 0; k < 3; k++)
      aim[k] = target[k] - from[k], al += aim[k] * aim[k];
    for (int k = 0; k < 3; k++) {
      o[k * lanes + i] = (float)from[k];
      d[k * lanes + i] = (float)(aim[k] / sqrt(al));
    }
  }
}

static void rays_skimming_cones_hit(void **state) {
  (void)state;
  uint32_t id;
  glint_scene *s = scene_with_default_material(&id);
  for (int i = 0; i < 3; i++) {
    const skim_cone *c = &skim_cones[i];
    glint_vec3 base = {c->base[0], c->base[1], c->base[2]};
    glint_vec3 apex = {c->base[0] + c->height * c->axis[0],
                       c->base[1] + c->height * c->axis[1],
                       c->base[2] + c->height * c->axis[2]};
    ASSERT_OK(glint_scene_add_cone(s, base, c->rb, apex, c->rt, id, &e_));
  }
  static const glint_accel accels[4] = {GLINT_ACCEL_NONE, GLINT_ACCEL_BVH,
                                        GLINT_ACCEL_BVH2, GLINT_ACCEL_BVH8};
  every_walk_hits(s, accels, 4, 30000, skimming_rays, NULL, "skimming rays");
  glint_scene_destroy(s);
}

/* Valid files in the shapes people's tools write them: a UTF-8 byte-order
 * mark, CR LF or CR-only (old Mac) line ends, tabs. Each must load to the
 * same scene as its plain LF twin; errors keep counting lines. */
static void unusual_text_files_load(void **state) {
  (void)state;
  static const char *const nff_forms[] = {
      "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\n"
      "resolution 8 8\nl 0 5 -5\nf 1 1 1 1 0 1 0 1\ns 0 0 0 1\n",
      "\xEF\xBB\xBFv\r\nfrom 0 0 -5\r\nat 0 0 0\r\nup 0 1 0\r\nangle "
      "40\r\nhither 1\r\nresolution 8 8\r\nl 0 5 -5\r\nf 1 1 1 1 0 1 0 "
      "1\r\ns 0 0 0 1\r\n",
      "v\rfrom 0 0 -5\rat 0 0 0\rup 0 1 0\rangle 40\rhither 1\r"
      "resolution\t8 8\rl 0 5 -5 # light\rf 1 1 1 1 0 1 0 1\rs 0 0 0 1",
  };
  glint_error e;
  for (size_t i = 0; i < sizeof nff_forms / sizeof *nff_forms; i++) {
    glint_scene *s;
    if (glint_scene_load_memory(nff_forms[i], strlen(nff_forms[i]), "a.nff", &s,
                                &e))
      fail_msg("form %zu: %s", i, e.message);
    glint_scene_info info;
    glint_scene_get_info(s, &info);
    assert_int_equal(info.spheres, 1);
    assert_int_equal(info.lights, 1);
    assert_int_equal(info.width, 8);
    glint_scene_destroy(s);
  }
  glint_scene *s;
  const char *bad = "v\rfrom 0 0 -5\rs 0 0 x 1\r";
  assert_int_equal(glint_scene_load_memory(bad, strlen(bad), "b.nff", &s, &e),
                   GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "b.nff:3:"));

  static const char *const meshes[][2] = {
      {"a.obj", "\xEF\xBB\xBFv 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r"},
      {"a.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf\t1 2 3\r\n"},
      {"a.ply", "ply\rformat ascii 1.0\relement vertex 3\rproperty float "
                "x\rproperty float y\rproperty float z\relement face "
                "1\rproperty list uchar int vertex_indices\rend_header\r0 0 "
                "0\r1 0 0\r0 1 0\r3 0 1 2\r"},
      {"a.ply", "\xEF\xBB\xBFply\nformat ascii 1.0\nelement vertex "
                "3\nproperty float x\nproperty float y\nproperty float "
                "z\nelement face 1\nproperty list uchar int "
                "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
  };
  for (size_t i = 0; i < sizeof meshes / sizeof *meshes; i++) {
    glint_material m;
    glint_material_default(&m);
    uint32_t id;
    ASSERT_OK(glint_scene_create(&s, &e));
    ASSERT_OK(glint_scene_add_material(s, &m, &id, &e));
    if (gli_scene_add_mesh_data(s, meshes[i][0], meshes[i][1],
                                strlen(meshes[i][1]), 1, (glint_vec3){0, 0, 0},
                                id, &e))
      fail_msg("mesh %zu: %s", i, e.message);
    glint_scene_info info;
    glint_scene_get_info(s, &info);
    assert_int_equal(info.triangles, 1);
    glint_scene_destroy(s);
  }

  /* A binary PLY whose header lines end in CR alone (its end_header line
   * indented, as the reader allows): only the header gets LFs, wherever a
   * comment says "format ascii" or "end_header" (such a
   * comment made the body text, and its CR byte in index 13 became an LF,
   * index 10). Vertex 13 is (0, 1, 0), vertex 10 (0, 5, 0). */
  static const char header[] =
      "ply\rformat binary_little_endian 1.0\rcomment not format ascii\r"
      "comment end_header\relement vertex 14\r"
      "property float x\rproperty float y\rproperty float z\relement face 1\r"
      "property list uchar int vertex_indices\r  end_header\t\r";
  unsigned char ply[sizeof header - 1 + 14 * 12 + 13];
  memcpy(ply, header, sizeof header - 1);
  float xyz[14][3] = {{0, 0, 0}, {1, 0, 0}};
  xyz[10][1] = 5, xyz[13][1] = 1;
  memcpy(ply + sizeof header - 1, xyz, sizeof xyz); /* x86: little-endian */
  unsigned char face[13] = {3, 0, 0, 0, 0, 1, 0, 0, 0, 13, 0, 0, 0};
  memcpy(ply + sizeof header - 1 + sizeof xyz, face, sizeof face);
  glint_material m;
  glint_material_default(&m);
  uint32_t id;
  ASSERT_OK(glint_scene_create(&s, &e));
  ASSERT_OK(glint_scene_add_material(s, &m, &id, &e));
  if (gli_scene_add_mesh_data(s, "b.ply", (const char *)ply, sizeof ply, 1,
                              (glint_vec3){0, 0, 0}, id, &e))
    fail_msg("binary PLY with CR line ends: %s", e.message);
  glint_scene_info info;
  glint_scene_get_info(s, &info);
  assert_int_equal(info.triangles, 1);
  assert_true(info.bounds_max.y == 1);
  glint_scene_destroy(s);
}

/* Bad input found by trying glint as a new user would: each gets one
 * message naming the file, the line (or line and column) and the problem. */
static void bad_input_is_named(void **state) {
  (void)state;
  static const char *const cases[][3] = {
      /* name, content, what the message must hold */
      {"empty.nff", "", "empty.nff: no scene"},
      {"blank.nff", "  \n\t\n# only a comment\n", "blank.nff: no scene"},
      {"ctl.nff", "\x1b[31mred\n", "ctl.nff:1: unknown entity '?[31mred'"},
      {"esc.json", "{\"materials\": {\"a\\uZZZZ\": {}}}",
       "esc.json:1:18: JSON syntax error: \\u needs four hexadecimal"},
      {"nul.json", "{\"materials\": {\"a\\u0000b\": {}}}",
       "nul.json:1:18: JSON syntax error: \\u0000"},
      {"bad.json", "{\"materials\": {\"a\\qb\": {}}}",
       "bad.json:1:18: JSON syntax error: an invalid escape sequence"},
      {"zero.json", "{\"image\": {\"width\": 064, \"height\": 48}}",
       "zero.json:1:21: JSON syntax error: a number with a leading zero"},
      {"tab.json", "{\"materials\": {\"a\tb\": {}}}",
       "tab.json:1:18: JSON syntax error: a control character"},
      {"empty.json", "", "empty.json:1:1: JSON syntax error"},
      /* a line break inside a string, which cJSON takes into a name (and
       * which stopped these checks for the rest of the file) */
      {"lf.json", "{\"materials\": {\"a\nb\": {}}, \"background\": [01, 0, 0]}",
       "lf.json:1:18: JSON syntax error: a control character inside a "
       "string"},
      {"cr.json", "{\"materials\": {\"a\rb\": {}}}",
       "cr.json:1:18: JSON syntax error: a control character inside a "
       "string"},
      /* control characters between tokens, which cJSON took for blanks */
      {"ctl.json", "{\x01\"background\": [0, 0, 0]}",
       "ctl.json:1:2: JSON syntax error: a control character between tokens"},
      {"vt.json", "{\"background\":\v[0, 0, 0]}",
       "vt.json:1:15: JSON syntax error: a control character between"},
      {"after.json", "{\"background\": [0, 0, 0]}\n\x1f",
       "after.json:2:1: JSON syntax error: a control character between"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    glint_scene *s = NULL;
    glint_error e;
    glint_status st = glint_scene_load_memory(cases[i][1], strlen(cases[i][1]),
                                              cases[i][0], &s, &e);
    if (st != GLINT_E_PARSE || !strstr(e.message, cases[i][2]))
      fail_msg("%s: status %d, message '%s', want '%s'", cases[i][0], st,
               st ? e.message : "", cases[i][2]);
  }
  /* NFF, OBJ and PLY read numbers as C's strtod does (so hexadecimal
   * floating point too, exactly); JSON only as RFC 8259 writes them */
  static const char hex[] = "v\nfrom 0 0 -9\nat 0 0 0\nup 0 1 0\nangle 40\n"
                            "hither 1\nresolution 8 8\nf 1 1 1 1 0 1 0 1\n"
                            "s 0x1p1 -0 0 0x.8p1\n";
  glint_scene *hs;
  glint_error he;
  ASSERT_OK(glint_scene_load_memory(hex, strlen(hex), "hex.nff", &hs, &he));
  glint_scene_info info;
  glint_scene_get_info(hs, &info);
  assert_true(info.bounds_min.x == 1 && info.bounds_max.x == 3);
  glint_scene_destroy(hs);
  /* valid JSON numbers stay valid: 0, -0, 0.5, 1e-3, 10 */
  static const char ok[] = "{\"background\": [0, -0, 0.5], \"ambient\": "
                           "[1e-3, 10, 0.0]}";
  glint_scene *s;
  glint_error e;
  ASSERT_OK(glint_scene_load_memory(ok, strlen(ok), "ok.json", &s, &e));
  glint_scene_destroy(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(thin_cylinder),
      cmocka_unit_test(huge_triangles),
      cmocka_unit_test(meshes_are_watertight),
      cmocka_unit_test(rays_grazing_a_box_corner_hit),
      cmocka_unit_test(rays_skimming_cones_hit),
      cmocka_unit_test(long_numbers_are_read_whole),
      cmocka_unit_test(unusual_text_files_load),
      cmocka_unit_test(bad_input_is_named),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
