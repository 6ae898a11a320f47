/* Ray-primitive intersection for one ray (docs/specification.md §3, thesis
 * §2.4), in the translation unit's precision. A hit counts only for tmin < t <
 * tmax. */
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

/* Triangle A, B, C, watertight (eq. 2.6-2.8's barycentric test, edges and
 * vertices included): each edge PQ gets the Plücker side of the ray,
 *   E = D·M + e·L,  with e = Q - P, M = (P - R) x (Q - R), L = (O - R) x D,
 * R the scene's triangle origin (close to the triangles, for precision). An
 * edge that two triangles share is the same P, Q in both, the other way
 * round, so its e and M are exact negations, and so is E (rounding is
 * symmetric): a ray can pass on one side of it or the other, never between
 * the two triangles. The ray hits where the three sides agree in sign (zero
 * counts as either); E over their sum is the barycentric weight of the
 * vertex opposite the edge. Then t from the plane through A with normal
 * N = (B - A) x (C - A), or any multiple of it (render/scalar_scene.c
 * stores it scaled to about unit length, so that N·(A - O) cannot
 * overflow). A degenerate triangle (N = 0) never hits. */
static inline int triangle_hit(vec3 a, const vec3 edge[3], const vec3 moment[3],
                               vec3 n, vec3 o, vec3 d, vec3 l, real tmin,
                               real tmax, real *t, real *u, real *v) {
  real side_ab = v3_dot(d, moment[0]) + v3_dot(edge[0], l);
  real side_bc = v3_dot(d, moment[1]) + v3_dot(edge[1], l);
  if ((side_ab < 0 && side_bc > 0) || (side_ab > 0 && side_bc < 0))
    return 0; /* most misses are known after two edges */
  real side_ca = v3_dot(d, moment[2]) + v3_dot(edge[2], l);
  if ((side_ab < 0 || side_bc < 0 || side_ca < 0) &&
      (side_ab > 0 || side_bc > 0 || side_ca > 0))
    return 0;
  real det = side_ab + side_bc + side_ca;
  real nd = v3_dot(n, d);
  if (det == 0 || nd == 0)
    return 0;
  real tt = v3_dot(n, v3_sub(a, o)) / nd;
  if (!(tt > tmin && tt < tmax))
    return 0;
  *t = tt;
  *u = side_ca / det; /* the weight of B, opposite edge CA */
  *v = side_ab / det; /* of C */
  return 1;
}

/* The ray's L = (O - R) x D for triangle_hit. */
static inline vec3 triangle_ray_moment(vec3 origin, vec3 o, vec3 d) {
  return v3_cross(v3_sub(o, origin), d);
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
  /* Solved from the ray's point nearest the base, o + s d with s = -w.d,
   * not from o: seen from afar, |w|^2 and (w.a)^2 are large and nearly
   * equal, and their difference (the squared distance to the axis, the
   * size of a thin cylinder) would lose every digit. Every ray that meets
   * the cone passes within the cone's own size of its base, so from that
   * point w is as small as the cone and so are the terms that cancel. The
   * roots are then t = s + r. No division: s needs only d to be unit.
   * (There w.d is 0 but for d's rounding, which a float d's many ulps
   * from unit make count on thin cylinders: it stays in b.) */
  vec3 w = v3_sub(o, base);
  real s = -v3_dot(w, d);
  w = v3_madd(w, s, d);
  real wa = v3_dot(w, axis), da = v3_dot(d, axis);
  real rw = rb + k * wa;
  /* a r^2 + 2 hb r + c = 0 */
  real qa = 1 - (1 + k * k) * da * da;
  real hb = v3_dot(w, d) - wa * da - k * da * rw;
  real qc = v3_dot(w, w) - wa * wa - rw * rw;
  real r0, r1;
  if (r_fabs(qa) < (real)1e-12) { /* along a line of the surface */
    if (hb == 0)
      return 0;
    r0 = r1 = -qc / (2 * hb);
  } else {
    real disc = hb * hb - qa * qc;
    if (disc < 0)
      return 0;
    real sq = r_sqrt(disc);
    /* The stable form of the two roots (no cancellation): q = -(hb +
     * sign(hb) sq), roots q/a and c/q. */
    real q = hb < 0 ? -(hb - sq) : -(hb + sq);
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
    real ti = s + roots[i];
    if (ti > tmin && ti < tmax && h >= 0 && h <= height)
      t[n++] = ti;
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
