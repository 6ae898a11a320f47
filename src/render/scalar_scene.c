/* Preparing and querying a scene for the scalar tracer. Compiled once per
 * precision (see math/real.h). */
#include "render/scalar_scene.h"

#include "render/backend.h"

#include "core/error.h"
#include "core/memory.h"
#include "accel/traverse.h"
#include "geometry/intersect.h"
#include "scene/scene.h"

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
    for (int k = 0; k < 3; k++) {
      glint_vec3 q = g->triangles[i].v[k];
      lo.x = fmin(lo.x, q.x), lo.y = fmin(lo.y, q.y), lo.z = fmin(lo.z, q.z);
      hi.x = fmax(hi.x, q.x), hi.y = fmax(hi.y, q.y), hi.z = fmax(hi.z, q.z);
    }
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
      t->n = from_d(n);
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
    r->absorbs = m->absorb.x != 0 || m->absorb.y != 0 || m->absorb.z != 0;
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

/* ---- nearest hit ------------------------------------------------------- */

/* One primitive of the BVH's (or the brute-force loop's) against the ray;
 * narrows *tmax on a nearer hit. */
static inline void hit_prim(const scene_r *s, uint32_t shape, uint32_t i,
                            vec3 o, vec3 d, vec3 l, real *tmax, hit_r *hit,
                            int *found) {
  real t, u, v;
  switch (shape) {
  case GLI_SHAPE_SPHERE: {
    int inside;
    if (sphere_hit(s->spheres[i].center, s->spheres[i].r2, o, d, s->eps, *tmax,
                   &t, &inside)) {
      *tmax = hit->t = t;
      hit->shape = GLI_SHAPE_SPHERE;
      hit->prim = i;
      hit->inside = inside;
      *found = 1;
    }
    break;
  }
  case GLI_SHAPE_TRIANGLE: {
    const triangle_r *tr = &s->triangles[i];
    if (triangle_hit(tr->a, tr->edge, tr->moment, tr->n, o, d, l, s->eps, *tmax,
                     &t, &u, &v)) {
      *tmax = hit->t = t;
      hit->shape = GLI_SHAPE_TRIANGLE;
      hit->prim = i;
      hit->u = u;
      hit->v = v;
      *found = 1;
    }
    break;
  }
  default: { /* GLI_SHAPE_CONE */
    const cone_r *c = &s->cones[i];
    real ts[2];
    if (cone_roots(c->base, c->axis, c->height, c->rb, c->k, o, d, s->eps,
                   *tmax, ts)) {
      *tmax = hit->t = ts[0];
      hit->shape = GLI_SHAPE_CONE;
      hit->prim = i;
      *found = 1;
    }
    break;
  }
  }
}

/* What a closest-hit walk's leaves need. */
typedef struct nearest_query {
  const scene_r *s;
  vec3 o, d, l;
  hit_r *hit;
  int *found;
} nearest_query;

static inline void nearest_leaf(void *ctx, uint32_t ref, real *tmax) {
  nearest_query *q = ctx;
  hit_prim(q->s, GLI_REF_SHAPE(ref), GLI_REF_INDEX(ref), q->o, q->d, q->l, tmax,
           q->hit, q->found);
}

int scalar_nearest_hit(const scene_r *s, vec3 o, vec3 d, real tmax,
                       hit_r *hit) {
  vec3 l = triangle_ray_moment(s->tri_origin, o, d);
  int found = 0;
  real t;
  for (size_t i = 0; i < s->plane_count; i++)
    if (plane_hit(s->planes[i].n, s->planes[i].d, o, d, s->eps, tmax, &t)) {
      tmax = hit->t = t;
      hit->shape = GLI_SHAPE_PLANE;
      hit->prim = (uint32_t)i;
      found = 1;
    }
  if (s->bvh->node_count == 0) { /* the thesis's brute force (§4.3) */
    for (size_t i = 0; i < s->sphere_count; i++)
      hit_prim(s, GLI_SHAPE_SPHERE, (uint32_t)i, o, d, l, &tmax, hit, &found);
    for (size_t i = 0; i < s->triangle_count; i++)
      hit_prim(s, GLI_SHAPE_TRIANGLE, (uint32_t)i, o, d, l, &tmax, hit, &found);
    for (size_t i = 0; i < s->cone_count; i++)
      hit_prim(s, GLI_SHAPE_CONE, (uint32_t)i, o, d, l, &tmax, hit, &found);
    return found;
  }
  nearest_query q = {s, o, d, l, hit, &found};
  bvh_closest(s->bvh, o, d, s->eps, &tmax, nearest_leaf, &q);
  return found;
}

/* ---- shadow rays ------------------------------------------------------- */

/* The transmission along a shadow ray is a product over crossings, so their
 * order does not matter. The distance travelled inside objects is
 * sum(t_exit) - sum(t_entry) over the crossings on the segment (an object
 * the ray starts inside has no entry; lights are assumed to lie outside
 * transparent objects), so absorption needs no pairing of crossings either:
 * exp(sum over entries of a t - sum over exits of a t). */
typedef struct shadow_acc {
  vec3 kt;       /* product of kt */
  vec3 exponent; /* Beer's law exponent, <= 0 */
} shadow_acc;

/* Returns 0 when the crossing is opaque. */
static inline int cross_surface(const scene_r *s, shadow_acc *acc,
                                uint32_t object, real t, int entering) {
  const material_r *m = &s->materials[s->objects[object].material];
  if (m->kt == 0)
    return 0;
  acc->kt = v3_scale(acc->kt, m->kt);
  if (m->absorbs)
    acc->exponent = v3_madd(acc->exponent, entering ? t : -t, m->absorb);
  return 1;
}

/* Every crossing of one primitive within (eps, dist); 0 if opaque. */
static inline int cross_prim(const scene_r *s, shadow_acc *acc, uint32_t shape,
                             uint32_t i, vec3 o, vec3 d, vec3 l, real dist) {
  real eps = s->eps;
  switch (shape) {
  case GLI_SHAPE_SPHERE: {
    real l1, l2;
    const sphere_r *sp = &s->spheres[i];
    if (!sphere_roots(sp->center, sp->r2, o, d, &l1, &l2))
      return 1;
    if (l1 > eps && l1 < dist && !cross_surface(s, acc, sp->object, l1, 1))
      return 0;
    if (l2 > eps && l2 < dist && !cross_surface(s, acc, sp->object, l2, 0))
      return 0;
    return 1;
  }
  case GLI_SHAPE_TRIANGLE: {
    real t, u, v;
    const triangle_r *tr = &s->triangles[i];
    if (triangle_hit(tr->a, tr->edge, tr->moment, tr->n, o, d, l, eps, dist, &t,
                     &u, &v) &&
        !cross_surface(s, acc, tr->object, t, v3_dot(tr->ng, d) < 0))
      return 0;
    return 1;
  }
  default: { /* GLI_SHAPE_CONE */
    const cone_r *c = &s->cones[i];
    real ts[2];
    int n = cone_roots(c->base, c->axis, c->height, c->rb, c->k, o, d, eps,
                       dist, ts);
    for (int k = 0; k < n; k++) {
      vec3 p = v3_madd(o, ts[k], d);
      int entering =
          v3_dot(cone_normal(c->base, c->axis, c->rb, c->k, p), d) < 0;
      if (!cross_surface(s, acc, c->object, ts[k], entering))
        return 0;
    }
    return 1;
  }
  }
}

/* What a segment walk's leaves need. */
typedef struct segment_query {
  const scene_r *s;
  shadow_acc *acc;
  vec3 o, d, l;
  real dist;
} segment_query;

static inline int segment_leaf(void *ctx, uint32_t ref) {
  segment_query *q = ctx;
  return cross_prim(q->s, q->acc, GLI_REF_SHAPE(ref), GLI_REF_INDEX(ref), q->o,
                    q->d, q->l, q->dist);
}

vec3 scalar_transmission(const scene_r *s, vec3 o, vec3 d, real dist) {
  vec3 l = triangle_ray_moment(s->tri_origin, o, d);
  shadow_acc acc = {v3(1, 1, 1), v3(0, 0, 0)};
  const vec3 black = v3(0, 0, 0);
  real t;
  for (size_t i = 0; i < s->plane_count; i++) {
    const plane_r *p = &s->planes[i];
    if (plane_hit(p->n, p->d, o, d, s->eps, dist, &t) &&
        !cross_surface(s, &acc, p->object, t, v3_dot(p->n, d) < 0))
      return black;
  }
  if (s->bvh->node_count == 0) {
    for (size_t i = 0; i < s->sphere_count; i++)
      if (!cross_prim(s, &acc, GLI_SHAPE_SPHERE, (uint32_t)i, o, d, l, dist))
        return black;
    for (size_t i = 0; i < s->triangle_count; i++)
      if (!cross_prim(s, &acc, GLI_SHAPE_TRIANGLE, (uint32_t)i, o, d, l, dist))
        return black;
    for (size_t i = 0; i < s->cone_count; i++)
      if (!cross_prim(s, &acc, GLI_SHAPE_CONE, (uint32_t)i, o, d, l, dist))
        return black;
  } else {
    segment_query q = {s, &acc, o, d, l, dist};
    if (!bvh_segment(s->bvh, o, d, s->eps, dist, segment_leaf, &q))
      return black;
  }
  if (acc.exponent.x == 0 && acc.exponent.y == 0 && acc.exponent.z == 0)
    return acc.kt;
  return v3_mul(acc.kt, v3(r_exp(r_fmin(acc.exponent.x, 0)),
                           r_exp(r_fmin(acc.exponent.y, 0)),
                           r_exp(r_fmin(acc.exponent.z, 0))));
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

static glint_status bind(const void *data, const gli_bvh *bvh, void **view,
                         glint_error *error) {
  scene_r *v = malloc(sizeof *v);
  if (!v)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  *v = *(const scene_r *)data;
  v->bvh = bvh;
  *view = v;
  return GLINT_OK;
}

static void unbind(void *view) { free(view); }

const data_ops REAL_NAME(gli_scalar_data) = {convert, release, bytes, bind,
                                             unbind};
