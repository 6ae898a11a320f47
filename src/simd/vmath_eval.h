/* Array entry points to the SIMD maths, one set per ISA (vmath_eval.c). */
#ifndef GLINT_SIMD_VMATH_EVAL_H
#define GLINT_SIMD_VMATH_EVAL_H

#include "glint.h"

#include <stddef.h>

#define GLI_VMATH_DECLARE(isa)                                                 \
  void gli_vmath_pow_##isa(const float *x, const float *y, float *out,         \
                           size_t n, glint_math math);                         \
  void gli_vmath_exp_##isa(const float *x, float *out, size_t n,               \
                           glint_math math);                                   \
  void gli_vmath_rcp_##isa(const float *x, float *out, size_t n, int newton);
GLI_VMATH_DECLARE(sse)
GLI_VMATH_DECLARE(avx2)
GLI_VMATH_DECLARE(avx512)
#undef GLI_VMATH_DECLARE

#endif
