/* pow and exp for W lanes (docs/specification.md §7, thesis §4.4.4): SSE has no
 * instruction for either, so each is built from the IEEE-754 representation and
 * a polynomial, in four variants chosen at run time (--math):
 *
 *   minimax  log2 by a degree-6 and 2^f by a degree-4 polynomial whose
 *            coefficients the Remez exchange in tools/remez.c produced
 *            (minimax_coeffs.h); the default.
 *   taylor   the same reductions with Taylor polynomials of lower degree:
 *            log2(1+x) to x^5 and 2^f to f^3 (the thesis: ~50 % faster).
 *   fast     bit manipulation alone, in the spirit of Intel's Approximate
 *            Math Library (written from the idea, after Schraudolph 1999:
 *            a float's bits, read as an integer, are a scaled, shifted,
 *            piecewise-linear log2 of its value).
 *   exact    libm's powf/expf lane by lane: the reference.
 *
 * pow(x, y) = 2^(y log2 x) for x > 0; exp(x) = 2^(x log2 e). */
#ifndef GLINT_SIMD_VMATH_H
#define GLINT_SIMD_VMATH_H

#include "glint.h"
#include "simd/minimax_coeffs.h"
#include "simd/simd.h"

#include <math.h>

/* Horner's rule over a coefficient array, lowest order first. */
static inline vfloat vm_horner(const float *c, int degree, vfloat x) {
  vfloat r = vf_set1(c[degree]);
  for (int k = degree - 1; k >= 0; k--)
    r = vf_fmadd(r, x, vf_set1(c[k]));
  return r;
}

/* x = 2^e m with m in [sqrt(1/2), sqrt(2)): returns m - 1 and sets *e.
 * x must be a positive normal number. */
static inline vfloat vm_split(vfloat x, vfloat *e) {
  vint bits = vf_bits(x);
  vint exponent = vi_sub(vi_shr(bits, 23), vi_set1(127));
  vfloat m = vi_as_vf(vi_or(vi_and(bits, vi_set1(0x007fffff)),
                            vi_set1(0x3f800000))); /* [1, 2) */
  vmask big = vf_gt(m, vf_set1(1.41421356f));
  m = vf_select(big, vf_mul(m, vf_set1(0.5f)), m);
  *e = vf_add(vi_to_vf(exponent), vf_select(big, vf_set1(1), vf_zero()));
  return vf_sub(m, vf_set1(1));
}

/* 2^k for integral k in [-126, 127], built in the exponent field. */
static inline vfloat vm_pow2i(vfloat k) {
  return vi_as_vf(vi_shl(vi_add(vf_to_vi(k), vi_set1(127)), 23));
}

/* Taylor coefficients: log2(1+x)/x = (1 - x/2 + x^2/3 - x^3/4 + x^4/5)/ln 2
 * and 2^f = e^(f ln 2) = sum (f ln 2)^k / k!, k <= 3. */
static const float gli_taylor_log2[5] = {
    1.442695041f, -0.7213475204f, 0.4808983469f, -0.3606737602f, 0.2885390082f};
static const float gli_taylor_exp2[4] = {1.0f, 0.6931471806f, 0.2402265070f,
                                         0.05550410866f};

/* log2 for positive normal x; other inputs give -126 (pow then gives 0). */
static inline vfloat vm_log2(vfloat x, glint_math math) {
  vmask tiny = vf_lt(x, vf_set1(1.17549435e-38f));
  vfloat r;
  if (math == GLINT_MATH_FAST) {
    /* bits / 2^23 - 127 is log2 with the mantissa taken as linear: exact at
     * powers of two, at most 0.086 below in between, and never positive
     * for x < 1 (centring its error would make pow(x < 1, 1000) explode). */
    r = vf_fmadd(vi_to_vf(vf_bits(x)), vf_set1(1.0f / 8388608.0f),
                 vf_set1(-127.0f));
  } else {
    vfloat e, t = vm_split(x, &e);
    vfloat p = math == GLINT_MATH_TAYLOR
                   ? vm_horner(gli_taylor_log2, 4, t)
                   : vm_horner(gli_log2_coeffs, GLI_LOG2_DEGREE, t);
    r = vf_fmadd(t, p, e);
  }
  return vf_select(tiny, vf_set1(-126.0f), r);
}

/* 2^x, clamped to [2^-126, 2^127]. */
static inline vfloat vm_exp2(vfloat x, glint_math math) {
  x = vf_min(vf_max(x, vf_set1(-126.0f)), vf_set1(127.0f));
  if (math == GLINT_MATH_FAST) {
    /* The inverse of the fast log2: write (x + 127 - c) 2^23 as bits. */
    vfloat b =
        vf_mul(vf_add(x, vf_set1(127.0f - 0.0430357f)), vf_set1(8388608.0f));
    return vi_as_vf(vf_to_vi(vf_max(b, vf_set1(8388608.0f))));
  }
  vfloat k = vf_floor(vf_add(x, vf_set1(0.5f)));
  vfloat f = vf_sub(x, k); /* [-1/2, 1/2] */
  vfloat p = math == GLINT_MATH_TAYLOR
                 ? vm_horner(gli_taylor_exp2, 3, f)
                 : vm_horner(gli_exp2_coeffs, GLI_EXP2_DEGREE, f);
  vfloat s = vm_pow2i(vf_max(k, vf_set1(-126.0f)));
  return vf_mul(p, s);
}

/* libm lane by lane. */
static inline vfloat vm_exact_pow(vfloat x, vfloat y) {
  SIMD_ALIGN float a[LANES], b[LANES];
  vf_store(a, x);
  vf_store(b, y);
  for (int i = 0; i < LANES; i++)
    a[i] = powf(a[i], b[i]);
  return vf_load(a);
}

static inline vfloat vm_exact_exp(vfloat x) {
  SIMD_ALIGN float a[LANES];
  vf_store(a, x);
  for (int i = 0; i < LANES; i++)
    a[i] = expf(a[i]);
  return vf_load(a);
}

/* x^y for x > 0 (callers mask other lanes). */
static inline vfloat vm_pow(vfloat x, vfloat y, glint_math math) {
  if (math == GLINT_MATH_EXACT)
    return vm_exact_pow(x, y);
  return vm_exp2(vf_mul(y, vm_log2(x, math)), math);
}

/* e^x. */
static inline vfloat vm_exp(vfloat x, glint_math math) {
  if (math == GLINT_MATH_EXACT)
    return vm_exact_exp(x);
  return vm_exp2(vf_mul(x, vf_set1(1.44269504f)), math);
}

/* Beer's law's factor e^x for x <= 0 (eq. 2.11), exactly 1 where x is 0:
 * a lane that crossed nothing absorbing keeps its light whatever the
 * approximation (the fast exp's e^0 is 0.978, the minimax's 1 - 6e-8), so
 * that no lane's colour depends on what its packet's other lanes met. */
static inline vfloat vm_beer(vfloat x, glint_math math) {
  return vf_select(vf_lt(x, vf_zero()), vm_exp(x, math), vf_set1(1));
}

#endif
