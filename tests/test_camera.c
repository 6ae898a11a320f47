/* Camera rays of docs/specification.md §2 for the centre and corner pixels. */
#include "test_util.h"

#include "render/camera.h"

static void near3(vec3 got, double x, double y, double z) {
  double l = sqrt(x * x + y * y + z * z);
  x /= l, y /= l, z /= l;
  if (fabs(got.x - x) > 1e-12 || fabs(got.y - y) > 1e-12 ||
      fabs(got.z - z) > 1e-12)
    fail_msg("got (%g %g %g), want (%g %g %g)", got.x, got.y, got.z, x, y, z);
}

/* Looking down -z with a 90-degree field of view: tan(45) = 1, so the image
 * plane at distance 1 spans x in [-1, 1] and y in [-0.75, 0.75] at 4:3. */
static void basis_and_corners(void **state) {
  (void)state;
  glint_camera g = {{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90};
  camera c;
  camera_init(&c, &g, 640, 480);
  near3(c.r, 1, 0, 0);
  near3(c.u, 0, 1, 0);
  near3(camera_dir(&c, 320, 240), 0, 0, -1);     /* centre */
  near3(camera_dir(&c, 0, 0), -1, 0.75, -1);     /* top-left corner */
  near3(camera_dir(&c, 640, 0), 1, 0.75, -1);    /* top-right corner */
  near3(camera_dir(&c, 0, 480), -1, -0.75, -1);  /* bottom-left corner */
  near3(camera_dir(&c, 640, 480), 1, -0.75, -1); /* bottom-right corner */
  /* The centre of the top-left pixel. */
  near3(camera_dir(&c, 0.5, 0.5), -1 + 1.0 / 640, 0.75 - 0.75 / 480, -1);
}

/* A general camera: the Whitted scene's, from (0, 2, 6) at (0, 1.25, 0). */
static void whitted_camera(void **state) {
  (void)state;
  glint_camera g = {{0, 2, 6}, {0, 1.25, 0}, {0, 1, 0}, 60};
  camera c;
  camera_init(&c, &g, 640, 480);
  near3(c.d, 0, -0.75, -6);
  near3(c.r, 1, 0, 0);
  /* u = r x d is up-ish and perpendicular to d. */
  near3(c.u, 0, 6, -0.75);
  near3(camera_dir(&c, 320, 240), 0, -0.75, -6);
  double t = tan(3.14159265358979323846 / 6);
  /* Top-left corner: d + (-t) r + (0.75 t) u. */
  double dl = sqrt(0.75 * 0.75 + 36), ul = dl;
  double x = -t, y = 0.75 * t;
  near3(camera_dir(&c, 0, 0), x, -0.75 / dl + y * 6 / ul,
        -6 / dl + y * -0.75 / ul);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(basis_and_corners),
      cmocka_unit_test(whitted_camera),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
