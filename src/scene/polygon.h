/* Triangulation of planar polygons; see polygon.c. */
#ifndef GLINT_SCENE_POLYGON_H
#define GLINT_SCENE_POLYGON_H

#include "glint.h"

#include <stddef.h>

/* Called once per triangle with three vertex indices; a non-zero return
 * stops and is returned. */
typedef int (*glint_polygon_emit)(void *user, size_t a, size_t b, size_t c);

/* Triangulates the n >= 3 vertices v (in order around the polygon), keeping
 * their orientation. Returns 0, an emit's non-zero result, or -1 (n < 3,
 * out of memory). */
int glint_triangulate(const glint_vec3 *v, size_t n, glint_polygon_emit emit,
                      void *user);

#endif
