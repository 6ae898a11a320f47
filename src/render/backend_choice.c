/* What GLINT_BACKEND_AUTO runs: the beams or the streams of the widest ISA
 * this CPU has, whichever the scene and settings favour. Beams keep a
 * packet's rays in registers from the camera to the last bounce and win
 * while those rays stay together; ray streams regroup the rays of every
 * generation into full packets, at the cost of storing them, and win once
 * rays scatter: after bounces among many specular surfaces. Measured (one
 * thread, scripts/bench-compare.sh; README, "Performance"): the beams are
 * 5-20% faster on Whitted (one mirror) at every depth and on Billiard and
 * Giza up to depth 3; the two are level there at depth 5; the streams are
 * 1.2-2.5x faster on Billiard and Giza from depth 10, 1.2-1.5x on the SPD
 * scenes full of mirrors (balls, gears, rings, teapot) at depth 5 and 3x on
 * the mirror-room stress scene at depth 15. */
#include "core/error.h"
#include "render/backend.h"
#include "scene/scene.h"

/* Specular primitives (kr or kt > 0, planes aside) that make a scene's rays
 * scatter at any depth from 2, and the fewer that do from depth 5 (where
 * Billiard's and Giza's beams and streams are level; the streams 1.2x
 * faster on the mirror-room stress scene). */
#define SCATTER_PRIMS 64
#define SCATTER_PRIMS_DEEP 4
#define DEEP 5
/* Where the specular primitives are fewer than 1/SCATTER_SHARE of the
 * bounded ones, most rays end on diffuse surfaces and the few that bounce
 * make small generations: the streams pay from depth DEEPER only. The
 * SPD's mount (4 glass spheres among 512 or 8 192 diffuse triangles): the
 * beams 7% faster at depth 5 (mount-s6) and up to 15% at depth 7
 * (mount-s4), the two level at depth 10 on mount-s6 and the streams 12%
 * faster on mount-s4 there, and 4-25% faster at depth 15. Every other
 * scene measured has a specular share of 1/5 or more. */
#define SCATTER_SHARE 16
#define DEEPER 10

/* The specular primitives (kr or kt > 0, planes aside), and in *bounded
 * all primitives but planes. */
static size_t specular_prims(const glint_scene *scene, size_t *bounded) {
  size_t n = 0;
  *bounded = 0;
  for (size_t i = 0; i < scene->object_count; i++) {
    const gli_object *o = &scene->objects[i];
    const glint_material *m = &scene->materials[o->material];
    if (o->shape == GLI_SHAPE_PLANE)
      continue;
    *bounded += o->count;
    if (m->kr > 0 || m->kt > 0)
      n += o->count;
  }
  return n;
}

glint_backend glint_backend_choose(glint_backend backend,
                                   const glint_scene *scene,
                                   const glint_render_settings *settings) {
  if (backend != GLINT_BACKEND_AUTO || !scene || !settings)
    return glint_backend_resolve(backend);
  size_t bounded;
  size_t specular = specular_prims(scene, &bounded);
  int depth = settings->max_depth;
  int scatter =
      depth >= 2 && (specular >= SCATTER_PRIMS ||
                     (depth >= DEEP && specular >= SCATTER_PRIMS_DEEP));
  if (specular * SCATTER_SHARE < bounded && depth < DEEPER)
    scatter = 0;
  return glint_backend_resolve(scatter ? GLINT_BACKEND_STREAM
                                       : GLINT_BACKEND_AUTO);
}
