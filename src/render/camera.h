/* The pinhole camera of SPEC §2 (thesis eq. 2.1 with the aspect ratio folded
 * in), in the translation unit's precision. */
#ifndef GLINT_RENDER_CAMERA_H
#define GLINT_RENDER_CAMERA_H

#include "glint.h"
#include "math/vec3.h"

typedef struct camera {
  vec3 from, d, r, u; /* eye, view direction, right, up (orthonormal) */
  real tan_x, tan_y;  /* half extents of the image plane at distance 1 */
  real width, height;
} camera;

/* The basis is computed in double whatever the precision, so float and
 * double renders aim their rays identically. */
static inline void camera_init(camera *c, const glint_camera *g, int width,
                               int height) {
  double dx = g->at.x - g->from.x, dy = g->at.y - g->from.y,
         dz = g->at.z - g->from.z;
  double dl = sqrt(dx * dx + dy * dy + dz * dz);
  dx /= dl, dy /= dl, dz /= dl;
  /* r = normalize(d x up), u = r x d */
  double rx = dy * g->up.z - dz * g->up.y, ry = dz * g->up.x - dx * g->up.z,
         rz = dx * g->up.y - dy * g->up.x;
  double rl = sqrt(rx * rx + ry * ry + rz * rz);
  rx /= rl, ry /= rl, rz /= rl;
  double ux = ry * dz - rz * dy, uy = rz * dx - rx * dz, uz = rx * dy - ry * dx;
  double t = tan(g->fov_x_degrees * 3.14159265358979323846 / 360.0);
  c->from = v3((real)g->from.x, (real)g->from.y, (real)g->from.z);
  c->d = v3((real)dx, (real)dy, (real)dz);
  c->r = v3((real)rx, (real)ry, (real)rz);
  c->u = v3((real)ux, (real)uy, (real)uz);
  c->tan_x = (real)t;
  c->tan_y = (real)(t * height / width);
  c->width = (real)width;
  c->height = (real)height;
}

/* The unit direction through image point (px, py), in pixels from the
 * top-left corner (pixel centres at +0.5). */
static inline vec3 camera_dir(const camera *c, real px, real py) {
  real x = (2 * px / c->width - 1) * c->tan_x;
  real y = (1 - 2 * py / c->height) * c->tan_y;
  return v3_normalize(v3_madd(v3_madd(c->d, x, c->r), y, c->u));
}

#endif
