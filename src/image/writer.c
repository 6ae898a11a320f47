/* Image files written while a frame renders (glint_image_writer): tiles are
 * converted to 8 bits as they arrive, and a thread of the writer's own
 * encodes each batch of complete rows at once, so that encoding overlaps
 * rendering and the file is finished moments after the last tile. The file
 * itself is atomic (gli_atomic_open): it appears whole at finish or not at
 * all.
 *
 * A PNG or PPM is written top row first, so the 8-bit pixels live in bands
 * of BAND_ROWS rows that are taken when a tile first reaches them and
 * reused once encoded: the writer holds a few bands, not the image (a
 * 16384x16384 image needs 768 MiB of 8-bit pixels but a few MiB of bands),
 * and touches the same memory again (on the virtual machine where this was
 * measured, each 4 KiB page a process touches first costs it about 13 us:
 * 2.6 ms of 640x480 when every page was new). Tiles that come faster than
 * they are encoded wait for the encoder once BANDS_AHEAD bytes of bands
 * are held, if it has rows to encode; tiles out of order never wait, and
 * take what bands they need. A BMP, bottom row first, keeps the whole image
 * as one band. */
#include "image/image.h"

#include "core/error.h"
#include "core/thread.h"

#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Rows a band of a PNG or PPM holds: 30 KiB at 640 pixels a row. */
#define BAND_ROWS 16
/* The bands held before a tile waits for the encoder (at least 4). */
#define BANDS_AHEAD ((size_t)8 << 20)

struct glint_image_writer {
  int width, height;
  double gamma;
  gli_byte_encoding encoding; /* gamma's */
  glint_image_format format;
  glint_png_compression compression;
  gli_atomic_file file; /* the file, or (memory) a stream into `memory` */
  int in_memory;
  char *memory;
  size_t memory_size;
  glint_image image;   /* size and gamma; BMP: the 8-bit pixels (band 0) */
  int band_rows;       /* rows of the image a band holds */
  int most_taken;      /* bands held before a tile waits for the encoder */
  int *row_pixels;     /* pixels converted in each row so far */
  uint64_t *given;     /* a bit a pixel: given by a put (under `lock`) */
  gli_png_writer *png; /* PNG only, owned by the encoder thread */
  pthread_t encoder;
  pthread_mutex_t lock; /* guards everything below */
  pthread_cond_t wake;  /* rows became ready, or the writer is closing */
  pthread_cond_t room;  /* the encoder released bands, or stopped */
  uint8_t **bands;      /* [band]: its 8-bit pixels, or NULL (untouched or
                           encoded) */
  uint8_t **spare;      /* released bands, for the next to be taken */
  int spare_count;
  int taken;      /* bands held */
  int ready;      /* rows [0, ready) are complete */
  int encoded;    /* rows [0, encoded) are encoded */
  int signalled;  /* ready when the encoder was last woken */
  int batch_rows; /* rows worth waking the encoder for */
  int closing, discarding;
  int failed, failed_errno; /* the encoder could not write */
  int bad_put;              /* a put refused (refuse_put), or out of memory */
};

/* The bits [from, from + n) of word k, as a mask. */
static uint64_t span_mask(size_t k, size_t from, size_t n) {
  size_t lo = from > 64 * k ? from - 64 * k : 0;
  size_t hi = from + n < 64 * (k + 1) ? from + n - 64 * k : 64;
  uint64_t below_hi = hi == 64 ? ~(uint64_t)0 : ((uint64_t)1 << hi) - 1;
  return below_hi & ~(((uint64_t)1 << lo) - 1);
}

/* Whether any of pixels [from, from + n) (n >= 1) of the bitmap is set;
 * sets them all when none is. */
static int give_pixels(uint64_t *given, size_t from, size_t n) {
  size_t first = from / 64, last = (from + n - 1) / 64;
  for (size_t k = first; k <= last; k++)
    if (given[k] & span_mask(k, from, n))
      return 1;
  for (size_t k = first; k <= last; k++)
    given[k] |= span_mask(k, from, n);
  return 0;
}

static int band_count(const glint_image_writer *w) {
  return (w->height + w->band_rows - 1) / w->band_rows;
}

static size_t band_bytes(const glint_image_writer *w) {
  return (size_t)w->band_rows * (size_t)w->width * 3;
}

/* Row y's first pixel, in the band that holds it (taken). */
static uint8_t *row_of(const glint_image_writer *w, int y) {
  return w->bands[y / w->band_rows] +
         (size_t)(y % w->band_rows) * (size_t)w->width * 3;
}

/* Takes the bands that rows [from, to) lie in (under `lock`): a spare one
 * or a new one, after waiting for the encoder to release some where many
 * are held and it has rows to encode (which needs no other tile, so the
 * wait ends). 0 on success, -1 out of memory. */
static int take_bands(glint_image_writer *w, int from, int to) {
  for (int b = from / w->band_rows; b <= (to - 1) / w->band_rows; b++) {
    if (w->bands[b])
      continue;
    while (!w->spare_count && w->taken >= w->most_taken &&
           w->ready > w->encoded && !w->failed) {
      pthread_cond_signal(&w->wake);
      w->signalled = w->ready;
      pthread_cond_wait(&w->room, &w->lock);
    }
    if (w->bands[b]) /* another put took it while this one waited */
      continue;
    w->bands[b] =
        w->spare_count ? w->spare[--w->spare_count] : malloc(band_bytes(w));
    if (!w->bands[b])
      return -1;
    w->taken++;
  }
  return 0;
}

/* Releases, for reuse, the bands whose rows were all encoded now that
 * rows [from, to) are (under `lock`; a BMP's one band stays to the end). */
static void release_bands(glint_image_writer *w, int from, int to) {
  if (w->format == GLINT_FORMAT_BMP)
    return;
  for (int b = from / w->band_rows; b < to / w->band_rows; b++)
    if (w->bands[b]) {
      w->spare[w->spare_count++] = w->bands[b];
      w->bands[b] = NULL;
      w->taken--;
    }
}

/* Encodes rows [from, to); a PNG or PPM a band's part at a time, a BMP
 * (bottom row first) once every row is there. 0 on success. */
static int encode_rows(glint_image_writer *w, int from, int to) {
  size_t row_bytes = (size_t)w->width * 3;
  if (w->format == GLINT_FORMAT_BMP)
    return to == w->height ? gli_bmp_encode(&w->image, w->file.f) : 0;
  for (int y = from; y < to;) {
    int band_end = (y / w->band_rows + 1) * w->band_rows;
    int n = (band_end < to ? band_end : to) - y;
    const uint8_t *rows = row_of(w, y);
    if (w->format == GLINT_FORMAT_PNG
            ? gli_png_rows(w->png, rows, n, row_bytes) != 0
            : fwrite(rows, row_bytes, (size_t)n, w->file.f) != (size_t)n)
      return -1;
    y += n;
  }
  if (w->format == GLINT_FORMAT_PNG && to == w->height) {
    gli_png_writer *png = w->png;
    w->png = NULL; /* gli_png_end frees it, whatever it returns */
    return gli_png_end(png);
  }
  return 0;
}

static void *encode_loop(void *arg) {
  glint_image_writer *w = arg;
  pthread_mutex_lock(&w->lock);
  while (w->encoded < w->height && !w->discarding) {
    if (w->ready == w->encoded) {
      if (w->closing)
        break; /* rows are missing: finish says so */
      pthread_cond_wait(&w->wake, &w->lock);
      continue;
    }
    int from = w->encoded, to = w->ready;
    pthread_mutex_unlock(&w->lock);
    errno = 0;
    int bad = encode_rows(w, from, to);
    int saved = errno;
    pthread_mutex_lock(&w->lock);
    if (bad) {
      w->failed = 1;
      w->failed_errno = saved;
      break;
    }
    w->encoded = to;
    release_bands(w, from, to);
    pthread_cond_broadcast(&w->room);
  }
  pthread_cond_broadcast(&w->room); /* no tile waits for a stopped encoder */
  pthread_mutex_unlock(&w->lock);
  return NULL;
}

static void writer_free(glint_image_writer *w) {
  gli_png_abort(w->png);
  pthread_mutex_destroy(&w->lock);
  pthread_cond_destroy(&w->wake);
  pthread_cond_destroy(&w->room);
  if (w->bands)
    for (int b = 0; b < band_count(w); b++)
      free(w->bands[b]);
  for (int k = 0; k < w->spare_count; k++)
    free(w->spare[k]);
  free(w->bands);
  free(w->spare);
  free(w->row_pixels);
  free(w->given);
  free(w);
}

/* A writer of `format` (named `label` in messages) with its encoder not
 * yet started: open_target gives it the stream. */
static glint_status writer_create(const char *label, glint_image_format format,
                                  int width, int height, double gamma,
                                  glint_png_compression compression,
                                  glint_image_writer **out,
                                  glint_error *error) {
  if (format != GLINT_FORMAT_PNG && format != GLINT_FORMAT_BMP &&
      format != GLINT_FORMAT_PPM)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: unknown image format (use .png, .bmp or .ppm)", label);
  if (width < 1 || height < 1 || width > GLINT_MAX_DIMENSION ||
      height > GLINT_MAX_DIMENSION)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "image size %dx%d is outside 1..%d", width, height,
                    GLINT_MAX_DIMENSION);
  if (gli_gamma_check(gamma, error))
    return GLINT_E_ARGUMENT;
  if ((unsigned)compression > GLINT_PNG_SMALLEST)
    return gli_fail(error, GLINT_E_ARGUMENT, "unknown PNG compression %d",
                    (int)compression);
  glint_image_writer *w = calloc(1, sizeof *w);
  if (!w)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  w->width = width;
  w->height = height;
  w->gamma = gamma;
  gli_byte_encoding_init(&w->encoding, gamma);
  w->format = format;
  w->compression = compression;
  w->batch_rows = height / 16 > 16 ? height / 16 : 16;
  w->image = (glint_image){width, height, gamma, NULL};
  w->band_rows = format == GLINT_FORMAT_BMP ? height : BAND_ROWS;
  size_t ahead = BANDS_AHEAD / band_bytes(w);
  w->most_taken = ahead > 4 ? (int)(ahead < INT_MAX ? ahead : INT_MAX) : 4;
  w->bands = calloc((size_t)band_count(w), sizeof *w->bands);
  w->spare = calloc((size_t)band_count(w), sizeof *w->spare);
  w->row_pixels = calloc((size_t)height, sizeof *w->row_pixels);
  w->given =
      calloc(((size_t)width * (size_t)height + 63) / 64, sizeof *w->given);
  pthread_mutex_init(&w->lock, NULL);
  pthread_cond_init(&w->wake, NULL);
  pthread_cond_init(&w->room, NULL);
  if (w->bands && format == GLINT_FORMAT_BMP) /* whole: refused now */
    w->image.rgb = w->bands[0] = malloc(band_bytes(w));
  if (!w->bands || !w->spare || !w->row_pixels || !w->given ||
      (format == GLINT_FORMAT_BMP && !w->bands[0])) {
    writer_free(w);
    return gli_fail(error, GLINT_E_MEMORY, "out of memory for a %dx%d image",
                    width, height);
  }
  *out = w;
  return GLINT_OK;
}

/* Writes the header into w->file.f and starts the encoder; on failure
 * frees the writer (the caller has closed nothing yet). */
static glint_status start_encoder(glint_image_writer *w, const char *label,
                                  glint_error *error) {
  /* The path is the caller's; keep our own for the rename and messages. */
  char *own_label = strdup(label);
  int header_bad = 0;
  if (w->format == GLINT_FORMAT_PNG)
    header_bad = !(w->png = gli_png_begin(w->file.f, w->width, w->height,
                                          w->gamma, w->compression));
  else if (w->format == GLINT_FORMAT_PPM)
    header_bad = gli_ppm_header(w->file.f, w->width, w->height);
  int thread_err = 0;
  if (!own_label || header_bad ||
      (thread_err = gli_thread_start(&w->encoder, encode_loop, w)) != 0) {
    if (w->in_memory) {
      fclose(w->file.f);
      free(w->memory);
    } else {
      gli_atomic_discard(&w->file);
    }
    free(own_label);
    writer_free(w);
    if (thread_err)
      return gli_fail(error, GLINT_E_MEMORY,
                      "%s: cannot start the thread that encodes it: %s", label,
                      strerror(thread_err));
    return gli_fail(error, GLINT_E_MEMORY, "%s: cannot start writing", label);
  }
  w->file.path = own_label;
  return GLINT_OK;
}

glint_status glint_image_writer_open(const char *path, int width, int height,
                                     double gamma,
                                     glint_png_compression compression,
                                     glint_image_writer **out,
                                     glint_error *error) {
  GLI_NOT_NULL(path, "path", error);
  GLI_NOT_NULL(out, "writer", error);
  glint_image_format format =
      path ? glint_image_format_from_path(path) : GLINT_FORMAT_UNKNOWN;
  glint_image_writer *w = NULL;
  glint_status st =
      writer_create(path, format, width, height, gamma, compression, &w, error);
  if (st)
    return st;
  if ((st = gli_atomic_open(path, &w->file, error))) {
    writer_free(w);
    return st;
  }
  if ((st = start_encoder(w, path, error)))
    return st;
  *out = w;
  return GLINT_OK;
}

glint_status glint_image_writer_open_memory(glint_image_format format,
                                            int width, int height, double gamma,
                                            glint_png_compression compression,
                                            glint_image_writer **out,
                                            glint_error *error) {
  GLI_NOT_NULL(out, "writer", error);
  if (format != GLINT_FORMAT_PNG && format != GLINT_FORMAT_BMP &&
      format != GLINT_FORMAT_PPM)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "unknown image format %d (GLINT_FORMAT_PNG, "
                    "GLINT_FORMAT_BMP or GLINT_FORMAT_PPM)",
                    (int)format);
  static const char label[] = "image in memory";
  glint_image_writer *w = NULL;
  glint_status st = writer_create(label, format, width, height, gamma,
                                  compression, &w, error);
  if (st)
    return st;
  w->in_memory = 1;
  if (!(w->file.f = open_memstream(&w->memory, &w->memory_size))) {
    writer_free(w);
    return gli_fail(error, GLINT_E_MEMORY, "%s: out of memory", label);
  }
  if ((st = start_encoder(w, label, error)))
    return st;
  *out = w;
  return GLINT_OK;
}

/* Refuses a put, and spoils the image: a tile the caller meant to give is
 * missing from it, whatever was wrong with the tile. */
static glint_status refuse_put(glint_image_writer *w, glint_error *error,
                               const char *fmt, ...) GLI_PRINTF(3, 4);
static glint_status refuse_put(glint_image_writer *w, glint_error *error,
                               const char *fmt, ...) {
  pthread_mutex_lock(&w->lock);
  w->bad_put = 1;
  pthread_mutex_unlock(&w->lock);
  char message[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(message, sizeof message, fmt, ap);
  va_end(ap);
  return gli_fail(error, GLINT_E_ARGUMENT, "%s: %s", w->file.path, message);
}

glint_status glint_image_writer_put(glint_image_writer *w,
                                    const glint_tile *tile,
                                    glint_error *error) {
  GLI_NOT_NULL(w, "writer", error);
  if (!tile)
    return refuse_put(w, error, "tile is NULL");
  if (!tile->pixels)
    return refuse_put(w, error, "the tile's pixels are NULL");
  if (tile->width < 1 || tile->height < 1)
    return refuse_put(w, error, "tile %dx%d at (%d, %d) is empty", tile->width,
                      tile->height, tile->x, tile->y);
  if (tile->stride < (size_t)tile->width * 3)
    return refuse_put(w, error,
                      "the tile's stride %zu is less than its %zu floats a row",
                      tile->stride, (size_t)tile->width * 3);
  if (tile->x < 0 || tile->y < 0 || tile->width > w->width - tile->x ||
      tile->height > w->height - tile->y)
    return refuse_put(
        w, error, "tile %dx%d at (%d, %d) is outside the %dx%d image",
        tile->width, tile->height, tile->x, tile->y, w->width, w->height);
  /* Every pixel is given once: a tile that repeats one is refused before
   * it is converted, so that a row is complete only when each of its
   * pixels came (counting pixels a row, the left half given twice passed
   * for a whole row, and the right half's unset bytes were written). */
  pthread_mutex_lock(&w->lock);
  int repeated = 0;
  for (int y = tile->y; y < tile->y + tile->height && !repeated; y++)
    repeated = give_pixels(w->given, (size_t)y * w->width + tile->x,
                           (size_t)tile->width);
  if (repeated) {
    /* the rows given before the repeat stay marked: the image is spoilt */
    w->bad_put = 1;
    pthread_mutex_unlock(&w->lock);
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: tile %dx%d at (%d, %d) repeats pixels already given",
                    w->file.path, tile->width, tile->height, tile->x, tile->y);
  }
  if (!w->bad_put && take_bands(w, tile->y, tile->y + tile->height)) {
    w->bad_put = 1; /* its pixels are marked given but have nowhere to go */
    pthread_mutex_unlock(&w->lock);
    return gli_fail(error, GLINT_E_MEMORY,
                    "%s: out of memory for the image's rows %d to %d",
                    w->file.path, tile->y, tile->y + tile->height - 1);
  }
  int spoilt = w->bad_put;
  pthread_mutex_unlock(&w->lock);
  if (spoilt)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: an earlier tile was refused, so the image cannot be "
                    "finished",
                    w->file.path);
  /* Tiles are disjoint now, and their bands stay until their rows are
   * encoded: the conversion needs no lock. */
  for (int y = 0; y < tile->height; y++)
    gli_byte_encode(&w->encoding, tile->pixels + (size_t)y * tile->stride,
                    row_of(w, tile->y + y) + (size_t)tile->x * 3,
                    (size_t)tile->width * 3);
  pthread_mutex_lock(&w->lock);
  for (int y = tile->y; y < tile->y + tile->height; y++)
    w->row_pixels[y] += tile->width;
  int ready = w->ready;
  while (ready < w->height && w->row_pixels[ready] == w->width)
    ready++;
  /* Wake the encoder for a batch of rows, not for every band: each wake-up
   * of a sleeping thread costs the rendering thread a system call (and, in
   * a virtual machine, an interrupt between CPUs). In the last batch, wake
   * it for every band: the rows still unencoded when the last tile comes
   * are what the caller waits for. */
  if (ready > w->ready) {
    if (ready - w->signalled >= w->batch_rows ||
        ready > w->height - w->batch_rows) {
      pthread_cond_signal(&w->wake);
      w->signalled = ready;
    }
    w->ready = ready;
  }
  int failed = w->failed, failed_errno = w->failed_errno;
  pthread_mutex_unlock(&w->lock);
  if (failed)
    return gli_fail(error, gli_errno_status(failed_errno),
                    "%s: writing failed: %s", w->file.path,
                    failed_errno ? strerror(failed_errno) : "encoder error");
  return GLINT_OK;
}

/* Tells the encoder to stop (after what is ready, or at once) and waits. */
static void stop_encoder(glint_image_writer *w, int discard) {
  pthread_mutex_lock(&w->lock);
  w->closing = 1;
  w->discarding = discard;
  pthread_cond_signal(&w->wake);
  pthread_mutex_unlock(&w->lock);
  pthread_join(w->encoder, NULL);
}

/* Why a finished writer has no whole image, or GLINT_OK. */
static glint_status incomplete(const glint_image_writer *w,
                               glint_error *error) {
  const char *path = w->file.path;
  if (w->failed)
    return gli_fail(
        error, gli_errno_status(w->failed_errno), "%s: writing failed: %s",
        path, w->failed_errno ? strerror(w->failed_errno) : "encoder error");
  if (w->bad_put)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: a tile was refused, so the image cannot be finished",
                    path);
  if (w->encoded < w->height) {
    int complete = 0; /* anywhere, not only from the top (w->ready) */
    for (int y = 0; y < w->height; y++)
      complete += w->row_pixels[y] == w->width;
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: only %d of the image's %d rows were complete; "
                    "nothing was written",
                    path, complete, w->height);
  }
  return GLINT_OK;
}

glint_status glint_image_writer_finish(glint_image_writer *w,
                                       glint_error *error) {
  GLI_NOT_NULL(w, "writer", error);
  if (w->in_memory) {
    glint_image_writer_discard(w);
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "an image writer in memory ends with "
                    "glint_image_writer_finish_memory");
  }
  stop_encoder(w, 0);
  char *path = (char *)w->file.path;
  glint_status st = incomplete(w, error);
  if (st)
    gli_atomic_discard(&w->file);
  else
    st = gli_atomic_commit(&w->file, 0, 0, error);
  free(path);
  writer_free(w);
  return st;
}

glint_status glint_image_writer_finish_memory(glint_image_writer *w,
                                              void **bytes, size_t *size,
                                              glint_error *error) {
  if (!w || !bytes || !size) {
    glint_image_writer_discard(w);
    return gli_fail(error, GLINT_E_ARGUMENT, "%s: %s is NULL", __func__,
                    !w       ? "writer"
                    : !bytes ? "bytes"
                             : "size");
  }
  if (!w->in_memory) {
    glint_image_writer_discard(w);
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "an image writer of a file ends with "
                    "glint_image_writer_finish");
  }
  stop_encoder(w, 0);
  glint_status st = incomplete(w, error);
  int closed = fclose(w->file.f); /* sets memory and memory_size */
  if (!st && closed != 0)
    st = gli_fail(error, GLINT_E_MEMORY, "%s: out of memory", w->file.path);
  if (st) {
    free(w->memory);
  } else {
    *bytes = w->memory;
    *size = w->memory_size;
  }
  free((char *)w->file.path);
  writer_free(w);
  return st;
}

const char *glint_image_writer_temp_path(const glint_image_writer *w) {
  return w && !w->in_memory && !w->file.unnamed ? w->file.temp : NULL;
}

void glint_image_writer_discard(glint_image_writer *w) {
  if (!w)
    return;
  stop_encoder(w, 1);
  if (w->in_memory) {
    fclose(w->file.f);
    free(w->memory);
  } else {
    gli_atomic_discard(&w->file);
  }
  free((char *)w->file.path);
  writer_free(w);
}
