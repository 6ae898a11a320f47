#include "scene/text.h"

#include "core/error.h"
#include "scene/file.h"
#include "scene/number.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_FILE_BYTES ((size_t)4 << 30)

glint_status text_open(text_file *t, const char *path, char comment,
                       glint_error *error) {
  memset(t, 0, sizeof *t);
  t->path = path;
  t->comment = comment;
  t->line = 1;
  char *data;
  size_t size;
  glint_status st = file_read_all(path, MAX_FILE_BYTES, &data, &size, error);
  if (st != GLINT_OK)
    return st;
  if ((st = file_check_text(path, data, size, 1, error)) != GLINT_OK) {
    free(data);
    return st;
  }
  t->data = data;
  t->size = size;
  t->pos = data;
  return GLINT_OK;
}

void text_close(text_file *t) {
  free(t->data);
  t->data = NULL;
}

/* Skips white space and comments; stops at a newline if `stop_at_eol`. */
static void skip(text_file *t, int stop_at_eol) {
  for (;;) {
    char c = *t->pos;
    if (c == '\n') {
      if (stop_at_eol)
        return;
      t->line++;
      t->pos++;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      t->pos++;
    } else if (c != 0 && c == t->comment) {
      while (*t->pos && *t->pos != '\n')
        t->pos++;
    } else {
      return;
    }
  }
}

static int is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' ||
         c == '\v';
}

const char *text_span(text_file *t, size_t *len) {
  skip(t, 0);
  t->token_line = t->line;
  const char *start = t->pos, *p = start;
  if (!*p)
    return NULL;
  char comment = t->comment;
  while (*p && !is_space(*p) && !(comment && *p == comment))
    p++;
  t->pos = p;
  *len = (size_t)(p - start);
  return start;
}

const char *text_token(text_file *t, char *buf, size_t size) {
  size_t n;
  const char *tok = text_span(t, &n);
  if (!tok)
    return NULL;
  if (n >= size) /* longer than any word the caller knows: shown cut */
    n = size - 1;
  memcpy(buf, tok, n);
  buf[n] = '\0';
  return buf;
}

/* A token for a message: at most 40 characters, "..." when cut. */
static void quote(char *out, size_t size, const char *tok, size_t len) {
  if (len > 40)
    snprintf(out, size, "%.40s...", tok);
  else
    snprintf(out, size, "%.*s", (int)len, tok);
}

int text_more_on_line(text_file *t) {
  skip(t, 1);
  return *t->pos && *t->pos != '\n';
}

glint_status text_number(text_file *t, const char *what, double *out,
                         glint_error *error) {
  size_t len;
  const char *tok = text_span(t, &len);
  if (!tok)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s:%d: the file ends where %s was expected", t->path,
                    t->line, what);
  int r = number_parse(tok, len, out);
  if (r == NUMBER_OK)
    return GLINT_OK;
  char shown[48];
  quote(shown, sizeof shown, tok, len);
  if (r == NUMBER_BAD)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s:%d: expected a number for %s, found '%s'", t->path,
                    t->token_line, what, shown);
  return gli_fail(error, GLINT_E_PARSE,
                  "%s:%d: %s is '%s', not a finite number", t->path,
                  t->token_line, what, shown);
}

glint_status text_vec3(text_file *t, const char *what, glint_vec3 *out,
                       glint_error *error) {
  glint_status st;
  if ((st = text_number(t, what, &out->x, error)) ||
      (st = text_number(t, what, &out->y, error)) ||
      (st = text_number(t, what, &out->z, error)))
    return st;
  return GLINT_OK;
}

glint_status text_int(text_file *t, const char *what, long min, long max,
                      long *out, glint_error *error) {
  size_t len;
  const char *span = text_span(t, &len);
  if (!span)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s:%d: the file ends where %s was expected", t->path,
                    t->line, what);
  char buf[48];
  const char *tok = buf;
  if (len > 40) { /* no whole number a scene needs is this long */
    quote(buf, sizeof buf, span, len);
    return gli_fail(error, GLINT_E_PARSE,
                    "%s:%d: expected a whole number for %s, found '%s'",
                    t->path, t->token_line, what, tok);
  }
  memcpy(buf, span, len);
  buf[len] = '\0';
  char *end;
  errno = 0;
  long v = strtol(tok, &end, 10);
  if (end == tok || *end != '\0' || errno == ERANGE)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s:%d: expected a whole number for %s, found '%s'",
                    t->path, t->token_line, what, tok);
  if (v < min || v > max)
    return gli_fail(error, GLINT_E_PARSE, "%s:%d: %s is %ld, outside %ld..%ld",
                    t->path, t->token_line, what, v, min, max);
  *out = v;
  return GLINT_OK;
}
