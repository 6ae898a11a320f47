#include "scene/text.h"

#include "core/error.h"
#include "scene/file.h"
#include "scene/number.h"

#include <ctype.h>
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

const char *text_token(text_file *t, char *buf, size_t size) {
  skip(t, 0);
  t->token_line = t->line;
  if (!*t->pos)
    return NULL;
  size_t n = 0;
  while (*t->pos && !isspace((unsigned char)*t->pos) &&
         !(t->comment && *t->pos == t->comment)) {
    if (n + 1 < size)
      buf[n++] = *t->pos;
    t->pos++;
  }
  buf[n] = '\0';
  return buf;
}

int text_more_on_line(text_file *t) {
  skip(t, 1);
  return *t->pos && *t->pos != '\n';
}

glint_status text_number(text_file *t, const char *what, double *out,
                         glint_error *error) {
  char buf[128];
  const char *tok = text_token(t, buf, sizeof buf);
  if (!tok)
    return gli_fail(error, GLINT_E_PARSE,
                      "%s:%d: the file ends where %s was expected", t->path,
                      t->line, what);
  int r = number_parse(tok, strlen(tok), out);
  if (r == NUMBER_BAD)
    return gli_fail(error, GLINT_E_PARSE,
                      "%s:%d: expected a number for %s, found '%s'", t->path,
                      t->token_line, what, tok);
  if (r == NUMBER_NOT_FINITE)
    return gli_fail(error, GLINT_E_PARSE,
                      "%s:%d: %s is '%s', not a finite number", t->path,
                      t->token_line, what, tok);
  return GLINT_OK;
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
  char buf[128];
  const char *tok = text_token(t, buf, sizeof buf);
  if (!tok)
    return gli_fail(error, GLINT_E_PARSE,
                      "%s:%d: the file ends where %s was expected", t->path,
                      t->line, what);
  char *end;
  errno = 0;
  long v = strtol(tok, &end, 10);
  if (end == tok || *end != '\0' || errno == ERANGE)
    return gli_fail(error, GLINT_E_PARSE,
                      "%s:%d: expected a whole number for %s, found '%s'",
                      t->path, t->token_line, what, tok);
  if (v < min || v > max)
    return gli_fail(error, GLINT_E_PARSE,
                      "%s:%d: %s is %ld, outside %ld..%ld", t->path,
                      t->token_line, what, v, min, max);
  *out = v;
  return GLINT_OK;
}
