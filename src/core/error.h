/* Error reporting: every fallible internal function takes a glint_error * that
 * may be NULL and fills it through gli_fail(). */
#ifndef GLINT_CORE_ERROR_H
#define GLINT_CORE_ERROR_H

#include "glint.h"

#if defined(__GNUC__)
#define GLI_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define GLI_PRINTF(f, a)
#endif

/* Records status and a printf-formatted message; returns status. */
glint_status gli_fail(glint_error *error, glint_status status,
                      const char *format, ...) GLI_PRINTF(3, 4);

/* The status of a failed system call: GLINT_E_MEMORY where it ran out of
 * memory (ENOMEM), GLINT_E_IO otherwise. */
glint_status gli_errno_status(int err);

/* Refuses a NULL pointer argument p of a public function, naming both by
 * glint.h's names: "glint_render: image is NULL". */
#define GLI_NOT_NULL(p, name, error)                                           \
  do {                                                                         \
    if (!(p))                                                                  \
      return gli_fail((error), GLINT_E_ARGUMENT, "%s: %s is NULL", __func__,   \
                      name);                                                   \
  } while (0)

/* Clears an error record (status GLINT_OK, empty message). */
void gli_error_clear(glint_error *error);

#endif
