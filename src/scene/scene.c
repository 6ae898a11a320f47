/* Building a scene through the public API, with every argument checked: a
 * NaN or an infinity never reaches a tracer. */
#include "scene/scene.h"

#include "core/error.h"
#include "core/memory.h"
#include "scene/polygon.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The triangles a scene holds (their indices are 32-bit). */
#define GLI_MAX_MESH_TRIANGLES (UINT32_MAX - 1)

int gli_vec3_finite(glint_vec3 v) {
  return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

int gli_in_range(double x) { return fabs(x) <= GLINT_MAX_COORDINATE; }

int gli_vec3_in_range(glint_vec3 v) {
  return gli_in_range(v.x) && gli_in_range(v.y) && gli_in_range(v.z);
}

static double vlen(glint_vec3 v) {
  return sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

static glint_vec3 vsub(glint_vec3 a, glint_vec3 b) {
  return (glint_vec3){a.x - b.x, a.y - b.y, a.z - b.z};
}

static glint_vec3 vcross(glint_vec3 a, glint_vec3 b) {
  return (glint_vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                      a.x * b.y - a.y * b.x};
}

void glint_material_default(glint_material *m) {
  if (!m)
    return;
  memset(m, 0, sizeof *m);
  m->color = (glint_vec3){1, 1, 1};
  m->checker_odd = (glint_vec3){1, 1, 1};
  m->checker_even = (glint_vec3){0, 0, 0};
  m->checker_size = 1;
  m->ka = 0.1;
  m->kd = 0.9;
  m->h = 1;
  m->ior = 1;
}

glint_status glint_scene_create(glint_scene **out, glint_error *error) {
  GLI_NOT_NULL(out, "scene", error);
  glint_scene *s = calloc(1, sizeof *s);
  if (!s)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory creating a scene");
  s->camera = (glint_camera){{0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 60};
  s->width = 640;
  s->height = 480;
  s->ambient = (glint_vec3){1, 1, 1};
  s->ear_tests_left = GLI_SCENE_EAR_TESTS;
  *out = s;
  return GLINT_OK;
}

void glint_scene_destroy(glint_scene *s) {
  if (!s)
    return;
  free(s->lights);
  free(s->materials);
  free(s->objects);
  free(s->spheres);
  free(s->planes);
  free(s->triangles);
  free(s->tri_normals);
  free(s->cones);
  gli_animation_free(&s->animation);
  free(s);
}

static glint_status oom(glint_error *error) {
  return gli_fail(error, GLINT_E_MEMORY, "out of memory building the scene");
}

glint_status gli_camera_check_field(const glint_camera *c,
                                    gli_camera_field *field,
                                    glint_error *error) {
  *field = !gli_vec3_in_range(c->from) ? GLI_CAMERA_FROM
           : !gli_vec3_in_range(c->at) ? GLI_CAMERA_AT
           : !gli_vec3_in_range(c->up) ? GLI_CAMERA_UP
                                       : GLI_CAMERA_FOV;
  if (*field != GLI_CAMERA_FOV)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "camera: coordinates must be " GLI_RANGE_TEXT);
  if (!isfinite(c->fov_x_degrees))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "camera: the field of view is not a finite number");
  if (!(c->fov_x_degrees > 0 && c->fov_x_degrees < 180))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "camera: field of view %g is not between 0 and 180 "
                    "degrees",
                    c->fov_x_degrees);
  *field = GLI_CAMERA_AT;
  glint_vec3 d = vsub(c->at, c->from);
  if (vlen(d) == 0)
    return gli_fail(error, GLINT_E_ARGUMENT, "camera: 'from' and 'at' are %s",
                    d.x == 0 && d.y == 0 && d.z == 0
                        ? "the same point"
                        : "too close for a direction between them");
  *field = GLI_CAMERA_UP;
  /* up scaled to a largest component of 1, as the camera's basis does (an
   * up of 1e-300 was "zero or parallel": its cross product underflowed) */
  double um = fmax(fabs(c->up.x), fmax(fabs(c->up.y), fabs(c->up.z)));
  glint_vec3 up = {c->up.x / um, c->up.y / um, c->up.z / um};
  double dl = vlen(d), ul = um > 0 ? vlen(up) : 0;
  if (ul == 0 || vlen(vcross(d, up)) <= 1e-9 * dl * ul)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "camera: 'up' is zero or parallel to the view "
                    "direction");
  return GLINT_OK;
}

glint_status gli_camera_check(const glint_camera *c, glint_error *error) {
  gli_camera_field unused;
  return gli_camera_check_field(c, &unused, error);
}

glint_status glint_camera_check(const glint_camera *c, glint_error *error) {
  GLI_NOT_NULL(c, "camera", error);
  return gli_camera_check(c, error);
}

glint_status glint_scene_set_camera(glint_scene *s, const glint_camera *c,
                                    glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  GLI_NOT_NULL(c, "camera", error);
  glint_status st = gli_camera_check(c, error);
  if (st)
    return st;
  s->camera = *c;
  return GLINT_OK;
}

glint_status glint_scene_set_resolution(glint_scene *s, int w, int h,
                                        glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  if (w < 1 || h < 1 || w > GLINT_MAX_DIMENSION || h > GLINT_MAX_DIMENSION)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "resolution %dx%d is outside 1..%d", w, h,
                    GLINT_MAX_DIMENSION);
  s->width = w;
  s->height = h;
  return GLINT_OK;
}

static glint_status check_color(glint_vec3 c, const char *what,
                                glint_error *error) {
  if (!gli_vec3_finite(c))
    return gli_fail(error, GLINT_E_ARGUMENT, "%s must be finite", what);
  if (c.x < 0 || c.y < 0 || c.z < 0)
    return gli_fail(error, GLINT_E_ARGUMENT, "%s must not be negative", what);
  if (c.x > GLINT_MAX_COLOR || c.y > GLINT_MAX_COLOR || c.z > GLINT_MAX_COLOR)
    return gli_fail(error, GLINT_E_ARGUMENT, "%s must not exceed %g", what,
                    GLINT_MAX_COLOR);
  return GLINT_OK;
}

static glint_status set_color(glint_vec3 *field, glint_vec3 c, const char *what,
                              glint_error *error) {
  glint_status st = check_color(c, what, error);
  if (st == GLINT_OK)
    *field = c;
  return st;
}

glint_status glint_scene_set_background(glint_scene *s, glint_vec3 c,
                                        glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  return set_color(&s->background, c, "background colour", error);
}

glint_status glint_scene_set_ambient(glint_scene *s, glint_vec3 c,
                                     glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  return set_color(&s->ambient, c, "ambient light", error);
}

glint_status glint_scene_add_light(glint_scene *s, glint_vec3 p, glint_vec3 c,
                                   glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  if (!gli_vec3_in_range(p))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "light position must be " GLI_RANGE_TEXT);
  glint_status st = check_color(c, "light colour", error);
  if (st != GLINT_OK)
    return st;
  gli_light l = {p, c};
  return GLI_PUSH(s->lights, s->light_count, s->light_cap, l) ? oom(error)
                                                              : GLINT_OK;
}

glint_status glint_scene_add_material(glint_scene *s, const glint_material *m,
                                      uint32_t *id, glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  GLI_NOT_NULL(m, "material", error);
  glint_status st;
  if ((st = check_color(m->color, "material colour", error)) ||
      (st = check_color(m->checker_odd, "checker colour", error)) ||
      (st = check_color(m->checker_even, "checker colour", error)) ||
      (st = check_color(m->absorb, "absorbance", error)))
    return st;
  const double k[] = {m->ka, m->kd, m->ks, m->h, m->kr, m->kt};
  const char *names[] = {"ka", "kd", "ks", "h", "kr", "kt"};
  for (int i = 0; i < 6; i++)
    if (!isfinite(k[i]) || k[i] < 0)
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "material %s = %g must be a finite number >= 0", names[i],
                      k[i]);
    else if (k[i] > GLINT_MAX_COLOR && i != 3) /* the exponent h aside */
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "material %s = %g must not exceed %g", names[i], k[i],
                      GLINT_MAX_COLOR);
  if (!isfinite(m->ior) || m->ior <= 0)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "material ior = %g must be a finite number > 0", m->ior);
  if (m->ior < 1 / GLINT_MAX_COLOR || m->ior > GLINT_MAX_COLOR)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "material ior = %g is outside %g..%g", m->ior,
                    1 / GLINT_MAX_COLOR, GLINT_MAX_COLOR);
  if (m->texture != GLINT_TEXTURE_NONE &&
      m->texture != GLINT_TEXTURE_CHECKER_PLANAR &&
      m->texture != GLINT_TEXTURE_CHECKER_SOLID)
    return gli_fail(error, GLINT_E_ARGUMENT, "unknown texture kind %d",
                    (int)m->texture);
  /* Cells finer than a millionth are below a float coordinate's resolution
   * (the SIMD backends' cell of a point disagreed with scalar-double's),
   * and past 1e15 wider than any scene: from 1e38 the float backends'
   * 1/size was 0, one colour everywhere. */
  if (m->texture != GLINT_TEXTURE_NONE &&
      !(m->checker_size >= GLINT_MIN_CHECKER && gli_in_range(m->checker_size)))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "checker size %g is outside %g..%g", m->checker_size,
                    GLINT_MIN_CHECKER, GLINT_MAX_COORDINATE);
  if (s->material_count >= UINT32_MAX)
    return gli_fail(error, GLINT_E_ARGUMENT, "too many materials");
  if (GLI_PUSH(s->materials, s->material_count, s->material_cap, *m))
    return oom(error);
  if (id)
    *id = (uint32_t)(s->material_count - 1);
  return GLINT_OK;
}

glint_status gli_scene_begin_object(glint_scene *s, gli_shape shape,
                                    uint32_t material, glint_error *error) {
  if (material >= s->material_count)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "material %u does not exist (the scene has %zu)", material,
                    s->material_count);
  if (s->object_count >= UINT32_MAX - 1)
    return gli_fail(error, GLINT_E_ARGUMENT, "too many objects");
  size_t first = 0;
  switch (shape) {
  case GLI_SHAPE_SPHERE: first = s->sphere_count; break;
  case GLI_SHAPE_TRIANGLE: first = s->triangle_count; break;
  case GLI_SHAPE_CONE: first = s->cone_count; break;
  case GLI_SHAPE_PLANE: first = s->plane_count; break;
  }
  if (first >= UINT32_MAX)
    return gli_fail(error, GLINT_E_ARGUMENT, "too many primitives");
  gli_object o = {material, (uint32_t)shape, (uint32_t)first, 0, {0, 0, 0}};
  return GLI_PUSH(s->objects, s->object_count, s->object_cap, o) ? oom(error)
                                                                 : GLINT_OK;
}

glint_status glint_scene_add_sphere(glint_scene *s, glint_vec3 c, double r,
                                    uint32_t material, glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  if (!gli_vec3_in_range(c) || !gli_in_range(r))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "sphere: centre and radius must be " GLI_RANGE_TEXT);
  if (!(r > 0))
    return gli_fail(error, GLINT_E_ARGUMENT, "sphere: radius %g must be > 0",
                    r);
  glint_status st =
      gli_scene_begin_object(s, GLI_SHAPE_SPHERE, material, error);
  if (st)
    return st;
  gli_object *o = &s->objects[s->object_count - 1];
  gli_sphere_prim p = {c, r, (uint32_t)(s->object_count - 1)};
  if (GLI_PUSH(s->spheres, s->sphere_count, s->sphere_cap, p)) {
    s->object_count--;
    return oom(error);
  }
  o->count = 1;
  o->origin = c;
  return GLINT_OK;
}

glint_status glint_scene_add_plane(glint_scene *s, glint_vec3 n, glint_vec3 p,
                                   uint32_t material, glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  if (!gli_vec3_in_range(n) || !gli_vec3_in_range(p))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "plane: coordinates must be " GLI_RANGE_TEXT);
  /* scaled by its largest component first: a normal of any length, even
   * one whose squared length underflows (1e-200), has a direction */
  double big = fmax(fabs(n.x), fmax(fabs(n.y), fabs(n.z)));
  if (!(big > 0))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "plane: the normal must not be zero");
  glint_vec3 ns = {n.x / big, n.y / big, n.z / big};
  double len = vlen(ns);
  glint_status st = gli_scene_begin_object(s, GLI_SHAPE_PLANE, material, error);
  if (st)
    return st;
  glint_vec3 u = {ns.x / len, ns.y / len, ns.z / len};
  gli_plane_prim pl = {u, -(u.x * p.x + u.y * p.y + u.z * p.z),
                       (uint32_t)(s->object_count - 1)};
  if (GLI_PUSH(s->planes, s->plane_count, s->plane_cap, pl)) {
    s->object_count--;
    return oom(error);
  }
  s->objects[s->object_count - 1].count = 1;
  return GLINT_OK;
}

glint_status gli_scene_check_triangle(glint_vec3 a, glint_vec3 b, glint_vec3 c,
                                      const glint_vec3 normals[3],
                                      glint_error *error) {
  if (!gli_vec3_in_range(a) || !gli_vec3_in_range(b) || !gli_vec3_in_range(c))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "triangle: coordinates must be " GLI_RANGE_TEXT);
  for (int i = 0; normals && i < 3; i++)
    if (!gli_vec3_in_range(normals[i]))
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "vertex normals must be " GLI_RANGE_TEXT);
  return GLINT_OK;
}

glint_status gli_scene_push_triangle(glint_scene *s, glint_vec3 a, glint_vec3 b,
                                     glint_vec3 c, const glint_vec3 normals[3],
                                     glint_error *error) {
  glint_status st = gli_scene_check_triangle(a, b, c, normals, error);
  return st ? st : gli_scene_append_triangle(s, a, b, c, normals, error);
}

glint_status gli_scene_append_triangle(glint_scene *s, glint_vec3 a,
                                       glint_vec3 b, glint_vec3 c,
                                       const glint_vec3 normals[3],
                                       glint_error *error) {
  gli_object *o = &s->objects[s->object_count - 1];
  if (s->triangle_count >= GLI_MAX_MESH_TRIANGLES)
    return gli_fail(error, GLINT_E_ARGUMENT, "too many triangles");
  gli_triangle_prim t = {
      {a, b, c}, (uint32_t)(s->object_count - 1), GLI_NO_NORMALS};
  if (normals) {
    if (s->tri_normal_count >= UINT32_MAX - 3)
      return gli_fail(error, GLINT_E_ARGUMENT, "too many normals");
    if (gli_grow((void **)&s->tri_normals, &s->tri_normal_cap,
                 s->tri_normal_count + 3, sizeof *s->tri_normals))
      return oom(error);
    t.normals = (uint32_t)s->tri_normal_count;
    for (int i = 0; i < 3; i++) {
      glint_vec3 nv = normals[i];
      double l = vlen(nv);
      /* A zero normal falls back to the face normal at shading time. */
      s->tri_normals[s->tri_normal_count++] =
          l > 0 ? (glint_vec3){nv.x / l, nv.y / l, nv.z / l} : nv;
    }
  }
  if (GLI_PUSH(s->triangles, s->triangle_count, s->triangle_cap, t))
    return oom(error);
  o->count++;
  return GLINT_OK;
}

/* A mesh's triangles in the order of their centroids along a Morton
 * (Z-order) curve, 10 bits an axis within the mesh's bounds: triangles
 * near one another in space are near in memory, so the BVH's leaves, which
 * gather neighbours, read neighbouring records. A scanner's or a modeller's
 * file order need not be so: the 200k-triangle dragon's primary rays
 * waited on the triangle records that leaves named (the costliest
 * instruction of the walk) and ran 5% faster so ordered. A mesh's order
 * is nowhere else visible: messages name a triangle by its place in the
 * file, checked before this. No memory: the file's order, still correct. */
static uint32_t morton_spread(uint32_t v) { /* bit k to bit 3k */
  v &= 0x3ff;
  v = (v | (v << 16)) & 0x030000ff;
  v = (v | (v << 8)) & 0x0300f00f;
  v = (v | (v << 4)) & 0x030c30c3;
  return (v | (v << 2)) & 0x09249249;
}

/* Three times the centroid of the triangle of vertices v[0..2]. */
static void centroid3(const glint_vec3 *pos, const uint32_t *v, double c[3]) {
  c[0] = pos[v[0]].x + pos[v[1]].x + pos[v[2]].x;
  c[1] = pos[v[0]].y + pos[v[1]].y + pos[v[2]].y;
  c[2] = pos[v[0]].z + pos[v[1]].z + pos[v[2]].z;
}

/* Sorts the n keys in `a` by their top 32 bits, of which the low 30 are
 * used, in three stable passes of 10 bits (least significant first)
 * between a and b; returns the one holding the result. */
static const uint64_t *radix_sort30(uint64_t *a, uint64_t *b, size_t n) {
  for (int shift = 32; shift < 62; shift += 10) {
    size_t start[1024] = {0};
    for (size_t i = 0; i < n; i++)
      start[(a[i] >> shift) & 1023]++;
    size_t sum = 0;
    for (int k = 0; k < 1024; k++) {
      size_t c = start[k];
      start[k] = sum;
      sum += c;
    }
    for (size_t i = 0; i < n; i++)
      b[start[(a[i] >> shift) & 1023]++] = a[i];
    uint64_t *t = a;
    a = b;
    b = t;
  }
  return a;
}

uint32_t *gli_morton_order(const glint_vec3 *pos, const uint32_t *triples,
                           size_t count) {
  if (count < GLI_MORTON_MIN_TRIANGLES || count > UINT32_MAX)
    return NULL;
  uint64_t *keys = malloc(2 * count * sizeof *keys);
  uint32_t *order = malloc(count * sizeof *order);
  if (!keys || !order) {
    free(keys);
    free(order);
    return NULL;
  }
  /* centroids (times 3) and their bounds */
  double lo[3] = {INFINITY, INFINITY, INFINITY};
  double hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < count; i++) {
    double c[3];
    centroid3(pos, &triples[3 * i], c);
    for (int a = 0; a < 3; a++) {
      lo[a] = c[a] < lo[a] ? c[a] : lo[a];
      hi[a] = c[a] > hi[a] ? c[a] : hi[a];
    }
  }
  for (size_t i = 0; i < count; i++) {
    double c[3];
    centroid3(pos, &triples[3 * i], c);
    uint32_t code = 0;
    for (int a = 0; a < 3; a++) {
      /* The API's meshes come here unchecked: a NaN or an infinity goes
       * to a cell, as any number does (the push refuses it later). */
      double f = (c[a] - lo[a]) / (hi[a] - lo[a]);
      uint32_t cell = !(f > 0) ? 0 : f < 1 ? (uint32_t)(f * 1023) : 1023;
      code |= morton_spread(cell) << a;
    }
    keys[i] = (uint64_t)code << 32 | i; /* ties keep the file's order */
  }
  const uint64_t *sorted = radix_sort30(keys, keys + count, count);
  for (size_t i = 0; i < count; i++)
    order[i] = (uint32_t)sorted[i];
  free(keys);
  return order;
}

glint_status glint_scene_add_triangle(glint_scene *s, glint_vec3 a,
                                      glint_vec3 b, glint_vec3 c,
                                      uint32_t material, glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  if (!gli_vec3_in_range(a) || !gli_vec3_in_range(b) || !gli_vec3_in_range(c))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "triangle: coordinates must be " GLI_RANGE_TEXT);
  glint_status st =
      gli_scene_begin_object(s, GLI_SHAPE_TRIANGLE, material, error);
  if (st)
    return st;
  st = gli_scene_push_triangle(s, a, b, c, NULL, error);
  if (st)
    s->object_count--;
  return st;
}

glint_status glint_scene_add_cone(glint_scene *s, glint_vec3 base, double rb,
                                  glint_vec3 apex, double ra, uint32_t material,
                                  glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  if (!gli_vec3_in_range(base) || !gli_vec3_in_range(apex) ||
      !gli_in_range(rb) || !gli_in_range(ra))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "cone: coordinates and radii must be " GLI_RANGE_TEXT);
  if (rb < 0 || ra < 0)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "cone: radii %g and %g must be >= 0", rb, ra);
  if (rb == 0 && ra == 0) /* (the message said ">= 0" of two zeros) */
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "cone: both radii are 0: it has no surface");
  glint_vec3 axis = vsub(apex, base);
  if (vlen(axis) == 0)
    return gli_fail(error, GLINT_E_ARGUMENT, "cone: base and apex are %s",
                    axis.x == 0 && axis.y == 0 && axis.z == 0
                        ? "the same point"
                        : "too close for an axis between them");
  glint_status st = gli_scene_begin_object(s, GLI_SHAPE_CONE, material, error);
  if (st)
    return st;
  gli_cone_prim p = {base, apex, rb, ra, (uint32_t)(s->object_count - 1)};
  if (GLI_PUSH(s->cones, s->cone_count, s->cone_cap, p)) {
    s->object_count--;
    return oom(error);
  }
  s->objects[s->object_count - 1].count = 1;
  return GLINT_OK;
}

glint_status glint_scene_add_mesh(glint_scene *s, const glint_mesh *m,
                                  uint32_t material, glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  GLI_NOT_NULL(m, "mesh", error);
  /* (an empty mesh needs no arrays, as an empty array needs no memory) */
  if (!m->positions && m->vertex_count)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "mesh: positions is NULL, but vertex_count is %zu",
                    m->vertex_count);
  if (!m->indices && m->triangle_count)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "mesh: indices is NULL, but triangle_count is %zu",
                    m->triangle_count);
  /* 3 * triangle_count must not wrap (past it the loop below would check
   * a few indices and the copy read beyond them) */
  if (m->triangle_count > GLI_MAX_MESH_TRIANGLES)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "mesh: %zu triangles, more than a scene holds (%zu)",
                    m->triangle_count, (size_t)GLI_MAX_MESH_TRIANGLES);
  for (size_t i = 0; i < 3 * m->triangle_count; i++)
    if (m->indices[i] >= m->vertex_count)
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "mesh: triangle %zu refers to vertex %u, but the "
                      "mesh has %zu",
                      i / 3, m->indices[i], m->vertex_count);
  glint_status st =
      gli_scene_begin_object(s, GLI_SHAPE_TRIANGLE, material, error);
  if (st)
    return st;
  size_t tri0 = s->triangle_count, nrm0 = s->tri_normal_count;
  uint32_t *order =
      gli_morton_order(m->positions, m->indices, m->triangle_count);
  for (size_t k = 0; k < m->triangle_count && st == GLINT_OK; k++) {
    const uint32_t *ix = &m->indices[3 * (order ? order[k] : k)];
    glint_vec3 n[3];
    if (m->normals)
      for (int c = 0; c < 3; c++)
        n[c] = m->normals[ix[c]];
    st = gli_scene_push_triangle(s, m->positions[ix[0]], m->positions[ix[1]],
                                 m->positions[ix[2]], m->normals ? n : NULL,
                                 error);
  }
  if (st) { /* leave the scene as it was */
    s->triangle_count = tri0;
    s->tri_normal_count = nrm0;
    s->object_count--;
  }
  free(order);
  return st;
}

/* For glint_scene_get_scale. An object with no extent (a triangle object
 * whose corners are one point) renders as nothing either way: it has no
 * size to compare. */
static double size_or_none(double size) { return size > 0 ? size : INFINITY; }

static double smallest_object(const glint_scene *s) {
  double least = INFINITY;
  for (size_t i = 0; i < s->sphere_count; i++)
    least = fmin(least, size_or_none(s->spheres[i].radius));
  /* A cone's height counts as well as its radius: a cone whose height is
   * near epsilon is lost as any object that small is (at h = 1e-3 and
   * epsilon 1e-3, with radius 2, the float and double backends drew it
   * differently, and the note said nothing). Its slope (rb - ra) / h alone
   * is not checked. */
  for (size_t i = 0; i < s->cone_count; i++) {
    const gli_cone_prim *c = &s->cones[i];
    least = fmin(least, size_or_none(fmin(fmax(c->base_radius, c->apex_radius),
                                          vlen(vsub(c->apex, c->base)))));
  }
  for (size_t o = 0; o < s->object_count; o++) {
    const gli_object *obj = &s->objects[o];
    if (obj->shape != GLI_SHAPE_TRIANGLE || obj->count == 0)
      continue;
    glint_vec3 lo = {INFINITY, INFINITY, INFINITY},
               hi = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = obj->first; i < obj->first + obj->count; i++)
      for (int k = 0; k < 3; k++)
        gli_bounds_grow(&lo, &hi, s->triangles[i].v[k], 0.0);
    least = fmin(
        least, size_or_none(fmax(hi.x - lo.x, fmax(hi.y - lo.y, hi.z - lo.z))));
  }
  return least;
}

void glint_scene_get_info(const glint_scene *s, glint_scene_info *info) {
  if (!info)
    return;
  if (!s) {
    memset(info, 0, sizeof *info);
    return;
  }
  info->camera = s->camera;
  info->width = s->width;
  info->height = s->height;
  info->background = s->background;
  info->ambient = s->ambient;
  info->lights = s->light_count;
  info->materials = s->material_count;
  info->objects = s->object_count;
  info->spheres = s->sphere_count;
  info->planes = s->plane_count;
  info->triangles = s->triangle_count;
  info->cones = s->cone_count;
  glint_vec3 lo = {INFINITY, INFINITY, INFINITY},
             hi = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < s->sphere_count; i++)
    gli_bounds_grow(&lo, &hi, s->spheres[i].center, s->spheres[i].radius);
  for (size_t i = 0; i < s->triangle_count; i++)
    for (int k = 0; k < 3; k++)
      gli_bounds_grow(&lo, &hi, s->triangles[i].v[k], 0.0);
  for (size_t i = 0; i < s->cone_count; i++) {
    double r = fmax(s->cones[i].base_radius, s->cones[i].apex_radius);
    gli_bounds_grow(&lo, &hi, s->cones[i].base, r);
    gli_bounds_grow(&lo, &hi, s->cones[i].apex, r);
  }
  info->bounds_min = lo;
  info->bounds_max = hi;
}

void glint_scene_get_scale(const glint_scene *s, double *epsilon,
                           double *smallest) {
  if (epsilon)
    *epsilon = s ? gli_scene_epsilon(s) : 0;
  if (smallest)
    *smallest = s ? smallest_object(s) : 0;
}

/* (gli_higher, not fmax: once per vertex) */
static double absmax3(glint_vec3 v, double m) {
  m = gli_higher(fabs(v.x), m);
  m = gli_higher(fabs(v.y), m);
  return gli_higher(fabs(v.z), m);
}

double gli_scene_epsilon(const glint_scene *s) {
  return gli_epsilon_at(gli_scene_extent(s), s->camera.from);
}

double gli_epsilon_at(double extent, glint_vec3 eye) {
  double m = absmax3(eye, extent);
  if (!(m > 1e-6))
    m = 1e-6;
  return 1e-4 * m;
}

double gli_scene_extent(const glint_scene *s) {
  double m = 0;
  for (size_t i = 0; i < s->sphere_count; i++)
    m = fmax(m, absmax3(s->spheres[i].center, 0) + s->spheres[i].radius);
  for (size_t i = 0; i < s->triangle_count; i++)
    for (int k = 0; k < 3; k++)
      m = absmax3(s->triangles[i].v[k], m);
  for (size_t i = 0; i < s->cone_count; i++) {
    const gli_cone_prim *c = &s->cones[i];
    double r = fmax(c->base_radius, c->apex_radius);
    m = fmax(m, absmax3(c->base, 0) + r);
    m = fmax(m, absmax3(c->apex, 0) + r);
  }
  return m;
}
