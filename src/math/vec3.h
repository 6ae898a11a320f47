/* 3-vectors in the translation unit's precision (see real.h). */
#ifndef GLINT_MATH_VEC3_H
#define GLINT_MATH_VEC3_H

#include "math/real.h"

typedef struct vec3 {
  real x, y, z;
} vec3;

static inline vec3 v3(real x, real y, real z) {
  vec3 r = {x, y, z};
  return r;
}
static inline vec3 v3_add(vec3 a, vec3 b) {
  return v3(a.x + b.x, a.y + b.y, a.z + b.z);
}
static inline vec3 v3_sub(vec3 a, vec3 b) {
  return v3(a.x - b.x, a.y - b.y, a.z - b.z);
}
static inline vec3 v3_mul(vec3 a, vec3 b) {
  return v3(a.x * b.x, a.y * b.y, a.z * b.z);
}
static inline vec3 v3_scale(vec3 a, real s) {
  return v3(a.x * s, a.y * s, a.z * s);
}
static inline vec3 v3_neg(vec3 a) { return v3(-a.x, -a.y, -a.z); }
/* a + s*b */
static inline vec3 v3_madd(vec3 a, real s, vec3 b) {
  return v3(a.x + s * b.x, a.y + s * b.y, a.z + s * b.z);
}
static inline real v3_dot(vec3 a, vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline vec3 v3_cross(vec3 a, vec3 b) {
  return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
            a.x * b.y - a.y * b.x);
}
static inline real v3_len(vec3 a) { return r_sqrt(v3_dot(a, a)); }
static inline vec3 v3_normalize(vec3 a) {
  return v3_scale(a, (real)1 / v3_len(a));
}
static inline real v3_get(vec3 a, int axis) {
  return axis == 0 ? a.x : axis == 1 ? a.y : a.z;
}

#endif
