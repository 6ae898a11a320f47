/* Image regression. The four thesis scenes at 160x120 (5 spp, depth 5) with
 * scalar-double must match the committed golden images in tests/golden at
 * PSNR >= 50 dB: bit-identical on the machine that made them, with room for
 * a last-bit difference of another libm or compiler (50 dB is an RMS error
 * of 0.8 of one level). And scalar-float must match scalar-double at PSNR >=
 * 45 dB on all four scenes at depth 5 (issue 2).
 *
 * Regenerate the goldens with: build/tests/test_golden --update */
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define GOLDEN_PSNR 50.0
/* Measured: 75.6 dB at the least (whitted). */
#define FLOAT_VS_DOUBLE_PSNR 72.0

static int update;
static const char *scenes[] = {"whitted", "giza", "billiard", "phong"};

static glint_image *render(const char *name, glint_backend backend, int w,
                           int h, int depth) {
  glint_scene *s;
  ASSERT_OK(glint_scene_builtin(name, &s, &e_));
  glint_render_settings rs;
  glint_render_settings_default(&rs);
  rs.width = w;
  rs.height = h;
  rs.max_depth = depth;
  rs.backend = backend;
  glint_image *im;
  ASSERT_OK(glint_render(s, &rs, &im, NULL, &e_));
  glint_scene_destroy(s);
  return im;
}

static void golden_images(void **state) {
  (void)state;
  for (int i = 0; i < 4; i++) {
    char path[512];
    snprintf(path, sizeof path, "%s/tests/golden/%s.png", GLINT_SOURCE_DIR,
             scenes[i]);
    glint_image *im =
        render(scenes[i], GLINT_BACKEND_SCALAR_DOUBLE, 160, 120, 5);
    if (update) {
      ASSERT_OK(glint_image_write(im, path, &e_));
      printf("wrote %s\n", path);
    } else {
      glint_image *golden;
      ASSERT_OK(glint_image_read(path, &golden, &e_));
      double psnr = glint_image_psnr(im, golden);
      printf("%-9s golden PSNR %.2f dB\n", scenes[i], psnr);
      if (psnr < GOLDEN_PSNR)
        fail_msg("%s differs from its golden image: PSNR %.2f dB < %.0f dB",
                 scenes[i], psnr, GOLDEN_PSNR);
      glint_image_destroy(golden);
    }
    glint_image_destroy(im);
  }
}

static void float_matches_double(void **state) {
  (void)state;
  for (int i = 0; i < 4; i++) {
    glint_image *f = render(scenes[i], GLINT_BACKEND_SCALAR_FLOAT, 320, 240, 5);
    glint_image *d =
        render(scenes[i], GLINT_BACKEND_SCALAR_DOUBLE, 320, 240, 5);
    double psnr = glint_image_psnr(f, d);
    printf("%-9s scalar-float vs scalar-double PSNR %.2f dB\n", scenes[i],
           psnr);
    if (psnr < FLOAT_VS_DOUBLE_PSNR)
      fail_msg("%s: float vs double PSNR %.2f dB < %.0f dB", scenes[i], psnr,
               FLOAT_VS_DOUBLE_PSNR);
    glint_image_destroy(f);
    glint_image_destroy(d);
  }
}

int main(int argc, char **argv) {
  update = argc > 1 && strcmp(argv[1], "--update") == 0;
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(golden_images),
      cmocka_unit_test(float_matches_double),
  };
  if (update)
    return cmocka_run_group_tests(tests, NULL, NULL) ? 1 : 0;
  return cmocka_run_group_tests(tests, NULL, NULL);
}
