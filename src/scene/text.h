/* Reading text scene and mesh files: the whole file in memory (gzip
 * transparently), tokens that know their line, numbers checked in full, and
 * errors as "FILE:LINE: what is wrong". */
#ifndef GLINT_SCENE_TEXT_H
#define GLINT_SCENE_TEXT_H

#include "glint.h"

#include <stddef.h>

typedef struct text_file {
  const char *path;
  const char *data; /* NUL-terminated; the caller's */
  size_t size;
  const char *pos;
  long line;       /* of the next character */
  long token_line; /* of the last token read */
  char comment;    /* starts a comment to the end of the line; 0: none */
} text_file;

/* Reads the file's bytes `data` (`size` of them and then a NUL, kept by
 * the caller while t is in use); `path` names the file in messages. Text
 * only: binary data is an error. */
glint_status gli_text_begin(text_file *t, const char *path, const char *data,
                            size_t size, char comment, glint_error *error);

/* The next token (white space and comments skipped) in place: its first
 * character and *len; NULL at the end of the file. */
const char *gli_text_span(text_file *t, size_t *len);
/* The next token copied into buf (cut to size - 1 characters). */
const char *gli_text_token(text_file *t, char *buf, size_t size);

/* Whether another token follows on the current line. */
int gli_text_more_on_line(text_file *t);

/* The next token as a finite number; `what` names it in errors. */
glint_status gli_text_number(text_file *t, const char *what, double *out,
                             glint_error *error);
glint_status gli_text_vec3(text_file *t, const char *what, glint_vec3 *out,
                           glint_error *error);
/* The next token as a whole number in [min, max]. */
glint_status gli_text_int(text_file *t, const char *what, long min, long max,
                          long *out, glint_error *error);

/* Pieces shared with the mesh readers, which scan their own buffers. */
/* A piece of the file for an error message, in buf: at most cap - 4 bytes
 * then "...", anything unprintable as '?', so that binary garbage cannot
 * garble the message. Returns buf. */
const char *gli_text_quote(char *buf, size_t cap, const char *s, size_t len);
/* White space within a line (inline: the mesh readers ask it of every
 * byte, and a call each was 6% of the dragon's load). */
static inline int gli_text_is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}
/* A whole number: optional sign and 1..18 digits (enough for any index,
 * and no overflow). Advances *s; -1 when there is none, -2 when it has
 * more digits (GLI_TEXT_TOO_LONG). */
#define GLI_TEXT_TOO_LONG (-2)
int gli_text_parse_whole(const char **s, const char *end, long long *out);

#endif
