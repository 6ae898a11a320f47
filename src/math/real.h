/* The scalar precision of a translation unit. The scalar tracer is one source
 * compiled twice (docs/specification.md §1: the thesis's "float" and "double"
 * builds): the build defines GLINT_REAL_FLOAT or GLINT_REAL_DOUBLE, and
 * REAL_NAME() gives every exported symbol a suffix so both live in one binary.
 */
#ifndef GLINT_MATH_REAL_H
#define GLINT_MATH_REAL_H

#include <math.h>

#if defined(GLINT_REAL_DOUBLE)
typedef double real;
#define REAL_SUFFIX double
#define REAL_IS_DOUBLE 1
#define r_sqrt sqrt
#define r_pow pow
#define r_exp exp
#define r_floor floor
#define r_fabs fabs
#define r_fmin fmin
#define r_fmax fmax
#define REAL_MAX 1.7976931348623157e308
#elif defined(GLINT_REAL_FLOAT)
typedef float real;
#define REAL_SUFFIX float
#define REAL_IS_DOUBLE 0
#define r_sqrt sqrtf
#define r_pow powf
#define r_exp expf
#define r_floor floorf
#define r_fabs fabsf
#define r_fmin fminf
#define r_fmax fmaxf
#define REAL_MAX 3.40282347e38f
#else
#error "define GLINT_REAL_FLOAT or GLINT_REAL_DOUBLE before including real.h"
#endif

/* min and max as single instructions (minss/maxsd): fmin and fmax are
 * library calls, being defined for NaN operands, which never occur here. */
static inline real r_min(real a, real b) { return a < b ? a : b; }
static inline real r_max(real a, real b) { return a > b ? a : b; }

#define REAL_GLUE2(a, b) a##_##b
#define REAL_GLUE(a, b) REAL_GLUE2(a, b)
#define REAL_NAME(name) REAL_GLUE(name, REAL_SUFFIX)

#endif
