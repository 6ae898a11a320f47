/* Triangulating planar polygons (NFF p and pp, OBJ faces). NFF promises
 * convex polygons, but the SPD's own gears have 144-vertex faces with teeth:
 * a fan from the first vertex would cover the gaps between the teeth, and
 * its long slivers overlap in every BVH node. So:
 *   - triangles as they are, convex quadrilaterals as a fan;
 *   - a polygon star-shaped around its centroid: a fan from the centroid
 *     (short wedges, and exact);
 *   - anything else: ear clipping (Meisters 1975), in the polygon's plane.
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
static glint_vec3 newell(const glint_vec3 *v, size_t n) {
  glint_vec3 nrm = {0, 0, 0};
  for (size_t i = 0; i < n; i++) {
    glint_vec3 a = v[i], b = v[(i + 1) % n];
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

/* p strictly inside triangle abc (all seen along nrm). */
static int inside(glint_vec3 p, glint_vec3 a, glint_vec3 b, glint_vec3 c,
                  glint_vec3 nrm) {
  return dot(cross(sub(b, a), sub(p, a)), nrm) > 0 &&
         dot(cross(sub(c, b), sub(p, b)), nrm) > 0 &&
         dot(cross(sub(a, c), sub(p, c)), nrm) > 0;
}

int glint_triangulate(const glint_vec3 *v, size_t n, glint_vec3 *centroid,
                      glint_polygon_emit emit, void *user) {
  if (n < 3)
    return -1;
  if (n == 3)
    return emit(user, 0, 1, 2);
  glint_vec3 nrm = newell(v, n);
  int convex = 1;
  for (size_t i = 0; i < n && convex; i++)
    convex = turns_left(v[i], v[(i + 1) % n], v[(i + 2) % n], nrm);
  if (n == 4 && convex)
    return emit(user, 0, 1, 2) || emit(user, 0, 2, 3);

  /* Star-shaped around the centroid? Then wedges from it. */
  glint_vec3 c = {0, 0, 0};
  for (size_t i = 0; i < n; i++)
    c.x += v[i].x, c.y += v[i].y, c.z += v[i].z;
  c.x /= (double)n, c.y /= (double)n, c.z /= (double)n;
  *centroid = c;
  int star = 1;
  for (size_t i = 0; i < n && star; i++)
    star = dot(cross(sub(v[i], c), sub(v[(i + 1) % n], c)), nrm) > 0;
  if (star) {
    for (size_t i = 0; i < n; i++) {
      int r = emit(user, GLINT_POLYGON_CENTROID, i, (i + 1) % n);
      if (r)
        return r;
    }
    return 0;
  }

  /* Ear clipping: a vertex whose corner turns the polygon's way and whose
   * triangle holds no other vertex is cut off, until three remain. */
  size_t *idx = malloc(n * sizeof *idx);
  if (!idx)
    return -1;
  for (size_t i = 0; i < n; i++)
    idx[i] = i;
  size_t m = n, guard = 0, i = 0;
  while (m > 3) {
    size_t a = idx[(i + m - 1) % m], b = idx[i % m], cc = idx[(i + 1) % m];
    int ear = turns_left(v[a], v[b], v[cc], nrm);
    for (size_t k = 0; ear && k < m; k++) {
      size_t p = idx[k];
      if (p != a && p != b && p != cc && inside(v[p], v[a], v[b], v[cc], nrm))
        ear = 0;
    }
    if (ear) {
      int r = emit(user, a, b, cc);
      if (r) {
        free(idx);
        return r;
      }
      memmove(idx + i % m, idx + i % m + 1, (m - i % m - 1) * sizeof *idx);
      m--;
      guard = 0;
    } else {
      i++;
      if (++guard > m) { /* degenerate (collinear or self-crossing): fan */
        int r = 0;
        for (size_t k = 1; k + 1 < m && !r; k++)
          r = emit(user, idx[0], idx[k], idx[k + 1]);
        free(idx);
        return r;
      }
    }
  }
  int r = emit(user, idx[0], idx[1], idx[2]);
  free(idx);
  return r;
}
