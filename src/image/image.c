#define _GNU_SOURCE /* realpath, O_TMPFILE */
/* Images in memory, format dispatch by extension, and the atomic write: the
 * encoder writes a temporary file in the destination folder, which is flushed,
 * synced and renamed over the destination only when complete. A failure or an
 * interruption never leaves a partial image or destroys an existing one. */
#include "image/image.h"

#include "core/error.h"

#include <errno.h>
#include <limits.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

glint_status gli_image_create_for(const char *path, int w, int h,
                                  glint_image **image, glint_error *error) {
  glint_status st = glint_image_create(w, h, image, error);
  if (st == GLINT_E_MEMORY)
    gli_fail(error, st, "%s: out of memory for its %dx%d pixels", path, w, h);
  return st;
}

glint_status glint_image_create(int w, int h, glint_image **out,
                                glint_error *error) {
  GLI_NOT_NULL(out, "image", error);
  if (w < 1 || h < 1 || w > GLINT_MAX_DIMENSION || h > GLINT_MAX_DIMENSION)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "image size %dx%d is outside 1..%d", w, h,
                    GLINT_MAX_DIMENSION);
  glint_image *im = malloc(sizeof *im);
  uint8_t *rgb = calloc((size_t)w * (size_t)h, 3);
  if (!im || !rgb) {
    free(im);
    free(rgb);
    return gli_fail(error, GLINT_E_MEMORY, "out of memory for a %dx%d image", w,
                    h);
  }
  im->width = w;
  im->height = h;
  im->gamma = 1;
  im->rgb = rgb;
  *out = im;
  return GLINT_OK;
}

void glint_image_destroy(glint_image *im) {
  if (im) {
    free(im->rgb);
    free(im);
  }
}

int glint_image_width(const glint_image *im) { return im ? im->width : 0; }
int glint_image_height(const glint_image *im) { return im ? im->height : 0; }
uint8_t *glint_image_pixels(glint_image *im) { return im ? im->rgb : NULL; }
const uint8_t *glint_image_pixels_const(const glint_image *im) {
  return im ? im->rgb : NULL;
}

glint_image_format glint_image_format_from_path(const char *path) {
  if (!path)
    return GLINT_FORMAT_UNKNOWN;
  const char *slash = strrchr(path, '/');
  const char *dot = strrchr(slash ? slash : path, '.');
  if (!dot)
    return GLINT_FORMAT_UNKNOWN;
  if (strcasecmp(dot, ".png") == 0)
    return GLINT_FORMAT_PNG;
  if (strcasecmp(dot, ".bmp") == 0)
    return GLINT_FORMAT_BMP;
  if (strcasecmp(dot, ".ppm") == 0)
    return GLINT_FORMAT_PPM;
  return GLINT_FORMAT_UNKNOWN;
}

static glint_status unknown_format(const char *path, glint_error *error) {
  return gli_fail(error, GLINT_E_ARGUMENT,
                  "%s: unknown image format (use .png, .bmp or .ppm)", path);
}

typedef struct encode_job {
  const glint_image *image;
  glint_image_format format;
  glint_png_compression compression;
} encode_job;

#ifndef NAME_MAX
#define NAME_MAX 255
#endif

/* "dir/name.png" -> "dir/.name.png.XXXXXX" (claim_name); of a name too
 * long for the dot and the suffix (248 bytes or more), only its first NAME_MAX
 * - 8 bytes go into the temporary name. */
static char *temp_template(const char *path) {
  const char *slash = strrchr(path, '/');
  size_t dirlen = slash ? (size_t)(slash - path) + 1 : 0;
  const char *base = path + dirlen;
  size_t baselen = strlen(base);
  if (baselen > NAME_MAX - 8)
    baselen = NAME_MAX - 8;
  size_t n = strlen(path) + 16;
  char *t = malloc(n);
  if (t)
    snprintf(t, n, "%.*s.%.*s.XXXXXX", (int)dirlen, path, (int)baselen, base);
  return t;
}

/* Replaces the last six characters of `name` (XXXXXX) with random ones. */
static void randomise_suffix(char *name, int attempt) {
  static const char letters[] =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  char *x = name + strlen(name) - 6;
  unsigned char r[6];
  if (getrandom(r, sizeof r, 0) != (ssize_t)sizeof r) {
    /* no entropy to be had: a mix of the clock and the attempt */
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    uint64_t v = (uint64_t)ts.tv_nsec * 2654435761u + (uint64_t)attempt +
                 (uint64_t)getpid() * 40503u;
    for (int k = 0; k < 6; k++, v >>= 8)
      r[k] = (unsigned char)v;
  }
  for (int k = 0; k < 6; k++)
    x[k] = letters[r[k] % (sizeof letters - 1)];
}

/* Where the file system and /proc allow (Linux's O_TMPFILE, linked later
 * through /proc/self/fd: open(2)), an unnamed file in the folder of
 * `path`, which claim_name names once it is complete; else -1 and the
 * caller names one. */
static int create_unnamed(const char *path) {
#ifdef O_TMPFILE
  if (access("/proc/self/fd", X_OK) != 0)
    return -1;
  const char *slash = strrchr(path, '/');
  char *folder =
      slash ? strndup(path, (size_t)(slash - path) + 1) : strdup(".");
  if (!folder)
    return -1;
  int fd = open(folder, O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  free(folder);
  return fd;
#else
  (void)path;
  return -1;
#endif
}

/* Replaces the last six characters of `name` (XXXXXX) with random ones
 * until no file has that name, and claims it: fd < 0 creates the file
 * there and returns its descriptor; else fd, an unnamed file
 * (create_unnamed), is linked there and returned. -1 with errno on
 * failure. Not mkstemp: its 0600 would need the umask to be read, which
 * only setting it does, a change every thread of the process sees (a file
 * another thread made meanwhile would get mode 0666). With mode 0666 here
 * the kernel applies the umask. */
static int claim_name(char *name, int fd) {
  char proc[64];
  snprintf(proc, sizeof proc, "/proc/self/fd/%d", fd);
  for (int attempt = 0; attempt < 1000; attempt++) {
    randomise_suffix(name, attempt);
    int got;
    if (fd < 0)
      got = open(name, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    else
      got = linkat(AT_FDCWD, proc, AT_FDCWD, name, AT_SYMLINK_FOLLOW) == 0 ? fd
                                                                           : -1;
    if (got >= 0 || errno != EEXIST)
      return got;
  }
  errno = EEXIST;
  return -1;
}

/* Whether the folder of `path` has the sticky bit (as /tmp has) and so
 * lets no one but the owner of the file `file`, the folder's owner or root
 * replace it, whatever the file's mode: the rename after a render would
 * fail, which is found now. */
static int sticky_forbids(const char *path, const struct stat *file) {
  uid_t me = geteuid();
  if (me == 0 || file->st_uid == me)
    return 0;
  const char *slash = strrchr(path, '/');
  char *folder = slash ? strndup(path, (size_t)(slash - path) + 1) : NULL;
  struct stat sb;
  int forbids = stat(folder ? folder : ".", &sb) == 0 &&
                (sb.st_mode & S_ISVTX) && sb.st_uid != me;
  free(folder);
  return forbids;
}

/* Creates the temporary file beside `path`; returns its descriptor. With
 * *unnamed set (the caller may pass NULL: a named file), the file has no
 * name yet and *temp is the template that claim_name completes. */
static int open_temp_shown(const char *path, const char *shown, char **temp,
                           int *unnamed, glint_error *error) {
  /* What is there already: only a regular file the user may write is
   * replaced. The rename asks only the folder, and would put a file in the
   * place of a device or a pipe (of /dev/null through a link to it) or of
   * a file the user may not write. */
  struct stat sb;
  int exists = stat(path, &sb) == 0;
  /* A loop of links: the rename would replace one of them. */
  if (!exists && errno == ELOOP) {
    gli_fail(error, GLINT_E_IO, "%s: cannot write: %s", shown, strerror(errno));
    return -1;
  }
  if (exists) {
    if (S_ISDIR(sb.st_mode)) {
      gli_fail(error, GLINT_E_IO, "%s: is a directory", shown);
      return -1;
    }
    if (!S_ISREG(sb.st_mode)) {
      gli_fail(error, GLINT_E_IO, "%s: not a regular file", shown);
      return -1;
    }
    if (access(path, W_OK) != 0) {
      gli_fail(error, GLINT_E_IO, "%s: cannot write: %s", shown,
               strerror(errno));
      return -1;
    }
    if (sticky_forbids(path, &sb)) {
      gli_fail(error, GLINT_E_IO,
               "%s: cannot replace: it belongs to another user, in a folder "
               "with the sticky bit",
               shown);
      return -1;
    }
  }
  const char *slash = strrchr(path, '/');
  if (strlen(slash ? slash + 1 : path) > NAME_MAX) {
    /* found now, before a render, not by the rename after it */
    gli_fail(error, GLINT_E_IO, "%s: cannot write here: %s", shown,
             strerror(ENAMETOOLONG));
    return -1;
  }
  *temp = temp_template(path);
  if (!*temp) {
    gli_fail(error, GLINT_E_MEMORY, "out of memory");
    return -1;
  }
  int fd = unnamed ? create_unnamed(path) : -1;
  if (unnamed)
    *unnamed = fd >= 0;
  if (fd < 0)
    fd = claim_name(*temp, -1);
  if (fd < 0) {
    gli_fail(error, GLINT_E_IO, "%s: cannot write here: %s", shown,
             strerror(errno));
    free(*temp);
    *temp = NULL;
  }
  return fd;
}

/* open_temp_shown for `path`, reached as `given` (the same name, or a
 * link to path): messages name what the user gave, and where it leads. */
static int open_temp(const char *path, const char *given, char **temp,
                     int *unnamed, glint_error *error) {
  char *shown = NULL;
  if (strcmp(given, path) != 0) {
    size_t n = strlen(given) + strlen(path) + 16;
    if ((shown = malloc(n)))
      snprintf(shown, n, "%s (a link to %s)", given, path);
  }
  int fd = open_temp_shown(path, shown ? shown : given, temp, unnamed, error);
  free(shown);
  return fd;
}

glint_status glint_image_check_writable(const char *path, glint_error *error) {
  GLI_NOT_NULL(path, "path", error);
  if (glint_image_format_from_path(path) == GLINT_FORMAT_UNKNOWN)
    return unknown_format(path, error);
  return gli_check_folder_writable(path, error);
}

/* The name that a dangling link at `path` leads to, followed link by link
 * to the first that does not exist; NULL for a loop of links. */
static char *dangling_target(const char *path) {
  char *at = strdup(path);
  for (int hops = 0; at && hops < 40; hops++) { /* Linux's own limit */
    struct stat sb;
    if (lstat(at, &sb) != 0 || !S_ISLNK(sb.st_mode))
      return at;
    char to[PATH_MAX];
    ssize_t n = readlink(at, to, sizeof to);
    if (n < 0 || n == (ssize_t)sizeof to)
      break;
    /* A relative link is relative to its own folder. */
    const char *slash = strrchr(at, '/');
    size_t folder = to[0] == '/' || !slash ? 0 : (size_t)(slash - at) + 1;
    char *next = malloc(folder + (size_t)n + 1);
    if (next) {
      memcpy(next, at, folder);
      memcpy(next + folder, to, (size_t)n);
      next[folder + (size_t)n] = '\0';
    }
    free(at);
    at = next;
  }
  free(at);
  return NULL;
}

/* Where `path` is a symbolic link, the file it names (written through the
 * link, as a shell's > writes, so the link stays a link; a dangling link's
 * file is created, where its folder exists); else NULL, for path itself. */
static char *link_target(const char *path) {
  struct stat sb;
  if (lstat(path, &sb) != 0 || !S_ISLNK(sb.st_mode))
    return NULL;
  char *real = realpath(path, NULL);
  return real || errno != ENOENT ? real : dangling_target(path);
}

char *glint_output_file(const char *path) {
  if (!path)
    return NULL;
  struct stat sb;
  if (lstat(path, &sb) != 0 || !S_ISLNK(sb.st_mode))
    return strdup(path);
  return link_target(path);
}

glint_status gli_check_folder_writable(const char *path, glint_error *error) {
  char *target = link_target(path);
  /* A name the kernel takes no longer than PATH_MAX: its folder may be
   * shorter, and be written, and the file then fail to be named once
   * rendered (or a benchmark's results lost after the whole run). */
  if (strlen(target ? target : path) >= PATH_MAX) {
    free(target);
    return gli_fail(error, GLINT_E_IO, "%s: %s", path, strerror(ENAMETOOLONG));
  }
  char *temp;
  /* Unnamed where the file system allows: a process killed between the
   * creation and the unlink left a named one (glint render --frames checks
   * every frame's file before the first is rendered). */
  int unnamed;
  int fd = open_temp(target ? target : path, path, &temp, &unnamed, error);
  free(target);
  if (fd < 0)
    return error ? error->status : GLINT_E_IO;
  close(fd);
  if (!unnamed)
    unlink(temp);
  free(temp);
  return GLINT_OK;
}

glint_status gli_atomic_open(const char *path, gli_atomic_file *file,
                             glint_error *error) {
  file->target = link_target(path);
  const char *dest = file->target ? file->target : path;
  int fd = open_temp(dest, path, &file->temp, &file->unnamed, error);
  if (fd < 0) {
    free(file->target);
    return error ? error->status : GLINT_E_IO;
  }
  /* A file replaced keeps its permissions (a new one has 0666 less the
   * umask, as claim_name or create_unnamed made it). */
  struct stat sb;
  if (stat(dest, &sb) == 0 && S_ISREG(sb.st_mode))
    fchmod(fd, sb.st_mode & 07777);
  file->path = path;
  file->f = fdopen(fd, "wb");
  if (!file->f) {
    int saved = errno;
    close(fd);
    if (!file->unnamed)
      unlink(file->temp);
    free(file->temp);
    free(file->target);
    return gli_fail(error, GLINT_E_IO, "%s: %s", path, strerror(saved));
  }
  return GLINT_OK;
}

glint_status gli_atomic_commit(gli_atomic_file *file, int failed,
                               int failed_errno, glint_error *error) {
  int bad = failed, saved = failed_errno;
  if (!bad && fflush(file->f) != 0)
    bad = 1, saved = errno;
  if (!bad && fsync(fileno(file->f)) != 0 && errno != EINVAL)
    bad = 1, saved = errno;
  /* An unnamed file is named now, microseconds before the rename. */
  if (!bad && file->unnamed) {
    if (claim_name(file->temp, fileno(file->f)) < 0)
      bad = 1, saved = errno;
    else
      file->unnamed = 0;
  }
  if (fclose(file->f) != 0 && !bad)
    bad = 1, saved = errno;
  if (!bad && rename(file->temp, file->target ? file->target : file->path) != 0)
    bad = 1, saved = errno;
  if (bad && !file->unnamed)
    unlink(file->temp);
  free(file->temp);
  free(file->target);
  if (bad)
    return gli_fail(error, gli_errno_status(saved), "%s: writing failed: %s",
                    file->path, saved ? strerror(saved) : "encoder error");
  return GLINT_OK;
}

void gli_atomic_discard(gli_atomic_file *file) {
  fclose(file->f);
  if (!file->unnamed)
    unlink(file->temp);
  free(file->temp);
  free(file->target);
}

glint_status gli_write_atomically(const char *path, write_fn write,
                                  const void *data, glint_error *error) {
  gli_atomic_file file;
  glint_status st = gli_atomic_open(path, &file, error);
  if (st)
    return st;
  errno = 0;
  int bad = write(data, file.f);
  return gli_atomic_commit(&file, bad, errno, error);
}

typedef struct byte_span {
  const void *bytes;
  size_t size;
} byte_span;

static int write_span(const void *data, FILE *f) {
  const byte_span *s = data;
  return s->size && fwrite(s->bytes, 1, s->size, f) != s->size ? -1 : 0;
}

/* Whether `bytes` begin as a file of `format` does: its signature (PNG's
 * eight bytes, BMP's "BM", binary PPM's "P6" and a blank). */
static int starts_as(glint_image_format format, const unsigned char *bytes,
                     size_t size) {
  static const unsigned char png[8] = {0x89, 'P',  'N',  'G',
                                       '\r', '\n', 0x1a, '\n'};
  switch (format) {
  case GLINT_FORMAT_PNG: return size > 8 && memcmp(bytes, png, 8) == 0;
  case GLINT_FORMAT_BMP: return size > 2 && bytes[0] == 'B' && bytes[1] == 'M';
  default:
    return size > 3 && bytes[0] == 'P' && bytes[1] == '6' &&
           strchr(" \t\r\n#", bytes[2]) && bytes[2];
  }
}

glint_status glint_image_write_encoded(const char *path, const void *bytes,
                                       size_t size, glint_error *error) {
  GLI_NOT_NULL(path, "path", error);
  GLI_NOT_NULL(bytes, "bytes", error);
  glint_image_format format = glint_image_format_from_path(path);
  if (format == GLINT_FORMAT_UNKNOWN)
    return unknown_format(path, error);
  /* A wrong or damaged buffer must not replace a good file. */
  if (!starts_as(format, bytes, size))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: the %zu bytes given are not a %s file", path, size,
                    format == GLINT_FORMAT_PNG   ? "PNG"
                    : format == GLINT_FORMAT_BMP ? "BMP"
                                                 : "binary PPM");
  byte_span span = {bytes, size};
  return gli_write_atomically(path, write_span, &span, error);
}

static int encode_image(const void *data, FILE *f) {
  const encode_job *job = data;
  return job->format == GLINT_FORMAT_PNG
             ? gli_png_encode(job->image, job->compression, f)
         : job->format == GLINT_FORMAT_BMP ? gli_bmp_encode(job->image, f)
                                           : gli_ppm_encode(job->image, f);
}

glint_status glint_image_write_with(const glint_image *im, const char *path,
                                    glint_png_compression compression,
                                    glint_error *error) {
  GLI_NOT_NULL(im, "image", error);
  GLI_NOT_NULL(path, "path", error);
  glint_image_format fmt = glint_image_format_from_path(path);
  if (fmt == GLINT_FORMAT_UNKNOWN)
    return unknown_format(path, error);
  if ((unsigned)compression > GLINT_PNG_SMALLEST)
    return gli_fail(error, GLINT_E_ARGUMENT, "unknown PNG compression %d",
                    (int)compression);
  encode_job job = {im, fmt, compression};
  return gli_write_atomically(path, encode_image, &job, error);
}

glint_status glint_image_write_stream(const glint_image *im, FILE *stream,
                                      glint_image_format format,
                                      glint_png_compression compression,
                                      glint_error *error) {
  GLI_NOT_NULL(im, "image", error);
  GLI_NOT_NULL(stream, "stream", error);
  if (format != GLINT_FORMAT_PNG && format != GLINT_FORMAT_BMP &&
      format != GLINT_FORMAT_PPM)
    return gli_fail(error, GLINT_E_ARGUMENT, "unknown image format %d",
                    (int)format);
  if ((unsigned)compression > GLINT_PNG_SMALLEST)
    return gli_fail(error, GLINT_E_ARGUMENT, "unknown PNG compression %d",
                    (int)compression);
  encode_job job = {im, format, compression};
  errno = 0;
  if (encode_image(&job, stream) || fflush(stream) != 0)
    return gli_fail(error, GLINT_E_IO, "writing the image failed: %s",
                    errno ? strerror(errno) : "encoder error");
  return GLINT_OK;
}

glint_status glint_image_write(const glint_image *im, const char *path,
                               glint_error *error) {
  GLI_NOT_NULL(im, "image", error); /* named as the caller called it */
  GLI_NOT_NULL(path, "path", error);
  return glint_image_write_with(im, path, GLINT_PNG_FAST, error);
}

/* glint_image_read, or with out NULL glint_image_read_size. */
static glint_status read_image(const char *path, glint_image **out, int size[2],
                               glint_error *error) {
  glint_image_format fmt = glint_image_format_from_path(path);
  if (fmt == GLINT_FORMAT_UNKNOWN)
    return unknown_format(path, error);
  /* Asked first: a folder opens and reads as a damaged image, a FIFO
   * without a writer blocks the open. */
  struct stat sb;
  if (stat(path, &sb) != 0)
    return gli_fail(error, GLINT_E_IO, "%s: %s", path, strerror(errno));
  if (!S_ISREG(sb.st_mode))
    return gli_fail(error, GLINT_E_IO, "%s: %s", path,
                    S_ISDIR(sb.st_mode) ? "a folder, not an image"
                                        : "not a regular file");
  if (sb.st_size == 0) /* said so, not that it is no PNG, BMP or PPM */
    return gli_fail(error, GLINT_E_PARSE, "%s: the file is empty", path);
  FILE *f = fopen(path, "rb");
  if (!f)
    return gli_fail(error, GLINT_E_IO, "%s: %s", path, strerror(errno));
  glint_status st =
      fmt == GLINT_FORMAT_PNG   ? gli_png_decode(f, path, out, size, error)
      : fmt == GLINT_FORMAT_BMP ? gli_bmp_decode(f, path, out, size, error)
                                : gli_ppm_decode(f, path, out, size, error);
  fclose(f);
  return st;
}

long long gli_file_size(FILE *f) {
  struct stat sb;
  if (fstat(fileno(f), &sb) != 0 || !S_ISREG(sb.st_mode))
    return -1;
  return (long long)sb.st_size;
}

glint_status glint_image_read(const char *path, glint_image **out,
                              glint_error *error) {
  GLI_NOT_NULL(path, "path", error);
  GLI_NOT_NULL(out, "image", error);
  int size[2];
  return read_image(path, out, size, error);
}

glint_status glint_image_read_size(const char *path, int *width, int *height,
                                   glint_error *error) {
  GLI_NOT_NULL(path, "path", error);
  GLI_NOT_NULL(width, "width", error);
  GLI_NOT_NULL(height, "height", error);
  int size[2];
  glint_status st = read_image(path, NULL, size, error);
  if (st == GLINT_OK) {
    *width = size[0];
    *height = size[1];
  }
  return st;
}

double glint_image_psnr(const glint_image *a, const glint_image *b) {
  if (!a || !b || a->width != b->width || a->height != b->height)
    return -1;
  size_t n = (size_t)a->width * (size_t)a->height * 3;
  double sum = 0;
  for (size_t i = 0; i < n; i++) {
    double d = (double)a->rgb[i] - (double)b->rgb[i];
    sum += d * d;
  }
  if (sum == 0)
    return INFINITY;
  return 10 * log10(255.0 * 255.0 / (sum / (double)n));
}
