/* The committed world (include/glint.h, "Worlds and renderers"): a private
 * copy of the scene (or, inside glint_render, the caller's scene itself), its
 * BVH, and the scene converted for each family of
 * backends in use. Conversions are made on first use by a renderer, under
 * the world's lock, and never change afterwards, so renderers on any threads
 * read them without locking. */
#ifndef GLINT_RENDER_WORLD_H
#define GLINT_RENDER_WORLD_H

#include "accel/bvh.h"
#include "render/backend.h"

#include <pthread.h>
#include <stdatomic.h>

struct glint_world {
  atomic_int refs; /* the caller's reference and one per renderer */
  const glint_scene *scene;
  glint_scene *owned_scene; /* the copy, or NULL when the scene is borrowed */
  double epsilon;           /* docs/specification.md §3, fixed at commit */
  double extent; /* the primitives' scale, for a frame camera's epsilon */
  pthread_mutex_t lock;
  int bvh_built;
  gli_bvh bvh;
  void *data[DATA_KIND_COUNT];
  double prepare_seconds; /* conversions and BVH build so far */
};

/* Commits without building anything yet (glint_render builds only what its
 * backend and accel use). `borrow` uses the scene itself instead of a copy:
 * only for a world that cannot outlive the call that made it, as
 * glint_render's (a copy of a 32k-triangle mesh costs milliseconds). Its
 * BVH is built on every core the process may use (glint_cpu_count). */
glint_status gli_world_create(const glint_scene *scene, int borrow,
                              glint_world **world, glint_error *error);
void gli_world_retain(glint_world *world);
void gli_world_release(glint_world *world);

/* The BVH, built on first use; with its wide tree when `wide` (a walk of
 * every ray alone, --accel bvh8), collapsed on first such use where the
 * build did not (accel/bvh.h). */
glint_status gli_world_bvh(glint_world *world, int wide, const gli_bvh **bvh,
                           glint_error *error);
/* The scene converted for one family of backends, on first use. */
glint_status gli_world_data(glint_world *world, data_kind kind,
                            const void **data, glint_error *error);
/* What has been built so far: BVH and data sizes and times. */
void gli_world_stats(glint_world *world, glint_stats *stats);

#endif
