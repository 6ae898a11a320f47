/* What GLINT_BACKEND_AUTO runs: the beams or the streams of the widest ISA
 * this CPU has, whichever the scene and settings favour. Beams keep a
 * packet's rays in registers from the camera to the last bounce and win
 * while those rays stay together; ray streams regroup the rays of every
 * generation into full packets, at the cost of storing them, and win once
 * rays scatter: after many bounces among specular surfaces. Measured (one
 * thread, glint bench, docs/performance.md "The default backend"): the
 * beams are 10-23% faster on Whitted at every depth, on Billiard and Giza
 * up to depth 5 and on the SPD scenes with few specular surfaces
 * (mount-s6, tetra-s6); the streams are 1.2-2.5x faster on Billiard and
 * Giza from depth 10 and 1.2-1.5x on the SPD scenes full of mirrors (balls,
 * gears, rings, teapot) at depth 5. */
#include "core/error.h"
#include "render/backend.h"
#include "scene/scene.h"

/* Specular primitives (kr or kt > 0, planes aside) that make a scene's rays
 * scatter at any depth from 2, and the fewer that do from depth 8. */
#define SCATTER_PRIMS 64
#define SCATTER_PRIMS_DEEP 4
#define DEEP 8

static size_t specular_prims(const glint_scene *scene) {
  size_t n = 0;
  for (size_t i = 0; i < scene->object_count; i++) {
    const gli_object *o = &scene->objects[i];
    const glint_material *m = &scene->materials[o->material];
    if (o->shape != GLI_SHAPE_PLANE && (m->kr > 0 || m->kt > 0))
      n += o->count;
  }
  return n;
}

glint_backend glint_backend_choose(glint_backend backend,
                                   const glint_scene *scene,
                                   const glint_render_settings *settings) {
  if (backend != GLINT_BACKEND_AUTO || !scene || !settings)
    return glint_backend_resolve(backend);
  size_t specular = specular_prims(scene);
  int depth = settings->max_depth;
  int scatter =
      depth >= 2 && (specular >= SCATTER_PRIMS ||
                     (depth >= DEEP && specular >= SCATTER_PRIMS_DEEP));
  return glint_backend_resolve(scatter ? GLINT_BACKEND_STREAM
                                       : GLINT_BACKEND_AUTO);
}
