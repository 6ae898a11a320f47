/* The beam backends against the scalar reference (issue 3):
 *  - for 100 000 random rays per scene and every SIMD width, the packet
 *    nearest hit is the scalar nearest hit: the same object and t within
 *    1e-5 relative (a different object counts only as a tie, when both hits
 *    lie at the same t, e.g. on an edge two triangles share);
 *  - full renders of the four scenes at depths 1, 5 and 15 match scalar-float
 *    at PSNR >= 70 dB (default maths; 73.3 dB measured at the least);
 *  - results are identical from run to run and for any thread count. */
#define GLINT_REAL_FLOAT
#include "test_util.h"

#include "test_views.h"
#include "render/scalar_scene.h"
#include "scene/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define RAYS 100000
/* Measured: 73.3 dB at the least (whitted, depth 15). */
#define MATCH_PSNR 70.0

static const char *scenes[] = {"whitted", "giza", "billiard", "phong"};

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

/* A random unit vector. */
static vec3 random_dir(unsigned long long *s) {
  double z = 2 * uniform(s) - 1, a = 6.283185307179586 * uniform(s);
  double r = sqrt(1 - z * z);
  return v3((float)(r * cos(a)), (float)(r * sin(a)), (float)z);
}

static void nearest_hits_agree(void **state) {
  (void)state;
  for (size_t si = 0; si < 4; si++) {
    glint_scene *g;
    ASSERT_OK(glint_scene_builtin(scenes[si], &g, &e_));
    glint_scene_info info;
    glint_scene_get_info(g, &info);
    vec3 from = v3((float)info.camera.from.x, (float)info.camera.from.y,
                   (float)info.camera.from.z);
    vec3 ahead =
        v3_normalize(v3_sub(v3((float)info.camera.at.x, (float)info.camera.at.y,
                               (float)info.camera.at.z),
                            from));
    test_view ref_view;
    const scene_r *ref =
        test_view_open(g, DATA_SCALAR_FLOAT, GLINT_ACCEL_NONE, &ref_view);
    for (size_t k = 0; k < sizeof packets / sizeof *packets; k++) {
      if (backend_missing(packets[k].backend))
        continue;
      test_view packet_view;
      void *prep =
          test_view_open(g, gli_backend_ops_of(packets[k].backend)->data,
                         GLINT_ACCEL_NONE, &packet_view);
      int w = packets[k].width, ties = 0, hits = 0;
      unsigned long long seed = 1234 + si;
      for (int base = 0; base < RAYS; base += w) {
        float o[3 * 16], d[3 * 16], t[16];
        int obj[16], bits = 0;
        for (int i = 0; i < w; i++) {
          vec3 org, dir = random_dir(&seed);
          if (uniform(&seed) < 0.5) {
            org = from; /* camera rays, forward-ish */
            dir = v3_normalize(v3_madd(dir, 1.5f, ahead));
          } else {
            org = v3((float)(16 * uniform(&seed) - 8),
                     (float)(10 * uniform(&seed) + 0.01),
                     (float)(24 * uniform(&seed) - 12));
          }
          o[i] = org.x, o[w + i] = org.y, o[2 * w + i] = org.z;
          d[i] = dir.x, d[w + i] = dir.y, d[2 * w + i] = dir.z;
          if (uniform(&seed) < 0.9) /* some lanes inactive */
            bits |= 1 << i;
        }
        packets[k].nearest(prep, o, d, bits, t, obj);
        for (int i = 0; i < w; i++) {
          if (!(bits >> i & 1))
            continue;
          hit_r h;
          vec3 org = v3(o[i], o[w + i], o[2 * w + i]);
          vec3 dir = v3(d[i], d[w + i], d[2 * w + i]);
          int found =
              gli_scalar_nearest_hit_float(ref, &org, &dir, REAL_MAX, &h);
          int ref_obj = -1;
          if (found) {
            hits++;
            switch (h.shape) {
            case GLI_SHAPE_SPHERE:
              ref_obj = (int)ref->spheres[h.prim].object;
              break;
            case GLI_SHAPE_PLANE:
              ref_obj = (int)ref->planes[h.prim].object;
              break;
            default: ref_obj = (int)ref->triangles[h.prim].object; break;
            }
          }
          int same_t = found && obj[i] >= 0 &&
                       fabs((double)t[i] - h.t) <= 1e-5 * fmax(1.0, h.t);
          if (obj[i] == ref_obj && (!found || same_t))
            continue;
          if (same_t) {
            ties++;
            continue;
          }
          fail_msg("%s, %s, ray %d: packet object %d t %.9g, scalar object "
                   "%d t %.9g",
                   scenes[si], glint_backend_name(packets[k].backend), base + i,
                   obj[i], (double)t[i], ref_obj, found ? (double)h.t : -1.0);
        }
      }
      printf("%-8s %-6s %d rays, %d hits, %d ties\n", scenes[si],
             glint_backend_name(packets[k].backend), RAYS, hits, ties);
      assert_true(hits > RAYS / 20); /* the rays do meet the scene */
      assert_true(ties <= RAYS / 1000);
      test_view_close(&packet_view);
    }
    test_view_close(&ref_view);
    glint_scene_destroy(g);
  }
}

static glint_image *render(const char *name, glint_backend b, int depth,
                           int threads, glint_stats *st) {
  glint_scene *s;
  ASSERT_OK(glint_scene_builtin(name, &s, &e_));
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.width = 320;
  rs.height = 240;
  rs.max_depth = depth;
  rs.backend = b;
  rs.threads = threads;
  glint_image *im;
  ASSERT_OK(glint_render(s, &rs, &im, st, &e_));
  glint_scene_destroy(s);
  return im;
}

static void renders_match_scalar_float(void **state) {
  (void)state;
  static const int depths[] = {1, 5, 15};
  for (size_t si = 0; si < 4; si++)
    for (int di = 0; di < 3; di++) {
      glint_image *ref =
          render(scenes[si], GLINT_BACKEND_SCALAR_FLOAT, depths[di], 0, NULL);
      for (size_t k = 0; k < sizeof packets / sizeof *packets; k++) {
        if (backend_missing(packets[k].backend))
          continue;
        glint_stats st;
        glint_image *im =
            render(scenes[si], packets[k].backend, depths[di], 0, &st);
        double psnr = glint_image_psnr(ref, im);
        printf("%-8s depth %2d %-6s PSNR %6.2f dB, lane utilisation %5.1f%%, "
               "%.2f sub-beams per beam\n",
               scenes[si], depths[di], glint_backend_name(packets[k].backend),
               psnr,
               100.0 * (double)st.active_lanes /
                   ((double)st.packet_tests * packets[k].width),
               (double)st.sub_beams / (double)st.beams);
        if (psnr < MATCH_PSNR)
          fail_msg("%s depth %d %s: PSNR %.2f dB < %.0f dB", scenes[si],
                   depths[di], glint_backend_name(packets[k].backend), psnr,
                   MATCH_PSNR);
        assert_int_equal(st.backend, packets[k].backend);
        assert_true(st.beams > 0 && st.sub_beams > 0 && st.packet_tests > 0);
        assert_true(st.active_lanes <=
                    st.packet_tests * (uint64_t)packets[k].width);
        glint_image_destroy(im);
      }
      glint_image_destroy(ref);
    }
}

static void identical_run_to_run_and_across_threads(void **state) {
  (void)state;
  for (size_t k = 0; k < sizeof packets / sizeof *packets; k++) {
    if (backend_missing(packets[k].backend))
      continue;
    glint_image *a = render("billiard", packets[k].backend, 8, 1, NULL);
    glint_image *b = render("billiard", packets[k].backend, 8, 2, NULL);
    glint_image *c = render("billiard", packets[k].backend, 8, 3, NULL);
    assert_true(isinf(glint_image_psnr(a, b)));
    assert_true(isinf(glint_image_psnr(a, c)));
    glint_image_destroy(a);
    glint_image_destroy(b);
    glint_image_destroy(c);
  }
}

/* The centre column of an odd-wide image looks along a plane through the
 * eye: its rays, exactly level with the plane, miss it in every backend.
 * The packet backends made the image plane's x as px sx + ox, whose terms
 * rounded apart left 1e-8 at the centre, and the AVX2 and AVX-512 ones
 * drew the whole column as the plane, hit 1e7 away (14.5 dB); they now
 * make it in camera_dir's operations (render/camera.h), exactly 0. */
static void the_image_centre_is_exact(void **state) {
  (void)state;
  static const char json[] =
      "{\"camera\": {\"from\": [0, 1, 6], \"at\": [0, 1, 0], \"fov\": 60},"
      " \"background\": [0.25, 0.45, 0.85],"
      " \"lights\": [{\"position\": [-4, 8, 6]}],"
      " \"materials\": {\"wall\": {\"color\": [1, 0, 0]}},"
      " \"objects\": [{\"type\": \"plane\", \"material\": \"wall\","
      " \"normal\": [1, 0, 0], \"point\": [-1, 0, 0]},"
      " {\"type\": \"plane\", \"material\": \"wall\","
      " \"normal\": [0, 1, 0], \"point\": [0, 1, 0]}]}";
  glint_scene *scene;
  ASSERT_OK(glint_scene_load_memory(json, sizeof json - 1, "level.json", &scene,
                                    &e_));
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.width = 9, rs.height = 9, rs.spp = 1, rs.max_depth = 1, rs.threads = 1;
  rs.backend = GLINT_BACKEND_SCALAR_DOUBLE;
  glint_image *ref;
  ASSERT_OK(glint_render(scene, &rs, &ref, NULL, &e_));
  for (int b = GLINT_BACKEND_SCALAR_FLOAT; b < GLINT_BACKEND_COUNT; b++) {
    if (b == GLINT_BACKEND_STREAM || backend_missing((glint_backend)b))
      continue;
    rs.backend = (glint_backend)b;
    glint_image *im;
    ASSERT_OK(glint_render(scene, &rs, &im, NULL, &e_));
    double psnr = glint_image_psnr(ref, im);
    if (!isinf(psnr))
      fail_msg("%s: PSNR %.2f dB against scalar-double",
               glint_backend_name((glint_backend)b), psnr);
    glint_image_destroy(im);
  }
  glint_image_destroy(ref);
  glint_scene_destroy(scene);
}

int main(void) {
  /* Every test here is of the SIMD backends. */
  if (!glint_backend_supported(GLINT_BACKEND_SSE)) {
    printf("SKIPPED: this CPU (or GLINT_ISA) has no SIMD backend\n");
    return SKIP_EXIT;
  }
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(nearest_hits_agree),
      cmocka_unit_test(renders_match_scalar_float),
      cmocka_unit_test(identical_run_to_run_and_across_threads),
      cmocka_unit_test(the_image_centre_is_exact),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
