/* pow, exp and rcp of the SIMD maths library on whole arrays, for the tests
 * and for tools: compiled once per ISA like the tracers. */
#include "simd/vmath.h"

#include <string.h>

typedef enum vmath_op { OP_POW, OP_EXP, OP_RCP } vmath_op;

/* Runs `op` over n values, a vector at a time; the last vector's unused
 * lanes hold 1, a value every operation takes. */
static void eval(vmath_op op, const float *x, const float *y, float *out,
                 size_t n, glint_math math, int newton) {
  for (size_t i = 0; i < n; i += LANES) {
    SIMD_ALIGN float a[LANES], b[LANES], r[LANES];
    size_t k = n - i < LANES ? n - i : LANES;
    for (size_t j = 0; j < LANES; j++) {
      a[j] = j < k ? x[i + j] : 1.0f;
      b[j] = y && j < k ? y[i + j] : 1.0f;
    }
    vfloat va = vf_load(a);
    vfloat v = op == OP_POW   ? vm_pow(va, vf_load(b), math)
               : op == OP_EXP ? vm_exp(va, math)
                              : vf_rcp(va, newton);
    vf_store(r, v);
    memcpy(out + i, r, k * sizeof *r);
  }
}

void ISA_NAME(gli_vmath_pow)(const float *x, const float *y, float *out,
                             size_t n, glint_math math) {
  eval(OP_POW, x, y, out, n, math, 1);
}

void ISA_NAME(gli_vmath_exp)(const float *x, float *out, size_t n,
                             glint_math math) {
  eval(OP_EXP, x, NULL, out, n, math, 1);
}

/* 1/x as the packet tracers divide (eq. 3.1), with or without the Newton
 * step. */
void ISA_NAME(gli_vmath_rcp)(const float *x, float *out, size_t n, int newton) {
  eval(OP_RCP, x, NULL, out, n, GLINT_MATH_MINIMAX, newton);
}
