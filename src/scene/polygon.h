/* Triangulation of planar polygons; see polygon.c. */
#ifndef GLINT_SCENE_POLYGON_H
#define GLINT_SCENE_POLYGON_H

#include "glint.h"

#include <stddef.h>

/* Called once per triangle with three vertex indices; a non-zero return
 * stops and is returned. */
typedef int (*gli_polygon_emit)(void *user, size_t a, size_t b, size_t c);

/* 1 if no corner of the polygon v[0..n) turns against its (Newell) normal:
 * a fan from any corner then covers it exactly. Straight corners count as
 * convex. */
int gli_polygon_is_convex(const glint_vec3 *v, size_t n);

#define GLI_TRIANGULATE_NO_MEMORY (-1) /* or n < 3 */
#define GLI_TRIANGULATE_TOO_COMPLEX (-2)

/* The work ear clipping may do for all the polygons of one scene, in
 * point-in-triangle tests: about two seconds. Per scene, not per polygon:
 * a file repeating a polygon just under a per-polygon limit would load for
 * minutes. Only polygons with thousands of inward corners spend it. */
#define GLI_SCENE_EAR_TESTS ((size_t)1 << 28)
#define GLI_EAR_LIMIT_TEXT                                                     \
  "the concave polygons of a scene get 2^28 ear-clipping tests in all"

/* Triangulates the n >= 3 vertices v (in order around the polygon), keeping
 * their orientation, spending point-in-triangle tests from *tests_left.
 * Returns 0, an emit's non-zero result, GLI_TRIANGULATE_NO_MEMORY, or
 * GLI_TRIANGULATE_TOO_COMPLEX when ear clipping would take more tests than
 * are left (a polygon with tens of thousands of inward corners, or many
 * with thousands) rather than hang. */
int gli_triangulate(const glint_vec3 *v, size_t n, gli_polygon_emit emit,
                    void *user, size_t *tests_left);

#endif
