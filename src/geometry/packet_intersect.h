/* Ray-primitive intersection for W rays at a time (thesis §4.1, listing
 * 4.4): the packet forms of geometry/intersect.h's tests, against the
 * packet scene's records (render/packet_scene.h). Each updates the lanes'
 * nearest hits.
 *
 * Each formula is written once over lanes of rays and lanes of primitives
 * (the *_lanes functions): a packet passes its W rays and one primitive
 * broadcast; a single ray passes itself broadcast and W primitives of a
 * leaf block (render/leaf_blocks.h). */
#ifndef GLINT_GEOMETRY_PACKET_INTERSECT_H
#define GLINT_GEOMETRY_PACKET_INTERSECT_H

#include "render/leaf_blocks.h"
#include "render/packet_scene.h"
#include "scene/scene.h"
#include "simd/vvec3.h"

#include <float.h>

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

/* Algorithm 2.1's two crossings l1 <= l2 of the line with the sphere, for
 * the lanes of the result (the others miss it). The distance to the centre
 * is taken perpendicular to the ray, the stable form of sphere_roots
 * (geometry/intersect.h). */
static ALWAYS_INLINE vmask sphere_lanes(vvec3 center, vfloat r2, vvec3 o,
                                        vvec3 d, vmask active, vfloat *l1,
                                        vfloat *l2) {
  vvec3 v = vv_sub(center, o);
  vfloat proj = vv_dot(v, d);
  vvec3 perp = vv_madd(v, vf_neg(proj), d);
  vfloat dist2 = vv_dot(perp, perp);
  vmask m = vm_and(active, vf_le(dist2, r2));
  if (vm_none(m))
    return m; /* the thesis's early rejection, for the whole packet */
  vfloat half = vf_sqrt(vf_sub(r2, dist2));
  *l1 = vf_sub(proj, half), *l2 = vf_add(proj, half);
  return m;
}

/* The crossing a ray meets first beyond eps, of the two sphere_lanes found
 * for the lanes of m: l1 from outside, l2 from inside (*outside says
 * which); returns the lanes where it lies nearer than tmax. */
static ALWAYS_INLINE vmask sphere_first(vmask m, vfloat l1, vfloat l2,
                                        vfloat eps, vfloat tmax, vfloat *t,
                                        vmask *outside) {
  *outside = vf_gt(l1, eps);
  *t = vf_select(*outside, l1, l2);
  return vm_and(vm_and(m, vf_gt(l2, eps)), vf_lt(*t, tmax));
}

/* Algorithm 2.1 for all lanes against one sphere: updates the hits that are
 * nearer than those found so far. */
/* Spheres and planes record only the object: each is one primitive, so the
 * object names it. */
static ALWAYS_INLINE void packet_sphere(const psphere *sp, vvec3 o, vvec3 d,
                                        vmask active, vfloat eps,
                                        packet_hit *h) {
  vfloat l1, l2;
  vmask m =
      sphere_lanes(vv_get(sp->center), vs_get(&sp->r2), o, d, active, &l1, &l2);
  if (vm_none(m))
    return;
  vfloat t;
  vmask outside;
  vmask win = sphere_first(m, l1, l2, eps, h->t, &t, &outside);
  h->t = vf_select(win, t, h->t);
  h->object = vi_select(win, vi_set1(sp->object), h->object);
  h->inside = vm_select(win, vm_andnot(vm_true(), outside), h->inside);
}

/* Eq. 2.5 for all lanes, the division by rcp (eq. 3.1): the lanes of
 * `active` that cross the plane within (eps, tmax), with their t and N·D
 * (negative: from the front). */
static ALWAYS_INLINE vmask plane_lanes(const pplane *pl, vvec3 o, vvec3 d,
                                       vmask active, vfloat eps, vfloat tmax,
                                       int newton, vfloat *t, vfloat *nd) {
  vvec3 n = vv_get(pl->n);
  vfloat denom = vv_dot(n, d);
  *t = vf_mul(vf_neg(vf_add(vv_dot(n, o), vs_get(&pl->d))),
              vf_rcp(denom, newton));
  *nd = denom;
  return vm_and(vm_and(active, vf_neq(denom, vf_zero())),
                vm_and(vf_gt(*t, eps), vf_lt(*t, tmax)));
}

static ALWAYS_INLINE void packet_plane(const pplane *pl, vvec3 o, vvec3 d,
                                       vmask active, vfloat eps, int newton,
                                       packet_hit *h) {
  vfloat t, nd;
  vmask win = plane_lanes(pl, o, d, active, eps, h->t, newton, &t, &nd);
  h->t = vf_select(win, t, h->t);
  h->object = vi_select(win, vi_set1(pl->object), h->object);
}

/* Where a triangle test reads its triangles: one, broadcast to every lane,
 * or a leaf block's, one a lane. Each field is read where the formula uses
 * it, so that a broadcast folds into the instruction using it and a packet
 * that misses after two edges never reads the rest (building all 24
 * vectors first cost the stream backends 8% on gears-s4). The choice is a
 * constant at every call: the test is compiled once for each. */
typedef struct triangle_lanes {
  int in_block; /* 0: `one`; 1: `block` */
  const ptriangle *one;
  const block_triangle *block;
} triangle_lanes;

static ALWAYS_INLINE vvec3 tri_edge(triangle_lanes tr, int k) {
  return tr.in_block ? block_vec(tr.block->edge[k]) : vv_get(tr.one->edge[k]);
}
static ALWAYS_INLINE vvec3 tri_moment(triangle_lanes tr, int k) {
  return tr.in_block ? block_vec(tr.block->moment[k])
                     : vv_get(tr.one->moment[k]);
}
static ALWAYS_INLINE vvec3 tri_normal(triangle_lanes tr) {
  return tr.in_block ? block_vec(tr.block->n) : vv_get(tr.one->n);
}
static ALWAYS_INLINE vvec3 tri_vertex(triangle_lanes tr) {
  return tr.in_block ? block_vec(tr.block->a) : vv_get(tr.one->a);
}

/* The watertight test of triangle_hit (geometry/intersect.h) for all lanes,
 * l = (O - R) x D being the lanes' packet_triangle_moment. The divisions are
 * deferred: t is compared as a multiple of |N·D| (its sign folded in), so
 * lanes that miss never pay for a reciprocal. Returns the lanes that cross
 * the triangle within (eps, tmax), with their t, u, v. */
static ALWAYS_INLINE vmask triangle_cross_lanes(triangle_lanes tr, vvec3 o,
                                                vvec3 d, vvec3 l, vmask active,
                                                vfloat eps, vfloat tmax,
                                                int newton, vfloat *t,
                                                vfloat *u, vfloat *v) {
  vfloat side_ab = vv_dot_add(d, tri_moment(tr, 0), vv_dot(tri_edge(tr, 0), l));
  vfloat side_bc = vv_dot_add(d, tri_moment(tr, 1), vv_dot(tri_edge(tr, 1), l));
  vfloat side_ca = vv_dot_add(d, tri_moment(tr, 2), vv_dot(tri_edge(tr, 2), l));
  /* A lane misses where some side is negative and some positive: its
   * least below zero and its greatest above. */
  vfloat zero = vf_zero();
  vfloat least = vf_min(vf_min(side_ab, side_bc), side_ca);
  vfloat greatest = vf_max(vf_max(side_ab, side_bc), side_ca);
  vmask m =
      vm_andnot(active, vm_and(vf_lt(least, zero), vf_gt(greatest, zero)));
  if (vm_none(m))
    return m;
  vvec3 n = tri_normal(tr);
  vfloat nd = vv_dot(n, d);
  vfloat sign = vi_as_vf(vi_and(vf_bits(nd), vi_set1((int)0x80000000u)));
  vfloat and_ = vf_abs(nd);
  /* x ^ sign(N·D) multiplies x by that sign, exactly */
  vfloat ts = vi_as_vf(
      vi_xor(vf_bits(vv_dot(n, vv_sub(tri_vertex(tr), o))), vf_bits(sign)));
  vfloat det = vf_add(vf_add(side_ab, side_bc), side_ca);
  m = vm_and(m, vm_and(vm_and(vf_gt(and_, zero), vf_neq(det, zero)),
                       vm_and(vf_gt(ts, vf_mul(eps, and_)),
                              vf_lt(ts, vf_mul(tmax, and_)))));
  if (vm_none(m))
    return m;
  *t = vf_mul(ts, vf_rcp(and_, newton));
  vfloat inv_det = vf_rcp(det, newton);
  *u = vf_mul(side_ca, inv_det); /* the weight of B, opposite edge CA */
  *v = vf_mul(side_ab, inv_det); /* of C */
  /* The reciprocal's last bit can push t to the limits it was tested
   * against as a multiple of N·D: test again. */
  return vm_and(m, vm_and(vf_gt(*t, eps), vf_lt(*t, tmax)));
}

/* triangle_cross_lanes for one triangle and the packet's lanes. */
static ALWAYS_INLINE vmask packet_triangle_cross(const ptriangle *tr, vvec3 o,
                                                 vvec3 d, vvec3 l, vmask active,
                                                 vfloat eps, vfloat tmax,
                                                 int newton, vfloat *t,
                                                 vfloat *u, vfloat *v) {
  triangle_lanes one = {0, tr, NULL};
  return triangle_cross_lanes(one, o, d, l, active, eps, tmax, newton, t, u, v);
}

/* The lanes' L = (O - R) x D for packet_triangle_cross. */
static ALWAYS_INLINE vvec3 packet_triangle_moment(const vscalar *origin,
                                                  vvec3 o, vvec3 d) {
  return vv_cross(vv_sub(o, vv_get(origin)), d);
}

static ALWAYS_INLINE void packet_triangle(const ptriangle *tr, uint32_t index,
                                          vvec3 o, vvec3 d, vvec3 l,
                                          vmask active, vfloat eps, int newton,
                                          packet_hit *h) {
  vfloat t, u, v;
  vmask win =
      packet_triangle_cross(tr, o, d, l, active, eps, h->t, newton, &t, &u, &v);
  if (vm_none(win))
    return;
  h->t = vf_select(win, t, h->t);
  h->u = vf_select(win, u, h->u);
  h->v = vf_select(win, v, h->v);
  h->object = vi_select(win, vi_set1(tr->object), h->object);
  h->prim = vi_select(win, vi_set1((int)index), h->prim);
}

/* A cone's fields as lanes (see pcone). */
typedef struct cone_lanes {
  vvec3 base, axis;
  vfloat height, rb, k, reach2;
} cone_lanes;

/* The lanes of `active` whose lines may meet the cone, w = o - base: a
 * cone lies within the cylinder of its widest radius R about its axis, and
 * a line of direction d (unit) passes the axis line at the distance
 * |w.n|/|n|, n = d x axis, which a line that meets the cone does not
 * exceed. Most of a packet's cone tests miss it whole, and this test takes
 * about a third of the instructions of the quadratic that would find so.
 * Conservative: w.n is computed within 8u|w| of its value (u = 2^-24: u|w|
 * from w's rounding, 4u|w| from n's, 3u|w||n| from the dot), so a line
 * within R is kept when (w.n)^2 <= (R|n| + e)^2 with e = 16u(|w| + R); and
 * (x + e)^2 <= (1 + 1/16) x^2 + 17 e^2 <= reach2 |n|^2 + 2^-34 (|w|^2 +
 * reach2), reach2 being 1.07 R^2 (cone_r), which also covers the rounding
 * of these sums and of the roots' window. A line along the axis (n = 0) is
 * kept. */
static ALWAYS_INLINE vmask cone_reach_lanes(const cone_lanes *c, vvec3 w,
                                            vvec3 d, vmask active) {
  vvec3 n = vv_cross(d, c->axis);
  vfloat wn = vv_dot(w, n);
  vfloat slack = vf_mul(vf_set1(0x1p-34f), vv_dot_add(w, w, c->reach2));
  vfloat bound = vf_fmadd(c->reach2, vv_dot(n, n), slack);
  return vm_and(active, vf_le(vf_mul(wn, wn), bound));
}

/* The cone quadratic of cone_roots (geometry/intersect.h) for all lanes:
 * the lanes with a first and a second crossing within (eps, tmax) and the
 * height window, nearest first in *t0. */
static ALWAYS_INLINE void cone_roots_lanes(const cone_lanes *c, vvec3 o,
                                           vvec3 d, vmask active, vfloat eps,
                                           vfloat tmax, vfloat *t0, vmask *m0,
                                           vfloat *t1, vmask *m1) {
  /* From the ray's point nearest the base, o + s d, as cone_roots in
   * geometry/intersect.h explains. */
  vvec3 axis = c->axis;
  vvec3 w = vv_sub(o, c->base);
  *m0 = *m1 = vm_false();
  active = cone_reach_lanes(c, w, d, active);
  if (vm_none(active))
    return;
  vfloat k = c->k, rb = c->rb, height = c->height;
  vfloat s = vf_neg(vv_dot(w, d));
  w = vv_madd(w, s, d);
  vfloat wa = vv_dot(w, axis), da = vv_dot(d, axis);
  vfloat rw = vf_fmadd(k, wa, rb);
  vfloat qa = vf_fnmadd(vf_fmadd(k, k, vf_set1(1)), vf_mul(da, da), vf_set1(1));
  vfloat hb = /* half of b */
      vf_fnmadd(vf_mul(k, da), rw, vf_fnmadd(wa, da, vv_dot(w, d)));
  vfloat qc = vf_fnmadd(rw, rw, vf_fnmadd(wa, wa, vv_dot(w, w)));
  vfloat disc = vf_fnmadd(qa, qc, vf_mul(hb, hb));
  vmask m = vm_and(active, vf_ge(disc, vf_zero()));
  if (vm_none(m))
    return;
  vfloat sq = vf_sqrt(vf_max(disc, vf_zero()));
  /* The stable pair: q = -(hb + sign(hb) sq), roots q/a and c/q, the
   * divisions by rcp (eq. 3.1). Along a line of the surface (a ~ 0) the
   * one root is -c/(2 hb). */
  vfloat q =
      vf_neg(vf_select(vf_lt(hb, vf_zero()), vf_sub(hb, sq), vf_add(hb, sq)));
  vmask linear = vf_lt(vf_abs(qa), vf_set1(1e-12f));
  vfloat ra = vf_mul(q, vf_rcp(qa, 1)), rc = vf_mul(qc, vf_rcp(q, 1));
  vfloat a0 = vf_min(ra, rc), a1 = vf_max(ra, rc);
  if (vm_any(vm_and(m, linear))) {
    vfloat lin = vf_div(vf_neg(qc), vf_add(hb, hb));
    a0 = vf_select(linear, lin, a0);
    a1 = vf_select(linear, lin, a1);
  }
  vfloat h0 = vf_fmadd(a0, da, wa), h1 = vf_fmadd(a1, da, wa);
  vfloat t0s = vf_add(s, a0), t1s = vf_add(s, a1);
  vmask v0 = vm_and(vm_and(m, vm_and(vf_gt(t0s, eps), vf_lt(t0s, tmax))),
                    vm_and(vf_ge(h0, vf_zero()), vf_le(h0, height)));
  vmask v1 = vm_and(
      vm_and(vm_andnot(m, linear), vm_and(vf_gt(t1s, eps), vf_lt(t1s, tmax))),
      vm_and(vf_ge(h1, vf_zero()), vf_le(h1, height)));
  /* Nearest first. */
  *t0 = vf_select(v0, t0s, t1s);
  *m0 = vm_or(v0, v1);
  *t1 = t1s;
  *m1 = vm_and(v0, v1);
}

/* cone_roots_lanes for one cone and the packet's lanes. */
static ALWAYS_INLINE void packet_cone_roots(const pcone *c, vvec3 o, vvec3 d,
                                            vmask active, vfloat eps,
                                            vfloat tmax, vfloat *t0, vmask *m0,
                                            vfloat *t1, vmask *m1) {
  cone_lanes lanes = {vv_get(c->base), vv_get(c->axis), vs_get(&c->height),
                      vs_get(&c->rb),  vs_get(&c->k),   vs_get(&c->reach2)};
  cone_roots_lanes(&lanes, o, d, active, eps, tmax, t0, m0, t1, m1);
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

/* ---- surface normals ---------------------------------------------------- */

/* A sphere's outward unit normal at p. Normalised, not scaled by 1/r: see
 * surface_at in render/scalar_tracer.c. */
static ALWAYS_INLINE vvec3 packet_sphere_normal(vvec3 center, vvec3 p,
                                                int newton) {
  return vv_normalize(vv_sub(p, center), newton);
}

/* A cone's outward normal at p, not normalised:
 * q - h a - k (rb + k h) a with q = p - base, h = q.a (cone_normal in
 * geometry/intersect.h). */
static ALWAYS_INLINE vvec3 packet_cone_normal(vvec3 base, vvec3 axis, vfloat rb,
                                              vfloat k, vvec3 p) {
  vvec3 q = vv_sub(p, base);
  vfloat hq = vv_dot(q, axis);
  return vv_madd(q, vf_neg(vf_fmadd(k, vf_fmadd(k, hq, rb), hq)), axis);
}

#endif
