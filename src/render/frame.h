/* What every backend needs to know about the frame being rendered: the
 * user's settings, validated and resolved. */
#ifndef GLINT_RENDER_FRAME_H
#define GLINT_RENDER_FRAME_H

#include "glint.h"

/* Tiles are the unit of work handed to threads. 16x16 pixels divides into
 * every beam shape (2x2, 4x2, 4x4) and keeps 1200 tiles in a 640x480 frame
 * for load balancing. */
#define GLINT_TILE_SIZE 16

typedef struct glint_frame {
  int width, height, spp, max_depth;
  glint_math math;
  int rcp_newton;
  glint_accel accel;
  double epsilon;            /* SPEC §3: smallest t of a hit */
  const float (*samples)[2]; /* spp offsets from the pixel centre, in pixels */
} glint_frame;

typedef struct tile_rect {
  int x0, y0, x1, y1; /* pixels [x0, x1) x [y0, y1) */
} tile_rect;

/* SPEC §5: the sample positions of a pixel, as offsets from its centre. One
 * sample is the centre; five are the thesis's centre and (±1/4, ±1/4);
 * any other count is a deterministic Hammersley set. */
void glint_sample_offsets(int spp, float (*offsets)[2]);

#endif
