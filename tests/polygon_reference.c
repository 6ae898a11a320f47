/* The triangulation of scene/polygon.c without its grid of inward
 * corners, every ear tested against the whole list, under other names:
 * test_nff checks that the grid changes nothing of what is cut. */
#define GLI_POLYGON_NO_GRID 1
#define gli_triangulate reference_triangulate
#define gli_polygon_is_convex reference_polygon_is_convex
#include "scene/polygon.c"
