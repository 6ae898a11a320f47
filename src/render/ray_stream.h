/* Ray streams: the stream tracer's memory (render/stream_tracer.c). A
 * generation's rays as structure-of-arrays buffers of bounded capacity, all
 * carved from one per-thread block; compaction (appending a packet's live
 * lanes contiguously, so the next generation's packets are full again); and
 * the log through which rays add what they bring to their pixels. Compiled
 * once per ISA with the tracer. */
#ifndef GLINT_RENDER_RAY_STREAM_H
#define GLINT_RENDER_RAY_STREAM_H

#include "render/frame.h"
#include "simd/vvec3.h"

#include <stdint.h>
#include <string.h>
#include <x86intrin.h>

#define STREAM_CAPACITY 4096 /* rays per generation buffer */

/* A generation's rays, structure of arrays. */
typedef struct ray_stream {
  float *ox, *oy, *oz, *dx, *dy, *dz, *wr, *wg, *wb;
  int32_t *pixel;
  int count, cursor;
} ray_stream;

/* Shadow rays whose tracing waits (render/stream_tracer.c, shadow rays of
 * the deeper generations): from the shading point o towards a light, d
 * unit, the light at distance dist; what the ray brings to its pixel if
 * nothing blocks it (c, scaled by the transmission found); and its sort
 * key (shadow_key). */
typedef struct shadow_stream {
  float *ox, *oy, *oz, *dx, *dy, *dz, *dist, *cr, *cg, *cb;
  int32_t *pixel, *key;
  uint16_t *order, *sorted; /* the rays' order by key, and the sort's spare */
  int count;
} shadow_stream;

typedef struct stream_scratch {
  /* Two streams per generation level: the transmitted (refracted) rays and
   * the reflected ones. Kept apart, each is coherent: a packet of rays
   * that entered a glass sphere all meet it again from inside, while a
   * packet mixing them with rays bounced off it would shade two objects
   * per packet, lane by lane. (Level 0, the primary rays, is made in
   * registers and stays empty.) */
  ray_stream *levels;
  float *accum; /* tile pixels x (r, g, b, unused), summed over samples */
  float *log;   /* (r, g, b, pixel) waiting to be added (see fold_log) */
  int log_count;
  shadow_stream shadows;
} stream_scratch;

enum { TRANSMITTED = 0, REFLECTED = 1 };
#define STREAM(sc, level, kind) (&(sc)->levels[2 * (level) + (kind)])

/* ---- memory ------------------------------------------------------------ */

#define RAY_FLOATS 9
#define LOG_CAPACITY 512     /* a multiple of every W; 8 KiB stays in L1 */
#define SHADOW_CAPACITY 4096 /* waiting shadow rays (at most 65 536) */
#define SHADOW_FLOATS 12     /* ten floats, the pixel and the key */

/* Each array has room for W floats past its capacity: compress-stores
 * write whole vectors. */
#define SLOTS (STREAM_CAPACITY + GLI_SIMD_WIDTH)

static inline size_t level_bytes(void) {
  return (size_t)SLOTS * (RAY_FLOATS * sizeof(float) + sizeof(int32_t)) +
         (RAY_FLOATS + 1) * 64;
}

static inline size_t accum_bytes(void) {
  return (size_t)GLI_TILE_SIZE * GLI_TILE_SIZE * 4 * sizeof(float) +
         (size_t)LOG_CAPACITY * 4 * sizeof(float) + 2 * 64;
}

static inline size_t shadow_bytes(void) {
  return (size_t)(SHADOW_CAPACITY + GLI_SIMD_WIDTH) *
             (SHADOW_FLOATS * sizeof(float) + 2 * sizeof(uint16_t)) +
         (SHADOW_FLOATS + 2) * 64;
}

static inline size_t scratch_bytes(int levels) {
  return sizeof(stream_scratch) + 64 +
         (size_t)levels * 2 * (sizeof(ray_stream) + level_bytes()) +
         accum_bytes() + shadow_bytes() + 64 * 32;
}

/* Carves the scratch block (allocated by the driver, 64-byte aligned) into
 * the buffers, each aligned for the widest vector. */
static inline char *align64(char *p) {
  return (char *)(((uintptr_t)p + 63) & ~(uintptr_t)63);
}

static inline stream_scratch *carve(void *scratch, int levels) {
  char *p = scratch;
  stream_scratch *sc = (stream_scratch *)p;
  p = align64(p + sizeof *sc);
  sc->levels = (ray_stream *)p;
  p = align64(p + (size_t)levels * 2 * sizeof *sc->levels);
  for (int l = 0; l < 2 * levels; l++) {
    ray_stream *r = &sc->levels[l];
    float **f[RAY_FLOATS] = {&r->ox, &r->oy, &r->oz, &r->dx, &r->dy,
                             &r->dz, &r->wr, &r->wg, &r->wb};
    for (int k = 0; k < RAY_FLOATS; k++) {
      *f[k] = (float *)p;
      p = align64(p + SLOTS * sizeof(float));
    }
    r->pixel = (int32_t *)p;
    p = align64(p + SLOTS * sizeof(int32_t));
    r->count = r->cursor = 0;
  }
  sc->accum = (float *)p;
  p = align64(p + (size_t)GLI_TILE_SIZE * GLI_TILE_SIZE * 4 * sizeof(float));
  sc->log = (float *)p;
  sc->log_count = 0;
  p = align64(p + (size_t)LOG_CAPACITY * 4 * sizeof(float));
  shadow_stream *sh = &sc->shadows;
  float **f[10] = {&sh->ox, &sh->oy,   &sh->oz, &sh->dx, &sh->dy,
                   &sh->dz, &sh->dist, &sh->cr, &sh->cg, &sh->cb};
  int32_t **i[2] = {&sh->pixel, &sh->key};
  const size_t slots = SHADOW_CAPACITY + GLI_SIMD_WIDTH;
  for (int k = 0; k < 10; k++) {
    *f[k] = (float *)p;
    p = align64(p + slots * sizeof(float));
  }
  for (int k = 0; k < 2; k++) {
    *i[k] = (int32_t *)p;
    p = align64(p + slots * sizeof(int32_t));
  }
  sh->order = (uint16_t *)p;
  p = align64(p + slots * sizeof(uint16_t));
  sh->sorted = (uint16_t *)p;
  sh->count = 0;
  return sc;
}

/* Compaction: the lanes of m appended at the stream's end. */
static ALWAYS_INLINE void ray_stream_append(ray_stream *r, vmask m, vvec3 o,
                                            vvec3 d, vvec3 w, vint pixel) {
  int n = r->count;
  vv_compress_store(r->ox + n, r->oy + n, r->oz + n, m, o);
  vv_compress_store(r->dx + n, r->dy + n, r->dz + n, m, d);
  vv_compress_store(r->wr + n, r->wg + n, r->wb + n, m, w);
  r->count += vf_compress_store((float *)r->pixel + n, m, vi_as_vf(pixel));
}

/* The same for shadow rays that wait: from o along d to a light at
 * distance dist, bringing `brings` to `pixel` where nothing blocks them,
 * sorted later by `key`. */
static ALWAYS_INLINE void shadow_stream_append(shadow_stream *sh, vmask m,
                                               vvec3 o, vvec3 d, vfloat dist,
                                               vvec3 brings, vint pixel,
                                               vint key) {
  int n = sh->count;
  vv_compress_store(sh->ox + n, sh->oy + n, sh->oz + n, m, o);
  vv_compress_store(sh->dx + n, sh->dy + n, sh->dz + n, m, d);
  vf_compress_store(sh->dist + n, m, dist);
  vv_compress_store(sh->cr + n, sh->cg + n, sh->cb + n, m, brings);
  vf_compress_store((float *)sh->pixel + n, m, vi_as_vf(pixel));
  sh->count += vf_compress_store((float *)sh->key + n, m, vi_as_vf(key));
}

/* What secondary rays bring to pixels is logged, a packet at a time with
 * four vector stores, and folded into the pixels when the log fills and at
 * the end of the tile: a packet's rays can share a pixel (rays from one
 * primary sample meet again in a later generation), so the adds must be
 * done one by one, and done in one tight sequential pass they cost a
 * fraction of doing them packet by packet. (Measured: a gather-add-scatter
 * with AVX-512 conflict detection, or a loop over the packet's lanes, each
 * cost as much as all the rest of the secondary rays' work on Whitted.) */
static inline void fold_log(stream_scratch *sc) {
  /* Entries are (r, g, b, pixel) and pixels (r, g, b, unused): one 4-wide
   * load, add and store each. */
  float *accum = sc->accum;
  const float *log = sc->log;
  for (int i = 0; i < sc->log_count; i++) {
    const float *e = log + 4 * i;
    int32_t px;
    memcpy(&px, e + 3, sizeof px);
    __m128 sum = _mm_add_ps(_mm_load_ps(accum + 4 * px), _mm_load_ps(e));
    _mm_store_ps(accum + 4 * px, sum);
  }
  sc->log_count = 0;
}

static ALWAYS_INLINE void accumulate(stream_scratch *sc, vmask m, vint pixel,
                                     vvec3 c) {
  if (sc->log_count > LOG_CAPACITY - LANES)
    fold_log(sc);
  int n = sc->log_count;
  /* inactive lanes bring nothing, to pixel 0 */
  vf_store_quads(sc->log + 4 * n, vf_keep(m, c.x), vf_keep(m, c.y),
                 vf_keep(m, c.z), vi_as_vf(vi_select(m, pixel, vi_set1(0))));
  sc->log_count = n + LANES;
}

#endif
