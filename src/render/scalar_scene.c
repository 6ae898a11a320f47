/* Preparing and querying a scene for the scalar tracer. Compiled once per
 * precision (see math/real.h). */
#include "render/scalar_scene.h"

#include "render/backend.h"

#include "core/error.h"
#include "core/memory.h"
#include "render/scalar_rays.h"
#include "scene/scene.h"

#include <math.h>
#include <stdlib.h>

static vec3 from_d(glint_vec3 v) { return v3((real)v.x, (real)v.y, (real)v.z); }

static glint_vec3 dsub(glint_vec3 a, glint_vec3 b) {
  glint_vec3 r = {a.x - b.x, a.y - b.y, a.z - b.z};
  return r;
}

static glint_vec3 dcross(glint_vec3 a, glint_vec3 b) {
  glint_vec3 r = {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                  a.x * b.y - a.y * b.x};
  return r;
}

/* The two world axes least aligned with n: a planar checker on a floor
 * (n = +y) is indexed by x and z, exactly as docs/specification.md §8 writes
 * it. */
static void planar_axes(glint_vec3 n, int *u, int *v) {
  double ax = fabs(n.x), ay = fabs(n.y), az = fabs(n.z);
  if (ay >= ax && ay >= az)
    *u = 0, *v = 2;
  else if (ax >= az)
    *u = 1, *v = 2;
  else
    *u = 0, *v = 1;
}

/* The view of a world converted without a BVH, and of --accel none. */
static const gli_bvh no_bvh;

/* Whether a light may lie inside an object that lets light through and
 * absorbs it: inside the box of its primitives, or behind such a plane.
 * Only then can a shadow ray enter an object it does not leave, and need
 * the stretch to the light (shadow_acc, render/scalar_rays.h); elsewhere
 * that accounting is skipped (it cost the beams 1.5% of Whitted's
 * instructions, where the light is outside the glass). */
static int light_may_be_inside_absorber(const glint_scene *g) {
  for (size_t i = 0; i < g->object_count; i++) {
    const gli_object *o = &g->objects[i];
    const glint_material *m = &g->materials[o->material];
    if (m->kt <= 0 ||
        (m->absorb.x == 0 && m->absorb.y == 0 && m->absorb.z == 0))
      continue;
    if (o->shape == GLI_SHAPE_PLANE)
      return 1; /* a half-space: rare enough to take as yes */
    /* its primitives' boxes as the BVH builder bounds them */
    float lo[3] = {INFINITY, INFINITY, INFINITY},
          hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t k = o->first; k < o->first + o->count; k++) {
      float plo[3], phi[3];
      gli_bvh_ref_box(g, GLI_REF(o->shape, k), plo, phi);
      for (int a = 0; a < 3; a++)
        lo[a] = fminf(lo[a], plo[a]), hi[a] = fmaxf(hi[a], phi[a]);
    }
    for (size_t j = 0; j < g->light_count; j++) {
      glint_vec3 p = g->lights[j].position;
      if (p.x >= lo[0] && p.x <= hi[0] && p.y >= lo[1] && p.y <= hi[1] &&
          p.z >= lo[2] && p.z <= hi[2])
        return 1;
    }
  }
  return 0;
}

glint_status scalar_scene_prepare(const glint_scene *g, double eps,
                                  scene_r **out, glint_error *error) {
  scene_r *s = calloc(1, sizeof *s);
  if (!s)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  s->sphere_count = g->sphere_count;
  s->plane_count = g->plane_count;
  s->triangle_count = g->triangle_count;
  s->light_count = g->light_count;
  s->normal_count = g->tri_normal_count;
  s->object_count = g->object_count;
  s->material_count = g->material_count;
  s->spheres = gli_aligned_calloc(g->sphere_count, sizeof *s->spheres);
  s->planes = gli_aligned_calloc(g->plane_count, sizeof *s->planes);
  s->triangles = gli_aligned_calloc(g->triangle_count, sizeof *s->triangles);
  s->cone_count = g->cone_count;
  s->cones = gli_aligned_calloc(g->cone_count, sizeof *s->cones);
  s->normals = gli_aligned_calloc(g->tri_normal_count, sizeof *s->normals);
  s->objects = gli_aligned_calloc(g->object_count, sizeof *s->objects);
  s->materials = gli_aligned_calloc(g->material_count, sizeof *s->materials);
  s->lights = gli_aligned_calloc(g->light_count, sizeof *s->lights);
  if (!s->spheres || !s->planes || !s->triangles || !s->cones || !s->normals ||
      !s->objects || !s->materials || !s->lights) {
    scalar_scene_release(s);
    return gli_fail(error, GLINT_E_MEMORY,
                    "out of memory preparing the "
                    "scene");
  }

  for (size_t i = 0; i < g->sphere_count; i++) {
    const gli_sphere_prim *p = &g->spheres[i];
    s->spheres[i] =
        (sphere_r){from_d(p->center), (real)(p->radius * p->radius), p->object};
  }
  for (size_t i = 0; i < g->plane_count; i++) {
    const gli_plane_prim *p = &g->planes[i];
    s->planes[i] = (plane_r){from_d(p->normal), (real)p->d, p->object};
  }
  /* The triangles' origin R: the centre of their bounds, rounded to this
   * precision so that the rays' L and the edges' moments share it. */
  glint_vec3 lo = {INFINITY, INFINITY, INFINITY},
             hi = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < g->triangle_count; i++)
    for (int k = 0; k < 3; k++)
      gli_bounds_grow(&lo, &hi, g->triangles[i].v[k], 0.0);
  s->tri_origin = g->triangle_count ? v3((real)(0.5 * (lo.x + hi.x)),
                                         (real)(0.5 * (lo.y + hi.y)),
                                         (real)(0.5 * (lo.z + hi.z)))
                                    : v3(0, 0, 0);
  glint_vec3 r = {s->tri_origin.x, s->tri_origin.y, s->tri_origin.z};
  for (size_t i = 0; i < g->triangle_count; i++) {
    const gli_triangle_prim *p = &g->triangles[i];
    /* Edges, moments and normal in double, then rounded once. */
    glint_vec3 v[3] = {p->v[0], p->v[1], p->v[2]};
    glint_vec3 e1 = dsub(v[1], v[0]), e2 = dsub(v[2], v[0]);
    glint_vec3 n = dcross(e1, e2);
    double nl = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    triangle_r *t = &s->triangles[i];
    t->a = from_d(v[0]);
    if (nl > 0 && isfinite(nl)) {
      for (int k = 0; k < 3; k++) {
        glint_vec3 from = v[k], to = v[(k + 1) % 3];
        t->edge[k] = from_d(dsub(to, from));
        t->moment[k] = from_d(dcross(dsub(from, r), dsub(to, r)));
      }
      t->ng = v3((real)(n.x / nl), (real)(n.y / nl), (real)(n.z / nl));
      /* N's length is the square of the triangle's size, and triangle_hit's
       * N·(A - O) its cube: edges of 1e13 seen from 1e12 away overflow a
       * float there (1e39), and the triangle vanished. t is a ratio of
       * two products with N, so N is stored scaled by a power of two to a
       * length in [0.5, 1): exact, t unchanged to the bit wherever it did
       * not overflow or underflow. */
      int exponent;
      frexp(nl, &exponent);
      /* (one ldexp, not three: a power of two's product rounds as ldexp
       * does, and the three calls were over a quarter of this loop's
       * instructions) */
      double scale = ldexp(1.0, -exponent);
      if (exponent > -1000 && exponent < 1000)
        t->n = from_d((glint_vec3){n.x * scale, n.y * scale, n.z * scale});
      else
        t->n = from_d((glint_vec3){ldexp(n.x, -exponent), ldexp(n.y, -exponent),
                                   ldexp(n.z, -exponent)});
    } /* else degenerate: zero edges and normal, never hit */
    t->object = p->object;
    t->normals = p->normals;
  }
  for (size_t i = 0; i < g->cone_count; i++) {
    const gli_cone_prim *c = &g->cones[i];
    glint_vec3 a = {c->apex.x - c->base.x, c->apex.y - c->base.y,
                    c->apex.z - c->base.z};
    double h = sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    cone_r *r = &s->cones[i];
    r->base = from_d(c->base);
    r->axis = v3((real)(a.x / h), (real)(a.y / h), (real)(a.z / h));
    r->height = (real)h;
    r->rb = (real)c->base_radius;
    r->k = (real)((c->apex_radius - c->base_radius) / h);
    double widest = fmax(fabs(c->base_radius), fabs(c->apex_radius));
    r->reach2 = (real)(1.07 * widest * widest);
    r->object = c->object;
  }
  for (size_t i = 0; i < g->tri_normal_count; i++)
    s->normals[i] = from_d(g->tri_normals[i]);
  for (size_t i = 0; i < g->material_count; i++) {
    const glint_material *m = &g->materials[i];
    material_r *r = &s->materials[i];
    r->color = from_d(m->color);
    r->odd = from_d(m->checker_odd);
    r->even = from_d(m->checker_even);
    r->inv_size = (real)(1.0 / m->checker_size);
    r->ka = (real)m->ka, r->kd = (real)m->kd, r->ks = (real)m->ks;
    r->h = (real)m->h, r->kr = (real)m->kr, r->kt = (real)m->kt;
    r->ior = (real)m->ior;
    r->absorb = from_d(m->absorb);
    r->texture = (int)m->texture;
    r->absorbs =
        (m->absorb.x != 0) | (m->absorb.y != 0) << 1 | (m->absorb.z != 0) << 2;
  }
  for (size_t i = 0; i < g->object_count; i++) {
    const gli_object *o = &g->objects[i];
    object_r *r = &s->objects[i];
    r->material = o->material;
    r->shape = o->shape;
    r->first = o->first;
    r->count = o->count;
    r->smooth = o->shape == GLI_SHAPE_TRIANGLE && o->count > 0 &&
                g->triangles[o->first].normals != GLI_NO_NORMALS;
    r->origin = from_d(o->origin);
    glint_vec3 n = {0, 1, 0};
    if (o->shape == GLI_SHAPE_PLANE)
      n = g->planes[o->first].normal;
    planar_axes(n, &r->axis_u, &r->axis_v);
  }
  for (size_t i = 0; i < g->light_count; i++)
    s->lights[i] =
        (light_r){from_d(g->lights[i].position), from_d(g->lights[i].color)};

  s->lights_in_absorbers = light_may_be_inside_absorber(g);
  s->background = from_d(g->background);
  s->ambient = from_d(g->ambient);
  s->eps = (real)eps;
  s->bvh = &no_bvh;
  *out = s;
  return GLINT_OK;
}

size_t scalar_scene_bytes(const scene_r *s) {
  return sizeof *s + s->sphere_count * sizeof *s->spheres +
         s->plane_count * sizeof *s->planes +
         s->triangle_count * sizeof *s->triangles +
         s->cone_count * sizeof *s->cones +
         s->normal_count * sizeof *s->normals +
         s->object_count * sizeof *s->objects +
         s->material_count * sizeof *s->materials +
         s->light_count * sizeof *s->lights;
}

void scalar_scene_release(scene_r *s) {
  if (!s)
    return;
  gli_aligned_free(s->spheres);
  gli_aligned_free(s->planes);
  gli_aligned_free(s->triangles);
  gli_aligned_free(s->cones);
  gli_aligned_free(s->normals);
  gli_aligned_free(s->objects);
  gli_aligned_free(s->materials);
  gli_aligned_free(s->lights);
  free(s);
}

/* ---- the queries (render/scalar_rays.h) -------------------------------- */

int scalar_nearest_hit(const scene_r *s, const vec3 *o, const vec3 *d,
                       real tmax, hit_r *hit) {
  return ray_nearest(s, *o, *d, tmax, hit);
}

vec3 scalar_transmission(const scene_r *s, const vec3 *o, const vec3 *d,
                         real dist) {
  return ray_transmission(s, *o, *d, dist);
}

/* ---- the world's conversion and a renderer's view (render/backend.h) ---- */

static glint_status convert(const glint_scene *g, double eps, void **data,
                            glint_error *error) {
  scene_r *s = NULL;
  glint_status st = scalar_scene_prepare(g, eps, &s, error);
  *data = s;
  return st;
}

static void release(void *data) { scalar_scene_release(data); }

static size_t bytes(const void *data) { return scalar_scene_bytes(data); }

static glint_status bind(const void *data, const gli_bvh *bvh,
                         glint_accel accel, void **view, glint_error *error) {
  scene_r *v = malloc(sizeof *v);
  if (!v)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  *v = *(const scene_r *)data;
  v->bvh = bvh;
  v->walk_wide = accel == GLINT_ACCEL_BVH8 && bvh->wide.nodes;
  *view = v;
  return GLINT_OK;
}

static void unbind(void *view) { free(view); }

static void set_epsilon(void *view, double eps) {
  ((scene_r *)view)->eps = (real)eps;
}

const data_ops REAL_NAME(gli_scalar_data) = {convert, release, bytes,
                                             bind,    unbind,  set_epsilon};
