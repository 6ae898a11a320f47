/* Binned SAH construction (see bvh.h). Each node's primitives are binned by
 * centroid into BINS slabs along all three axes in one pass; a sweep over the
 * bins gives the surface area heuristic cost of every slab boundary,
 *   cost = C_node + (A_left C_left + A_right C_right) / A,
 * with C a side's summed primitive costs,
 * and the cheapest split wins unless keeping a leaf is cheaper. */
#include "accel/bvh.h"

#include "core/error.h"
#include "core/memory.h"
#include "core/thread.h"
#include "core/timer.h"
#include "scene/scene.h"

#include <emmintrin.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BINS 16
#define MAX_LEAF 16 /* never more references in a leaf */
/* Costs in triangle tests. Visiting an inner node tests both children's
 * boxes; a sphere or cylinder test is cheaper than a triangle's in packets.
 * Chosen by measurement on the SPD suite (glint bench --spd, avx512 and
 * stream-avx512): with one cost for every shape, balls-s4 (spheres) wanted
 * a node cost near 8 and the triangle scenes near 2.5; per-shape costs give
 * both (balls-s4 6% faster, rings-s4 2%, the triangle scenes unchanged). */
#define COST_NODE 2.5f
static const float prim_cost[3] = {
    [GLI_SHAPE_SPHERE] = 0.4f,
    [GLI_SHAPE_TRIANGLE] = 1.0f,
    [GLI_SHAPE_CONE] = 0.6f,
};

typedef struct box {
  float lo[3], hi[3];
} box;

/* Float bounds that contain [lo, hi] given in double: rounded to nearest,
 * then one step outward when that went inward (nextafterf is a call;
 * scaling by 1 -/+ 2^-23 is one float step for normal numbers, and bounds
 * around zero only need to be conservative). */
static inline double dmin(double a, double b) { return a < b ? a : b; }
static inline double dmax(double a, double b) { return a > b ? a : b; }
static float down(double x) {
  float f = (float)x;
  if ((double)f <= x)
    return f;
  return f > 0 ? f * (1 - 0x1p-23f) : f < 0 ? f * (1 + 0x1p-23f) : -FLT_MIN;
}
static float up(double x) {
  float f = (float)x;
  if ((double)f >= x)
    return f;
  return f > 0 ? f * (1 + 0x1p-23f) : f < 0 ? f * (1 - 0x1p-23f) : FLT_MIN;
}

static box box_of(double lo[3], double hi[3]) {
  box b;
  for (int k = 0; k < 3; k++) {
    b.lo[k] = down(lo[k]);
    b.hi[k] = up(hi[k]);
  }
  return b;
}

static box sphere_box(const gli_sphere_prim *s) {
  double c[3] = {s->center.x, s->center.y, s->center.z};
  double lo[3], hi[3];
  for (int k = 0; k < 3; k++)
    lo[k] = c[k] - s->radius, hi[k] = c[k] + s->radius;
  return box_of(lo, hi);
}

static box triangle_box(const gli_triangle_prim *t) {
  double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX},
         hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
  for (int i = 0; i < 3; i++) {
    double v[3] = {t->v[i].x, t->v[i].y, t->v[i].z};
    for (int k = 0; k < 3; k++)
      lo[k] = dmin(lo[k], v[k]), hi[k] = dmax(hi[k], v[k]);
  }
  return box_of(lo, hi);
}

/* The two end disks' boxes: a disk of radius r with unit normal a reaches
 * r sqrt(1 - a_k^2) along axis k. */
static box cone_box(const gli_cone_prim *c) {
  double a[3] = {c->apex.x - c->base.x, c->apex.y - c->base.y,
                 c->apex.z - c->base.z};
  double len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  double p[2][3] = {{c->base.x, c->base.y, c->base.z},
                    {c->apex.x, c->apex.y, c->apex.z}};
  double r[2] = {c->base_radius, c->apex_radius};
  double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX},
         hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
  for (int e = 0; e < 2; e++)
    for (int k = 0; k < 3; k++) {
      double ak = a[k] / len;
      double ext = r[e] * sqrt(dmax(0.0, 1 - ak * ak));
      lo[k] = dmin(lo[k], p[e][k] - ext);
      hi[k] = dmax(hi[k], p[e][k] + ext);
    }
  return box_of(lo, hi);
}

/* ---- the builder ------------------------------------------------------ */

/* Boxes in SSE registers: lo and hi as (x, y, z, unused), so growing one is
 * two instructions. Centroids are kept doubled (lo + hi), which bins the
 * same. The build runs on the baseline x86-64 ISA, which has SSE2. */
typedef struct box4 {
  __m128 lo, hi;
} box4;

static box4 box4_empty(void) {
  box4 b = {_mm_set1_ps(FLT_MAX), _mm_set1_ps(-FLT_MAX)};
  return b;
}

static void box4_grow(box4 *b, box4 o) {
  b->lo = _mm_min_ps(b->lo, o.lo);
  b->hi = _mm_max_ps(b->hi, o.hi);
}

static void box4_grow_point(box4 *b, __m128 p) {
  b->lo = _mm_min_ps(b->lo, p);
  b->hi = _mm_max_ps(b->hi, p);
}

/* Half the surface area (the factor cancels in the heuristic), in
 * registers: d = hi - lo, d.x d.y + d.y d.z + d.z d.x. Empty boxes (lo >
 * hi) give 0. */
static float box4_area(box4 b) {
  __m128 d = _mm_max_ps(_mm_sub_ps(b.hi, b.lo), _mm_setzero_ps());
  __m128 rot = _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 2, 1)); /* y z x */
  __m128 p = _mm_mul_ps(d, rot);                              /* xy yz zx */
  __m128 s = _mm_add_ss(p, _mm_shuffle_ps(p, p, _MM_SHUFFLE(3, 3, 3, 1)));
  s = _mm_add_ss(s, _mm_shuffle_ps(p, p, _MM_SHUFFLE(3, 3, 3, 2)));
  return _mm_cvtss_f32(s);
}

/* What every thread of a build reads: the references and their boxes,
 * which each task permutes only within its own range. */
typedef struct builder {
  box4 *boxes; /* by reference, in the order of refs */
  uint32_t *refs;
} builder;

/* A node to build: its range of references, its bounds and the bounds of
 * its (doubled) centroids. */
typedef struct task {
  uint32_t node, begin, end;
  int depth;
  box4 bounds, cbounds;
} task;

static void store_bounds(gli_bvh_node *n, box4 b) {
  float lo[4], hi[4];
  _mm_storeu_ps(lo, b.lo);
  _mm_storeu_ps(hi, b.hi);
  memcpy(n->lo, lo, sizeof n->lo);
  memcpy(n->hi, hi, sizeof n->hi);
}

/* Bounds and centroid bounds of [begin, end), for splits not made by bins. */
static void measure(const builder *b, uint32_t begin, uint32_t end,
                    box4 *bounds, box4 *cbounds) {
  *bounds = box4_empty();
  *cbounds = box4_empty();
  for (uint32_t i = begin; i < end; i++) {
    box4_grow(bounds, b->boxes[i]);
    box4_grow_point(cbounds, _mm_add_ps(b->boxes[i].lo, b->boxes[i].hi));
  }
}

static void swap_refs(builder *b, uint32_t i, uint32_t j) {
  uint32_t r = b->refs[i];
  b->refs[i] = b->refs[j];
  b->refs[j] = r;
  box4 t = b->boxes[i];
  b->boxes[i] = b->boxes[j];
  b->boxes[j] = t;
}

/* Splits task t; returns the first index of the right half and fills the
 * halves' bounds, or returns t->begin to keep a leaf. */
static uint32_t split(builder *b, const task *t, int *axis_out, box4 *lb,
                      box4 *lc, box4 *rb, box4 *rc) {
  uint32_t begin = t->begin, end = t->end, n = end - begin;
  /* Small nodes get fewer bins: the per-node cost of clearing and sweeping
   * bins dominates the lower levels, which hold most of the nodes. */
  const int bins = n < 16 ? 4 : n < 64 ? 8 : BINS;
  float clo[4], chi[4], scale[4] = {0, 0, 0, 0};
  _mm_storeu_ps(clo, t->cbounds.lo);
  _mm_storeu_ps(chi, t->cbounds.hi);
  int any_axis = 0;
  for (int k = 0; k < 3; k++) {
    float ext = chi[k] - clo[k];
    scale[k] = ext > 0 ? (float)bins * (1 - 1e-6f) / ext : 0;
    any_axis |= ext > 0;
  }
  uint32_t mid;
  if (!any_axis) { /* every centroid in one point */
    if (n <= MAX_LEAF)
      return begin;
    *axis_out = 0;
    mid = begin + n / 2;
    goto by_count;
  }

  /* One pass bins all three axes. Neighbouring primitives of a mesh often
   * fall in the same bin, and each update would wait for the previous one's
   * store: two sets of bins, for even and odd primitives, merged after,
   * break that chain. */
  box4 bin_box[3][BINS], bin_box2[3][BINS];
  float bin_cost[3][BINS], bin_cost2[3][BINS]; /* sums of prim_cost */
  int dual = n > 256;
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < bins; i++) {
      bin_box[k][i] = bin_box2[k][i] = box4_empty();
      bin_cost[k][i] = bin_cost2[k][i] = 0;
    }
  __m128 vlo = t->cbounds.lo, vscale = _mm_loadu_ps(scale);
  __m128i maxbin = _mm_set1_epi32(bins - 1), zero = _mm_setzero_si128();
  for (uint32_t i = begin; i < end; i++) {
    box4 bx = b->boxes[i];
    __m128 c = _mm_add_ps(bx.lo, bx.hi);
    __m128i bi = _mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(c, vlo), vscale));
    /* clamp to [0, BINS-1] (SSE2 has no integer min/max: compare) */
    bi = _mm_and_si128(bi, _mm_cmpgt_epi32(bi, _mm_set1_epi32(-1)));
    __m128i over = _mm_cmpgt_epi32(bi, maxbin);
    bi = _mm_or_si128(_mm_and_si128(over, maxbin), _mm_andnot_si128(over, bi));
    (void)zero;
    int idx[4];
    _mm_storeu_si128((__m128i *)idx, bi);
    int odd = dual & (int)i;
    box4(*bb)[BINS] = odd ? bin_box2 : bin_box;
    float(*costs)[BINS] = odd ? bin_cost2 : bin_cost;
    float cost = prim_cost[GLI_REF_SHAPE(b->refs[i])];
    for (int k = 0; k < 3; k++) {
      costs[k][idx[k]] += cost;
      box4_grow(&bb[k][idx[k]], bx);
    }
  }
  if (dual)
    for (int k = 0; k < 3; k++)
      for (int i = 0; i < bins; i++) {
        box4_grow(&bin_box[k][i], bin_box2[k][i]);
        bin_cost[k][i] += bin_cost2[k][i];
      }

  float best = FLT_MAX;
  int best_axis = -1, best_bin = 0;
  for (int k = 0; k < 3; k++) {
    if (scale[k] == 0)
      continue;
    /* Right-to-left sweep, then left-to-right evaluating each boundary. */
    float right_area[BINS], right_cost[BINS];
    box4 acc = box4_empty();
    float sum = 0;
    for (int i = bins - 1; i > 0; i--) {
      box4_grow(&acc, bin_box[k][i]);
      sum += bin_cost[k][i];
      right_area[i] = box4_area(acc);
      right_cost[i] = sum;
    }
    acc = box4_empty();
    sum = 0;
    for (int i = 0; i < bins - 1; i++) {
      box4_grow(&acc, bin_box[k][i]);
      sum += bin_cost[k][i];
      if (sum == 0 || right_cost[i + 1] == 0)
        continue;
      float cost = box4_area(acc) * sum + right_area[i + 1] * right_cost[i + 1];
      if (cost < best) {
        best = cost;
        best_axis = k;
        best_bin = i;
      }
    }
  }
  float leaf_cost = 0; /* every primitive is in one bin of axis 0 */
  for (int i = 0; i < bins; i++)
    leaf_cost += bin_cost[0][i];
  float area = box4_area(t->bounds);
  float split_cost = COST_NODE + (area > 0 ? best / area : leaf_cost);
  if (best_axis < 0 || (n <= MAX_LEAF && leaf_cost <= split_cost)) {
    if (n <= MAX_LEAF)
      return begin;
    *axis_out = 0; /* cannot split by bins: halve by count */
    mid = begin + n / 2;
    goto by_count;
  }

  /* Partition by bin; the halves' bounds are the bins' unions, their
   * centroid bounds are gathered on the way. */
  {
    int k = best_axis;
    float lo_k = clo[k], scale_k = scale[k];
    uint32_t i = begin, j = end;
    *lc = box4_empty();
    *rc = box4_empty();
    while (i < j) {
      __m128 c = _mm_add_ps(b->boxes[i].lo, b->boxes[i].hi);
      const float *blo = (const float *)&b->boxes[i].lo;
      const float *bhi = (const float *)&b->boxes[i].hi;
      /* The binning's conversion and clamp exactly (cvtt gives INT_MIN for
       * NaN or out of range, where a C cast would be undefined). */
      int bi = _mm_cvtt_ss2si(_mm_set_ss((blo[k] + bhi[k] - lo_k) * scale_k));
      bi = bi < 0 ? 0 : bi > bins - 1 ? bins - 1 : bi;
      if (bi <= best_bin) {
        box4_grow_point(lc, c);
        i++;
      } else {
        box4_grow_point(rc, c);
        swap_refs(b, i, --j);
      }
    }
    *lb = box4_empty();
    *rb = box4_empty();
    for (int q = 0; q < bins; q++)
      box4_grow(q <= best_bin ? lb : rb, bin_box[k][q]);
    *axis_out = k;
    return i;
  }

by_count:
  measure(b, begin, mid, lb, lc);
  measure(b, mid, end, rb, rc);
  return mid;
}

/* The box4 of a node's box. */
static box4 node_box(const gli_bvh_node *n) {
  return (box4){_mm_setr_ps(n->lo[0], n->lo[1], n->lo[2], 0),
                _mm_setr_ps(n->hi[0], n->hi[1], n->hi[2], 0)};
}

/* Expected node visits and primitive tests of a ray through the tree
 * (every node's area over the root's; leaves count their primitives). */
static double sah_cost(const gli_bvh *bvh) {
  if (bvh->node_count == 0)
    return 0;
  double total = 0;
  for (uint32_t i = 0; i < bvh->node_count; i++) {
    const gli_bvh_node *n = &bvh->nodes[i];
    total += (double)box4_area(node_box(n)) * (n->count ? n->count : 1);
  }
  double area = box4_area(node_box(&bvh->nodes[0]));
  return area > 0 ? total / area : 0;
}

/* The node array starts half a cache line in, so that the sibling pairs
 * that follow the root, (1, 2), (3, 4), ..., each fill one line: a packet
 * tests both children of most nodes it enters, and a pair straddling two
 * lines was two misses (the 200k-triangle dragon's primary rays: the
 * loads of a node's box were the walk's costliest instructions). */
_Static_assert(2 * sizeof(gli_bvh_node) == GLI_ALIGN,
               "a sibling pair of BVH nodes fills one cache line");

static gli_bvh_node *nodes_alloc(size_t count) {
  gli_bvh_node *line_start = gli_aligned_calloc(count + 1, sizeof *line_start);
  return line_start ? line_start + 1 : NULL;
}

static void nodes_free(gli_bvh_node *nodes) {
  if (nodes)
    gli_aligned_free(nodes - 1);
}

/* ---- growing the tree, on one thread or several ------------------------ */

/* Where a node lies while the tree grows. A subtree over references
 * [b, e) rooted at slot s owns the 2(e - b) - 1 slots from s (a binary
 * tree over k leaves-worth of references has at most 2k - 1 nodes): its
 * left subtree, over [b, mid), starts at s + 1, and its right one at
 * s + 2(mid - b). So a node's slot depends on the splits alone, not on
 * which thread made them or when, and threads grow disjoint subtrees (of
 * disjoint ranges of references) with nothing shared but a queue of tasks.
 * An inner node's offset holds its right child's slot while it grows (the
 * left one is the next slot); lay_out then copies the nodes into the order
 * the depth-first build on one thread gives them, children pairs adjacent:
 * the tree, node for node, is the same whatever the threads. */
#define TASK_STACK (4 * GLI_BVH_MAX_DEPTH) /* a thread's own tasks */
/* Right children of this many references or more go to the queue, for
 * any thread to take: the dragon's 202 520 triangles built on 2 threads in
 * 54 ms with 1 024, 57 with 4 096 (one thread: 85). */
#define SHARE_MIN_REFS 1024
/* Fewer references are built on one thread: 16 384 build in about 5 ms,
 * against some 0.1 ms to start a thread. */
#define PARALLEL_MIN_REFS 16384

typedef struct grower {
  builder *b;
  gli_bvh_node *slots;
  int threads;
  task *queue;     /* tasks any thread may take: disjoint ranges of at least */
  uint32_t queued; /* SHARE_MIN_REFS references, so n / that at most */
  int busy;        /* threads growing a task */
  int depth;       /* the deepest level, once every thread has ended */
  uint32_t splits; /* the inner nodes, likewise */
  pthread_mutex_t lock;
  pthread_cond_t more; /* a task queued, or every thread idle */
} grower;

static void share(grower *g, const task *t) {
  pthread_mutex_lock(&g->lock);
  g->queue[g->queued++] = *t;
  pthread_cond_signal(&g->more);
  pthread_mutex_unlock(&g->lock);
}

/* Grows the subtree of task `first` depth first, the left child first,
 * with an explicit stack; *depth: the deepest level seen, *splits counts
 * the inner nodes. */
static void grow(grower *g, task first, task *stack, int *depth,
                 uint32_t *splits) {
  builder *b = g->b;
  int sp = 0;
  stack[sp++] = first;
  while (sp > 0) {
    task t = stack[--sp];
    gli_bvh_node *node = &g->slots[t.node];
    store_bounds(node, t.bounds);
    if (t.depth > *depth)
      *depth = t.depth;
    int axis = 0;
    box4 lb, lc, rb, rc;
    uint32_t mid = t.begin;
    if (t.end - t.begin > 1 && t.depth < GLI_BVH_MAX_DEPTH - 1)
      mid = split(b, &t, &axis, &lb, &lc, &rb, &rc);
    if (mid == t.begin) {
      if (t.end - t.begin > UINT16_MAX) { /* depth exhausted: still split */
        mid = t.begin + (t.end - t.begin) / 2;
        measure(b, t.begin, mid, &lb, &lc);
        measure(b, mid, t.end, &rb, &rc);
      } else {
        node->offset = t.begin;
        node->count = (uint16_t)(t.end - t.begin);
        node->axis = 0;
        continue;
      }
    }
    task right = {
        t.node + 2 * (mid - t.begin), mid, t.end, t.depth + 1, rb, rc};
    node->offset = right.node;
    node->count = 0;
    node->axis = (uint8_t)axis;
    ++*splits;
    if (g->threads > 1 && t.end - mid >= SHARE_MIN_REFS)
      share(g, &right);
    else
      stack[sp++] = right;
    stack[sp++] = (task){t.node + 1, t.begin, mid, t.depth + 1, lb, lc};
  }
}

/* A thread's part: queued tasks until none is queued and none is growing
 * (which could queue more). */
static void grow_queued(grower *g, task *stack) {
  int depth = 0;
  uint32_t splits = 0;
  pthread_mutex_lock(&g->lock);
  for (;;) {
    while (g->queued == 0 && g->busy > 0)
      pthread_cond_wait(&g->more, &g->lock);
    if (g->queued == 0)
      break;
    /* the largest first: a large task taken last kept one thread busy
     * alone at the end (a few dozen are queued at once) */
    uint32_t largest = 0;
    for (uint32_t i = 1; i < g->queued; i++)
      if (g->queue[i].end - g->queue[i].begin >
          g->queue[largest].end - g->queue[largest].begin)
        largest = i;
    task t = g->queue[largest];
    g->queue[largest] = g->queue[--g->queued];
    g->busy++;
    pthread_mutex_unlock(&g->lock);
    grow(g, t, stack, &depth, &splits);
    pthread_mutex_lock(&g->lock);
    if (--g->busy == 0 && g->queued == 0)
      pthread_cond_broadcast(&g->more); /* the end: wake the idle */
  }
  if (depth > g->depth)
    g->depth = depth;
  g->splits += splits;
  pthread_mutex_unlock(&g->lock);
}

typedef struct grow_thread {
  grower *g;
  task stack[TASK_STACK];
} grow_thread;

static void *grow_thread_run(void *arg) {
  grow_thread *w = arg;
  grow_queued(w->g, w->stack);
  return NULL;
}

/* Copies the grown tree from its slots into out in the order of the
 * depth-first build on one thread: each node, as it is taken from the
 * stack, gets its children the next two places. */
static void lay_out(const gli_bvh_node *slots, gli_bvh_node *out) {
  struct {
    uint32_t slot, to;
  } stack[2 * GLI_BVH_MAX_DEPTH + 2];
  int sp = 0;
  uint32_t count = 1;
  stack[sp].slot = 0, stack[sp++].to = 0;
  while (sp > 0) {
    sp--;
    uint32_t slot = stack[sp].slot, to = stack[sp].to;
    gli_bvh_node n = slots[slot];
    if (n.count == 0) {
      uint32_t left = count;
      count += 2;
      stack[sp].slot = n.offset, stack[sp++].to = left + 1;
      stack[sp].slot = slot + 1, stack[sp++].to = left;
      n.offset = left;
    }
    out[to] = n;
  }
}

/* The tree over the n references of b from `root`, grown on up to
 * `threads` threads (the calling one among them): its nodes in their
 * final order into *nodes (*count of them), its depth into *depth; -1 out
 * of memory. */
static int grow_tree(builder *b, task root, uint32_t n, int threads,
                     gli_bvh_node **nodes, uint32_t *count, int *depth) {
  if (threads < 2 || n < PARALLEL_MIN_REFS)
    threads = 1;
  else if ((uint32_t)threads > n / SHARE_MIN_REFS) /* more would idle */
    threads = (int)(n / SHARE_MIN_REFS);
  grower g = {b,
              nodes_alloc(2 * (size_t)n),
              threads,
              malloc((n / SHARE_MIN_REFS + 1) * sizeof(task)),
              0,
              0,
              0,
              0,
              PTHREAD_MUTEX_INITIALIZER,
              PTHREAD_COND_INITIALIZER};
  task *stack = malloc(TASK_STACK * sizeof *stack);
  grow_thread *helpers =
      threads > 1 ? malloc((size_t)(threads - 1) * sizeof *helpers) : NULL;
  pthread_t *ids =
      threads > 1 ? malloc((size_t)(threads - 1) * sizeof *ids) : NULL;
  if (!g.slots || !g.queue || !stack || (threads > 1 && (!helpers || !ids))) {
    nodes_free(g.slots), free(g.queue), free(stack), free(helpers), free(ids);
    return -1;
  }
  g.queue[g.queued++] = root;
  int started = 0;
  for (int i = 0; i < threads - 1; i++) {
    helpers[started].g = &g;
    if (gli_thread_start(&ids[started], grow_thread_run, &helpers[started]) ==
        0)
      started++; /* (one refused: the others, and this thread, do its share) */
  }
  grow_queued(&g, stack);
  for (int i = 0; i < started; i++)
    pthread_join(ids[i], NULL);
  free(g.queue), free(stack), free(helpers), free(ids);
  pthread_mutex_destroy(&g.lock);
  pthread_cond_destroy(&g.more);
  uint32_t used = 1 + 2 * g.splits;
  gli_bvh_node *laid = nodes_alloc(used);
  if (laid)
    lay_out(g.slots, laid);
  nodes_free(g.slots);
  if (!laid)
    return -1;
  *nodes = laid;
  *count = used;
  *depth = g.depth;
  return 0;
}

/* The packets' tree: the binary tree with each subtree cut into one leaf
 * where that is cheaper for packets by the surface area heuristic with a
 * node cost of PACKET_COST_NODE, computed bottom-up (the optimal cut of
 * the given tree, as a collapse by SAH does). The references of a subtree
 * are a contiguous range, so a cut leaf is that range. Only for scenes of
 * GLI_BVH_PACKET_CUT_PRIMS primitives or more: there the triangles outgrow the
 * caches and each node a packet visits is a miss, while the packet tests
 * a leaf's primitives for all its lanes at once; on the 200k-triangle
 * dragon's primary rays (README, "Memory order") the packets ran 5%
 * faster, its shaded renders 5-8% (AVX2 and AVX-512), and the scalar walk,
 * which tests a leaf's primitives one ray at a time, keeps the finer tree (cut
 * for it too, scalar-float renders 7% slower). On the SPD scenes (under 10 000
 * primitives, cache-resident) a cut tree measured within noise of the full one,
 * so they keep one tree. */
#define PACKET_COST_NODE 5.0f

/* What the cut of a subtree knows of it. */
typedef struct subtree {
  float cost;     /* its packet SAH cost, in units of its root's area */
  float prims;    /* the summed prim_cost of its references */
  uint32_t first; /* its references: [first, first + count) */
  uint32_t count;
  uint32_t nodes; /* the nodes of its cut */
} subtree;

/* The packet costs of the subtree at `node`, marking the binary nodes that
 * become packet leaves: cut[] their reference count (0: not cut), first[]
 * their first reference. */
static subtree cut_costs(const gli_bvh *bvh, uint32_t node, uint16_t *cut,
                         uint32_t *first) {
  const gli_bvh_node *n = &bvh->nodes[node];
  subtree st = {0, 0, n->offset, n->count, 1};
  if (n->count) {
    for (uint32_t k = n->offset; k < n->offset + n->count; k++)
      st.prims += prim_cost[GLI_REF_SHAPE(bvh->refs[k])];
    st.cost = st.prims;
    return st;
  }
  subtree l = cut_costs(bvh, n->offset, cut, first);
  subtree r = cut_costs(bvh, n->offset + 1, cut, first);
  float area = box4_area(node_box(n));
  float al = box4_area(node_box(&bvh->nodes[n->offset]));
  float ar = box4_area(node_box(&bvh->nodes[n->offset + 1]));
  /* a refit may have swapped the children: the range starts at either */
  st.first = l.first < r.first ? l.first : r.first;
  st.count = l.count + r.count;
  st.prims = l.prims + r.prims;
  st.nodes = 1 + l.nodes + r.nodes;
  st.cost = PACKET_COST_NODE +
            (area > 0 ? (al * l.cost + ar * r.cost) / area : st.prims);
  if (st.count <= MAX_LEAF && st.prims <= st.cost) {
    cut[node] = (uint16_t)st.count;
    first[node] = st.first;
    st.cost = st.prims;
    st.nodes = 1;
  }
  return st;
}

/* Copies the subtree at binary node `from` into packet node `to`, a cut
 * node as the leaf of its subtree's references. */
static void cut_copy(gli_bvh *bvh, const uint16_t *cut, const uint32_t *first,
                     uint32_t from, uint32_t to) {
  const gli_bvh_node *n = &bvh->nodes[from];
  gli_bvh_node *p = &bvh->packet_nodes[to];
  *p = *n;
  bvh->packet_wide[to] =
      bvh->wide.of_binary ? bvh->wide.of_binary[from] : GLI_WIDE_NONE;
  if (n->count)
    return;
  if (cut[from]) {
    /* never a hand-over point: those hold at least 128 references */
    p->offset = first[from];
    p->count = cut[from];
    p->axis = 0;
    p->flags = 0;
    bvh->packet_wide[to] = GLI_WIDE_NONE;
    return;
  }
  uint32_t left = bvh->packet_node_count;
  bvh->packet_node_count += 2;
  p->offset = left;
  cut_copy(bvh, cut, first, n->offset, left);
  cut_copy(bvh, cut, first, n->offset + 1, left + 1);
}

/* Sets the packets' tree: the binary one itself, or in a large scene its
 * cut (cut_costs); on failure, neither tree. */
static glint_status cut_for_packets(gli_bvh *bvh, glint_error *error) {
  bvh->packet_nodes = bvh->nodes;
  bvh->packet_wide = bvh->wide.of_binary;
  bvh->packet_node_count = bvh->node_count;
  if (bvh->node_count == 0 || bvh->ref_count < GLI_BVH_PACKET_CUT_PRIMS)
    return GLINT_OK;
  uint16_t *cut = calloc(bvh->node_count, sizeof *cut);
  uint32_t *first = malloc(bvh->node_count * sizeof *first);
  gli_bvh_node *nodes = NULL;
  uint32_t *wide = NULL;
  if (cut && first) {
    uint32_t count = cut_costs(bvh, 0, cut, first).nodes;
    nodes = nodes_alloc(count);
    wide = malloc(count * sizeof *wide);
  }
  if (nodes && wide) {
    bvh->packet_nodes = nodes;
    bvh->packet_wide = wide;
    bvh->packet_node_count = 1;
    cut_copy(bvh, cut, first, 0, 0);
  }
  free(cut);
  free(first);
  if (!nodes || !wide) {
    nodes_free(nodes);
    free(wide);
    gli_bvh_free(bvh);
    return gli_fail(error, GLINT_E_MEMORY,
                    "out of memory cutting the BVH for packets");
  }
  return GLINT_OK;
}

/* The trees derived from a finished binary BVH: the wide one, where
 * packets may hand subtrees over to it (else only --accel bvh8 walks it,
 * and gli_bvh_add_wide collapses it then: on the 200k-triangle dragon the
 * collapse was 70 ms of a 660 ms glint render, every animation frame
 * collapsed its refitted tree again, and no walk read it), and the
 * packets'; on failure, none. */
static glint_status derive_trees(gli_bvh *bvh, const glint_scene *scene,
                                 glint_error *error) {
  glint_status st = gli_wide_may_hand_over(bvh->spheres, bvh->cones)
                        ? gli_wide_build(bvh, scene, 1, &bvh->wide, error)
                        : GLINT_OK;
  if (st) {
    gli_bvh_free(bvh);
    return st;
  }
  return cut_for_packets(bvh, error);
}

glint_status gli_bvh_add_wide(gli_bvh *bvh, const glint_scene *scene,
                              glint_error *error) {
  if (bvh->node_count == 0 || bvh->wide.nodes)
    return GLINT_OK;
  /* (no hand-over points to mark: derive_trees would have collapsed it) */
  return gli_wide_build(bvh, scene, 0, &bvh->wide, error);
}

glint_status gli_bvh_build(const glint_scene *scene, int threads, gli_bvh *bvh,
                           glint_error *error) {
  double t0 = gli_now();
  memset(bvh, 0, sizeof *bvh);
  bvh->spheres = scene->sphere_count;
  bvh->triangles = scene->triangle_count;
  bvh->cones = scene->cone_count;
  size_t n = scene->sphere_count + scene->triangle_count + scene->cone_count;
  /* A hierarchy over a handful of primitives costs more in box tests than
   * it saves (Billiard's ten spheres: 0.284 s against 0.247 s tested
   * directly, scalar-float, depth 5): below this size none is built. */
  if (n <= GLI_BVH_MIN_PRIMS)
    return GLINT_OK;
  if (n > GLI_MAX_BVH_PRIMS)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "too many primitives for the BVH (%zu)", n);
  builder b = {0};
  b.boxes = gli_aligned_calloc(n, sizeof *b.boxes);
  b.refs = malloc(n * sizeof *b.refs);
  if (!b.boxes || !b.refs) {
    gli_aligned_free(b.boxes);
    free(b.refs);
    return gli_fail(error, GLINT_E_MEMORY,
                    "out of memory building the BVH of %zu primitives", n);
  }
  size_t r = 0;
  box bx;
  for (size_t i = 0; i < scene->sphere_count; i++, r++) {
    b.refs[r] = GLI_REF(GLI_SHAPE_SPHERE, i);
    bx = sphere_box(&scene->spheres[i]);
    b.boxes[r] = (box4){_mm_setr_ps(bx.lo[0], bx.lo[1], bx.lo[2], 0),
                        _mm_setr_ps(bx.hi[0], bx.hi[1], bx.hi[2], 0)};
  }
  for (size_t i = 0; i < scene->triangle_count; i++, r++) {
    b.refs[r] = GLI_REF(GLI_SHAPE_TRIANGLE, i);
    bx = triangle_box(&scene->triangles[i]);
    b.boxes[r] = (box4){_mm_setr_ps(bx.lo[0], bx.lo[1], bx.lo[2], 0),
                        _mm_setr_ps(bx.hi[0], bx.hi[1], bx.hi[2], 0)};
  }
  for (size_t i = 0; i < scene->cone_count; i++, r++) {
    b.refs[r] = GLI_REF(GLI_SHAPE_CONE, i);
    bx = cone_box(&scene->cones[i]);
    b.boxes[r] = (box4){_mm_setr_ps(bx.lo[0], bx.lo[1], bx.lo[2], 0),
                        _mm_setr_ps(bx.hi[0], bx.hi[1], bx.hi[2], 0)};
  }

  task root = {0, 0, (uint32_t)n, 1, box4_empty(), box4_empty()};
  measure(&b, 0, (uint32_t)n, &root.bounds, &root.cbounds);
  int failed = grow_tree(&b, root, (uint32_t)n, threads, &bvh->nodes,
                         &bvh->node_count, &bvh->depth);
  gli_aligned_free(b.boxes);
  if (failed) {
    free(b.refs);
    return gli_fail(error, GLINT_E_MEMORY,
                    "out of memory building the BVH of %zu primitives", n);
  }
  bvh->refs = b.refs;
  bvh->ref_count = (uint32_t)n;
  bvh->cost = bvh->built_cost = sah_cost(bvh);
  bvh->build_seconds = gli_now() - t0;
  return derive_trees(bvh, scene, error);
}

/* The box of reference r in the scene as it is now. */
static box ref_box(const glint_scene *scene, uint32_t r) {
  uint32_t i = GLI_REF_INDEX(r);
  switch (GLI_REF_SHAPE(r)) {
  case GLI_SHAPE_SPHERE: return sphere_box(&scene->spheres[i]);
  case GLI_SHAPE_TRIANGLE: return triangle_box(&scene->triangles[i]);
  default: return cone_box(&scene->cones[i]);
  }
}

void gli_bvh_ref_box(const glint_scene *scene, uint32_t ref, float lo[3],
                     float hi[3]) {
  box b = ref_box(scene, ref);
  memcpy(lo, b.lo, sizeof b.lo);
  memcpy(hi, b.hi, sizeof b.hi);
}

glint_status gli_bvh_refit(const gli_bvh *from, const glint_scene *scene,
                           gli_bvh *bvh, glint_error *error) {
  double t0 = gli_now();
  memset(bvh, 0, sizeof *bvh);
  if (from->spheres != scene->sphere_count ||
      from->triangles != scene->triangle_count ||
      from->cones != scene->cone_count)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "a BVH refits only the primitives it was built over");
  bvh->spheres = from->spheres;
  bvh->triangles = from->triangles;
  bvh->cones = from->cones;
  if (from->node_count == 0)
    return GLINT_OK; /* no hierarchy: nothing to refit */
  bvh->nodes = nodes_alloc(from->node_count);
  bvh->refs = malloc(from->ref_count * sizeof *bvh->refs);
  if (!bvh->nodes || !bvh->refs) {
    gli_bvh_free(bvh);
    return gli_fail(error, GLINT_E_MEMORY, "out of memory refitting the BVH");
  }
  memcpy(bvh->refs, from->refs, from->ref_count * sizeof *bvh->refs);
  memcpy(bvh->nodes, from->nodes, from->node_count * sizeof *bvh->nodes);
  bvh->node_count = from->node_count;
  bvh->ref_count = from->ref_count;
  bvh->depth = from->depth;
  /* Children come after their parent (the builder appends them), so one
   * backward pass sees every child before its parent. */
  for (uint32_t i = bvh->node_count; i-- > 0;) {
    gli_bvh_node *n = &bvh->nodes[i];
    box4 b = box4_empty();
    if (n->count) {
      for (uint32_t k = n->offset; k < n->offset + n->count; k++) {
        box bx = ref_box(scene, bvh->refs[k]);
        box4_grow(&b, (box4){_mm_setr_ps(bx.lo[0], bx.lo[1], bx.lo[2], 0),
                             _mm_setr_ps(bx.hi[0], bx.hi[1], bx.hi[2], 0)});
      }
    } else {
      /* Packets visit the child on their side of the split axis first
       * (accel/packet_traverse.h), the left one being lower along it: the
       * objects have turned, so the axis becomes the one that separates
       * the children's centres most now, and the lower child goes left
       * (a node's subtree is found by its offset, so two siblings swap). */
      gli_bvh_node *l = &bvh->nodes[n->offset], *r = l + 1;
      float best = -1, gap = 0;
      for (int k = 0; k < 3; k++) {
        float d = (r->lo[k] + r->hi[k]) - (l->lo[k] + l->hi[k]);
        if (fabsf(d) > best)
          best = fabsf(d), gap = d, n->axis = (uint8_t)k;
      }
      if (gap < 0) {
        gli_bvh_node t = *l;
        *l = *r;
        *r = t;
      }
      for (uint32_t c = n->offset; c < n->offset + 2; c++)
        box4_grow(&b, node_box(&bvh->nodes[c]));
    }
    store_bounds(n, b);
  }
  bvh->cost = sah_cost(bvh);
  bvh->built_cost = from->built_cost;
  bvh->build_seconds = gli_now() - t0;
  return derive_trees(bvh, scene, error);
}

void gli_bvh_free(gli_bvh *bvh) {
  if (bvh->packet_nodes != bvh->nodes)
    nodes_free(bvh->packet_nodes);
  if (bvh->packet_wide != bvh->wide.of_binary)
    free(bvh->packet_wide);
  gli_wide_free(&bvh->wide);
  nodes_free(bvh->nodes);
  free(bvh->refs);
  memset(bvh, 0, sizeof *bvh);
}

uint64_t gli_bvh_bytes(const gli_bvh *bvh) {
  uint64_t packets = bvh->packet_nodes != bvh->nodes
                         ? (uint64_t)bvh->packet_node_count *
                               (sizeof(gli_bvh_node) + sizeof *bvh->packet_wide)
                         : 0;
  return (uint64_t)bvh->node_count * sizeof(gli_bvh_node) +
         (uint64_t)bvh->ref_count * sizeof(uint32_t) + packets;
}
