#include "core/error.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>

glint_status gli_fail(glint_error *error, glint_status status,
                      const char *format, ...) {
  if (error) {
    va_list args;
    va_start(args, format);
    vsnprintf(error->message, sizeof error->message, format, args);
    va_end(args);
    error->status = status;
  }
  return status;
}

glint_status gli_errno_status(int err) {
  return err == ENOMEM ? GLINT_E_MEMORY : GLINT_E_IO;
}

void gli_error_clear(glint_error *error) {
  if (error) {
    error->status = GLINT_OK;
    error->message[0] = '\0';
  }
}

const char *glint_status_name(glint_status status) {
  switch (status) {
  case GLINT_OK: return "ok";
  case GLINT_E_ARGUMENT: return "argument";
  case GLINT_E_UNSUPPORTED: return "unsupported";
  case GLINT_E_IO: return "io";
  case GLINT_E_PARSE: return "parse";
  case GLINT_E_MEMORY: return "memory";
  case GLINT_E_CANCELLED: return "cancelled";
  }
  return "unknown";
}

const char *glint_version(void) {
#define GLI_STR2(x) #x
#define GLI_STR(x) GLI_STR2(x)
  return GLI_STR(GLINT_VERSION_MAJOR) "." GLI_STR(
      GLINT_VERSION_MINOR) "." GLI_STR(GLINT_VERSION_PATCH);
}
