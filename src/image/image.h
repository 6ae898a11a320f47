#ifndef GLINT_IMAGE_IMAGE_H
#define GLINT_IMAGE_IMAGE_H

#include "glint.h"

#include <stdio.h>

struct glint_image {
  int width, height;
  double gamma; /* what the pixels were encoded with (PNG's gAMA) */
  uint8_t *rgb; /* width*height*3, top row first */
};

struct glint_film {
  int width, height;
  float *rgb; /* width*height*3, top row first, aligned */
};

/* docs/specification.md §4's 8-bit conversion of linear values: clamp to
 * [0, 1], then c^(1/gamma), then round(255 c) (image/byte_encoding.c). An
 * encoding is prepared once per gamma (a few powf a byte, about 0.05 ms,
 * for a gamma other than 1) and then used for whole films and, while a
 * frame renders, for each finished tile, from any number of threads. */
#define GLI_BYTE_BINS (0x3F800000u >> 16) /* floats in [0, 1) by top bits */
typedef struct gli_byte_encoding {
  double gamma;
  int one_step;                 /* a bin holds at most one threshold */
  float threshold[257];         /* [k]: the least value encoded as k or more */
  uint8_t start[GLI_BYTE_BINS]; /* the byte at each bin's lower end */
} gli_byte_encoding;
void gli_byte_encoding_init(gli_byte_encoding *encoding, double gamma);
void gli_byte_encode(const gli_byte_encoding *encoding, const float *src,
                     uint8_t *dst, size_t n);
/* One value by the formula itself, as the tests check the tables. */
uint8_t gli_byte_encode_one(float c, double gamma);

/* Writes `path` atomically: write(data, f) fills a temporary file beside
 * it (returning 0 on success), which is flushed, synced and renamed over
 * `path` only when complete. */
typedef int (*write_fn)(const void *data, FILE *f);
/* Whether gli_write_atomically could write `path` now (not a folder, and
 * its folder takes a new file); leaves nothing behind. */
glint_status gli_check_folder_writable(const char *path, glint_error *error);
/* glint_image_create for the pixels of file `path`, which its message of
 * running out of memory names. */
glint_status gli_image_create_for(const char *path, int w, int h,
                                  glint_image **image, glint_error *error);
glint_status gli_write_atomically(const char *path, write_fn write,
                                  const void *data, glint_error *error);

/* The same in steps, for files written while their pixels arrive: open the
 * temporary file, write to `f`, then commit (flush, sync, rename; `failed`
 * with its errno discards instead and reports the failure) or discard.
 * Where the file system allows, the temporary file has no name until the
 * commit links it (O_TMPFILE): a process killed before then leaves
 * nothing behind. */
typedef struct gli_atomic_file {
  const char *path;
  char *target; /* where path is a symbolic link, the file it names */
  char *temp;   /* the temporary name, which `unnamed` has not taken yet */
  int unnamed;
  FILE *f;
} gli_atomic_file;
glint_status gli_atomic_open(const char *path, gli_atomic_file *file,
                             glint_error *error);
glint_status gli_atomic_commit(gli_atomic_file *file, int failed,
                               int failed_errno, glint_error *error);
void gli_atomic_discard(gli_atomic_file *file);

/* GLINT_E_ARGUMENT unless GLINT_MIN_GAMMA <= gamma <= GLINT_MAX_GAMMA: the
 * one check of every call that takes a gamma. */
glint_status gli_gamma_check(double gamma, glint_error *error);

/* Film encoders: 0 on success. EXR returns -1 with errno 0 on a library
 * error, and is absent (GLINT_HAVE_EXR undefined) in builds without
 * OpenEXR. */
int gli_pfm_encode(const glint_film *film, FILE *f);
int gli_exr_encode(const glint_film *film, FILE *f);

/* Encoders write the whole image to an open stream; 0 on success. */
int gli_png_encode(const glint_image *image, glint_png_compression compression,
                   FILE *f);
/* The PNG encoder in steps, for rows that arrive over time: begin writes
 * the header, rows appends `rows` rows (row_bytes apart), end the rest and
 * frees; abort frees without finishing. NULL or -1 on failure (after which
 * only abort remains, and end has freed already). */
typedef struct gli_png_writer gli_png_writer;
gli_png_writer *gli_png_begin(FILE *f, int width, int height, double gamma,
                              glint_png_compression compression);
int gli_png_rows(gli_png_writer *w, const uint8_t *rgb, int rows,
                 size_t row_bytes);
int gli_png_end(gli_png_writer *w);
void gli_png_abort(gli_png_writer *w);
int gli_bmp_encode(const glint_image *image, FILE *f);
int gli_ppm_encode(const glint_image *image, FILE *f);
int gli_ppm_header(FILE *f, int width, int height); /* before the rows */

/* Decoders read a whole image, or with `image` NULL its header alone,
 * checked as for reading it; `size` gets the width and height. On failure
 * they fill error naming `path`. */

/* The size of the file f reads, or -1 where it has none (not a regular
 * file): a header's pixel count is checked against it before the pixels
 * are allocated (a 100-byte file claiming 16384 x 16384 pixels had 805 MB
 * reserved). */
long long gli_file_size(FILE *f);
glint_status gli_png_decode(FILE *f, const char *path, glint_image **image,
                            int size[2], glint_error *error);
glint_status gli_bmp_decode(FILE *f, const char *path, glint_image **image,
                            int size[2], glint_error *error);
glint_status gli_ppm_decode(FILE *f, const char *path, glint_image **image,
                            int size[2], glint_error *error);

#endif
