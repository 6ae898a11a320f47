#include "scene/file.h"

#include "core/error.h"
#include "core/memory.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

/* strerror_r (XSI), not strerror: scenes may be loaded on several threads. */
static glint_status io_fail(glint_error *e, const char *path, const char *what,
                            int err) {
  char buf[256];
  if (strerror_r(err, buf, sizeof buf) != 0)
    snprintf(buf, sizeof buf, "error %d", err);
  return gli_fail(e, gli_errno_status(err), "%s: %s%s", path, what, buf);
}

static glint_status too_large(glint_error *e, const char *path,
                              size_t max_bytes) {
  if (max_bytes >= (size_t)1 << 30 && max_bytes % ((size_t)1 << 30) == 0)
    return gli_fail(e, GLINT_E_IO, "%s: larger than %zu GiB", path,
                    max_bytes >> 30);
  return gli_fail(e, GLINT_E_IO, "%s: larger than %zu bytes", path, max_bytes);
}

/* A compressed file may unpack to at most this many times its own size
 * beyond the first UNPACK_FREE bytes. Scenes and meshes unpack to 2-10
 * times theirs (numbers are dense: the SPD dragon's PLY 3.3 times); a file
 * of little but repetition, such as a gigabyte of blanks in a few
 * megabytes, would otherwise be held whole in memory up to max_bytes before
 * its parser could refuse it, and one of a sphere repeated (250 MB of it
 * in 0.5 MB) would become 25 million spheres and gigabytes of scene. */
#define UNPACK_RATIO 32
#define UNPACK_FREE ((size_t)16 << 20)

/* A text file's first read, which a binary file fails. */
#define FIRST_TEXT_BYTES ((size_t)64 << 10)

/* The bytes read so far, growing by doubling, with room for a NUL. */
typedef struct file_buffer {
  char *data;
  size_t size, cap; /* cap: at most max_bytes + 1, to see a file is more */
} file_buffer;

/* Room for at least one more byte, the capacity doubled or made `want`
 * (the size a file says it has); 0, or -1 out of memory. */
static int buffer_grow(file_buffer *b, size_t want, size_t max_bytes) {
  if (b->size < b->cap)
    return 0;
  size_t cap = b->cap * 2 > want ? b->cap * 2 : want;
  cap = cap < max_bytes + 1 ? cap : max_bytes + 1;
  char *bigger = realloc(b->data, cap + 1);
  if (!bigger)
    return -1;
  gli_advise_huge(bigger, cap + 1);
  b->data = bigger;
  b->cap = cap;
  return 0;
}

/* Takes the `n` bytes just read at b->size: a text file's NUL, or a file
 * past max_bytes, is an error. */
static glint_status buffer_take(file_buffer *b, size_t n, const char *path,
                                size_t max_bytes, int text, glint_error *e) {
  if (text && memchr(b->data + b->size, '\0', n))
    return gli_file_check_text(path, b->data, b->size + n, 1, e);
  b->size += n;
  return b->size > max_bytes ? too_large(e, path, max_bytes) : GLINT_OK;
}

/* A plain file: past the limit refused unread (a sparse file of gigabytes
 * was read whole first, up to the limit: seconds and as many gigabytes of
 * memory); it fits exactly, a text one once its first part is read and
 * has no NUL. */
static glint_status read_plain(FILE *raw, const char *path, off_t file_size,
                               size_t max_bytes, int text, file_buffer *b,
                               glint_error *e) {
  if ((uintmax_t)file_size > max_bytes)
    return too_large(e, path, max_bytes);
  size_t full = (size_t)file_size + 1;
  if (full < FIRST_TEXT_BYTES)
    full = FIRST_TEXT_BYTES;
  if (full > max_bytes + 1)
    full = max_bytes + 1;
  b->cap = text && full > FIRST_TEXT_BYTES ? FIRST_TEXT_BYTES : full;
  b->data = malloc(b->cap + 1);
  for (;;) {
    if (!b->data || buffer_grow(b, full, max_bytes))
      return gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
    errno = 0;
    size_t n = fread(b->data + b->size, 1, b->cap - b->size, raw);
    if (n == 0)
      return ferror(raw)
                 ? io_fail(e, path, "cannot read: ", errno ? errno : EIO)
                 : GLINT_OK;
    glint_status st = buffer_take(b, n, path, max_bytes, text, e);
    if (st)
      return st;
  }
}

/* A gzip file, inflated in one pass: members may follow each other (gzip
 * concatenates them), and anything else after the last is an error (zlib's
 * gzread ignores it without a word; a check that trusted a file whose last
 * four bytes were its unpacked length let a crafted file lose what
 * followed its first member). */
static glint_status read_gzip(FILE *raw, const char *path, off_t file_size,
                              size_t max_bytes, int text, file_buffer *b,
                              glint_error *e) {
  enum { CHUNK = 1 << 17 };
  unsigned char *in = malloc(CHUNK);
  b->cap = FIRST_TEXT_BYTES < max_bytes + 1 ? FIRST_TEXT_BYTES : max_bytes + 1;
  b->data = malloc(b->cap + 1);
  z_stream z;
  memset(&z, 0, sizeof z);
  if (!in || !b->data || inflateInit2(&z, 15 + 16) != Z_OK) {
    free(in);
    return gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
  }
  glint_status st = GLINT_OK;
  int in_member = 1, at_end = 0;
  unsigned long long read = 0; /* compressed bytes read from the file */
  while (!st) {
    /* input: at least the two bytes of a member's magic after a member */
    if (z.avail_in < (in_member ? 1u : 2u) && !at_end) {
      if (z.avail_in)
        memmove(in, z.next_in, z.avail_in);
      errno = 0;
      size_t n = fread(in + z.avail_in, 1, CHUNK - z.avail_in, raw);
      if (n == 0 && ferror(raw)) {
        st = io_fail(e, path, "cannot read: ", errno ? errno : EIO);
        break;
      }
      at_end = n == 0;
      read += n;
      z.next_in = in;
      z.avail_in += (uInt)n;
      continue;
    }
    if (!in_member) {
      if (z.avail_in == 0)
        break; /* the end, after a whole member */
      if (z.avail_in < 2 || z.next_in[0] != 0x1f || z.next_in[1] != 0x8b) {
        st = gli_fail(e, GLINT_E_PARSE,
                      "%s: data after the end of the compressed stream "
                      "(a damaged or appended-to file)",
                      path);
        break;
      }
      if (inflateReset(&z) != Z_OK) {
        st = gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
        break;
      }
      in_member = 1;
    }
    if (z.avail_in == 0 && at_end) {
      st = gli_fail(e, GLINT_E_PARSE, "%s: the compressed file is truncated",
                    path);
      break;
    }
    if (buffer_grow(b, 0, max_bytes)) {
      st = gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
      break;
    }
    size_t room = b->cap - b->size;
    z.next_out = (Bytef *)b->data + b->size;
    z.avail_out = (uInt)(room < (1u << 30) ? room : 1u << 30);
    uInt before = z.avail_out;
    int zr = inflate(&z, Z_NO_FLUSH);
    if (zr == Z_DATA_ERROR || zr == Z_NEED_DICT) {
      st = gli_fail(e, GLINT_E_PARSE, "%s: damaged compressed file: %s", path,
                    z.msg ? z.msg : "bad data");
      break;
    }
    if (zr == Z_MEM_ERROR) {
      st = gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
      break;
    }
    st = buffer_take(b, before - z.avail_out, path, max_bytes, text, e);
    /* Against what has been unpacked from, not the file's size, which a
     * file with a hole (truncate -s 200G) or data appended after its
     * members makes as large as it likes: such a file of 5 MB unpacked
     * 4 GiB of blanks, in 25-50 s, before its end was reached. */
    unsigned long long used = read - z.avail_in;
    if (!st && b->size > UNPACK_FREE && b->size / UNPACK_RATIO > used)
      st = gli_fail(e, GLINT_E_PARSE,
                    "%s: unpacks to more than %d times its compressed size "
                    "(%zu bytes from the first %llu of its %lld): too "
                    "repetitive for a scene or mesh",
                    path, UNPACK_RATIO, b->size, used, (long long)file_size);
    if (zr == Z_STREAM_END)
      in_member = 0;
  }
  inflateEnd(&z);
  free(in);
  return st;
}

glint_status gli_file_read_all(const char *path, size_t max_bytes, int text,
                               char **out, size_t *out_size, glint_error *e) {
  struct stat sb;
  if (stat(path, &sb) != 0)
    return io_fail(e, path, "", errno);
  if (!S_ISREG(sb.st_mode))
    return gli_fail(e, GLINT_E_IO, "%s: not a regular file", path);
  errno = 0;
  FILE *raw = fopen(path, "rb");
  if (!raw)
    return errno ? io_fail(e, path, "", errno)
                 : gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
  /* gzip by its magic, whatever the name */
  unsigned char magic[2];
  int gzip =
      fread(magic, 1, 2, raw) == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
  rewind(raw);
  file_buffer b = {NULL, 0, 0};
  glint_status st =
      gzip ? read_gzip(raw, path, sb.st_size, max_bytes, text, &b, e)
           : read_plain(raw, path, sb.st_size, max_bytes, text, &b, e);
  fclose(raw);
  if (st) {
    free(b.data);
    return st;
  }
  b.data[b.size] = '\0';
  *out = b.data;
  *out_size = b.size;
  return GLINT_OK;
}

glint_status gli_file_source_read(const gli_file_source *source,
                                  const char *path, size_t max_bytes, int text,
                                  char **data, size_t *size,
                                  glint_error *error) {
  if (!source)
    return gli_file_read_all(path, max_bytes, text, data, size, error);
  return source->read(source->context, path, max_bytes, text, data, size,
                      error);
}

void gli_file_skip_bom(const char **data, size_t *size) {
  if (*size >= 3 && memcmp(*data, "\xEF\xBB\xBF", 3) == 0) {
    *data += 3;
    *size -= 3;
  }
}

void gli_text_line_column(const char *data, const char *at, size_t first_line,
                          size_t *line, size_t *column) {
  *line = first_line;
  *column = 1;
  for (const char *p = data; p < at; p++) {
    if (*p == '\n' || (*p == '\r' && p[1] != '\n')) {
      (*line)++;
      *column = 1;
    } else if (((unsigned char)*p & 0xC0) != 0x80) {
      (*column)++;
    }
  }
}

glint_status gli_file_check_text(const char *path, const char *data,
                                 size_t size, size_t first_line,
                                 glint_error *e) {
  const unsigned char *u = (const unsigned char *)data;
  if (first_line == 1 && size >= 2 &&
      ((u[0] == 0xFF && u[1] == 0xFE) || (u[0] == 0xFE && u[1] == 0xFF)))
    return gli_fail(e, GLINT_E_PARSE,
                    "%s: UTF-16 text; glint reads text files in UTF-8", path);
  const char *nul = memchr(data, '\0', size);
  if (!nul)
    return GLINT_OK;
  size_t line, column;
  gli_text_line_column(data, nul, first_line, &line, &column);
  return gli_fail(e, GLINT_E_PARSE,
                  "%s:%zu:%zu: a NUL byte: binary data where text was expected",
                  path, line, column);
}
