/* What one ray finds in the scene, in the translation unit's precision: its
 * nearest hit and the transmission of a shadow ray (docs/specification.md
 * §4): the scalar backends' queries (render/scalar_scene.c). A packet's
 * lane that walks part of the BVH alone (render/block_rays.h) shares its
 * hit record and the shadow crossings' accounting (shadow_acc,
 * cross_surface), and tests primitives with the packet formulas. */
#ifndef GLINT_RENDER_SCALAR_RAYS_H
#define GLINT_RENDER_SCALAR_RAYS_H

#include "accel/traverse.h"
#include "accel/wide_traverse.h"
#include "geometry/intersect.h"
#include "render/frame.h"
#include "render/scalar_scene.h"
#include "scene/scene.h"

/* The ray's moment for the triangle tests, only where there are triangles:
 * a cross product every query would make on scenes of spheres and planes
 * (the scalar tracer 3% slower on Whitted). */
static inline vec3 ray_moment(const scene_r *s, vec3 o, vec3 d) {
  return s->triangle_count ? triangle_ray_moment(s->tri_origin, o, d)
                           : v3(0, 0, 0);
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
typedef struct ray_nearest_query {
  const scene_r *s;
  vec3 o, d, l;
  hit_r *hit;
  int *found;
} ray_nearest_query;

static inline void ray_nearest_leaf(void *ctx, uint32_t ref, real *tmax) {
  ray_nearest_query *q = ctx;
  hit_prim(q->s, GLI_REF_SHAPE(ref), GLI_REF_INDEX(ref), q->o, q->d, q->l, tmax,
           q->hit, q->found);
}

static inline void ray_nearest_wide_leaf(void *ctx, uint32_t first,
                                         uint32_t count, real *tmax) {
  ray_nearest_query *q = ctx;
  const uint32_t *refs = q->s->bvh->wide.refs;
  for (uint32_t k = first; k < first + count; k++)
    ray_nearest_leaf(ctx, refs[k], tmax);
}

/* The nearest hit in the wide BVH (accel/wide_bvh.h), narrowing *tmax.
 * Apart (noinline): its walk's stack of several KiB then stays out of the
 * frame of the query every ray makes. The ray comes by address (o, d and
 * l): by value, every query packed its vectors for the call through memory
 * in a way the CPU cannot forward (the scalar tracer 25% slower on
 * Whitted, which never walks the wide tree). */
static __attribute__((noinline)) int
ray_nearest_wide(const scene_r *s, const vec3 ray[3], real *tmax, hit_r *hit) {
  int found = 0;
  uint64_t tests = 0;
  ray_nearest_query q = {s, ray[0], ray[1], ray[2], hit, &found};
  wide_closest(s->bvh, 0, ray[0], ray[1], s->eps, tmax, ray_nearest_wide_leaf,
               &q, &tests);
  return found;
}

/* The nearest hit along o + t d, eps < t < tmax: the planes (unbounded,
 * outside the BVH), then the binary BVH, or the wide one (--accel bvh8),
 * or every primitive (--accel none, the thesis's brute force, §4.3). */
static inline __attribute__((always_inline)) int
ray_nearest(const scene_r *s, vec3 o, vec3 d, real tmax, hit_r *hit) {
  vec3 l = ray_moment(s, o, d);
  int found = 0;
  real t;
  for (size_t i = 0; i < s->plane_count; i++)
    if (plane_hit(s->planes[i].n, s->planes[i].d, o, d, s->eps, tmax, &t)) {
      tmax = hit->t = t;
      hit->shape = GLI_SHAPE_PLANE;
      hit->prim = (uint32_t)i;
      found = 1;
    }
  if (s->bvh->node_count == 0) {
    for (size_t i = 0; i < s->sphere_count; i++)
      hit_prim(s, GLI_SHAPE_SPHERE, (uint32_t)i, o, d, l, &tmax, hit, &found);
    for (size_t i = 0; i < s->triangle_count; i++)
      hit_prim(s, GLI_SHAPE_TRIANGLE, (uint32_t)i, o, d, l, &tmax, hit, &found);
    for (size_t i = 0; i < s->cone_count; i++)
      hit_prim(s, GLI_SHAPE_CONE, (uint32_t)i, o, d, l, &tmax, hit, &found);
    return found;
  }
  if (s->walk_wide) {
    const vec3 ray[3] = {o, d, l};
    return ray_nearest_wide(s, ray, &tmax, hit) | found;
  }
  ray_nearest_query q = {s, o, d, l, hit, &found};
  bvh_closest(s->bvh, o, d, s->eps, &tmax, ray_nearest_leaf, &q);
  return found;
}

/* ---- shadow rays ------------------------------------------------------- */

/* The transmission along a shadow ray is a product over crossings, so their
 * order does not matter. The distance travelled inside objects is
 * sum(t_exit) - sum(t_entry) over the crossings on the segment: an object
 * the ray starts inside has no entry, and its exit's -a t counts the
 * stretch from the origin. One the light lies inside has no exit, and its
 * stretch ends at the light, dist: -a (dist - t). So absorption needs no
 * pairing of crossings either: exp(sum over entries of a t - sum over exits
 * of a t - max(0, open) dist), open being the sum of a over entries less
 * that over exits, what the ray entered and did not leave. (Not where the
 * origin and the light lie inside one object, with no crossing between
 * them, nor inside two different objects that absorb one channel, where
 * the two terms of open cancel.) */
typedef struct shadow_acc {
  vec3 kt;       /* product of kt */
  vec3 exponent; /* sum of +a t entering, -a t leaving */
  vec3 open;     /* sum of +a entering, -a leaving, where the scene's
                    lights_in_absorbers (else 0) */
} shadow_acc;

/* What a shadow ray that crossed nothing lets through. */
static inline shadow_acc shadow_acc_clear(void) {
  shadow_acc acc = {v3(1, 1, 1), v3(0, 0, 0), v3(0, 0, 0)};
  return acc;
}

/* Returns 0 when the crossing is opaque. */
static inline int cross_surface(const scene_r *s, shadow_acc *acc,
                                uint32_t object, real t, int entering) {
  const material_r *m = &s->materials[s->objects[object].material];
  if (m->kt == 0)
    return 0;
  acc->kt = v3_scale(acc->kt, m->kt);
  if (m->absorbs) {
    acc->exponent = v3_madd(acc->exponent, entering ? t : -t, m->absorb);
    if (s->lights_in_absorbers) /* else open stays 0 */
      acc->open = v3_madd(acc->open, entering ? 1 : -1, m->absorb);
  }
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
typedef struct ray_segment_query {
  const scene_r *s;
  shadow_acc *acc;
  vec3 o, d, l;
  real dist;
} ray_segment_query;

static inline int ray_segment_leaf(void *ctx, uint32_t ref) {
  ray_segment_query *q = ctx;
  return cross_prim(q->s, q->acc, GLI_REF_SHAPE(ref), GLI_REF_INDEX(ref), q->o,
                    q->d, q->l, q->dist);
}

static inline int ray_segment_wide_leaf(void *ctx, uint32_t first,
                                        uint32_t count) {
  ray_segment_query *q = ctx;
  const uint32_t *refs = q->s->bvh->wide.refs;
  for (uint32_t k = first; k < first + count; k++)
    if (!ray_segment_leaf(ctx, refs[k]))
      return 0;
  return 1;
}

/* The crossings in the wide BVH; 0 when one is opaque. Apart, as
 * ray_nearest_wide. */
static __attribute__((noinline)) int ray_segment_wide(const scene_r *s,
                                                      const vec3 ray[3],
                                                      real dist,
                                                      shadow_acc *acc) {
  uint64_t tests = 0;
  ray_segment_query q = {s, acc, ray[0], ray[1], ray[2], dist};
  return wide_segment(s->bvh, 0, ray[0], ray[1], s->eps, dist,
                      ray_segment_wide_leaf, &q, &tests);
}

/* Beer's law's exponent for a shadow ray's crossings over (0, dist), at
 * most 0 (see shadow_acc). */
static inline real shadow_exponent(real exponent, real open, real dist) {
  return r_fmin(exponent - r_fmax(open, 0) * dist, 0);
}

/* The light a shadow ray's crossings let through over (0, dist): kt times
 * Beer's law. */
static inline vec3 shadow_acc_result(const shadow_acc *acc, real dist) {
  if (acc->exponent.x == 0 && acc->exponent.y == 0 && acc->exponent.z == 0)
    return acc->kt;
  const vec3 e = acc->exponent, open = acc->open;
  return v3_mul(acc->kt, v3(r_exp(shadow_exponent(e.x, open.x, dist)),
                            r_exp(shadow_exponent(e.y, open.y, dist)),
                            r_exp(shadow_exponent(e.z, open.z, dist))));
}

/* docs/specification.md §4's transmission from o along unit d over dist:
 * the planes, then the BVH as ray_nearest walks it. */
static inline __attribute__((always_inline)) vec3
ray_transmission(const scene_r *s, vec3 o, vec3 d, real dist) {
  const real light = dist; /* Beer's stretches run to the light */
  dist -= r_fmax(s->eps, dist * (real)GLI_SHADOW_SHORT);
  vec3 l = ray_moment(s, o, d);
  shadow_acc acc = shadow_acc_clear();
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
  } else if (s->walk_wide) {
    const vec3 ray[3] = {o, d, l};
    if (!ray_segment_wide(s, ray, dist, &acc))
      return black;
  } else {
    ray_segment_query q = {s, &acc, o, d, l, dist};
    if (!bvh_segment(s->bvh, o, d, s->eps, dist, ray_segment_leaf, &q))
      return black;
  }
  return shadow_acc_result(&acc, light);
}

#endif
