/* The interface every tracer implements, in two halves.
 *
 * Conversion (per world): a scene is converted once into the layout a family
 * of backends reads (scalar float, scalar double, or the packet scene of one
 * instruction set, shared by its beam and stream backends). The world owns
 * these and never changes them.
 *
 * Rendering (per renderer): a renderer binds converted data to the
 * acceleration structure it uses (a view: a small private header over the
 * world's arrays) and renders tiles of frames from any number of threads;
 * per-thread state lives in `scratch`. */
#ifndef GLINT_RENDER_BACKEND_H
#define GLINT_RENDER_BACKEND_H

#include "accel/bvh.h"
#include "render/frame.h"

#include <stddef.h>

/* The converted layouts, one per family of backends. */
typedef enum data_kind {
  DATA_SCALAR_FLOAT = 0,
  DATA_SCALAR_DOUBLE,
  DATA_PACKET_SSE,
  DATA_PACKET_AVX2,
  DATA_PACKET_AVX512,
  DATA_KIND_COUNT
} data_kind;

typedef struct data_ops {
  /* Converts the scene; eps is the world's smallest hit distance. */
  glint_status (*convert)(const glint_scene *scene, double eps, void **data,
                          glint_error *error);
  void (*release)(void *data);
  size_t (*bytes)(const void *data);
  /* A view of the data that traverses `bvh` (node_count 0: brute force)
   * as `accel` says (glint.h). */
  glint_status (*bind)(const void *data, const gli_bvh *bvh, glint_accel accel,
                       void **view, glint_error *error);
  void (*unbind)(void *view);
  /* The smallest hit distance of a view's frames from now on: the
   * epsilon depends on the camera (docs/specification.md §3), and a frame
   * may have its own (glint_frame_settings.camera). */
  void (*set_epsilon)(void *view, double eps);
} data_ops;

typedef struct gli_backend_ops {
  data_kind data;
  /* Whether its rays may walk the wide BVH alone (the hybrid walks,
   * --accel bvh8); the stream backends' never do (render/packet_rays.h). */
  int walks_alone;
  /* Per-thread working memory for frames up to max_depth, allocated by the
   * renderer (aligned, zeroed); NULL: none. */
  size_t (*scratch_bytes)(int max_depth);
  /* Writes the tile's averaged, unclamped linear RGB into rgb (row-major,
   * tile width x tile height x 3) and adds its counts to stats. */
  void (*render_tile)(const void *view, const frame_params *frame,
                      const tile_rect *tile, void *scratch, float *rgb,
                      glint_stats *stats);
  /* The tile's primary rays' nearest hits only (glint_trace_primary):
   * returns how many hit. */
  uint64_t (*primary_tile)(const void *view, const frame_params *frame,
                           const tile_rect *tile, glint_stats *stats);
} gli_backend_ops;

extern const data_ops gli_scalar_data_float;
extern const data_ops gli_scalar_data_double;
extern const data_ops gli_packet_data_sse;
extern const data_ops gli_packet_data_avx2;
extern const data_ops gli_packet_data_avx512;

extern const gli_backend_ops gli_scalar_ops_float;
extern const gli_backend_ops gli_scalar_ops_double;
extern const gli_backend_ops gli_beam_ops_sse;
extern const gli_backend_ops gli_beam_ops_avx2;
extern const gli_backend_ops gli_beam_ops_avx512;
extern const gli_backend_ops gli_stream_ops_sse;
extern const gli_backend_ops gli_stream_ops_avx2;
extern const gli_backend_ops gli_stream_ops_avx512;

/* Test hooks: the packet nearest hit of one beam of W rays (origins and
 * directions as x[W] y[W] z[W]), per ISA, on a bound packet view. */
void gli_beam_nearest_hit_sse(const void *view, const float *o, const float *d,
                              int active_bits, float *t, int *object);
void gli_beam_nearest_hit_avx2(const void *view, const float *o, const float *d,
                               int active_bits, float *t, int *object);
void gli_beam_nearest_hit_avx512(const void *view, const float *o,
                                 const float *d, int active_bits, float *t,
                                 int *object);

/* The ops of a concrete backend, and of a converted layout (NULL if not
 * built in). */
const gli_backend_ops *gli_backend_ops_of(glint_backend backend);
const data_ops *gli_data_ops_of(data_kind kind);

#endif
