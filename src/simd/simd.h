/* The SIMD layer: one thin wrapper per instruction set, all exposing the same
 * small vocabulary, so packet code is written once and compiled once per ISA
 * (the build defines GLINT_ISA_SSE, GLINT_ISA_AVX2 or GLINT_ISA_AVX512 and
 * the matching compiler flags). After Embree's vfloat/vbool wrappers.
 *
 *   vfloat   W floats           vint    W 32-bit integers
 *   vmask    W lane flags       W       GLI_SIMD_WIDTH
 *
 * ISA_NAME(x) gives a symbol an ISA suffix, so the three builds link into one
 * binary and are picked at run time by CPUID. */
#ifndef GLINT_SIMD_SIMD_H
#define GLINT_SIMD_SIMD_H

#if defined(GLINT_ISA_SSE)
#include "simd/simd_sse.h"
#define ISA_SUFFIX sse
#elif defined(GLINT_ISA_AVX2)
#include "simd/simd_avx2.h"
#define ISA_SUFFIX avx2
#elif defined(GLINT_ISA_AVX512)
#include "simd/simd_avx512.h"
#define ISA_SUFFIX avx512
#else
#error "define GLINT_ISA_SSE, GLINT_ISA_AVX2 or GLINT_ISA_AVX512"
#endif

#define ISA_GLUE2(a, b) a##_##b
#define ISA_GLUE(a, b) ISA_GLUE2(a, b)
#define ISA_NAME(name) ISA_GLUE(name, ISA_SUFFIX)

#define LANES GLI_SIMD_WIDTH
#define SIMD_ALIGN __attribute__((aligned(64)))

/* ---- derived operations, the same for every ISA ------------------------ */

/* Sign-bit arithmetic: one instruction each. */
static inline vfloat vf_neg(vfloat a) {
  return vi_as_vf(vi_xor(vf_bits(a), vi_set1((int)0x80000000u)));
}
static inline vfloat vf_abs(vfloat a) {
  return vi_as_vf(vi_and(vf_bits(a), vi_set1(0x7fffffff)));
}
/* c - a*b */
static inline vfloat vf_fnmadd(vfloat a, vfloat b, vfloat c) {
  return vf_sub(c, vf_mul(a, b));
}
/* m ? a : b for masks */
static inline vmask vm_select(vmask m, vmask a, vmask b) {
  return vm_or(vm_and(m, a), vm_andnot(b, m));
}
static inline int vm_any(vmask m) { return vm_bits(m) != 0; }
static inline int vm_none(vmask m) { return vm_bits(m) == 0; }
static inline int vm_first(vmask m) {
  return __builtin_ctz((unsigned)vm_bits(m));
}

/* 1/a by the hardware estimate refined with one Newton–Raphson step, eq. 3.1:
 * x1 = 2 x0 - a x0^2 = x0 (2 - a x0). Without the step (newton = 0) the
 * estimate's ~12 bits show in the image: the thesis's figure 5.7. */
static inline vfloat vf_rcp(vfloat a, int newton) {
  vfloat x0 = vf_rcp_estimate(a);
  if (!newton)
    return x0;
  return vf_mul(x0, vf_fnmadd(a, x0, vf_set1(2.0f)));
}

/* 1/sqrt(a) by the hardware estimate refined with one Newton–Raphson step,
 * eq. 3.2: x1 = 3/2 x0 - 1/2 a x0^3 = x0 (3/2 - a/2 x0^2).
 * docs/specification.md §7 allows this or listing 3.4's sqrt + rcp; this one
 * avoids sqrt's long latency. */
static inline vfloat vf_rsqrt(vfloat a, int newton) {
  vfloat x0 = vf_rsqrt_estimate(a);
  if (!newton)
    return x0;
  vfloat half_a = vf_mul(a, vf_set1(0.5f));
  return vf_mul(x0, vf_fnmadd(vf_mul(half_a, x0), x0, vf_set1(1.5f)));
}

/* Lane i holds i. */
static inline vint vi_lane_index(void) {
  SIMD_ALIGN int idx[LANES];
  for (int i = 0; i < LANES; i++)
    idx[i] = i;
  return vi_load(idx);
}

#endif
