/* The pinhole camera of docs/specification.md §2 (thesis eq. 2.1 with the
 * aspect ratio folded in), in the translation unit's precision. */
#ifndef GLINT_RENDER_CAMERA_H
#define GLINT_RENDER_CAMERA_H

#include "glint.h"
#include "math/vec3.h"
#include "render/frame.h"

typedef struct camera {
  vec3 from, d, r, u; /* eye, view direction, right, up (orthonormal) */
  real tan_x, tan_y;  /* half extents of the image plane at distance 1 */
  real width, height;
} camera;

/* The basis is computed in double whatever the precision, so float and
 * double renders aim their rays identically; this rounds it once. */
static inline void camera_from_basis(camera *c, const camera_basis *b) {
  c->from = v3((real)b->from[0], (real)b->from[1], (real)b->from[2]);
  c->d = v3((real)b->dir[0], (real)b->dir[1], (real)b->dir[2]);
  c->r = v3((real)b->right[0], (real)b->right[1], (real)b->right[2]);
  c->u = v3((real)b->up[0], (real)b->up[1], (real)b->up[2]);
  c->tan_x = (real)b->tan_x;
  c->tan_y = (real)b->tan_y;
  c->width = (real)b->width;
  c->height = (real)b->height;
}

static inline void camera_init(camera *c, const glint_camera *g, int width,
                               int height) {
  camera_basis b;
  gli_camera_basis_init(&b, g, width, height);
  camera_from_basis(c, &b);
}

/* The unit direction through image point (px, py), in pixels from the
 * top-left corner (pixel centres at +0.5). */
static inline vec3 camera_dir(const camera *c, real px, real py) {
  real x = (2 * px / c->width - 1) * c->tan_x;
  real y = (1 - 2 * py / c->height) * c->tan_y;
  return v3_normalize(v3_madd(v3_madd(c->d, x, c->r), y, c->u));
}

#endif
