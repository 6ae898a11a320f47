#include "render/frame.h"

#include <math.h>

/* Van der Corput radical inverse in base 2. */
static double radical_inverse2(unsigned i) {
  double r = 0, f = 0.5;
  for (; i; i >>= 1, f *= 0.5)
    if (i & 1)
      r += f;
  return r;
}

/* n points of the Hammersley set in the pixel, (i + 1/2)/n across and the
 * radical inverse of i down, shifted by `shift` (toroidally) down and across.
 */
static void hammersley(int n, double shift, float (*o)[2]) {
  for (int i = 0; i < n; i++) {
    double x = (i + 0.5) / n + shift,
           y = radical_inverse2((unsigned)i) + 0.5 / n + shift;
    x -= floor(x);
    y -= floor(y);
    o[i][0] = (float)(x - 0.5);
    o[i][1] = (float)(y - 0.5);
  }
}

void gli_sample_offsets(int spp, float (*o)[2]) {
  if (spp == 1) {
    o[0][0] = o[0][1] = 0;
    return;
  }
  if (spp < 5) {
    hammersley(spp, 0, o);
    return;
  }
  /* Thesis §4.4.2; beyond five, more points between them, so that a
   * pattern's first five samples are always the thesis's (the viewer
   * refines an image sample by sample in this order). */
  static const float thesis[5][2] = {{0, 0},
                                     {-0.25f, -0.25f},
                                     {0.25f, -0.25f},
                                     {-0.25f, 0.25f},
                                     {0.25f, 0.25f}};
  for (int i = 0; i < 5; i++)
    o[i][0] = thesis[i][0], o[i][1] = thesis[i][1];
  hammersley(spp - 5, 0.5, o + 5);
}
