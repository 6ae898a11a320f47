/* Collapsing the binary BVH into the wide one (see wide_bvh.h). Opening the
 * child of largest surface area first keeps the children that rays are most
 * likely to enter near the root, as Embree's BVH8 builder does (Wald et al.
 * 2014, "Embree: a kernel framework for efficient CPU ray tracing", §4).
 *
 * The binary tree's leaves are sized for packets, which test a leaf's
 * primitives for all their lanes at once (up to 16 references, 4-10 on
 * the SPD scenes); a single ray tests them one after another, so a leaf of
 * more than GLI_WIDE_LEAF references is opened too, into two halves of its
 * references split at their centroids' median along the widest axis. The
 * wide tree has its own copy of the references for this, so that the
 * binary tree's order (which decides exact ties) stays as built. */
#include "accel/wide_bvh.h"

#include "accel/bvh.h"
#include "core/error.h"
#include "core/memory.h"
#include "core/timer.h"
#include "scene/scene.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A child being placed: a binary node, or references split off a leaf. */
typedef struct slot {
  uint32_t binary;       /* the binary node, or GLI_WIDE_NONE for a range */
  uint32_t begin, count; /* its references (count 0: a binary inner node) */
  float lo[3], hi[3];
} slot;

typedef struct collapser {
  const gli_bvh *binary;
  const glint_scene *scene;
  uint32_t *refs; /* the wide tree's copy, reordered within leaves */
  gli_wide_bvh *wide;
  uint32_t capacity;
  int failed;
} collapser;

static float half_area(const slot *s) {
  float dx = s->hi[0] - s->lo[0], dy = s->hi[1] - s->lo[1],
        dz = s->hi[2] - s->lo[2];
  return dx * dy + dy * dz + dz * dx;
}

static slot binary_slot(const collapser *c, uint32_t b) {
  const gli_bvh_node *n = &c->binary->nodes[b];
  slot s = {b, n->offset, n->count, {0}, {0}};
  memcpy(s.lo, n->lo, sizeof s.lo);
  memcpy(s.hi, n->hi, sizeof s.hi);
  if (!n->count)
    s.begin = 0;
  return s;
}

/* The references [begin, begin + count) as a slot, with their box. */
static slot range_slot(const collapser *c, uint32_t begin, uint32_t count) {
  slot s = {GLI_WIDE_NONE,
            begin,
            count,
            {FLT_MAX, FLT_MAX, FLT_MAX},
            {-FLT_MAX, -FLT_MAX, -FLT_MAX}};
  for (uint32_t k = begin; k < begin + count; k++) {
    float lo[3], hi[3];
    gli_bvh_ref_box(c->scene, c->refs[k], lo, hi);
    for (int a = 0; a < 3; a++) {
      s.lo[a] = fminf(s.lo[a], lo[a]);
      s.hi[a] = fmaxf(s.hi[a], hi[a]);
    }
  }
  return s;
}

static int openable(const slot *s) {
  return s->count == 0 || s->count > GLI_WIDE_LEAF;
}

typedef struct keyed_ref {
  float key;
  uint32_t ref;
} keyed_ref;

static int by_ref(const void *a, const void *b) {
  uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
  return (x > y) - (x < y);
}

static int by_key(const void *a, const void *b) {
  float x = ((const keyed_ref *)a)->key, y = ((const keyed_ref *)b)->key;
  return (x > y) - (x < y);
}

/* Splits an openable slot into two. */
static void open_slot(collapser *c, const slot *s, slot *a, slot *b) {
  if (s->count == 0) {
    uint32_t first = c->binary->nodes[s->binary].offset;
    *a = binary_slot(c, first);
    *b = binary_slot(c, first + 1);
    return;
  }
  /* Sort the references by centroid along the axis where the slot is
   * widest, and halve them. */
  int axis = 0;
  for (int k = 1; k < 3; k++)
    if (s->hi[k] - s->lo[k] > s->hi[axis] - s->lo[axis])
      axis = k;
  keyed_ref small[GLI_WIDE_LEAF * 8];
  keyed_ref *keyed = s->count <= sizeof small / sizeof *small
                         ? small
                         : malloc(s->count * sizeof *keyed);
  uint32_t half = s->count / 2;
  if (keyed) {
    for (uint32_t k = 0; k < s->count; k++) {
      float lo[3], hi[3];
      uint32_t ref = c->refs[s->begin + k];
      gli_bvh_ref_box(c->scene, ref, lo, hi);
      keyed[k] = (keyed_ref){lo[axis] + hi[axis], ref};
    }
    qsort(keyed, s->count, sizeof *keyed, by_key);
    for (uint32_t k = 0; k < s->count; k++)
      c->refs[s->begin + k] = keyed[k].ref;
    if (keyed != small)
      free(keyed);
  } /* (out of memory: halve them unsorted, still correct) */
  *a = range_slot(c, s->begin, half);
  *b = range_slot(c, s->begin + half, s->count - half);
}

static uint32_t new_node(collapser *c) {
  gli_wide_bvh *w = c->wide;
  if (w->node_count == c->capacity) {
    uint32_t cap = c->capacity ? 2 * c->capacity : 64;
    gli_wide_node *grown = gli_aligned_calloc(cap, sizeof *grown);
    if (!grown) {
      c->failed = 1;
      return GLI_WIDE_NONE;
    }
    if (w->nodes)
      memcpy(grown, w->nodes, w->node_count * sizeof *grown);
    gli_aligned_free(w->nodes);
    w->nodes = grown;
    c->capacity = cap;
  }
  return w->node_count++;
}

/* Makes the wide node of an openable slot; returns its index. */
static uint32_t collapse(collapser *c, const slot *from, int depth) {
  uint32_t w = new_node(c);
  if (w == GLI_WIDE_NONE)
    return 0;
  if (from->binary != GLI_WIDE_NONE && from->count == 0)
    c->wide->of_binary[from->binary] = w;
  if (depth > c->wide->depth)
    c->wide->depth = depth;
  slot slots[GLI_WIDE];
  int n = 0;
  if (openable(from)) {
    open_slot(c, from, &slots[0], &slots[1]);
    n = 2;
  } else {
    slots[n++] = *from; /* a root that is one small leaf */
  }
  while (n < GLI_WIDE) {
    int best = -1;
    float best_area = -1;
    for (int k = 0; k < n; k++)
      if (openable(&slots[k]) && half_area(&slots[k]) > best_area)
        best = k, best_area = half_area(&slots[k]);
    if (best < 0)
      break;
    slot opened = slots[best];
    open_slot(c, &opened, &slots[best], &slots[n]);
    n++;
  }
  uint32_t child[GLI_WIDE] = {0};
  uint16_t count[GLI_WIDE] = {0};
  for (int k = 0; k < n; k++) {
    /* A leaf too big for single rays opens into a node of its own while
     * the tree is shallow enough for the walks' stacks. */
    if (slots[k].count == 0 ||
        (openable(&slots[k]) && depth < GLI_WIDE_MAX_DEPTH - 1)) {
      child[k] = collapse(c, &slots[k], depth + 1);
    } else {
      /* A leaf's references in order, which groups them by shape (the top
       * bits) for render/leaf_blocks.h. Binary leaves hold at most
       * UINT16_MAX references (accel/bvh.c), and so do their parts. */
      qsort(&c->refs[slots[k].begin], slots[k].count, sizeof *c->refs, by_ref);
      child[k] = slots[k].begin;
      count[k] = (uint16_t)slots[k].count;
    }
  }
  /* (the array may have grown during the recursion: index it afresh) */
  gli_wide_node *node = &c->wide->nodes[w];
  for (int k = 0; k < GLI_WIDE; k++)
    for (int a = 0; a < 3; a++) {
      node->bounds[0][a][k] = k < n ? slots[k].lo[a] : INFINITY;
      node->bounds[1][a][k] = k < n ? slots[k].hi[a] : -INFINITY;
    }
  memcpy(node->child, child, sizeof child);
  memcpy(node->count, count, sizeof count);
  return w;
}

/* Marks the binary nodes where a packet may hand its few remaining lanes a
 * subtree: the roots of wide nodes (the others have no wide counterpart)
 * whose subtrees hold at least GLI_HAND_OVER_REFS references, at least
 * half of them spheres or cones. Where triangles lie, single rays do not pay: a
 * packet's triangle test is cheap, a few products per lane, while its
 * sphere and cone tests take square roots and divisions for every lane
 * (gears-s4, all triangles, was 8% slower with hand-overs; balls-s4 and
 * rings-s4 11-15% faster); mount-s6, 8192 triangles and 4 spheres, took 6%
 * more instructions while a single sphere anywhere in a subtree marked it.
 * Nor in small subtrees, where a packet's few box tests cost less than its
 * lanes' set-up (the stress scenes mirror-room and glass-in-glass, 52 and
 * 108 primitives, were 11-16% slower with hand-overs everywhere; from 128
 * references none lost and sticks gained most: README, "Performance"). */
static void mark_hand_overs(gli_bvh *binary, gli_wide_bvh *wide) {
  /* children come after their parents: one backward pass, counting each
   * subtree's references and its spheres and cones among them */
  typedef struct subtree {
    uint32_t refs, round;
  } subtree;
  subtree *below = malloc(binary->node_count * sizeof *below);
  for (uint32_t i = binary->node_count; i-- > 0 && below;) {
    gli_bvh_node *n = &binary->nodes[i];
    subtree *b = &below[i];
    if (n->count) {
      b->refs = n->count;
      b->round = 0;
      for (uint32_t k = n->offset; k < n->offset + n->count; k++)
        b->round += GLI_REF_SHAPE(binary->refs[k]) != GLI_SHAPE_TRIANGLE;
    } else {
      b->refs = below[n->offset].refs + below[n->offset + 1].refs;
      b->round = below[n->offset].round + below[n->offset + 1].round;
    }
    n->flags = (uint8_t)(n->count == 0 && b->refs >= GLI_HAND_OVER_REFS &&
                                 2 * (uint64_t)b->round >= b->refs &&
                                 wide->of_binary[i] != GLI_WIDE_NONE
                             ? GLI_NODE_HAND_OVER
                             : 0);
    wide->hand_overs += n->flags & GLI_NODE_HAND_OVER;
  }
  free(below); /* (out of memory: no hand-overs, still correct) */
}

glint_status gli_wide_build(gli_bvh *binary, const glint_scene *scene, int mark,
                            gli_wide_bvh *wide, glint_error *error) {
  double t0 = gli_now();
  memset(wide, 0, sizeof *wide);
  if (binary->node_count == 0)
    return GLINT_OK;
  wide->of_binary = malloc(binary->node_count * sizeof *wide->of_binary);
  wide->refs = malloc(binary->ref_count * sizeof *wide->refs);
  if (!wide->of_binary || !wide->refs) {
    gli_wide_free(wide);
    return gli_fail(error, GLINT_E_MEMORY,
                    "out of memory building the wide BVH");
  }
  memcpy(wide->refs, binary->refs, binary->ref_count * sizeof *wide->refs);
  wide->ref_count = binary->ref_count;
  wide->binary_count = binary->node_count;
  for (uint32_t i = 0; i < binary->node_count; i++)
    wide->of_binary[i] = GLI_WIDE_NONE;
  collapser c = {binary, scene, wide->refs, wide, 0, 0};
  slot root = binary_slot(&c, 0);
  collapse(&c, &root, 1);
  if (mark)
    mark_hand_overs(binary, wide);
  if (c.failed) {
    gli_wide_free(wide);
    return gli_fail(error, GLINT_E_MEMORY,
                    "out of memory building the wide BVH");
  }
  wide->build_seconds = gli_now() - t0;
  return GLINT_OK;
}

void gli_wide_free(gli_wide_bvh *wide) {
  gli_aligned_free(wide->nodes);
  free(wide->of_binary);
  free(wide->refs);
  memset(wide, 0, sizeof *wide);
}

uint64_t gli_wide_bytes(const gli_wide_bvh *wide) {
  if (!wide->nodes)
    return 0;
  return (uint64_t)wide->node_count * sizeof(gli_wide_node) +
         (uint64_t)wide->binary_count * sizeof *wide->of_binary +
         (uint64_t)wide->ref_count * sizeof *wide->refs;
}
