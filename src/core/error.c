#include "core/error.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A message is one line of text whatever it quotes: a control character
 * from a file name or a scene (an escape sequence, a newline) is shown as
 * '?', and a message longer than the buffer keeps its start and its end,
 * where the problem is said ("PATH: No such file or directory" after a
 * path of 5000 characters), with "..." between. */
static void set_message(char *out, size_t size, const char *format,
                        va_list args) {
  va_list again;
  va_copy(again, args);
  int n = vsnprintf(out, size, format, args);
  char *whole = n >= (int)size ? malloc((size_t)n + 1) : NULL;
  if (whole) {
    vsnprintf(whole, (size_t)n + 1, format, again);
    size_t head = size / 2 - 3, tail = size - 1 - head - 3;
    memcpy(out, whole, head);
    memcpy(out + head, "...", 3);
    memcpy(out + head + 3, whole + n - tail, tail + 1);
    free(whole);
  }
  va_end(again);
  for (unsigned char *p = (unsigned char *)out; *p; p++)
    if (*p < 0x20 || *p == 0x7f)
      *p = '?';
}

glint_status gli_fail(glint_error *error, glint_status status,
                      const char *format, ...) {
  if (error) {
    va_list args;
    va_start(args, format);
    set_message(error->message, sizeof error->message, format, args);
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
