/* Packet kernels: W rays at a time in SoA layout with a lane mask (SPEC §6,
 * thesis §4.1 and listing 4.4), written once against the SIMD layer and
 * compiled once per ISA. The beam tracer (SPEC §6) and the stream tracer are
 * both built from these.
 *
 * Every function takes the pow/exp variant and the rcp Newton switch as
 * arguments; callers pass constants for the default path, so the compiler
 * folds them away there (see beam_tracer.c). */
#ifndef GLINT_RENDER_PACKET_H
#define GLINT_RENDER_PACKET_H

#include "render/packet_scene.h"
#include "scene/scene.h"
#include "simd/simd.h"
#include "simd/vmath.h"

#include <float.h>
#include <stddef.h>
#include <x86intrin.h>

#ifdef GLINT_PROFILE_NOINLINE
#define ALWAYS_INLINE __attribute__((noinline))
#else
#define ALWAYS_INLINE inline __attribute__((always_inline))
#endif

/* ---- vectors of W 3-vectors ------------------------------------------- */

typedef struct vvec3 {
  vfloat x, y, z;
} vvec3;

static ALWAYS_INLINE vvec3 vv_set1(vec3 a) {
  vvec3 r = {vf_set1(a.x), vf_set1(a.y), vf_set1(a.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_add(vvec3 a, vvec3 b) {
  vvec3 r = {vf_add(a.x, b.x), vf_add(a.y, b.y), vf_add(a.z, b.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_sub(vvec3 a, vvec3 b) {
  vvec3 r = {vf_sub(a.x, b.x), vf_sub(a.y, b.y), vf_sub(a.z, b.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_mul(vvec3 a, vvec3 b) {
  vvec3 r = {vf_mul(a.x, b.x), vf_mul(a.y, b.y), vf_mul(a.z, b.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_scale(vvec3 a, vfloat s) {
  vvec3 r = {vf_mul(a.x, s), vf_mul(a.y, s), vf_mul(a.z, s)};
  return r;
}
/* a + s b */
static ALWAYS_INLINE vvec3 vv_madd(vvec3 a, vfloat s, vvec3 b) {
  vvec3 r = {vf_fmadd(s, b.x, a.x), vf_fmadd(s, b.y, a.y),
             vf_fmadd(s, b.z, a.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_neg(vvec3 a) {
  vvec3 r = {vf_neg(a.x), vf_neg(a.y), vf_neg(a.z)};
  return r;
}
/* The thesis's SoA dot product (listing 4.5), with fused multiply-adds. */
static ALWAYS_INLINE vfloat vv_dot(vvec3 a, vvec3 b) {
  return vf_fmadd(a.x, b.x, vf_fmadd(a.y, b.y, vf_mul(a.z, b.z)));
}
static ALWAYS_INLINE vvec3 vv_cross(vvec3 a, vvec3 b) {
  vvec3 r = {vf_sub(vf_mul(a.y, b.z), vf_mul(a.z, b.y)),
             vf_sub(vf_mul(a.z, b.x), vf_mul(a.x, b.z)),
             vf_sub(vf_mul(a.x, b.y), vf_mul(a.y, b.x))};
  return r;
}
static ALWAYS_INLINE vvec3 vv_select(vmask m, vvec3 a, vvec3 b) {
  vvec3 r = {vf_select(m, a.x, b.x), vf_select(m, a.y, b.y),
             vf_select(m, a.z, b.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_normalize(vvec3 a, int newton) {
  return vv_scale(a, vf_rsqrt(vv_dot(a, a), newton));
}
/* Three consecutive vscalars (a packet-scene vec3) across lanes. */
static ALWAYS_INLINE vvec3 vv_get(const vscalar *p) {
  vvec3 r = {vs_get(&p[0]), vs_get(&p[1]), vs_get(&p[2])};
  return r;
}

/* A vec3 stored in a record, splat across lanes. It reads one float past
 * the vec3, which every record below has. */
static ALWAYS_INLINE vvec3 vv_splat(const vec3 *p) {
  vvec3 r;
  vfloat unused;
  vf_splat4(&p->x, &r.x, &r.y, &r.z, &unused);
  return r;
}

/* Lane-wise gather of a vec3 field at `offset` floats into records of
 * `stride` floats, indexed by idx. */
static ALWAYS_INLINE vvec3 vv_gather(const float *base, vint idx, int stride,
                                     int offset) {
  vint i = vi_add(vi_mul_const(idx, stride), vi_set1(offset));
  vvec3 r = {vf_gather(base, i), vf_gather(base, vi_add(i, vi_set1(1))),
             vf_gather(base, vi_add(i, vi_set1(2)))};
  return r;
}

/* ---- a packet's nearest hits ----------------------------------------- */

typedef struct packet_hit {
  vfloat t, u, v;
  vint object; /* -1: no hit */
  vint prim;
  vmask inside; /* spheres: the ray started inside */
} packet_hit;

static ALWAYS_INLINE void packet_hit_init(packet_hit *h) {
  h->t = vf_set1(FLT_MAX);
  h->u = h->v = vf_zero();
  h->object = vi_set1(-1);
  h->prim = vi_set1(0);
  h->inside = vm_false();
}

static ALWAYS_INLINE void count_tests(glint_stats *st, size_t tests,
                                      int lanes) {
  st->packet_tests += tests;
  st->active_lanes += (uint64_t)tests * (uint64_t)lanes;
}

/* Algorithm 2.1 for all lanes against one sphere: updates the hits that are
 * nearer than those found so far. */
/* Spheres and planes record only the object: each is one primitive, so the
 * object names it. */
static ALWAYS_INLINE void packet_sphere(const psphere *sp, vvec3 o, vvec3 d,
                                        vmask active, vfloat eps,
                                        packet_hit *h) {
  vvec3 v = vv_sub(vv_get(sp->center), o);
  vfloat proj = vv_dot(v, d);
  vvec3 perp = vv_madd(v, vf_neg(proj), d);
  vfloat dist2 = vv_dot(perp, perp);
  vfloat r2 = vs_get(&sp->r2);
  vmask m = vm_and(active, vf_le(dist2, r2));
  if (vm_none(m))
    return; /* the thesis's early rejection, for the whole packet */
  vfloat half = vf_sqrt(vf_sub(r2, dist2));
  vfloat l1 = vf_sub(proj, half), l2 = vf_add(proj, half);
  vmask outside = vf_gt(l1, eps);
  vfloat t = vf_select(outside, l1, l2);
  vmask win = vm_and(vm_and(m, vf_gt(l2, eps)), vf_lt(t, h->t));
  h->t = vf_select(win, t, h->t);
  h->object = vi_select(win, vi_set1(sp->object), h->object);
  h->inside = vm_select(win, vm_andnot(vm_true(), outside), h->inside);
}

/* Eq. 2.5, the division by rcp (eq. 3.1). */
static ALWAYS_INLINE void packet_plane(const pplane *pl, vvec3 o, vvec3 d,
                                       vmask active, vfloat eps, int newton,
                                       packet_hit *h) {
  vvec3 n = vv_get(pl->n);
  vfloat denom = vv_dot(n, d);
  vfloat t = vf_mul(vf_neg(vf_add(vv_dot(n, o), vs_get(&pl->d))),
                    vf_rcp(denom, newton));
  vmask win = vm_and(vm_and(active, vf_neq(denom, vf_zero())),
                     vm_and(vf_gt(t, eps), vf_lt(t, h->t)));
  h->t = vf_select(win, t, h->t);
  h->object = vi_select(win, vi_set1(pl->object), h->object);
}

/* Möller–Trumbore (eq. 2.6–2.8) refactored around the triangle's stored
 * normal N = e1 x e2, as Embree's packet intersector does: with s = O - A
 * and R = s x D, det = -D·N, u det = e2·R, v det = -e1·R, t det = s·N. One
 * cross product per ray instead of two. The division is deferred: u, v and
 * t are compared as multiples of |det| (its sign folded in), so lanes that
 * miss never pay for the reciprocal. Returns the lanes that cross the
 * triangle within (eps, tmax), with their t, u, v. */
static ALWAYS_INLINE vmask packet_triangle_cross(const ptriangle *tr, vvec3 o,
                                                 vvec3 d, vmask active,
                                                 vfloat eps, vfloat tmax,
                                                 int newton, vfloat *t,
                                                 vfloat *u, vfloat *v) {
  vvec3 n = vv_get(tr->n);
  vfloat det = vf_neg(vv_dot(d, n));
  vfloat sign = vi_as_vf(vi_and(vf_bits(det), vi_set1((int)0x80000000u)));
  vfloat adet = vf_abs(det);
  vvec3 s = vv_sub(o, vv_get(tr->a));
  vvec3 r = vv_cross(s, d);
  /* x ^ sign(det) multiplies x by the sign of det, exactly */
  vfloat us =
      vi_as_vf(vi_xor(vf_bits(vv_dot(vv_get(tr->e2), r)), vf_bits(sign)));
  vmask m = vm_and(vm_and(active, vf_gt(adet, vf_zero())),
                   vm_and(vf_ge(us, vf_zero()), vf_le(us, adet)));
  if (vm_none(m))
    return m;
  vfloat vs = vi_as_vf(
      vi_xor(vf_bits(vf_neg(vv_dot(vv_get(tr->e1), r))), vf_bits(sign)));
  m = vm_and(m, vm_and(vf_ge(vs, vf_zero()), vf_le(vf_add(us, vs), adet)));
  if (vm_none(m))
    return m;
  vfloat ts = vi_as_vf(vi_xor(vf_bits(vv_dot(s, n)), vf_bits(sign)));
  m = vm_and(
      m, vm_and(vf_gt(ts, vf_mul(eps, adet)), vf_lt(ts, vf_mul(tmax, adet))));
  if (vm_none(m))
    return m;
  vfloat inv = vf_rcp(adet, newton);
  *t = vf_mul(ts, inv);
  *u = vf_mul(us, inv);
  *v = vf_mul(vs, inv);
  /* The reciprocal's last bit can push t to the limits it was tested
   * against as a multiple of det: test again. */
  return vm_and(m, vm_and(vf_gt(*t, eps), vf_lt(*t, tmax)));
}

static ALWAYS_INLINE void packet_triangle(const ptriangle *tr, uint32_t index,
                                          vvec3 o, vvec3 d, vmask active,
                                          vfloat eps, int newton,
                                          packet_hit *h) {
  vfloat t, u, v;
  vmask win =
      packet_triangle_cross(tr, o, d, active, eps, h->t, newton, &t, &u, &v);
  if (vm_none(win))
    return;
  h->t = vf_select(win, t, h->t);
  h->u = vf_select(win, u, h->u);
  h->v = vf_select(win, v, h->v);
  h->object = vi_select(win, vi_set1(tr->object), h->object);
  h->prim = vi_select(win, vi_set1((int)index), h->prim);
}

/* The cone quadratic of cone_roots (geometry/intersect.h) for all lanes:
 * the lanes with a first and a second crossing within (eps, tmax) and the
 * height window, nearest first in *t0. */
static ALWAYS_INLINE void packet_cone_roots(const pcone *c, vvec3 o, vvec3 d,
                                            vmask active, vfloat eps,
                                            vfloat tmax, vfloat *t0, vmask *m0,
                                            vfloat *t1, vmask *m1) {
  vvec3 axis = vv_get(c->axis);
  vvec3 w = vv_sub(o, vv_get(c->base));
  vfloat k = vs_get(&c->k), rb = vs_get(&c->rb), height = vs_get(&c->height);
  vfloat wa = vv_dot(w, axis), da = vv_dot(d, axis);
  vfloat rw = vf_fmadd(k, wa, rb);
  vfloat qa = vf_fnmadd(vf_fmadd(k, k, vf_set1(1)), vf_mul(da, da), vf_set1(1));
  vfloat qb = vf_mul(vf_set1(2), vf_fnmadd(vf_mul(k, da), rw,
                                           vf_fnmadd(wa, da, vv_dot(w, d))));
  vfloat qc = vf_fnmadd(rw, rw, vf_fnmadd(wa, wa, vv_dot(w, w)));
  vfloat disc = vf_fnmadd(vf_mul(vf_set1(4), qa), qc, vf_mul(qb, qb));
  vmask m = vm_and(active, vf_ge(disc, vf_zero()));
  *m0 = *m1 = vm_false();
  if (vm_none(m))
    return;
  vfloat sq = vf_sqrt(vf_max(disc, vf_zero()));
  /* The stable pair: q = -(b + sign(b) sq) / 2, roots q/a and c/q, the
   * divisions by rcp (eq. 3.1). Along a line of the surface (a ~ 0) the
   * one root is -c/b. */
  vfloat q = vf_mul(vf_set1(-0.5f), vf_select(vf_lt(qb, vf_zero()),
                                              vf_sub(qb, sq), vf_add(qb, sq)));
  vmask linear = vf_lt(vf_abs(qa), vf_set1(1e-12f));
  vfloat ra = vf_mul(q, vf_rcp(qa, 1)), rc = vf_mul(qc, vf_rcp(q, 1));
  vfloat a0 = vf_min(ra, rc), a1 = vf_max(ra, rc);
  if (vm_any(vm_and(m, linear))) {
    vfloat lin = vf_div(vf_neg(qc), qb);
    a0 = vf_select(linear, lin, a0);
    a1 = vf_select(linear, lin, a1);
  }
  vfloat h0 = vf_fmadd(a0, da, wa), h1 = vf_fmadd(a1, da, wa);
  vmask v0 = vm_and(vm_and(m, vm_and(vf_gt(a0, eps), vf_lt(a0, tmax))),
                    vm_and(vf_ge(h0, vf_zero()), vf_le(h0, height)));
  vmask v1 = vm_and(
      vm_and(vm_andnot(m, linear), vm_and(vf_gt(a1, eps), vf_lt(a1, tmax))),
      vm_and(vf_ge(h1, vf_zero()), vf_le(h1, height)));
  /* Nearest first. */
  *t0 = vf_select(v0, a0, a1);
  *m0 = vm_or(v0, v1);
  *t1 = a1;
  *m1 = vm_and(v0, v1);
}

static ALWAYS_INLINE void packet_cone(const pcone *c, vvec3 o, vvec3 d,
                                      vmask active, vfloat eps, packet_hit *h) {
  vfloat t0, t1;
  vmask m0, m1;
  packet_cone_roots(c, o, d, active, eps, h->t, &t0, &m0, &t1, &m1);
  if (vm_none(m0))
    return;
  h->t = vf_select(m0, t0, h->t);
  h->object = vi_select(m0, vi_set1(c->object), h->object);
}

/* ---- the BVH for packets ------------------------------------------------ */

/* What the slab tests of a packet need: 1/D (a zero component made tiny,
 * so 0 * inf never makes a NaN) and -O/D. */
typedef struct packet_inv {
  vvec3 inv, neg_o_inv;
  int neg[3]; /* the packet's direction sign per axis (first active lane) */
} packet_inv;

static ALWAYS_INLINE vfloat vf_nonzero(vfloat a) {
  vfloat tiny = vf_set1(1e-30f);
  vfloat signed_tiny = vi_as_vf(
      vi_or(vf_bits(tiny), vi_and(vf_bits(a), vi_set1((int)0x80000000u))));
  return vf_select(vf_lt(vf_abs(a), tiny), signed_tiny, a);
}

static ALWAYS_INLINE packet_inv packet_inverse(vvec3 o, vvec3 d, vmask active,
                                               int newton) {
  packet_inv r;
  r.inv.x = vf_rcp(vf_nonzero(d.x), newton);
  r.inv.y = vf_rcp(vf_nonzero(d.y), newton);
  r.inv.z = vf_rcp(vf_nonzero(d.z), newton);
  r.neg_o_inv = vv_neg(vv_mul(o, r.inv));
  SIMD_ALIGN float dx[W], dy[W], dz[W];
  vf_store(dx, d.x);
  vf_store(dy, d.y);
  vf_store(dz, d.z);
  int lane = vm_any(active) ? vm_first(active) : 0;
  r.neg[0] = dx[lane] < 0;
  r.neg[1] = dy[lane] < 0;
  r.neg[2] = dz[lane] < 0;
  return r;
}

/* The slab test for all lanes of `active` against a node's box within
 * (tmin, tmax). The far distance is widened by a few ulps so rounding in
 * the reciprocal cannot cull a hit on the box's surface. */
static ALWAYS_INLINE vmask packet_box(const glint_bvh_node *n,
                                      const packet_inv *r, vfloat tmin,
                                      vfloat tmax, vmask active) {
  vfloat lx, ly, lz, hx, hy, hz, unused0, unused1;
  vf_splat4(&n->lo[0], &lx, &ly, &lz, &hx);
  vf_splat4(&n->hi[1], &hy, &hz, &unused0, &unused1);
  vfloat t0x = vf_fmadd(lx, r->inv.x, r->neg_o_inv.x);
  vfloat t1x = vf_fmadd(hx, r->inv.x, r->neg_o_inv.x);
  vfloat t0y = vf_fmadd(ly, r->inv.y, r->neg_o_inv.y);
  vfloat t1y = vf_fmadd(hy, r->inv.y, r->neg_o_inv.y);
  vfloat t0z = vf_fmadd(lz, r->inv.z, r->neg_o_inv.z);
  vfloat t1z = vf_fmadd(hz, r->inv.z, r->neg_o_inv.z);
  vfloat near = vf_max(vf_max(vf_min(t0x, t1x), vf_min(t0y, t1y)),
                       vf_max(vf_min(t0z, t1z), tmin));
  vfloat far = vf_min(vf_min(vf_max(t0x, t1x), vf_max(t0y, t1y)),
                      vf_min(vf_max(t0z, t1z), tmax));
  return vm_and(active, vf_le(near, vf_mul(far, vf_set1(1.0000005f))));
}

/* One referenced primitive against the lanes of m. */
static ALWAYS_INLINE void packet_prim(const packet_scene *ps, uint32_t ref,
                                      vvec3 o, vvec3 d, vmask m, vfloat eps,
                                      int newton, packet_hit *h) {
  uint32_t i = GLINT_REF_INDEX(ref);
  switch (GLINT_REF_SHAPE(ref)) {
  case GLINT_SHAPE_SPHERE:
    packet_sphere(&ps->spheres[i], o, d, m, eps, h);
    break;
  case GLINT_SHAPE_TRIANGLE:
    packet_triangle(&ps->triangles[i], i, o, d, m, eps, newton, h);
    break;
  default: packet_cone(&ps->cones[i], o, d, m, eps, h); break;
  }
}

/* Every object against every active lane (the thesis's brute force, §4.3):
 * per lane the nearest hit wins. */
static ALWAYS_INLINE void packet_nearest(const packet_scene *ps, vvec3 o,
                                         vvec3 d, vmask active, int newton,
                                         packet_hit *h, glint_stats *st) {
  const scene_r *s = ps->s;
  packet_hit_init(h);
  vfloat eps = vs_get(&ps->eps);
  int lanes = vm_count(active);
  count_tests(st, s->plane_count, lanes);
  for (size_t i = 0; i < s->plane_count; i++)
    packet_plane(&ps->planes[i], o, d, active, eps, newton, h);
  const glint_bvh *bvh = s->bvh;
  if (bvh->node_count == 0) {
    count_tests(st, s->sphere_count + s->triangle_count + s->cone_count, lanes);
    for (size_t i = 0; i < s->sphere_count; i++)
      packet_sphere(&ps->spheres[i], o, d, active, eps, h);
    for (size_t i = 0; i < s->triangle_count; i++)
      packet_triangle(&ps->triangles[i], (uint32_t)i, o, d, active, eps, newton,
                      h);
    for (size_t i = 0; i < s->cone_count; i++)
      packet_cone(&ps->cones[i], o, d, active, eps, h);
    return;
  }
  /* Depth first; the child the packet's direction meets first is pushed
   * last. A node's box is tested when it is popped, against the lanes'
   * nearest hits so far, so boxes behind a hit are skipped. */
  packet_inv r = packet_inverse(o, d, active, newton);
  uint32_t stack[GLINT_BVH_MAX_DEPTH];
  int sp = 0;
  stack[sp++] = 0;
  while (sp > 0) {
    const glint_bvh_node *n = &bvh->nodes[stack[--sp]];
    vmask m = packet_box(n, &r, eps, h->t, active);
    count_tests(st, 1, lanes);
    if (vm_none(m))
      continue;
    if (n->count == 0) {
      int far = !r.neg[n->axis];
      stack[sp++] = n->offset + (uint32_t)far;
      stack[sp++] = n->offset + (uint32_t)!far;
    } else {
      count_tests(st, n->count, vm_count(m));
      for (uint32_t k = 0; k < n->count; k++)
        packet_prim(ps, bvh->refs[n->offset + k], o, d, m, eps, newton, h);
    }
  }
}

/* ---- shadow rays ------------------------------------------------------ */

/* SPEC §4's transmission toward a light, for W shadow rays at once (the
 * scalar_transmission of scalar_scene.c, lane-parallel): each opaque crossing
 * kills its lane; each transparent one multiplies by kt and adds to the Beer
 * exponent (+a t entering, -a t leaving). */
typedef struct shadow_state {
  vvec3 kt, exponent;
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
    sh->exponent = vv_madd(sh->exponent, st, vv_get(pm->absorb));
    sh->absorbed |=
        (m->absorb.x != 0) | (m->absorb.y != 0) << 1 | (m->absorb.z != 0) << 2;
  }
}

/* Every crossing of one primitive by the shadow lanes within (eps, dist). */
static ALWAYS_INLINE void packet_cross_prim(const packet_scene *ps,
                                            uint32_t shape, uint32_t i, vvec3 o,
                                            vvec3 d, vfloat dist, vfloat eps,
                                            int newton, shadow_state *sh) {
  switch (shape) {
  case GLINT_SHAPE_SPHERE: {
    const psphere *sp = &ps->spheres[i];
    vvec3 v = vv_sub(vv_get(sp->center), o);
    vfloat proj = vv_dot(v, d);
    vvec3 perp = vv_madd(v, vf_neg(proj), d);
    vfloat dist2 = vv_dot(perp, perp);
    vfloat r2 = vs_get(&sp->r2);
    vmask m = vm_and(sh->alive, vf_le(dist2, r2));
    if (vm_none(m))
      return;
    vfloat half = vf_sqrt(vf_sub(r2, dist2));
    vfloat l1 = vf_sub(proj, half), l2 = vf_add(proj, half);
    vmask c1 = vm_and(m, vm_and(vf_gt(l1, eps), vf_lt(l1, dist)));
    vmask c2 = vm_and(m, vm_and(vf_gt(l2, eps), vf_lt(l2, dist)));
    shadow_cross(ps, sp->object, c1, l1, vm_true(), sh);
    shadow_cross(ps, sp->object, c2, l2, vm_false(), sh);
    break;
  }
  case GLINT_SHAPE_TRIANGLE: {
    const ptriangle *tr = &ps->triangles[i];
    vfloat t, u, v;
    vmask c = packet_triangle_cross(tr, o, d, sh->alive, eps, dist, newton, &t,
                                    &u, &v);
    /* Entering: against the normal, which the unnormalised one shares. */
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
      vvec3 q = vv_sub(vv_madd(o, t, d), vv_get(c->base));
      vvec3 axis = vv_get(c->axis);
      vfloat hq = vv_dot(q, axis);
      vfloat kk = vs_get(&c->k);
      vvec3 n = vv_madd(
          q, vf_neg(vf_fmadd(kk, vf_fmadd(kk, hq, vs_get(&c->rb)), hq)), axis);
      shadow_cross(ps, c->object, k ? m1 : m0, t,
                   vf_lt(vv_dot(n, d), vf_zero()), sh);
    }
    break;
  }
  }
}

static ALWAYS_INLINE vvec3 packet_transmission(const packet_scene *ps, vvec3 o,
                                               vvec3 d, vfloat dist,
                                               vmask active, glint_math math,
                                               int newton, glint_stats *st) {
  const scene_r *s = ps->s;
  shadow_state sh = {{vf_set1(1), vf_set1(1), vf_set1(1)},
                     {vf_zero(), vf_zero(), vf_zero()},
                     active,
                     0};
  vfloat eps = vs_get(&ps->eps);
  int lanes = vm_count(active);
  count_tests(st, s->plane_count, lanes);
  for (size_t i = 0; i < s->plane_count && vm_any(sh.alive); i++) {
    const pplane *pl = &ps->planes[i];
    vvec3 n = vv_get(pl->n);
    vfloat denom = vv_dot(n, d);
    vfloat t = vf_mul(vf_neg(vf_add(vv_dot(n, o), vs_get(&pl->d))),
                      vf_rcp(denom, newton));
    vmask c = vm_and(vm_and(sh.alive, vf_neq(denom, vf_zero())),
                     vm_and(vf_gt(t, eps), vf_lt(t, dist)));
    shadow_cross(ps, pl->object, c, t, vf_lt(denom, vf_zero()), &sh);
  }
  const glint_bvh *bvh = s->bvh;
  if (bvh->node_count == 0) {
    count_tests(st, s->sphere_count + s->triangle_count + s->cone_count, lanes);
    for (size_t i = 0; i < s->sphere_count && vm_any(sh.alive); i++)
      packet_cross_prim(ps, GLINT_SHAPE_SPHERE, (uint32_t)i, o, d, dist, eps,
                        newton, &sh);
    for (size_t i = 0; i < s->triangle_count && vm_any(sh.alive); i++)
      packet_cross_prim(ps, GLINT_SHAPE_TRIANGLE, (uint32_t)i, o, d, dist, eps,
                        newton, &sh);
    for (size_t i = 0; i < s->cone_count && vm_any(sh.alive); i++)
      packet_cross_prim(ps, GLINT_SHAPE_CONE, (uint32_t)i, o, d, dist, eps,
                        newton, &sh);
  } else if (vm_any(sh.alive)) {
    /* Every node the lanes' segments pass through; done when every lane
     * is blocked. */
    packet_inv r = packet_inverse(o, d, sh.alive, newton);
    uint32_t stack[GLINT_BVH_MAX_DEPTH];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0 && vm_any(sh.alive)) {
      const glint_bvh_node *n = &bvh->nodes[stack[--sp]];
      vmask m = packet_box(n, &r, eps, dist, sh.alive);
      count_tests(st, 1, vm_count(sh.alive));
      if (vm_none(m))
        continue;
      if (n->count == 0) {
        stack[sp++] = n->offset + 1;
        stack[sp++] = n->offset;
      } else {
        vmask keep = vm_andnot(sh.alive, m); /* lanes not in this box */
        sh.alive = m;
        count_tests(st, n->count, vm_count(m));
        for (uint32_t k = 0; k < n->count && vm_any(sh.alive); k++) {
          uint32_t ref = bvh->refs[n->offset + k];
          packet_cross_prim(ps, GLINT_REF_SHAPE(ref), GLINT_REF_INDEX(ref), o,
                            d, dist, eps, newton, &sh);
        }
        sh.alive = vm_or(sh.alive, keep);
      }
    }
  }
  vvec3 z = {vf_zero(), vf_zero(), vf_zero()};
  if (vm_none(sh.alive))
    return z;
  vvec3 r = sh.kt;
  if (sh.absorbed & 1)
    r.x = vf_mul(r.x, vm_exp(vf_min(sh.exponent.x, vf_zero()), math));
  if (sh.absorbed & 2)
    r.y = vf_mul(r.y, vm_exp(vf_min(sh.exponent.y, vf_zero()), math));
  if (sh.absorbed & 4)
    r.z = vf_mul(r.z, vm_exp(vf_min(sh.exponent.z, vf_zero()), math));
  return vv_select(sh.alive, r, z);
}

/* ---- surfaces and local shading -------------------------------------- */

/* Where the lanes of a sub-beam met one object, with the normal facing the
 * ray. */
typedef struct packet_surface {
  vvec3 p, n;
  vmask front; /* hit the outside: entering a closed object */
} packet_surface;

#define FLOATS_OF(type) ((int)(sizeof(type) / sizeof(float)))
#define FLOAT_OFFSET(type, field) ((int)(offsetof(type, field) / sizeof(float)))

static ALWAYS_INLINE packet_surface packet_surface_at(const packet_scene *ps,
                                                      const object_r *ob,
                                                      const packet_hit *h,
                                                      vvec3 o, vvec3 d,
                                                      int newton) {
  const scene_r *s = ps->s;
  packet_surface f;
  f.p = vv_madd(o, h->t, d);
  vvec3 ng;
  switch (ob->shape) {
  case GLINT_SHAPE_SPHERE:
    /* Normalised, not scaled by 1/r: see surface_at in scalar_tracer.c. */
    ng = vv_normalize(vv_sub(f.p, vv_get(ps->spheres[ob->first].center)),
                      newton);
    f.front = vm_andnot(vm_true(), h->inside);
    break;
  case GLINT_SHAPE_PLANE:
    ng = vv_get(ps->planes[ob->first].n);
    f.front = vf_lt(vv_dot(ng, d), vf_zero());
    break;
  case GLINT_SHAPE_CONE: {
    /* q - h a - k (rb + k h) a: see cone_normal in geometry/intersect.h */
    const pcone *c = &ps->cones[ob->first];
    vvec3 axis = vv_get(c->axis);
    vvec3 q = vv_sub(f.p, vv_get(c->base));
    vfloat hq = vv_dot(q, axis), k = vs_get(&c->k);
    ng = vv_normalize(
        vv_madd(q, vf_neg(vf_fmadd(k, vf_fmadd(k, hq, vs_get(&c->rb)), hq)),
                axis),
        newton);
    f.front = vf_lt(vv_dot(ng, d), vf_zero());
    break;
  }
  default: /* triangles */
    if (ob->count == 1)
      ng = vv_set1(s->triangles[ob->first].ng);
    else
      ng = vv_gather((const float *)s->triangles, h->prim,
                     FLOATS_OF(triangle_r), FLOAT_OFFSET(triangle_r, ng));
    f.front = vf_lt(vv_dot(ng, d), vf_zero());
    if (ob->smooth) {
      /* Interpolated vertex normals (NFF polygonal patches). */
      vint n0 = vf_bits(
          vf_gather((const float *)s->triangles,
                    vi_add(vi_mul_const(h->prim, FLOATS_OF(triangle_r)),
                           vi_set1(FLOAT_OFFSET(triangle_r, normals)))));
      /* Lanes outside the sub-beam may hold a flat triangle's -1. */
      n0 = vi_mul_const(vi_select(vi_eq(n0, vi_set1(-1)), vi_set1(0), n0), 3);
      const float *nb = (const float *)s->normals;
      vvec3 a = vv_gather(nb, n0, 1, 0);
      vvec3 b = vv_gather(nb, n0, 1, 3);
      vvec3 c = vv_gather(nb, n0, 1, 6);
      vfloat w = vf_sub(vf_sub(vf_set1(1), h->u), h->v);
      vvec3 n = vv_madd(vv_madd(vv_scale(a, w), h->u, b), h->v, c);
      n = vv_normalize(n, newton);
      vmask facing = vf_lt(vv_dot(n, d), vf_zero());
      f.n = vv_select(facing, n, vv_neg(n));
      return f;
    }
    break;
  }
  f.n = vv_select(f.front, ng, vv_neg(ng));
  return f;
}

/* floor(a) mod 2, as 0 or 1, without integer conversion (exact while the
 * cell index fits a float's 24 bits; farther out every index is even). */
static ALWAYS_INLINE vfloat vf_parity(vfloat f) {
  return vf_fnmadd(vf_set1(2), vf_floor(vf_mul(f, vf_set1(0.5f))), f);
}

/* The surface colour C (SPEC §4 textures) for one material: the parity of
 * the sum of the cell indices picks the checker colour. */
static ALWAYS_INLINE vvec3 packet_color(const material_r *m,
                                        const pmaterial *pm, const object_r *ob,
                                        vvec3 p) {
  if (m->texture == GLINT_TEXTURE_NONE)
    return vv_get(pm->color);
  vfloat cells;
  vfloat inv = vs_get(&pm->inv_size);
  if (m->texture == GLINT_TEXTURE_CHECKER_PLANAR) {
    vfloat axes[3] = {p.x, p.y, p.z};
    cells = vf_add(vf_floor(vf_mul(axes[ob->axis_u], inv)),
                   vf_floor(vf_mul(axes[ob->axis_v], inv)));
  } else {
    vvec3 q = vv_scale(vv_sub(p, vv_set1(ob->origin)), inv);
    cells = vf_add(vf_add(vf_floor(q.x), vf_floor(q.y)), vf_floor(q.z));
  }
  vmask odd = vf_eq(vf_parity(cells), vf_set1(1));
  return vv_select(odd, vv_get(pm->odd), vv_get(pm->even));
}

/* The unit direction l from p to a light, its distance, and N·l; returns
 * the lanes of m that face the light (the others need no shadow ray). */
static ALWAYS_INLINE vmask packet_toward_light(const plight *li, vvec3 p,
                                               vvec3 n, vmask m, int newton,
                                               vvec3 *l, vfloat *dist,
                                               vfloat *nl) {
  vvec3 v = vv_sub(vv_get(li->position), p);
  vfloat dist2 = vv_dot(v, v);
  vfloat inv = vf_rsqrt(dist2, newton);
  *dist = vf_mul(dist2, inv);
  *l = vv_scale(v, inv);
  *nl = vv_dot(n, *l);
  return vm_and(m, vf_gt(*nl, vf_zero()));
}

/* Eq. 2.9/2.10's local part for the lanes of m, whose coefficients may
 * differ lane by lane (a beam's sub-beams, a stream's mixed packet) or not:
 *   C (ka Ia + sum S kd N·L IL) + sum S ks (V·R)^h IL,
 * one shadow packet per light. `highlights` = 0 says no lane has ks > 0.
 * When `shadow_ticks` is given, the time-stamp cycles spent tracing shadow
 * rays are added to it (the stream tracer's stage timing). */
static ALWAYS_INLINE vvec3 packet_lights(
    const packet_scene *ps, const packet_surface *f, vvec3 d, vmask m, vvec3 c,
    vvec3 ambient, vfloat kd, vfloat ks, vfloat h, int highlights,
    glint_math math, int newton, glint_stats *st, uint64_t *shadow_ticks) {
  const scene_r *s = ps->s;
  vvec3 diffuse = ambient;
  vvec3 highlight = {vf_zero(), vf_zero(), vf_zero()};
  for (size_t j = 0; j < s->light_count; j++) {
    const plight *li = &ps->lights[j];
    vvec3 l;
    vfloat dist, nl;
    vmask lit = packet_toward_light(li, f->p, f->n, m, newton, &l, &dist, &nl);
    if (vm_none(lit))
      continue;
    st->shadow_rays += (uint64_t)vm_count(lit);
    uint64_t t0 = shadow_ticks ? __rdtsc() : 0;
    vvec3 sj = packet_transmission(ps, f->p, l, dist, lit, math, newton, st);
    if (shadow_ticks)
      *shadow_ticks += __rdtsc() - t0;
    vvec3 il = vv_mul(sj, vv_get(li->color));
    diffuse = vv_madd(diffuse, vf_keep(lit, vf_mul(kd, nl)), il);
    if (highlights) {
      /* R = 2(L·N)N - L, and V = -D: V·R = 2(L·N)(-D·N) + D·L */
      vfloat vr =
          vf_fmadd(vf_add(nl, nl), vf_neg(vv_dot(d, f->n)), vv_dot(d, l));
      vmask hl =
          vm_and(vm_and(lit, vf_gt(ks, vf_zero())), vf_gt(vr, vf_zero()));
      if (vm_any(hl)) {
        vfloat p = vm_pow(vf_max(vr, vf_set1(FLT_MIN)), h, math);
        highlight = vv_madd(highlight, vf_keep(hl, vf_mul(ks, p)), il);
      }
    }
  }
  return vv_add(vv_mul(c, diffuse), highlight);
}

/* Eq. 2.12 and 2.13 for the lanes of m. The refracted directions are valid
 * in *refract_mask; lanes with total internal reflection are not in it and
 * their reflection weight is kr + kt. */
static ALWAYS_INLINE void packet_secondary(const material_r *mat,
                                           const pmaterial *pm,
                                           const packet_surface *f, vvec3 d,
                                           vmask m, vvec3 *reflected,
                                           vfloat *kr, vvec3 *refracted,
                                           vmask *refract_mask, vmask *tir) {
  vfloat cosi = vf_neg(vv_dot(d, f->n));
  *reflected = vv_madd(d, vf_add(cosi, cosi), f->n);
  *kr = vs_get(&pm->kr);
  *refract_mask = vm_false();
  *tir = vm_false();
  if (mat->kt > 0) {
    vfloat eta = vf_select(f->front, vs_get(&pm->eta_in), vs_get(&pm->eta_out));
    vfloat k = vf_fnmadd(vf_mul(eta, eta), vf_fnmadd(cosi, cosi, vf_set1(1)),
                         vf_set1(1));
    *tir = vm_and(m, vf_lt(k, vf_zero()));
    *refract_mask = vm_andnot(m, *tir);
    vfloat coef = vf_sub(vf_mul(eta, cosi), vf_sqrt(vf_max(k, vf_zero())));
    *refracted = vv_madd(vv_scale(d, eta), coef, f->n);
    *kr = vf_select(*tir, vs_get(&pm->kr_tir), *kr);
  }
}

/* Beer's law (eq. 2.11) on the lanes that travelled inside the object. */
static ALWAYS_INLINE vvec3 packet_beer(const material_r *mat,
                                       const pmaterial *pm,
                                       const packet_surface *f, vfloat t,
                                       vmask m, vvec3 color, glint_math math) {
  if (!mat->absorbs)
    return color;
  vmask inside = vm_andnot(m, f->front);
  if (vm_none(inside))
    return color;
  vfloat nt = vf_neg(t);
  /* exp(0) = 1: channels that absorb nothing are left alone. */
  if (mat->absorb.x != 0)
    color.x = vf_select(
        inside,
        vf_mul(color.x, vm_exp(vf_mul(vs_get(&pm->absorb[0]), nt), math)),
        color.x);
  if (mat->absorb.y != 0)
    color.y = vf_select(
        inside,
        vf_mul(color.y, vm_exp(vf_mul(vs_get(&pm->absorb[1]), nt), math)),
        color.y);
  if (mat->absorb.z != 0)
    color.z = vf_select(
        inside,
        vf_mul(color.z, vm_exp(vf_mul(vs_get(&pm->absorb[2]), nt), math)),
        color.z);
  return color;
}

#endif
