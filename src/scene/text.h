/* Reading text scene and mesh files: the whole file in memory (gzip
 * transparently), tokens that know their line, numbers checked in full, and
 * errors as "FILE:LINE: what is wrong". */
#ifndef GLINT_SCENE_TEXT_H
#define GLINT_SCENE_TEXT_H

#include "glint.h"

#include <stddef.h>

typedef struct text_file {
  const char *path;
  char *data; /* NUL-terminated */
  size_t size;
  const char *pos;
  int line;       /* of the next character */
  int token_line; /* of the last token read */
  char comment;   /* starts a comment to the end of the line; 0: none */
} text_file;

/* Reads `path` (decompressing .gz) into memory. */
glint_status text_open(text_file *t, const char *path, char comment,
                       glint_error *error);
void text_close(text_file *t);

/* The next white-space separated token (copied into buf), or NULL at the
 * end of the file. */
/* The next token (white space and comments skipped) in place: its first
 * character and *len; NULL at the end of the file. */
const char *text_span(text_file *t, size_t *len);
/* The next token copied into buf (cut to size - 1 characters). */
const char *text_token(text_file *t, char *buf, size_t size);

/* Whether another token follows on the current line. */
int text_more_on_line(text_file *t);

/* The next token as a finite number; `what` names it in errors. */
glint_status text_number(text_file *t, const char *what, double *out,
                         glint_error *error);
glint_status text_vec3(text_file *t, const char *what, glint_vec3 *out,
                       glint_error *error);
/* The next token as a whole number in [min, max]. */
glint_status text_int(text_file *t, const char *what, long min, long max,
                      long *out, glint_error *error);

#endif
