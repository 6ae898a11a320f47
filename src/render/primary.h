/* Primary beams (docs/specification.md §2, §6): W camera rays made in registers
 * for a block of BW x BH pixels of a tile, lane i on pixel (bx + i % BW, by + i
 * / BW), one sample position at a time. Shared by the beam and the stream
 * tracers (and glint_trace_primary), so all of them aim their rays identically.
 */
#ifndef GLINT_RENDER_PRIMARY_H
#define GLINT_RENDER_PRIMARY_H

#include "render/camera.h"
#include "render/frame.h"
#include "render/packet_shading.h"

/* Block shapes: 2x2 for SSE, 4x2 for AVX2, 4x4 for AVX-512 (issue 3). */
#if GLI_SIMD_WIDTH == 4
#define BLOCK_W 2
#else
#define BLOCK_W 4
#endif
#define BLOCK_H (LANES / BLOCK_W)

typedef struct primary_beams {
  vfloat lane_x, lane_y; /* each lane's pixel offset in its block */
  vfloat width, height, tan_x, tan_y; /* the image plane (camera.h) */
  vvec3 from, d, r, u;                /* the camera, splatted */
} primary_beams;

static ALWAYS_INLINE primary_beams primary_beams_init(const camera *cam) {
  primary_beams pb;
  SIMD_ALIGN float lx[LANES], ly[LANES];
  for (int i = 0; i < LANES; i++) {
    lx[i] = (float)(i % BLOCK_W);
    ly[i] = (float)(i / BLOCK_W);
  }
  pb.lane_x = vf_load(lx);
  pb.lane_y = vf_load(ly);
  pb.width = vf_set1(cam->width);
  pb.height = vf_set1(cam->height);
  pb.tan_x = vf_set1(cam->tan_x);
  pb.tan_y = vf_set1(cam->tan_y);
  pb.from = vv_set1(cam->from);
  pb.d = vv_set1(cam->d);
  pb.r = vv_set1(cam->r);
  pb.u = vv_set1(cam->u);
  return pb;
}

/* The pixel coordinates of the block at (bx, by) in *px, *py; returns the
 * lanes whose pixels lie inside the tile (a tile's edge may cut a block). */
static ALWAYS_INLINE vmask primary_block(const primary_beams *pb,
                                         const tile_rect *tile, int bx, int by,
                                         vfloat *px, vfloat *py) {
  *px = vf_add(vf_set1((float)bx), pb->lane_x);
  *py = vf_add(vf_set1((float)by), pb->lane_y);
  return vm_and(vf_lt(*px, vf_set1((float)tile->x1)),
                vf_lt(*py, vf_set1((float)tile->y1)));
}

/* The unit directions through the block's pixels at sample offset
 * (sample[0], sample[1]) from each pixel's centre. */
static ALWAYS_INLINE vvec3 primary_dir(const primary_beams *pb, vfloat px,
                                       vfloat py, const float sample[2],
                                       int newton) {
  /* docs/specification.md §2: x = (2 px / W - 1) tan_x, y = (1 - 2 py / H)
   * tan_y, in camera_dir's operations (render/camera.h): exactly 0 at the
   * image's centre, where px sx + ox, its terms rounded apart, was 1e-8
   * and a ray level with a plane through the eye hit it 1e7 away (the
   * middle column or row of an odd-sized image drawn as the plane). */
  vfloat one = vf_set1(1);
  vfloat sx = vf_add(px, vf_set1(0.5f + sample[0]));
  vfloat sy = vf_add(py, vf_set1(0.5f + sample[1]));
  vfloat x = vf_mul(vf_sub(vf_div(vf_add(sx, sx), pb->width), one), pb->tan_x);
  vfloat y = vf_mul(vf_sub(one, vf_div(vf_add(sy, sy), pb->height)), pb->tan_y);
  return vv_normalize(vv_madd(vv_madd(pb->d, x, pb->r), y, pb->u), newton);
}

/* Stores a block's colours into a tile's film (RGB rows of `tw` pixels),
 * the block's corner at (x, y) in the tile: a whole block row by row, a
 * block cut by the tile's edge lane by lane. */
static ALWAYS_INLINE void primary_block_store(float *rgb, int tw, int x, int y,
                                              vmask valid, vvec3 color) {
  SIMD_ALIGN float r[LANES], g[LANES], b[LANES];
  vf_store(r, color.x);
  vf_store(g, color.y);
  vf_store(b, color.z);
  unsigned bits = (unsigned)vm_bits(valid);
  if (bits == (1u << LANES) - 1) {
    for (int j = 0; j < BLOCK_H; j++) {
      float *out = rgb + ((size_t)(y + j) * (size_t)tw + (size_t)x) * 3;
      for (int i = 0; i < BLOCK_W; i++) {
        out[3 * i] = r[j * BLOCK_W + i];
        out[3 * i + 1] = g[j * BLOCK_W + i];
        out[3 * i + 2] = b[j * BLOCK_W + i];
      }
    }
    return;
  }
  for (int i = 0; i < LANES; i++)
    if (bits >> i & 1) {
      float *out = rgb + ((size_t)(y + i / BLOCK_W) * (size_t)tw +
                          (size_t)(x + i % BLOCK_W)) *
                             3;
      out[0] = r[i];
      out[1] = g[i];
      out[2] = b[i];
    }
}

#endif
