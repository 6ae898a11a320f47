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

/* Triangulates the n >= 3 vertices v (in order around the polygon), keeping
 * their orientation. Returns 0, an emit's non-zero result,
 * GLI_TRIANGULATE_NO_MEMORY, or GLI_TRIANGULATE_TOO_COMPLEX when ear
 * clipping would take more than about 2^27 point-in-triangle tests (a
 * polygon with tens of thousands of inward corners) rather than hang. */
int gli_triangulate(const glint_vec3 *v, size_t n, gli_polygon_emit emit,
                    void *user);

#endif
