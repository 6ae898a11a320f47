/* BVH traversal for one ray, in the translation unit's precision (see
 * math/real.h): the slab test and the two walks the scalar tracer uses,
 * written once: closest hit (front to back) and segment (every leaf a
 * shadow ray's segment passes through, until one blocks it). The caller's
 * leaf function tests one primitive reference. Packets:
 * accel/packet_traverse.h. */
#ifndef GLINT_ACCEL_TRAVERSE_H
#define GLINT_ACCEL_TRAVERSE_H

#include "accel/bvh.h"
#include "math/vec3.h"

#include <math.h>
#include <stdint.h>

/* The ray's reciprocal direction for slab tests; a zero component becomes
 * a huge one of the same sign, so 0 * inf never makes a NaN. */
static inline vec3 safe_inverse(vec3 d) {
  const real tiny = (real)1e-30;
  real x = r_fabs(d.x) < tiny ? (d.x < 0 ? -tiny : tiny) : d.x;
  real y = r_fabs(d.y) < tiny ? (d.y < 0 ? -tiny : tiny) : d.y;
  real z = r_fabs(d.z) < tiny ? (d.z < 0 ? -tiny : tiny) : d.z;
  return v3(1 / x, 1 / y, 1 / z);
}

/* The slab test (Kay and Kajiya 1986): the entry distance into the node's
 * box, or infinity when the ray misses it within (tmin, tmax). (Not
 * REAL_MAX: a ray without a hit yet has tmax = REAL_MAX, and every missed
 * box would pass entry <= tmax.) The far distance is widened by a few ulps
 * so rounding cannot cull a hit on the box's surface. */
static inline real box_entry(const gli_bvh_node *n, vec3 o, vec3 inv, real tmin,
                             real tmax) {
  real t0x = ((real)n->lo[0] - o.x) * inv.x,
       t1x = ((real)n->hi[0] - o.x) * inv.x;
  real t0y = ((real)n->lo[1] - o.y) * inv.y,
       t1y = ((real)n->hi[1] - o.y) * inv.y;
  real t0z = ((real)n->lo[2] - o.z) * inv.z,
       t1z = ((real)n->hi[2] - o.z) * inv.z;
  real near = r_max(r_max(r_min(t0x, t1x), r_min(t0y, t1y)),
                    r_max(r_min(t0z, t1z), tmin));
  real far = r_min(r_min(r_max(t0x, t1x), r_max(t0y, t1y)),
                   r_min(r_max(t0z, t1z), tmax));
  return near <= far * (real)1.0000005 ? near : (real)INFINITY;
}

/* Tests primitive `ref`, narrowing *tmax on a nearer hit. */
typedef void (*bvh_closest_fn)(void *ctx, uint32_t ref, real *tmax);

/* The closest-hit walk: at an inner node both children's boxes are tested
 * and the nearer is visited first; the farther waits on the stack with its
 * entry distance, and is skipped if a hit has come closer since. */
static inline __attribute__((always_inline)) void
bvh_closest(const gli_bvh *bvh, vec3 o, vec3 d, real tmin, real *tmax,
            bvh_closest_fn leaf, void *ctx) {
  const gli_bvh_node *nodes = bvh->nodes;
  if (nodes[0].count) { /* a single leaf: its box test would only cost */
    for (uint32_t k = 0; k < nodes[0].count; k++)
      leaf(ctx, bvh->refs[k], tmax);
    return;
  }
  vec3 inv = safe_inverse(d);
  struct {
    uint32_t node;
    real entry;
  } stack[GLI_BVH_STACK];
  int sp = 0;
  uint32_t node = 0;
  if (box_entry(&nodes[0], o, inv, tmin, *tmax) > *tmax)
    return;
  for (;;) {
    const gli_bvh_node *n = &nodes[node];
    if (n->count == 0) {
      uint32_t a = n->offset, b = n->offset + 1;
      real ta = box_entry(&nodes[a], o, inv, tmin, *tmax);
      real tb = box_entry(&nodes[b], o, inv, tmin, *tmax);
      if (ta > tb) {
        real tt = ta;
        ta = tb, tb = tt;
        uint32_t nn = a;
        a = b, b = nn;
      }
      if (ta <= *tmax) {
        if (tb <= *tmax) {
          stack[sp].node = b;
          stack[sp++].entry = tb;
        }
        node = a;
        continue;
      }
    } else {
      for (uint32_t k = 0; k < n->count; k++)
        leaf(ctx, bvh->refs[n->offset + k], tmax);
    }
    do {
      if (sp == 0)
        return;
      --sp;
    } while (stack[sp].entry > *tmax);
    node = stack[sp].node;
  }
}

/* Tests primitive `ref` against a segment; returns 0 when it blocks it. */
typedef int (*bvh_segment_fn)(void *ctx, uint32_t ref);

/* The segment walk: every node the segment (tmin, tmax) passes through, in
 * any order; returns 0 as soon as the leaf function reports a block. */
static inline __attribute__((always_inline)) int
bvh_segment(const gli_bvh *bvh, vec3 o, vec3 d, real tmin, real tmax,
            bvh_segment_fn leaf, void *ctx) {
  const gli_bvh_node *nodes = bvh->nodes;
  vec3 inv = safe_inverse(d);
  uint32_t stack[GLI_BVH_STACK];
  int sp = 0;
  stack[sp++] = 0;
  while (sp > 0) {
    const gli_bvh_node *n = &nodes[stack[--sp]];
    /* (a root that is a single leaf needs no box test) */
    if (n != nodes && box_entry(n, o, inv, tmin, tmax) > tmax)
      continue;
    if (n->count == 0) {
      stack[sp++] = n->offset + 1;
      stack[sp++] = n->offset;
    } else {
      for (uint32_t k = 0; k < n->count; k++)
        if (!leaf(ctx, bvh->refs[n->offset + k]))
          return 0;
    }
  }
  return 1;
}

#endif
