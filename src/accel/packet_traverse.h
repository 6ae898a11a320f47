/* BVH traversal for W rays at a time: the slab test of a packet against a
 * node's box and the two walks every packet backend uses, written once:
 * closest hit (front to back, boxes behind the lanes' hits skipped) and
 * segment (every leaf a shadow packet's segments pass through, until every
 * lane is blocked). The caller's leaf function tests a leaf's primitives.
 *
 * Both walks are hybrid (Benthin, Wald, Woop, Ernst and Mark 2012,
 * "Combining single and packet-ray tracing for arbitrary ray distributions
 * on the Intel MIC architecture"): a packet walks the binary tree (its
 * packets' cut, gli_bvh.packet_nodes) while
 * enough of its lanes stay together; where at most `alone` lanes enter a
 * node that has a wide counterpart (accel/wide_bvh.h), the caller's subtree
 * function walks that subtree with each of them alone, through the wide
 * tree (accel/wide_traverse.h), and the packet goes on without them. */
#ifndef GLINT_ACCEL_PACKET_TRAVERSE_H
#define GLINT_ACCEL_PACKET_TRAVERSE_H

#include "accel/bvh.h"
#include "simd/vvec3.h"

#include <float.h>
#include <math.h>

/* The lanes at or below which a packet hands a subtree to its lanes, one
 * at a time: chosen by measurement on balls-s4, rings-s4 and teapot-s4, one
 * thread, thresholds 0-4 (README, "Performance"): SSE 2 of 4, AVX2 3 of 8,
 * AVX-512 3 of 16. */
#ifndef GLI_HYBRID_LANES
#if LANES == 4
#define GLI_HYBRID_LANES 2
#else
#define GLI_HYBRID_LANES 3
#endif
#endif

#include "glint.h"

/* Packet statistics: `tests` tests of `lanes` active lanes each (often
 * none: the planes and brute-force tests of a scene with a BVH and no
 * planes). */
static ALWAYS_INLINE void count_tests(glint_stats *st, size_t tests,
                                      int lanes) {
  if (tests == 0)
    return;
  st->packet_tests += tests;
  st->active_lanes += (uint64_t)tests * (uint64_t)lanes;
}

/* The same, kept in locals by the walks and added to the statistics once a
 * walk ends: the leaf functions may write the statistics, so a count there
 * was a load and a store at every node (3% of the instructions on
 * mount-s6). */
typedef struct test_count {
  uint64_t tests, lanes;
} test_count;

static ALWAYS_INLINE void add_tests(test_count *c, size_t tests, int lanes) {
  c->tests += tests;
  c->lanes += (uint64_t)tests * (uint64_t)lanes;
}

static ALWAYS_INLINE void flush_tests(glint_stats *st, test_count boxes,
                                      test_count prims) {
  st->packet_tests += boxes.tests + prims.tests;
  st->active_lanes += boxes.lanes + prims.lanes;
}

/* The lanes' origins as the slab tests read them (plane_distance, for
 * the lower and the upper planes). With fmas, B/D - O/D is off by up to an
 * ulp of O/D, which the widening of packet_box does not cover: -O moved 8
 * ulps (of O) towards each side's planes, -(O + 8u|O|) for the lower and
 * -(O - 8u|O|) for the upper (u = 2^-24), moves each plane farther out than
 * that (see packet_box). Without fmas, (B - O)/D is a few ulps of itself
 * off, which the widening covers: -O for both. A shading point's shadow
 * packets, one per light, share it. */
typedef struct packet_origin {
  vvec3 lo, hi;
} packet_origin;

static ALWAYS_INLINE packet_origin packet_origin_of(vvec3 o) {
  /* -O as 0 - O and |O| as max(O, -O), without the sign-mask constants
   * that vv_neg and vf_abs load: SSE's packet walks 0.5-1% fewer render
   * instructions on the SPD scenes, the others unchanged */
  vvec3 neg_o = vv_sub((vvec3){vf_zero(), vf_zero(), vf_zero()}, o);
#if GLI_SIMD_FUSED
  vfloat spread = vf_set1(0x1p-21f);
  vvec3 mag = {vf_max(o.x, neg_o.x), vf_max(o.y, neg_o.y),
               vf_max(o.z, neg_o.z)};
  packet_origin r = {vv_madd(neg_o, vf_neg(spread), mag),
                     vv_madd(neg_o, spread, mag)};
#else
  packet_origin r = {neg_o, neg_o};
#endif
  return r;
}

/* What the slab tests of a packet need: 1/D (a zero component made tiny,
 * so 0 * inf never makes a NaN) and, per axis, the lower and the upper
 * planes' terms of plane_distance. */
typedef struct packet_inv {
  vvec3 inv, lo_off, hi_off;
  int neg[3]; /* the packet's direction sign per axis (first active lane) */
} packet_inv;

/* A plane's distance (B - O)/D along the lanes, `off` being the plane
 * side's term: -O/D with one fma where the ISA fuses, a multiply-add; -O
 * without (SSE), where B/D - O/D would be two roundings and as many
 * instructions as (B - O) * (1/D). */
static ALWAYS_INLINE vfloat plane_distance(vfloat b, vfloat inv, vfloat off) {
#if GLI_SIMD_FUSED
  return vf_fmadd(b, inv, off);
#else
  return vf_mul(vf_add(b, off), inv);
#endif
}

/* |m| (m >= 0) with the sign of s. */
static ALWAYS_INLINE vfloat vf_signed_as(vfloat m, vfloat s) {
  return vi_as_vf(
      vi_or(vf_bits(m), vi_and(vf_bits(s), vi_set1((int)0x80000000u))));
}

static ALWAYS_INLINE vfloat vf_nonzero(vfloat a) {
  vfloat tiny = vf_set1(1e-30f);
  return vf_select(vf_lt(vf_abs(a), tiny), vf_signed_as(tiny, a), a);
}

static ALWAYS_INLINE packet_inv packet_inverse(const packet_origin *po, vvec3 d,
                                               vmask active, int newton) {
  packet_inv r;
  r.inv.x = vf_rcp(vf_nonzero(d.x), newton);
  r.inv.y = vf_rcp(vf_nonzero(d.y), newton);
  r.inv.z = vf_rcp(vf_nonzero(d.z), newton);
#if GLI_SIMD_FUSED
  r.lo_off = vv_mul(po->lo, r.inv);
  r.hi_off = vv_mul(po->hi, r.inv);
#else
  r.lo_off = r.hi_off = po->lo; /* -O for both sides */
#endif
  SIMD_ALIGN float dx[LANES], dy[LANES], dz[LANES];
  vf_store(dx, d.x);
  vf_store(dy, d.y);
  vf_store(dz, d.z);
  int lane = vm_any(active) ? vm_first(active) : 0;
  r.neg[0] = dx[lane] < 0;
  r.neg[1] = dy[lane] < 0;
  r.neg[2] = dz[lane] < 0;
  return r;
}

#define BOX_WIDENING 1.0000005f /* the far distance's few ulps */

/* The slab test for all lanes of `active` against a node's box within
 * (tmin, tmax), conservative: a ray that touches the box is never culled.
 * Each distance is plane_distance's: B/D - O/D in one fma where the ISA
 * has fmas, six instructions a box where (B - O)/D takes twelve. The
 * fma's error, dominated by the rounding of O/D, is an ulp of O/D: far
 * more than an ulp of the distance when the origin lies farther from the
 * coordinates' zero than from the box, and such errors culled hits on box
 * faces (rays through a mesh's vertices missed it). Moving O 8 ulps
 * outwards (packet_origin) moves each plane at least 7u|O/D| farther out,
 * more than that error. The far distance is widened by a few ulps of
 * itself, for the rounding of the distance and of the reciprocal. (Ize
 * 2013, "Robust BVH ray traversal", bounds the slab test's errors so.)
 * *near_out receives the lanes' entry distances. */
static ALWAYS_INLINE vmask packet_box_near(const gli_bvh_node *n,
                                           const packet_inv *r, vfloat tmin,
                                           vfloat tmax, vmask active,
                                           vfloat *near_out) {
  vfloat lx, ly, lz, hx, hy, hz, unused0, unused1;
  vf_splat4(&n->lo[0], &lx, &ly, &lz, &hx);
  vf_splat4(&n->hi[1], &hy, &hz, &unused0, &unused1);
  /* Without fmas both sides' term is -O: one set of registers, not two. */
  const vvec3 *hi_off = GLI_SIMD_FUSED ? &r->hi_off : &r->lo_off;
  vfloat t0x = plane_distance(lx, r->inv.x, r->lo_off.x);
  vfloat t1x = plane_distance(hx, r->inv.x, hi_off->x);
  vfloat t0y = plane_distance(ly, r->inv.y, r->lo_off.y);
  vfloat t1y = plane_distance(hy, r->inv.y, hi_off->y);
  vfloat t0z = plane_distance(lz, r->inv.z, r->lo_off.z);
  vfloat t1z = plane_distance(hz, r->inv.z, hi_off->z);
  vfloat near = vf_max(vf_max(vf_min(t0x, t1x), vf_min(t0y, t1y)),
                       vf_max(vf_min(t0z, t1z), tmin));
  vfloat far = vf_min(vf_min(vf_max(t0x, t1x), vf_max(t0y, t1y)),
                      vf_min(vf_max(t0z, t1z), tmax));
  *near_out = near;
  return vm_and(active, vf_le(near, vf_mul(far, vf_set1(BOX_WIDENING))));
}

/* The test alone, where the entry distances are not wanted. */
static ALWAYS_INLINE vmask packet_box(const gli_bvh_node *n,
                                      const packet_inv *r, vfloat tmin,
                                      vfloat tmax, vmask active) {
  vfloat near;
  return packet_box_near(n, r, tmin, tmax, active, &near);
}

/* Tests a leaf's primitive `ref` for the lanes of m (closest hit: narrowing
 * the lanes' nearest distances that the walk reads through tmax). */
typedef void (*packet_leaf_fn)(void *ctx, uint32_t ref, vmask m);

/* Starts the loads of what the leaf functions will read of a leaf's `count`
 * primitives `refs`. The closest-hit walk calls it for each leaf child of
 * a node before the children's box tests, so that the primitives' misses
 * overlap the tests: on the 200k-triangle dragon's primary rays the first
 * read of a triangle was the walk's costliest instruction, and prefetched
 * before the leaf's box test the rays ran 10% faster (AVX-512 beams and
 * streams, one thread, when each box was tested as it was popped). The segment
 * walk has none: there its mere presence made the streams' shadow packets
 * 5-8% slower on the SPD scenes, whose primitives the caches hold. */
typedef void (*packet_prefetch_fn)(void *ctx, const uint32_t *refs,
                                   uint32_t count);

/* Walks the subtree at wide node `wide` with each lane of m alone. */
typedef void (*packet_alone_fn)(void *ctx, uint32_t wide, vmask m);

/* The wide node that can take over at packet inner node `node` from the
 * lanes of m, or GLI_WIDE_NONE. The node's flag is tested first: the lane
 * count is a branch no predictor guesses, which cost gears-s4 (no
 * hand-over points) 5% when it came first. alone = 0: never (a constant
 * 0 leaves nothing of the hand-over in the walk). */
static ALWAYS_INLINE uint32_t hand_over(const gli_bvh *bvh,
                                        const gli_bvh_node *n, uint32_t node,
                                        vmask m, int alone) {
  if (!alone || !(n->flags & GLI_NODE_HAND_OVER) || vm_count(m) > alone)
    return GLI_WIDE_NONE;
  return bvh->packet_wide[node];
}

/* The closest-hit walk, depth first. An inner node's two children are
 * tested together (two independent chains of arithmetic, where testing
 * each as it was popped made one long chain per node), and the packet goes
 * on into the child its direction meets first, while the other waits on
 * the stack with its lanes' entry distances. Popped, it is culled by one
 * comparison against the lanes' nearest hits so far (*tmax, which the leaf
 * function narrows), so boxes behind a hit are skipped without their
 * node being read again; a lane it passes is one the box test at that
 * moment would pass, so the walk finds what testing on popping found, and
 * counts the same tests. */
static ALWAYS_INLINE void
packet_bvh_closest(const gli_bvh *bvh, const packet_origin *po, vvec3 d,
                   vmask active, vfloat tmin, const vfloat *tmax, int newton,
                   glint_stats *st, packet_prefetch_fn prefetch,
                   packet_leaf_fn leaf, int alone, packet_alone_fn walk_alone,
                   void *ctx) {
  int lanes = vm_count(active);
  packet_inv r = packet_inverse(po, d, active, newton);
  const gli_bvh_node *nodes = bvh->packet_nodes;
  uint32_t stack[GLI_BVH_STACK];
  /* +inf in the lanes that miss the box: popped, it is compared with the
   * nearest hits widened and held to FLT_MAX (a lane without a hit has
   * FLT_MAX, widened to +inf), which no lane's entry passes but one it
   * entered; no NaN, whose comparison SSE's cmpleps signals. */
  vfloat entry[GLI_BVH_STACK];
  int sp = 0;
  uint64_t box_tests = 1; /* each of `lanes` lanes */
  test_count prims = {0, 0};
  uint32_t node = 0;
  const gli_bvh_node *n = nodes;
  if (n->count)
    prefetch(ctx, bvh->refs + n->offset, n->count);
  vmask m = packet_box(n, &r, tmin, *tmax, active);
  int more = vm_any(m);
  while (more) {
    if (n->count == 0) {
      uint32_t wide = hand_over(bvh, n, node, m, alone);
      if (__builtin_expect(wide == GLI_WIDE_NONE, 1)) {
        const gli_bvh_node *c = &nodes[n->offset];
        if (c[0].count)
          prefetch(ctx, bvh->refs + c[0].offset, c[0].count);
        if (c[1].count)
          prefetch(ctx, bvh->refs + c[1].offset, c[1].count);
        vfloat near0, near1;
        vmask m0 = packet_box_near(&c[0], &r, tmin, *tmax, active, &near0);
        vmask m1 = packet_box_near(&c[1], &r, tmin, *tmax, active, &near1);
        box_tests += 2;
        int hit0 = vm_any(m0), hit1 = vm_any(m1);
        if (hit0 | hit1) {
          /* the child the direction meets first: the upper one (1) where
           * the packet runs towards the axis's lower end */
          int first = hit0 & hit1 ? r.neg[n->axis] : hit1;
          if (hit0 & hit1) {
            stack[sp] = n->offset + (uint32_t)!first;
            entry[sp++] = first ? vf_select(m0, near0, vf_set1(INFINITY))
                                : vf_select(m1, near1, vf_set1(INFINITY));
          }
          node = n->offset + (uint32_t)first;
          m = first ? m1 : m0;
          n = &c[first];
          continue;
        }
      } else {
        walk_alone(ctx, wide, m);
      }
    } else {
      add_tests(&prims, n->count, vm_count(m));
      for (uint32_t k = 0; k < n->count; k++)
        leaf(ctx, bvh->refs[n->offset + k], m);
    }
    /* the nearest waiting box that a lane may still find a nearer hit in */
    more = 0;
    while (sp > 0 && !more) {
      sp--;
      m = vf_le(entry[sp],
                vf_min(vf_mul(*tmax, vf_set1(BOX_WIDENING)), vf_set1(FLT_MAX)));
      more = vm_any(m);
    }
    if (more) {
      node = stack[sp];
      n = &nodes[node];
    }
  }
  test_count boxes = {box_tests, box_tests * (uint64_t)lanes};
  flush_tests(st, boxes, prims);
}

/* The segment walk of shadow rays: every leaf the lanes' segments (tmin,
 * tmax) pass through, in any order, until no lane is *alive. An inner
 * node's children are tested together (see packet_bvh_closest), the second
 * waiting on the stack with the lanes that entered it; both tests count the
 * lanes alive at the node (testing on popping counted the second's at its
 * pop, and none where every lane was blocked first). While a leaf's
 * primitives are tested, *alive holds only the lanes inside its box; the
 * leaf function clears the lanes it blocks. */
static ALWAYS_INLINE void
packet_bvh_segment(const gli_bvh *bvh, const packet_origin *po, vvec3 d,
                   vfloat tmin, vfloat tmax, vmask *alive, int newton,
                   glint_stats *st, packet_leaf_fn leaf, int alone,
                   packet_alone_fn walk_alone, void *ctx) {
  if (vm_none(*alive))
    return;
  packet_inv r = packet_inverse(po, d, *alive, newton);
  const gli_bvh_node *nodes = bvh->packet_nodes;
  uint32_t stack[GLI_BVH_STACK];
  vmask entered[GLI_BVH_STACK];
  int sp = 0;
  test_count boxes = {1, (uint64_t)vm_count(*alive)}, prims = {0, 0};
  uint32_t node = 0;
  const gli_bvh_node *n = nodes;
  vmask m = packet_box(n, &r, tmin, tmax, *alive);
  int more = vm_any(m);
  while (more) {
    if (n->count == 0) {
      uint32_t wide = hand_over(bvh, n, node, m, alone);
      if (__builtin_expect(wide == GLI_WIDE_NONE, 1)) {
        const gli_bvh_node *c = &nodes[n->offset];
        vmask m0 = packet_box(&c[0], &r, tmin, tmax, *alive);
        vmask m1 = packet_box(&c[1], &r, tmin, tmax, *alive);
        add_tests(&boxes, 2, vm_count(*alive));
        int hit0 = vm_any(m0), hit1 = vm_any(m1);
        if (hit0 | hit1) {
          if (hit0 & hit1) {
            stack[sp] = n->offset + 1;
            entered[sp++] = m1;
          }
          node = n->offset + (uint32_t)!hit0;
          m = hit0 ? m0 : m1;
          n = &c[!hit0];
          continue;
        }
      } else {
        walk_alone(ctx, wide, m); /* clears the lanes it finds blocked */
      }
    } else {
      vmask outside = vm_andnot(*alive, m); /* lanes not in this box */
      *alive = m;
      add_tests(&prims, n->count, vm_count(m));
      for (uint32_t k = 0; k < n->count && vm_any(*alive); k++)
        leaf(ctx, bvh->refs[n->offset + k], *alive);
      *alive = vm_or(*alive, outside);
    }
    /* the next waiting box that a lane still alive entered */
    more = 0;
    while (sp > 0 && !more && vm_any(*alive)) {
      sp--;
      m = vm_and(entered[sp], *alive);
      more = vm_any(m);
    }
    if (more) {
      node = stack[sp];
      n = &nodes[node];
    }
  }
  flush_tests(st, boxes, prims);
}

#endif
