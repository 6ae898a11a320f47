/* The BVH against brute force (issue 4): on random rays, every backend's
 * nearest hit through the hierarchy is the one testing every primitive
 * finds (the same object; t equal to 1e-5, or a tie at the same t);
 * renders with and without it are the same image; and images are
 * bit-identical for any number of threads. Scenes: Giza (the only thesis
 * scene above the BVH's size threshold) and the SPD scenes. */
#define GLINT_REAL_FLOAT
#include "test_util.h"

#include "test_views.h"
#include "render/scalar_scene.h"
#include "scene/scene.h"
#include "shared.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RAYS 20000

/* Giza needs nothing (the thesis's other scenes have too few primitives to
 * get a BVH at all); the SPD scenes (every shape: spheres, cones, polygons,
 * patches) need ../shared. */
typedef struct scene_list {
  const char *names[8];
} scene_list;
static const scene_list own = {{"giza", NULL}};
static const scene_list spd = {
    {"scenes/spd/balls-s2.nff", "scenes/spd/gears-s1.nff",
     "scenes/spd/mount-s4.nff", "scenes/spd/rings-s2.nff",
     "scenes/spd/teapot-s2.nff", "scenes/spd/tetra-s4.nff",
     "scenes/spd/tree-s4.nff", NULL}};

static glint_scene *load(const char *name) {
  glint_scene *s;
  if (strchr(name, '/'))
    ASSERT_OK(glint_scene_load(shared_path(name), &s, &e_));
  else
    ASSERT_OK(glint_scene_builtin(name, &s, &e_));
  return s;
}

static double uniform(unsigned long long *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

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

static void nearest_hits_equal_brute_force(void **state) {
  const char *const *scenes = ((const scene_list *)*state)->names;
  for (size_t si = 0; scenes[si]; si++) {
    glint_scene *g = load(scenes[si]);
    glint_scene_info info;
    glint_scene_get_info(g, &info);
    int ties = 0;
    /* Scalar float and double. */
    test_view vb, vn;
    const scene_r *fb = test_view_open(g, DATA_SCALAR_FLOAT, 1, &vb);
    const scene_r *fn = test_view_open(g, DATA_SCALAR_FLOAT, 0, &vn);
    assert_true(fb->bvh->node_count > 0);
    assert_true(fn->bvh->node_count == 0);
    unsigned long long seed = 99 + si;
    for (int i = 0; i < RAYS; i++) {
      float o[3], d[3];
      make_ray(&info, &seed, o, d);
      hit_r ha, hb;
      int fa = gli_scalar_nearest_hit_float(
          fb, v3(o[0], o[1], o[2]), v3(d[0], d[1], d[2]), REAL_MAX, &ha);
      int fbr = gli_scalar_nearest_hit_float(
          fn, v3(o[0], o[1], o[2]), v3(d[0], d[1], d[2]), REAL_MAX, &hb);
      compare(scenes[si], "scalar-float", fa ? object_of(fb, &ha) : -1, ha.t,
              fbr ? object_of(fn, &hb) : -1, hb.t, &ties);
    }
    /* Every packet width: the BVH packet traversal against the brute-force
     * packet loop. */
    for (size_t k = 0; k < sizeof packets / sizeof *packets; k++) {
      if (backend_missing(packets[k].backend))
        continue;
      data_kind kind = gli_backend_ops_of(packets[k].backend)->data;
      test_view pvb, pvn;
      void *pb = test_view_open(g, kind, 1, &pvb);
      void *pn = test_view_open(g, kind, 0, &pvn);
      int w = packets[k].width;
      for (int base = 0; base < RAYS; base += w) {
        float o[3 * 16], d[3 * 16], ta[16], tb[16];
        int oa[16], ob[16], bits = 0;
        for (int i = 0; i < w; i++) {
          float oo[3], dd[3];
          make_ray(&info, &seed, oo, dd);
          for (int c = 0; c < 3; c++)
            o[c * w + i] = oo[c], d[c * w + i] = dd[c];
          bits |= (uniform(&seed) < 0.9) << i;
        }
        packets[k].nearest(pb, o, d, bits, ta, oa);
        packets[k].nearest(pn, o, d, bits, tb, ob);
        for (int i = 0; i < w; i++)
          if (bits >> i & 1)
            compare(scenes[si], glint_backend_name(packets[k].backend), oa[i],
                    ta[i], ob[i], tb[i], &ties);
      }
      test_view_close(&pvb);
      test_view_close(&pvn);
    }
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

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
      {"nearest_hits_equal_brute_force", nearest_hits_equal_brute_force, NULL,
       NULL, (void *)&own},
      {"renders_equal", renders_equal, NULL, NULL, (void *)&own},
      {"nearest_hits_equal_brute_force_shared", nearest_hits_equal_brute_force,
       NULL, NULL, (void *)&spd},
      {"renders_equal_shared", renders_equal, NULL, NULL, (void *)&spd},
  };
  return glint_run_tests(tests, argc, argv, NULL, NULL);
}
