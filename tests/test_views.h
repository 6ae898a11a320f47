/* Tests of internals read a committed world's converted layouts directly:
 * a view of one layout, walking the world's BVH as `accel` says
 * (GLINT_ACCEL_NONE: without it). */
#ifndef GLINT_TEST_VIEWS_H
#define GLINT_TEST_VIEWS_H

#include "test_util.h"

#include "render/backend.h"
#include "render/world.h"

typedef struct test_view {
  glint_world *world;
  const data_ops *layout;
  void *view;
} test_view;

static const gli_bvh test_no_bvh;

static void *test_view_open(const glint_scene *scene, data_kind kind,
                            glint_accel accel, test_view *tv) {
  ASSERT_OK(gli_world_create(scene, 0, &tv->world, &e_));
  const void *data;
  ASSERT_OK(gli_world_data(tv->world, kind, &data, &e_));
  const gli_bvh *bvh = &test_no_bvh;
  if (accel != GLINT_ACCEL_NONE)
    ASSERT_OK(gli_world_bvh(tv->world, 1, &bvh, &e_));
  tv->layout = gli_data_ops_of(kind);
  ASSERT_OK(tv->layout->bind(data, bvh, accel, &tv->view, &e_));
  return tv->view;
}

static void test_view_close(test_view *tv) {
  tv->layout->unbind(tv->view);
  gli_world_release(tv->world);
}

#endif
