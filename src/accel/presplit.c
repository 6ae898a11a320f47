/* Pre-splitting (see presplit.h). A piece of a cone is the part between
 * two fractions of its axis, halved at the middle fraction. A piece's gain
 * is the surface area its box loses when replaced by its halves' boxes: the
 * surface area heuristic's measure of how many fewer rays would visit it
 * (MacDonald and Booth 1990). A max-heap hands out the budget by gain. */
#include "accel/presplit.h"

#include "accel/bvh.h"

#include <stdlib.h>

/* A split must shrink the summed box area by this fraction of the piece's
 * own: a piece about as long as it is wide gains less (a cylinder as long
 * as its diameter, cut across the axes, gains 0.2 to 0.3), and its halves'
 * boxes would overlap nearly as much as the whole. Measured: rings-s4 and
 * sticks gain the same from 0.05 to 0.15, less at 0.3. */
#define MIN_GAIN 0.15f

typedef struct candidate {
  float gain;
  uint32_t index;
} candidate;

typedef struct splitter {
  const glint_scene *scene;
  uint32_t *refs;
  gli_ref_box *boxes;
  gli_ref_part *parts;
  candidate *heap;
  size_t heap_count;
} splitter;

static float half_area(const gli_ref_box *b) {
  float d[3];
  for (int k = 0; k < 3; k++)
    d[k] = b->hi[k] > b->lo[k] ? b->hi[k] - b->lo[k] : 0;
  return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

gli_ref_box gli_ref_part_box(const glint_scene *scene, uint32_t ref,
                             gli_ref_part part) {
  uint32_t i = GLI_REF_INDEX(ref);
  switch (GLI_REF_SHAPE(ref)) {
  case GLI_SHAPE_SPHERE: return gli_sphere_box(&scene->spheres[i]);
  case GLI_SHAPE_TRIANGLE: return gli_triangle_box(&scene->triangles[i]);
  default: break;
  }
  const gli_cone_prim *c = &scene->cones[i];
  gli_ref_box b = gli_cone_part_box(c, part.s0, part.s1);
  if (part.s0 > 0 || part.s1 < 1) {
    /* A point part of the way along the axis comes from arithmetic in
     * double whose rounding must not leave a sliver of the cone out of
     * both halves' boxes: widened by a few float steps of the cone's size
     * and place (the cone's, not the part's, so that a part's box is never
     * wider than the parts it was merged from: bvh.c, drop_repeats). */
    double r = gli_dmax(fabs(c->base_radius), fabs(c->apex_radius));
    const double lo[3] = {c->base.x, c->base.y, c->base.z},
                 hi[3] = {c->apex.x, c->apex.y, c->apex.z};
    for (int k = 0; k < 3; k++) {
      float e = (float)((fabs(lo[k]) + fabs(hi[k]) + fabs(hi[k] - lo[k]) +
                         2 * r) *
                        0x1p-21);
      b.lo[k] -= e;
      b.hi[k] += e;
    }
  }
  return b;
}

/* Piece i's halves and the area its box would lose to them. */
static float halve(const splitter *s, size_t i, gli_ref_part half[2],
                   gli_ref_box box[2]) {
  gli_ref_part p = s->parts[i];
  float mid = 0.5f * (p.s0 + p.s1);
  half[0] = (gli_ref_part){p.s0, mid};
  half[1] = (gli_ref_part){mid, p.s1};
  for (int h = 0; h < 2; h++)
    box[h] = gli_ref_part_box(s->scene, s->refs[i], half[h]);
  return half_area(&s->boxes[i]) - half_area(&box[0]) - half_area(&box[1]);
}

static void heap_push(splitter *s, float gain, uint32_t index) {
  size_t i = s->heap_count++;
  while (i > 0 && s->heap[(i - 1) / 2].gain < gain) {
    s->heap[i] = s->heap[(i - 1) / 2];
    i = (i - 1) / 2;
  }
  s->heap[i] = (candidate){gain, index};
}

static candidate heap_pop(splitter *s) {
  candidate top = s->heap[0], last = s->heap[--s->heap_count];
  size_t i = 0;
  for (;;) {
    size_t c = 2 * i + 1;
    if (c >= s->heap_count)
      break;
    if (c + 1 < s->heap_count && s->heap[c + 1].gain > s->heap[c].gain)
      c++;
    if (s->heap[c].gain <= last.gain)
      break;
    s->heap[i] = s->heap[c];
    i = c;
  }
  if (s->heap_count)
    s->heap[i] = last;
  return top;
}

/* Offers piece i to the heap if halving it gains enough (and its fractions
 * can still be halved in float). */
static void offer(splitter *s, size_t i) {
  gli_ref_part half[2];
  gli_ref_box box[2];
  float gain = halve(s, i, half, box);
  float mg = getenv("GLINT_MG") ? (float)atof(getenv("GLINT_MG")) : MIN_GAIN;
  if (gain > mg * half_area(&s->boxes[i]) && half[0].s1 > half[0].s0 &&
      half[1].s1 > half[1].s0)
    heap_push(s, gain, (uint32_t)i);
}

static int splittable(const glint_scene *scene, uint32_t ref) {
  if (GLI_REF_SHAPE(ref) != GLI_SHAPE_CONE)
    return 0;
  uint32_t object = scene->cones[GLI_REF_INDEX(ref)].object;
  return scene->materials[scene->objects[object].material].kt == 0;
}

size_t gli_presplit(const glint_scene *scene, uint32_t *refs,
                    gli_ref_box *boxes, gli_ref_part *parts, size_t n,
                    size_t capacity) {
  for (size_t i = 0; i < n; i++)
    parts[i] = (gli_ref_part){0, 1};
  size_t cones = 0;
  for (size_t i = 0; i < n; i++)
    cones += splittable(scene, refs[i]);
  size_t budget = n + (getenv("GLINT_BUDGET") ? (size_t)(atof(getenv("GLINT_BUDGET")) * cones) : GLI_PRESPLIT_BUDGET * cones);
  if (budget > capacity)
    budget = capacity;
  if (budget <= n)
    return n;
  /* Each split pops one candidate and pushes at most two. */
  splitter s = {scene, refs, boxes, parts, malloc(budget * sizeof *s.heap), 0};
  if (!s.heap) /* out of memory: the references as they are */
    return n;
  for (size_t i = 0; i < n; i++)
    if (splittable(scene, refs[i]))
      offer(&s, i);
  size_t count = n;
  while (s.heap_count > 0 && count < budget) {
    uint32_t i = heap_pop(&s).index;
    gli_ref_part half[2];
    gli_ref_box box[2];
    halve(&s, i, half, box);
    boxes[i] = box[0];
    parts[i] = half[0];
    refs[count] = refs[i];
    boxes[count] = box[1];
    parts[count] = half[1];
    count++;
    offer(&s, i);
    offer(&s, count - 1);
  }
  free(s.heap);
  return count;
}
