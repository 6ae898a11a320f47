/* What W rays at once find in the packet scene: their nearest hits, and
 * the transmission of shadow rays toward a light (docs/specification.md §4);
 * the packet forms of scalar_nearest_hit and scalar_transmission
 * (render/scalar_scene.c). The BVH walks are accel/packet_traverse.h's. */
#ifndef GLINT_RENDER_PACKET_RAYS_H
#define GLINT_RENDER_PACKET_RAYS_H

#include "accel/packet_traverse.h"
#include "geometry/packet_intersect.h"
#include "render/packet_scene.h"
#include "render/block_rays.h"
#include "render/frame.h"
#include "scene/scene.h"
#include "simd/vmath.h"

/* ---- lanes alone (accel/packet_traverse.h's hybrid walks) -------------- */

/* Whether the packet walks of this translation unit hand rays over to the
 * wide tree (hybrid walks, --accel bvh8). The stream backends say 0
 * (render/stream_tracer.c): their packets are refilled every generation, so
 * few of their lanes part ways (at best 3-5% faster with hand-overs on
 * balls-s4 and rings-s4), while the mere presence of the hand-over cost them
 * 9% on gears-s4 (in the walk's loop) and 10% with AVX2 on small scenes (the
 * calls for bvh8, outside it). */
#ifndef PACKET_HAND_OVER
#define PACKET_HAND_OVER 1
#endif

/* Whether the segment walk of shadow rays is a function of its own rather
 * than inlined into packet_transmission: 1 for the SSE streams
 * (render/stream_tracer.c), whose shading leaves SSE's 16 registers too few
 * for the slab test inlined there: 56 instructions a box test on gears-s2,
 * 47 apart as in the beams; their render instructions fall 2-9% on the
 * thesis's scenes and the SPD's (callgrind). The other builds lose up to
 * 8% by the call, so keep it inlined. */
#ifndef PACKET_WALKS_APART
#define PACKET_WALKS_APART 0
#endif

/* Whether the closest-hit walk is a function of its own rather than inlined
 * into packet_nearest: 1 for the stream backends (render/stream_tracer.c),
 * where it is inlined into every shading of the tracer's one large loop.
 * Inlined there, the walk that tests an inner node's children together ran
 * the AVX-512 streams 4-8% slower than the walk before it on tree-s4,
 * teapot-s4 and tetra-s6; apart, 2-6% faster on the SPD scenes (pinned,
 * medians of 7-15). The beams, which lose up to 9% by the call on giza at
 * depth 1, keep it inlined. */
#ifndef PACKET_NEAREST_APART
#define PACKET_NEAREST_APART 0
#endif

/* A packet's rays as scalars, for its lanes that walk alone (stored at
 * each hand-over, which is rare, rather than for every packet). */
typedef struct lane_rays {
  SIMD_ALIGN float o[3][LANES], d[3][LANES];
} lane_rays;

static ALWAYS_INLINE void lane_rays_store(lane_rays *r, vvec3 o, vvec3 d) {
  vf_store(r->o[0], o.x), vf_store(r->o[1], o.y), vf_store(r->o[2], o.z);
  vf_store(r->d[0], d.x), vf_store(r->d[1], d.y), vf_store(r->d[2], d.z);
}

static ALWAYS_INLINE void lane_ray(const lane_rays *r, int k, vec3 *o,
                                   vec3 *d) {
  *o = v3(r->o[0][k], r->o[1][k], r->o[2][k]);
  *d = v3(r->d[0][k], r->d[1][k], r->d[2][k]);
}

/* The lanes' moments for the triangle tests (render/scalar_rays.h's
 * ray_moment), made when a query first tests a triangle: in scenes with a
 * few triangles among other shapes (an SPD scene's ground polygon) most
 * queries test none, and making it for every query cost tree-s4 3% of its
 * render instructions. Meshes pay the test of `made` per triangle (up to 2%
 * on teapot-s2 and tetra-s4); making it at once where most primitives are
 * triangles cost more than it saved, through its branch per query. */
typedef struct lazy_moment {
  vvec3 l;
  int made;
} lazy_moment;

static ALWAYS_INLINE vvec3 moment_of(const packet_scene *ps, lazy_moment *lm,
                                     vvec3 o, vvec3 d) {
  if (!lm->made) {
    lm->l = packet_triangle_moment(ps->tri_origin, o, d);
    lm->made = 1;
  }
  return lm->l;
}

/* One referenced primitive against the lanes of m. */
static ALWAYS_INLINE void packet_prim(const packet_scene *ps, uint32_t ref,
                                      vvec3 o, vvec3 d, lazy_moment *l, vmask m,
                                      vfloat eps, int newton, packet_hit *h) {
  uint32_t i = GLI_REF_INDEX(ref);
  switch (GLI_REF_SHAPE(ref)) {
  case GLI_SHAPE_SPHERE: packet_sphere(&ps->spheres[i], o, d, m, eps, h); break;
  case GLI_SHAPE_TRIANGLE:
    packet_triangle(&ps->triangles[i], i, o, d, moment_of(ps, l, o, d), m, eps,
                    newton, h);
    break;
  default: packet_cone(&ps->cones[i], o, d, m, eps, h); break;
  }
}

/* The closest-hit walk's packet_prefetch_fn: the lines of a leaf's
 * triangles start loading (a triangle's record is the largest a leaf
 * reads: two or three lines with AVX2 and AVX-512, all of them prefetched;
 * seven with SSE's broadcast numbers, of which the first, second and last),
 * where the scene's triangles outgrow the caches (ps->prefetch). */
static ALWAYS_INLINE void prefetch_prims(const packet_scene *ps,
                                         const uint32_t *refs, uint32_t count) {
  if (!ps->prefetch)
    return;
  for (uint32_t k = 0; k < count; k++)
    if (GLI_REF_SHAPE(refs[k]) == GLI_SHAPE_TRIANGLE) {
      const char *p = (const char *)&ps->triangles[GLI_REF_INDEX(refs[k])];
      __builtin_prefetch(p);
      __builtin_prefetch(p + 64);
      __builtin_prefetch(p + sizeof *ps->triangles - 1);
    }
  /* An effect GCC can see: it took a function of prefetches alone for a
   * pure one, whose calls it may drop, and dropped them from the walks it
   * inlined. */
  __asm__ volatile("");
}

/* What a closest-hit walk's leaves need. */
typedef struct nearest_query {
  const packet_scene *ps;
  vvec3 o, d;
  lazy_moment *l;
  const packet_origin *po;
  vfloat eps;
  int newton;
  packet_hit *h;
  glint_stats *st;
} nearest_query;

static ALWAYS_INLINE void nearest_prefetch(void *ctx, const uint32_t *refs,
                                           uint32_t count) {
  prefetch_prims(((nearest_query *)ctx)->ps, refs, count);
}

static ALWAYS_INLINE void nearest_leaf(void *ctx, uint32_t ref, vmask m) {
  nearest_query *q = ctx;
  packet_prim(q->ps, ref, q->o, q->d, q->l, m, q->eps, q->newton, q->h);
}

/* Each lane of m finds its nearest hit in the subtree alone
 * (render/block_rays.h), and the packet's hits take what it found. */
static __attribute__((cold, noinline)) void
nearest_alone(void *ctx, uint32_t wide, vmask m) {
  nearest_query *q = ctx;
  const scene_r *s = q->ps->s;
  packet_hit *h = q->h;
  lane_rays lanes;
  lane_rays_store(&lanes, q->o, q->d);
  SIMD_ALIGN float t[LANES], u[LANES], v[LANES];
  SIMD_ALIGN int object[LANES], prim[LANES];
  vf_store(t, h->t), vf_store(u, h->u), vf_store(v, h->v);
  vi_store(object, h->object), vi_store(prim, h->prim);
  int inside = vm_bits(h->inside), won = 0;
  for (int bits = vm_bits(m); bits; bits &= bits - 1) {
    int k = __builtin_ctz((unsigned)bits);
    vec3 o, d;
    lane_ray(&lanes, k, &o, &d);
    hit_r hit;
    float tmax = t[k];
    q->st->alone_walks++;
    if (!block_nearest_below(q->ps, q->ps->blocks, wide, o, d, q->newton, &tmax,
                             &hit, &q->st->alone_tests))
      continue;
    won = 1;
    t[k] = hit.t;
    switch (hit.shape) {
    case GLI_SHAPE_SPHERE:
      object[k] = (int)s->spheres[hit.prim].object;
      inside = hit.inside ? inside | 1 << k : inside & ~(1 << k);
      break;
    case GLI_SHAPE_TRIANGLE:
      object[k] = (int)s->triangles[hit.prim].object;
      prim[k] = (int)hit.prim;
      u[k] = hit.u, v[k] = hit.v;
      break;
    default: object[k] = (int)s->cones[hit.prim].object; break;
    }
  }
  if (!won)
    return;
  h->t = vf_load(t), h->u = vf_load(u), h->v = vf_load(v);
  h->object = vi_load(object), h->prim = vi_load(prim);
  h->inside = vm_from_bits(inside);
}

/* The hybrid closest-hit walk (--accel bvh, where the tree has hand-over
 * points) or every lane alone (bvh8): apart from packet_nearest, so that
 * the walk every other packet takes, inlined there, holds no call. */
static __attribute__((noinline)) void
nearest_hybrid(nearest_query *q, const gli_bvh *bvh, vmask active) {
  const packet_scene *ps = q->ps;
  if (ps->alone_lanes == LANES)
    nearest_alone(q, 0, active);
  else
    packet_bvh_closest(bvh, q->po, q->d, active, q->eps, &q->h->t, q->newton,
                       q->st, nearest_prefetch, nearest_leaf, ps->alone_lanes,
                       nearest_alone, q);
}

/* The closest-hit walk of packet_nearest (see PACKET_NEAREST_APART). */
#if PACKET_NEAREST_APART
#define NEAREST_WALK_INLINING __attribute__((noinline))
#else
#define NEAREST_WALK_INLINING ALWAYS_INLINE
#endif
static NEAREST_WALK_INLINING void
nearest_walk(nearest_query *q, const gli_bvh *bvh, vmask active) {
  packet_bvh_closest(bvh, q->po, q->d, active, q->eps, &q->h->t, q->newton,
                     q->st, nearest_prefetch, nearest_leaf, 0, nearest_alone,
                     q);
}

/* The lanes' nearest hits: the planes (unbounded, outside the BVH), then
 * the BVH's primitives, or every primitive when there is no BVH (the
 * thesis's brute force, §4.3). */
static ALWAYS_INLINE void packet_nearest(const packet_scene *ps, vvec3 o,
                                         vvec3 d, vmask active, int newton,
                                         packet_hit *h, glint_stats *st) {
  const scene_r *s = ps->s;
  packet_hit_init(h);
  vfloat eps = vs_get(&ps->eps);
  const gli_bvh *bvh = s->bvh;
  count_tests(st, ps->outside_tests, vm_count(active));
  for (size_t i = 0; i < s->plane_count; i++)
    packet_plane(&ps->planes[i], o, d, active, eps, newton, h);
  if (bvh->node_count == 0) {
    for (size_t i = 0; i < s->sphere_count; i++)
      packet_sphere(&ps->spheres[i], o, d, active, eps, h);
    if (s->triangle_count) {
      vvec3 l = packet_triangle_moment(ps->tri_origin, o, d);
      for (size_t i = 0; i < s->triangle_count; i++)
        packet_triangle(&ps->triangles[i], (uint32_t)i, o, d, l, active, eps,
                        newton, h);
    }
    for (size_t i = 0; i < s->cone_count; i++)
      packet_cone(&ps->cones[i], o, d, active, eps, h);
    return;
  }
  packet_origin po = packet_origin_of(o);
  lazy_moment l = {{vf_zero(), vf_zero(), vf_zero()}, 0};
  nearest_query q = {ps, o, d, &l, &po, eps, newton, h, st};
  if (PACKET_HAND_OVER && ps->alone_lanes)
    nearest_hybrid(&q, bvh, active);
  else
    nearest_walk(&q, bvh, active);
}

/* ---- shadow rays ------------------------------------------------------ */

/* docs/specification.md §4's transmission toward a light, for W shadow rays at
 * once (the ray_transmission of render/scalar_rays.h, lane-parallel): each
 * opaque crossing kills its lane; each transparent one multiplies by kt and
 * adds to the Beer exponent (+a t entering, -a t leaving) and to what the
 * lane entered and did not leave (+a entering, -a leaving: shadow_acc). */
typedef struct shadow_state {
  vvec3 kt, exponent, open;
  vmask alive;
  int absorbed; /* bit c: channel c met an absorbing surface */
} shadow_state;

static ALWAYS_INLINE void shadow_cross(const packet_scene *ps, int object,
                                       vmask crossing, vfloat t, vmask entering,
                                       shadow_state *sh) {
  if (vm_none(crossing))
    return;
  uint32_t mi = ps->s->objects[object].material;
  const material_r *m = &ps->s->materials[mi];
  if (m->kt == 0) {
    sh->alive = vm_andnot(sh->alive, crossing);
    return;
  }
  const pmaterial *pm = &ps->materials[mi];
  vfloat k = vf_select(crossing, vs_get(&pm->kt), vf_set1(1));
  sh->kt = vv_scale(sh->kt, k);
  if (m->absorbs) {
    vfloat signed_t = vf_select(entering, t, vf_neg(t));
    vfloat st = vf_keep(crossing, signed_t);
    vvec3 a = vv_get(pm->absorb);
    sh->exponent = vv_madd(sh->exponent, st, a);
    if (ps->s->lights_in_absorbers) { /* else open stays 0 */
      vfloat sign =
          vf_keep(crossing, vf_select(entering, vf_set1(1), vf_set1(-1)));
      sh->open = vv_madd(sh->open, sign, a);
    }
    sh->absorbed |= m->absorbs;
  }
}

/* Every crossing of one primitive by the shadow lanes within (eps, dist). */
static ALWAYS_INLINE void packet_cross_prim(const packet_scene *ps,
                                            uint32_t shape, uint32_t i, vvec3 o,
                                            vvec3 d, lazy_moment *l,
                                            vfloat dist, vfloat eps, int newton,
                                            shadow_state *sh) {
  switch (shape) {
  case GLI_SHAPE_SPHERE: {
    const psphere *sp = &ps->spheres[i];
    vfloat l1, l2;
    vmask m = sphere_lanes(vv_get(sp->center), vs_get(&sp->r2), o, d, sh->alive,
                           &l1, &l2);
    if (vm_none(m))
      return;
    vmask c1 = vm_and(m, vm_and(vf_gt(l1, eps), vf_lt(l1, dist)));
    vmask c2 = vm_and(m, vm_and(vf_gt(l2, eps), vf_lt(l2, dist)));
    shadow_cross(ps, sp->object, c1, l1, vm_true(), sh);
    shadow_cross(ps, sp->object, c2, l2, vm_false(), sh);
    break;
  }
  case GLI_SHAPE_TRIANGLE: {
    const ptriangle *tr = &ps->triangles[i];
    vfloat t, u, v;
    vmask c = packet_triangle_cross(tr, o, d, moment_of(ps, l, o, d), sh->alive,
                                    eps, dist, newton, &t, &u, &v);
    /* Entering: against the normal, which the scaled one shares. */
    shadow_cross(ps, tr->object, c, t,
                 vf_lt(vv_dot(vv_get(tr->n), d), vf_zero()), sh);
    break;
  }
  default: {
    const pcone *c = &ps->cones[i];
    vfloat t0, t1;
    vmask m0, m1;
    packet_cone_roots(c, o, d, sh->alive, eps, dist, &t0, &m0, &t1, &m1);
    if (vm_none(m0))
      break;
    if (ps->s->materials[ps->s->objects[c->object].material].kt == 0) {
      /* opaque: no need to know which side is entered */
      shadow_cross(ps, c->object, m0, t0, vm_true(), sh);
      break;
    }
    for (int k = 0; k < 2 && vm_any(k ? m1 : m0); k++) {
      vfloat t = k ? t1 : t0;
      vvec3 n =
          packet_cone_normal(vv_get(c->base), vv_get(c->axis), vs_get(&c->rb),
                             vs_get(&c->k), vv_madd(o, t, d));
      shadow_cross(ps, c->object, k ? m1 : m0, t,
                   vf_lt(vv_dot(n, d), vf_zero()), sh);
    }
    break;
  }
  }
}

/* What a segment walk's leaves need. */
typedef struct segment_query {
  const packet_scene *ps;
  vvec3 o, d;
  lazy_moment *l;
  const packet_origin *po;
  vfloat dist, eps;
  int newton;
  shadow_state *sh;
  glint_stats *st;
} segment_query;

/* Each lane of m gathers the crossings in the subtree alone
 * (render/block_rays.h): the lanes blocked die, the others' kt and Beer
 * exponents take what they crossed. */
static __attribute__((cold, noinline)) void
segment_alone(void *ctx, uint32_t wide, vmask m) {
  segment_query *q = ctx;
  shadow_state *sh = q->sh;
  lane_rays lanes;
  lane_rays_store(&lanes, q->o, q->d);
  SIMD_ALIGN float kt[3][LANES], ex[3][LANES], open[3][LANES], dist[LANES];
  vf_store(kt[0], sh->kt.x), vf_store(kt[1], sh->kt.y),
      vf_store(kt[2], sh->kt.z);
  vf_store(ex[0], sh->exponent.x), vf_store(ex[1], sh->exponent.y),
      vf_store(ex[2], sh->exponent.z);
  vf_store(open[0], sh->open.x), vf_store(open[1], sh->open.y),
      vf_store(open[2], sh->open.z);
  vf_store(dist, q->dist);
  int alive = vm_bits(sh->alive), crossed = 0;
  for (int bits = vm_bits(m); bits; bits &= bits - 1) {
    int k = __builtin_ctz((unsigned)bits);
    vec3 o, d;
    lane_ray(&lanes, k, &o, &d);
    shadow_acc acc = shadow_acc_clear();
    q->st->alone_walks++;
    if (!block_segment_below(q->ps, q->ps->blocks, wide, o, d, dist[k],
                             q->newton, &acc, &q->st->alone_tests)) {
      alive &= ~(1 << k);
      continue;
    }
    if (acc.kt.x == 1 && acc.kt.y == 1 && acc.kt.z == 1 &&
        acc.exponent.x == 0 && acc.exponent.y == 0 && acc.exponent.z == 0)
      continue; /* crossed nothing */
    crossed = 1;
    kt[0][k] *= acc.kt.x, kt[1][k] *= acc.kt.y, kt[2][k] *= acc.kt.z;
    ex[0][k] += acc.exponent.x, ex[1][k] += acc.exponent.y,
        ex[2][k] += acc.exponent.z;
    open[0][k] += acc.open.x, open[1][k] += acc.open.y,
        open[2][k] += acc.open.z;
    sh->absorbed |= (acc.exponent.x != 0) | (acc.exponent.y != 0) << 1 |
                    (acc.exponent.z != 0) << 2;
  }
  sh->alive = vm_from_bits(alive);
  if (!crossed)
    return;
  sh->kt = (vvec3){vf_load(kt[0]), vf_load(kt[1]), vf_load(kt[2])};
  sh->exponent = (vvec3){vf_load(ex[0]), vf_load(ex[1]), vf_load(ex[2])};
  sh->open = (vvec3){vf_load(open[0]), vf_load(open[1]), vf_load(open[2])};
}

static ALWAYS_INLINE void segment_leaf(void *ctx, uint32_t ref, vmask alive) {
  (void)alive; /* the walk keeps it in q->sh->alive */
  segment_query *q = ctx;
  packet_cross_prim(q->ps, GLI_REF_SHAPE(ref), GLI_REF_INDEX(ref), q->o, q->d,
                    q->l, q->dist, q->eps, q->newton, q->sh);
}

/* The hybrid segment walk, apart as nearest_hybrid. */
static __attribute__((noinline)) void segment_hybrid(segment_query *q,
                                                     const gli_bvh *bvh) {
  const packet_scene *ps = q->ps;
  if (ps->alone_lanes == LANES)
    segment_alone(q, 0, q->sh->alive);
  else
    packet_bvh_segment(bvh, q->po, q->d, q->eps, q->dist, &q->sh->alive,
                       q->newton, q->st, segment_leaf, ps->alone_lanes,
                       segment_alone, q);
}

/* The plain segment walk, apart from packet_transmission where
 * PACKET_WALKS_APART. */
static __attribute__((noinline)) void segment_apart(segment_query *q,
                                                    const gli_bvh *bvh) {
  packet_bvh_segment(bvh, q->po, q->d, q->eps, q->dist, &q->sh->alive,
                     q->newton, q->st, segment_leaf, 0, segment_alone, q);
}

/* The lanes' transmission along o + t d, t in (eps, dist); po is
 * packet_origin_of(o), made once for all lights. */
static ALWAYS_INLINE vvec3 packet_transmission(const packet_scene *ps, vvec3 o,
                                               const packet_origin *po, vvec3 d,
                                               vfloat dist, vmask active,
                                               glint_math math, int newton,
                                               glint_stats *st) {
  const scene_r *s = ps->s;
  const vfloat light = dist; /* Beer's stretches run to the light */
  dist = vf_sub(
      dist, vf_max(vs_get(&ps->eps), vf_mul(dist, vf_set1(GLI_SHADOW_SHORT))));
  shadow_state sh = {{vf_set1(1), vf_set1(1), vf_set1(1)},
                     {vf_zero(), vf_zero(), vf_zero()},
                     {vf_zero(), vf_zero(), vf_zero()},
                     active,
                     0};
  vfloat eps = vs_get(&ps->eps);
  lazy_moment l = {{vf_zero(), vf_zero(), vf_zero()}, 0};
  const gli_bvh *bvh = s->bvh;
  count_tests(st, ps->outside_tests, vm_count(active));
  for (size_t i = 0; i < s->plane_count && vm_any(sh.alive); i++) {
    const pplane *pl = &ps->planes[i];
    vfloat t, nd;
    vmask c = plane_lanes(pl, o, d, sh.alive, eps, dist, newton, &t, &nd);
    shadow_cross(ps, pl->object, c, t, vf_lt(nd, vf_zero()), &sh);
  }
  if (bvh->node_count == 0) {
    for (size_t i = 0; i < s->sphere_count && vm_any(sh.alive); i++)
      packet_cross_prim(ps, GLI_SHAPE_SPHERE, (uint32_t)i, o, d, &l, dist, eps,
                        newton, &sh);
    for (size_t i = 0; i < s->triangle_count && vm_any(sh.alive); i++)
      packet_cross_prim(ps, GLI_SHAPE_TRIANGLE, (uint32_t)i, o, d, &l, dist,
                        eps, newton, &sh);
    for (size_t i = 0; i < s->cone_count && vm_any(sh.alive); i++)
      packet_cross_prim(ps, GLI_SHAPE_CONE, (uint32_t)i, o, d, &l, dist, eps,
                        newton, &sh);
  } else if (vm_any(sh.alive)) {
    segment_query q = {ps, o, d, &l, po, dist, eps, newton, &sh, st};
    if (PACKET_HAND_OVER && ps->alone_lanes)
      segment_hybrid(&q, bvh);
    else if (PACKET_WALKS_APART)
      segment_apart(&q, bvh);
    else
      packet_bvh_segment(bvh, po, d, eps, dist, &sh.alive, newton, st,
                         segment_leaf, 0, segment_alone, &q);
  }
  vvec3 z = {vf_zero(), vf_zero(), vf_zero()};
  if (vm_none(sh.alive))
    return z;
  vvec3 r = sh.kt;
  if (s->lights_in_absorbers) { /* stretches that end at the light */
    vfloat zero = vf_zero();
    sh.exponent.x = vf_fnmadd(vf_max(sh.open.x, zero), light, sh.exponent.x);
    sh.exponent.y = vf_fnmadd(vf_max(sh.open.y, zero), light, sh.exponent.y);
    sh.exponent.z = vf_fnmadd(vf_max(sh.open.z, zero), light, sh.exponent.z);
  }
  if (sh.absorbed & 1)
    r.x = vf_mul(r.x, vm_beer(vf_min(sh.exponent.x, vf_zero()), math));
  if (sh.absorbed & 2)
    r.y = vf_mul(r.y, vm_beer(vf_min(sh.exponent.y, vf_zero()), math));
  if (sh.absorbed & 4)
    r.z = vf_mul(r.z, vm_beer(vf_min(sh.exponent.z, vf_zero()), math));
  return vv_select(sh.alive, r, z);
}

#endif
