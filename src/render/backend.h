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
  void (*render_tile)(const void *prepared, const glint_tile *tile,
                      void *scratch, float *rgb, glint_stats *stats);
} glint_backend_ops;

extern const glint_backend_ops glint_scalar_ops_float;
extern const glint_backend_ops glint_scalar_ops_double;

#endif
