/* What the BVH tests (tests/test_bvh.c, tests/test_wide_bvh.c) share: the
 * scenes they walk (Giza, the only thesis scene above the BVH's size
 * threshold; glass-rods, long cones of glass and metal across each other,
 * whose shadows pass through glass; and SPD scenes of every shape: spheres,
 * cones, polygons, patches, which need ../shared), random rays through them,
 * the object a scalar hit names, and box containment. Include after choosing
 * the scalar precision (math/real.h). */
#ifndef GLINT_TEST_BVH_SCENES_H
#define GLINT_TEST_BVH_SCENES_H

#include "render/scalar_scene.h"
#include "shared.h"
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct scene_list {
  const char *names[8];
} scene_list;
static const scene_list own = {{"giza", "stress/glass-rods.json", NULL}};
static const scene_list spd = {
    {"scenes/spd/balls-s2.nff", "scenes/spd/gears-s1.nff",
     "scenes/spd/mount-s4.nff", "scenes/spd/rings-s2.nff",
     "scenes/spd/teapot-s2.nff", "scenes/spd/tetra-s4.nff",
     "scenes/spd/tree-s4.nff", NULL}};

/* A built-in scene by name, one of the repository's scenes/stress/, or a
 * file under ../shared by its path there. */
static glint_scene *load(const char *name) {
  glint_scene *s;
  if (strncmp(name, "stress/", 7) == 0) {
    char path[512];
    snprintf(path, sizeof path, "%s/scenes/%s", GLINT_SOURCE_DIR, name);
    ASSERT_OK(glint_scene_load(path, &s, &e_));
  } else if (strchr(name, '/'))
    ASSERT_OK(glint_scene_load(shared_path(name), &s, &e_));
  else
    ASSERT_OK(glint_scene_builtin(name, &s, &e_));
  return s;
}

static int object_of(const scene_r *s, const hit_r *h) {
  switch (h->shape) {
  case GLI_SHAPE_SPHERE: return (int)s->spheres[h->prim].object;
  case GLI_SHAPE_PLANE: return (int)s->planes[h->prim].object;
  case GLI_SHAPE_CONE: return (int)s->cones[h->prim].object;
  default: return (int)s->triangles[h->prim].object;
  }
}

/* Rays from inside the scene's bounds (and its camera) in all directions. */
static void make_ray(const glint_scene_info *info, unsigned long long *seed,
                     float o[3], float d[3]) {
  if (uniform(seed) < 0.3) {
    o[0] = (float)info->camera.from.x;
    o[1] = (float)info->camera.from.y;
    o[2] = (float)info->camera.from.z;
  } else {
    const double *lo = &info->bounds_min.x, *hi = &info->bounds_max.x;
    for (int k = 0; k < 3; k++)
      o[k] = (float)(lo[k] + (hi[k] - lo[k]) * (1.2 * uniform(seed) - 0.1));
  }
  double z = 2 * uniform(seed) - 1, a = 6.283185307179586 * uniform(seed);
  double r = sqrt(1 - z * z);
  d[0] = (float)(r * cos(a));
  d[1] = (float)(r * sin(a));
  d[2] = (float)z;
}

/* Whether box a holds box b. */
static int holds(const float alo[3], const float ahi[3], const float blo[3],
                 const float bhi[3]) {
  for (int k = 0; k < 3; k++)
    if (blo[k] < alo[k] || bhi[k] > ahi[k])
      return 0;
  return 1;
}

#endif
