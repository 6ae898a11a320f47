/* What a frame asks of a backend: the camera, size, samples, depth and
 * maths of one frame, validated and resolved by the renderer. Everything a
 * backend needs that may change from frame to frame is here; everything that
 * does not (geometry, materials, the BVH) is in the committed world. */
#ifndef GLINT_RENDER_FRAME_H
#define GLINT_RENDER_FRAME_H

#include "glint.h"

/* Tiles are the unit of work handed to threads. 16x16 pixels divides into
 * every beam shape (2x2, 4x2, 4x4) and keeps 1200 tiles in a 640x480 frame
 * for load balancing. */
#define GLI_TILE_SIZE GLINT_TILE_SIZE

/* The pinhole camera of docs/specification.md §2 as an orthonormal basis,
 * computed once per frame in double whatever the precision (see
 * render/camera.h). */
typedef struct camera_basis {
  double from[3], dir[3], right[3], up[3];
  double tan_x, tan_y; /* half extents of the image plane at distance 1 */
  int width, height;
} camera_basis;

void gli_camera_basis_init(camera_basis *basis, const glint_camera *camera,
                           int width, int height);

/* docs/specification.md §4 (Faint rays): a reflected or refracted ray
 * whose weight (the product of the kr, kt and Beer factors on its way from
 * the eye) is below 2^-24 in every channel is not traced, whatever the
 * depth limit: what it could add to its pixel is below a float's precision
 * relative to what it sees (adaptive tree depth, R. Hall and D. Greenberg,
 * "A testbed for realistic image synthesis", 1983). A Whitted ray tree that
 * splits at every glass surface grows 1.3-1.6 times a level: without the
 * rule Billiard at depth 64 would not finish in days. The thesis scenes'
 * 8-bit images at depths 1-15 are unchanged by it (tests/test_shading.c
 * counts the rays it leaves). */
#define GLI_MIN_RAY_WEIGHT 0x1p-24

/* The largest weight a ray of the stream backends carries
 * (render/stream_tracer.c), which add w times what each hit brings to its
 * pixel rather than summing the ray tree from its leaves. Coefficients of
 * up to GLINT_MAX_COLOR (kr = kt = 1e6) overflow a float weight in a few
 * bounces, and an infinite weight times a light's zero term (a shadowed
 * light, a black channel) is NaN, which turned a whole pixel black where
 * the other backends saturate it. A hit brings at most a light's colour
 * times a surface's terms, 1e6 x (1e12 + 1e6), so 2^64 (1.8e19) keeps that
 * product finite; a weight that large saturates its pixel wherever a hit
 * brings more than 2^-64, as the ray trees of the other backends do. */
#define GLI_MAX_RAY_WEIGHT 0x1p64

/* A shadow ray's crossings are looked for short of its light, by the
 * scene's epsilon or 2^-20 of the distance, whichever is more: a light on
 * a surface (a lamp on a wall) has that surface at the segment's very end,
 * where rounding put the crossing before the light at some pixels and
 * after it at others, and the lit side was speckled with shadow. (pbrt-v4
 * ends its shadow rays short so, by 1e-4 of the segment.) The stretch to
 * the light inside an object (Beer's law) still runs to the light. */
#define GLI_SHADOW_SHORT 0x1p-20

typedef struct frame_params {
  camera_basis camera;
  int spp, max_depth;
  glint_math math;
  int rcp_newton;
  const float (*samples)[2]; /* spp offsets from the pixel centre, in pixels */
} frame_params;

typedef struct tile_rect {
  int x0, y0, x1, y1; /* pixels [x0, x1) x [y0, y1) */
} tile_rect;

/* docs/specification.md §5: the sample positions of a pixel, as offsets from
 * its centre. One sample is the centre; five are the thesis's centre and (±1/4,
 * ±1/4); fewer are a deterministic Hammersley set, and more are the
 * thesis's five followed by a Hammersley set shifted half a pixel. */
void gli_sample_offsets(int spp, float (*offsets)[2]);

#endif
