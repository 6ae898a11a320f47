/* remez: minimax polynomial coefficients for glint's SIMD pow and exp
 * (docs/specification.md §7, thesis §4.4.4), by the Remez exchange algorithm.
 *
 * It fits, in relative error:
 *   log2(1 + x) / x  for x in [sqrt(1/2) - 1, sqrt(2) - 1]  (pow's log2)
 *   2^f              for f in [-1/2, 1/2]                    (exp2, exp)
 * and prints src/simd/minimax_coeffs.h. Regenerate with
 *
 *   build/tools/remez --log2-degree 6 --exp2-degree 4 >
 * src/simd/minimax_coeffs.h
 *
 * The exchange (E. Ya. Remez, 1934): start from Chebyshev nodes; solve for
 * the polynomial whose weighted error equioscillates with magnitude E on
 * the n+2 reference points; move each reference point to the extremum of
 * the error in its stretch between sign changes; repeat until the largest
 * error equals |E|. Arithmetic is in long double. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DEGREE 16
#define SAMPLES 20000

typedef long double ld;
typedef ld (*func)(ld);

static ld log2_ratio(ld x) {
  if (fabsl(x) < 1e-12L)
    return 1.0L / logl(2.0L) * (1 - x / 2 + x * x / 3);
  return log1pl(x) / x / logl(2.0L);
}

static ld exp2_f(ld x) { return exp2l(x); }

static ld poly(const ld *c, int n, ld x) {
  ld r = c[n];
  for (int k = n - 1; k >= 0; k--)
    r = r * x + c[k];
  return r;
}

/* Weighted (relative) error of the polynomial at x. */
static ld err_at(func f, const ld *c, int n, ld x) {
  ld fx = f(x);
  return (poly(c, n, x) - fx) / fx;
}

/* Solves A z = b (m x m) by Gaussian elimination with partial pivoting. */
static int solve(ld a[][MAX_DEGREE + 2], ld *b, int m) {
  for (int col = 0; col < m; col++) {
    int piv = col;
    for (int r = col + 1; r < m; r++)
      if (fabsl(a[r][col]) > fabsl(a[piv][col]))
        piv = r;
    if (a[piv][col] == 0)
      return -1;
    for (int k = 0; k < m; k++) {
      ld t = a[col][k];
      a[col][k] = a[piv][k];
      a[piv][k] = t;
    }
    ld t = b[col];
    b[col] = b[piv];
    b[piv] = t;
    for (int r = col + 1; r < m; r++) {
      ld q = a[r][col] / a[col][col];
      for (int k = col; k < m; k++)
        a[r][k] -= q * a[col][k];
      b[r] -= q * b[col];
    }
  }
  for (int r = m - 1; r >= 0; r--) {
    for (int k = r + 1; k < m; k++)
      b[r] -= a[r][k] * b[k];
    b[r] /= a[r][r];
  }
  return 0;
}

/* Minimax polynomial of degree n for f on [lo, hi]; returns max rel error. */
static ld remez(func f, ld lo, ld hi, int n, ld *c) {
  int m = n + 2;
  ld ref[MAX_DEGREE + 2];
  for (int i = 0; i < m; i++)
    ref[i] = (lo + hi) / 2 -
             (hi - lo) / 2 *
                 cosl(3.14159265358979323846264338327950288L * i / (m - 1));
  ld max_err = 0;
  for (int iter = 0; iter < 100; iter++) {
    /* sum c_k x_i^k - (-1)^i E f(x_i) = f(x_i): relative error E. */
    ld a[MAX_DEGREE + 2][MAX_DEGREE + 2], b[MAX_DEGREE + 2];
    for (int i = 0; i < m; i++) {
      ld p = 1;
      for (int k = 0; k <= n; k++, p *= ref[i])
        a[i][k] = p;
      a[i][n + 1] = (i % 2 ? 1 : -1) * f(ref[i]);
      b[i] = f(ref[i]);
    }
    if (solve(a, b, m)) {
      fprintf(stderr, "remez: singular system\n");
      exit(1);
    }
    for (int k = 0; k <= n; k++)
      c[k] = b[k];
    ld level = fabsl(b[n + 1]);

    /* New reference: the extremum of the error between sign changes. */
    ld xs[SAMPLES + 1], es[SAMPLES + 1];
    for (int i = 0; i <= SAMPLES; i++) {
      xs[i] = lo + (hi - lo) * i / SAMPLES;
      es[i] = err_at(f, c, n, xs[i]);
    }
    ld next[MAX_DEGREE + 2];
    int count = 0, best = 0;
    max_err = 0;
    for (int i = 0; i <= SAMPLES; i++) {
      if (fabsl(es[i]) > max_err)
        max_err = fabsl(es[i]);
      if (i > 0 && (es[i] > 0) != (es[best] > 0)) {
        if (count < MAX_DEGREE + 2)
          next[count++] = xs[best];
        best = i;
      } else if (fabsl(es[i]) > fabsl(es[best])) {
        best = i;
      }
    }
    if (count < MAX_DEGREE + 2)
      next[count++] = xs[best];
    /* Keep the m alternating extrema with the largest errors: drop the
     * smaller end while there are too many. */
    while (count > m) {
      if (fabsl(err_at(f, c, n, next[0])) <
          fabsl(err_at(f, c, n, next[count - 1])))
        memmove(next, next + 1, sizeof *next * (size_t)--count);
      else
        count--;
    }
    if (count < m)
      break; /* cannot improve: the error no longer alternates enough */
    memcpy(ref, next, sizeof *ref * (size_t)m);
    if (max_err - level <= 1e-6L * max_err)
      break;
  }
  return max_err;
}

/* The error after rounding the coefficients to float. */
static ld float_error(func f, ld lo, ld hi, int n, const ld *c) {
  ld fc[MAX_DEGREE + 1], worst = 0;
  for (int k = 0; k <= n; k++)
    fc[k] = (float)c[k];
  for (int i = 0; i <= SAMPLES; i++) {
    ld x = lo + (hi - lo) * i / SAMPLES;
    ld e = fabsl(err_at(f, fc, n, x));
    if (e > worst)
      worst = e;
  }
  return worst;
}

static void emit(const char *name, const char *id, const char *what, int n,
                 const ld *c, ld err, ld ferr) {
  printf("/* %s\n * degree %d; max relative error %.3Le (%.3Le with float "
         "coefficients) */\n",
         what, n, err, ferr);
  printf("#define GLI_%s_DEGREE %d\n", name, n);
  printf("static const float gli_%s_coeffs[%d] = {\n", id, n + 1);
  for (int k = 0; k <= n; k++)
    printf("    %.9ef,\n", (double)c[k]);
  printf("};\n\n");
}

int main(int argc, char **argv) {
  int log2_degree = 6, exp2_degree = 4;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--log2-degree") == 0 && i + 1 < argc)
      log2_degree = atoi(argv[++i]);
    else if (strcmp(argv[i], "--exp2-degree") == 0 && i + 1 < argc)
      exp2_degree = atoi(argv[++i]);
    else {
      fprintf(stderr,
              "usage: remez [--log2-degree N] [--exp2-degree N] (1..%d)\n",
              MAX_DEGREE);
      return 2;
    }
  }
  if (log2_degree < 1 || log2_degree > MAX_DEGREE || exp2_degree < 1 ||
      exp2_degree > MAX_DEGREE) {
    fprintf(stderr, "remez: degrees must be 1..%d\n", MAX_DEGREE);
    return 2;
  }
  ld lc[MAX_DEGREE + 1], ec[MAX_DEGREE + 1];
  ld llo = sqrtl(0.5L) - 1, lhi = sqrtl(2.0L) - 1;
  ld lerr = remez(log2_ratio, llo, lhi, log2_degree, lc);
  ld eerr = remez(exp2_f, -0.5L, 0.5L, exp2_degree, ec);
  printf("/* clang-format off */\n"
         "/* Minimax coefficients for glint's SIMD pow and exp "
         "(docs/specification.md §7).\n"
         " * Generated by tools/remez.c; do not edit. Regenerate with:\n"
         " *   build/tools/remez --log2-degree %d --exp2-degree %d > "
         "src/simd/minimax_coeffs.h */\n"
         "#ifndef GLINT_SIMD_MINIMAX_COEFFS_H\n"
         "#define GLINT_SIMD_MINIMAX_COEFFS_H\n\n",
         log2_degree, exp2_degree);
  emit("LOG2", "log2",
       "log2(1 + x) = x P(x), x in [sqrt(1/2) - 1, sqrt(2) - 1]", log2_degree,
       lc, lerr, float_error(log2_ratio, llo, lhi, log2_degree, lc));
  emit("EXP2", "exp2", "2^f = Q(f), f in [-1/2, 1/2]", exp2_degree, ec, eerr,
       float_error(exp2_f, -0.5L, 0.5L, exp2_degree, ec));
  printf("/* clang-format on */\n\n#endif\n");
  return 0;
}
