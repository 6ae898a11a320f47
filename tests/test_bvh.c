/* The BVH against brute force (issue 4): on random rays, every backend's
 * nearest hit through the hierarchy is the one testing every primitive
 * finds (the same object; t equal to 1e-5, or a tie at the same t), for
 * every walk: packets alone in the binary tree (bvh2), the hybrid that
 * hands subtrees to single rays in the wide tree (bvh), every ray alone
 * (bvh8); renders with and without it are the same image; and images are
 * bit-identical for any number of threads. Scenes: Giza (the only thesis
 * scene above the BVH's size threshold) and the SPD scenes, and a random
 * scene large enough for the packets' cut of the tree, and to be built on
 * several threads (the same tree, node for node). The wide tree itself and
 * the scalar single rays: tests/test_wide_bvh.c. */
#define GLINT_REAL_FLOAT
#include "test_util.h"

#include "test_views.h"
#include "accel/bvh.h"
#include "render/scalar_scene.h"
#include "scene/scene.h"
#include "bvh_scenes.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RAYS 20000

typedef void (*nearest_fn)(const void *, const float *, const float *, int,
                           float *, int *);
static const struct {
  glint_backend backend;
  int width;
  nearest_fn nearest;
} packets[] = {
    {GLINT_BACKEND_SSE, 4, gli_beam_nearest_hit_sse},
    {GLINT_BACKEND_AVX2, 8, gli_beam_nearest_hit_avx2},
    {GLINT_BACKEND_AVX512, 16, gli_beam_nearest_hit_avx512},
};

static void compare(const char *scene, const char *backend, int obj_a,
                    float t_a, int obj_b, float t_b, int *ties) {
  int same_t = obj_a >= 0 && obj_b >= 0 &&
               fabs((double)t_a - t_b) <= 1e-5 * fmax(1.0, t_b);
  if (obj_a == obj_b && (obj_a < 0 || same_t))
    return;
  if (same_t) {
    (*ties)++;
    return;
  }
  fail_msg("%s, %s: BVH object %d t %.9g, brute force object %d t %.9g", scene,
           backend, obj_a, (double)t_a, obj_b, (double)t_b);
}

/* Every packet width through each of `walks` against the brute-force
 * packet loop, on `rays` random rays of the scene (the lanes each active
 * with probability 0.9); counts ties. */
static void packets_agree(glint_scene *g, const char *name,
                          const glint_accel *walks, int nwalks, int rays,
                          unsigned long long *seed, int *ties) {
  glint_scene_info info;
  glint_scene_get_info(g, &info);
  for (size_t k = 0; k < sizeof packets / sizeof *packets; k++) {
    if (backend_missing(packets[k].backend))
      continue;
    data_kind kind = gli_backend_ops_of(packets[k].backend)->data;
    for (int wi = 0; wi < nwalks; wi++) {
      test_view pvb, pvn;
      void *pb = test_view_open(g, kind, walks[wi], &pvb);
      void *pn = test_view_open(g, kind, GLINT_ACCEL_NONE, &pvn);
      int w = packets[k].width;
      char what[64];
      snprintf(what, sizeof what, "%s --accel %s",
               glint_backend_name(packets[k].backend),
               glint_accel_name(walks[wi]));
      for (int base = 0; base < rays; base += w) {
        float o[3 * 16], d[3 * 16], ta[16], tb[16];
        int oa[16], ob[16], bits = 0;
        for (int i = 0; i < w; i++) {
          float oo[3], dd[3];
          make_ray(&info, seed, oo, dd);
          for (int c = 0; c < 3; c++)
            o[c * w + i] = oo[c], d[c * w + i] = dd[c];
          bits |= (uniform(seed) < 0.9) << i;
        }
        packets[k].nearest(pb, o, d, bits, ta, oa);
        packets[k].nearest(pn, o, d, bits, tb, ob);
        for (int i = 0; i < w; i++)
          if (bits >> i & 1)
            compare(name, what, oa[i], ta[i], ob[i], tb[i], ties);
      }
      test_view_close(&pvb);
      test_view_close(&pvn);
    }
  }
}

static void nearest_hits_equal_brute_force(void **state) {
  const char *const *scenes = ((const scene_list *)*state)->names;
  for (size_t si = 0; scenes[si]; si++) {
    glint_scene *g = load(scenes[si]);
    glint_scene_info info;
    glint_scene_get_info(g, &info);
    int ties = 0;
    /* Scalar float and double. */
    test_view vb, vn;
    const scene_r *fb =
        test_view_open(g, DATA_SCALAR_FLOAT, GLINT_ACCEL_BVH, &vb);
    const scene_r *fn =
        test_view_open(g, DATA_SCALAR_FLOAT, GLINT_ACCEL_NONE, &vn);
    assert_true(fb->bvh->node_count > 0);
    assert_true(fn->bvh->node_count == 0);
    unsigned long long seed = 99 + si;
    for (int i = 0; i < RAYS; i++) {
      float o[3], d[3];
      make_ray(&info, &seed, o, d);
      hit_r ha, hb;
      vec3 org = v3(o[0], o[1], o[2]), dir = v3(d[0], d[1], d[2]);
      int fa = gli_scalar_nearest_hit_float(fb, &org, &dir, REAL_MAX, &ha);
      int fbr = gli_scalar_nearest_hit_float(fn, &org, &dir, REAL_MAX, &hb);
      compare(scenes[si], "scalar-float", fa ? object_of(fb, &ha) : -1, ha.t,
              fbr ? object_of(fn, &hb) : -1, hb.t, &ties);
    }
    /* Every packet width and walk against the brute-force packet loop. */
    static const glint_accel walks[3] = {GLINT_ACCEL_BVH, GLINT_ACCEL_BVH2,
                                         GLINT_ACCEL_BVH8};
    packets_agree(g, scenes[si], walks, 3, RAYS, &seed, &ties);
    printf("%-26s %zu triangles, %zu spheres, %zu cones: agree (%d ties)\n",
           scenes[si], info.triangles, info.spheres, info.cones, ties);
    assert_true(ties < RAYS / 500);
    test_view_close(&vb);
    test_view_close(&vn);
    glint_scene_destroy(g);
  }
}

static glint_image *render(glint_scene *s, glint_backend b, glint_accel a,
                           int threads) {
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.width = rs.height = 96;
  rs.spp = 1;
  rs.backend = b;
  rs.accel = a;
  rs.threads = threads;
  glint_image *im;
  ASSERT_OK(glint_render(s, &rs, &im, NULL, &e_));
  return im;
}

/* Shadow rays, refraction, everything: the same image with or without the
 * BVH, and for 1, 2 and 3 threads. */
static void renders_equal(void **state) {
  const char *const *scenes = ((const scene_list *)*state)->names;
  for (size_t si = 0; scenes[si]; si++) {
    glint_scene *g = load(scenes[si]);
    for (int b = GLINT_BACKEND_SCALAR_FLOAT; b <= GLINT_BACKEND_AVX512; b++) {
      if (backend_missing((glint_backend)b))
        continue;
      glint_image *a = render(g, (glint_backend)b, GLINT_ACCEL_BVH, 1);
      glint_image *n = render(g, (glint_backend)b, GLINT_ACCEL_NONE, 1);
      /* The other walks: the binary tree alone, every ray alone. */
      for (int walk = GLINT_ACCEL_BVH2; walk <= GLINT_ACCEL_BVH8; walk++) {
        glint_image *x = render(g, (glint_backend)b, (glint_accel)walk, 1);
        double px = glint_image_psnr(x, n);
        if (px < 60)
          fail_msg("%s %s: --accel %s vs none PSNR %.2f dB", scenes[si],
                   glint_backend_name((glint_backend)b),
                   glint_accel_name((glint_accel)walk), px);
        glint_image_destroy(x);
      }
      glint_image *t2 = render(g, (glint_backend)b, GLINT_ACCEL_BVH, 2);
      glint_image *t3 = render(g, (glint_backend)b, GLINT_ACCEL_BVH, 3);
      double psnr = glint_image_psnr(a, n);
      if (psnr < 60)
        fail_msg("%s %s: BVH vs none PSNR %.2f dB", scenes[si],
                 glint_backend_name((glint_backend)b), psnr);
      assert_true(isinf(glint_image_psnr(a, t2)));
      assert_true(isinf(glint_image_psnr(a, t3)));
      glint_image_destroy(a);
      glint_image_destroy(n);
      glint_image_destroy(t2);
      glint_image_destroy(t3);
    }
    glint_scene_destroy(g);
  }
}

/* The packets' cut of a large scene's tree: smaller than the binary tree,
 * every reference once in leaves of at most 16 whose boxes hold them,
 * every inner node before its children, which share a cache line and
 * whose boxes it holds. */
static void assert_packet_tree_sound(const gli_bvh *b, const glint_scene *g) {
  assert_true(b->packet_nodes != b->nodes);
  assert_true(b->packet_node_count > 1 && b->packet_node_count < b->node_count);
  char *seen = calloc(b->ref_count, 1);
  for (uint32_t i = 0; i < b->packet_node_count; i++) {
    const gli_bvh_node *n = &b->packet_nodes[i];
    if (n->count) {
      assert_true(n->count <= 16 && n->offset + n->count <= b->ref_count);
      for (uint32_t k = n->offset; k < n->offset + n->count; k++) {
        float lo[3], hi[3];
        gli_bvh_ref_box(g, b->refs[k], lo, hi);
        assert_true(holds(n->lo, n->hi, lo, hi));
        assert_false(seen[k]);
        seen[k] = 1;
      }
      continue;
    }
    assert_true(n->offset > i && n->offset + 1 < b->packet_node_count);
    assert_int_equal((uintptr_t)&b->packet_nodes[n->offset] % 64, 0);
    for (uint32_t c = n->offset; c < n->offset + 2; c++)
      assert_true(
          holds(n->lo, n->hi, b->packet_nodes[c].lo, b->packet_nodes[c].hi));
  }
  for (uint32_t k = 0; k < b->ref_count; k++)
    assert_true(seen[k]);
  free(seen);
}

/* A scene of GLI_BVH_PACKET_CUT_PRIMS primitives and more (random small
 * triangles, spheres and cones): the packets walk a cut of the binary tree
 * (accel/bvh.c, cut_costs), sound as built and as a refit for moved
 * objects makes it again, and finding the nearest hits brute force finds
 * for every packet width and walk (the hybrid hands its lanes the wide
 * tree at the packet tree's nodes). */
static void assert_sound(const gli_bvh *b, size_t prims);

static void large_scene_packet_tree(void **state) {
  (void)state;
  glint_scene *g;
  ASSERT_OK(glint_scene_create(&g, &e_));
  glint_material mat;
  glint_material_default(&mat);
  uint32_t m;
  ASSERT_OK(glint_scene_add_material(g, &mat, &m, &e_));
  unsigned long long seed = 7;
  for (int i = 0; i < GLI_BVH_PACKET_CUT_PRIMS + 2000; i++) {
    glint_vec3 c = {100 * uniform(&seed), 100 * uniform(&seed),
                    100 * uniform(&seed)};
    if (i % 3 == 0) {
      ASSERT_OK(glint_scene_add_sphere(g, c, 0.3 * uniform(&seed), m, &e_));
    } else if (i % 7 == 1) {
      glint_vec3 a = {c.x + uniform(&seed), c.y + uniform(&seed), c.z + 1};
      ASSERT_OK(glint_scene_add_cone(g, c, 0.1, a, 0.05, m, &e_));
    } else {
      glint_vec3 b = {c.x + uniform(&seed), c.y, c.z + uniform(&seed)};
      glint_vec3 d = {c.x, c.y + uniform(&seed), c.z + uniform(&seed)};
      ASSERT_OK(glint_scene_add_triangle(g, c, b, d, m, &e_));
    }
  }
  test_view vb;
  const scene_r *fb =
      test_view_open(g, DATA_SCALAR_FLOAT, GLINT_ACCEL_BVH, &vb);
  assert_packet_tree_sound(fb->bvh, g);
  test_view_close(&vb);
  /* An animation's next frame refits the tree and cuts it again. */
  gli_bvh built, refit;
  ASSERT_OK(gli_bvh_build(g, 1, &built, &e_));
  glint_scene *moved;
  ASSERT_OK(gli_scene_copy(g, &moved, &e_));
  glint_transform turn = {{0, 40, 0}, {30, 60, 0}, {0, 0, 0}, 1.5};
  for (uint32_t o = 0; o < moved->object_count; o += 5)
    assert_int_equal(gli_object_transform(moved, o, &turn), 0);
  ASSERT_OK(gli_bvh_refit(&built, moved, &refit, &e_));
  assert_packet_tree_sound(&refit, moved);
  gli_bvh_free(&refit);
  gli_bvh_free(&built);
  glint_scene_destroy(moved);

  /* Built on several threads, the tree is the same, node for node (grown
   * in slots placed by the splits alone, accel/bvh.c, grow_tree). */
  gli_bvh one;
  ASSERT_OK(gli_bvh_build(g, 1, &one, &e_));
  for (int threads = 2; threads <= 9; threads += 7) {
    gli_bvh many;
    ASSERT_OK(gli_bvh_build(g, threads, &many, &e_));
    assert_int_equal(many.node_count, one.node_count);
    assert_int_equal(many.depth, one.depth);
    assert_memory_equal(many.nodes, one.nodes,
                        one.node_count * sizeof *one.nodes);
    assert_memory_equal(many.refs, one.refs, one.ref_count * sizeof *one.refs);
    assert_int_equal(many.packet_node_count, one.packet_node_count);
    assert_memory_equal(many.packet_nodes, one.packet_nodes,
                        one.packet_node_count * sizeof *one.packet_nodes);
    gli_bvh_free(&many);
  }
  assert_sound(&one, one.ref_count);
  gli_bvh_free(&one);

  int ties = 0;
  static const glint_accel walks[2] = {GLINT_ACCEL_BVH, GLINT_ACCEL_BVH2};
  packets_agree(g, "large scene", walks, 2, 1024, &seed, &ties);
  assert_true(ties < 8);
  glint_scene_destroy(g);
}

/* Every inner node of `b` comes before its children and holds their boxes,
 * its two children share a cache line (accel/bvh.c, nodes_alloc), and
 * every primitive is referenced once. */
static void assert_sound(const gli_bvh *b, size_t prims) {
  assert_int_equal(b->ref_count, prims);
  char *seen = calloc(prims, 1);
  for (uint32_t i = 0; i < b->node_count; i++) {
    const gli_bvh_node *n = &b->nodes[i];
    if (n->count) {
      for (uint32_t k = n->offset; k < n->offset + n->count; k++) {
        uint32_t r = b->refs[k];
        size_t flat = GLI_REF_INDEX(r);
        if (GLI_REF_SHAPE(r) != GLI_SHAPE_SPHERE)
          flat += b->spheres;
        if (GLI_REF_SHAPE(r) == GLI_SHAPE_CONE)
          flat += b->triangles;
        assert_true(flat < prims);
        assert_false(seen[flat]);
        seen[flat] = 1;
      }
      continue;
    }
    assert_true(n->offset > i); /* children after their parent */
    assert_int_equal((uintptr_t)&b->nodes[n->offset] % 64, 0);
    for (uint32_t c = n->offset; c < n->offset + 2; c++)
      assert_true(holds(n->lo, n->hi, b->nodes[c].lo, b->nodes[c].hi));
  }
  free(seen);
}

/* Refitting (accel/bvh.c, used for an animation's next frame): over the
 * scene it was built for, the same boxes; over the scene moved as one, the
 * boxes moved and the surface area cost unchanged; over objects moved
 * apart, sound boxes that hold them where they are now; and a scene with
 * other primitives is refused. */
static void refit_follows_moved_objects(void **state) {
  (void)state;
  glint_scene *g = load("giza");
  gli_bvh built, refit;
  ASSERT_OK(gli_bvh_build(g, 1, &built, &e_));
  assert_true(built.node_count > 1);
  assert_sound(&built, g->sphere_count + g->triangle_count + g->cone_count);
  assert_true(built.cost > 1 && built.cost == built.built_cost);
  ASSERT_OK(gli_bvh_refit(&built, g, &refit, &e_));
  assert_sound(&refit, g->sphere_count + g->triangle_count + g->cone_count);
  assert_true(fabs(refit.cost - built.cost) <= 1e-9 * built.cost);
  assert_memory_equal(&refit.nodes[0].lo, &built.nodes[0].lo,
                      sizeof built.nodes[0].lo);
  assert_memory_equal(&refit.nodes[0].hi, &built.nodes[0].hi,
                      sizeof built.nodes[0].hi);
  gli_bvh_free(&refit);

  /* Everything moved by (3, -2, 5): the root box moves, the cost stays. */
  glint_transform shift = {{3, -2, 5}, {0, 0, 0}, {0, 0, 0}, 1};
  glint_scene *moved;
  ASSERT_OK(gli_scene_copy(g, &moved, &e_));
  for (uint32_t o = 0; o < moved->object_count; o++)
    assert_int_equal(gli_object_transform(moved, o, &shift), 0);
  ASSERT_OK(gli_bvh_refit(&built, moved, &refit, &e_));
  assert_sound(&refit, g->sphere_count + g->triangle_count + g->cone_count);
  const double d[3] = {3, -2, 5};
  for (int k = 0; k < 3; k++) {
    assert_true(fabs(refit.nodes[0].lo[k] - (built.nodes[0].lo[k] + d[k])) <
                1e-4);
    assert_true(fabs(refit.nodes[0].hi[k] - (built.nodes[0].hi[k] + d[k])) <
                1e-4);
  }
  assert_true(fabs(refit.cost - built.cost) <= 1e-3 * built.cost);
  assert_true(refit.built_cost == built.built_cost);
  gli_bvh_free(&refit);
  glint_scene_destroy(moved);

  /* One object turned and moved away: the boxes hold it where it is. */
  ASSERT_OK(gli_scene_copy(g, &moved, &e_));
  glint_transform turn = {{0, 40, 0}, {30, 60, 0}, {0, 0, 0}, 1.5};
  uint32_t last = moved->object_count - 1;
  assert_int_equal(gli_object_transform(moved, last, &turn), 0);
  ASSERT_OK(gli_bvh_refit(&built, moved, &refit, &e_));
  assert_sound(&refit, g->sphere_count + g->triangle_count + g->cone_count);
  for (size_t i = 0; i < moved->triangle_count; i++)
    for (int v = 0; v < 3; v++) {
      float p[3] = {(float)moved->triangles[i].v[v].x,
                    (float)moved->triangles[i].v[v].y,
                    (float)moved->triangles[i].v[v].z};
      assert_true(holds(refit.nodes[0].lo, refit.nodes[0].hi, p, p));
    }
  assert_true(refit.cost >= 1);
  gli_bvh_free(&refit);

  /* Other primitives: refused. */
  uint32_t m;
  glint_material mat;
  glint_material_default(&mat);
  ASSERT_OK(glint_scene_add_material(moved, &mat, &m, &e_));
  ASSERT_OK(glint_scene_add_sphere(moved, (glint_vec3){0, 0, 0}, 1, m, &e_));
  glint_error e;
  assert_int_equal(gli_bvh_refit(&built, moved, &refit, &e), GLINT_E_ARGUMENT);
  glint_scene_destroy(moved);
  gli_bvh_free(&built);
  glint_scene_destroy(g);
}

/* A tree deeper than the levels the heuristic splits: 140 000 copies of
 * one triangle (whose boxes' centres coincide, so only halving splits
 * them) under 99 specks 16 times apart along each axis, each of which the
 * heuristic peels off one level at a time. The nodes below those levels,
 * still holding more references than a leaf takes, are halved on; every
 * walk's stack holds the deepest (the scalar backends' shadow walk wrote
 * past its stack of GLI_BVH_MAX_DEPTH: a crash in a release build, and
 * AddressSanitizer's stack-buffer-overflow). Every backend renders the
 * scene as scalar-double does. */
static void the_deepest_tree_is_walked(void **state) {
  (void)state;
  enum { COPIES = 140000 };
  glint_scene *g;
  ASSERT_OK(glint_scene_create(&g, &e_));
  glint_material mat;
  glint_material_default(&mat);
  uint32_t m;
  ASSERT_OK(glint_scene_add_material(g, &mat, &m, &e_));
  ASSERT_OK(glint_scene_add_light(g, (glint_vec3){300, 400, 3000},
                                  (glint_vec3){1, 1, 1}, &e_));
  glint_vec3 v[3] = {{-1000, -1000, 0}, {1000, -1000, 0}, {0, 1000, 0}};
  uint32_t *ix = malloc(3 * sizeof *ix * COPIES);
  assert_non_null(ix);
  for (size_t i = 0; i < 3 * (size_t)COPIES; i++)
    ix[i] = (uint32_t)(i % 3);
  glint_mesh mesh = {v, NULL, 3, ix, COPIES};
  ASSERT_OK(glint_scene_add_mesh(g, &mesh, m, &e_));
  free(ix);
  for (int a = 0; a < 3; a++)
    for (int k = 0; k < 33; k++) {
      double p = 500 / pow(16, k), t[3][3] = {{0}};
      t[0][a] = t[1][a] = t[2][a] = p;
      t[1][a] *= 1.001;
      t[2][(a + 1) % 3] = p * 1e-3;
      ASSERT_OK(glint_scene_add_triangle(
          g, (glint_vec3){t[0][0], t[0][1], t[0][2]},
          (glint_vec3){t[1][0], t[1][1], t[1][2]},
          (glint_vec3){t[2][0], t[2][1], t[2][2]}, m, &e_));
    }
  ASSERT_OK(glint_scene_add_plane(g, (glint_vec3){0, 0, 1},
                                  (glint_vec3){0, 0, -100}, m, &e_));
  glint_camera cam = {{0, 0, 3000}, {0, 0, 0}, {0, 1, 0}, 60};
  ASSERT_OK(glint_scene_set_camera(g, &cam, &e_));
  gli_bvh built;
  ASSERT_OK(gli_bvh_build(g, 1, &built, &e_));
  printf("depth %d of at most %d split by the heuristic\n", built.depth,
         GLI_BVH_MAX_DEPTH);
  assert_true(built.depth >= GLI_BVH_MAX_DEPTH);
  gli_bvh_free(&built);
  /* one world, its tree built once, for every backend and walk */
  glint_world *world;
  ASSERT_OK(glint_world_commit(g, &world, NULL, &e_));
  glint_image *ref = NULL;
  static const glint_accel walks[] = {GLINT_ACCEL_BVH, GLINT_ACCEL_BVH2,
                                      GLINT_ACCEL_BVH8};
  static const glint_backend order[] = {
      GLINT_BACKEND_SCALAR_DOUBLE, GLINT_BACKEND_SCALAR_FLOAT,
      GLINT_BACKEND_SSE,           GLINT_BACKEND_AVX2,
      GLINT_BACKEND_AVX512,        GLINT_BACKEND_STREAM_SSE,
      GLINT_BACKEND_STREAM_AVX2,   GLINT_BACKEND_STREAM_AVX512};
  for (size_t i = 0; i < sizeof order / sizeof *order; i++) {
    glint_backend b = order[i];
    if (backend_missing(b))
      continue;
    for (int k = 0; k < 3; k++) {
      if (b == GLINT_BACKEND_SCALAR_DOUBLE && k)
        break; /* the reference */
      glint_render_settings rs;
      glint_render_settings_default(&rs);
      rs.width = rs.height = 16;
      rs.spp = 1;
      rs.threads = 1;
      rs.max_depth = 2;
      rs.backend = b;
      rs.accel = walks[k];
      glint_renderer *r;
      glint_film *film;
      glint_image *im;
      ASSERT_OK(glint_renderer_create(world, &rs, &r, &e_));
      ASSERT_OK(glint_film_create(16, 16, &film, &e_));
      ASSERT_OK(glint_image_create(16, 16, &im, &e_));
      ASSERT_OK(glint_renderer_render(r, NULL, film, NULL, &e_));
      ASSERT_OK(glint_film_to_image(film, 1, im, &e_));
      glint_film_destroy(film);
      glint_renderer_destroy(r);
      if (!ref) {
        ref = im;
        continue;
      }
      double psnr = glint_image_psnr(ref, im);
      if (psnr < 40)
        fail_msg("%s, accel %d: PSNR %.2f dB against scalar-double",
                 glint_backend_name(b), (int)walks[k], psnr);
      glint_image_destroy(im);
    }
  }
  glint_image_destroy(ref);
  glint_world_destroy(world);
  glint_scene_destroy(g);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
      {"nearest_hits_equal_brute_force", nearest_hits_equal_brute_force, NULL,
       NULL, (void *)&own},
      {"renders_equal", renders_equal, NULL, NULL, (void *)&own},
      {"refit_follows_moved_objects", refit_follows_moved_objects, NULL, NULL,
       NULL},
      {"large_scene_packet_tree", large_scene_packet_tree, NULL, NULL, NULL},
      {"the_deepest_tree_is_walked", the_deepest_tree_is_walked, NULL, NULL,
       NULL},
      {"nearest_hits_equal_brute_force_shared", nearest_hits_equal_brute_force,
       NULL, NULL, (void *)&spd},
      {"renders_equal_shared", renders_equal, NULL, NULL, (void *)&spd},
  };
  return glint_run_tests(tests, argc, argv, NULL, NULL);
}
