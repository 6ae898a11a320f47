/* The Portable Float Map: a text header "PF\n<width> <height>\n<scale>\n"
 * (a negative scale means little-endian), then 32-bit float RGB rows from
 * the bottom of the image up. */
#include "image/image.h"

#include <stdlib.h>
#include <string.h>

int gli_pfm_encode(const glint_film *film, FILE *f) {
  if (fprintf(f, "PF\n%d %d\n-1.0\n", film->width, film->height) < 0)
    return -1;
  size_t row = (size_t)film->width * 3;
  uint32_t probe = 1;
  int little = *(const uint8_t *)&probe == 1;
  float *swapped = little ? NULL : malloc(row * sizeof *swapped);
  if (!little && !swapped)
    return -1;
  for (int y = film->height - 1; y >= 0; y--) {
    const float *src = film->rgb + (size_t)y * row;
    if (!little) {
      for (size_t i = 0; i < row; i++) {
        uint32_t v;
        memcpy(&v, &src[i], 4);
        v = (v >> 24) | ((v >> 8) & 0xff00) | ((v << 8) & 0xff0000) | (v << 24);
        memcpy(&swapped[i], &v, 4);
      }
      src = swapped;
    }
    if (fwrite(src, sizeof *src, row, f) != row) {
      free(swapped);
      return -1;
    }
  }
  free(swapped);
  return 0;
}
