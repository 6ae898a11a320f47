/* The mesh readers (src/scene/mesh.c): OBJ, ASCII and binary PLY, gzip.
 * Small files written here check every feature and every error; the real
 * meshes of the shared folder check the triangle counts at full size.
 *
 * Every error test loads into a scene that already holds geometry and
 * checks that a failed load leaves it exactly as it was. */
#include "test_util.h"

#include "scene/scene.h"
#include "shared.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

typedef glint_vec3 V;

#define MAX_FILES 192 /* more than the tests write */

/* The temporary folder (the group state) and the files written into it, so
 * that teardown can remove them. */
typedef struct fixture {
  char dir[256];
  char files[MAX_FILES][320];
  int nfiles;
} fixture;

static int setup(void **state) {
  fixture *f = calloc(1, sizeof *f);
  if (!f)
    return -1;
  snprintf(f->dir, sizeof f->dir, "/tmp/glint_test_mesh_XXXXXX");
  if (!mkdtemp(f->dir)) {
    free(f);
    return -1;
  }
  *state = f;
  return 0;
}

static int teardown(void **state) {
  fixture *f = *state;
  for (int i = 0; i < f->nfiles; i++)
    unlink(f->files[i]);
  rmdir(f->dir);
  free(f);
  return 0;
}

/* The path of `name` in the folder, remembered for removal. */
static const char *path_of(fixture *f, const char *name) {
  for (int i = 0; i < f->nfiles; i++) {
    const char *slash = strrchr(f->files[i], '/');
    if (strcmp(slash + 1, name) == 0)
      return f->files[i];
  }
  assert_true(f->nfiles < MAX_FILES);
  char path[sizeof f->files[0]];
  snprintf(path, sizeof path, "%s/%s", f->dir, name);
  memcpy(f->files[f->nfiles], path, sizeof path);
  return f->files[f->nfiles++];
}

static const char *write_bytes(fixture *f, const char *name, const void *data,
                               size_t size) {
  const char *path = path_of(f, name);
  FILE *fp = fopen(path, "wb");
  assert_non_null(fp);
  assert_int_equal(fwrite(data, 1, size, fp), size);
  assert_int_equal(fclose(fp), 0);
  return path;
}

static const char *write_text(fixture *f, const char *name, const char *text) {
  return write_bytes(f, name, text, strlen(text));
}

static const char *write_gz(fixture *f, const char *name, const char *text) {
  const char *path = path_of(f, name);
  gzFile gz = gzopen(path, "wb9");
  assert_non_null(gz);
  assert_int_equal(gzwrite(gz, text, (unsigned)strlen(text)),
                   (int)strlen(text));
  assert_int_equal(gzclose(gz), Z_OK);
  return path;
}

/* Loads `path` into a new scene at scale 1, failing the test on error. */
static glint_scene *load(const char *path, double scale, V translate) {
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  ASSERT_OK(glint_scene_add_mesh_file(s, path, scale, translate, m, &e_));
  return s;
}

static void assert_vec(V got, double x, double y, double z) {
  if (fabs(got.x - x) > 1e-9 || fabs(got.y - y) > 1e-9 ||
      fabs(got.z - z) > 1e-9)
    fail_msg("got (%g, %g, %g), expected (%g, %g, %g)", got.x, got.y, got.z, x,
             y, z);
}

static void assert_tri(const glint_scene *s, size_t i, V a, V b, V c) {
  assert_true(i < s->triangle_count);
  const gli_triangle_prim *t = &s->triangles[i];
  assert_vec(t->v[0], a.x, a.y, a.z);
  assert_vec(t->v[1], b.x, b.y, b.z);
  assert_vec(t->v[2], c.x, c.y, c.z);
}

/* The normal of corner k of triangle i, which must be smooth. */
static V normal_of(const glint_scene *s, size_t i, int k) {
  assert_int_not_equal(s->triangles[i].normals, GLI_NO_NORMALS);
  return s->tri_normals[s->triangles[i].normals + (uint32_t)k];
}

/* A load that must fail with `status` and a message holding the file's
 * path and each of the fragments, into a scene with geometry already in it
 * that must come out unchanged. */
static void expect_fail_path(const char *path, glint_status status,
                             const char *frag1, const char *frag2) {
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  ASSERT_OK(glint_scene_add_triangle(s, (V){0, 0, 0}, (V){1, 0, 0},
                                     (V){0, 1, 0}, m, &e_));
  ASSERT_OK(gli_scene_begin_object(s, GLI_SHAPE_TRIANGLE, m, &e_));
  V n[3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  ASSERT_OK(gli_scene_push_triangle(s, (V){0, 0, 1}, (V){1, 0, 1}, (V){0, 1, 1},
                                    n, &e_));
  size_t objects = s->object_count, tris = s->triangle_count,
         normals = s->tri_normal_count;
  gli_triangle_prim before[2];
  memcpy(before, s->triangles, sizeof before);

  glint_error e;
  memset(&e, 0, sizeof e);
  glint_status st = glint_scene_add_mesh_file(s, path, 1, (V){0, 0, 0}, m, &e);
  if (st != status)
    fail_msg("%s: status %s, expected %s (message '%s')", path,
             glint_status_name(st), glint_status_name(status), e.message);
  assert_int_equal(e.status, status);
  if (!strstr(e.message, path))
    fail_msg("message '%s' lacks the path '%s'", e.message, path);
  if (frag1 && !strstr(e.message, frag1))
    fail_msg("message '%s' lacks '%s'", e.message, frag1);
  if (frag2 && !strstr(e.message, frag2))
    fail_msg("message '%s' lacks '%s'", e.message, frag2);

  assert_int_equal(s->object_count, objects);
  assert_int_equal(s->triangle_count, tris);
  assert_int_equal(s->tri_normal_count, normals);
  assert_memory_equal(before, s->triangles, sizeof before);
  glint_scene_destroy(s);
}

static void expect_fail(fixture *f, const char *name, const char *text,
                        glint_status status, const char *frag1,
                        const char *frag2) {
  expect_fail_path(write_text(f, name, text), status, frag1, frag2);
}

/* ------------------------------------------------------------------------ */
/* OBJ                                                                      */
/* ------------------------------------------------------------------------ */

static void obj_triangle_scaled_and_moved(void **state) {
  fixture *f = *state;
  const char *p = write_text(f, "tri.obj",
                             "# one triangle\n"
                             "v 0 0 0\nv 1 0 0\nv 0 1 0 1.0\n"
                             "f 1 2 3\n");
  glint_scene *s = load(p, 2, (V){10, 20, 30});
  assert_int_equal(s->object_count, 1);
  assert_int_equal(s->triangle_count, 1);
  assert_int_equal(s->objects[0].shape, GLI_SHAPE_TRIANGLE);
  assert_int_equal(s->objects[0].count, 1);
  assert_tri(s, 0, (V){10, 20, 30}, (V){12, 20, 30}, (V){10, 22, 30});
  assert_int_equal(s->triangles[0].normals, GLI_NO_NORMALS);
  /* Solid textures follow the mesh: its local origin is the translation. */
  assert_vec(s->objects[0].origin, 10, 20, 30);
  glint_scene_destroy(s);
}

/* The summed signed area (in z = const planes) of triangles [from, to). */
static double area_xy(const glint_scene *s, size_t from, size_t to) {
  double area = 0;
  for (size_t i = from; i < to; i++) {
    const gli_triangle_prim *t = &s->triangles[i];
    double a = 0.5 * ((t->v[1].x - t->v[0].x) * (t->v[2].y - t->v[0].y) -
                      (t->v[1].y - t->v[0].y) * (t->v[2].x - t->v[0].x));
    if (a < -1e-12)
      fail_msg("triangle %zu is turned over (area %g)", i, a);
    area += a;
  }
  return area;
}

/* A quad is two triangles from its first corner; a larger convex face is
 * bisected (scene/polygon.c), as NFF's polygons are: a fan of a 64-corner
 * disc is 62 slivers from one corner, each with a box as large as the
 * disc's, and rendered as one face of 4 096 corners 18-40 times slower
 * than bisected. */
static void obj_polygons_are_cut(void **state) {
  fixture *f = *state;
  const char *p = write_text(f, "poly.obj",
                             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                             "v 0 0 1\nv 1 0 1\nv 2 1 1\nv 1 2 1\nv 0 1 1\n"
                             "f 1 2 3 4\n"     /* quad: 2 triangles */
                             "f 5 6 7 8 9\n"); /* pentagon: 3 */
  glint_scene *s = load(p, 1, (V){0, 0, 0});
  assert_int_equal(s->object_count, 1);
  assert_int_equal(s->triangle_count, 5);
  assert_tri(s, 0, (V){0, 0, 0}, (V){1, 0, 0}, (V){1, 1, 0});
  assert_tri(s, 1, (V){0, 0, 0}, (V){1, 1, 0}, (V){0, 1, 0});
  assert_tri(s, 2, (V){0, 0, 1}, (V){1, 0, 1}, (V){2, 1, 1});
  assert_tri(s, 3, (V){2, 1, 1}, (V){1, 2, 1}, (V){0, 1, 1});
  assert_tri(s, 4, (V){0, 1, 1}, (V){0, 0, 1}, (V){2, 1, 1});
  glint_scene_destroy(s);
  /* The disc: its 62 triangles cover it, and no corner is in more than
   * about twice the bisection's depth (a fan puts its first corner in all). */
  enum { CORNERS = 64 };
  const double turn = 6.283185307179586 / CORNERS;
  char text[CORNERS * 64 + 512], *t = text;
  for (int i = 0; i < CORNERS; i++)
    t += sprintf(t, "v %.17g %.17g 0\n", cos(turn * i), sin(turn * i));
  t += sprintf(t, "f");
  for (int i = 1; i <= CORNERS; i++)
    t += sprintf(t, " %d", i);
  sprintf(t, "\n");
  s = load(write_text(f, "disc.obj", text), 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, CORNERS - 2);
  double area = area_xy(s, 0, s->triangle_count);
  assert_true(fabs(area - CORNERS / 2.0 * sin(turn)) < 1e-9);
  int most = 0;
  for (int i = 0; i < CORNERS; i++) {
    V c = {cos(turn * i), sin(turn * i), 0};
    int in = 0;
    for (size_t k = 0; k < s->triangle_count; k++)
      for (int j = 0; j < 3; j++)
        in += fabs(s->triangles[k].v[j].x - c.x) < 1e-9 &&
              fabs(s->triangles[k].v[j].y - c.y) < 1e-9;
    most = in > most ? in : most;
  }
  printf("64-corner disc: at most %d triangles share a corner\n", most);
  assert_true(most <= 12); /* bisected: 10; fanned: 62 */
  glint_scene_destroy(s);
}

/* A concave face is not fanned (a fan from its first corner would cover
 * what is not the face): an L that its first corner cannot see whole, and an
 * arrow quad whose fan from corner 1 would double-cover, in OBJ and in PLY.
 * Their triangles cover exactly the face's area, all facing its way. */
static void concave_faces_are_ear_clipped(void **state) {
  fixture *f = *state;
  static const char obj[] = "v 0 0 0\nv 4 0 0\nv 4 1 0\nv 1 1 0\nv 1 3 0\n"
                            "v 0 3 0\n"
                            "v 0 0 1\nv 2 1 1\nv 0 2 1\nv 1 1 1\n"
                            "f 3 4 5 6 1 2\n" /* L: area 4 + 2 = 6 */
                            "f 7 8 9 10\n";   /* arrow: area 1 */
  glint_scene *s = load(write_text(f, "concave.obj", obj), 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, 4 + 2);
  assert_true(fabs(area_xy(s, 0, 4) - 6) < 1e-12);
  assert_true(fabs(area_xy(s, 4, 6) - 1) < 1e-12);
  glint_scene_destroy(s);
  static const char ply[] = "ply\nformat ascii 1.0\nelement vertex 6\n"
                            "property float x\nproperty float y\n"
                            "property float z\nelement face 1\n"
                            "property list uchar int vertex_indices\n"
                            "end_header\n0 0 0\n4 0 0\n4 1 0\n1 1 0\n"
                            "1 3 0\n0 3 0\n6 2 3 4 5 0 1\n";
  s = load(write_text(f, "concave.ply", ply), 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, 4);
  assert_true(fabs(area_xy(s, 0, 4) - 6) < 1e-12);
  glint_scene_destroy(s);
}

static void obj_negative_indices(void **state) {
  fixture *f = *state;
  const char *p = write_text(f, "neg.obj",
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                             "f -3 -2 -1\n"
                             "v 5 5 5\n"
                             "f -1 1 -3\n"); /* v4 v1 v2 */
  glint_scene *s = load(p, 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, 2);
  assert_tri(s, 0, (V){0, 0, 0}, (V){1, 0, 0}, (V){0, 1, 0});
  assert_tri(s, 1, (V){5, 5, 5}, (V){0, 0, 0}, (V){1, 0, 0});
  glint_scene_destroy(s);
}

static void obj_vertex_forms_and_normals(void **state) {
  fixture *f = *state;
  const char *p = write_text(f, "forms.obj",
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                             "vt 0 0\nvt 1 0\nvt 0 1\n"
                             "vn 0 0 2\nvn 0 3 0\nvn 4 0 0\n"
                             "f 1/1/1 2/2/2 3/3/3\n" /* i/t/n: smooth */
                             "f 1//3 2//2 3//1\n"    /* i//n: smooth */
                             "f 1/1 2/2 3/3\n"       /* i/t: flat */
                             "f 1//1 2 3//1\n"       /* mixed: flat */
                             "f 1/-3/-3 2/-2/-2 3/-1/-1\n");
  glint_scene *s = load(p, 3, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, 5);
  /* Normals are unit length (the scene normalises them), not scaled. */
  assert_vec(normal_of(s, 0, 0), 0, 0, 1);
  assert_vec(normal_of(s, 0, 1), 0, 1, 0);
  assert_vec(normal_of(s, 0, 2), 1, 0, 0);
  assert_vec(normal_of(s, 1, 0), 1, 0, 0);
  assert_vec(normal_of(s, 1, 2), 0, 0, 1);
  assert_int_equal(s->triangles[2].normals, GLI_NO_NORMALS);
  assert_int_equal(s->triangles[3].normals, GLI_NO_NORMALS);
  assert_vec(normal_of(s, 4, 0), 0, 0, 1);
  assert_vec(normal_of(s, 4, 2), 1, 0, 0);
  assert_tri(s, 4, (V){0, 0, 0}, (V){3, 0, 0}, (V){0, 3, 0});
  assert_int_equal(s->tri_normal_count, 9);
  glint_scene_destroy(s);
}

static void obj_ignores_known_statements(void **state) {
  fixture *f = *state;
  const char *p =
      write_text(f, "known.obj",
                 "# comment\r\n"
                 "mtllib box.mtl\r\n"
                 "o box\r\ng side front\r\ns 1\r\ns off\r\nusemtl red\r\n"
                 "v 0 0 0 # trailing comment\r\n"
                 "\tv\t1 0 0\r\n"
                 "v 0 1 0 0.5 0.5 0.5\r\n" /* the vertex colour extension */
                 "v 1 1 0\r\n"
                 "vp 0.5\r\ncstype bspline\r\ndeg 3\r\nl 1 2\r\np 1\r\n"
                 "lod 1\r\nbevel off\r\nc_interp on\r\nd_interp off\r\n"
                 "f 1 2 \\\r\n 3\r\n" /* a continuation line */
                 "\r\n   \r\n"
                 "f 2 4 3"); /* no final newline */
  glint_scene *s = load(p, 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, 2);
  assert_tri(s, 1, (V){1, 0, 0}, (V){1, 1, 0}, (V){0, 1, 0});
  glint_scene_destroy(s);
  /* A UTF-8 byte order mark, as some Windows exporters write. */
  p = write_text(f, "bom.obj",
                 "\xef\xbb\xbfv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  s = load(p, 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, 1);
  glint_scene_destroy(s);
}

/* A grid of n x n unit quads in z = 0, two triangles each, its faces in
 * a scrambled order (quad k is the (k * 769) mod n^2-th); the faces at
 * file places bad1 and bad2 (-1: none) use a vertex beyond the coordinate
 * limit. Returns the OBJ text (free it). */
static char *scrambled_grid(int n, int bad1, int bad2) {
  size_t cap = 32 * (size_t)(n + 1) * (n + 1) + 64 * (size_t)n * n, len = 0;
  char *text = malloc(cap);
  assert_non_null(text);
  for (int y = 0; y <= n; y++)
    for (int x = 0; x <= n; x++)
      len += (size_t)snprintf(text + len, cap - len, "v %d %d 0\n", x, y);
  len += (size_t)snprintf(text + len, cap - len, "v 2e15 0 0\n");
  int far = (n + 1) * (n + 1) + 1, face = 0;
  for (int k = 0; k < n * n; k++) {
    int q = (int)(((long)k * 769) % (n * n)), x = q % n, y = q / n;
    int a = y * (n + 1) + x + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
    int tri[2][3] = {{a, b, c}, {a, c, d}};
    for (int t = 0; t < 2; t++, face++)
      len += (size_t)snprintf(text + len, cap - len, "f %d %d %d\n",
                              face == bad1 || face == bad2 ? far : tri[t][0],
                              tri[t][1], tri[t][2]);
  }
  assert_true(len < cap);
  return text;
}

/* Triangle t's first vertex and three times its centroid, as one integer
 * (the grid's coordinates are small whole numbers). */
static long triangle_key(const gli_triangle_prim *t) {
  long cx = lround(t->v[0].x + t->v[1].x + t->v[2].x);
  long cy = lround(t->v[0].y + t->v[1].y + t->v[2].y);
  return ((cx * 1000 + cy) * 100 + lround(t->v[0].x)) * 100 + lround(t->v[0].y);
}

/* The distance from each triangle's centroid to the next one's, summed
 * (city-block, grid units). */
static double walk_length(const gli_triangle_prim *t, size_t count) {
  double sum = 0;
  for (size_t i = 1; i < count; i++) {
    double dx = (t[i].v[0].x + t[i].v[1].x + t[i].v[2].x) -
                (t[i - 1].v[0].x + t[i - 1].v[1].x + t[i - 1].v[2].x);
    double dy = (t[i].v[0].y + t[i].v[1].y + t[i].v[2].y) -
                (t[i - 1].v[0].y + t[i - 1].v[1].y + t[i - 1].v[2].y);
    sum += (fabs(dx) + fabs(dy)) / 3;
  }
  return sum;
}

static int compare_long(const void *a, const void *b) {
  long x = *(const long *)a, y = *(const long *)b;
  return (x > y) - (x < y);
}

/* A mesh of GLI_MORTON_MIN_TRIANGLES or more is kept along a Morton curve
 * (gli_morton_order, scene.c), whatever its file's order: the same
 * triangles, each turned as in the file, with neighbours in space near in
 * memory; the API's meshes alike. A bad triangle is still named by its
 * place in the file, the first of two. */
static void large_meshes_are_kept_in_space_order(void **state) {
  fixture *f = *state;
  enum { N = 32, COUNT = 2 * N * N };
  assert_true(COUNT >= GLI_MORTON_MIN_TRIANGLES);
  char *text = scrambled_grid(N, -1, -1);
  glint_scene *s = load(write_text(f, "grid.obj", text), 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, COUNT);

  /* The file's triangles in its order, read back from the text. */
  uint32_t m;
  glint_scene *file = scene_with_default_material(&m);
  ASSERT_OK(gli_scene_begin_object(file, GLI_SHAPE_TRIANGLE, m, &e_));
  glint_vec3 *pos = calloc((N + 1) * (N + 1) + 1, sizeof *pos);
  uint32_t *indices = calloc(3 * COUNT, sizeof *indices);
  long *got = calloc(2 * COUNT, sizeof *got), *want = got + COUNT;
  assert_true(pos && indices && got);
  size_t npos = 0, nidx = 0;
  for (const char *line = text; *line; line = strchr(line, '\n') + 1) {
    int a, b, c;
    double x, y, z;
    if (sscanf(line, "v %lf %lf %lf", &x, &y, &z) == 3)
      pos[npos++] = (V){x, y, z};
    else if (sscanf(line, "f %d %d %d", &a, &b, &c) == 3) {
      ASSERT_OK(gli_scene_push_triangle(file, pos[a - 1], pos[b - 1],
                                        pos[c - 1], NULL, &e_));
      indices[nidx++] = (uint32_t)a - 1;
      indices[nidx++] = (uint32_t)b - 1;
      indices[nidx++] = (uint32_t)c - 1;
    }
  }
  assert_int_equal(file->triangle_count, COUNT);

  /* The same triangles, each once. */
  for (size_t i = 0; i < COUNT; i++) {
    got[i] = triangle_key(&s->triangles[i]);
    want[i] = triangle_key(&file->triangles[i]);
  }
  qsort(got, COUNT, sizeof *got, compare_long);
  qsort(want, COUNT, sizeof *want, compare_long);
  assert_memory_equal(got, want, COUNT * sizeof *got);
  for (size_t i = 1; i < COUNT; i++)
    assert_true(want[i] != want[i - 1]); /* the keys tell them apart */

  /* Neighbours near: along the Morton curve a step is 1.4 units on
   * average; in the scrambled file, 7.5. */
  double walked = walk_length(s->triangles, COUNT);
  double scrambled = walk_length(file->triangles, COUNT);
  if (!(walked < 1.6 * COUNT && walked < scrambled / 4))
    fail_msg("consecutive triangles %g apart in all, the file's %g", walked,
             scrambled);

  /* The API's meshes: in the order the file's reader gives. */
  glint_scene *api = scene_with_default_material(&m);
  glint_mesh mesh = {pos, NULL, npos, indices, COUNT};
  ASSERT_OK(glint_scene_add_mesh(api, &mesh, m, &e_));
  assert_int_equal(api->triangle_count, COUNT);
  for (size_t i = 0; i < COUNT; i++)
    for (int k = 0; k < 3; k++)
      assert_vec(api->triangles[i].v[k], s->triangles[i].v[k].x,
                 s->triangles[i].v[k].y, s->triangles[i].v[k].z);
  glint_scene_destroy(api);

  /* Unchecked numbers reach the ordering: refused after it, no harm. */
  for (int k = 0; k < 3; k++) {
    V saved = pos[5];
    pos[5] = (V[]){{NAN, 0, 0}, {0, INFINITY, 0}, {0, 0, -1e300}}[k];
    api = scene_with_default_material(&m);
    glint_error err;
    assert_int_equal(glint_scene_add_mesh(api, &mesh, m, &err),
                     GLINT_E_ARGUMENT);
    if (!strstr(err.message, "coordinates"))
      fail_msg("message '%s'", err.message);
    assert_int_equal(api->triangle_count, 0);
    glint_scene_destroy(api);
    pos[5] = saved;
  }
  glint_scene_destroy(file);
  glint_scene_destroy(s);
  free(got);
  free(indices);
  free(pos);
  free(text);

  /* Faces 1500 and 700 (from 0) use a vertex past the limit: 700 is named,
   * by its line. */
  text = scrambled_grid(N, 1500, 700);
  char line[32];
  snprintf(line, sizeof line, "bad.obj:%d: vertex ", (N + 1) * (N + 1) + 702);
  expect_fail(f, "bad.obj", text, GLINT_E_ARGUMENT, line,
              "magnitude at most 1e15");
  free(text);
}

static void obj_gzip_and_two_meshes(void **state) {
  fixture *f = *state;
  const char *text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
  const char *gz = write_gz(f, "quad.obj.gz", text);
  /* gzip is recognised by content: a compressed file with a plain name
   * loads too, and a plain one with .gz. */
  const char *gz_plain_name = write_gz(f, "quad2.obj", text);
  const char *plain_gz_name = write_text(f, "quad3.obj.gz", text);
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  ASSERT_OK(glint_scene_add_mesh_file(s, gz, 1, (V){0, 0, 0}, m, &e_));
  ASSERT_OK(
      glint_scene_add_mesh_file(s, gz_plain_name, 1, (V){0, 0, 5}, m, &e_));
  ASSERT_OK(
      glint_scene_add_mesh_file(s, plain_gz_name, 1, (V){0, 0, 9}, m, &e_));
  assert_int_equal(s->object_count, 3);
  assert_int_equal(s->triangle_count, 6);
  for (uint32_t i = 0; i < 3; i++) {
    assert_int_equal(s->objects[i].first, 2 * i);
    assert_int_equal(s->objects[i].count, 2);
    assert_int_equal(s->triangles[2 * i].object, i);
  }
  assert_tri(s, 3, (V){1, 0, 5}, (V){1, 1, 5}, (V){0, 1, 5});
  glint_scene_destroy(s);
}

/* ------------------------------------------------------------------------ */
/* PLY                                                                      */
/* ------------------------------------------------------------------------ */

/* A square (a quad face) and a triangle, with extra properties and
 * elements that the reader must skip. */
static const char ply_ascii_text[] =
    "ply\n"
    "format ascii 1.0\n"
    "comment made by hand\n"
    "obj_info nothing\n"
    "element material 1\n" /* before the vertices, skipped */
    "property uchar red\n"
    "property list uchar float weights\n"
    "element vertex 5\n"
    "property float x\n"
    "property float confidence\n"
    "property float y\n"
    "property float z\n"
    "property uchar intensity\n"
    "element face 2\n"
    "property uchar flags\n"
    "property list uchar int vertex_indices\n"
    "property list uchar float texcoord\n"
    "element edge 1\n"
    "property int vertex1\n"
    "property int vertex2\n"
    "end_header\n"
    "255 2 0.5 0.25\n"
    "0 0.9 0 0 7\n"
    "1 0.9 0 0 7\n"
    "1 0.9 1 0 7\n"
    "0 0.9 1 0 7\n"
    "\n"
    "0.5 1 2 -1 3\r\n"
    "1 4 0 1 2 3 0\n"
    "0 3 0 1 4 3 0.5 0.5 1\n"
    "0 1\n";

static void ply_ascii_skips_what_it_does_not_use(void **state) {
  fixture *f = *state;
  glint_scene *s =
      load(write_text(f, "square.ply", ply_ascii_text), 2, (V){1, 1, 1});
  assert_int_equal(s->object_count, 1);
  assert_int_equal(s->triangle_count, 3);
  assert_tri(s, 0, (V){1, 1, 1}, (V){3, 1, 1}, (V){3, 3, 1});
  assert_tri(s, 1, (V){1, 1, 1}, (V){3, 3, 1}, (V){1, 3, 1});
  assert_tri(s, 2, (V){1, 1, 1}, (V){3, 1, 1}, (V){2, 5, -1});
  assert_int_equal(s->triangles[0].normals, GLI_NO_NORMALS);
  glint_scene_destroy(s);
  /* The same, gzip-compressed. */
  s = load(write_gz(f, "square.ply.gz", ply_ascii_text), 2, (V){1, 1, 1});
  assert_int_equal(s->triangle_count, 3);
  glint_scene_destroy(s);
}

/* Less usual but valid: CRLF lines, faces declared before vertices,
 * integer coordinates, and normals without nz (so: flat). */
static void ply_ascii_unusual_but_valid(void **state) {
  fixture *f = *state;
  /* (a blank after the magic 'ply' was refused; other lines took one) */
  const char *p = write_text(f, "unusual.ply",
                             "ply \r\nformat ascii 1.0\r\n"
                             "element face 1\r\n"
                             "property list uint8 int32 vertex_indices\r\n"
                             "element vertex 3\r\n"
                             "property short x\r\nproperty short y\r\n"
                             "property int z\r\nproperty float nx\r\n"
                             "property float ny\r\nend_header\r\n"
                             "3 2 1 0\r\n"
                             "0 0 0 1 0\r\n-4 0 0 1 0\r\n0 5 0 1 0\r\n");
  glint_scene *s = load(p, 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, 1);
  assert_tri(s, 0, (V){0, 5, 0}, (V){-4, 0, 0}, (V){0, 0, 0});
  assert_int_equal(s->triangles[0].normals, GLI_NO_NORMALS);
  glint_scene_destroy(s);
}

/* The absolute area of the mesh's triangles. */
static double mesh_area(const glint_scene *s) {
  double sum = 0;
  for (size_t i = 0; i < s->triangle_count; i++) {
    const glint_vec3 *v = s->triangles[i].v;
    double ux = v[1].x - v[0].x, uy = v[1].y - v[0].y;
    double wx = v[2].x - v[0].x, wy = v[2].y - v[0].y;
    sum += fabs(ux * wy - uy * wx) / 2;
  }
  return sum;
}

/* A concave face listed before the vertices (PLY allows any order) is cut
 * by ears once they are read, as when it comes after them: it was cut as a
 * fan, covering the notch of this L (area 5). */
static void ply_faces_before_vertices(void **state) {
  fixture *f = *state;
  static const char *const bodies[] = {
      "ply\nformat ascii 1.0\nelement face 1\n"
      "property list uchar int vertex_indices\nelement vertex 6\n"
      "property float x\nproperty float y\nproperty float z\nend_header\n"
      "6 0 1 2 3 4 5\n3 -2 0\n1 -2 0\n1 0 0\n0 0 0\n0 -3 0\n3 -3 0\n",
      "ply\nformat ascii 1.0\nelement vertex 6\n"
      "property float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "3 -2 0\n1 -2 0\n1 0 0\n0 0 0\n0 -3 0\n3 -3 0\n6 0 1 2 3 4 5\n"};
  for (int i = 0; i < 2; i++) {
    glint_scene *s =
        load(write_text(f, i ? "after.ply" : "before.ply", bodies[i]), 1,
             (V){0, 0, 0});
    assert_int_equal(s->triangle_count, 4);
    if (fabs(mesh_area(s) - 5) > 1e-9)
      fail_msg("%s: the triangles cover %g, not the L's 5",
               i ? "after" : "before", mesh_area(s));
    glint_scene_destroy(s);
  }
}

/* A face too concave to cut (a comb of 20 000 teeth: the ear clipping's
 * budget runs out), listed before the vertices, is named as such (a face
 * read after them is named by its line, as any other error there; each
 * comb costs the budget's two seconds, so one is tested). */
static void ply_face_too_concave(void **state) {
  fixture *f = *state;
  enum { TEETH = 20000, N = 2 * TEETH + 3 };
  size_t cap = (size_t)N * 48 + 4096;
  char *text = malloc(cap), *p = text;
  assert_non_null(text);
  p += sprintf(p,
               "ply\nformat ascii 1.0\nelement face 1\n"
               "property list int int vertex_indices\n"
               "element vertex %d\nproperty float x\nproperty float y\n"
               "property float z\nend_header\n%d",
               N, N);
  for (int i = 0; i < N; i++)
    p += sprintf(p, " %d", i);
  /* the comb: a bar along x at y in [-1, 0], spikes to y = 10 */
  p += sprintf(p, "\n0 -1 0\n%d -1 0\n", 2 * TEETH);
  for (int i = TEETH; i > 0; i--)
    p += sprintf(p, "%d 0 0\n%d 10 0\n", 2 * i, 2 * i - 1);
  p += sprintf(p, "0 0 0\n");
  assert_true((size_t)(p - text) < cap);
  expect_fail(f, "comb.ply", text, GLINT_E_PARSE,
              "comb.ply: a face listed before the vertices: the face of "
              "40003 vertices has too many inward corners to triangulate",
              NULL);
  free(text);
}

/* Triangle strips (a 'tristrips' element): each index after a strip's
 * first two makes a triangle with the two before it, every other one
 * turned so that all face one way; -1 starts a new strip; a triangle that
 * repeats a vertex (a strip turning) is dropped. Here a strip over a
 * 2 x 1 grid of unit squares (4 triangles), a turn, and after -1 a strip
 * of one triangle: 5 triangles of area 2.5, all facing +z. A file with
 * strips and no faces loads; one with neither is a point cloud. */
static void ply_tristrips(void **state) {
  fixture *f = *state;
  static const char *const body =
      "ply\nformat ascii 1.0\nelement vertex 9\n"
      "property float x\nproperty float y\nproperty float z\n"
      "element tristrips 1\nproperty list int int vertex_indices\n"
      "end_header\n"
      "0 1 0\n0 0 0\n1 1 0\n1 0 0\n2 1 0\n2 0 0\n5 0 0\n6 0 0\n5 1 0\n"
      "12 0 1 2 3 4 5 5 5 -1 6 7 8\n";
  glint_scene *s = load(write_text(f, "strip.ply", body), 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, 5);
  if (fabs(mesh_area(s) - 2.5) > 1e-9)
    fail_msg("the strips cover %g, not 2.5", mesh_area(s));
  for (size_t i = 0; i < s->triangle_count; i++) {
    const glint_vec3 *v = s->triangles[i].v;
    double z = (v[1].x - v[0].x) * (v[2].y - v[0].y) -
               (v[1].y - v[0].y) * (v[2].x - v[0].x);
    if (z <= 0)
      fail_msg("triangle %zu of the strips faces -z", i);
  }
  glint_scene_destroy(s);
  expect_fail(f, "stripidx.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\n"
              "property float x\nproperty float y\nproperty float z\n"
              "element tristrips 1\nproperty list int int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2 3\n",
              GLINT_E_PARSE,
              "stripidx.ply:13: triangle strip refers to vertex 3, but only 3 "
              "are defined",
              NULL);
  expect_fail(f, "stripnone.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\n"
              "property float x\nproperty float y\nproperty float z\n"
              "element tristrips 1\nproperty int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n4\n",
              GLINT_E_PARSE,
              "stripnone.ply:8: the triangle strip's 'vertex_indices' must be "
              "a list of integers",
              NULL);
  /* A binary file's strip is named as a strip, by its number from 0 (it
   * was "face 1", in a file with no faces). */
  static const char strip_head[] =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\n"
      "element tristrips 2\nproperty list uchar int vertex_indices\n"
      "end_header\n";
  unsigned char bin[sizeof strip_head - 1 + 4 * 12 + 2 * 13];
  size_t nb = sizeof strip_head - 1;
  memcpy(bin, strip_head, nb);
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1e30f}};
  memcpy(bin + nb, xyz, sizeof xyz); /* (x86: little-endian floats) */
  nb += sizeof xyz;
  const int32_t strips[2][3] = {{0, 1, 2}, {1, 2, 3}};
  for (int k = 0; k < 2; k++) {
    bin[nb++] = 3;
    memcpy(bin + nb, strips[k], sizeof strips[k]);
    nb += sizeof strips[k];
  }
  expect_fail_path(
      write_bytes(f, "farstrip.ply", bin, nb), GLINT_E_ARGUMENT,
      "farstrip.ply: triangle strip 1: vertex 3, scaled by 1: ", NULL);
  /* strips of restarts alone: no triangle, and no empty face element to
   * blame (it said "the face element is empty") */
  expect_fail(f, "restarts.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\n"
              "property float x\nproperty float y\nproperty float z\n"
              "element tristrips 1\nproperty list int int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n4 -1 -1 -1 -1\n",
              GLINT_E_PARSE,
              "restarts.ply: no faces (its faces and strips make no triangle)",
              NULL);
}

/* A binary PLY body under construction, in either byte order. */
typedef struct bin {
  unsigned char b[8192];
  size_t n;
  int big;
} bin;

static void put_text(bin *b, const char *s) {
  size_t n = strlen(s);
  assert_true(b->n + n <= sizeof b->b);
  memcpy(b->b + b->n, s, n);
  b->n += n;
}

static void put_uint(bin *b, uint64_t v, int size) {
  assert_true(b->n + (size_t)size <= sizeof b->b);
  for (int i = 0; i < size; i++) {
    int shift = 8 * (b->big ? size - 1 - i : i);
    b->b[b->n++] = (unsigned char)(v >> shift);
  }
}

static void put_f32(bin *b, float v) {
  uint32_t u;
  memcpy(&u, &v, 4);
  put_uint(b, u, 4);
}

static void put_f64(bin *b, double v) {
  uint64_t u;
  memcpy(&u, &v, 8);
  put_uint(b, u, 8);
}

/* A square and a triangle with normals, extra properties of every width
 * and an extra element. `vertices` and `faces` are the counts the header
 * declares; the body always holds 5 and 2. */
static void make_binary_ply(bin *b, int big, int vertices, int faces) {
  memset(b, 0, sizeof *b);
  b->big = big;
  char head[1024];
  snprintf(head, sizeof head,
           "ply\n"
           "format %s 1.0\n"
           "comment binary test\n"
           "element vertex %d\n"
           "property double x\n"
           "property int16 confidence\n"
           "property float32 y\n"
           "property float z\n"
           "property float nx\n"
           "property float ny\n"
           "property float nz\n"
           "property uint8 intensity\n"
           "property list uchar double extra\n"
           "element face %d\n"
           "property list uint8 uint32 vertex_index\n"
           "property ushort flags\n"
           "element range_grid 2\n"
           "property int row\n"
           "property char what\n"
           "end_header\n",
           big ? "binary_big_endian" : "binary_little_endian", vertices, faces);
  put_text(b, head);
  static const double pos[5][3] = {
      {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 2, -1.25}};
  for (int i = 0; i < 5; i++) {
    put_f64(b, pos[i][0]);
    put_uint(b, (uint16_t)-3, 2);
    put_f32(b, (float)pos[i][1]);
    put_f32(b, (float)pos[i][2]);
    put_f32(b, 0);
    put_f32(b, 0);
    put_f32(b, (float)(i + 1)); /* normal (0, 0, i+1) */
    put_uint(b, 200, 1);
    put_uint(b, (uint64_t)i, 1); /* a list of i doubles */
    for (int k = 0; k < i; k++)
      put_f64(b, k);
  }
  put_uint(b, 4, 1);
  for (uint32_t v = 0; v < 4; v++)
    put_uint(b, v, 4);
  put_uint(b, 0xbeef, 2);
  put_uint(b, 3, 1);
  put_uint(b, 0, 4);
  put_uint(b, 1, 4);
  put_uint(b, 4, 4);
  put_uint(b, 0, 2);
  for (int i = 0; i < 2; i++) {
    put_uint(b, 7, 4);
    put_uint(b, 1, 1);
  }
}

static void check_binary_scene(const glint_scene *s) {
  assert_int_equal(s->triangle_count, 3);
  assert_tri(s, 0, (V){0, 0, 0}, (V){1, 0, 0}, (V){1, 1, 0});
  assert_tri(s, 1, (V){0, 0, 0}, (V){1, 1, 0}, (V){0, 1, 0});
  assert_tri(s, 2, (V){0, 0, 0}, (V){1, 0, 0}, (V){0.5, 2, -1.25});
  /* Vertex normals: smooth shading, normalised. */
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++)
      assert_vec(normal_of(s, (size_t)i, k), 0, 0, 1);
}

static void ply_binary_both_byte_orders(void **state) {
  fixture *f = *state;
  bin b;
  make_binary_ply(&b, 0, 5, 2);
  glint_scene *s = load(write_bytes(f, "le.ply", b.b, b.n), 1, (V){0, 0, 0});
  check_binary_scene(s);
  glint_scene_destroy(s);
  make_binary_ply(&b, 1, 5, 2);
  s = load(write_bytes(f, "be.ply", b.b, b.n), 1, (V){0, 0, 0});
  check_binary_scene(s);
  glint_scene_destroy(s);
  /* Line breaks and blanks after the last element of a binary file are
   * ignored (more data: ply_binary_errors). */
  put_text(&b, "\n\n");
  s = load(write_bytes(f, "be_padded.ply", b.b, b.n), 1, (V){0, 0, 0});
  check_binary_scene(s);
  glint_scene_destroy(s);
}

static void ply_binary_errors(void **state) {
  fixture *f = *state;
  bin b;
  make_binary_ply(&b, 0, 5, 2);
  /* Offsets: each vertex is 32 bytes and a list of i doubles. */
  const char *end = strstr((const char *)b.b, "end_header\n");
  size_t body = (size_t)(end - (const char *)b.b) + 11;
  size_t vertex3 = body + 3 * 32 + 8 * (0 + 1 + 2);
  size_t first_face = body + 5 * 32 + 8 * (0 + 1 + 2 + 3 + 4);
  /* Files cut short: between vertices, inside a vertex, between faces,
   * inside a face. */
  expect_fail_path(write_bytes(f, "cut_v.ply", b.b, vertex3), GLINT_E_PARSE,
                   "cut_v.ply: the file ends after 3 of 5 vertices", NULL);
  expect_fail_path(write_bytes(f, "cut_v2.ply", b.b, vertex3 + 13),
                   GLINT_E_PARSE, "the file ends after 3 of 5 vertices", NULL);
  expect_fail_path(write_bytes(f, "cut_f.ply", b.b, first_face + 19),
                   GLINT_E_PARSE, "the file ends after 1 of 2 faces", NULL);
  expect_fail_path(write_bytes(f, "cut_f2.ply", b.b, first_face + 7),
                   GLINT_E_PARSE, "the file ends after 0 of 2 faces", NULL);
  expect_fail_path(write_bytes(f, "cut_grid.ply", b.b, b.n - 1), GLINT_E_PARSE,
                   "the file ends after 1 of 2 'range_grid'", NULL);
  /* A face index out of range, and a list count that is garbage. */
  make_binary_ply(&b, 0, 5, 2);
  b.b[first_face + 1 + 4 * 2] = 9;
  expect_fail_path(write_bytes(f, "range.ply", b.b, b.n), GLINT_E_PARSE,
                   "face 0: face refers to vertex 9, but only 5 are defined",
                   NULL);
  make_binary_ply(&b, 0, 5, 2);
  b.b[first_face] = 2;
  expect_fail_path(write_bytes(f, "two.ply", b.b, b.n), GLINT_E_PARSE,
                   "face 0: a face needs at least 3 vertices, found 2", NULL);
  /* A NaN and an infinity in a vertex. */
  make_binary_ply(&b, 0, 5, 2);
  size_t y1 = body + 32 + 8 + 2; /* vertex 1's y */
  memcpy(b.b + y1, "\x00\x00\xc0\x7f", 4);
  expect_fail_path(write_bytes(f, "nan.ply", b.b, b.n), GLINT_E_PARSE,
                   "vertex 1: the vertex's y is nan, not a finite number",
                   "(and face 0 uses it)");
  make_binary_ply(&b, 1, 5, 2); /* a shorter format line */
  y1 = (size_t)(strstr((const char *)b.b, "end_header\n") - (const char *)b.b) +
       11 + 32 + 8 + 2;
  memcpy(b.b + y1, "\x7f\x80\x00\x00", 4);
  expect_fail_path(write_bytes(f, "inf.ply", b.b, b.n), GLINT_E_PARSE,
                   "vertex 1: the vertex's y is inf, not a finite number",
                   NULL);
  /* Data after the last element: counts too small, data lost (it was
   * ignored), even where it is zeros. */
  make_binary_ply(&b, 0, 5, 2);
  put_text(&b, "\n");
  put_uint(&b, 0, 8);
  put_uint(&b, 0, 4);
  expect_fail_path(write_bytes(f, "more.ply", b.b, b.n), GLINT_E_PARSE,
                   "more.ply: 13 bytes after the last element (the header's "
                   "counts are too small)",
                   NULL);
}

/* A face list whose count is absurd must be refused, not allocated. */
static void ply_absurd_list_counts(void **state) {
  fixture *f = *state;
  bin b;
  memset(&b, 0, sizeof b);
  put_text(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
               "property float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uint int vertex_indices\n"
               "end_header\n");
  for (int i = 0; i < 9; i++)
    put_f32(&b, (float)(i % 4 == 0));
  put_uint(&b, 4000000000u, 4);
  put_uint(&b, 0, 4);
  expect_fail_path(write_bytes(f, "absurd.ply", b.b, b.n), GLINT_E_PARSE,
                   "face 0: a face with 4000000000 vertices", NULL);
  /* A large count that is not absurd, but more than the file holds. */
  b.n -= 8;
  put_uint(&b, 100000, 4);
  put_uint(&b, 0, 4);
  expect_fail_path(write_bytes(f, "long.ply", b.b, b.n), GLINT_E_PARSE,
                   "the file ends after 0 of 1 faces", NULL);
  /* A negative count. */
  memset(&b, 0, sizeof b);
  put_text(&b, "ply\nformat binary_big_endian 1.0\nelement vertex 1\n"
               "property float x\nproperty float y\nproperty float z\n"
               "property list char int junk\n"
               "element face 0\nproperty list uchar int vertex_indices\n"
               "end_header\n");
  put_f32(&b, 0);
  put_f32(&b, 0);
  put_f32(&b, 0);
  put_uint(&b, 0xff, 1);
  expect_fail_path(write_bytes(f, "negative.ply", b.b, b.n), GLINT_E_PARSE,
                   "vertex 0: the count of the vertex's list 'junk' is -1",
                   NULL);
  /* ASCII: a huge count ends at the end of the line. */
  expect_fail(f, "absurd_ascii.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
              "property float y\nproperty float z\nelement face 1\n"
              "property list uint int vertex_indices\nend_header\n"
              "0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n",
              GLINT_E_PARSE, "absurd_ascii.ply:13: a face with 4000000000",
              NULL);
  expect_fail(f, "long_ascii.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
              "property float y\nproperty float z\n"
              "property list uint int junk\nelement face 1\n"
              "property list uint int vertex_indices\nend_header\n"
              "0 0 0 0\n1 0 0 4000000000 1 2\n0 1 0 0\n3 0 1 2\n",
              GLINT_E_PARSE,
              "long_ascii.ply:12: expected a number for the vertex's 'junk', "
              "found the end of the line",
              NULL);
  /* ASCII: a count or an index beyond the type the header gives it. */
  expect_fail(f, "uchar_ascii.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
              "property float y\nproperty float z\nelement face 1\n"
              "property list uchar int vertex_indices\nend_header\n"
              "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n",
              GLINT_E_PARSE,
              "uchar_ascii.ply:13: the count of the face's list "
              "'vertex_indices' is 300, outside the uchar type",
              NULL);
  expect_fail(f, "uint_ascii.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
              "property float y\nproperty float z\nelement face 1\n"
              "property list uchar uint vertex_indices\nend_header\n"
              "0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n",
              GLINT_E_PARSE,
              "uint_ascii.ply:13: a face's vertex index is -2, outside the "
              "uint type",
              NULL);
  /* ASCII: a coordinate the header calls an integer is one (300 and 0.5
   * in a char were taken as they were written). */
  expect_fail(f, "char_x.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty char x\n"
              "property uchar y\nproperty uchar z\nelement face 1\n"
              "property list uchar int vertex_indices\nend_header\n"
              "300 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
              GLINT_E_PARSE,
              "char_x.ply:10: the vertex's x is 300, outside the char type",
              NULL);
  expect_fail(f, "half_x.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty short x\n"
              "property float y\nproperty float z\nelement face 1\n"
              "property list uchar int vertex_indices\nend_header\n"
              "0 0 0\n0.5 0 0\n0 1 0\n3 0 1 2\n",
              GLINT_E_PARSE,
              "half_x.ply:11: expected a whole number for the vertex's x, "
              "found '0.5'",
              NULL);
}

/* An ASCII PLY with one thing wrong, built from the good header. */
#define PLY_HEAD                                                               \
  "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"                \
  "property float y\nproperty float z\nelement face 2\n"                       \
  "property list uchar int vertex_indices\nend_header\n"

static void ply_ascii_errors(void **state) {
  fixture *f = *state;
  /* Lines: the header takes 1-9, the vertices 10-13, the faces 14-15. */
  expect_fail(f, "ok.ply",
              PLY_HEAD "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n"
                       "3 0 2 x\n",
              GLINT_E_PARSE,
              "ok.ply:15: expected a whole number for a face's vertex index, "
              "found 'x'",
              NULL);
  expect_fail(f, "number.ply", PLY_HEAD "0 0 0\n1 0 0\n1 abc 0\n",
              GLINT_E_PARSE,
              "number.ply:12: expected a number for the vertex's y, found "
              "'abc'",
              NULL);
  expect_fail(f, "nan.ply",
              PLY_HEAD "0 0 0\n1 0 nan\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",
              GLINT_E_PARSE,
              "nan.ply:11: the vertex's z is 'nan', not a finite number (and "
              "the face on line 14 uses it)",
              NULL);
  /* the first such vertex unused, a later one used: numbered as the faces
   * number it, from 0 (it was "vertex 4", from 1, and "triangle 1") */
  expect_fail(
      f, "nan3.ply",
      PLY_HEAD "0 0 0\nnan 0 0\n1 1 0\n0 inf 0\n3 0 2 3\n3 0 1 2\n",
      GLINT_E_PARSE,
      "nan3.ply:14: the face uses vertex 3, which is not a finite point", NULL);
  expect_fail(
      f, "nan-normal.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nproperty float nx\n"
      "property float ny\nproperty float nz\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 nan 1\n3 0 1 2\n",
      GLINT_E_PARSE,
      "nan-normal.ply:15: the vertex's ny is 'nan', not a finite number "
      "(and the face on line 16 uses it)",
      NULL);
  expect_fail(f, "trunc.ply", PLY_HEAD "0 0 0\n1 0 0\n", GLINT_E_PARSE,
              "the file ends after 2 of 4 vertices", NULL);
  expect_fail(f, "trunc_line.ply", PLY_HEAD "0 0 0\n1 0 0\n1 1 0\n0 1",
              GLINT_E_PARSE, "the file ends after 3 of 4 vertices", NULL);
  expect_fail(f, "trunc_faces.ply",
              PLY_HEAD "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                       "3 0 1 2\n",
              GLINT_E_PARSE, "the file ends after 1 of 2 faces", NULL);
  expect_fail(f, "short_line.ply", PLY_HEAD "0 0 0\n1 0\n1 1 0\n0 1 0\n",
              GLINT_E_PARSE,
              "short_line.ply:11: expected a number for the vertex's z, "
              "found the end of the line",
              NULL);
  expect_fail(f, "extra.ply", PLY_HEAD "0 0 0\n1 0 0 5\n", GLINT_E_PARSE,
              "extra.ply:11: unexpected '5' after the 3 properties of the "
              "vertex",
              NULL);
  expect_fail(f, "range.ply",
              PLY_HEAD "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n"
                       "3 0 2 900\n",
              GLINT_E_PARSE,
              "range.ply:15: face refers to vertex 900, but only 4 are "
              "defined",
              NULL);
  expect_fail(f, "negidx.ply",
              PLY_HEAD "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                       "3 0 1 -1\n3 0 1 2\n",
              GLINT_E_PARSE, "negidx.ply:14: face refers to vertex -1", NULL);
  expect_fail(f, "twoverts.ply",
              PLY_HEAD "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                       "3 0 1 2\n2 0 1\n",
              GLINT_E_PARSE,
              "twoverts.ply:15: a face needs at least 3 vertices, found 2",
              NULL);
  expect_fail(f, "toomuch.ply",
              PLY_HEAD "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                       "3 0 1 2\n3 0 2 3\n3 1 2 3\n",
              GLINT_E_PARSE, "toomuch.ply:16: unexpected '3' after the last",
              NULL);
}

static void ply_header_errors(void **state) {
  fixture *f = *state;
  expect_fail(f, "magic.ply", "plx\nformat ascii 1.0\n", GLINT_E_PARSE,
              "magic.ply:1: not a PLY file", NULL);
  expect_fail(
      f, "format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n",
      GLINT_E_PARSE,
      "format.ply:2: unsupported PLY format 'binary_middle_endian'", NULL);
  expect_fail(f, "version.ply", "ply\nformat ascii 2.0\nend_header\n",
              GLINT_E_PARSE, "version.ply:2: unsupported PLY version '2.0'",
              NULL);
  /* a second format replaced the first, and the body was read as it */
  expect_fail(f, "formats.ply",
              "ply\nformat ascii 1.0\ncomment x\n"
              "format binary_little_endian 1.0\nend_header\n",
              GLINT_E_PARSE,
              "formats.ply:4: a second format line (the first is on line 2)",
              NULL);
  expect_fail(f, "type.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\n"
              "property int64 x\nend_header\n",
              GLINT_E_PARSE, "type.ply:4: unsupported property type 'int64'",
              NULL);
  expect_fail(f, "listtype.ply",
              "ply\nformat ascii 1.0\nelement face 1\n"
              "property list float int vertex_indices\nend_header\n",
              GLINT_E_PARSE,
              "listtype.ply:4: the count of the list 'vertex_indices' must "
              "have an integer type",
              NULL);
  expect_fail(f, "floatidx.ply",
              "ply\nformat ascii 1.0\nelement face 1\n"
              "property list uchar float vertex_indices\nend_header\n",
              GLINT_E_PARSE, "floatidx.ply:4: the face's 'vertex_indices' must",
              NULL);
  expect_fail(f, "keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 1\n",
              GLINT_E_PARSE, "keyword.ply:3: unknown header keyword 'elemnt'",
              NULL);
  expect_fail(f, "noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n",
              GLINT_E_PARSE, "noend.ply:3: the file ends inside the header",
              NULL);
  expect_fail(f, "orphan.ply", "ply\nformat ascii 1.0\nproperty float x\n",
              GLINT_E_PARSE, "orphan.ply:3: 'property' before any 'element'",
              NULL);
  expect_fail(f, "count.ply", "ply\nformat ascii 1.0\nelement vertex -4\n",
              GLINT_E_PARSE, "count.ply:3: expected a count of vertex", NULL);
  expect_fail(
      f, "hugecount.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\n",
      GLINT_E_PARSE, "hugecount.ply:3: 99999999999 vertices are too", NULL);
  expect_fail(f, "noformat.ply", "ply\nend_header\n", GLINT_E_PARSE,
              "no 'format' line", NULL);
  expect_fail(f, "noz.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
              "property float y\nelement face 0\n"
              "property list uchar int vertex_indices\nend_header\n0 0\n",
              GLINT_E_PARSE, "the vertex element has no 'z' property", NULL);
  expect_fail(f, "noface.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
              "property float y\nproperty float z\nend_header\n0 0 0\n",
              GLINT_E_PARSE, "no 'face' element", NULL);
  expect_fail(f, "nolist.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
              "property float y\nproperty float z\nelement face 0\n"
              "property list uchar int corners\nend_header\n0 0 0\n",
              GLINT_E_PARSE, "no 'vertex_indices' list", NULL);
  expect_fail(f, "nofaces.ply", PLY_HEAD "0 0 0\n1 0 0\n1 1 0\n0 1 0\n",
              GLINT_E_PARSE, "the file ends after 0 of 2 faces", NULL);
  expect_fail(f, "zero.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
              "property float y\nproperty float z\nelement face 0\n"
              "property list uchar int vertex_indices\nend_header\n0 0 0\n",
              GLINT_E_PARSE, "zero.ply: no faces", NULL);
  expect_fail(f, "twice.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
              "property float x\n",
              GLINT_E_PARSE, "twice.ply:5: a second 'x' property", NULL);
  expect_fail(f, "binhead.ply", "ply\nformat ascii 1.0\ncomm\001\000nt\n",
              GLINT_E_PARSE, "binhead.ply:3: unknown header keyword 'comm?'",
              NULL);
}

/* ------------------------------------------------------------------------ */
/* OBJ errors and files of every kind of wrong                              */
/* ------------------------------------------------------------------------ */

static void obj_errors(void **state) {
  fixture *f = *state;
  /* The number on line 12. */
  expect_fail(f, "number.obj",
              "# 1\n# 2\n# 3\n# 4\n# 5\n# 6\n# 7\n# 8\n# 9\n# 10\n"
              "v 0 0 0\nv 1 abc 0\n",
              GLINT_E_PARSE,
              "number.obj:12: expected a number for the vertex's y, found "
              "'abc'",
              NULL);
  expect_fail(
      f, "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", GLINT_E_PARSE,
      "nan.obj:2: the vertex's x is 'nan', not a finite number (and the "
      "face on line 4 uses it)",
      NULL);
  /* the first such vertex unused, a later one used: named by number, at
   * the face's line (it was "triangle N", counted after faces were cut) */
  expect_fail(
      f, "nan2.obj", "v nan 0 0\nv 0 0 0\nv 1 0 0\nv 0 inf 0\nf 2 3 4\n",
      GLINT_E_PARSE,
      "nan2.obj:5: the face uses vertex 4, which is not a finite point", NULL);
  expect_fail(
      f, "inf.obj", "v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", GLINT_E_PARSE,
      "inf.obj:1: the vertex's z is '1e999', not a finite number", NULL);
  /* A normal too, where a face uses it (it was read as zero, and the face
   * shaded flat there); unused: nonfinite_vertices_no_face_uses. */
  expect_fail(f, "vn-nan.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 nan\n"
              "f 1//1 2//2 3//1\n",
              GLINT_E_PARSE,
              "vn-nan.obj:5: the normal's z is 'nan', not a finite number "
              "(and the face on line 6 uses it)",
              NULL);
  expect_fail(f, "vn-nan2.obj",
              "vn inf 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 nan 0\n"
              "f 1//2 2//3 3//2\n",
              GLINT_E_PARSE,
              "vn-nan2.obj:7: the face uses normal 3, which is not a finite "
              "direction",
              NULL);
  expect_fail(f, "vn.obj", "vn 0 x 0\n", GLINT_E_PARSE,
              "vn.obj:1: expected a number for the normal's y, found 'x'",
              NULL);
  expect_fail(f, "short.obj", "v 0 0\n", GLINT_E_PARSE,
              "short.obj:1: expected a number for the vertex's z, found the "
              "end of the line",
              NULL);
  /* a continuation on the last line: the face is line 4's */
  expect_fail(f, "cont.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n",
              GLINT_E_PARSE, "cont.obj:4: ", NULL);
  /* ... and as the file's very last byte: the face is short, not '\' */
  expect_fail(
      f, "cont-end.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\", GLINT_E_PARSE,
      "cont-end.obj:4: a face needs at least 3 vertices, found 2", NULL);
  expect_fail(f, "long.obj", "v 0 0 0 1 1 1 1 1\n", GLINT_E_PARSE,
              "long.obj:1: unexpected '1' after the vertex's coordinates",
              NULL);
  expect_fail(f, "keyword.obj", "v 0 0 0\n\nxyz 1 2\n", GLINT_E_PARSE,
              "keyword.obj:3: unknown keyword 'xyz'", NULL);
  expect_fail(f, "two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", GLINT_E_PARSE,
              "two.obj:3: a face needs at least 3 vertices, found 2", NULL);
  expect_fail(f, "none.obj", "v 0 0 0\nf\n", GLINT_E_PARSE,
              "none.obj:2: a face needs at least 3 vertices, found 0", NULL);
  expect_fail(f, "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 900\n",
              GLINT_E_PARSE,
              "range.obj:4: face refers to vertex 900, but only 3 are "
              "defined",
              NULL);
  expect_fail(
      f, "later.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", GLINT_E_PARSE,
      "later.obj:3: face refers to vertex 3, but only 2 are defined", NULL);
  expect_fail(f, "negrange.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
              GLINT_E_PARSE,
              "negrange.obj:4: face refers to vertex -4 (counting back from "
              "the last), but only 3 are defined",
              NULL);
  expect_fail(f, "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
              GLINT_E_PARSE, "zero.obj:4: face refers to vertex 0", NULL);
  expect_fail(f, "normal.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n"
              "f 1//1 2//1 3//2\n",
              GLINT_E_PARSE,
              "normal.obj:5: face refers to normal 2, but only 1 is defined",
              NULL);
  expect_fail(f, "tex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n",
              GLINT_E_PARSE,
              "tex.obj:4: face refers to texture coordinate 1, but only 0 "
              "are defined",
              NULL);
  static const char *const bad[] = {"1/",  "1/2/", "1//", "a",    "1/2/3/4",
                                    "1.5", "1 /2", "/1",  "+-1",  "1x",
                                    "//1", "1/a",  "",    "1//2x"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    char text[128], name[32];
    snprintf(text, sizeof text,
             "v 0 0 0\nvt 0 0\nvn 0 0 1\nv 1 0 0\nv 0 1 0\nf 1 2 %s\n", bad[i]);
    snprintf(name, sizeof name, "corner%zu.obj", i);
    /* Each is either a malformed corner or leaves a face of 2 corners. */
    expect_fail(f, name, text, GLINT_E_PARSE, ":6: ", NULL);
  }
  expect_fail(f, "corner.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/\n",
              GLINT_E_PARSE,
              "corner.obj:4: bad face vertex '3/' (expected i, i/t, i//n or "
              "i/t/n)",
              NULL);
  expect_fail(f, "bigindex.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n",
              GLINT_E_PARSE,
              "bigindex.obj:4: face vertex '99999999999999999999999': an "
              "index of more than 18 digits, beyond any list",
              NULL);
  expect_fail(f, "nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", GLINT_E_PARSE,
              "nofaces.obj: no faces", NULL);
  expect_fail(f, "comments.obj", "# nothing\n\n", GLINT_E_PARSE,
              "comments.obj: no faces", NULL);
  /* A long garbage keyword is cut short in the message. */
  expect_fail(f, "longkw.obj",
              "abcdefghijklmnopqrstuvwxyzabcdefghijklmnopqrstuvwxyz 1\n",
              GLINT_E_PARSE, "longkw.obj:1: unknown keyword 'abcdefghij",
              "...'");
}

static void files_of_every_kind_of_wrong(void **state) {
  fixture *f = *state;
  /* Missing, a folder, empty. */
  char missing[300];
  snprintf(missing, sizeof missing, "%s/missing.obj", f->dir);
  expect_fail_path(missing, GLINT_E_IO, "No such file", NULL);
  char folder[300];
  snprintf(folder, sizeof folder, "%s/folder.ply", f->dir);
  assert_int_equal(mkdir(folder, 0700), 0);
  expect_fail_path(folder, GLINT_E_IO, "not a regular file", NULL);
  rmdir(folder);
  expect_fail(f, "empty.obj", "", GLINT_E_PARSE, "empty.obj: the file is empty",
              NULL);
  expect_fail(f, "empty.ply", "", GLINT_E_PARSE, "empty.ply: the file is empty",
              NULL);
  expect_fail_path(write_gz(f, "empty.obj.gz", ""), GLINT_E_PARSE,
                   "the file is empty", NULL);
  /* Binary garbage, with NUL bytes. */
  unsigned char junk[4096];
  uint32_t x = 12345;
  for (size_t i = 0; i < sizeof junk; i++) {
    x = x * 1103515245u + 12345u;
    junk[i] = (unsigned char)(x >> 16);
  }
  junk[0] = 'v'; /* so that the first line is plausible */
  junk[1] = ' ';
  junk[100] = '\0';
  expect_fail_path(write_bytes(f, "junk.obj", junk, sizeof junk), GLINT_E_PARSE,
                   "junk.obj:", "binary data");
  expect_fail_path(write_bytes(f, "junk.ply", junk, sizeof junk), GLINT_E_PARSE,
                   "junk.ply:1: not a PLY file", NULL);
  /* Text garbage. */
  expect_fail(f, "text.obj", "hello world\n", GLINT_E_PARSE,
              "text.obj:1: unknown keyword 'hello'", NULL);
  /* A binary PLY header with a NUL in it. */
  static const char nul_head[] = "ply\nformat binary_little_endian 1.0\n"
                                 "element vertex 1\0\n";
  expect_fail_path(
      write_bytes(f, "nulhead.ply", nul_head, sizeof nul_head - 1),
      GLINT_E_PARSE,
      "nulhead.ply:3:17: a NUL byte: binary data where text was expected",
      NULL);
  /* Not a mesh extension. */
  expect_fail(f, "mesh.stl", "solid\n", GLINT_E_ARGUMENT, "not a mesh file",
              NULL);
}

static void gzip_damage_is_an_error(void **state) {
  fixture *f = *state;
  /* Big enough that a cut in the middle leaves whole lines before it. */
  size_t cap = 400000, n = 0;
  char *text = malloc(cap);
  assert_non_null(text);
  for (int i = 0; n + 64 < cap; i++)
    n += (size_t)snprintf(text + n, cap - n, "v %d.%d 1.%d 2\n", i, i * 7 % 13,
                          i % 977);
  n += (size_t)snprintf(text + n, cap - n, "f 1 2 3\n");
  const char *path = write_gz(f, "whole.obj.gz", text);
  free(text);
  glint_scene *s = load(path, 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, 1);
  glint_scene_destroy(s);

  FILE *fp = fopen(path, "rb");
  assert_non_null(fp);
  unsigned char *gz = malloc(cap);
  assert_non_null(gz);
  size_t size = fread(gz, 1, cap, fp);
  fclose(fp);
  assert_true(size > 1000 && size < cap);
  /* Cut in the middle, cut before the trailer, cut inside the header. */
  expect_fail_path(write_bytes(f, "half.obj.gz", gz, size / 2), GLINT_E_PARSE,
                   "half.obj.gz: the compressed file is truncated", NULL);
  expect_fail_path(write_bytes(f, "notrailer.obj.gz", gz, size - 8),
                   GLINT_E_PARSE, "the compressed file is truncated", NULL);
  expect_fail_path(write_bytes(f, "head.obj.gz", gz, 6), GLINT_E_PARSE,
                   "head.obj.gz", NULL);
  /* A wrong checksum, and damaged data. */
  gz[size - 8] ^= 0x55;
  expect_fail_path(write_bytes(f, "crc.obj.gz", gz, size), GLINT_E_PARSE,
                   "crc.obj.gz: damaged compressed file", NULL);
  gz[size - 8] ^= 0x55;
  /* Members may follow each other (gzip concatenates them), but anything
   * else after the last is refused: zlib's gzread ignores it silently. */
  unsigned char *twice = malloc(2 * size + 16);
  assert_non_null(twice);
  memcpy(twice, gz, size);
  memcpy(twice + size, gz, size);
  s = load(write_bytes(f, "twice.obj.gz", twice, 2 * size), 1, (V){0, 0, 0});
  assert_int_equal(s->triangle_count, 2);
  glint_scene_destroy(s);
  memcpy(twice + size, "garbage!!!", 10);
  expect_fail_path(
      write_bytes(f, "tail.obj.gz", twice, size + 10), GLINT_E_PARSE,
      "tail.obj.gz: data after the end of the compressed stream", NULL);
  /* ...even when the file's last four bytes are the unpacked length, as
   * a single member's are (such a file was trusted unchecked: what
   * followed the garbage was lost) */
  memcpy(twice + size + 10, gz + size - 4, 4);
  expect_fail_path(
      write_bytes(f, "tail3.obj.gz", twice, size + 14), GLINT_E_PARSE,
      "tail3.obj.gz: data after the end of the compressed stream", NULL);
  memcpy(twice + size, gz, size);
  twice[2 * size] = 0x1f; /* half a member's magic */
  expect_fail_path(write_bytes(f, "tail2.obj.gz", twice, 2 * size + 1),
                   GLINT_E_PARSE, "data after the end of the compressed stream",
                   NULL);
  free(twice);
  for (size_t i = size / 3; i < size / 3 + 40; i++)
    gz[i] ^= 0xa5;
  expect_fail_path(write_bytes(f, "damaged.obj.gz", gz, size), GLINT_E_PARSE,
                   "damaged.obj.gz: damaged compressed file", NULL);
  free(gz);

  /* 24 MiB of one vertex line in some 100 kilobytes: refused once it
   * unpacks past 16 MiB and 32 times its size, not held whole (up to
   * 4 GiB) for the parser, nor made 3 million vertices (a gigabyte of one
   * sphere repeated in NFF took gigabytes and minutes). */
  const char *bomb = path_of(f, "repeated.obj.gz");
  gzFile out = gzopen(bomb, "wb9");
  assert_non_null(out);
  static const char line[8] = "v 1 2 3\n";
  char *lines = malloc(1 << 20);
  assert_non_null(lines);
  for (size_t i = 0; i < 1 << 20; i += sizeof line)
    memcpy(lines + i, line, sizeof line);
  for (int i = 0; i < 24; i++)
    assert_int_equal(gzwrite(out, lines, 1 << 20), 1 << 20);
  assert_int_equal(gzclose(out), Z_OK);
  free(lines);
  expect_fail_path(bomb, GLINT_E_PARSE,
                   "repeated.obj.gz: unpacks to more than 32 times its "
                   "compressed size",
                   NULL);
  /* The same with a hole after it (a 64 GiB file of some 100 kilobytes):
   * measured against what it unpacked from, not the file's size, it is
   * refused as soon (a 5 MB file so made unpacked 4 GiB of blanks). */
  if (truncate(bomb, (off_t)64 << 30) != 0) {
    printf("a sparse file: SKIPPED (%s)\n", strerror(errno));
    return;
  }
  expect_fail_path(bomb, GLINT_E_PARSE,
                   "repeated.obj.gz: unpacks to more than 32 times its "
                   "compressed size",
                   "of its 68719476736)");
}

/* Points and normals no face uses may be nan (scanners write them so): the
 * mesh loads. Both were refused, however unused. (Where a face uses one,
 * obj_errors and ply_errors.) */
static void nonfinite_vertices_no_face_uses(void **state) {
  fixture *f = *state;
  static const char ply[] =
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\n"
      "property float y\nproperty float z\nproperty float nx\n"
      "property float ny\nproperty float nz\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 -3 0 0 0 1\n3 -3 0 0 0 1\n3 0 0 0 0 1\n0 0 0 0 0 1\n"
      "9 9 9 nan nan nan\n4 0 1 2 3\n";
  static const char obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan nan nan\n"
                            "vn 0 0 1\nvn nan 0 0\nf 1//1 2//1 3//1\n";
  const char *paths[] = {write_text(f, "cloud.ply", ply),
                         write_text(f, "cloud.obj", obj)};
  for (int i = 0; i < 2; i++) {
    uint32_t m;
    glint_scene *s = scene_with_default_material(&m);
    ASSERT_OK(glint_scene_add_mesh_file(s, paths[i], 1, (V){0, 0, 0}, m, &e_));
    assert_int_equal(s->triangle_count, i == 0 ? 2 : 1);
    for (size_t k = 0; k < s->tri_normal_count; k++)
      assert_true(isfinite(s->tri_normals[k].x) &&
                  isfinite(s->tri_normals[k].y) &&
                  isfinite(s->tri_normals[k].z));
    glint_scene_destroy(s);
  }
}

/* A sparse file (no disk used) of `bytes` NUL bytes named `name` is
 * refused with `status` and `message`, unread: taking at most 64 MiB of
 * memory. Skipped where the file system has no such file. */
static void expect_sparse_refused_unread(fixture *f, const char *name,
                                         off_t bytes, glint_status status,
                                         const char *message) {
  const char *path = path_of(f, name);
  int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  assert_true(fd >= 0);
  if (ftruncate(fd, bytes) != 0) {
    close(fd);
    unlink(path);
    print_message("no file of %lld bytes here (%s)\n", (long long)bytes,
                  strerror(errno));
    skip();
  }
  close(fd);
  struct rusage before, after;
  getrusage(RUSAGE_SELF, &before);
  expect_fail_path(path, status, message, NULL);
  getrusage(RUSAGE_SELF, &after);
  unlink(path);
  /* ru_maxrss is in KiB */
  if (after.ru_maxrss - before.ru_maxrss > 64 << 10)
    fail_msg("refusing %s took %ld MiB", name,
             (after.ru_maxrss - before.ru_maxrss) >> 10);
}

/* A plain file past the 4 GiB limit is refused unread: it was read whole,
 * up to the limit, before (4 GiB of memory). */
static void a_file_past_the_limit_is_refused_unread(void **state) {
  expect_sparse_refused_unread(*state, "sparse.obj", ((off_t)4 << 30) + 1,
                               GLINT_E_IO, "sparse.obj: larger than 4 GiB");
}

/* A text file of 1 GiB of NUL bytes, under the limit, is refused at its
 * first line without being read whole (1 GiB of memory, and 18 s for
 * 3 GiB, before); the first NUL of a text file is reported on its line
 * wherever it lies. */
static void a_binary_file_for_a_text_one_is_refused_unread(void **state) {
  fixture *f = *state;
  expect_sparse_refused_unread(f, "zeros.obj", (off_t)1 << 30, GLINT_E_PARSE,
                               "zeros.obj:1:1: a NUL byte");
  const char *path = path_of(f, "zeros.obj");
  /* A NUL past the first read, on line 3. */
  FILE *w = fopen(path, "wb");
  assert_non_null(w);
  fputs("v 0 0 0\nv 1 0 0\n", w);
  for (int i = 0; i < 100000; i++)
    fputc(' ', w);
  fputc('\0', w);
  fclose(w);
  expect_fail_path(path, GLINT_E_PARSE, "zeros.obj:3:100001: a NUL byte", NULL);
  /* UTF-16 (a byte-order mark) is named as such. */
  w = fopen(path, "wb");
  assert_non_null(w);
  fwrite("\xff\xfev\0 \0"
         "1\0",
         1, 8, w);
  fclose(w);
  expect_fail_path(path, GLINT_E_PARSE, "zeros.obj: UTF-16 text", NULL);
  unlink(path);
}

/* ------------------------------------------------------------------------ */
/* Packed scenes (src/scene/pack.c)                                         */
/* ------------------------------------------------------------------------ */

/* A JSON scene with a gzip mesh used twice and a PLY, packed: the block
 * loads the same scene with the files gone, and every damaged block is an
 * error (never a read outside it). */
static void packed_scene_needs_no_files(void **state) {
  fixture *f = *state;
  const char *quad = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
  const char *obj = write_gz(f, "packed_quad.obj.gz", quad);
  const char *ply = write_text(f, "packed_tri.ply", ply_ascii_text);
  const char *json = write_text(
      f, "packed.json",
      "{\"materials\": {\"m\": {}}, \"objects\": ["
      "{\"type\": \"mesh\", \"file\": \"packed_quad.obj.gz\", "
      "\"material\": \"m\"},"
      "{\"type\": \"mesh\", \"file\": \"packed_quad.obj.gz\", \"translate\": "
      "[0, 0, 3], \"material\": \"m\"},"
      "{\"type\": \"mesh\", \"file\": \"packed_tri.ply\", \"scale\": 2, "
      "\"material\": \"m\"}]}");
  glint_scene *direct;
  ASSERT_OK(glint_scene_load(json, &direct, &e_));
  void *block;
  size_t size;
  ASSERT_OK(glint_scene_pack(json, &block, &size, &e_));
  /* The files, each once: the scene, the OBJ decompressed, the PLY. */
  assert_true(size < 200 + strlen(quad) + sizeof ply_ascii_text +
                         strlen(json) * 3 + 400);
  char moved[3][400];
  const char *paths[3] = {json, obj, ply};
  for (int i = 0; i < 3; i++) {
    snprintf(moved[i], sizeof moved[i], "%s.away", paths[i]);
    assert_int_equal(rename(paths[i], moved[i]), 0);
  }
  glint_scene *packed;
  ASSERT_OK(glint_scene_load_packed(block, size, &packed, &e_));
  assert_int_equal(packed->triangle_count, direct->triangle_count);
  assert_int_equal(packed->object_count, direct->object_count);
  assert_int_equal(packed->triangle_count, 2 + 2 + 3);
  for (size_t i = 0; i < direct->triangle_count; i++)
    assert_memory_equal(&packed->triangles[i], &direct->triangles[i],
                        sizeof direct->triangles[i]);
  glint_scene_destroy(packed);
  /* Every truncation, and a changed byte in each header field, in the
   * scene file's name and in a file's text: damaged, GLINT_E_PARSE as
   * glint.h says (a changed name was GLINT_E_ARGUMENT, "not a scene file";
   * a changed digit in a file loaded as another scene) */
  for (size_t n = 0; n < size; n++) {
    glint_error e;
    glint_scene *s = NULL;
    assert_int_equal(glint_scene_load_packed(block, n, &s, &e), GLINT_E_PARSE);
    assert_null(s);
  }
  unsigned char *bytes = block;
  const size_t fields[] = {0, 8, 12, 16, 18, size / 2, size - 5, size - 1};
  for (size_t i = 0; i < sizeof fields / sizeof *fields; i++) {
    unsigned char saved = bytes[fields[i]];
    bytes[fields[i]] ^= 0x40;
    glint_error e;
    glint_scene *s = NULL;
    glint_status st = glint_scene_load_packed(block, size, &s, &e);
    assert_int_equal(st, GLINT_E_PARSE);
    assert_non_null(strstr(e.message, "packed scene: damaged"));
    if (i > 0) /* past the magic, the checksum finds it */
      assert_non_null(strstr(e.message, "checksum"));
    bytes[fields[i]] = saved;
  }
  glint_free(block);
  for (int i = 0; i < 3; i++)
    assert_int_equal(rename(moved[i], paths[i]), 0);
  glint_scene_destroy(direct);
  /* A file that cannot be read is the error glint_scene_load gives. */
  const char *missing = write_text(
      f, "packed_missing.json",
      "{\"materials\": {\"m\": {}}, \"objects\": [{\"type\": \"mesh\", "
      "\"file\": \"nowhere.obj\", \"material\": \"m\"}]}");
  glint_error e;
  assert_int_equal(glint_scene_pack(missing, &block, &size, &e), GLINT_E_IO);
  assert_non_null(strstr(e.message, "nowhere.obj"));
}

static void bad_arguments(void **state) {
  fixture *f = *state;
  const char *p = write_text(f, "arg.obj",
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                             "v 1e14 0 0\nf 1 2 3\nf 1 2 4\n");
  uint32_t m;
  glint_scene *s = scene_with_default_material(&m);
  glint_error e;
  assert_int_equal(glint_scene_add_mesh_file(s, p, 0, (V){0, 0, 0}, m, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "scale"));
  assert_int_equal(glint_scene_add_mesh_file(s, p, -1, (V){0, 0, 0}, m, &e),
                   GLINT_E_ARGUMENT);
  assert_int_equal(glint_scene_add_mesh_file(s, p, NAN, (V){0, 0, 0}, m, &e),
                   GLINT_E_ARGUMENT);
  assert_int_equal(
      glint_scene_add_mesh_file(s, p, 1, (V){0, INFINITY, 0}, m, &e),
      GLINT_E_ARGUMENT);
  assert_int_equal(glint_scene_add_mesh_file(s, p, 1, (V){0, 0, 0}, m + 1, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "material"));
  assert_int_equal(glint_scene_add_mesh_file(s, NULL, 1, (V){0, 0, 0}, m, &e),
                   GLINT_E_ARGUMENT);
  /* Scaling 1e14 by 1e10 goes beyond GLINT_MAX_COORDINATE: refused after
   * one good triangle was pushed, and rolled back. */
  assert_int_equal(glint_scene_add_mesh_file(s, p, 1e10, (V){0, 0, 0}, m, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "arg.obj:"));
  assert_non_null(strstr(e.message, ": vertex "));
  assert_non_null(strstr(e.message, ", scaled by 1e+10: "));
  assert_non_null(strstr(e.message, "magnitude at most 1e15"));
  assert_int_equal(s->object_count, 0);
  assert_int_equal(s->triangle_count, 0);
  /* Moved past it: the move is named (it said only "scaled by 1") */
  assert_int_equal(glint_scene_add_mesh_file(s, p, 1, (V){1e15, 0, 0}, m, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(
      strstr(e.message, "scaled by 1 and moved by (1e+15, 0, 0): "));
  assert_int_equal(s->triangle_count, 0);
  /* The error record is optional. */
  assert_int_equal(glint_scene_add_mesh_file(s, p, 1e10, (V){0, 0, 0}, m, NULL),
                   GLINT_E_ARGUMENT);
  assert_int_equal(s->triangle_count, 0);
  ASSERT_OK(glint_scene_add_mesh_file(s, p, 1, (V){0, 0, 0}, m, &e_));
  assert_int_equal(s->triangle_count, 2);
  /* A file's own vertex beyond the limit (finite in double, infinite in
   * float) is refused as well. */
  const char *far = write_text(f, "far.obj",
                               "v 0 0 0\nv 1 0 0\nv 0 1e300 0\n"
                               "f 1 2 3\n");
  assert_int_equal(glint_scene_add_mesh_file(s, far, 1, (V){0, 0, 0}, m, &e),
                   GLINT_E_ARGUMENT);
  /* named by its number, as the faces name it, at the face's line (it
   * said "triangle 0") */
  assert_non_null(strstr(e.message, "far.obj:4: vertex 3, scaled by 1: "));
  assert_int_equal(s->triangle_count, 2);
  glint_scene_destroy(s);
}

/* ------------------------------------------------------------------------ */
/* The real meshes                                                          */
/* ------------------------------------------------------------------------ */

static void real_meshes_shared(void **state) {
  (void)state;
  static const struct {
    const char *name;
    size_t triangles;
  } meshes[] = {
      {"bunny.obj", 3674},
      {"teapot.obj", 992},
      {"dragon_res4.obj", 11102},
      {"dragon_res3.obj", 47794},
      {"snowden_lo.obj", 37629},
      {"cornell_box.obj", 34}, /* 17 quads (two are commented out) */
      {"dragon_vrip_res2.ply.gz", 202520},
  };
  for (size_t i = 0; i < sizeof meshes / sizeof *meshes; i++) {
    char sub[64];
    snprintf(sub, sizeof sub, "data/%s", meshes[i].name);
    glint_scene *s = load(shared_path(sub), 1, (V){0, 0, 0});
    if (s->triangle_count != meshes[i].triangles)
      fail_msg("%s: %zu triangles, expected %zu", meshes[i].name,
               s->triangle_count, meshes[i].triangles);
    assert_int_equal(s->object_count, 1);
    glint_scene_destroy(s);
  }
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(obj_triangle_scaled_and_moved),
      cmocka_unit_test(obj_polygons_are_cut),
      cmocka_unit_test(concave_faces_are_ear_clipped),
      cmocka_unit_test(obj_negative_indices),
      cmocka_unit_test(obj_vertex_forms_and_normals),
      cmocka_unit_test(obj_ignores_known_statements),
      cmocka_unit_test(obj_gzip_and_two_meshes),
      cmocka_unit_test(large_meshes_are_kept_in_space_order),
      cmocka_unit_test(ply_ascii_skips_what_it_does_not_use),
      cmocka_unit_test(ply_ascii_unusual_but_valid),
      cmocka_unit_test(ply_binary_both_byte_orders),
      cmocka_unit_test(ply_binary_errors),
      cmocka_unit_test(ply_absurd_list_counts),
      cmocka_unit_test(ply_ascii_errors),
      cmocka_unit_test(ply_header_errors),
      cmocka_unit_test(obj_errors),
      cmocka_unit_test(files_of_every_kind_of_wrong),
      cmocka_unit_test(gzip_damage_is_an_error),
      cmocka_unit_test(a_file_past_the_limit_is_refused_unread),
      cmocka_unit_test(a_binary_file_for_a_text_one_is_refused_unread),
      cmocka_unit_test(nonfinite_vertices_no_face_uses),
      cmocka_unit_test(ply_faces_before_vertices),
      cmocka_unit_test(ply_face_too_concave),
      cmocka_unit_test(ply_tristrips),
      cmocka_unit_test(packed_scene_needs_no_files),
      cmocka_unit_test(bad_arguments),
      cmocka_unit_test(real_meshes_shared),
  };
  return glint_run_tests(tests, argc, argv, setup, teardown);
}
