/* Triangulating planar polygons (NFF p and pp, OBJ faces). NFF promises
 * convex polygons, but the SPD's own gears have 144-vertex faces with teeth:
 * a fan from the first vertex would cover the gaps between the teeth. And
 * the shape of the triangles matters to the BVH: long slivers all crossing
 * the middle of a face overlap in every node a ray there visits. So:
 *   - triangles as they are, convex quadrilaterals as a fan;
 *   - a convex polygon: recursive bisection (cut by the diagonal from its
 *     first vertex to the middle one, then each half the same way), which
 *     leaves small triangles along the rim and only logarithmically many
 *     large ones inside;
 *   - anything else: ear clipping (Meisters 1975) in the polygon's plane
 *     until what remains is convex (for a gear: its teeth come off as small
 *     ears), then bisection.
 * Triangles keep the polygon's orientation (counter-clockwise = front). */
#include "scene/polygon.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static glint_vec3 sub(glint_vec3 a, glint_vec3 b) {
  return (glint_vec3){a.x - b.x, a.y - b.y, a.z - b.z};
}
static glint_vec3 cross(glint_vec3 a, glint_vec3 b) {
  return (glint_vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                      a.x * b.y - a.y * b.x};
}
static double dot(glint_vec3 a, glint_vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

/* Newell's method: the polygon's area-weighted normal, robust for any
 * planar (even concave) polygon. Its vertices are v[idx[i]], or v[i] when
 * idx is NULL. */
static glint_vec3 newell(const glint_vec3 *v, const size_t *idx, size_t n) {
  glint_vec3 nrm = {0, 0, 0};
  for (size_t i = 0; i < n; i++) {
    size_t j = (i + 1) % n;
    glint_vec3 a = v[idx ? idx[i] : i], b = v[idx ? idx[j] : j];
    nrm.x += (a.y - b.y) * (a.z + b.z);
    nrm.y += (a.z - b.z) * (a.x + b.x);
    nrm.z += (a.x - b.x) * (a.y + b.y);
  }
  return nrm;
}

static int turns_left(glint_vec3 a, glint_vec3 b, glint_vec3 c,
                      glint_vec3 nrm) {
  return dot(cross(sub(b, a), sub(c, b)), nrm) > 0;
}

static int same_point(glint_vec3 p, glint_vec3 q) {
  return p.x == q.x && p.y == q.y && p.z == q.z;
}

/* p inside triangle abc or on its edges (all seen along nrm), p not one of
 * its corners. An inward corner on the cut a-c blocks the ear too: cutting
 * there would leave a polygon that touches itself, and the next ear could
 * then span the gap (a comb whose teeth stand on one line). */
static int blocks(glint_vec3 p, glint_vec3 a, glint_vec3 b, glint_vec3 c,
                  glint_vec3 nrm) {
  if (same_point(p, a) || same_point(p, b) || same_point(p, c))
    return 0;
  return dot(cross(sub(b, a), sub(p, a)), nrm) >= 0 &&
         dot(cross(sub(c, b), sub(p, b)), nrm) >= 0 &&
         dot(cross(sub(a, c), sub(p, c)), nrm) >= 0;
}

/* A convex polygon idx[0..n): cut by the diagonal idx[0]-idx[n/2] and each
 * half the same way (depth log n). */
static int bisect(const size_t *idx, size_t n, size_t *tmp,
                  gli_polygon_emit emit, void *user) {
  if (n == 3)
    return emit(user, idx[0], idx[1], idx[2]);
  size_t k = n / 2;
  int r = bisect(idx, k + 1, tmp, emit, user); /* idx[0..k] */
  if (r)
    return r;
  /* idx[k..n) and idx[0] */
  memcpy(tmp, idx + k, (n - k) * sizeof *tmp);
  tmp[n - k] = idx[0];
  return bisect(tmp, n - k + 1, tmp + n - k + 1, emit, user);
}

/* The inward corners in cells of the polygon's plane, so that an ear's
 * test reads those near its triangle rather than all of them (a gear's
 * 144 corners, half of them inward, spent 18% of gears-s4's whole process
 * in the tests). Each corner is in the cell of its projection (x, y) onto
 * the plane, in a grid of side x cells over the polygon's box; a corner is
 * put in when it first turns inward and stays (the test skips those no
 * longer inward), so the grid answers exactly what the list does. */
typedef struct corner_grid {
  double *x, *y; /* each vertex's coordinates in the plane */
  double x0, y0, cell_x, cell_y, margin;
  size_t side, *head, *chain; /* cell lists: head[cell], chain[vertex] */
  unsigned char *in;          /* the vertex is in its cell's list */
} corner_grid;

#define NO_CORNER ((size_t)-1)

typedef struct ring {
  const glint_vec3 *v;
  glint_vec3 nrm;
  size_t *prev, *next;
  unsigned char *reflex;       /* the corner does not turn the polygon's way */
  size_t *rlist, rlen, rcount; /* reflex vertices (rlen entries, rcount live) */
  corner_grid *grid;           /* NULL: the list alone */
} ring;

static size_t grid_cell(const corner_grid *c, double x, double y, size_t *cx,
                        size_t *cy) {
  double fx = (x - c->x0) / c->cell_x, fy = (y - c->y0) / c->cell_y;
  double last = (double)(c->side - 1);
  *cx = (size_t)(fx > 0 ? (fx < last ? fx : last) : 0);
  *cy = (size_t)(fy > 0 ? (fy < last ? fy : last) : 0);
  return *cy * c->side + *cx;
}

static void grid_add(corner_grid *c, size_t i) {
  if (!c || c->in[i])
    return;
  size_t cx, cy, cell = grid_cell(c, c->x[i], c->y[i], &cx, &cy);
  c->chain[i] = c->head[cell];
  c->head[cell] = i;
  c->in[i] = 1;
}

static void grid_free(corner_grid *c) {
  if (!c)
    return;
  free(c->x), free(c->head), free(c->chain), free(c->in);
  free(c);
}

/* The grid of the n vertices v, seen along nrm, for `inward` inward
 * corners; NULL where a list is as quick (a few inward corners), where
 * memory runs out, or where the plane is not defined (a zero normal). */
static corner_grid *grid_make(const glint_vec3 *v, size_t n, glint_vec3 nrm,
                              size_t inward) {
#ifdef GLI_POLYGON_NO_GRID /* tests/polygon_reference.c: the list alone */
  return NULL;
#endif
  double len = sqrt(dot(nrm, nrm));
  if (inward < 32 || !(len > 0) || !isfinite(len))
    return NULL;
  glint_vec3 k = {nrm.x / len, nrm.y / len, nrm.z / len};
  /* u: k crossed with the axis it is least along; w = k x u */
  glint_vec3 axis = fabs(k.x) <= fabs(k.y) && fabs(k.x) <= fabs(k.z)
                        ? (glint_vec3){1, 0, 0}
                    : fabs(k.y) <= fabs(k.z) ? (glint_vec3){0, 1, 0}
                                             : (glint_vec3){0, 0, 1};
  glint_vec3 u = cross(k, axis);
  double ul = sqrt(dot(u, u));
  u = (glint_vec3){u.x / ul, u.y / ul, u.z / ul};
  glint_vec3 w = cross(k, u);
  corner_grid *c = calloc(1, sizeof *c);
  size_t side = 1;
  while (side * side < inward && side < 256)
    side++;
  if (c) {
    c->x = malloc(2 * n * sizeof *c->x);
    c->head = malloc(side * side * sizeof *c->head);
    c->chain = malloc(n * sizeof *c->chain);
    c->in = calloc(n, 1);
  }
  if (!c || !c->x || !c->head || !c->chain || !c->in) {
    grid_free(c);
    return NULL;
  }
  c->y = c->x + n;
  double x1 = -INFINITY, y1 = -INFINITY, reach = 0;
  c->x0 = c->y0 = INFINITY;
  for (size_t i = 0; i < n; i++) {
    c->x[i] = dot(v[i], u), c->y[i] = dot(v[i], w);
    c->x0 = fmin(c->x0, c->x[i]), x1 = fmax(x1, c->x[i]);
    c->y0 = fmin(c->y0, c->y[i]), y1 = fmax(y1, c->y[i]);
    reach = fmax(reach, fmax(fabs(v[i].x), fmax(fabs(v[i].y), fabs(v[i].z))));
  }
  if (!isfinite(x1 - c->x0) || !isfinite(y1 - c->y0)) {
    grid_free(c);
    return NULL;
  }
  c->side = side;
  c->cell_x = (x1 - c->x0) / (double)side;
  c->cell_y = (y1 - c->y0) / (double)side;
  if (!(c->cell_x > 0))
    c->cell_x = 1;
  if (!(c->cell_y > 0))
    c->cell_y = 1;
  /* the projections' rounding, far beyond it: a corner the test finds in
   * a triangle (to the last bit of its own arithmetic) is never outside
   * the triangle's box widened so */
  c->margin = 1e-9 * reach;
  for (size_t i = 0; i < side * side; i++)
    c->head[i] = NO_CORNER;
  return c;
}

static int corner_reflex(const ring *g, size_t i) {
  return !turns_left(g->v[g->prev[i]], g->v[i], g->v[g->next[i]], g->nrm);
}

/* A corner's neighbour was cut off: its turn is measured again. (For a
 * simple polygon an inward corner can only become convex; a corner that
 * rounding makes inward is listed again.) */
static void update_corner(ring *g, size_t i) {
  int now = corner_reflex(g, i);
  if (now && !g->reflex[i]) {
    g->rcount++;
    g->rlist[g->rlen++] = i;
    grid_add(g->grid, i);
  } else if (!now && g->reflex[i]) {
    g->rcount--;
  }
  g->reflex[i] = (unsigned char)now;
}

/* No corner turns against nrm (corners that do not turn at all allowed). */
static int convex_about(const glint_vec3 *v, size_t n, glint_vec3 nrm) {
  for (size_t i = 0; i < n; i++) {
    glint_vec3 a = v[i], b = v[(i + 1) % n], c = v[(i + 2) % n];
    if (dot(cross(sub(b, a), sub(c, b)), nrm) < 0)
      return 0;
  }
  return 1;
}

int gli_polygon_is_convex(const glint_vec3 *v, size_t n) {
  return convex_about(v, n, newell(v, NULL, n));
}

/* The remaining vertex that came first in the polygon: what is left is
 * bisected (or fanned) from there. */
static size_t first_vertex(const ring *g, size_t b, size_t m) {
  size_t first = b;
  for (size_t k = 0, i = b; k < m; k++, i = g->next[i])
    if (i < first)
      first = i;
  return first;
}

/* Whether an inward corner blocks the ear a-b-c (as the list's test
 * finds): those in the cells its triangle's box, widened, overlaps. */
static int grid_blocks(const ring *g, size_t a, size_t b, size_t c) {
  const corner_grid *q = g->grid;
  double m = q->margin;
  double lx = fmin(q->x[a], fmin(q->x[b], q->x[c])) - m;
  double hx = fmax(q->x[a], fmax(q->x[b], q->x[c])) + m;
  double ly = fmin(q->y[a], fmin(q->y[b], q->y[c])) - m;
  double hy = fmax(q->y[a], fmax(q->y[b], q->y[c])) + m;
  size_t x0, y0, x1, y1;
  grid_cell(q, lx, ly, &x0, &y0);
  grid_cell(q, hx, hy, &x1, &y1);
  for (size_t cy = y0; cy <= y1; cy++)
    for (size_t cx = x0; cx <= x1; cx++)
      for (size_t p = q->head[cy * q->side + cx]; p != NO_CORNER;
           p = q->chain[p])
        if (g->reflex[p] && p != a && p != c && q->x[p] >= lx &&
            q->x[p] <= hx && q->y[p] >= ly && q->y[p] <= hy &&
            blocks(g->v[p], g->v[a], g->v[b], g->v[c], g->nrm))
          return 1;
  return 0;
}

int gli_triangulate(const glint_vec3 *v, size_t n, gli_polygon_emit emit,
                    void *user, size_t *tests_left) {
  if (n < 3)
    return GLI_TRIANGULATE_NO_MEMORY;
  if (n == 3)
    return emit(user, 0, 1, 2);
  /* idx: the convex rest in order; tmp: bisection's scratch (each level
   * needs at most n/2 + 2 more, 2n in all); prev/next: the remaining
   * polygon as a ring; rlist: room for the n corners and two re-listings
   * per ear cut. */
  size_t *idx = malloc((8 * n + 2) * sizeof *idx);
  unsigned char *reflex = malloc(n);
  if (!idx || !reflex) {
    free(idx);
    free(reflex);
    return GLI_TRIANGULATE_NO_MEMORY;
  }
  size_t *tmp = idx + n;
  ring g = {v,
            {0, 0, 0},
            tmp + 2 * n + 2,
            tmp + 3 * n + 2,
            reflex,
            tmp + 4 * n + 2,
            0,
            0,
            NULL};
  for (size_t i = 0; i < n; i++) {
    idx[i] = i;
    g.prev[i] = i ? i - 1 : n - 1;
    g.next[i] = i + 1 < n ? i + 1 : 0;
  }
  g.nrm = newell(v, idx, n);
  /* Convex but for corners that do not turn at all (vertices along an
   * edge, each an inward corner to corner_reflex): bisected at once. Ear
   * clipping, as for a polygon with teeth, ran out of tests on a square of
   * 40 000 such vertices. */
  int convex = convex_about(v, n, g.nrm);
  for (size_t i = 0; i < n; i++) {
    reflex[i] = (unsigned char)(!convex && corner_reflex(&g, i));
    if (reflex[i])
      g.rlist[g.rlen++] = i, g.rcount++;
  }
  if ((g.grid = grid_make(v, n, g.nrm, g.rcount)))
    for (size_t k = 0; k < g.rlen; k++)
      grid_add(g.grid, g.rlist[k]);

  int r = 0;
  size_t m = n, b = 0, misses = 0, tests = 0;
  for (;;) {
    if (m == 3 || g.rcount == 0) { /* convex: bisection */
      b = first_vertex(&g, b, m);
      for (size_t k = 0, i = b; k < m; k++, i = g.next[i])
        idx[k] = i;
      if (m != 4)
        r = bisect(idx, m, tmp, emit, user);
      else if (!(r = emit(user, idx[0], idx[1], idx[2]))) /* (its status) */
        r = emit(user, idx[0], idx[2], idx[3]);
      break;
    }
    /* Ear clipping: a corner that turns the polygon's way and whose triangle
     * holds no other vertex is cut off. Only inward corners need testing: if
     * any vertex is inside the triangle, one of them is (Meisters 1975). */
    size_t a = g.prev[b], c = g.next[b];
    int ear = !reflex[b];
    if (ear) {
      if (g.rlen > 2 * g.rcount + 16) { /* drop entries no longer inward */
        size_t live = 0;
        for (size_t k = 0; k < g.rlen; k++)
          if (reflex[g.rlist[k]])
            g.rlist[live++] = g.rlist[k];
        g.rlen = live;
      }
      tests += g.rlen; /* the list's count, read from the grid or not */
      if (g.grid)
        ear = !grid_blocks(&g, a, b, c);
      for (size_t k = 0; !g.grid && ear && k < g.rlen; k++) {
        size_t p = g.rlist[k];
        if (reflex[p] && p != a && p != c &&
            blocks(v[p], v[a], v[b], v[c], g.nrm))
          ear = 0;
      }
    }
    if (ear) {
      if ((r = emit(user, a, b, c)))
        break;
      g.next[a] = c;
      g.prev[c] = a;
      m--;
      update_corner(&g, a);
      update_corner(&g, c);
      b = c;
      misses = 0;
    } else {
      b = c;
      if (++misses > m) { /* degenerate (collinear or self-crossing): fan */
        b = first_vertex(&g, b, m);
        for (size_t k = 0, i = g.next[b]; k + 2 < m && !r; k++, i = g.next[i])
          r = emit(user, b, i, g.next[i]);
        break;
      }
    }
    if (tests > *tests_left) { /* only inward corners are tested */
      r = GLI_TRIANGULATE_TOO_COMPLEX;
      break;
    }
  }
  *tests_left -= tests < *tests_left ? tests : *tests_left;
  grid_free(g.grid);
  free(idx);
  free(reflex);
  return r;
}
