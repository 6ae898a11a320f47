/* Ray-primitive intersection for one ray (SPEC §3, thesis §2.4), in the
 * translation unit's precision. A hit counts only for tmin < t < tmax. */
#ifndef GLINT_GEOMETRY_INTERSECT_H
#define GLINT_GEOMETRY_INTERSECT_H

#include "math/vec3.h"

/* Sphere by the geometric algorithm 2.1: project v = S - O on the (unit)
 * direction, reject when the ray passes farther than r from the centre, then
 * l1 = proj - half chord, l2 = proj + half chord. The squared distance is
 * taken from the perpendicular v - proj*d rather than |v|^2 - proj^2: the same
 * quantity, without the cancellation that ruins it in float for spheres far
 * from the origin (Haines et al., Ray Tracing Gems, ch. 7).
 * Returns 1 with both roots when the line meets the sphere. */
static inline int sphere_roots(vec3 center, real r2, vec3 o, vec3 d, real *l1,
                               real *l2) {
  vec3 v = v3_sub(center, o);
  real proj = v3_dot(v, d);
  vec3 perp = v3_madd(v, -proj, d);
  real dist2 = v3_dot(perp, perp);
  if (dist2 > r2)
    return 0;
  real half = r_sqrt(r2 - dist2);
  *l1 = proj - half;
  *l2 = proj + half;
  return 1;
}

/* Nearest hit in (tmin, tmax). *inside tells whether the origin is inside the
 * sphere (step 6 of algorithm 2.1): then the hit is the far root l2. */
static inline int sphere_hit(vec3 center, real r2, vec3 o, vec3 d, real tmin,
                             real tmax, real *t, int *inside) {
  real l1, l2;
  if (!sphere_roots(center, r2, o, d, &l1, &l2) || l2 <= tmin)
    return 0; /* missed, or the sphere lies behind the origin */
  if (l1 > tmin) {
    if (l1 >= tmax)
      return 0;
    *t = l1;
    *inside = 0;
    return 1;
  }
  if (l2 >= tmax)
    return 0;
  *t = l2;
  *inside = 1;
  return 1;
}

/* Plane n·X + d = 0 (eq. 2.5): t = -(n·O + d) / (n·dir). Parallel rays and
 * hits at t <= tmin miss. */
static inline int plane_hit(vec3 n, real d, vec3 o, vec3 dir, real tmin,
                            real tmax, real *t) {
  real denom = v3_dot(n, dir);
  if (denom == 0)
    return 0;
  real tt = -(v3_dot(n, o) + d) / denom;
  if (!(tt > tmin && tt < tmax))
    return 0;
  *t = tt;
  return 1;
}

/* Triangle A, A+e1, A+e2 by Möller–Trumbore: the barycentric test of eq.
 * 2.6–2.8 (u >= 0, v >= 0, u + v <= 1, edges and vertices included) solved
 * without first intersecting the plane. A degenerate triangle (e1 x e2 = 0)
 * gives det = 0 and never hits. */
static inline int triangle_hit(vec3 a, vec3 e1, vec3 e2, vec3 o, vec3 d,
                               real tmin, real tmax, real *t, real *u,
                               real *v) {
  vec3 p = v3_cross(d, e2);
  real det = v3_dot(e1, p);
  if (det == 0)
    return 0;
  real inv = (real)1 / det;
  vec3 s = v3_sub(o, a);
  real uu = v3_dot(s, p) * inv;
  if (!(uu >= 0 && uu <= 1))
    return 0;
  vec3 q = v3_cross(s, e1);
  real vv = v3_dot(d, q) * inv;
  if (!(vv >= 0 && uu + vv <= 1))
    return 0;
  real tt = v3_dot(e2, q) * inv;
  if (!(tt > tmin && tt < tmax))
    return 0;
  *t = tt;
  *u = uu;
  *v = vv;
  return 1;
}

/* An open cone or cylinder (no end caps, as NFF specifies): base B with
 * radius rb, unit axis a, height H, slope k = (ra - rb) / H. With w = O - B
 * and h(t) = w·a + t D·a the height of the point along the axis, a point is
 * on the surface where its squared distance from the axis equals the
 * radius there:  |w + tD|^2 - h^2 = (rb + k h)^2,  0 <= h <= H,
 * a quadratic A t^2 + B t + C = 0 with (D unit)
 *   A = 1 - (1 + k^2)(D·a)^2
 *   B = 2 (w·D - (w·a)(D·a) - k (D·a)(rb + k w·a))
 *   C = w·w - (w·a)^2 - (rb + k w·a)^2.
 * Returns both crossings within (tmin, tmax) and the height window, nearest
 * first, and how many there are (0, 1 or 2). */
static inline int cone_roots(vec3 base, vec3 axis, real height, real rb, real k,
                             vec3 o, vec3 d, real tmin, real tmax, real t[2]) {
  vec3 w = v3_sub(o, base);
  real wa = v3_dot(w, axis), da = v3_dot(d, axis);
  real rw = rb + k * wa;
  real qa = 1 - (1 + k * k) * da * da;
  real qb = 2 * (v3_dot(w, d) - wa * da - k * da * rw);
  real qc = v3_dot(w, w) - wa * wa - rw * rw;
  real r0, r1;
  if (r_fabs(qa) < (real)1e-12) { /* along a line of the surface */
    if (qb == 0)
      return 0;
    r0 = r1 = -qc / qb;
  } else {
    real disc = qb * qb - 4 * qa * qc;
    if (disc < 0)
      return 0;
    real sq = r_sqrt(disc);
    /* The stable form of the two roots (no cancellation). */
    real q = qb < 0 ? (real)-0.5 * (qb - sq) : (real)-0.5 * (qb + sq);
    r0 = q / qa;
    r1 = q != 0 ? qc / q : r0;
    if (r0 > r1) {
      real tmp = r0;
      r0 = r1;
      r1 = tmp;
    }
  }
  int n = 0;
  real roots[2] = {r0, r1};
  for (int i = 0; i < (r0 == r1 ? 1 : 2); i++) {
    real h = wa + roots[i] * da;
    if (roots[i] > tmin && roots[i] < tmax && h >= 0 && h <= height)
      t[n++] = roots[i];
  }
  return n;
}

/* The outward normal at p: the gradient of |q|^2 - h^2 - (rb + k h)^2 with
 * q = p - B, that is q - h a - k (rb + k h) a (unnormalised). */
static inline vec3 cone_normal(vec3 base, vec3 axis, real rb, real k, vec3 p) {
  vec3 q = v3_sub(p, base);
  real h = v3_dot(q, axis);
  return v3_madd(q, -(h + k * (rb + k * h)), axis);
}

#endif
