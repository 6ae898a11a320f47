/* Single rays through the wide BVH (accel/wide_bvh.h), in the translation
 * unit's precision: the slab test of one ray against a node's eight
 * children, and the two walks of accel/traverse.h over the wide tree:
 * closest hit (children visited nearest entry first; those behind the hit
 * found skipped) and segment (every leaf a shadow ray's segment passes
 * through, in any order, until one blocks it). A walk may start at any
 * wide node: a packet hands its lanes a subtree
 * (accel/packet_traverse.h). In the packet kernels' translation units the
 * eight children are tested in SIMD (simd/simd.h's vnode); elsewhere, as
 * the scalar backends' clear reference, one after another. */
#ifndef GLINT_ACCEL_WIDE_TRAVERSE_H
#define GLINT_ACCEL_WIDE_TRAVERSE_H

#include "accel/traverse.h"

#if defined(GLINT_ISA_SSE) || defined(GLINT_ISA_AVX2) ||                       \
    defined(GLINT_ISA_AVX512)
#include "simd/simd.h"
#define WIDE_SIMD 1
#endif

/* A stack deep enough for any walk: each level leaves at most
 * GLI_WIDE - 1 children waiting. */
#define GLI_WIDE_STACK (GLI_WIDE * GLI_WIDE_MAX_DEPTH)

typedef struct wide_ray {
  vec3 o, inv;
  int near[3]; /* per axis, the bounds[] index of the plane met first */
#ifdef WIDE_SIMD
  real near_off[3], far_off[3]; /* node_distance's terms, per axis */
#endif
} wide_ray;

#ifdef WIDE_SIMD
/* A plane's distance (B - O)/D to the ray, `off` being the plane's term
 * of wide_ray: plane_distance's form (accel/packet_traverse.h), one fma
 * where the ISA fuses. */
static inline vnode node_distance(vnode b, vnode inv, vnode off) {
#if GLI_SIMD_FUSED
  return vn_fmadd(b, inv, off);
#else
  return vn_mul(vn_add(b, off), inv);
#endif
}

/* The terms of node_distance for the planes of one axis, as
 * packet_origin's (accel/packet_traverse.h, where the argument is): with
 * fmas, -O/D for the origin moved 8 ulps towards the side that moves the
 * near planes nearer and the far planes farther; without, -O. */
static inline void wide_ray_axis(real o, real inv, real *near_off,
                                 real *far_off) {
#if GLI_SIMD_FUSED
  real shift = r_fabs(o) * (real)0x1p-21;
  real toward = inv < 0 ? -shift : shift;
  *near_off = -(o + toward) * inv, *far_off = -(o - toward) * inv;
#else
  (void)inv;
  *near_off = *far_off = -o;
#endif
}
#endif

static inline wide_ray wide_ray_make(vec3 o, vec3 d) {
  wide_ray r;
  r.o = o;
  r.inv = safe_inverse(d);
  r.near[0] = r.inv.x < 0;
  r.near[1] = r.inv.y < 0;
  r.near[2] = r.inv.z < 0;
#ifdef WIDE_SIMD
  wide_ray_axis(o.x, r.inv.x, &r.near_off[0], &r.far_off[0]);
  wide_ray_axis(o.y, r.inv.y, &r.near_off[1], &r.far_off[1]);
  wide_ray_axis(o.z, r.inv.z, &r.near_off[2], &r.far_off[2]);
#endif
  return r;
}

/* The slab test (Kay and Kajiya 1986) of the ray against all children of
 * n within (tmin, tmax): bit k is set when child k is hit, entry[k] being
 * its entry distance. With the direction's signs known, each axis's nearer
 * and farther planes are picked rather than sorted (Williams et al. 2005,
 * "An efficient and robust ray-box intersection algorithm"); the far
 * distance is widened as box_entry's is. In SIMD the distances are
 * node_distance's, conservative as packet_box's are. */
static inline __attribute__((always_inline)) unsigned
wide_hits(const gli_wide_node *n, const wide_ray *r, real tmin, real tmax,
          real entry[GLI_WIDE]) {
  const int nx = r->near[0], ny = r->near[1], nz = r->near[2];
#ifdef WIDE_SIMD
  /* real is float here: the packet kernels' precision */
  vnode ix = vn_set1(r->inv.x), iy = vn_set1(r->inv.y), iz = vn_set1(r->inv.z);
  vnode nox = vn_set1(r->near_off[0]), noy = vn_set1(r->near_off[1]),
        noz = vn_set1(r->near_off[2]);
  /* without fmas the near and far terms are the same, -O */
  vnode fox = GLI_SIMD_FUSED ? vn_set1(r->far_off[0]) : nox;
  vnode foy = GLI_SIMD_FUSED ? vn_set1(r->far_off[1]) : noy;
  vnode foz = GLI_SIMD_FUSED ? vn_set1(r->far_off[2]) : noz;
  vnode lo = vn_set1(tmin), hi = vn_set1(tmax), widen = vn_set1(1.0000005f);
  unsigned bits = 0;
  for (int h = 0; h < GLI_WIDE; h += GLI_NODE_LANES) {
    vnode tnx = node_distance(vn_load(&n->bounds[nx][0][h]), ix, nox);
    vnode tny = node_distance(vn_load(&n->bounds[ny][1][h]), iy, noy);
    vnode tnz = node_distance(vn_load(&n->bounds[nz][2][h]), iz, noz);
    vnode tfx = node_distance(vn_load(&n->bounds[1 - nx][0][h]), ix, fox);
    vnode tfy = node_distance(vn_load(&n->bounds[1 - ny][1][h]), iy, foy);
    vnode tfz = node_distance(vn_load(&n->bounds[1 - nz][2][h]), iz, foz);
    vnode near = vn_max(vn_max(tnx, tny), vn_max(tnz, lo));
    vnode far = vn_min(vn_min(tfx, tfy), vn_min(tfz, hi));
    bits |= (unsigned)vn_le_bits(near, vn_mul(far, widen)) << h;
    vn_store(&entry[h], near);
  }
  return bits;
#else
  unsigned bits = 0;
  for (int k = 0; k < GLI_WIDE; k++) {
    real tnx = ((real)n->bounds[nx][0][k] - r->o.x) * r->inv.x;
    real tny = ((real)n->bounds[ny][1][k] - r->o.y) * r->inv.y;
    real tnz = ((real)n->bounds[nz][2][k] - r->o.z) * r->inv.z;
    real tfx = ((real)n->bounds[1 - nx][0][k] - r->o.x) * r->inv.x;
    real tfy = ((real)n->bounds[1 - ny][1][k] - r->o.y) * r->inv.y;
    real tfz = ((real)n->bounds[1 - nz][2][k] - r->o.z) * r->inv.z;
    real near = r_max(r_max(tnx, tny), r_max(tnz, tmin));
    real far = r_min(r_min(tfx, tfy), r_min(tfz, tmax));
    entry[k] = near;
    bits |= (unsigned)(near <= far * (real)1.0000005) << k;
  }
  return bits;
#endif
}

/* Tests the leaf's references bvh->wide.refs[first .. first + count - 1],
 * narrowing *tmax on a nearer hit. */
typedef void (*wide_closest_fn)(void *ctx, uint32_t first, uint32_t count,
                                real *tmax);
/* Tests them against a segment; returns 0 when one blocks it. */
typedef int (*wide_segment_fn)(void *ctx, uint32_t first, uint32_t count);

/* A child waiting on a walk's stack: a wide node (count 0) or a leaf's
 * references. */
typedef struct wide_item {
  uint32_t child, count;
  real entry;
} wide_item;

/* The closest-hit walk of the subtree at wide node `start` (0: the whole
 * tree). *tests counts the nodes and leaves tested. */
static inline __attribute__((always_inline)) void
wide_closest(const gli_bvh *bvh, uint32_t start, vec3 o, vec3 d, real tmin,
             real *tmax, wide_closest_fn leaf, void *ctx, uint64_t *tests) {
  const gli_wide_node *nodes = bvh->wide.nodes;
  wide_ray r = wide_ray_make(o, d);
  wide_item stack[GLI_WIDE_STACK];
  int sp = 0;
  wide_item cur = {start, 0, tmin};
  /* counted in a local: the leaf function may write *tests' statistics */
  uint64_t tested = 0;
  for (;;) {
    if (cur.count == 0) {
      const gli_wide_node *n = &nodes[cur.child];
      real entry[GLI_WIDE];
      unsigned hits = wide_hits(n, &r, tmin, *tmax, entry);
      ++tested;
      if (hits) {
        int k = __builtin_ctz(hits);
        hits &= hits - 1;
        wide_item near = {n->child[k], n->count[k], entry[k]};
        if (!hits) { /* one child: on to it */
          cur = near;
          continue;
        }
        k = __builtin_ctz(hits);
        hits &= hits - 1;
        wide_item far = {n->child[k], n->count[k], entry[k]};
        if (far.entry < near.entry) {
          wide_item t = near;
          near = far, far = t;
        }
        if (!hits) { /* two: the nearer now, the other later */
          stack[sp++] = far;
          cur = near;
          continue;
        }
        /* More: every child hit onto the stack, sorted so that the nearest
         * is on top (insertion sort: at most eight), and taken off at
         * once. */
        int base = sp;
        stack[sp++] = far;
        stack[sp++] = near;
        do {
          int k = __builtin_ctz(hits);
          hits &= hits - 1;
          wide_item it = {n->child[k], n->count[k], entry[k]};
          int j = sp++;
          while (j > base && stack[j - 1].entry < it.entry) {
            stack[j] = stack[j - 1];
            j--;
          }
          stack[j] = it;
        } while (hits);
        cur = stack[--sp];
        continue;
      }
    } else {
      ++tested;
      leaf(ctx, cur.child, cur.count, tmax);
    }
    do {
      if (sp == 0) {
        *tests += tested;
        return;
      }
      --sp;
    } while (stack[sp].entry > *tmax);
    cur = stack[sp];
  }
}

/* The segment walk of the subtree at wide node `start`: returns 0 as soon
 * as the leaf function reports a block. */
static inline __attribute__((always_inline)) int
wide_segment(const gli_bvh *bvh, uint32_t start, vec3 o, vec3 d, real tmin,
             real tmax, wide_segment_fn leaf, void *ctx, uint64_t *tests) {
  wide_ray r = wide_ray_make(o, d);
  /* Any order will do: no entry distances are kept or compared. */
  wide_item cur = {start, 0, tmin}, stack[GLI_WIDE_STACK];
  uint64_t tested = 0;
  for (int sp = 0;;) {
    if (cur.count) {
      ++tested;
      if (!leaf(ctx, cur.child, cur.count)) {
        *tests += tested;
        return 0;
      }
    } else {
      const gli_wide_node *n = &bvh->wide.nodes[cur.child];
      real entry[GLI_WIDE];
      unsigned hits = wide_hits(n, &r, tmin, tmax, entry);
      ++tested;
      if (hits) { /* on to the first child hit; the others wait */
        int k = __builtin_ctz(hits);
        cur = (wide_item){n->child[k], n->count[k], entry[k]};
        for (hits &= hits - 1; hits; hits &= hits - 1) {
          k = __builtin_ctz(hits);
          stack[sp++] = (wide_item){n->child[k], n->count[k], entry[k]};
        }
        continue;
      }
    }
    if (sp == 0) {
      *tests += tested;
      return 1;
    }
    cur = stack[--sp];
  }
}

#endif
