/* The wide BVH's leaves (accel/wide_bvh.h) laid out for single rays: each
 * leaf's primitives, grouped by shape (the wide tree sorts a leaf's
 * references so), in blocks of GLI_BLOCK_LANES whose fields are stored lane
 * by lane, so that one ray tests a whole block with the packet formulas of
 * geometry/packet_intersect.h, the ray broadcast and the primitives in the
 * lanes (Embree's triangle4/8 leaves; Wald, Benthin and Boulos 2008).
 * Built from the float scalar scene when a renderer binds a packet layout
 * to a BVH with a wide tree; compiled once per ISA. */
#ifndef GLINT_RENDER_LEAF_BLOCKS_H
#define GLINT_RENDER_LEAF_BLOCKS_H

#include "render/packet_scene.h"
#include "simd/vvec3.h"

#define BL GLI_BLOCK_LANES

typedef struct block_sphere {
  SIMD_ALIGN float center[3][BL];
  float r2[BL];
  uint32_t prim[BL];
} block_sphere;

typedef struct block_triangle {
  SIMD_ALIGN float a[3][BL];
  float edge[3][3][BL], moment[3][3][BL]; /* [edge][axis][lane] */
  float n[3][BL];
  uint32_t prim[BL];
} block_triangle;

typedef struct block_cone {
  SIMD_ALIGN float base[3][BL], axis[3][BL];
  float height[BL], rb[BL], k[BL], reach2[BL];
  uint32_t prim[BL];
} block_cone;

/* A run of one shape's primitives in a leaf: `count` lanes of block
 * `block` of that shape. */
typedef struct leaf_run {
  uint32_t block;
  uint16_t shape, count;
} leaf_run;

typedef struct leaf_blocks {
  /* A leaf's first run, by the position of its first reference in the
   * wide tree's refs; its runs follow, until they hold its count. */
  uint32_t *first_run;
  leaf_run *runs;
  block_sphere *spheres;
  block_triangle *triangles;
  block_cone *cones;
  size_t run_count, sphere_blocks, triangle_blocks, cone_blocks;
} leaf_blocks;

/* Three rows of a block (a field's x, y and z) as lanes. */
static inline vvec3 block_vec(const float (*rows)[BL]) {
  vvec3 r = {vf_load_block(rows[0]), vf_load_block(rows[1]),
             vf_load_block(rows[2])};
  return r;
}

#define leaf_blocks_build ISA_NAME(gli_leaf_blocks_build)
#define leaf_blocks_free ISA_NAME(gli_leaf_blocks_free)
#define leaf_blocks_bytes ISA_NAME(gli_leaf_blocks_bytes)

/* The blocks of every leaf of bvh->wide over scene s (NULL *out when the
 * BVH has no wide tree). */
glint_status leaf_blocks_build(const scene_r *s, const gli_bvh *bvh,
                               leaf_blocks **out, glint_error *error);
void leaf_blocks_free(leaf_blocks *b);
size_t leaf_blocks_bytes(const leaf_blocks *b);

#endif
