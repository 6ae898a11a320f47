/* The wide BVH: the binary BVH (accel/bvh.h) collapsed so that each node
 * holds up to eight children, their boxes stored plane by plane so that one
 * ray tests all eight in one SIMD instruction per plane (Wald, Benthin and
 * Boulos 2008, "Getting rid of packets"; Embree's BVH8). Single rays walk it
 * (accel/wide_traverse.h): the scalar backends, and the lanes of a packet
 * that too few lanes keep together (accel/packet_traverse.h). It keeps a
 * copy of the binary BVH's references (reordered within leaves), and each
 * wide node is the collapse of one binary node, so a packet walking the
 * binary tree can hand a subtree over to its lanes one at a time. */
#ifndef GLINT_ACCEL_WIDE_BVH_H
#define GLINT_ACCEL_WIDE_BVH_H

#include "glint.h"

#include <stdint.h>

#define GLI_WIDE 8
/* References a single ray tests at a leaf: bigger binary leaves are split
 * (wide_bvh.c). */
#define GLI_WIDE_LEAF 4
/* Levels of the wide tree: the binary tree's, plus the splits of leaves. */
#define GLI_WIDE_MAX_DEPTH 80

/* 256 bytes, four cache lines, 64-byte aligned. A ray's slab test reads
 * bounds[0] (lo) or bounds[1] (hi) as its nearer plane per axis, by its
 * direction's sign; an unused slot has an empty box (lo = +inf, hi =
 * -inf), which that test always rejects. */
typedef struct gli_wide_node {
  float bounds[2][3][GLI_WIDE]; /* [lo, hi][axis][child] */
  uint32_t child[GLI_WIDE]; /* inner: wide node index; leaf: first reference */
  uint16_t count[GLI_WIDE]; /* references of a leaf child; 0: inner or unused */
  uint8_t pad[16];
} __attribute__((aligned(64))) gli_wide_node;

#define GLI_WIDE_NONE UINT32_MAX

typedef struct gli_wide_bvh {
  gli_wide_node *nodes; /* NULL: none (no hierarchy, or --accel bvh2) */
  uint32_t node_count;
  /* The wide node collapsed from each binary node, or GLI_WIDE_NONE for
   * binary nodes that were opened into their parent's wide node. */
  uint32_t *of_binary;
  uint32_t binary_count;
  /* The binary tree's primitive references, reordered within its leaves
   * (a leaf child's are refs[child], ..., refs[child + count - 1]). */
  uint32_t *refs;
  uint32_t ref_count;
  int depth;
  /* Binary nodes marked GLI_NODE_HAND_OVER (0: packets never hand over,
   * and take the walk without it). */
  uint32_t hand_overs;
  double build_seconds;
} gli_wide_bvh;

struct gli_bvh;

/* Packets hand subtrees to their last lanes only where at least this many
 * references lie, at least half of them spheres or cones (wide_bvh.c,
 * mark_hand_overs, says why). */
#define GLI_HAND_OVER_REFS 128

/* Whether a tree over these primitives may have hand-over points: where
 * it cannot (fewer than GLI_HAND_OVER_REFS / 2 spheres and cones), only
 * --accel bvh8 walks the wide tree, and it is collapsed on demand
 * (gli_bvh_add_wide). */
static inline int gli_wide_may_hand_over(size_t spheres, size_t cones) {
  return spheres + cones >= GLI_HAND_OVER_REFS / 2;
}

/* Collapses a built (or refitted) binary BVH over `scene`: from the root
 * down, a wide node starts with its binary node's two children and opens
 * the child of largest surface area until it has GLI_WIDE children or only
 * leaves of at most GLI_WIDE_LEAF references, and, when `mark`, marks the
 * binary nodes where packets hand subtrees over (GLI_NODE_HAND_OVER; not
 * marking, it writes nothing of the binary tree, which others may be
 * walking). A BVH without hierarchy gives none. */
glint_status gli_wide_build(struct gli_bvh *binary, const glint_scene *scene,
                            int mark, gli_wide_bvh *wide, glint_error *error);
void gli_wide_free(gli_wide_bvh *wide);
uint64_t gli_wide_bytes(const gli_wide_bvh *wide);

#endif
