/* The camera basis of docs/specification.md §2 (thesis eq. 2.1 with the aspect
 * ratio folded in), computed in double once per frame. */
#include "render/frame.h"

#include <math.h>

void gli_camera_basis_init(camera_basis *c, const glint_camera *g, int width,
                           int height) {
  double dx = g->at.x - g->from.x, dy = g->at.y - g->from.y,
         dz = g->at.z - g->from.z;
  double dl = sqrt(dx * dx + dy * dy + dz * dz);
  dx /= dl, dy /= dl, dz /= dl;
  /* r = normalize(d x up), u = r x d; up scaled to a largest component of
   * 1 first (an up of 1e-300 is legal, and its cross product's squares
   * underflowed to a zero length) */
  double um = fmax(fabs(g->up.x), fmax(fabs(g->up.y), fabs(g->up.z)));
  double upx = g->up.x / um, upy = g->up.y / um, upz = g->up.z / um;
  double rx = dy * upz - dz * upy, ry = dz * upx - dx * upz,
         rz = dx * upy - dy * upx;
  double rl = sqrt(rx * rx + ry * ry + rz * rz);
  rx /= rl, ry /= rl, rz /= rl;
  double ux = ry * dz - rz * dy, uy = rz * dx - rx * dz, uz = rx * dy - ry * dx;
  double t = tan(g->fov_x_degrees * 3.14159265358979323846 / 360.0);
  *c = (camera_basis){{g->from.x, g->from.y, g->from.z},
                      {dx, dy, dz},
                      {rx, ry, rz},
                      {ux, uy, uz},
                      t,
                      t * height / width,
                      width,
                      height};
}
