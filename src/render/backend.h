/* The interface every tracer implements. A backend prepares its own copy of
 * the scene (precision, layout, acceleration structure) once, then renders
 * tiles from any number of threads; per-thread state lives in `scratch`. */
#ifndef GLINT_RENDER_BACKEND_H
#define GLINT_RENDER_BACKEND_H

#include "render/frame.h"

#include <stddef.h>

typedef struct glint_backend_ops {
  glint_status (*prepare)(const glint_scene *scene, const glint_frame *frame,
                          void **prepared, glint_stats *stats,
                          glint_error *error);
  void (*release)(void *prepared);
  /* Per-thread working memory, allocated by the driver (aligned, zeroed). */
  size_t (*scratch_bytes)(const void *prepared);
  /* Writes the tile's averaged, unclamped linear RGB into rgb (row-major,
   * tile width x tile height x 3) and adds its counts to stats. */
  void (*render_tile)(const void *prepared, const tile_rect *tile,
                      void *scratch, float *rgb, glint_stats *stats);
  /* The tile's primary rays' nearest hits only (glint_trace_primary):
   * returns how many hit. */
  uint64_t (*primary_tile)(const void *prepared, const tile_rect *tile,
                           glint_stats *stats);
} glint_backend_ops;

extern const glint_backend_ops glint_scalar_ops_float;
extern const glint_backend_ops glint_scalar_ops_double;
extern const glint_backend_ops glint_beam_ops_sse;
extern const glint_backend_ops glint_beam_ops_avx2;
extern const glint_backend_ops glint_beam_ops_avx512;
extern const glint_backend_ops glint_stream_ops_sse;
extern const glint_backend_ops glint_stream_ops_avx2;
extern const glint_backend_ops glint_stream_ops_avx512;

/* Test hooks: the packet nearest hit of one beam of W rays (origins and
 * directions as x[W] y[W] z[W]), per ISA, on a prepared beam backend. */
void glint_beam_nearest_hit_sse(const void *prepared, const float *o,
                                const float *d, int active_bits, float *t,
                                int *object);
void glint_beam_nearest_hit_avx2(const void *prepared, const float *o,
                                 const float *d, int active_bits, float *t,
                                 int *object);
void glint_beam_nearest_hit_avx512(const void *prepared, const float *o,
                                   const float *d, int active_bits, float *t,
                                   int *object);

/* The ops of a concrete backend (NULL if not built in). */
const glint_backend_ops *glint_backend_ops_of(glint_backend backend);

#endif
