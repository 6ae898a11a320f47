/* The SIMD maths library (docs/specification.md §7): each variant's largest
 * relative error over the inputs the renderer gives it, against a documented
 * bound, on every ISA this CPU runs. The bounds are the README's error table:
 *
 *   pow(x, y): y in [1, 1000] (Phong exponents), x such that x^y lies in
 *              [2^-20, 1] (smaller highlights are far below one 8-bit level)
 *   exp(x):    x in [-20, 0] (Beer's law; exp(-20) = 2e-9)
 *   rcp(x):    x in [1e-3, 1e3]
 */
#include "test_util.h"

#include "simd/vmath_eval.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define N 200000

typedef struct isa {
  const char *name;
  glint_backend backend;
  void (*pow)(const float *, const float *, float *, size_t, glint_math);
  void (*exp)(const float *, float *, size_t, glint_math);
  void (*rcp)(const float *, float *, size_t, int);
} isa;

static const isa isas[] = {
    {"sse", GLINT_BACKEND_SSE, gli_vmath_pow_sse, gli_vmath_exp_sse,
     gli_vmath_rcp_sse},
    {"avx2", GLINT_BACKEND_AVX2, gli_vmath_pow_avx2, gli_vmath_exp_avx2,
     gli_vmath_rcp_avx2},
    {"avx512", GLINT_BACKEND_AVX512, gli_vmath_pow_avx512, gli_vmath_exp_avx512,
     gli_vmath_rcp_avx512},
};

/* Documented bounds, by glint_math. */
static const double pow_bound[GLINT_MATH_COUNT] = {
    [GLINT_MATH_MINIMAX] = 5e-5,
    [GLINT_MATH_FAST] = 1.0, /* may lose a highlight: thesis fig. 5.7 */
    [GLINT_MATH_TAYLOR] = 5e-2,
    [GLINT_MATH_EXACT] = 1e-6};
static const double exp_bound[GLINT_MATH_COUNT] = {[GLINT_MATH_MINIMAX] = 1e-5,
                                                   [GLINT_MATH_FAST] = 5e-2,
                                                   [GLINT_MATH_TAYLOR] = 2e-3,
                                                   [GLINT_MATH_EXACT] = 1e-6};

static float x[N], y[N], out[N];

/* A small deterministic generator, so the test sees the same inputs. */
static void pow_errors(void **state) {
  (void)state;
  unsigned long long seed = 42;
  for (int i = 0; i < N; i++) {
    double yy = pow(10.0, 3.0 * uniform(&seed));
    double r = -20.0 * uniform(&seed);
    y[i] = (float)yy;
    x[i] = (float)pow(2.0, r / yy);
  }
  for (size_t k = 0; k < sizeof isas / sizeof *isas; k++) {
    if (backend_missing(isas[k].backend))
      continue;
    for (int m = 0; m < GLINT_MATH_COUNT; m++) {
      isas[k].pow(x, y, out, N, (glint_math)m);
      double worst = 0;
      for (int i = 0; i < N; i++) {
        double ref = pow((double)x[i], (double)y[i]);
        worst = fmax(worst, fabs(out[i] - ref) / ref);
      }
      printf("%-6s pow %-7s max relative error %.3e (bound %.0e)\n",
             isas[k].name, glint_math_name((glint_math)m), worst, pow_bound[m]);
      if (!(worst <= pow_bound[m]))
        fail_msg("%s pow %s: %.3e exceeds %.0e", isas[k].name,
                 glint_math_name((glint_math)m), worst, pow_bound[m]);
    }
  }
}

static void exp_errors(void **state) {
  (void)state;
  for (int i = 0; i < N; i++)
    x[i] = -20.0f * (float)i / (N - 1);
  for (size_t k = 0; k < sizeof isas / sizeof *isas; k++) {
    if (backend_missing(isas[k].backend))
      continue;
    for (int m = 0; m < GLINT_MATH_COUNT; m++) {
      isas[k].exp(x, out, N, (glint_math)m);
      double worst = 0;
      for (int i = 0; i < N; i++) {
        double ref = exp((double)x[i]);
        worst = fmax(worst, fabs(out[i] - ref) / ref);
      }
      printf("%-6s exp %-7s max relative error %.3e (bound %.0e)\n",
             isas[k].name, glint_math_name((glint_math)m), worst, exp_bound[m]);
      if (!(worst <= exp_bound[m]))
        fail_msg("%s exp %s: %.3e exceeds %.0e", isas[k].name,
                 glint_math_name((glint_math)m), worst, exp_bound[m]);
    }
  }
}

/* Eq. 3.1: one Newton step takes rcp's ~12 bits to nearly 24. */
static void rcp_errors(void **state) {
  (void)state;
  unsigned long long seed = 7;
  for (int i = 0; i < N; i++)
    x[i] = (float)pow(10.0, -3.0 + 6.0 * uniform(&seed));
  for (size_t k = 0; k < sizeof isas / sizeof *isas; k++) {
    if (backend_missing(isas[k].backend))
      continue;
    for (int newton = 0; newton < 2; newton++) {
      isas[k].rcp(x, out, N, newton);
      double worst = 0;
      for (int i = 0; i < N; i++)
        worst = fmax(worst, fabs((double)out[i] * x[i] - 1));
      double bound = newton ? 5e-7 : 1e-3;
      printf("%-6s rcp %s max relative error %.3e (bound %.0e)\n", isas[k].name,
             newton ? "+ Newton" : "alone   ", worst, bound);
      if (!(worst <= bound))
        fail_msg("%s rcp: %.3e exceeds %.0e", isas[k].name, worst, bound);
      /* Without the step the estimate is measurably coarse. */
      if (!newton && !(worst > 1e-6))
        fail_msg("%s: rcp without Newton is too exact to be the estimate",
                 isas[k].name);
    }
  }
}

/* Exact values at the ends of the ranges. */
static void special_values(void **state) {
  (void)state;
  for (size_t k = 0; k < sizeof isas / sizeof *isas; k++) {
    if (backend_missing(isas[k].backend))
      continue;
    float xs[4] = {1, 0.5f, 0.25f, 1e-30f}, ys[4] = {80, 1, 2, 40}, r[4];
    isas[k].pow(xs, ys, r, 4, GLINT_MATH_MINIMAX);
    assert_true(fabs(r[0] - 1) < 1e-5);
    assert_true(fabs(r[1] - 0.5) < 1e-6);
    assert_true(fabs(r[2] - 0.0625) < 1e-6);
    assert_true(r[3] >= 0 && r[3] < 1e-30); /* underflows to ~0, no NaN */
    float e0 = 0, e1;
    isas[k].exp(&e0, &e1, 1, GLINT_MATH_MINIMAX);
    assert_true(fabs(e1 - 1) < 1e-6);
  }
}

int main(void) {
  /* Every test here is of the SIMD backends. */
  if (!glint_backend_supported(GLINT_BACKEND_SSE)) {
    printf("SKIPPED: this CPU (or GLINT_ISA) has no SIMD backend\n");
    return SKIP_EXIT;
  }
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(pow_errors),
      cmocka_unit_test(exp_errors),
      cmocka_unit_test(rcp_errors),
      cmocka_unit_test(special_values),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
