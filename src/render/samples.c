#include "render/frame.h"

/* Van der Corput radical inverse in base 2. */
static double radical_inverse2(unsigned i) {
  double r = 0, f = 0.5;
  for (; i; i >>= 1, f *= 0.5)
    if (i & 1)
      r += f;
  return r;
}

void gli_sample_offsets(int spp, float (*o)[2]) {
  if (spp == 1) {
    o[0][0] = o[0][1] = 0;
    return;
  }
  if (spp == 5) { /* thesis §4.4.2 */
    static const float thesis[5][2] = {{0, 0},
                                       {-0.25f, -0.25f},
                                       {0.25f, -0.25f},
                                       {-0.25f, 0.25f},
                                       {0.25f, 0.25f}};
    for (int i = 0; i < 5; i++)
      o[i][0] = thesis[i][0], o[i][1] = thesis[i][1];
    return;
  }
  for (int i = 0; i < spp; i++) {
    double y = radical_inverse2((unsigned)i) + 0.5 / spp;
    if (y >= 1)
      y -= 1;
    o[i][0] = (float)((i + 0.5) / spp - 0.5);
    o[i][1] = (float)(y - 0.5);
  }
}
