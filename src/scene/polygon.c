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
 * planar (even concave) polygon. */
static glint_vec3 newell(const glint_vec3 *v, const size_t *idx, size_t n) {
  glint_vec3 nrm = {0, 0, 0};
  for (size_t i = 0; i < n; i++) {
    glint_vec3 a = v[idx[i]], b = v[idx[(i + 1) % n]];
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

static int is_convex(const glint_vec3 *v, const size_t *idx, size_t n,
                     glint_vec3 nrm) {
  for (size_t i = 0; i < n; i++)
    if (!turns_left(v[idx[i]], v[idx[(i + 1) % n]], v[idx[(i + 2) % n]], nrm))
      return 0;
  return 1;
}

/* p strictly inside triangle abc (all seen along nrm). */
static int inside(glint_vec3 p, glint_vec3 a, glint_vec3 b, glint_vec3 c,
                  glint_vec3 nrm) {
  return dot(cross(sub(b, a), sub(p, a)), nrm) > 0 &&
         dot(cross(sub(c, b), sub(p, b)), nrm) > 0 &&
         dot(cross(sub(a, c), sub(p, c)), nrm) > 0;
}

/* A convex polygon idx[0..n): cut by the diagonal idx[0]-idx[n/2] and each
 * half the same way (depth log n). */
static int bisect(const size_t *idx, size_t n, size_t *tmp,
                  glint_polygon_emit emit, void *user) {
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

int glint_triangulate(const glint_vec3 *v, size_t n, glint_polygon_emit emit,
                      void *user) {
  if (n < 3)
    return -1;
  if (n == 3)
    return emit(user, 0, 1, 2);
  /* idx: the polygon's remaining vertices; tmp: bisection's scratch (each
   * level needs at most n/2 + 2 more, 2n in all). */
  size_t *idx = malloc(3 * n * sizeof *idx + 2 * sizeof *idx);
  if (!idx)
    return -1;
  size_t *tmp = idx + n;
  for (size_t i = 0; i < n; i++)
    idx[i] = i;
  glint_vec3 nrm = newell(v, idx, n);
  int r = 0;
  size_t m = n, guard = 0, i = 0;
  while (!r) {
    if (m == 3 || is_convex(v, idx, m, nrm)) {
      r = m == 4 ? emit(user, idx[0], idx[1], idx[2]) ||
                       emit(user, idx[0], idx[2], idx[3])
                 : bisect(idx, m, tmp, emit, user);
      break;
    }
    /* Ear clipping: a vertex whose corner turns the polygon's way and whose
     * triangle holds no other vertex is cut off. */
    size_t a = idx[(i + m - 1) % m], b = idx[i % m], c = idx[(i + 1) % m];
    int ear = turns_left(v[a], v[b], v[c], nrm);
    for (size_t k = 0; ear && k < m; k++) {
      size_t p = idx[k];
      if (p != a && p != b && p != c && inside(v[p], v[a], v[b], v[c], nrm))
        ear = 0;
    }
    if (ear) {
      r = emit(user, a, b, c);
      memmove(idx + i % m, idx + i % m + 1, (m - i % m - 1) * sizeof *idx);
      m--;
      guard = 0;
    } else {
      i++;
      if (++guard > m) { /* degenerate (collinear or self-crossing): fan */
        for (size_t k = 1; k + 1 < m && !r; k++)
          r = emit(user, idx[0], idx[k], idx[k + 1]);
        break;
      }
    }
  }
  free(idx);
  return r;
}
