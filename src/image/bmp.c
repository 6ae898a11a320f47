/* 24-bit uncompressed BMP (BITMAPINFOHEADER), the thesis's output format:
 * rows bottom-up, BGR, each row padded to 4 bytes. */
#include "image/image.h"

#include "core/error.h"

#include <stdlib.h>
#include <string.h>

static void put16(uint8_t *p, uint32_t v) {
  p[0] = (uint8_t)v;
  p[1] = (uint8_t)(v >> 8);
}

static void put32(uint8_t *p, uint32_t v) {
  put16(p, v);
  put16(p + 2, v >> 16);
}

static uint32_t get16(const uint8_t *p) { return p[0] | (uint32_t)p[1] << 8; }
static uint32_t get32(const uint8_t *p) {
  return get16(p) | get16(p + 2) << 16;
}

int gli_bmp_encode(const glint_image *im, FILE *f) {
  uint32_t stride = ((uint32_t)im->width * 3 + 3) & ~3u;
  uint32_t data = stride * (uint32_t)im->height;
  uint8_t hdr[54] = {'B', 'M'};
  put32(hdr + 2, 54 + data); /* file size */
  put32(hdr + 10, 54);       /* pixel data offset */
  put32(hdr + 14, 40);       /* BITMAPINFOHEADER */
  put32(hdr + 18, (uint32_t)im->width);
  put32(hdr + 22, (uint32_t)im->height); /* positive: bottom-up */
  put16(hdr + 26, 1);                    /* planes */
  put16(hdr + 28, 24);                   /* bits per pixel */
  put32(hdr + 34, data);
  put32(hdr + 38, 2835); /* 72 dpi */
  put32(hdr + 42, 2835);
  if (fwrite(hdr, 1, sizeof hdr, f) != sizeof hdr)
    return -1;
  uint8_t *row = calloc(stride, 1);
  if (!row)
    return -1;
  for (int y = im->height - 1; y >= 0; y--) {
    const uint8_t *src = im->rgb + (size_t)y * im->width * 3;
    for (int x = 0; x < im->width; x++) {
      row[3 * x + 0] = src[3 * x + 2];
      row[3 * x + 1] = src[3 * x + 1];
      row[3 * x + 2] = src[3 * x + 0];
    }
    if (fwrite(row, 1, stride, f) != stride) {
      free(row);
      return -1;
    }
  }
  free(row);
  return 0;
}

glint_status gli_bmp_decode(FILE *f, const char *path, glint_image **out,
                            int size[2], glint_error *error) {
  uint8_t hdr[54];
  size_t got = fread(hdr, 1, sizeof hdr, f);
  if (got < 2 || hdr[0] != 'B' || hdr[1] != 'M')
    return gli_fail(error, GLINT_E_PARSE, "%s: not a BMP file", path);
  if (got != sizeof hdr) /* "BM" and less than its headers */
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: truncated BMP file (%zu bytes of its 54-byte header)",
                    path, got);
  uint32_t offset = get32(hdr + 10), hsize = get32(hdr + 14);
  int32_t w = (int32_t)get32(hdr + 18), h = (int32_t)get32(hdr + 22);
  if (hsize < 40)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: a BMP with a %lu-byte header (OS/2 or older; glint "
                    "reads Windows BMPs, of 40 bytes or more)",
                    path, (unsigned long)hsize);
  if (get16(hdr + 28) != 24 || get32(hdr + 30) != 0)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: only uncompressed 24-bit BMP is supported", path);
  if (offset < 14 + (uint64_t)hsize) /* in 32 bits, hsize 2^32 - 1 wrapped */
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: the pixels start at byte %lu, inside the %lu bytes "
                    "of the headers",
                    path, (unsigned long)offset, 14ul + hsize);
  /* A negative height means rows top to bottom; INT32_MIN has no positive
   * twin, and no size beyond glint's images is worth reading. */
  if (w < 1 || w > GLINT_MAX_DIMENSION || h == 0 || h < -GLINT_MAX_DIMENSION ||
      h > GLINT_MAX_DIMENSION)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: a BMP of %ld x %ld pixels (glint reads 1 to %d a "
                    "side)",
                    path, (long)w, (long)h, GLINT_MAX_DIMENSION);
  int top_down = h < 0;
  if (top_down)
    h = -h;
  size[0] = w;
  size[1] = h;
  if (!out)
    return GLINT_OK;
  uint32_t stride = ((uint32_t)w * 3 + 3) & ~3u;
  uint64_t needed = offset + (uint64_t)stride * (uint64_t)h;
  long long bytes = gli_file_size(f);
  if (bytes >= 0 && (uint64_t)bytes < needed)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: truncated BMP file (%lld bytes, where its %ld x %ld "
                    "pixels end at byte %llu)",
                    path, bytes, (long)w, (long)h, (unsigned long long)needed);
  glint_image *im;
  glint_status st = gli_image_create_for(path, w, h, &im, error);
  if (st)
    return st;
  uint8_t *row = malloc(stride);
  if (!row) {
    glint_image_destroy(im);
    return gli_fail(error, GLINT_E_MEMORY, "%s: out of memory", path);
  }
  if (fseek(f, (long)offset, SEEK_SET) != 0) {
    free(row);
    glint_image_destroy(im);
    return gli_fail(error, GLINT_E_PARSE, "%s: truncated BMP file", path);
  }
  for (int i = 0; i < h; i++) {
    if (fread(row, 1, stride, f) != stride) {
      free(row);
      glint_image_destroy(im);
      return gli_fail(error, GLINT_E_PARSE, "%s: truncated BMP file", path);
    }
    int y = top_down ? i : h - 1 - i;
    uint8_t *dst = im->rgb + (size_t)y * w * 3;
    for (int x = 0; x < w; x++) {
      dst[3 * x + 0] = row[3 * x + 2];
      dst[3 * x + 1] = row[3 * x + 1];
      dst[3 * x + 2] = row[3 * x + 0];
    }
  }
  free(row);
  *out = im;
  return GLINT_OK;
}
