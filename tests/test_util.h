/* Helpers shared by the tests. */
#ifndef GLINT_TEST_UTIL_H
#define GLINT_TEST_UTIL_H

#include <setjmp.h>
#include <stdio.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "glint.h"

#define ASSERT_OK(call)                                                        \
  do {                                                                         \
    glint_error e_;                                                            \
    e_.message[0] = '\0';                                                      \
    glint_status st_ = (call);                                                 \
    if (st_ != GLINT_OK)                                                       \
      fail_msg("%s failed: %s", #call, e_.message);                            \
  } while (0)

/* A new scene holding one material, glint_material_default's; its id in
 * *material. */
static inline glint_scene *scene_with_default_material(uint32_t *material) {
  glint_scene *g;
  ASSERT_OK(glint_scene_create(&g, &e_));
  glint_material mat;
  glint_material_default(&mat);
  ASSERT_OK(glint_scene_add_material(g, &mat, material, &e_));
  return g;
}

/* Expected 8-bit value of a linear colour channel: round(255 c)
 * (docs/specification.md §4). */
static inline int expected_byte(double c) {
  if (c <= 0)
    return 0;
  if (c >= 1)
    return 255;
  return (int)(255 * c + 0.5);
}

/* Whether this CPU (or GLINT_ISA) lacks backend b; says so when it does, so
 * that a run shows what it did not test. */
static inline int backend_missing(glint_backend b) {
  if (glint_backend_supported(b))
    return 0;
  printf("%s: SKIPPED (not on this CPU)\n", glint_backend_name(b));
  return 1;
}

/* The exit code for "this test cannot run here" (ctest reports SKIPPED). */
#define SKIP_EXIT 77

/* A seeded uniform number in [0, 1) (a 64-bit linear congruential
 * generator, Knuth's constants): the random rays of the tests, repeatable. */
static inline double uniform(unsigned long long *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

#endif
