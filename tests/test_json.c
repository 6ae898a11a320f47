/* glint's JSON scene format (docs/scene-format.md): every construct reads
 * into the scene it describes, the four files in scenes/ are the built-in
 * scenes exactly (the same scene structure, bit-identical renders), and
 * every kind of mistake is refused with a message naming the file and the
 * JSON path or the line and column.
 *
 * Test inputs are written into a fresh temporary folder, removed at the end.
 * In the JSON texts below ' stands for " (see write_json), which keeps them
 * readable. */
#include "test_util.h"

#include "scene/scene.h"

#include <dirent.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef glint_vec3 V;

typedef struct fixture {
  char dir[64];
} fixture;

/* ---- files -------------------------------------------------------------- */

static void remove_tree(const char *path) {
  DIR *d = opendir(path);
  if (d) {
    struct dirent *entry;
    while ((entry = readdir(d)) != NULL) {
      if (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0)
        continue;
      char child[1024];
      snprintf(child, sizeof child, "%s/%s", path, entry->d_name);
      remove_tree(child);
    }
    closedir(d);
    rmdir(path);
  } else {
    unlink(path);
  }
}

static int setup(void **state) {
  fixture *f = calloc(1, sizeof *f);
  if (!f)
    return -1;
  snprintf(f->dir, sizeof f->dir, "/tmp/glint-json-XXXXXX");
  if (!mkdtemp(f->dir)) {
    free(f);
    return -1;
  }
  *state = f;
  return 0;
}

static int teardown(void **state) {
  fixture *f = *state;
  remove_tree(f->dir);
  free(f);
  return 0;
}

/* Writes `size` bytes of `text` to the fixture's folder as `name`; the full
 * path goes to `path`. */
static void write_bytes(const fixture *f, const char *name, const char *text,
                        size_t size, char *path, size_t path_size) {
  snprintf(path, path_size, "%s/%s", f->dir, name);
  FILE *out = fopen(path, "wb");
  assert_non_null(out);
  assert_int_equal(fwrite(text, 1, size, out), size);
  assert_int_equal(fclose(out), 0);
}

/* Writes `text` with every ' turned into ". */
static void write_json(const fixture *f, const char *name, const char *text,
                       char *path, size_t path_size) {
  size_t n = strlen(text);
  char *copy = malloc(n + 1);
  assert_non_null(copy);
  for (size_t i = 0; i <= n; i++)
    copy[i] = text[i] == '\'' ? '"' : text[i];
  write_bytes(f, name, copy, n, path, path_size);
  free(copy);
}

/* Loads `text` (with ' for ") that must be right. */
static glint_scene *load_ok(const fixture *f, const char *text) {
  char path[256];
  write_json(f, "ok.json", text, path, sizeof path);
  glint_scene *s = NULL;
  glint_error e;
  if (glint_scene_load(path, &s, &e) != GLINT_OK)
    fail_msg("loading %s failed: %s", text, e.message);
  assert_non_null(s);
  return s;
}

/* The message must be `path` followed at once by `after_path`. */
static void check_message(const char *message, const char *path,
                          const char *after_path) {
  size_t n = strlen(path);
  if (strncmp(message, path, n) != 0 ||
      strncmp(message + n, after_path, strlen(after_path)) != 0)
    fail_msg("message\n  '%s'\nshould be\n  '%s%s...'", message, path,
             after_path);
}

/* Loading `path` must fail with `want` and a message starting with the
 * path and then `after_path`, and must not touch the output. */
static void load_fails(const char *path, glint_status want,
                       const char *after_path) {
  glint_scene *s = NULL;
  glint_error e;
  memset(&e, 0, sizeof e);
  glint_status st = glint_scene_load(path, &s, &e);
  if (st != want)
    fail_msg("%s: status %s, expected %s (%s)", path, glint_status_name(st),
             glint_status_name(want), e.message);
  assert_int_equal(e.status, want);
  assert_null(s);
  check_message(e.message, path, after_path);
  /* Without an error record it fails the same way, quietly. */
  assert_int_equal(glint_scene_load(path, &s, NULL), want);
  assert_null(s);
}

/* ---- comparing scenes --------------------------------------------------- */

#define SAME(a, b) assert_memory_equal(&(a), &(b), sizeof(a))

static void same_material(const glint_material *a, const glint_material *b) {
  SAME(a->color, b->color);
  assert_int_equal(a->texture, b->texture);
  SAME(a->checker_odd, b->checker_odd);
  SAME(a->checker_even, b->checker_even);
  SAME(a->checker_size, b->checker_size);
  SAME(a->ka, b->ka);
  SAME(a->kd, b->kd);
  SAME(a->ks, b->ks);
  SAME(a->h, b->h);
  SAME(a->kr, b->kr);
  SAME(a->kt, b->kt);
  SAME(a->ior, b->ior);
  SAME(a->absorb, b->absorb);
}

/* Field by field, bit for bit (padding aside). */
static void same_scene(const glint_scene *a, const glint_scene *b) {
  SAME(a->camera.from, b->camera.from);
  SAME(a->camera.at, b->camera.at);
  SAME(a->camera.up, b->camera.up);
  SAME(a->camera.fov_x_degrees, b->camera.fov_x_degrees);
  assert_int_equal(a->width, b->width);
  assert_int_equal(a->height, b->height);
  SAME(a->background, b->background);
  SAME(a->ambient, b->ambient);
  assert_int_equal(a->light_count, b->light_count);
  for (size_t i = 0; i < a->light_count; i++) {
    SAME(a->lights[i].position, b->lights[i].position);
    SAME(a->lights[i].color, b->lights[i].color);
  }
  assert_int_equal(a->material_count, b->material_count);
  for (size_t i = 0; i < a->material_count; i++)
    same_material(&a->materials[i], &b->materials[i]);
  assert_int_equal(a->object_count, b->object_count);
  for (size_t i = 0; i < a->object_count; i++) {
    assert_int_equal(a->objects[i].material, b->objects[i].material);
    assert_int_equal(a->objects[i].shape, b->objects[i].shape);
    assert_int_equal(a->objects[i].first, b->objects[i].first);
    assert_int_equal(a->objects[i].count, b->objects[i].count);
    SAME(a->objects[i].origin, b->objects[i].origin);
  }
  assert_int_equal(a->sphere_count, b->sphere_count);
  for (size_t i = 0; i < a->sphere_count; i++) {
    SAME(a->spheres[i].center, b->spheres[i].center);
    SAME(a->spheres[i].radius, b->spheres[i].radius);
    assert_int_equal(a->spheres[i].object, b->spheres[i].object);
  }
  assert_int_equal(a->plane_count, b->plane_count);
  for (size_t i = 0; i < a->plane_count; i++) {
    SAME(a->planes[i].normal, b->planes[i].normal);
    SAME(a->planes[i].d, b->planes[i].d);
    assert_int_equal(a->planes[i].object, b->planes[i].object);
  }
  assert_int_equal(a->triangle_count, b->triangle_count);
  for (size_t i = 0; i < a->triangle_count; i++) {
    SAME(a->triangles[i].v, b->triangles[i].v);
    assert_int_equal(a->triangles[i].object, b->triangles[i].object);
    assert_int_equal(a->triangles[i].normals, b->triangles[i].normals);
  }
  assert_int_equal(a->tri_normal_count, b->tri_normal_count);
  assert_int_equal(a->cone_count, b->cone_count);
  for (size_t i = 0; i < a->cone_count; i++) {
    SAME(a->cones[i].base, b->cones[i].base);
    SAME(a->cones[i].apex, b->cones[i].apex);
    SAME(a->cones[i].base_radius, b->cones[i].base_radius);
    SAME(a->cones[i].apex_radius, b->cones[i].apex_radius);
    assert_int_equal(a->cones[i].object, b->cones[i].object);
  }
}

static glint_image *render(const glint_scene *s, glint_backend backend) {
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.width = 160;
  rs.height = 120;
  rs.spp = 1;
  rs.max_depth = 5;
  rs.backend = backend;
  glint_image *im;
  ASSERT_OK(glint_render(s, &rs, &im, NULL, &e_));
  return im;
}

/* ---- what the format describes ------------------------------------------ */

static void every_construct_reads(void **state) {
  const fixture *f = *state;
  glint_scene *s = load_ok(
      f,
      "{\n"
      "  'camera': {'from': [1, 2, 3], 'at': [0, 1, -1], 'up': [0, 0, 1],\n"
      "             'fov': 45.5},\n"
      "  'image': {'width': 320, 'height': 200},\n"
      "  'background': [0.1, 0.2, 0.3],\n"
      "  'ambient': [0.5, 0.25, 0.125],\n"
      "  'lights': [{'position': [1, 10, 2], 'color': [0.5, 0.6, 0.7]},\n"
      "             {'position': [-1, 5, -2]}],\n"
      "  'materials': {\n"
      "    'plain': {},\n"
      "    'glass': {'color': [0.9, 0.8, 0.7], 'ka': 0.01, 'kd': 0.02,\n"
      "              'ks': 0.9, 'h': 80, 'kr': 0.1, 'kt': 0.85, 'ior': 1.5,\n"
      "              'absorb': [0.1, 0.025, 0]},\n"
      "    'floor': {'texture': {'type': 'checker-planar', 'odd': [1, 0, 0],\n"
      "                          'even': [1, 1, 0], 'size': 2}},\n"
      "    'ball': {'texture': {'type': 'checker-solid'}},\n"
      "    'odd name \\u00e9': {'kd': 0.5}\n"
      "  },\n"
      "  'objects': [\n"
      "    {'type': 'sphere', 'material': 'glass', 'center': [0, 1.5, 0],\n"
      "     'radius': 1.25},\n"
      "    {'type': 'plane', 'material': 'floor', 'normal': [0, 2, 0],\n"
      "     'point': [0, -1, 0]},\n"
      "    {'type': 'triangle', 'material': 'plain',\n"
      "     'vertices': [[0, 0, 0], [1, 0, 0], [0, 1, 0.5]]},\n"
      "    {'type': 'cone', 'material': 'ball', 'base': [0, 0, 0],\n"
      "     'base_radius': 1, 'apex': [0, 3, 0], 'apex_radius': 0.25},\n"
      "    {'material': 'odd name \\u00e9', 'radius': 0.5, 'type': 'sphere',\n"
      "     'center': [4, 5, 6]}\n"
      "  ]\n"
      "}\n");
  glint_scene_info info;
  glint_scene_get_info(s, &info);
  assert_int_equal(info.lights, 2);
  assert_int_equal(info.materials, 5);
  assert_int_equal(info.objects, 5);
  assert_int_equal(info.spheres, 2);
  assert_int_equal(info.planes, 1);
  assert_int_equal(info.triangles, 1);
  assert_int_equal(info.cones, 1);
  assert_int_equal(info.width, 320);
  assert_int_equal(info.height, 200);

  assert_true(s->camera.from.x == 1 && s->camera.from.y == 2 &&
              s->camera.from.z == 3);
  assert_true(s->camera.at.x == 0 && s->camera.at.y == 1 &&
              s->camera.at.z == -1);
  assert_true(s->camera.up.x == 0 && s->camera.up.y == 0 &&
              s->camera.up.z == 1);
  assert_true(s->camera.fov_x_degrees == 45.5);
  assert_true(s->background.x == 0.1 && s->background.y == 0.2 &&
              s->background.z == 0.3);
  assert_true(s->ambient.x == 0.5 && s->ambient.y == 0.25 &&
              s->ambient.z == 0.125);
  assert_true(s->lights[0].position.y == 10 && s->lights[0].color.x == 0.5 &&
              s->lights[0].color.z == 0.7);
  assert_true(s->lights[1].position.x == -1 && s->lights[1].color.x == 1 &&
              s->lights[1].color.y == 1 && s->lights[1].color.z == 1);

  /* Materials in the file's order; what is left out is the default. */
  glint_material want;
  glint_material_default(&want);
  same_material(&s->materials[0], &want);
  want.color = (V){0.9, 0.8, 0.7};
  want.ka = 0.01;
  want.kd = 0.02;
  want.ks = 0.9;
  want.h = 80;
  want.kr = 0.1;
  want.kt = 0.85;
  want.ior = 1.5;
  want.absorb = (V){0.1, 0.025, 0};
  same_material(&s->materials[1], &want);
  glint_material_default(&want);
  want.texture = GLINT_TEXTURE_CHECKER_PLANAR;
  want.checker_odd = (V){1, 0, 0};
  want.checker_even = (V){1, 1, 0};
  want.checker_size = 2;
  same_material(&s->materials[2], &want);
  glint_material_default(&want);
  want.texture = GLINT_TEXTURE_CHECKER_SOLID;
  same_material(&s->materials[3], &want);
  assert_true(s->materials[4].kd == 0.5);

  /* Objects in the file's order, each with its material. */
  static const uint32_t shapes[5] = {GLI_SHAPE_SPHERE, GLI_SHAPE_PLANE,
                                     GLI_SHAPE_TRIANGLE, GLI_SHAPE_CONE,
                                     GLI_SHAPE_SPHERE};
  static const uint32_t materials[5] = {1, 2, 0, 3, 4};
  for (int i = 0; i < 5; i++) {
    assert_int_equal(s->objects[i].shape, shapes[i]);
    assert_int_equal(s->objects[i].material, materials[i]);
  }
  assert_true(s->spheres[0].center.y == 1.5 && s->spheres[0].radius == 1.25);
  assert_true(s->spheres[1].center.x == 4 && s->spheres[1].center.z == 6 &&
              s->spheres[1].radius == 0.5);
  /* The normal is made unit; the plane is y = -1. */
  assert_true(s->planes[0].normal.y == 1 && s->planes[0].d == 1);
  assert_true(s->triangles[0].v[1].x == 1 && s->triangles[0].v[2].y == 1 &&
              s->triangles[0].v[2].z == 0.5);
  assert_true(s->cones[0].base_radius == 1 && s->cones[0].apex.y == 3 &&
              s->cones[0].apex_radius == 0.25);
  glint_scene_destroy(s);
}

static void defaults_are_the_librarys(void **state) {
  const fixture *f = *state;
  glint_scene *fresh;
  ASSERT_OK(glint_scene_create(&fresh, &e_));

  /* Nothing given: glint_scene_create's scene. */
  glint_scene *s = load_ok(f, "{}");
  same_scene(s, fresh);
  glint_scene_destroy(s);
  s = load_ok(f, "{'lights': [], 'materials': {}, 'objects': []}");
  same_scene(s, fresh);
  glint_scene_destroy(s);

  /* A camera needs only from and at: up +y, 60 degrees. */
  s = load_ok(f, "{'camera': {'from': [0, 1, 5], 'at': [0, 0, 0]}}");
  assert_true(s->camera.up.x == 0 && s->camera.up.y == 1 &&
              s->camera.up.z == 0);
  assert_true(s->camera.fov_x_degrees == 60);
  assert_int_equal(s->width, 640);
  assert_int_equal(s->height, 480);
  glint_scene_destroy(s);

  /* A UTF-8 byte-order mark is allowed, and the order of sections is free:
   * objects may come before the materials they name. */
  s = load_ok(f, "\xef\xbb\xbf{'objects': [{'type': 'sphere', 'material': "
                 "'m', 'center': [0, 0, 0], 'radius': 1}], 'materials': "
                 "{'m': {}}}");
  assert_int_equal(s->sphere_count, 1);
  glint_scene_destroy(s);
  glint_scene_destroy(fresh);
}

/* scenes/NAME.json is built-in NAME: the same scene, and renders equal to
 * the last bit with the reference backend and with the default one. */
static void scene_files_are_the_builtins(void **state) {
  (void)state;
  for (size_t i = 0; i < glint_builtin_scene_count(); i++) {
    const char *name = glint_builtin_scene_name(i);
    char path[1024];
    snprintf(path, sizeof path, "%s/scenes/%s.json", GLINT_SOURCE_DIR, name);
    glint_scene *file, *builtin;
    ASSERT_OK(glint_scene_load(path, &file, &e_));
    ASSERT_OK(glint_scene_builtin(name, &builtin, &e_));
    same_scene(file, builtin);
    const glint_backend backends[2] = {GLINT_BACKEND_SCALAR_DOUBLE,
                                       GLINT_BACKEND_AUTO};
    for (int b = 0; b < 2; b++) {
      glint_image *a = render(file, backends[b]);
      glint_image *c = render(builtin, backends[b]);
      printf("%-9s %-13s PSNR %g dB\n", name, glint_backend_name(backends[b]),
             glint_image_psnr(a, c));
      assert_memory_equal(glint_image_pixels_const(a),
                          glint_image_pixels_const(c), (size_t)160 * 120 * 3);
      assert_true(isinf(glint_image_psnr(a, c)));
      glint_image_destroy(a);
      glint_image_destroy(c);
    }
    glint_scene_destroy(file);
    glint_scene_destroy(builtin);
  }
}

/* A mesh's file is found beside the scene file (or where an absolute path
 * says), and the mesh reader's errors come back under the object's path. */
static void meshes_resolve_beside_the_scene(void **state) {
  const fixture *f = *state;
  char sub[128], scene[256], obj[256], missing[256], json[1024];
  snprintf(sub, sizeof sub, "%s/sub", f->dir);
  assert_int_equal(mkdir(sub, 0700), 0);
  write_bytes(f, "sub/tetra.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
              "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
              strlen("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                     "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"),
              obj, sizeof obj);
  snprintf(missing, sizeof missing, "%s/sub/nope.obj", f->dir);

  write_json(f, "sub/mesh.json",
             "{'materials': {'m': {}}, 'objects': [\n"
             "  {'type': 'sphere', 'material': 'm', 'center': [0, 0, 0],\n"
             "   'radius': 1},\n"
             "  {'type': 'mesh', 'material': 'm', 'file': 'tetra.obj',\n"
             "   'scale': 2, 'translate': [10, 20, 30]}]}",
             scene, sizeof scene);
  glint_scene *s = NULL;
  glint_error e;
  glint_status st = glint_scene_load(scene, &s, &e);
  if (st == GLINT_E_UNSUPPORTED) {
    /* The mesh reader is not in this build yet: its refusal passes
     * through, under the object's path, naming the resolved file. */
    printf("mesh files unsupported here: %s\n", e.message);
    assert_null(s);
    check_message(e.message, scene, ": objects[1]: ");
    assert_non_null(strstr(e.message, obj));
  } else {
    if (st != GLINT_OK)
      fail_msg("%s", e.message);
    assert_int_equal(s->object_count, 2);
    assert_int_equal(s->triangle_count, 4);
    /* Scaled by 2, then moved: the bounding box is (10,20,30)-(12,22,32). */
    V lo = {INFINITY, INFINITY, INFINITY},
      hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t t = 0; t < s->triangle_count; t++)
      for (int k = 0; k < 3; k++) {
        V v = s->triangles[t].v[k];
        lo = (V){fmin(lo.x, v.x), fmin(lo.y, v.y), fmin(lo.z, v.z)};
        hi = (V){fmax(hi.x, v.x), fmax(hi.y, v.y), fmax(hi.z, v.z)};
      }
    assert_true(lo.x == 10 && lo.y == 20 && lo.z == 30);
    assert_true(hi.x == 12 && hi.y == 22 && hi.z == 32);
    glint_scene_destroy(s);
  }

  /* A missing mesh, by a relative and by an absolute path. */
  write_json(f, "sub/missing.json",
             "{'materials': {'m': {}}, 'objects': [{'type': 'mesh', "
             "'material': 'm', 'file': 'nope.obj'}]}",
             scene, sizeof scene);
  s = NULL;
  st = glint_scene_load(scene, &s, &e);
  assert_true(st == GLINT_E_IO || st == GLINT_E_UNSUPPORTED);
  assert_null(s);
  check_message(e.message, scene, ": objects[0]: ");
  assert_non_null(strstr(e.message, missing));

  snprintf(json, sizeof json,
           "{'materials': {'m': {}}, 'objects': [{'type': 'mesh', "
           "'material': 'm', 'file': '%s'}]}",
           missing);
  write_json(f, "absolute.json", json, scene, sizeof scene);
  st = glint_scene_load(scene, &s, &e);
  assert_true(st == GLINT_E_IO || st == GLINT_E_UNSUPPORTED);
  check_message(e.message, scene, ": objects[0]: ");
  assert_non_null(strstr(e.message, missing));
}

/* ---- what the format refuses -------------------------------------------- */

typedef struct bad_case {
  const char *json;       /* ' stands for " */
  const char *after_path; /* what the message says after the file's path */
} bad_case;

#define M "'materials': {'m': {}}, "
#define SPHERE "{'type': 'sphere', 'material': 'm', 'center': [0, 0, 0], "

static const bad_case syntax_cases[] = {
    {"{\n  'camera': {\n    'from': [0, 1 2]\n  }\n}",
     ":3:19: JSON syntax error: found '2'"},
    {"{'lights': [],}",
     ":1:15: JSON syntax error: found '}' after a comma (JSON allows no "
     "trailing comma)"},
    {"{'a': [1, 2,]}", ":1:13: JSON syntax error: found ']' after a comma"},
    {"{\n 'a': 'abc\n}", ":2:7: JSON syntax error: a string that is never "
                         "closed"},
    {"{'camera': NaN}", ":1:12: JSON syntax error: found 'NaN' (JSON has no "
                        "NaN or Infinity)"},
    {"{'camera': -Infinity}", ":1:12: JSON syntax error: found '-Infinity'"},
    {"// a comment\n{}", ":1:1: JSON syntax error: found a comment"},
    {"", ":1:1: JSON syntax error: the file is empty"},
    {"  \n\n ",
     ":3:2: JSON syntax error: the file holds nothing but white space"},
    {"{} x", ":1:4: JSON syntax error: found 'x'"},
    /* right after an empty object, not at its '}' */
    {"{}]", ":1:3: JSON syntax error: found ']'"},
    {"{ }x", ":1:4: JSON syntax error: found 'x'"},
    {"{'a': {}]}", ":1:9: JSON syntax error: found ']'"},
    {"{'objects': [", ":1:14: JSON syntax error: the file ends early"},
    /* ending after a closed string (it said the string never closed) and
     * after a value inside an array (it said "found '0'", at the value) */
    {"{'background'", ":1:14: JSON syntax error: the file ends early"},
    {"{'background': [0, 0", ":1:21: JSON syntax error: the file ends early"},
    {"{'a': {'b': true\n", ":2:1: JSON syntax error: the file ends early"},
    {"{'a': [1, 2] 3", ":1:14: JSON syntax error: found '3'"},
    {"{objects: []}", ":1:2: JSON syntax error: found 'objects'"},
    {"{'a' 1}", ":1:6: JSON syntax error: found '1'"},
    {"{'a': tru}", ":1:7: JSON syntax error: found 'tru'"},
    /* lines that end in a lone CR are lines (it said 1:10) */
    {"{\r\r'a': tru}", ":3:6: JSON syntax error: found 'tru'"},
    {"{'a\\q': 1}", ":1:4: JSON syntax error: an invalid escape sequence"},
    /* numbers as RFC 8259 writes them, not as strtod reads them */
    {"{'a': [1., 0]}",
     ":1:8: JSON syntax error: a number without a digit after its decimal"},
    {"{'a': .5}",
     ":1:7: JSON syntax error: a number without a digit before its decimal"},
    {"{'a': -.5}",
     ":1:7: JSON syntax error: a number without a digit before its decimal"},
    {"{'a': 2e}",
     ":1:7: JSON syntax error: a number whose exponent has no digits"},
    {"{'a': 064}", ":1:7: JSON syntax error: a number with a leading zero"},
    /* strings are UTF-8 */
    {"{'a\xff\xfe': 1}",
     ":1:4: JSON syntax error: a string that is not UTF-8 text"},
    /* an overlong '/', a lead byte past U+10FFFF, a lone continuation byte
     * (the first two were taken) */
    {"{'a\xc0\xaf': 1}",
     ":1:4: JSON syntax error: a string that is not UTF-8 text"},
    {"{'a\xf5\x80\x80\x80': 1}",
     ":1:4: JSON syntax error: a string that is not UTF-8 text"},
    {"{'a\x80': 1}",
     ":1:4: JSON syntax error: a string that is not UTF-8 text"},
    /* Columns count characters: the é is two bytes. */
    {"{'\xc3\xa9': x}", ":1:7: JSON syntax error: found 'x'"},
    {"{'a': \xc3\xa9}", ":1:7: JSON syntax error: found '\xc3\xa9' (U+00E9)"},
    /* characters that look like nothing say which they are */
    {"\xef\xbb\xbf\xef\xbb\xbf{}",
     ":1:1: JSON syntax error: found '\xef\xbb\xbf' (U+FEFF)"},
    /* A byte order mark is not a column, and alone it is an empty file. */
    {"\xef\xbb\xbf{ 'a': 1,}",
     ":1:10: JSON syntax error: found '}' after a comma"},
    {"\xef\xbb\xbf", ":1:1: JSON syntax error: the file is empty"},
    /* The first problem is the one said, whichever check finds it (the
     * strict number and escape checks said the later one). */
    {"{'a': tru, 'b': 01}", ":1:7: JSON syntax error: found 'tru'"},
    {"{'a': [1 2], 'b': '\\q'}", ":1:10: JSON syntax error: found '2'"},
    {"// a comment\n{'a': 01}", ":1:1: JSON syntax error: found a comment"},
    {"{'a': 1}} 'b': 01", ":1:9: JSON syntax error: found '}'"},
    {"{'a': 01, 'b': tru}",
     ":1:7: JSON syntax error: a number with a leading zero"},
    {"{'a':\xc2\xa0"
     "1}",
     ":1:6: JSON syntax error: found '\xc2\xa0' (U+00A0)"},
    {"{'a': \xc3}", ":1:7: JSON syntax error: found the byte 0xc3"},
    {"{\r\n\t'a': [1 2]}", ":2:10: JSON syntax error: found '2'"},
};

static const bad_case structure_cases[] = {
    /* The top level. */
    {"[1]", ": expected an object at the top level, found an array of 1 "
            "element"},
    {"{'epsilon': 1e-4}",
     ": unknown field \"epsilon\" (known: camera, image, background, "
     "ambient, lights, materials, objects, animation)"},
    {"{'objects': [], 'objects': []}", ": field \"objects\" appears twice"},
    {"{'Camera': {}}", ": unknown field \"Camera\""},
    /* Camera and image. */
    {"{'camera': 5}", ": camera: expected an object, found a number (5)"},
    {"{'camera': {'from': [0, 0, 5]}}", ": camera: missing \"at\""},
    {"{'camera': {'from': [0, 0, 5], 'at': [0, 0, 0], 'fov': 'wide'}}",
     ": camera.fov: expected a number, found a string (\"wide\")"},
    {"{'camera': {'from': [0, 0, 5], 'at': [0, 0, 0], 'fov': null}}",
     ": camera.fov: expected a number, found null"},
    {"{'camera': {'from': [0, 0, 5], 'at': [0, 0, 0], 'fov': 180}}",
     ": camera: field of view 180 is not between 0 and 180 degrees"},
    {"{'camera': {'from': [0, 0, 5], 'at': [0, 0, 5]}}",
     ": camera: 'from' and 'at' are the same point"},
    {"{'camera': {'from': [0, 5, 0], 'at': [0, 0, 0]}}",
     ": camera: 'up' is zero or parallel to the view direction"},
    {"{'camera': {'from': [0, 0, 5], 'at': [0, 0, 0], 'angle': 60}}",
     ": camera: unknown field \"angle\" (known: from, at, up, fov)"},
    {"{'image': {'width': 0, 'height': 480}}",
     ": image.width: 0 is outside 1..16384"},
    {"{'image': {'width': 640, 'height': 1e9}}",
     ": image.height: 1000000000 is outside 1..16384"},
    {"{'image': {'width': 640.5, 'height': 480}}",
     ": image.width: expected a whole number, found 640.5"},
    /* as few digits as say the number (it said 1.0000000000000001e+300) */
    {"{'image': {'width': 1e300, 'height': 480}}",
     ": image.width: 1e+300 is outside 1..16384"},
    {"{'image': {'width': 2.0000000000000004, 'height': 480}}",
     ": image.width: expected a whole number, found 2.0000000000000004"},
    {"{'image': {'width': '640', 'height': 480}}",
     ": image.width: expected a number, found a string (\"640\")"},
    {"{'image': {'width': 640}}", ": image: missing \"height\""},
    /* Colours. */
    {"{'background': [1, 2]}",
     ": background: expected an array of 3 numbers, found an array of 2 "
     "elements"},
    {"{'background': [-1, 0, 0]}",
     ": background: background colour must not be negative"},
    {"{'ambient': true}",
     ": ambient: expected an array of 3 numbers, found a boolean (true)"},
    {"{'ambient': [1, 1, 1e999]}",
     ": ambient[2]: the number is too large: it is not finite"},
    /* Lights. */
    {"{'lights': {}}", ": lights: expected an array, found an object"},
    {"{'lights': [{'position': [0, 9, 0]}, {'color': [1, 1, 1]}]}",
     ": lights[1]: missing \"position\""},
    {"{'lights': [{'position': [0, 9, 0], 'color': [1, 1, 'x']}]}",
     ": lights[0].color[2]: expected a number, found a string (\"x\")"},
    {"{'lights': [{'position': [0, 9, 0], 'color': [1, -1, 1]}]}",
     ": lights[0]: light colour must not be negative"},
    {"{'lights': [{'position': [0, 9, 0], 'intensity': 2}]}",
     ": lights[0]: unknown field \"intensity\" (known: position, color)"},
    {"{'lights': [[0, 9, 0]]}",
     ": lights[0]: expected an object, found an array of 3 elements"},
    /* Materials. */
    {"{'materials': []}",
     ": materials: expected an object, found an array of 0 elements"},
    {"{'materials': {'m': 1}}",
     ": materials.m: expected an object, found a number (1)"},
    {"{'materials': {'glass': {'kd': 0.1, 'kdd': 0.2}}}",
     ": materials.glass: unknown field \"kdd\" (known: color, ka, kd, ks, h, "
     "kr, kt, ior, absorb, texture)"},
    {"{'materials': {'glass': {'kd': 0.1, 'kd': 0.2}}}",
     ": materials.glass: field \"kd\" appears twice"},
    {"{'materials': {'glass': {}, 'm': {}, 'glass': {'kd': 1}}}",
     ": materials.glass: a second material named \"glass\""},
    {"{'materials': {'glass': {'kd': -1}}}",
     ": materials.glass: material kd = -1 must be a finite number >= 0"},
    {"{'materials': {'glass': {'ior': 0}}}",
     ": materials.glass: material ior = 0 must be a finite number > 0"},
    {"{'materials': {'glass': {'h': -1e999}}}",
     ": materials.glass.h: the number is too large: it is not finite"},
    {"{'materials': {'glass': {'absorb': [0, 0]}}}",
     ": materials.glass.absorb: expected an array of 3 numbers"},
    {"{'materials': {'my glass': {'kdd': 1}}}",
     ": materials[\"my glass\"]: unknown field \"kdd\""},
    {"{'materials': {'a\\u0001b': {'x': 1}}}",
     ": materials[\"a\\u0001b\"]: unknown field \"x\""},
    {"{'materials': {'floor': {'texture': 'checker'}}}",
     ": materials.floor.texture: expected an object, found a string "
     "(\"checker\")"},
    {"{'materials': {'floor': {'texture': {'size': 2}}}}",
     ": materials.floor.texture: missing \"type\""},
    {"{'materials': {'floor': {'texture': {'type': 'checker'}}}}",
     ": materials.floor.texture.type: unknown texture type \"checker\" "
     "(checker-planar, checker-solid)"},
    {"{'materials': {'floor': {'texture': {'type': 'checker-solid', "
     "'size': 0}}}}",
     ": materials.floor: checker size 0 is outside 1e-06..1e+15"},
    /* 1/size was 0 in float from 1e38: one colour, where double has two */
    {"{'materials': {'floor': {'texture': {'type': 'checker-solid', "
     "'size': 1e300}}}}",
     ": materials.floor: checker size 1e+300 is outside 1e-06..1e+15"},
    {"{'materials': {'floor': {'texture': {'type': 'checker-solid', "
     "'size': 1e-39}}}}",
     ": materials.floor: checker size 1e-39 is outside 1e-06..1e+15"},
    {"{'materials': {'floor': {'texture': {'type': 'checker-solid', "
     "'odd': ['red', 0, 0]}}}}",
     ": materials.floor.texture.odd[0]: expected a number, found a string"},
    {"{'materials': {'floor': {'texture': {'type': 'checker-solid', "
     "'scale': 2}}}}",
     ": materials.floor.texture: unknown field \"scale\" (known: type, odd, "
     "even, size)"},
    /* Objects. */
    {"{'objects': {}}", ": objects: expected an array, found an object"},
    {"{" M "'objects': ['sphere']}",
     ": objects[0]: expected an object, found a string (\"sphere\")"},
    {"{" M "'objects': [{'material': 'm'}]}", ": objects[0]: missing \"type\""},
    {"{" M "'objects': [{'type': 1}]}",
     ": objects[0].type: expected a string, found a number (1)"},
    {"{" M "'objects': [{'type': 'torus', 'material': 'm'}]}",
     ": objects[0].type: unknown object type \"torus\" (sphere, plane, "
     "triangle, cone, mesh)"},
    {"{" M "'objects': [" SPHERE "'radius': 1}, " SPHERE "'radius': 1}, " SPHERE
     "'radius': '1'}]}",
     ": objects[2].radius: expected a number, found a string"},
    {"{" M "'objects': [" SPHERE "'radius': 1}, " SPHERE "'radius': 1}, " SPHERE
     "'r': 1}]}",
     ": objects[2]: unknown field \"r\" (known: type, material, center, "
     "radius, transform)"},
    {"{" M "'objects': [" SPHERE "'radius': 1}, " SPHERE "'radius': 1}, " SPHERE
     "'size': 1}]}",
     ": objects[2]: unknown field \"size\""},
    {"{" M "'objects': [" SPHERE "'radius': 1}, " SPHERE "'radius': 1}, " SPHERE
     "'radius': -1}]}",
     ": objects[2]: sphere: radius -1 must be > 0"},
    {"{" M "'objects': [" SPHERE "'radius': 0}]}",
     ": objects[0]: sphere: radius 0 must be > 0"},
    {"{" M "'objects': [{'type': 'sphere', 'material': 'm', 'radius': 1}]}",
     ": objects[0]: missing \"center\""},
    {"{" M "'objects': [{'type': 'sphere', 'material': 'm', 'center': [0, 0, "
     "0]}]}",
     ": objects[0]: missing \"radius\""},
    {"{" M "'objects': [{'type': 'sphere', 'center': [0, 0, 0], 'radius': 1}]}",
     ": objects[0]: missing \"material\""},
    {"{'materials': {'glass': {}, 'm': {}}, 'objects': [" SPHERE
     "'radius': 1}, "
     "{'type': 'sphere', 'material': 'glas', 'center': [0, 0, 0], "
     "'radius': 1}]}",
     ": objects[1].material: no material named \"glas\""},
    {"{'objects': [" SPHERE "'radius': 1}]}",
     ": objects[0].material: no material named \"m\" (the file defines no "
     "materials)"},
    {"{" M "'objects': [{'type': 'sphere', 'material': 3, 'center': [0, 0, "
     "0], 'radius': 1}]}",
     ": objects[0].material: expected a string, found a number (3)"},
    {"{" M "'objects': [{'type': 'sphere', 'material': 'm', 'center': [1, "
     "2], 'radius': 1}]}",
     ": objects[0].center: expected an array of 3 numbers, found an array of "
     "2 elements"},
    {"{" M "'objects': [{'type': 'sphere', 'material': 'm', 'center': [1, 2, "
     "3, 4], 'radius': 1}]}",
     ": objects[0].center: expected an array of 3 numbers, found an array of "
     "4 elements"},
    {"{" M "'objects': [{'type': 'sphere', 'material': 'm', 'center': [0, 0, "
     "1e999], 'radius': 1}]}",
     ": objects[0].center[2]: the number is too large: it is not finite"},
    {"{" M "'objects': [" SPHERE "'radius': -1e999}]}",
     ": objects[0].radius: the number is too large: it is not finite"},
    {"{" M "'objects': [{'type': 'plane', 'material': 'm', 'normal': [0, 0, "
     "0], 'point': [0, 0, 0]}]}",
     ": objects[0]: plane: the normal must not be zero"},
    {"{" M "'objects': [{'type': 'plane', 'material': 'm', 'normal': [0, 1, "
     "0]}]}",
     ": objects[0]: missing \"point\""},
    {"{" M "'objects': [{'type': 'triangle', 'material': 'm', 'vertices': "
     "[[0, 0, 0], [1, 0, 0]]}]}",
     ": objects[0].vertices: expected an array of 3 vertices ([x, y, z] "
     "each), found an array of 2 elements"},
    {"{" M "'objects': [{'type': 'triangle', 'material': 'm', 'vertices': "
     "[[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]}]}",
     ": objects[0].vertices: expected an array of 3 vertices"},
    {"{" M "'objects': [{'type': 'triangle', 'material': 'm', 'vertices': "
     "[[0, 0, 0], [1, 0], [0, 1, 0]]}]}",
     ": objects[0].vertices[1]: expected an array of 3 numbers, found an "
     "array of 2 elements"},
    {"{" M "'objects': [{'type': 'triangle', 'material': 'm', 'vertices': "
     "[[0, 0, 0], [1, 0, 0], [0, false, 0]]}]}",
     ": objects[0].vertices[2][1]: expected a number, found a boolean "
     "(false)"},
    {"{" M "'objects': [{'type': 'triangle', 'material': 'm', 'vertices': "
     "{}}]}",
     ": objects[0].vertices: expected an array of 3 vertices"},
    {"{" M "'objects': [{'type': 'triangle', 'material': 'm', 'vertices': "
     "[[0, 0, 0], [1, 0, 0], [0, 1, 0]], 'normal': [0, 0, 1]}]}",
     ": objects[0]: unknown field \"normal\" (known: type, material, "
     "vertices, transform)"},
    {"{" M "'objects': [{'type': 'cone', 'material': 'm', 'base': [0, 0, 0], "
     "'base_radius': 0, 'apex': [0, 1, 0], 'apex_radius': 0}]}",
     ": objects[0]: cone: both radii are 0: it has no surface"},
    {"{" M "'objects': [{'type': 'cone', 'material': 'm', 'base': [0, 0, 0], "
     "'base_radius': 1, 'apex': [0, 1, 0]}]}",
     ": objects[0]: missing \"apex_radius\""},
    {"{" M "'objects': [{'type': 'mesh', 'material': 'm'}]}",
     ": objects[0]: missing \"file\""},
    {"{" M "'objects': [{'type': 'mesh', 'material': 'm', 'file': ''}]}",
     ": objects[0].file: the file name is empty"},
    {"{" M "'objects': [{'type': 'mesh', 'material': 'm', 'file': 'a.obj', "
     "'scale': 0}]}",
     ": objects[0].scale: scale 0 must be > 0"},
    {"{" M "'objects': [{'type': 'mesh', 'material': 'm', 'file': 'a.obj', "
     "'translate': [1]}]}",
     ": objects[0].translate: expected an array of 3 numbers, found an array "
     "of 1 element"},
    {"{" M "'objects': [{'type': 'mesh', 'material': 'm', 'file': 'a.obj', "
     "'radius': 1}]}",
     ": objects[0]: unknown field \"radius\" (known: type, material, file, "
     "scale, translate, transform)"},
};

#undef M
#undef SPHERE

static void run_cases(const fixture *f, const bad_case *cases, size_t count) {
  for (size_t i = 0; i < count; i++) {
    char path[256];
    write_json(f, "bad.json", cases[i].json, path, sizeof path);
    load_fails(path, GLINT_E_PARSE, cases[i].after_path);
  }
}

static void syntax_errors_give_line_and_column(void **state) {
  const fixture *f = *state;
  run_cases(f, syntax_cases, sizeof syntax_cases / sizeof syntax_cases[0]);

  char path[256];
  /* Single quotes, which write_json would turn into double ones. */
  write_bytes(f, "quotes.json", "{'a': 1}", 8, path, sizeof path);
  load_fails(path, GLINT_E_PARSE,
             ":1:2: JSON syntax error: found ' (JSON strings take double "
             "quotes)");
  /* A NUL byte, and UTF-16. */
  write_bytes(f, "nul.json", "{\n\"a\":\0}", 8, path, sizeof path);
  load_fails(path, GLINT_E_PARSE, ":2:5: a NUL byte");
  write_bytes(f, "utf16.json", "\xff\xfe{\0}\0", 6, path, sizeof path);
  load_fails(path, GLINT_E_PARSE, ": UTF-16 text");
  /* Nesting deeper than glint takes is refused, not a crash, and named
   * (beyond cJSON's limit it was "found '['"; within it, cJSON's recursion
   * overflowed a 64 KiB stack); a string's brackets do not count. */
  char deep[4012];
  memcpy(deep, "[\"[[[[\",", 8);
  memset(deep + 8, '[', 2000);
  memset(deep + 2008, ']', 2001);
  deep[4009] = '\0';
  write_bytes(f, "deep.json", deep, 4009, path, sizeof path);
  load_fails(path, GLINT_E_PARSE,
             ":1:108: JSON syntax error: arrays and objects nested deeper "
             "than 100 levels");
  /* ... unless a syntax error comes before it */
  memcpy(deep, "[1,}", 4);
  memset(deep + 4, '[', 2000);
  write_bytes(f, "deep-after-error.json", deep, 2004, path, sizeof path);
  load_fails(path, GLINT_E_PARSE,
             ":1:4: JSON syntax error: found '}' after a comma");
}

/* A file nested 999 deep loads (and is refused) on a thread of 64 KiB of
 * stack, whatever comes before the nesting: cJSON never parses deeper than
 * 100 levels (it parsed the whole text when a problem it lets pass, such
 * as 01 or a tab in a string, came first, and its recursion overflowed the
 * stack). */
typedef struct small_load {
  const char *path;
  glint_status status;
  char message[sizeof((glint_error *)0)->message];
} small_load;

static void *load_on_a_small_stack(void *p) {
  small_load *l = p;
  glint_scene *s = NULL;
  glint_error e;
  l->status = glint_scene_load(l->path, &s, &e);
  snprintf(l->message, sizeof l->message, "%s", l->status ? e.message : "");
  glint_scene_destroy(s);
  return NULL;
}

static void deep_nesting_on_a_small_stack(void **state) {
  const fixture *f = *state;
  static const struct {
    const char *start, *said;
  } cases[] = {
      {"{\"a\": 01, \"b\": ", ":1:7: JSON syntax error: "},
      {"{\"a\": \"x\ty\", \"b\": ", ":1:9: JSON syntax error: a control"},
      {"{\"a\": \"x\ny\", \"b\": ", ": JSON syntax error: "},
      {"{\"a\": \"x\\\"[[[[\", \"b\": ", ":1:122: JSON syntax error: arrays"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    char text[1100], path[256];
    size_t n = strlen(cases[i].start);
    memcpy(text, cases[i].start, n);
    memset(text + n, '[', 999);
    write_bytes(f, "deep-small.json", text, n + 999, path, sizeof path);
    small_load l = {path, GLINT_OK, ""};
    pthread_attr_t attr;
    pthread_t thread;
    assert_int_equal(pthread_attr_init(&attr), 0);
    assert_int_equal(pthread_attr_setstacksize(&attr, (size_t)64 << 10), 0);
    assert_int_equal(pthread_create(&thread, &attr, load_on_a_small_stack, &l),
                     0);
    pthread_join(thread, NULL);
    pthread_attr_destroy(&attr);
    assert_int_equal(l.status, GLINT_E_PARSE);
    if (!strstr(l.message, cases[i].said))
      fail_msg("case %zu: '%s' lacks '%s'", i, l.message, cases[i].said);
  }
}

static void structure_errors_give_the_json_path(void **state) {
  const fixture *f = *state;
  run_cases(f, structure_cases,
            sizeof structure_cases / sizeof structure_cases[0]);

  /* A long name is cut in the message. */
  char json[512], name[201], path[256];
  memset(name, 'x', 200);
  name[0] = ' '; /* not a plain name: quoted in the path */
  name[200] = '\0';
  snprintf(json, sizeof json, "{'materials': {'%s': {'kd': -1}}}", name);
  write_json(f, "long.json", json, path, sizeof path);
  load_fails(path, GLINT_E_PARSE, ": materials[\" xxxxxxxxxx");
  glint_error e;
  glint_scene *s = NULL;
  assert_int_equal(glint_scene_load(path, &s, &e), GLINT_E_PARSE);
  if (!strstr(e.message, "xxx\"...]: material kd = -1"))
    fail_msg("the long name is not cut: %s", e.message);
}

static void unreadable_files_are_io_errors(void **state) {
  const fixture *f = *state;
  char path[256];
  snprintf(path, sizeof path, "%s/no-such-scene.json", f->dir);
  load_fails(path, GLINT_E_IO, ": No such file or directory");
  snprintf(path, sizeof path, "%s/folder.json", f->dir);
  assert_int_equal(mkdir(path, 0700), 0);
  load_fails(path, GLINT_E_IO, ": not a regular file");
  /* The extension is matched without regard to case. */
  write_json(f, "UPPER.JSON", "{'background': [0, 0, 1]}", path, sizeof path);
  glint_scene *s;
  ASSERT_OK(glint_scene_load(path, &s, &e_));
  assert_true(s->background.z == 1);
  glint_scene_destroy(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(every_construct_reads),
      cmocka_unit_test(defaults_are_the_librarys),
      cmocka_unit_test(scene_files_are_the_builtins),
      cmocka_unit_test(meshes_resolve_beside_the_scene),
      cmocka_unit_test(syntax_errors_give_line_and_column),
      cmocka_unit_test(deep_nesting_on_a_small_stack),
      cmocka_unit_test(structure_errors_give_the_json_path),
      cmocka_unit_test(unreadable_files_are_io_errors),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
