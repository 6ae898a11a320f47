/* pow and exp of the SIMD maths library on whole arrays, for the tests and
 * for tools: compiled once per ISA like the tracers. */
#include "simd/vmath.h"

#include <string.h>

void ISA_NAME(gli_vmath_pow)(const float *x, const float *y, float *out,
                             size_t n, glint_math math) {
  for (size_t i = 0; i < n; i += LANES) {
    SIMD_ALIGN float a[LANES], b[LANES], r[LANES];
    size_t k = n - i < LANES ? n - i : LANES;
    for (size_t j = 0; j < LANES; j++) {
      a[j] = j < k ? x[i + j] : 1.0f;
      b[j] = j < k ? y[i + j] : 1.0f;
    }
    vf_store(r, vm_pow(vf_load(a), vf_load(b), math));
    memcpy(out + i, r, k * sizeof *r);
  }
}

void ISA_NAME(gli_vmath_exp)(const float *x, float *out, size_t n,
                             glint_math math) {
  for (size_t i = 0; i < n; i += LANES) {
    SIMD_ALIGN float a[LANES], r[LANES];
    size_t k = n - i < LANES ? n - i : LANES;
    for (size_t j = 0; j < LANES; j++)
      a[j] = j < k ? x[i + j] : 0.0f;
    vf_store(r, vm_exp(vf_load(a), math));
    memcpy(out + i, r, k * sizeof *r);
  }
}

/* 1/x as the packet tracers divide (eq. 3.1), with or without the Newton
 * step. */
void ISA_NAME(gli_vmath_rcp)(const float *x, float *out, size_t n, int newton) {
  for (size_t i = 0; i < n; i += LANES) {
    SIMD_ALIGN float a[LANES], r[LANES];
    size_t k = n - i < LANES ? n - i : LANES;
    for (size_t j = 0; j < LANES; j++)
      a[j] = j < k ? x[i + j] : 1.0f;
    vf_store(r, vf_rcp(vf_load(a), newton));
    memcpy(out + i, r, k * sizeof *r);
  }
}
