/* The scenes the BVH tests walk (tests/test_bvh.c, tests/test_wide_bvh.c):
 * Giza, the only thesis scene above the BVH's size threshold, and SPD
 * scenes of every shape (spheres, cones, polygons, patches), which need
 * ../shared. */
#ifndef GLINT_TEST_BVH_SCENES_H
#define GLINT_TEST_BVH_SCENES_H

#include "shared.h"
#include "test_util.h"

#include <string.h>

typedef struct scene_list {
  const char *names[8];
} scene_list;
static const scene_list own = {{"giza", NULL}};
static const scene_list spd = {
    {"scenes/spd/balls-s2.nff", "scenes/spd/gears-s1.nff",
     "scenes/spd/mount-s4.nff", "scenes/spd/rings-s2.nff",
     "scenes/spd/teapot-s2.nff", "scenes/spd/tetra-s4.nff",
     "scenes/spd/tree-s4.nff", NULL}};

/* A built-in scene by name, or a file under ../shared by its path there. */
static glint_scene *load(const char *name) {
  glint_scene *s;
  if (strchr(name, '/'))
    ASSERT_OK(glint_scene_load(shared_path(name), &s, &e_));
  else
    ASSERT_OK(glint_scene_builtin(name, &s, &e_));
  return s;
}

#endif
