/* One ray at a time through the wide BVH against the leaf blocks
 * (render/leaf_blocks.h): its nearest hit and the crossings of a shadow
 * ray, each block tested in SIMD by the lane formulas of
 * geometry/packet_intersect.h with the ray broadcast. What a packet's lanes
 * use when the packet hands them a subtree (accel/packet_traverse.h); the
 * results are those of render/scalar_rays.h, in the packet kernels'
 * arithmetic. Compiled once per ISA. */
#ifndef GLINT_RENDER_BLOCK_RAYS_H
#define GLINT_RENDER_BLOCK_RAYS_H

#include "accel/wide_traverse.h"
#include "geometry/packet_intersect.h"
#include "render/leaf_blocks.h"
#include "render/scalar_rays.h"

/* One ray, broadcast. */
typedef struct block_ray {
  const packet_scene *ps;
  vvec3 o, d, l; /* l: triangle_ray_moment */
  vfloat eps;
  int newton;
} block_ray;

static ALWAYS_INLINE block_ray block_ray_make(const packet_scene *ps, vec3 o,
                                              vec3 d, int newton) {
  vec3 l = triangle_ray_moment(ps->s->tri_origin, o, d);
  block_ray r = {ps,         vv_set1(o),       vv_set1(d),
                 vv_set1(l), vs_get(&ps->eps), newton};
  return r;
}

static ALWAYS_INLINE vmask block_lanes(uint32_t count) {
  return vm_from_bits((int)((1u << count) - 1));
}

static ALWAYS_INLINE cone_lanes block_cone_lanes(const block_cone *b) {
  cone_lanes c = {block_vec(b->base),       block_vec(b->axis),
                  vf_load_block(b->height), vf_load_block(b->rb),
                  vf_load_block(b->k),      vf_load_block(b->reach2)};
  return c;
}

/* The lane of `win` with the smallest t. */
static ALWAYS_INLINE int nearest_lane(vmask win, vfloat t, float *out) {
  SIMD_ALIGN float ts[LANES];
  vf_store(ts, t);
  int bits = vm_bits(win), best = __builtin_ctz((unsigned)bits);
  for (bits &= bits - 1; bits; bits &= bits - 1) {
    int k = __builtin_ctz((unsigned)bits);
    if (ts[k] < ts[best])
      best = k;
  }
  *out = ts[best];
  return best;
}

/* ---- nearest hit -------------------------------------------------------- */

typedef struct block_nearest_query {
  block_ray r;
  const leaf_blocks *blocks;
  hit_r *hit;
  int found;
} block_nearest_query;

static void block_nearest_leaf(void *ctx, uint32_t first, uint32_t count,
                               float *tmax) {
  block_nearest_query *q = ctx;
  const block_ray *r = &q->r;
  const leaf_blocks *lb = q->blocks;
  const leaf_run *run = &lb->runs[lb->first_run[first]];
  for (uint32_t done = 0; done < count; done += run->count, run++) {
    vmask active = block_lanes(run->count);
    vfloat t = vf_zero(), u = vf_zero(), v = vf_zero(), l1, l2;
    vmask win, outside = vm_false();
    switch (run->shape) {
    case GLI_SHAPE_SPHERE: {
      const block_sphere *b = &lb->spheres[run->block];
      vmask m = sphere_lanes(block_vec(b->center), vf_load_block(b->r2), r->o,
                             r->d, active, &l1, &l2);
      if (vm_none(m))
        continue;
      win = sphere_first(m, l1, l2, r->eps, vf_set1(*tmax), &t, &outside);
      break;
    }
    case GLI_SHAPE_TRIANGLE: {
      triangle_lanes tl = {1, NULL, &lb->triangles[run->block]};
      win = triangle_cross_lanes(tl, r->o, r->d, r->l, active, r->eps,
                                 vf_set1(*tmax), r->newton, &t, &u, &v);
      break;
    }
    default: {
      cone_lanes cl = block_cone_lanes(&lb->cones[run->block]);
      vfloat t1 = vf_zero();
      vmask m1;
      cone_roots_lanes(&cl, r->o, r->d, active, r->eps, vf_set1(*tmax), &t,
                       &win, &t1, &m1);
      break;
    }
    }
    if (vm_none(win))
      continue;
    int k = nearest_lane(win, t, tmax);
    hit_r *h = q->hit;
    h->t = *tmax;
    h->shape = run->shape;
    q->found = 1;
    if (run->shape == GLI_SHAPE_SPHERE) {
      h->prim = lb->spheres[run->block].prim[k];
      h->inside = !(vm_bits(outside) >> k & 1);
    } else if (run->shape == GLI_SHAPE_TRIANGLE) {
      SIMD_ALIGN float us[LANES], vs[LANES];
      vf_store(us, u), vf_store(vs, v);
      h->prim = lb->triangles[run->block].prim[k];
      h->u = us[k], h->v = vs[k];
    } else {
      h->prim = lb->cones[run->block].prim[k];
    }
  }
}

/* The nearest hit in the subtree at wide node `node`, narrowing *tmax. */
static ALWAYS_INLINE int block_nearest_below(const packet_scene *ps,
                                             const leaf_blocks *blocks,
                                             uint32_t node, vec3 o, vec3 d,
                                             int newton, float *tmax,
                                             hit_r *hit, uint64_t *tests) {
  block_nearest_query q = {block_ray_make(ps, o, d, newton), blocks, hit, 0};
  wide_closest(ps->s->bvh, node, o, d, ps->s->eps, tmax, block_nearest_leaf, &q,
               tests);
  return q.found;
}

/* ---- shadow rays -------------------------------------------------------- */

typedef struct block_segment_query {
  block_ray r;
  const leaf_blocks *blocks;
  vfloat dist;
  shadow_acc *acc;
} block_segment_query;

/* The crossings of lanes `crossing` at distances t: 0 when one is opaque
 * (cross_surface, render/scalar_rays.h). */
static ALWAYS_INLINE int block_cross(const scene_r *s, const uint32_t *prim,
                                     uint32_t shape, vmask crossing, vfloat t,
                                     vmask entering, shadow_acc *acc) {
  if (vm_none(crossing))
    return 1;
  SIMD_ALIGN float ts[LANES];
  vf_store(ts, t);
  int enter = vm_bits(entering);
  for (int bits = vm_bits(crossing); bits; bits &= bits - 1) {
    int k = __builtin_ctz((unsigned)bits);
    uint32_t object = shape == GLI_SHAPE_SPHERE ? s->spheres[prim[k]].object
                      : shape == GLI_SHAPE_TRIANGLE
                          ? s->triangles[prim[k]].object
                          : s->cones[prim[k]].object;
    if (!cross_surface(s, acc, object, ts[k], enter >> k & 1))
      return 0;
  }
  return 1;
}

static int block_segment_leaf(void *ctx, uint32_t first, uint32_t count) {
  block_segment_query *q = ctx;
  const block_ray *r = &q->r;
  const scene_r *s = r->ps->s;
  const leaf_blocks *lb = q->blocks;
  const leaf_run *run = &lb->runs[lb->first_run[first]];
  for (uint32_t done = 0; done < count; done += run->count, run++) {
    vmask active = block_lanes(run->count);
    switch (run->shape) {
    case GLI_SHAPE_SPHERE: {
      const block_sphere *b = &lb->spheres[run->block];
      vfloat l1, l2;
      vmask m = sphere_lanes(block_vec(b->center), vf_load_block(b->r2), r->o,
                             r->d, active, &l1, &l2);
      if (vm_none(m))
        continue;
      vmask c1 = vm_and(m, vm_and(vf_gt(l1, r->eps), vf_lt(l1, q->dist)));
      vmask c2 = vm_and(m, vm_and(vf_gt(l2, r->eps), vf_lt(l2, q->dist)));
      if (!block_cross(s, b->prim, GLI_SHAPE_SPHERE, c1, l1, vm_true(),
                       q->acc) ||
          !block_cross(s, b->prim, GLI_SHAPE_SPHERE, c2, l2, vm_false(),
                       q->acc))
        return 0;
      break;
    }
    case GLI_SHAPE_TRIANGLE: {
      const block_triangle *b = &lb->triangles[run->block];
      triangle_lanes tl = {1, NULL, b};
      vfloat t = vf_zero(), u, v;
      vmask c = triangle_cross_lanes(tl, r->o, r->d, r->l, active, r->eps,
                                     q->dist, r->newton, &t, &u, &v);
      /* Entering: against the normal, which the scaled one shares. */
      if (!block_cross(s, b->prim, GLI_SHAPE_TRIANGLE, c, t,
                       vf_lt(vv_dot(tri_normal(tl), r->d), vf_zero()), q->acc))
        return 0;
      break;
    }
    default: {
      const block_cone *b = &lb->cones[run->block];
      cone_lanes cl = block_cone_lanes(b);
      vfloat t0 = vf_zero(), t1 = vf_zero();
      vmask m0, m1;
      cone_roots_lanes(&cl, r->o, r->d, active, r->eps, q->dist, &t0, &m0, &t1,
                       &m1);
      for (int k = 0; k < 2; k++) {
        vmask m = k ? m1 : m0;
        if (vm_none(m))
          break;
        vfloat t = k ? t1 : t0;
        vvec3 n = packet_cone_normal(cl.base, cl.axis, cl.rb, cl.k,
                                     vv_madd(r->o, t, r->d));
        if (!block_cross(s, b->prim, GLI_SHAPE_CONE, m, t,
                         vf_lt(vv_dot(n, r->d), vf_zero()), q->acc))
          return 0;
      }
      break;
    }
    }
  }
  return 1;
}

/* The crossings in the subtree at wide node `node` within (eps, dist),
 * gathered into *acc; 0 when one is opaque. */
static ALWAYS_INLINE int block_segment_below(const packet_scene *ps,
                                             const leaf_blocks *blocks,
                                             uint32_t node, vec3 o, vec3 d,
                                             float dist, int newton,
                                             shadow_acc *acc, uint64_t *tests) {
  block_segment_query q = {block_ray_make(ps, o, d, newton), blocks,
                           vf_set1(dist), acc};
  return wide_segment(ps->s->bvh, node, o, d, ps->s->eps, dist,
                      block_segment_leaf, &q, tests);
}

#endif
