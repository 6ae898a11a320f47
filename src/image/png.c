/* PNG through libpng. */
#include "image/image.h"

#include "core/error.h"

#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <zlib.h>
#include <stdlib.h>
#include <string.h>

/* libpng's complaints become part of glint's one message instead of lines
 * of their own on stderr: errors are kept for it, warnings dropped. */
typedef struct png_complaint {
  char message[128];
} png_complaint;

static void png_keep_error(png_structp png, png_const_charp message) {
  png_complaint *c = png_get_error_ptr(png);
  snprintf(c->message, sizeof c->message, "%s", message);
  png_longjmp(png, 1);
}

static void png_drop_warning(png_structp png, png_const_charp message) {
  (void)png;
  (void)message;
}

/* libpng's state for one file being written. Each step sets its own
 * setjmp, since libpng's longjmp must land in a function still running. */
struct gli_png_writer {
  png_structp png;
  png_infop info;
  png_complaint complaint; /* libpng holds its address */
};

void gli_png_abort(gli_png_writer *w) {
  if (w) {
    png_destroy_write_struct(&w->png, &w->info);
    free(w);
  }
}

/* The header of gli_png_begin; 0 on success. */
static int png_start(gli_png_writer *w, FILE *f, int width, int height,
                     double gamma, glint_png_compression compression) {
  if (setjmp(png_jmpbuf(w->png)))
    return -1;
  png_structp png = w->png;
  png_init_io(png, f);
  if (compression == GLINT_PNG_SMALLEST) {
    png_set_compression_level(png, 9);
    png_set_filter(png, 0, PNG_ALL_FILTERS);
  } else {
    /* Measured on the thesis scenes at 640x480 (zlib 1.2.13): zlib's
     * run-length strategy on the "sub" filter encodes in 3-5 ms against
     * 17-26 ms for the default (level 6, adaptive filters), files 10-90%
     * larger; level 1 is both slower and larger than it. */
    png_set_compression_strategy(png, Z_RLE);
    png_set_filter(png, 0, PNG_FILTER_SUB);
    /* Runs are matched at distance 1 only, so a smaller window loses
     * nothing, and blocks of 8192 symbols (memory level 7) came out
     * 0.2-1.5% smaller than 16384. zlib's state is then 96 KiB instead of
     * 256 KiB: on Whitted, one thread, the file was finished 0.58 ms after
     * the last tile instead of 0.94 ms (medians of 61). Windows below 8 KiB
     * slide too often: 512 bytes took 12.9 ms. */
    png_set_compression_window_bits(png, 13);
    png_set_compression_mem_level(png, 7);
  }
  png_set_IHDR(png, w->info, (png_uint_32)width, (png_uint_32)height, 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  /* The file's gamma is 1/encoding gamma (PNG specification, 11.3.3.2). */
  png_set_gAMA(png, w->info, 1.0 / gamma);
  png_write_info(png, w->info);
  return 0;
}

gli_png_writer *gli_png_begin(FILE *f, int width, int height, double gamma,
                              glint_png_compression compression) {
  gli_png_writer *w = calloc(1, sizeof *w);
  if (!w)
    return NULL;
  w->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &w->complaint,
                                   png_keep_error, png_drop_warning);
  if (w->png)
    w->info = png_create_info_struct(w->png);
  if (!w->info || png_start(w, f, width, height, gamma, compression)) {
    gli_png_abort(w);
    return NULL;
  }
  return w;
}

int gli_png_rows(gli_png_writer *w, const uint8_t *rgb, int rows,
                 size_t row_bytes) {
  if (setjmp(png_jmpbuf(w->png)))
    return -1;
  for (int y = 0; y < rows; y++)
    png_write_row(w->png, rgb + (size_t)y * row_bytes);
  return 0;
}

int gli_png_end(gli_png_writer *w) {
  if (setjmp(png_jmpbuf(w->png))) {
    gli_png_abort(w);
    return -1;
  }
  png_write_end(w->png, NULL);
  gli_png_abort(w); /* frees */
  return 0;
}

int gli_png_encode(const glint_image *im, glint_png_compression compression,
                   FILE *f) {
  gli_png_writer *w =
      gli_png_begin(f, im->width, im->height, im->gamma, compression);
  if (!w)
    return -1;
  if (gli_png_rows(w, im->rgb, im->height, (size_t)im->width * 3)) {
    gli_png_abort(w);
    return -1;
  }
  return gli_png_end(w) || ferror(f) ? -1 : 0;
}

/* Each row's first `width` bytes, palette indices, looked up into the row's
 * RGB in place (from the right: a pixel's three bytes lie at or after its
 * index). Returns the first index past the palette, else -1. */
static int palette_to_rgb(glint_image *im, const png_color *palette,
                          int colours) {
  for (int y = 0; y < im->height; y++) {
    uint8_t *row = im->rgb + (size_t)y * (size_t)im->width * 3;
    for (int x = im->width - 1; x >= 0; x--) {
      int index = row[x];
      if (index >= colours)
        return index;
      row[3 * x] = palette[index].red;
      row[3 * x + 1] = palette[index].green;
      row[3 * x + 2] = palette[index].blue;
    }
  }
  return -1;
}

glint_status gli_png_decode(FILE *f, const char *path, glint_image **out,
                            int size[2], glint_error *error) {
  /* The signature read here: a short file that is no PNG at all is not
   * called a cut-short one below */
  png_byte signature[8];
  size_t got = fread(signature, 1, sizeof signature, f);
  if (got == 0 || png_sig_cmp(signature, 0, got) != 0)
    return gli_fail(error, GLINT_E_PARSE, "%s: not a PNG file", path);
  if (got < sizeof signature)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: truncated PNG file (%zu bytes of its signature)", path,
                    got);
  png_complaint complaint = {"not a PNG file"};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &complaint,
                                           png_keep_error, png_drop_warning);
  if (!png)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  png_infop info = png_create_info_struct(png);
  glint_image *volatile im = NULL;
  png_bytep *volatile rows = NULL;
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, NULL);
    glint_image_destroy(im);
    free(rows);
    /* libpng's "Read Error" is the file ending early */
    if (strcmp(complaint.message, "Read Error") == 0)
      return gli_fail(error, GLINT_E_PARSE,
                      "%s: truncated PNG file (it ends before its IEND)", path);
    return gli_fail(error, GLINT_E_PARSE, "%s: not a valid PNG file (%s)", path,
                    complaint.message);
  }
  png_init_io(png, f);
  png_set_sig_bytes(png, (int)sizeof signature);
  /* Ancillary chunks are skipped unread: glint reads the pixels and a
   * palette only (tRNS's alpha is dropped anyway). libpng allocates a text
   * or suggested-palette chunk whole at the size its header claims, and
   * zeroes it, before reading a byte of it: a 43-byte file claiming a
   * 2 GiB tEXt cost 2 GiB, libpng's own size limit being a mere warning
   * when reading. */
  static const png_byte ignored[] = "bKGD\0cHRM\0eXIf\0gAMA\0hIST\0iCCP\0"
                                    "iTXt\0oFFs\0pCAL\0pHYs\0sBIT\0sCAL\0"
                                    "sPLT\0sRGB\0tEXt\0tIME\0zTXt";
  png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, NULL, 0);
  png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, ignored,
                              (int)(sizeof ignored / 5));
  png_read_info(png, info);
  png_uint_32 w = png_get_image_width(png, info);
  png_uint_32 h = png_get_image_height(png, info);
  /* 16-bit samples cut to 8 would hide differences glint compare is asked
   * to find (two images apart in the low bytes came out identical); glint
   * writes 8 bits a sample, and reads PPM's maxval 255 only, so here too. */
  if (png_get_bit_depth(png, info) > 8) {
    png_destroy_read_struct(&png, &info, NULL);
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: a PNG of 16-bit samples (glint reads 8 bits a "
                    "sample, as it writes)",
                    path);
  }
  /* Normalise every other PNG flavour to 8-bit RGB: greys expanded, alpha
   * dropped (glint's images are RGB). A palette's indices are read a byte
   * each and looked up here (palette_to_rgb): libpng makes an index past
   * the palette's end a black pixel with no more than a warning. */
  png_colorp palette = NULL;
  int colours = 0;
  int indexed = png_get_color_type(png, info) == PNG_COLOR_TYPE_PALETTE &&
                png_get_PLTE(png, info, &palette, &colours);
  if (indexed) {
    png_set_packing(png);
  } else { /* (gray_to_rgb expands palettes too) */
    png_set_expand(png);
    png_set_gray_to_rgb(png);
  }
  png_set_strip_alpha(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (w < 1 || h < 1 || w > GLINT_MAX_DIMENSION || h > GLINT_MAX_DIMENSION) {
    png_destroy_read_struct(&png, &info, NULL);
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: a PNG of %lu x %lu pixels (glint reads 1 to %d a "
                    "side)",
                    path, (unsigned long)w, (unsigned long)h,
                    GLINT_MAX_DIMENSION);
  }
  if (png_get_rowbytes(png, info) != (size_t)w * (indexed ? 1 : 3)) {
    png_destroy_read_struct(&png, &info, NULL);
    return gli_fail(error, GLINT_E_PARSE, "%s: unsupported PNG layout", path);
  }
  size[0] = (int)w;
  size[1] = (int)h;
  if (!out) {
    png_destroy_read_struct(&png, &info, NULL);
    return GLINT_OK;
  }
  glint_image *tmp;
  if (gli_image_create_for(path, (int)w, (int)h, &tmp, error)) {
    png_destroy_read_struct(&png, &info, NULL);
    return error ? error->status : GLINT_E_MEMORY;
  }
  im = tmp;
  rows = malloc(sizeof *rows * h);
  if (!rows) {
    png_destroy_read_struct(&png, &info, NULL);
    glint_image_destroy(tmp);
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  }
  for (png_uint_32 y = 0; y < h; y++)
    rows[y] = tmp->rgb + (size_t)y * w * 3;
  png_read_image(png, rows);
  png_read_end(png, NULL);
  free(rows);
  rows = NULL;
  int bad_index = indexed ? palette_to_rgb(tmp, palette, colours) : -1;
  png_destroy_read_struct(&png, &info, NULL);
  if (bad_index >= 0) {
    glint_image_destroy(tmp);
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: a pixel's palette index %d is past the palette's %d "
                    "colour%s",
                    path, bad_index, colours, colours == 1 ? "" : "s");
  }
  *out = tmp;
  return GLINT_OK;
}
