/* Committing a scene: see render/world.h. */
#include "render/world.h"

#include "core/error.h"
#include "core/timer.h"
#include "scene/scene.h"

#include <stdlib.h>

glint_status gli_world_create(const glint_scene *scene, int borrow,
                              glint_world **out, glint_error *error) {
  if (!scene)
    return gli_fail(error, GLINT_E_ARGUMENT, "no scene to commit");
  glint_world *w = calloc(1, sizeof *w);
  if (!w)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  w->scene = scene;
  if (!borrow) {
    glint_status st = gli_scene_copy(scene, &w->owned_scene, error);
    if (st) {
      free(w);
      return st;
    }
    w->scene = w->owned_scene;
  }
  atomic_init(&w->refs, 1);
  w->extent = gli_scene_extent(w->scene);
  w->epsilon = gli_epsilon_at(w->extent, w->scene->camera.from);
  pthread_mutex_init(&w->lock, NULL);
  *out = w;
  return GLINT_OK;
}

void gli_world_retain(glint_world *w) { atomic_fetch_add(&w->refs, 1); }

void gli_world_release(glint_world *w) {
  if (!w || atomic_fetch_sub(&w->refs, 1) != 1)
    return;
  for (int k = 0; k < DATA_KIND_COUNT; k++)
    if (w->data[k])
      gli_data_ops_of((data_kind)k)->release(w->data[k]);
  if (w->bvh_built)
    gli_bvh_free(&w->bvh);
  pthread_mutex_destroy(&w->lock);
  glint_scene_destroy(w->owned_scene);
  free(w);
}

glint_status gli_world_bvh(glint_world *w, int wide, const gli_bvh **bvh,
                           glint_error *error) {
  glint_status st = GLINT_OK;
  pthread_mutex_lock(&w->lock);
  double t0 = gli_now();
  if (!w->bvh_built) {
    st = gli_bvh_build(w->scene, glint_cpu_count(), &w->bvh, error);
    w->bvh_built = st == GLINT_OK;
  }
  /* (renderers walking the tree meanwhile read nothing this writes) */
  if (!st && wide)
    st = gli_bvh_add_wide(&w->bvh, w->scene, error);
  w->prepare_seconds += gli_now() - t0;
  pthread_mutex_unlock(&w->lock);
  *bvh = &w->bvh;
  return st;
}

glint_status gli_world_data(glint_world *w, data_kind kind, const void **data,
                            glint_error *error) {
  const data_ops *ops = gli_data_ops_of(kind);
  if (!ops)
    return gli_fail(error, GLINT_E_UNSUPPORTED,
                    "this build has no converter for layout %d", (int)kind);
  glint_status st = GLINT_OK;
  pthread_mutex_lock(&w->lock);
  if (!w->data[kind]) {
    double t0 = gli_now();
    st = ops->convert(w->scene, w->epsilon, &w->data[kind], error);
    w->prepare_seconds += gli_now() - t0;
  }
  pthread_mutex_unlock(&w->lock);
  *data = w->data[kind];
  return st;
}

void gli_world_stats(glint_world *w, glint_stats *stats) {
  pthread_mutex_lock(&w->lock);
  stats->prepare_seconds = w->prepare_seconds;
  stats->bvh_nodes = w->bvh_built ? w->bvh.node_count : 0;
  stats->bvh_bytes = w->bvh_built ? gli_bvh_bytes(&w->bvh) : 0;
  stats->bvh_build_seconds = w->bvh_built ? w->bvh.build_seconds : 0;
  stats->wide_nodes = w->bvh_built ? w->bvh.wide.node_count : 0;
  stats->wide_bytes = w->bvh_built ? gli_wide_bytes(&w->bvh.wide) : 0;
  stats->wide_build_seconds = w->bvh_built ? w->bvh.wide.build_seconds : 0;
  stats->scene_bytes = stats->bvh_bytes + stats->wide_bytes;
  for (int k = 0; k < DATA_KIND_COUNT; k++)
    if (w->data[k])
      stats->scene_bytes += gli_data_ops_of((data_kind)k)->bytes(w->data[k]);
  pthread_mutex_unlock(&w->lock);
}

/* ---- the public API ----------------------------------------------------- */

/* The end of a commit: the BVH (unless already refitted) and the layout of
 * the default backend now, the others on first use by a renderer that needs
 * them; the world is released on failure. */
static glint_status finish_commit(glint_world *w, glint_world **out,
                                  glint_stats *stats, glint_error *error) {
  const gli_bvh *bvh;
  glint_status st = gli_world_bvh(w, 0, &bvh, error);
  const gli_backend_ops *ops =
      gli_backend_ops_of(glint_backend_resolve(GLINT_BACKEND_AUTO));
  const void *data;
  if (!st)
    st = gli_world_data(w, ops->data, &data, error);
  if (st) {
    gli_world_release(w);
    return st;
  }
  if (stats)
    gli_world_stats(w, stats);
  *out = w;
  return GLINT_OK;
}

glint_status glint_world_commit(const glint_scene *scene, glint_world **out,
                                glint_stats *stats, glint_error *error) {
  GLI_NOT_NULL(scene, "scene", error);
  GLI_NOT_NULL(out, "world", error);
  glint_world *w = NULL;
  glint_status st = gli_world_create(scene, 0, &w, error);
  if (st)
    return st;
  return finish_commit(w, out, stats, error);
}

/* A refitted tree is kept while its surface area cost is at most this many
 * times its cost when built. Measured on the Stanford bunny moving for 48
 * frames (640x480, 2 threads): translated, the refitted tree costs what the
 * built one did and saves the build (1 ms of 2.5 a frame beyond rendering);
 * turned 7.5 degrees a frame, a refit's cost grows 5-14% while rendering
 * slows 15-40% (a cost ratio understates a turned tree's worse child
 * order), so turning objects get a new tree each frame. */
#define GLI_REFIT_LIMIT 1.02

glint_status glint_world_commit_at(const glint_scene *scene, double time,
                                   const glint_world *previous,
                                   glint_world **out, glint_stats *stats,
                                   glint_error *error) {
  GLI_NOT_NULL(scene, "scene", error);
  GLI_NOT_NULL(out, "world", error);
  glint_scene *still;
  glint_status st = glint_scene_at_time(scene, time, &still, error);
  if (st)
    return st;
  glint_world *w = NULL;
  if ((st = gli_world_create(still, 1, &w, error))) {
    glint_scene_destroy(still);
    return st;
  }
  w->owned_scene = still; /* the world's own copy: no second one */
  glint_error ignored;
  if (previous && previous->bvh_built &&
      gli_bvh_refit(&previous->bvh, still, &w->bvh, &ignored) == GLINT_OK) {
    if (w->bvh.cost <= GLI_REFIT_LIMIT * w->bvh.built_cost) {
      w->bvh_built = 1;
      w->prepare_seconds += w->bvh.build_seconds;
    } else {
      gli_bvh_free(&w->bvh); /* worn out: gli_world_bvh builds anew */
    }
  }
  return finish_commit(w, out, stats, error);
}

void glint_world_destroy(glint_world *w) { gli_world_release(w); }

void glint_world_get_info(const glint_world *w, glint_scene_info *info) {
  glint_scene_get_info(w ? w->scene : NULL, info);
}
