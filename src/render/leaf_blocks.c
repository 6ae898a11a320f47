/* Building the leaf blocks (see leaf_blocks.h). */
#include "render/leaf_blocks.h"

#include "core/error.h"
#include "core/memory.h"
#include "scene/scene.h"

#include <stdlib.h>
#include <string.h>

/* Calls visit(ctx, first, count) for every leaf of the wide tree. */
static void each_leaf(const gli_wide_bvh *w,
                      void (*visit)(void *, uint32_t, uint32_t), void *ctx) {
  for (uint32_t i = 0; i < w->node_count; i++)
    for (int k = 0; k < GLI_WIDE; k++)
      if (w->nodes[i].count[k])
        visit(ctx, w->nodes[i].child[k], w->nodes[i].count[k]);
}

typedef struct builder {
  const scene_r *s;
  const uint32_t *refs;
  leaf_blocks *b;
  int fill; /* 0: count only */
} builder;

static void put_sphere(const scene_r *s, block_sphere *bk, int lane,
                       uint32_t i) {
  const sphere_r *p = &s->spheres[i];
  bk->center[0][lane] = p->center.x;
  bk->center[1][lane] = p->center.y;
  bk->center[2][lane] = p->center.z;
  bk->r2[lane] = p->r2;
  bk->prim[lane] = i;
}

static void put_triangle(const scene_r *s, block_triangle *bk, int lane,
                         uint32_t i) {
  const triangle_r *p = &s->triangles[i];
  const vec3 *rows[8] = {&p->a,         &p->edge[0],   &p->edge[1],
                         &p->edge[2],   &p->moment[0], &p->moment[1],
                         &p->moment[2], &p->n};
  float(*dst[8])[BL] = {bk->a,         bk->edge[0],   bk->edge[1],
                        bk->edge[2],   bk->moment[0], bk->moment[1],
                        bk->moment[2], bk->n};
  for (int r = 0; r < 8; r++) {
    dst[r][0][lane] = rows[r]->x;
    dst[r][1][lane] = rows[r]->y;
    dst[r][2][lane] = rows[r]->z;
  }
  bk->prim[lane] = i;
}

static void put_cone(const scene_r *s, block_cone *bk, int lane, uint32_t i) {
  const cone_r *p = &s->cones[i];
  bk->base[0][lane] = p->base.x;
  bk->base[1][lane] = p->base.y;
  bk->base[2][lane] = p->base.z;
  bk->axis[0][lane] = p->axis.x;
  bk->axis[1][lane] = p->axis.y;
  bk->axis[2][lane] = p->axis.z;
  bk->height[lane] = p->height;
  bk->rb[lane] = p->rb;
  bk->k[lane] = p->k;
  bk->reach2[lane] = p->reach2;
  bk->prim[lane] = i;
}

/* One leaf: runs of at most BL references of one shape. */
static void visit_leaf(void *ctx, uint32_t first, uint32_t count) {
  builder *bd = ctx;
  leaf_blocks *b = bd->b;
  if (bd->fill)
    b->first_run[first] = (uint32_t)b->run_count;
  for (uint32_t k = 0; k < count;) {
    uint32_t shape = GLI_REF_SHAPE(bd->refs[first + k]);
    uint32_t n = 0;
    while (k + n < count && n < BL &&
           GLI_REF_SHAPE(bd->refs[first + k + n]) == shape)
      n++;
    size_t *blocks = shape == GLI_SHAPE_SPHERE     ? &b->sphere_blocks
                     : shape == GLI_SHAPE_TRIANGLE ? &b->triangle_blocks
                                                   : &b->cone_blocks;
    if (bd->fill) {
      b->runs[b->run_count] =
          (leaf_run){(uint32_t)*blocks, (uint16_t)shape, (uint16_t)n};
      for (uint32_t j = 0; j < n; j++) {
        uint32_t i = GLI_REF_INDEX(bd->refs[first + k + j]);
        if (shape == GLI_SHAPE_SPHERE)
          put_sphere(bd->s, &b->spheres[*blocks], (int)j, i);
        else if (shape == GLI_SHAPE_TRIANGLE)
          put_triangle(bd->s, &b->triangles[*blocks], (int)j, i);
        else
          put_cone(bd->s, &b->cones[*blocks], (int)j, i);
      }
    }
    b->run_count++;
    ++*blocks;
    k += n;
  }
}

glint_status leaf_blocks_build(const scene_r *s, const gli_bvh *bvh,
                               leaf_blocks **out, glint_error *error) {
  *out = NULL;
  const gli_wide_bvh *w = &bvh->wide;
  if (!w->nodes)
    return GLINT_OK;
  leaf_blocks *b = calloc(1, sizeof *b);
  if (!b)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  builder bd = {s, w->refs, b, 0};
  each_leaf(w, visit_leaf, &bd);
  b->first_run = malloc(w->ref_count * sizeof *b->first_run);
  b->runs = malloc(b->run_count * sizeof *b->runs + 1);
  b->spheres = gli_aligned_calloc(b->sphere_blocks, sizeof *b->spheres);
  b->triangles = gli_aligned_calloc(b->triangle_blocks, sizeof *b->triangles);
  b->cones = gli_aligned_calloc(b->cone_blocks, sizeof *b->cones);
  if (!b->first_run || !b->runs || (b->sphere_blocks && !b->spheres) ||
      (b->triangle_blocks && !b->triangles) || (b->cone_blocks && !b->cones)) {
    leaf_blocks_free(b);
    return gli_fail(error, GLINT_E_MEMORY,
                    "out of memory laying out the BVH's leaves");
  }
  b->run_count = b->sphere_blocks = b->triangle_blocks = b->cone_blocks = 0;
  bd.fill = 1;
  each_leaf(w, visit_leaf, &bd);
  *out = b;
  return GLINT_OK;
}

void leaf_blocks_free(leaf_blocks *b) {
  if (!b)
    return;
  free(b->first_run);
  free(b->runs);
  gli_aligned_free(b->spheres);
  gli_aligned_free(b->triangles);
  gli_aligned_free(b->cones);
  free(b);
}

size_t leaf_blocks_bytes(const leaf_blocks *b) {
  if (!b)
    return 0;
  return b->run_count * sizeof *b->runs +
         b->sphere_blocks * sizeof *b->spheres +
         b->triangle_blocks * sizeof *b->triangles +
         b->cone_blocks * sizeof *b->cones;
}
