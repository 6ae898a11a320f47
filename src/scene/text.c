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

glint_status gli_text_begin(text_file *t, const char *path, const char *data,
                            size_t size, char comment, glint_error *error) {
  memset(t, 0, sizeof *t);
  t->path = path;
  t->comment = comment;
  t->line = 1;
  glint_status st = gli_file_check_text(path, data, size, 1, error);
  if (st != GLINT_OK)
    return st;
  t->data = data;
  t->size = size;
  t->pos = data;
  size_t rest = size;
  gli_file_skip_bom(&t->pos, &rest);
  return GLINT_OK;
}

/* Skips white space and comments; stops at a newline if `stop_at_eol`. */
/* A line ends at LF, CR LF, or a CR alone (old Mac files). */
static int at_line_end(const char *p) {
  return *p == '\n' || (*p == '\r' && p[1] != '\n');
}

static void skip(text_file *t, int stop_at_eol) {
  for (;;) {
    char c = *t->pos;
    if (at_line_end(t->pos)) {
      if (stop_at_eol)
        return;
      t->line++;
      t->pos++;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      t->pos++;
    } else if (c != 0 && c == t->comment) {
      while (*t->pos && !at_line_end(t->pos))
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

const char *gli_text_span(text_file *t, size_t *len) {
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

const char *gli_text_token(text_file *t, char *buf, size_t size) {
  size_t n;
  const char *tok = gli_text_span(t, &n);
  if (!tok)
    return NULL;
  if (n >= size) /* longer than any word the caller knows: shown cut */
    n = size - 1;
  memcpy(buf, tok, n);
  buf[n] = '\0';
  return buf;
}

/* A piece of the file for an error message: at most about 40 bytes, with
 * anything unprintable as '?', so that binary garbage cannot garble it. */
const char *gli_text_quote(char *buf, size_t cap, const char *s, size_t len) {
  size_t max = cap - 4, n = len < max ? len : max;
  for (size_t i = 0; i < n; i++) {
    unsigned char ch = (unsigned char)s[i];
    buf[i] = ch >= 0x20 && ch < 0x7f ? (char)ch : '?';
  }
  if (len > n) {
    memcpy(buf + n, "...", 3);
    n += 3;
  }
  buf[n] = '\0';
  return buf;
}

/* A whole number: optional sign and 1..18 digits (enough for any index,
 * and no overflow). Advances *s; -1 when there is none. */
int gli_text_parse_whole(const char **s, const char *end, long long *out) {
  const char *p = *s;
  int neg = 0;
  if (p < end && (*p == '-' || *p == '+'))
    neg = *p++ == '-';
  const char *digits = p;
  long long v = 0;
  while (p < end && *p >= '0' && *p <= '9') {
    if (p - digits >= 18)
      return GLI_TEXT_TOO_LONG;
    v = v * 10 + (*p++ - '0');
  }
  if (p == digits)
    return -1;
  *s = p;
  *out = neg ? -v : v;
  return 0;
}

int gli_text_more_on_line(text_file *t) {
  skip(t, 1);
  return *t->pos && !at_line_end(t->pos);
}

/* The file ended where `what` was expected: said at the line of the last
 * token, `last` (the statement that ends too soon), not the line after the
 * file's last one. */
static glint_status file_ends(const text_file *t, long last, const char *what,
                              glint_error *error) {
  return gli_fail(error, GLINT_E_PARSE,
                  "%s:%ld: the file ends where %s was expected", t->path,
                  last > 0 ? last : t->line, what);
}

/* `kind` ("a number", "a whole number") expected for `what`, `shown` found
 * instead. A word on a later line than the token before (`last`): most
 * likely the line before ended a number short (the next entity's name),
 * said at that line, naming both. */
static glint_status not_a_number(const text_file *t, long last,
                                 const char *kind, const char *what,
                                 const char *shown, glint_error *error) {
  if (last > 0 && t->token_line > last)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s:%ld: expected %s for %s, found the end of the line "
                    "(line %ld begins '%s')",
                    t->path, last, kind, what, t->token_line, shown);
  return gli_fail(error, GLINT_E_PARSE,
                  "%s:%ld: expected %s for %s, found '%s'", t->path,
                  t->token_line, kind, what, shown);
}

glint_status gli_text_number(text_file *t, const char *what, double *out,
                             glint_error *error) {
  size_t len;
  long last = t->token_line;
  const char *tok = gli_text_span(t, &len);
  if (!tok)
    return file_ends(t, last, what, error);
  int r = gli_number_parse(tok, len, out);
  if (r == NUMBER_OK)
    return GLINT_OK;
  char shown[48];
  gli_text_quote(shown, sizeof shown, tok, len);
  if (r == NUMBER_BAD)
    return not_a_number(t, last, "a number", what, shown, error);
  return gli_fail(error, GLINT_E_PARSE,
                  "%s:%ld: %s is '%s', not a finite number", t->path,
                  t->token_line, what, shown);
}

glint_status gli_text_vec3(text_file *t, const char *what, glint_vec3 *out,
                           glint_error *error) {
  glint_status st;
  if ((st = gli_text_number(t, what, &out->x, error)) ||
      (st = gli_text_number(t, what, &out->y, error)) ||
      (st = gli_text_number(t, what, &out->z, error)))
    return st;
  return GLINT_OK;
}

glint_status gli_text_int(text_file *t, const char *what, long min, long max,
                          long *out, glint_error *error) {
  size_t len;
  long last = t->token_line;
  const char *span = gli_text_span(t, &len);
  if (!span)
    return file_ends(t, last, what, error);
  char buf[48];
  const char *tok = buf;
  if (len > 40) { /* no whole number a scene needs is this long */
    gli_text_quote(buf, sizeof buf, span, len);
    return gli_fail(error, GLINT_E_PARSE,
                    "%s:%ld: expected a whole number for %s, found '%s'",
                    t->path, t->token_line, what, tok);
  }
  memcpy(buf, span, len);
  buf[len] = '\0';
  char *end;
  errno = 0;
  long v = strtol(tok, &end, 10);
  if (end == tok || *end != '\0' || errno == ERANGE) {
    double any; /* a word, not a number of another kind: maybe a line short */
    int word = gli_number_parse(span, len, &any) == NUMBER_BAD;
    return not_a_number(t, word ? last : 0, "a whole number", what, tok, error);
  }
  if (v < min || v > max)
    return gli_fail(error, GLINT_E_PARSE, "%s:%ld: %s is %ld, outside %ld..%ld",
                    t->path, t->token_line, what, v, min, max);
  *out = v;
  return GLINT_OK;
}
