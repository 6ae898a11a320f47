/* Reflection, refraction and Beer's law for one ray (thesis eq. 2.11–2.13),
 * in the translation unit's precision. */
#ifndef GLINT_MATH_OPTICS_H
#define GLINT_MATH_OPTICS_H

#include "math/vec3.h"

/* Eq. 2.12: R = D - 2(D·N)N, for N facing against D. */
static inline vec3 reflect_dir(vec3 d, vec3 n) {
  return v3_madd(d, -2 * v3_dot(d, n), n);
}

/* Eq. 2.13 (Heckbert): T = eta D + (eta c - sqrt(k)) N with c = -D·N and
 * k = 1 - eta^2 (1 - c^2), N facing against D, eta = eta1 / eta2. Returns 0
 * on total internal reflection (k < 0), when there is no refracted ray. */
static inline int refract_dir(vec3 d, vec3 n, real eta, vec3 *t) {
  real c = -v3_dot(d, n);
  real k = 1 - eta * eta * (1 - c * c);
  if (k < 0)
    return 0;
  *t = v3_madd(v3_scale(d, eta), eta * c - r_sqrt(k), n);
  return 1;
}

/* Eq. 2.11: light crossing a distance s of a medium of absorbance a keeps
 * exp(-a s) of itself, per channel. */
static inline vec3 beer(vec3 absorb, real s) {
  return v3(r_exp(-absorb.x * s), r_exp(-absorb.y * s), r_exp(-absorb.z * s));
}

#endif
