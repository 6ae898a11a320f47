#include "scene/file.h"

#include "core/error.h"

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

/* Whether the gzip file at `path` has bytes after its last member, which
 * gzread ignores without a word: -1 when it cannot tell (reading failed).
 * Members may follow each other (gzip concatenates them); anything else
 * is garbage. Each member is inflated into a scratch buffer to find its
 * end. */
static int gzip_trailing_garbage(const char *path) {
  enum { CHUNK = 1 << 16 };
  FILE *raw = fopen(path, "rb");
  unsigned char *in = malloc(2 * CHUNK), *scratch = in + CHUNK;
  z_stream z;
  memset(&z, 0, sizeof z);
  if (!raw || !in || inflateInit2(&z, 15 + 16) != Z_OK) {
    if (raw)
      fclose(raw);
    free(in);
    return -1;
  }
  int verdict = -1, ended = 0;
  for (;;) {
    if (z.avail_in == 0) {
      size_t n = fread(in, 1, CHUNK, raw);
      if (n == 0) {
        verdict = ended ? 0 : -1;
        break;
      }
      z.next_in = in;
      z.avail_in = (uInt)n;
    }
    if (ended) { /* what follows a member: another, or garbage */
      if (z.avail_in < 2 && !feof(raw)) {
        memmove(in, z.next_in, z.avail_in);
        size_t n = fread(in + z.avail_in, 1, CHUNK - z.avail_in, raw);
        z.next_in = in;
        z.avail_in += (uInt)n;
      }
      if (z.avail_in < 2 || z.next_in[0] != 0x1f || z.next_in[1] != 0x8b) {
        verdict = 1;
        break;
      }
      if (inflateReset(&z) != Z_OK)
        break;
      ended = 0;
    }
    z.next_out = scratch;
    z.avail_out = CHUNK;
    int zr = inflate(&z, Z_NO_FLUSH);
    if (zr == Z_STREAM_END)
      ended = 1;
    else if (zr != Z_OK && zr != Z_BUF_ERROR)
      break;
  }
  inflateEnd(&z);
  fclose(raw);
  free(in);
  return verdict;
}

glint_status gli_file_read_all(const char *path, size_t max_bytes, int text,
                               char **out, size_t *out_size, glint_error *e) {
  struct stat sb;
  if (stat(path, &sb) != 0)
    return io_fail(e, path, "", errno);
  if (!S_ISREG(sb.st_mode))
    return gli_fail(e, GLINT_E_IO, "%s: not a regular file", path);
  errno = 0;
  gzFile f = gzopen(path, "rb");
  if (!f)
    return errno ? io_fail(e, path, "", errno)
                 : gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
  gzbuffer(f, 1 << 17);
  /* A plain file past the limit is refused unread (a sparse file of
   * gigabytes was read whole first, up to the limit: seconds and as many
   * gigabytes of memory). gzdirect reads the first bytes to tell. */
  if ((uintmax_t)sb.st_size > max_bytes && gzdirect(f)) {
    gzclose(f);
    return too_large(e, path, max_bytes);
  }
  /* A plain file fits exactly (a text one once its first part is read and
   * has no NUL); a compressed one grows by doubling. The capacity is one
   * more than allowed, to see that a file is more. */
  size_t full = (size_t)sb.st_size + 1, size = 0;
  if (full < FIRST_TEXT_BYTES)
    full = FIRST_TEXT_BYTES;
  if (full > max_bytes + 1)
    full = max_bytes + 1;
  size_t cap = text && full > FIRST_TEXT_BYTES ? FIRST_TEXT_BYTES : full;
  char *data = malloc(cap + 1);
  for (;;) {
    if (!data) {
      gzclose(f);
      return gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
    }
    size_t want = cap - size;
    int n =
        gzread(f, data + size, (unsigned)(want < (1u << 30) ? want : 1u << 30));
    if (n < 0) {
      int zerr;
      const char *msg = gzerror(f, &zerr);
      /* zlib's message starts with the path we are about to print. */
      size_t plen = strlen(path);
      if (strncmp(msg, path, plen) == 0 && msg[plen] == ':')
        msg += plen + (msg[plen + 1] == ' ' ? 2 : 1);
      glint_status st =
          zerr == Z_ERRNO
              ? io_fail(e, path, "cannot read: ", errno ? errno : EIO)
              : gli_fail(e, GLINT_E_PARSE, "%s: damaged compressed file: %s",
                         path, msg);
      gzclose(f);
      free(data);
      return st;
    }
    if (text && memchr(data + size, '\0', (size_t)n)) {
      glint_status st = gli_file_check_text(path, data, size + (size_t)n, 1, e);
      gzclose(f);
      free(data);
      return st;
    }
    size += (size_t)n;
    if (size > max_bytes) {
      gzclose(f);
      free(data);
      return too_large(e, path, max_bytes);
    }
    if (size > UNPACK_FREE && size / UNPACK_RATIO > (size_t)sb.st_size &&
        !gzdirect(f)) {
      gzclose(f);
      free(data);
      return gli_fail(e, GLINT_E_PARSE,
                      "%s: unpacks to more than %d times its compressed size "
                      "(%lld bytes): too repetitive for a scene or mesh",
                      path, UNPACK_RATIO, (long long)sb.st_size);
    }
    if (n == 0)
      break;
    if (size == cap) {
      cap = cap * 2 > full ? cap * 2 : full;
      cap = cap < max_bytes + 1 ? cap : max_bytes + 1;
      char *bigger = realloc(data, cap + 1);
      if (!bigger)
        free(data);
      data = bigger;
    }
  }
  /* A truncated gzip stream reads as a short file without an error from
   * gzread; only gzclose_r reports it. */
  int direct = gzdirect(f);
  int zst = gzclose_r(f);
  if (zst != Z_OK) {
    free(data);
    if (zst == Z_BUF_ERROR)
      return gli_fail(e, GLINT_E_PARSE, "%s: the compressed file is truncated",
                      path);
    /* Only the system failing to read is I/O; bad data is the file's. */
    return zst == Z_ERRNO
               ? io_fail(e, path, "cannot read: ", errno ? errno : EIO)
               : gli_fail(e, GLINT_E_PARSE, "%s: damaged compressed file",
                          path);
  }
  /* A single member ends with its length (mod 2^32): a file that does not
   * is several members, or one with garbage after it, which the slow check
   * tells apart. */
  if (!direct) {
    unsigned char tail[4] = {0, 0, 0, 0};
    FILE *raw = fopen(path, "rb");
    int single =
        raw && sb.st_size >= 4 && fseeko(raw, sb.st_size - 4, SEEK_SET) == 0 &&
        fread(tail, 1, 4, raw) == 4 &&
        ((uint32_t)tail[0] | (uint32_t)tail[1] << 8 | (uint32_t)tail[2] << 16 |
         (uint32_t)tail[3] << 24) == (uint32_t)size;
    if (raw)
      fclose(raw);
    if (!single && gzip_trailing_garbage(path) != 0) {
      free(data);
      return gli_fail(e, GLINT_E_PARSE,
                      "%s: data after the end of the compressed stream "
                      "(a damaged or appended-to file)",
                      path);
    }
  }
  data[size] = '\0';
  *out = data;
  *out_size = size;
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
