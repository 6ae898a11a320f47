/* A bounding volume hierarchy over every bounded primitive of a scene
 * (spheres, triangles, cones; unbounded planes are kept outside it), built
 * top-down by the surface area heuristic over binned centroids (Wald 2007,
 * "On fast construction of SAH-based bounding volume hierarchies"). One
 * BVH serves every backend: boxes are float, rounded outward so they hold
 * the double-precision primitives too. */
#ifndef GLINT_ACCEL_BVH_H
#define GLINT_ACCEL_BVH_H

#include "accel/wide_bvh.h"
#include "glint.h"

#include <stdint.h>

/* A primitive reference: its shape in the top two bits, its index in the
 * shape's array below them. */
#define GLI_REF(shape, index) ((uint32_t)(shape) << 30 | (uint32_t)(index))
#define GLI_REF_SHAPE(ref) ((ref) >> 30)
#define GLI_REF_INDEX(ref) ((ref)&0x3fffffffu)
#define GLI_MAX_BVH_PRIMS 0x3fffffffu

/* 32 bytes, two to a cache line. The children of an inner node are
 * adjacent: offset and offset + 1. */
typedef struct gli_bvh_node {
  float lo[3], hi[3];
  uint32_t offset; /* inner: first child; leaf: first reference */
  uint16_t count;  /* references in a leaf; 0 for an inner node */
  uint8_t axis;    /* an inner node's split axis */
  uint8_t flags;   /* GLI_NODE_HAND_OVER */
} gli_bvh_node;

/* A packet's few remaining lanes may walk this inner node's subtree alone
 * through the wide tree (accel/packet_traverse.h, accel/wide_bvh.h). */
#define GLI_NODE_HAND_OVER 1

/* The levels the surface area heuristic splits (bvh.c); below them a node
 * of more references than a leaf holds (UINT16_MAX) is still halved, at
 * most GLI_BVH_FORCED_SPLITS times for GLI_MAX_BVH_PRIMS references (2^30
 * halved 15 times fits a leaf). */
#define GLI_BVH_MAX_DEPTH 64
#define GLI_BVH_FORCED_SPLITS 16
/* What a walk's stack holds: one waiting child for each level of the
 * deepest tree, and both children of its deepest node (a segment walk
 * pushes them before testing them). Sized for the split levels alone, a
 * scene of 140 000 copies of one triangle overran the scalar backends'
 * shadow walk. */
#define GLI_BVH_STACK (GLI_BVH_MAX_DEPTH + GLI_BVH_FORCED_SPLITS + 2)
#define GLI_BVH_MIN_PRIMS 16 /* fewer bounded primitives: no hierarchy */
/* As many or more: the packets walk a cut of the tree (bvh.c, cut_costs). */
#define GLI_BVH_PACKET_CUT_PRIMS 40000

typedef struct gli_bvh {
  /* The same tree collapsed for single rays (accel/wide_bvh.h); built with
   * it where packets may hand subtrees over (gli_wide_may_hand_over), else
   * on demand (gli_bvh_add_wide), and refitted by collapsing the refitted
   * tree again. */
  gli_wide_bvh wide;
  gli_bvh_node *nodes;
  uint32_t node_count;
  /* The tree the packet walks take (accel/packet_traverse.h): `nodes`
   * itself, or in a large scene the same tree with the subtrees that
   * packets test faster as one leaf cut into one (bvh.c, cut_costs); and
   * per packet node, wide.of_binary of the binary node it copies. */
  gli_bvh_node *packet_nodes;
  uint32_t *packet_wide;
  uint32_t packet_node_count;
  uint32_t *refs;
  uint32_t ref_count;
  int depth;
  double build_seconds;
  /* What it was built over: a refit needs the same primitives. */
  size_t spheres, triangles, cones;
  /* The surface area heuristic's cost of a ray (MacDonald and Booth 1990):
   * the nodes' areas over the root's, leaves weighted by their primitives;
   * `built_cost` is the cost when the topology was built, which refits
   * keep, so that one can tell how far moving objects have worn it. */
  double cost, built_cost;
} gli_bvh;

/* Builds over the scene's spheres, triangles and cones. A scene with at most
 * GLI_BVH_MIN_PRIMS of them gives node_count = 0: test them all. A large
 * scene's tree is built on up to `threads` threads (1: the calling one
 * alone), and is the same tree whatever their number. */
glint_status gli_bvh_build(const glint_scene *scene, int threads, gli_bvh *bvh,
                           glint_error *error);
void gli_bvh_free(gli_bvh *bvh);

/* Collapses the wide tree of a built BVH where it has none yet (for
 * --accel bvh8, whose rays all walk it). */
glint_status gli_bvh_add_wide(gli_bvh *bvh, const glint_scene *scene,
                              glint_error *error);

/* The BVH of `scene` with `from`'s tree, every box recomputed bottom-up for
 * the primitives where they are now: for an animation's next frame, whose
 * objects moved but are the same (GLINT_E_ARGUMENT when the counts
 * differ). Far cheaper than a build; the tree gets worse as the objects
 * move away from where it was built (compare cost with built_cost). */
glint_status gli_bvh_refit(const gli_bvh *from, const glint_scene *scene,
                           gli_bvh *bvh, glint_error *error);

/* The float box of primitive reference `ref` as the builder bounds it. */
void gli_bvh_ref_box(const glint_scene *scene, uint32_t ref, float lo[3],
                     float hi[3]);

/* Bytes the built binary hierarchy occupies (nodes and references, and
 * the packets' cut of it where it has one; the wide one: gli_wide_bytes). */
uint64_t gli_bvh_bytes(const gli_bvh *bvh);

#endif
