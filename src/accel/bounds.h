/* Float boxes of double-precision primitives, rounded outward so that they
 * hold the primitives exactly: what the BVH builder (accel/bvh.c) and the
 * pre-splitter (accel/presplit.c) bound references with. */
#ifndef GLINT_ACCEL_BOUNDS_H
#define GLINT_ACCEL_BOUNDS_H

#include "scene/scene.h"

#include <float.h>
#include <math.h>

typedef struct gli_ref_box {
  float lo[3], hi[3];
} gli_ref_box;

static inline double gli_dmin(double a, double b) { return a < b ? a : b; }
static inline double gli_dmax(double a, double b) { return a > b ? a : b; }

/* Float bounds that contain [lo, hi] given in double: rounded to nearest,
 * then one step outward when that went inward (nextafterf is a call;
 * scaling by 1 -/+ 2^-23 is one float step for normal numbers, and bounds
 * around zero only need to be conservative). */
static inline float gli_round_down(double x) {
  float f = (float)x;
  if ((double)f <= x)
    return f;
  return f > 0 ? f * (1 - 0x1p-23f) : f < 0 ? f * (1 + 0x1p-23f) : -FLT_MIN;
}
static inline float gli_round_up(double x) {
  float f = (float)x;
  if ((double)f >= x)
    return f;
  return f > 0 ? f * (1 + 0x1p-23f) : f < 0 ? f * (1 - 0x1p-23f) : FLT_MIN;
}

static inline gli_ref_box gli_box_of(const double lo[3], const double hi[3]) {
  gli_ref_box b;
  for (int k = 0; k < 3; k++) {
    b.lo[k] = gli_round_down(lo[k]);
    b.hi[k] = gli_round_up(hi[k]);
  }
  return b;
}

static inline gli_ref_box gli_sphere_box(const gli_sphere_prim *s) {
  double c[3] = {s->center.x, s->center.y, s->center.z};
  double lo[3], hi[3];
  for (int k = 0; k < 3; k++)
    lo[k] = c[k] - s->radius, hi[k] = c[k] + s->radius;
  return gli_box_of(lo, hi);
}

static inline gli_ref_box gli_triangle_box(const gli_triangle_prim *t) {
  double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX},
         hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
  for (int i = 0; i < 3; i++) {
    double v[3] = {t->v[i].x, t->v[i].y, t->v[i].z};
    for (int k = 0; k < 3; k++)
      lo[k] = gli_dmin(lo[k], v[k]), hi[k] = gli_dmax(hi[k], v[k]);
  }
  return gli_box_of(lo, hi);
}

/* The part of a cone between fractions s0 <= s1 of the way from its base
 * to its apex: the convex hull of the disks there, so the two disks' boxes
 * (a disk of radius r with unit normal a reaches r sqrt(1 - a_k^2) along
 * axis k). The whole cone is s0 = 0, s1 = 1. */
static inline gli_ref_box gli_cone_part_box(const gli_cone_prim *c, double s0,
                                            double s1) {
  double b[3] = {c->base.x, c->base.y, c->base.z},
         t[3] = {c->apex.x, c->apex.y, c->apex.z};
  double a[3] = {c->apex.x - c->base.x, c->apex.y - c->base.y,
                 c->apex.z - c->base.z};
  double len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  double s[2] = {s0, s1};
  double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX},
         hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
  for (int e = 0; e < 2; e++) {
    double r = c->base_radius + s[e] * (c->apex_radius - c->base_radius);
    for (int k = 0; k < 3; k++) {
      /* the ends exactly where they are, not base + 1 (apex - base) */
      double p = s[e] == 0 ? b[k] : s[e] == 1 ? t[k] : b[k] + s[e] * a[k];
      double ak = a[k] / len;
      double ext = r * sqrt(gli_dmax(0.0, 1 - ak * ak));
      lo[k] = gli_dmin(lo[k], p - ext);
      hi[k] = gli_dmax(hi[k], p + ext);
    }
  }
  return gli_box_of(lo, hi);
}

#endif
