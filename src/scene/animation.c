/* Animation: a scene's frames; its camera through keyframes (linear or
 * Catmull-Rom) or an orbit; its objects through keyed transforms
 * (include/glint.h, "Animation"). Keys of either kind are tracks of numbers
 * interpolated component by component. */
#include "core/error.h"
#include "scene/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double pi = 3.14159265358979323846;

enum { CAMERA_VALUES = 10, TRANSFORM_VALUES = 10 };

/* ---- tracks ------------------------------------------------------------- */

static void track_free(gli_track *t) {
  free(t->times);
  free(t->values);
  memset(t, 0, sizeof *t);
}

static int track_copy(gli_track *dst, const gli_track *src) {
  *dst = *src;
  dst->times = NULL;
  dst->values = NULL;
  if (src->count == 0)
    return 1;
  dst->times = malloc(sizeof *dst->times * src->count);
  dst->values = malloc(sizeof *dst->values * src->count * src->width);
  if (!dst->times || !dst->values) {
    track_free(dst);
    return 0;
  }
  memcpy(dst->times, src->times, sizeof *dst->times * src->count);
  memcpy(dst->values, src->values,
         sizeof *dst->values * src->count * src->width);
  return 1;
}

static glint_status track_alloc(gli_track *t, size_t count, size_t width,
                                glint_interpolation interpolation,
                                glint_error *error) {
  if ((unsigned)interpolation > GLINT_INTERPOLATE_CATMULL_ROM)
    return gli_fail(error, GLINT_E_ARGUMENT, "unknown interpolation %d",
                    (int)interpolation);
  memset(t, 0, sizeof *t);
  t->times = malloc(sizeof *t->times * count);
  t->values = malloc(sizeof *t->values * count * width);
  if (!t->times || !t->values) {
    track_free(t);
    return gli_fail(error, GLINT_E_MEMORY, "out of memory for keys");
  }
  t->count = count;
  t->width = width;
  t->interpolation = interpolation;
  return GLINT_OK;
}

/* Key times must be finite and increase. */
static glint_status check_time(double time, size_t i, double before,
                               glint_error *error) {
  if (!isfinite(time))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "key %zu's time %g is not a finite number", i, time);
  if (i > 0 && !(time > before))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "key %zu's time %g does not come after the key before it",
                    i, time);
  return GLINT_OK;
}

/* Hermite interpolation between p0 (slope m0) and p1 (slope m1) over a span
 * of h seconds, at u in [0, 1]: the cubic with those end values and slopes
 * (slopes per second, hence the factors h). */
static double hermite(double p0, double m0, double p1, double m1, double h,
                      double u) {
  double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * h * m0 +
         (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * h * m1;
}

/* The Catmull-Rom slope of component j at key i: that of the line through
 * its neighbours, one-sided at the ends (Catmull and Rom, 1974, with the
 * keys' times as the parameter). */
static double slope(const gli_track *t, size_t i, size_t j) {
  size_t a = i > 0 ? i - 1 : i, b = i + 1 < t->count ? i + 1 : i;
  if (a == b)
    return 0;
  return (t->values[b * t->width + j] - t->values[a * t->width + j]) /
         (t->times[b] - t->times[a]);
}

/* The track at `time`, held still before its first key and after its
 * last. */
static void track_at(const gli_track *t, double time, double *out) {
  size_t n = t->count, w = t->width;
  if (time <= t->times[0] || n == 1) {
    memcpy(out, t->values, sizeof *out * w);
    return;
  }
  if (time >= t->times[n - 1]) {
    memcpy(out, t->values + (n - 1) * w, sizeof *out * w);
    return;
  }
  size_t i = 0;
  while (time >= t->times[i + 1])
    i++;
  double h = t->times[i + 1] - t->times[i], u = (time - t->times[i]) / h;
  const double *v0 = t->values + i * w, *v1 = v0 + w;
  for (size_t j = 0; j < w; j++)
    out[j] =
        t->interpolation == GLINT_INTERPOLATE_LINEAR
            ? v0[j] + (v1[j] - v0[j]) * u
            : hermite(v0[j], slope(t, i, j), v1[j], slope(t, i + 1, j), h, u);
}

/* ---- the animation's own arrays ----------------------------------------- */

int gli_animation_copy(gli_animation *dst, const gli_animation *src) {
  /* dst holds src's pointers (a struct copy): replace each with its own. */
  dst->motions = NULL;
  dst->motion_count = 0;
  if (!track_copy(&dst->camera_keys, &src->camera_keys))
    return 0;
  if (src->motion_count == 0)
    return 1;
  dst->motions = calloc(src->motion_count, sizeof *dst->motions);
  if (!dst->motions)
    return 0;
  for (size_t i = 0; i < src->motion_count; i++) {
    dst->motions[i].object = src->motions[i].object;
    if (!track_copy(&dst->motions[i].track, &src->motions[i].track))
      return 0;
    dst->motion_count = i + 1;
  }
  return 1;
}

void gli_animation_free(gli_animation *a) {
  track_free(&a->camera_keys);
  for (size_t i = 0; i < a->motion_count; i++)
    track_free(&a->motions[i].track);
  free(a->motions);
  a->motions = NULL;
  a->motion_count = 0;
}

/* ---- frames -------------------------------------------------------------- */

glint_status glint_scene_set_animation(glint_scene *s, const glint_animation *a,
                                       glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  GLI_NOT_NULL(a, "animation", error);
  if (!(a->fps >= GLINT_MIN_FPS && a->fps <= GLINT_MAX_FPS))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "animation: fps %g is not a number of frames a second "
                    "from %g to %g",
                    a->fps, GLINT_MIN_FPS, GLINT_MAX_FPS);
  if (a->first_frame < 0 || a->last_frame < a->first_frame ||
      a->last_frame > GLINT_MAX_FRAME)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "animation: frames %d..%d are not a range of frame "
                    "numbers 0..%d",
                    a->first_frame, a->last_frame, GLINT_MAX_FRAME);
  s->animation.present = 1;
  s->animation.frames = *a;
  return GLINT_OK;
}

int glint_scene_get_animation(const glint_scene *s, glint_animation *a) {
  if (!s || !a || !s->animation.present)
    return 0;
  *a = s->animation.frames;
  return 1;
}

/* ---- the camera -----------------------------------------------------------
 */

glint_status glint_scene_set_camera_keys(glint_scene *s,
                                         const glint_camera_key *keys,
                                         size_t count,
                                         glint_interpolation interpolation,
                                         glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  GLI_NOT_NULL(keys, "keys", error);
  if (count == 0)
    return gli_fail(error, GLINT_E_ARGUMENT, "camera keys: none given");
  for (size_t i = 0; i < count; i++) {
    glint_status st = gli_camera_check(&keys[i].camera, error);
    if (!st)
      st = check_time(keys[i].time, i, i ? keys[i - 1].time : 0, error);
    if (st)
      return st;
  }
  gli_track t;
  glint_status st = track_alloc(&t, count, CAMERA_VALUES, interpolation, error);
  if (st)
    return st;
  for (size_t i = 0; i < count; i++) {
    const glint_camera *c = &keys[i].camera;
    double v[CAMERA_VALUES] = {c->from.x, c->from.y,       c->from.z, c->at.x,
                               c->at.y,   c->at.z,         c->up.x,   c->up.y,
                               c->up.z,   c->fov_x_degrees};
    t.times[i] = keys[i].time;
    memcpy(t.values + i * CAMERA_VALUES, v, sizeof v);
  }
  track_free(&s->animation.camera_keys);
  s->animation.camera_keys = t;
  s->animation.camera_mode = GLI_CAMERA_KEYS;
  return GLINT_OK;
}

glint_status glint_scene_set_camera_orbit(glint_scene *s, glint_vec3 center,
                                          double radius, double height,
                                          double degrees, glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  /* degrees as any coordinate: 1e308 made every frame's angle infinite,
   * and its camera failed for coordinates the caller never gave */
  if (!gli_vec3_in_range(center) || !gli_in_range(height) ||
      !gli_in_range(degrees) || !(radius > 0) || !gli_in_range(radius))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "camera orbit: center, radius, height and degrees must "
                    "be " GLI_RANGE_TEXT ", the radius positive");
  /* the orbit's angle is spread over the frames: none, no orbit (it was
   * taken, and every frame's camera failed later) */
  if (!s->animation.present)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "camera orbit: the scene has no animation frames "
                    "(glint_scene_set_animation first)");
  s->animation.orbit_center = center;
  s->animation.orbit_radius = radius;
  s->animation.orbit_height = height;
  s->animation.orbit_degrees = degrees;
  s->animation.camera_mode = GLI_CAMERA_ORBIT;
  return GLINT_OK;
}

glint_status glint_scene_camera_at(const glint_scene *s, double time,
                                   glint_camera *out, glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  GLI_NOT_NULL(out, "camera", error);
  const gli_animation *a = &s->animation;
  if (!isfinite(time))
    return gli_fail(error, GLINT_E_ARGUMENT, "time %g is not finite", time);
  glint_camera c = s->camera;
  if (a->camera_mode == GLI_CAMERA_KEYS) {
    double v[CAMERA_VALUES];
    track_at(&a->camera_keys, time, v);
    c = (glint_camera){
        {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}, v[9]};
  } else if (a->camera_mode == GLI_CAMERA_ORBIT) {
    if (!a->present)
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "camera orbit: the scene has no animation frames");
    /* The angle sweeps `degrees` over the frames, the last frame one step
     * short of the whole, so that a full circle loops. */
    const glint_animation *f = &a->frames;
    double span = ((double)f->last_frame - f->first_frame + 1) / f->fps;
    double angle = a->orbit_degrees * pi / 180 * time / span;
    if (!isfinite(angle))
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "camera orbit: time %g is too far from the animation "
                      "for an angle",
                      time);
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

/* ---- objects ----------------------------------------------------------------
 */

void glint_transform_identity(glint_transform *t) {
  if (!t)
    return;
  memset(t, 0, sizeof *t);
  t->scale = 1;
}

static int transform_valid(const glint_transform *t) {
  return gli_vec3_in_range(t->translate) && gli_vec3_finite(t->rotate) &&
         gli_vec3_in_range(t->pivot) && gli_in_range(t->scale) && t->scale > 0;
}

glint_status glint_scene_set_object_motion(glint_scene *s, uint32_t object,
                                           const glint_transform_key *keys,
                                           size_t count,
                                           glint_interpolation interpolation,
                                           glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  GLI_NOT_NULL(keys, "keys", error);
  if (count == 0)
    return gli_fail(error, GLINT_E_ARGUMENT, "object motion: no keys given");
  if (object >= s->object_count)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "object motion: there is no object %u (the scene has %zu)",
                    object, s->object_count);
  for (size_t i = 0; i < count; i++) {
    if (!transform_valid(&keys[i].transform))
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "object motion: key %zu: translate, pivot and scale "
                      "must be " GLI_RANGE_TEXT ", rotate finite, and the "
                      "scale positive",
                      i);
    glint_status st =
        check_time(keys[i].time, i, i ? keys[i - 1].time : 0, error);
    if (st)
      return st;
  }
  gli_track t;
  glint_status st =
      track_alloc(&t, count, TRANSFORM_VALUES, interpolation, error);
  if (st)
    return st;
  for (size_t i = 0; i < count; i++) {
    const glint_transform *k = &keys[i].transform;
    double v[TRANSFORM_VALUES] = {
        k->translate.x, k->translate.y, k->translate.z, k->rotate.x,
        k->rotate.y,    k->rotate.z,    k->pivot.x,     k->pivot.y,
        k->pivot.z,     k->scale};
    t.times[i] = keys[i].time;
    memcpy(t.values + i * TRANSFORM_VALUES, v, sizeof v);
  }
  /* A new motion for the object replaces its old one. */
  gli_animation *a = &s->animation;
  for (size_t i = 0; i < a->motion_count; i++)
    if (a->motions[i].object == object) {
      track_free(&a->motions[i].track);
      a->motions[i].track = t;
      return GLINT_OK;
    }
  gli_motion *grown =
      realloc(a->motions, sizeof *grown * (a->motion_count + 1));
  if (!grown) {
    track_free(&t);
    return gli_fail(error, GLINT_E_MEMORY, "out of memory for a motion");
  }
  a->motions = grown;
  a->motions[a->motion_count++] = (gli_motion){object, t};
  return GLINT_OK;
}

int glint_scene_has_motion(const glint_scene *s) {
  return s && s->animation.motion_count > 0;
}

glint_status glint_scene_at_time(const glint_scene *s, double time,
                                 glint_scene **out, glint_error *error) {
  GLI_NOT_NULL(s, "scene", error);
  GLI_NOT_NULL(out, "still", error);
  glint_camera camera;
  glint_status st = glint_scene_camera_at(s, time, &camera, error);
  if (st)
    return st;
  glint_scene *still;
  if ((st = gli_scene_copy(s, &still, error)))
    return st;
  for (size_t i = 0; i < s->animation.motion_count; i++) {
    double v[TRANSFORM_VALUES];
    track_at(&s->animation.motions[i].track, time, v);
    glint_transform t = {
        {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}, v[9]};
    if (!transform_valid(&t)) { /* a spline overshooting its keys */
      glint_scene_destroy(still);
      const char *what = NULL;
      glint_vec3 value = t.rotate;
      if (!gli_vec3_in_range(t.translate))
        what = "translate", value = t.translate;
      else if (!gli_vec3_in_range(t.pivot))
        what = "pivot", value = t.pivot;
      else if (!gli_vec3_finite(t.rotate))
        what = "rotate";
      if (what)
        return gli_fail(error, GLINT_E_ARGUMENT,
                        "object %u's motion at %g s has a %s %s (the spline "
                        "through its keys overshoots them)",
                        s->animation.motions[i].object, time, what,
                        gli_vec3_finite(value) ? "beyond magnitude 1e15"
                                               : "that is not finite");
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "object %u's motion at %g s has a scale of %g",
                      s->animation.motions[i].object, time, t.scale);
    }
    if (gli_object_transform(still, s->animation.motions[i].object, &t)) {
      glint_scene_destroy(still);
      return gli_fail(error, GLINT_E_ARGUMENT,
                      "object %u's motion at %g s moves it beyond "
                      "coordinates of magnitude 1e15",
                      s->animation.motions[i].object, time);
    }
  }
  /* Still: the camera of this time, and nothing left to move. */
  still->camera = camera;
  gli_animation_free(&still->animation);
  still->animation.camera_mode = GLI_CAMERA_STILL;
  *out = still;
  return GLINT_OK;
}
