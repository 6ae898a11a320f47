/* Numbers in scene files (src/scene/number.c): the fast path must give
 * exactly strtod's double, bit for bit, and the same verdict on everything
 * that is not a finite number. */
#include "test_util.h"

#include "scene/number.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void same_as_strtod(const char *text) {
  double v = 12345, ref;
  char *end;
  ref = strtod(text, &end);
  int expected = end != text + strlen(text) || end == text ? NUMBER_BAD
                 : !isfinite(ref)                          ? NUMBER_NOT_FINITE
                                                           : NUMBER_OK;
  int got = gli_number_parse(text, strlen(text), &v);
  if (got != expected)
    fail_msg("'%s': gli_number_parse says %d, strtod %d", text, got, expected);
  if (got == NUMBER_OK && memcmp(&v, &ref, sizeof v) != 0)
    fail_msg("'%s': %.17g, strtod %.17g", text, v, ref);
}

static void hand_picked(void **state) {
  (void)state;
  static const char *cases[] = {"0",
                                "-0",
                                "+0",
                                "0.0",
                                "-0.0",
                                "1",
                                "-1",
                                "1.",
                                ".5",
                                "-.5",
                                "0.1",
                                "0.2",
                                "0.3",
                                "3.14159",
                                "-0.0503247",
                                "1e5",
                                "1E5",
                                "1e+5",
                                "1e-5",
                                "2.5e-3",
                                "123456789012345",
                                "1234567890123456",
                                "12345678901234567890",
                                "0.000000000000000000001",
                                "1e22",
                                "1e23",
                                "1e-22",
                                "1e-23",
                                "9e22",
                                "4.9e-324",
                                "1e-400",
                                "1e400",
                                "1.7976931348623157e308",
                                "1.7976931348623159e308",
                                "0.1000000000000000055511151231257827",
                                "000000000000000000000000001",
                                "0.30000000000000004",
                                "inf",
                                "-inf",
                                "nan",
                                "NaN",
                                "infinity",
                                "0x1p3",
                                "0x10",
                                "",
                                ".",
                                "-",
                                "+",
                                "e5",
                                "1e",
                                "1e+",
                                "1.5e-",
                                "1..5",
                                "1.5.5",
                                "--1",
                                "1-",
                                "1,5",
                                "abc",
                                "12a",
                                "1e5.5",
                                " 1",
                                "5e-0",
                                "0e0",
                                "1e0000000000000000000005"};
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
    same_as_strtod(cases[i]);
}

/* Decimals of every shape a mesh writer produces, from a fixed seed. */
static void random_decimals(void **state) {
  (void)state;
  uint64_t x = 0x9E3779B97F4A7C15u;
  char buf[64];
  for (int i = 0; i < 300000; i++) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    double v = ldexp((double)(x >> 11), -53) * 2 - 1;
    int digits = 1 + (int)(x >> 3 & 15), form = (int)(x & 3);
    int scale = (int)(x >> 8 & 63) - 32;
    v *= pow(10, scale);
    if (form == 0)
      snprintf(buf, sizeof buf, "%.*f", digits, v);
    else if (form == 1)
      snprintf(buf, sizeof buf, "%.*e", digits, v);
    else if (form == 2)
      snprintf(buf, sizeof buf, "%.*g", digits, v);
    else
      snprintf(buf, sizeof buf, "%lld", (long long)(x >> (x & 31)));
    same_as_strtod(buf);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(hand_picked),
      cmocka_unit_test(random_decimals),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
