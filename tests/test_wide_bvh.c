/* The wide BVH (accel/wide_bvh.h) and single rays through it
 * (accel/wide_traverse.h), in the scalar backends' precision this file is
 * compiled for (it is built twice, float and double): the collapsed tree is
 * sound (every primitive once, every box holding what is below it, small
 * leaves, each wide node the collapse of the binary node it names); on a
 * row of spheres the hits are the hand-computed ones; and on random rays
 * the nearest hits and shadow transmissions through the wide tree equal the
 * binary tree's and brute force's. Packets through the hybrid walks:
 * tests/test_bvh.c. */
#include "test_util.h"

#include "test_views.h"
#include "accel/bvh.h"
#include "render/scalar_scene.h"
#include "scene/scene.h"
#include "bvh_scenes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RAYS 20000

#if REAL_IS_DOUBLE
#define DATA_SCALAR DATA_SCALAR_DOUBLE
#else
#define DATA_SCALAR DATA_SCALAR_FLOAT
#endif

/* The scalar queries with the ray by value. */
static int scalar_nearest(const scene_r *s, vec3 o, vec3 d, real tmax,
                          hit_r *hit) {
  return scalar_nearest_hit(s, &o, &d, tmax, hit);
}

static vec3 scalar_transmission_of(const scene_r *s, vec3 o, vec3 d,
                                   real dist) {
  return scalar_transmission(s, &o, &d, dist);
}

/* ---- the tree ----------------------------------------------------------- */

/* Child k of wide node n as a box. */
static void child_box(const gli_wide_node *n, int k, float lo[3], float hi[3]) {
  for (int a = 0; a < 3; a++)
    lo[a] = n->bounds[0][a][k], hi[a] = n->bounds[1][a][k];
}

/* Walks the subtree at wide node w: every reference below it is counted in
 * seen[], and each lies inside the box (lo, hi) the parent gave it. */
static void walk(const glint_scene *g, const gli_bvh *b, uint32_t w,
                 const float lo[3], const float hi[3], int depth,
                 unsigned char *seen) {
  const gli_wide_bvh *wb = &b->wide;
  assert_true(w < wb->node_count);
  assert_true(depth <= wb->depth && depth <= GLI_WIDE_MAX_DEPTH);
  const gli_wide_node *n = &wb->nodes[w];
  int children = 0;
  for (int k = 0; k < GLI_WIDE; k++) {
    float clo[3], chi[3];
    child_box(n, k, clo, chi);
    if (clo[0] > chi[0]) { /* an unused slot: empty, and no references */
      assert_true(isinf(clo[0]) && isinf(chi[0]));
      assert_int_equal(n->count[k], 0);
      continue;
    }
    children++;
    assert_true(holds(lo, hi, clo, chi));
    if (n->count[k] == 0) {
      walk(g, b, n->child[k], clo, chi, depth + 1, seen);
      continue;
    }
    assert_true(n->count[k] <= GLI_WIDE_LEAF);
    for (uint32_t r = n->child[k]; r < n->child[k] + n->count[k]; r++) {
      uint32_t ref = wb->refs[r];
      float plo[3], phi[3];
      gli_bvh_ref_box(g, ref, plo, phi);
      assert_true(holds(clo, chi, plo, phi));
      size_t flat = GLI_REF_INDEX(ref);
      if (GLI_REF_SHAPE(ref) != GLI_SHAPE_SPHERE)
        flat += g->sphere_count;
      if (GLI_REF_SHAPE(ref) == GLI_SHAPE_CONE)
        flat += g->triangle_count;
      assert_int_equal(seen[flat], 0);
      seen[flat] = 1;
      /* grouped by shape: render/leaf_blocks.h relies on it */
      if (r > n->child[k])
        assert_true(GLI_REF_SHAPE(wb->refs[r - 1]) <= GLI_REF_SHAPE(ref));
    }
  }
  assert_true(children >= 1);
}

static void wide_tree_is_sound(void **state) {
  const char *const *scenes = ((const scene_list *)*state)->names;
  for (size_t si = 0; scenes[si]; si++) {
    glint_scene *g = load(scenes[si]);
    gli_bvh b;
    ASSERT_OK(gli_bvh_build(g, 1, &b, &e_));
    /* Collapsed with the BVH where packets may hand over to it, else on
     * demand (for --accel bvh8). */
    int may = gli_wide_may_hand_over(g->sphere_count, g->cone_count);
    if ((b.wide.nodes != NULL) != may)
      fail_msg("%s: %zu spheres and cones: wide tree %s with the BVH",
               scenes[si], g->sphere_count + g->cone_count,
               b.wide.nodes ? "collapsed" : "not collapsed");
    ASSERT_OK(gli_bvh_add_wide(&b, g, &e_));
    size_t prims = g->sphere_count + g->triangle_count + g->cone_count;
    assert_non_null(b.wide.nodes);
    assert_true(b.wide.node_count >= 1);
    assert_int_equal(b.wide.ref_count, prims);
    unsigned char *seen = calloc(prims, 1);
    walk(g, &b, 0, b.nodes[0].lo, b.nodes[0].hi, 1, seen);
    for (size_t i = 0; i < prims; i++)
      assert_int_equal(seen[i], 1);
    free(seen);
    /* Each wide node a binary node names holds exactly that node's box,
     * and the hand-over marks sit on such nodes only. */
    uint32_t named = 0, marked = 0;
    for (uint32_t i = 0; i < b.node_count; i++) {
      uint32_t w = b.wide.of_binary[i];
      if (b.nodes[i].flags & GLI_NODE_HAND_OVER) {
        assert_int_not_equal(w, GLI_WIDE_NONE);
        assert_int_equal(b.nodes[i].count, 0);
        marked++;
      }
      if (w == GLI_WIDE_NONE)
        continue;
      named++;
      float lo[3] = {INFINITY, INFINITY, INFINITY},
            hi[3] = {-INFINITY, -INFINITY, -INFINITY};
      for (int k = 0; k < GLI_WIDE; k++)
        for (int a = 0; a < 3; a++) {
          lo[a] = fminf(lo[a], b.wide.nodes[w].bounds[0][a][k]);
          hi[a] = fmaxf(hi[a], b.wide.nodes[w].bounds[1][a][k]);
        }
      assert_true(holds(lo, hi, b.nodes[i].lo, b.nodes[i].hi));
      assert_true(holds(b.nodes[i].lo, b.nodes[i].hi, lo, hi));
    }
    assert_int_equal(b.wide.of_binary[0], 0); /* the roots */
    assert_int_equal(marked, b.wide.hand_overs);
    printf("%-26s binary %u nodes (depth %d), wide %u nodes (depth %d, "
           "%.1f KiB, %.2f ms), %u named, %u hand-over points\n",
           scenes[si], b.node_count, b.depth, b.wide.node_count, b.wide.depth,
           (double)gli_wide_bytes(&b.wide) / 1024, b.wide.build_seconds * 1e3,
           named, marked);
    /* Triangles only: no hand-over points (wide_bvh.c, mark_hand_overs). */
    if (g->sphere_count == 0 && g->cone_count == 0)
      assert_int_equal(marked, 0);
    gli_bvh_free(&b);
    glint_scene_destroy(g);
  }
}

/* Hand-over points (accel/wide_bvh.c, mark_hand_overs) where at least half
 * of a large subtree's references are spheres or cones: a field of 400
 * triangles with 4 spheres among them has none (mount-s6's shape, where
 * they cost 6%), the same with 400 spheres and 4 triangles has some. */
static glint_scene *field(int triangles, int spheres) {
  uint32_t m;
  glint_scene *g = scene_with_default_material(&m);
  for (int k = 0; k < triangles; k++) {
    double x = k % 20, z = k / 20;
    ASSERT_OK(glint_scene_add_triangle(g, (glint_vec3){x, 0, z},
                                       (glint_vec3){x + 1, 0, z},
                                       (glint_vec3){x, 0.5, z + 1}, m, &e_));
  }
  for (int k = 0; k < spheres; k++) {
    double x = k % 20 + 0.5, z = k / 20 + 0.5;
    ASSERT_OK(glint_scene_add_sphere(g, (glint_vec3){x, 1, z}, 0.4, m, &e_));
  }
  return g;
}

static uint32_t hand_over_points(glint_scene *g) {
  gli_bvh b;
  ASSERT_OK(gli_bvh_build(g, 1, &b, &e_));
  uint32_t marked = b.wide.hand_overs;
  gli_bvh_free(&b);
  glint_scene_destroy(g);
  return marked;
}

static void hand_overs_where_spheres_and_cones_are_most(void **state) {
  (void)state;
  assert_int_equal(hand_over_points(field(400, 4)), 0);
  assert_true(hand_over_points(field(4, 400)) > 0);
  assert_true(hand_over_points(field(200, 200)) > 0);
  assert_int_equal(hand_over_points(field(0, 100)), 0); /* too small */
}

/* ---- hand-computed hits ------------------------------------------------- */

/* Forty spheres of radius 0.5 at x = 0, 2, ..., 78 (y = z = 0): enough for
 * a hierarchy of several levels. A ray along +x from x = -10 meets the
 * first at t = 9.5; one down the y axis at x = 2k meets sphere k at
 * t = 10 - 0.5; a ray between two spheres (x = 1) meets nothing; a shadow
 * ray along the row is blocked, one beside it is not. */
static void row_of_spheres_hits_as_computed(void **state) {
  (void)state;
  uint32_t m;
  glint_scene *g = scene_with_default_material(&m);
  for (int k = 0; k < 40; k++)
    ASSERT_OK(
        glint_scene_add_sphere(g, (glint_vec3){2.0 * k, 0, 0}, 0.5, m, &e_));
  static const glint_accel accels[3] = {GLINT_ACCEL_BVH8, GLINT_ACCEL_BVH,
                                        GLINT_ACCEL_NONE};
  for (int ai = 0; ai < 3; ai++) {
    test_view tv;
    const scene_r *s = test_view_open(g, DATA_SCALAR, accels[ai], &tv);
    if (accels[ai] == GLINT_ACCEL_BVH8)
      assert_true(s->walk_wide && s->bvh->wide.node_count > 1);
    hit_r h;
    assert_true(scalar_nearest(s, v3(-10, 0, 0), v3(1, 0, 0), REAL_MAX, &h));
    assert_true(fabs((double)h.t - 9.5) < 1e-5);
    assert_int_equal(h.prim, 0);
    for (int k = 0; k < 40; k += 3) {
      assert_true(scalar_nearest(s, v3((real)(2 * k), 10, 0), v3(0, -1, 0),
                                 REAL_MAX, &h));
      assert_true(fabs((double)h.t - 9.5) < 1e-5);
      assert_int_equal(h.shape, GLI_SHAPE_SPHERE);
      assert_int_equal(h.prim, (uint32_t)k);
      /* tmax short of the sphere: no hit */
      assert_false(scalar_nearest(s, v3((real)(2 * k), 10, 0), v3(0, -1, 0),
                                  (real)9.4, &h));
    }
    assert_false(scalar_nearest(s, v3(1, 10, 0), v3(0, -1, 0), REAL_MAX, &h));
    vec3 through = scalar_transmission_of(s, v3(-10, 0, 0), v3(1, 0, 0), 200);
    assert_true(through.x == 0 && through.y == 0 && through.z == 0);
    vec3 beside = scalar_transmission_of(s, v3(-10, 2, 0), v3(1, 0, 0), 200);
    assert_true(beside.x == 1 && beside.y == 1 && beside.z == 1);
    test_view_close(&tv);
  }
  glint_scene_destroy(g);
}

/* ---- random rays -------------------------------------------------------- */

static void wide_hits_equal_binary_and_brute_force(void **state) {
  const char *const *scenes = ((const scene_list *)*state)->names;
  for (size_t si = 0; scenes[si]; si++) {
    glint_scene *g = load(scenes[si]);
    glint_scene_info info;
    glint_scene_get_info(g, &info);
    test_view vw, vb, vn;
    const scene_r *wide = test_view_open(g, DATA_SCALAR, GLINT_ACCEL_BVH8, &vw);
    const scene_r *bin = test_view_open(g, DATA_SCALAR, GLINT_ACCEL_BVH, &vb);
    const scene_r *none = test_view_open(g, DATA_SCALAR, GLINT_ACCEL_NONE, &vn);
    assert_true(wide->walk_wide && !bin->walk_wide);
    unsigned long long seed = 4242 + si;
    int ties = 0, shadow_differ = 0;
    for (int i = 0; i < RAYS; i++) {
      float of[3], df[3];
      make_ray(&info, &seed, of, df);
      vec3 o = v3(of[0], of[1], of[2]), d = v3(df[0], df[1], df[2]);
      hit_r hw, hb, hn;
      int fw = scalar_nearest(wide, o, d, REAL_MAX, &hw);
      int fb = scalar_nearest(bin, o, d, REAL_MAX, &hb);
      int fn = scalar_nearest(none, o, d, REAL_MAX, &hn);
      assert_int_equal(fw, fn);
      assert_int_equal(fb, fn);
      if (fn) {
        /* the same distance; the same object unless two meet there */
        assert_true(fabs((double)hw.t - hn.t) <= 1e-9 * fmax(1.0, hn.t));
        assert_true(fabs((double)hb.t - hn.t) <= 1e-9 * fmax(1.0, hn.t));
        if (object_of(wide, &hw) != object_of(none, &hn))
          ties++;
      }
      /* A shadow ray over a random length: the same light gets through. */
      real dist = (real)(uniform(&seed) * 2 *
                         fmax(fmax(info.bounds_max.x - info.bounds_min.x,
                                   info.bounds_max.y - info.bounds_min.y),
                              info.bounds_max.z - info.bounds_min.z));
      vec3 tw = scalar_transmission_of(wide, o, d, dist);
      vec3 tn = scalar_transmission_of(none, o, d, dist);
      if (fabs((double)tw.x - tn.x) > 1e-5 ||
          fabs((double)tw.y - tn.y) > 1e-5 || fabs((double)tw.z - tn.z) > 1e-5)
        shadow_differ++;
    }
    printf("%-26s %s: %d rays agree (%d ties), %d shadow rays differ\n",
           scenes[si], REAL_IS_DOUBLE ? "double" : "float", RAYS, ties,
           shadow_differ);
    assert_true(ties < RAYS / 500);
    assert_int_equal(shadow_differ, 0);
    test_view_close(&vw);
    test_view_close(&vb);
    test_view_close(&vn);
    glint_scene_destroy(g);
  }
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
      {"wide_tree_is_sound", wide_tree_is_sound, NULL, NULL, (void *)&own},
      {"hand_overs_where_spheres_and_cones_are_most",
       hand_overs_where_spheres_and_cones_are_most, NULL, NULL, NULL},
      {"row_of_spheres_hits_as_computed", row_of_spheres_hits_as_computed, NULL,
       NULL, NULL},
      {"wide_hits_equal_binary_and_brute_force",
       wide_hits_equal_binary_and_brute_force, NULL, NULL, (void *)&own},
      {"wide_tree_is_sound_shared", wide_tree_is_sound, NULL, NULL,
       (void *)&spd},
      {"wide_hits_equal_binary_and_brute_force_shared",
       wide_hits_equal_binary_and_brute_force, NULL, NULL, (void *)&spd},
  };
  return glint_run_tests(tests, argc, argv, NULL, NULL);
}
