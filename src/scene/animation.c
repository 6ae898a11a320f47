/* Animation: a scene's frames, and its camera through keyframes (linear or
 * Catmull-Rom) or an orbit (include/glint.h, "Animation"). */
#include "core/error.h"
#include "scene/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double pi = 3.14159265358979323846;

glint_status glint_scene_set_animation(glint_scene *s, const glint_animation *a,
                                       glint_error *error) {
  if (!s || !a)
    return gli_fail(error, GLINT_E_ARGUMENT, "no scene or no animation");
  if (!(a->fps > 0) || !isfinite(a->fps) || a->fps > 1e6)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "animation: fps %g is not a positive number", a->fps);
  if (a->first_frame < 0 || a->last_frame < a->first_frame)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "animation: frames %d..%d are not a range of frame "
                    "numbers from 0",
                    a->first_frame, a->last_frame);
  s->animation.present = 1;
  s->animation.frames = *a;
  return GLINT_OK;
}

int glint_scene_get_animation(const glint_scene *s, glint_animation *a) {
  if (!s->animation.present)
    return 0;
  *a = s->animation.frames;
  return 1;
}

glint_status glint_scene_set_camera_keys(glint_scene *s,
                                         const glint_camera_key *keys,
                                         size_t count,
                                         glint_interpolation interpolation,
                                         glint_error *error) {
  if (!s || !keys || count == 0)
    return gli_fail(error, GLINT_E_ARGUMENT, "camera keys: none given");
  if ((unsigned)interpolation > GLINT_INTERPOLATE_CATMULL_ROM)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "camera keys: unknown interpolation %d",
                    (int)interpolation);
  for (size_t i = 0; i < count; i++) {
    glint_status st = gli_camera_check(&keys[i].camera, error);
    if (st)
      return st;
    if (!isfinite(keys[i].time) ||
        (i > 0 && !(keys[i].time > keys[i - 1].time)))
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "camera keys: key %zu's time %g does not come after "
                      "the key before it",
                      i, keys[i].time);
  }
  glint_camera_key *copy = malloc(sizeof *copy * count);
  if (!copy)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory for camera keys");
  memcpy(copy, keys, sizeof *copy * count);
  free(s->animation.keys);
  s->animation.keys = copy;
  s->animation.key_count = count;
  s->animation.interpolation = interpolation;
  s->animation.camera_mode = GLI_CAMERA_KEYS;
  return GLINT_OK;
}

glint_status glint_scene_set_camera_orbit(glint_scene *s, glint_vec3 center,
                                          double radius, double height,
                                          double degrees, glint_error *error) {
  if (!s || !gli_vec3_finite(center) || !isfinite(height) ||
      !isfinite(degrees) || !(radius > 0) || !isfinite(radius))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "camera orbit: center, height and degrees must be "
                    "finite and the radius positive");
  s->animation.orbit_center = center;
  s->animation.orbit_radius = radius;
  s->animation.orbit_height = height;
  s->animation.orbit_degrees = degrees;
  s->animation.camera_mode = GLI_CAMERA_ORBIT;
  return GLINT_OK;
}

/* Hermite interpolation between p0 (tangent m0) and p1 (tangent m1) over a
 * span of length h, at u in [0, 1]: the cubic with those end values and
 * slopes (tangents per second, hence the factors h). */
static double hermite(double p0, double m0, double p1, double m1, double h,
                      double u) {
  double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * h * m0 +
         (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * h * m1;
}

/* The camera's numbers as an array, for interpolating them alike. */
enum { CAMERA_VALUES = 10 };
static void camera_values(const glint_camera *c, double v[CAMERA_VALUES]) {
  double x[CAMERA_VALUES] = {c->from.x, c->from.y,       c->from.z, c->at.x,
                             c->at.y,   c->at.z,         c->up.x,   c->up.y,
                             c->up.z,   c->fov_x_degrees};
  memcpy(v, x, sizeof x);
}

static glint_camera camera_from(const double v[CAMERA_VALUES]) {
  glint_camera c = {
      {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}, v[9]};
  return c;
}

/* The Catmull-Rom tangent at key i: the slope through its neighbours, one-
 * sided at the ends (Catmull and Rom, 1974, with times as the parameter). */
static double tangent(const glint_camera_key *k, size_t n, size_t i,
                      size_t value) {
  size_t a = i > 0 ? i - 1 : i, b = i + 1 < n ? i + 1 : i;
  if (a == b)
    return 0;
  double va[CAMERA_VALUES], vb[CAMERA_VALUES];
  camera_values(&k[a].camera, va);
  camera_values(&k[b].camera, vb);
  return (vb[value] - va[value]) / (k[b].time - k[a].time);
}

static glint_camera keyed_camera(const gli_animation *a, double t) {
  const glint_camera_key *k = a->keys;
  size_t n = a->key_count;
  if (t <= k[0].time)
    return k[0].camera;
  if (t >= k[n - 1].time)
    return k[n - 1].camera;
  size_t i = 0;
  while (t >= k[i + 1].time)
    i++;
  double h = k[i + 1].time - k[i].time, u = (t - k[i].time) / h;
  double v0[CAMERA_VALUES], v1[CAMERA_VALUES], v[CAMERA_VALUES];
  camera_values(&k[i].camera, v0);
  camera_values(&k[i + 1].camera, v1);
  for (size_t j = 0; j < CAMERA_VALUES; j++)
    v[j] = a->interpolation == GLINT_INTERPOLATE_LINEAR
               ? v0[j] + (v1[j] - v0[j]) * u
               : hermite(v0[j], tangent(k, n, i, j), v1[j],
                         tangent(k, n, i + 1, j), h, u);
  return camera_from(v);
}

glint_status glint_scene_camera_at(const glint_scene *s, double time,
                                   glint_camera *out, glint_error *error) {
  const gli_animation *a = &s->animation;
  if (!isfinite(time))
    return gli_fail(error, GLINT_E_ARGUMENT, "time %g is not finite", time);
  glint_camera c = s->camera;
  if (a->camera_mode == GLI_CAMERA_KEYS) {
    c = keyed_camera(a, time);
  } else if (a->camera_mode == GLI_CAMERA_ORBIT) {
    if (!a->present)
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "camera orbit: the scene has no animation frames");
    /* The angle sweeps `degrees` over the frames, the last frame one step
     * short of the whole, so that a full circle loops. */
    const glint_animation *f = &a->frames;
    double span = (double)(f->last_frame - f->first_frame + 1) / f->fps;
    double angle = a->orbit_degrees * pi / 180 * time / span;
    glint_vec3 m = a->orbit_center;
    c.from =
        (glint_vec3){m.x + a->orbit_radius * sin(angle), m.y + a->orbit_height,
                     m.z + a->orbit_radius * cos(angle)};
    c.at = m;
    c.up = (glint_vec3){0, 1, 0};
  }
  glint_status st = gli_camera_check(&c, error);
  if (st)
    return st;
  *out = c;
  return GLINT_OK;
}
