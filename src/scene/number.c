#include "scene/number.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

/* Clinger's fast path (W. D. Clinger, "How to read floating point numbers
 * accurately", PLDI 1990): a decimal m x 10^e whose significand m is below
 * 2^53 and whose |e| <= 22 is exactly m and 10^|e| in doubles, so one IEEE
 * multiplication or division rounds it correctly. Mesh coordinates such as
 * "-0.0503247" are all of this kind; anything else goes to strtod. It makes
 * reading the 200k-triangle ASCII dragon about a third faster. */
static const double pow10_exact[23] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

static int fast_path(const char *p, const char *end, double *out) {
  int negative = 0;
  if (p < end && (*p == '-' || *p == '+'))
    negative = *p++ == '-';
  uint64_t m = 0;
  int digits = 0, exp10 = 0, any = 0;
  for (; p < end && *p >= '0' && *p <= '9'; p++, any = 1) {
    if (m || *p != '0')
      digits++;
    m = m * 10 + (uint64_t)(*p - '0');
    if (digits > 15)
      return 0;
  }
  if (p < end && *p == '.')
    for (p++; p < end && *p >= '0' && *p <= '9'; p++, any = 1) {
      if (m || *p != '0')
        digits++;
      m = m * 10 + (uint64_t)(*p - '0');
      exp10--;
      if (digits > 15)
        return 0;
    }
  if (!any)
    return 0;
  if (p < end && (*p == 'e' || *p == 'E')) {
    p++;
    int eneg = 0, e = 0, edigits = 0;
    if (p < end && (*p == '-' || *p == '+'))
      eneg = *p++ == '-';
    for (; p < end && *p >= '0' && *p <= '9'; p++, edigits++)
      if (e < 10000)
        e = e * 10 + (*p - '0');
    if (!edigits)
      return 0;
    exp10 += eneg ? -e : e;
  }
  if (p != end || exp10 < -22 || exp10 > 22)
    return 0;
  /* 15 digits keep m below 10^15 < 2^53. */
  double v = (double)m;
  v = exp10 < 0 ? v / pow10_exact[-exp10] : v * pow10_exact[exp10];
  *out = negative ? -v : v;
  return 1;
}

int gli_number_parse(const char *t, size_t len, double *out) {
  if (len == 0)
    return NUMBER_BAD;
  double v;
  if (!fast_path(t, t + len, &v)) {
    char *end;
    v = strtod(t, &end);
    if (end != t + len)
      return NUMBER_BAD;
  }
  if (!isfinite(v))
    return NUMBER_NOT_FINITE;
  *out = v;
  return NUMBER_OK;
}

number_locale gli_number_locale_begin(void) {
  number_locale l;
  l.c = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
  l.old = l.c ? uselocale(l.c) : (locale_t)0;
  return l;
}

void gli_number_locale_end(number_locale l) {
  if (l.c) {
    uselocale(l.old);
    freelocale(l.c);
  }
}
