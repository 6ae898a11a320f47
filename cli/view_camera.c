/* The viewer's camera moves: rotations about the scene's up axis and the
 * camera's right axis (Rodrigues' rotation formula), pans and dollies along
 * the camera's own frame. */
#include "view_camera.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const double degrees = 3.14159265358979323846 / 180.0;

static glint_vec3 add(glint_vec3 a, glint_vec3 b) {
  return (glint_vec3){a.x + b.x, a.y + b.y, a.z + b.z};
}
static glint_vec3 sub(glint_vec3 a, glint_vec3 b) {
  return (glint_vec3){a.x - b.x, a.y - b.y, a.z - b.z};
}
static glint_vec3 scale(glint_vec3 a, double s) {
  return (glint_vec3){a.x * s, a.y * s, a.z * s};
}
static double dot(glint_vec3 a, glint_vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
static glint_vec3 cross(glint_vec3 a, glint_vec3 b) {
  return (glint_vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                      a.x * b.y - a.y * b.x};
}
static double length(glint_vec3 a) { return sqrt(dot(a, a)); }
static glint_vec3 normalise(glint_vec3 a) {
  double l = length(a);
  return l > 0 ? scale(a, 1 / l) : a;
}

/* v rotated by `angle` radians about the unit axis k (Rodrigues):
 * v cos + (k x v) sin + k (k . v)(1 - cos). */
static glint_vec3 rotate(glint_vec3 v, glint_vec3 k, double angle) {
  double c = cos(angle), s = sin(angle);
  return add(add(scale(v, c), scale(cross(k, v), s)),
             scale(k, dot(k, v) * (1 - c)));
}

/* The camera's unit up (the scene's) and right axes for a view direction. */
static glint_vec3 right_axis(const glint_camera *c, glint_vec3 view) {
  return normalise(cross(view, normalise(c->up)));
}

/* Rotates `v` (a view direction) by yaw about up and pitch about right,
 * keeping it at least 1 degree away from up and down. */
static glint_vec3 swing(const glint_camera *c, glint_vec3 v, double yaw,
                        double pitch) {
  glint_vec3 up = normalise(c->up);
  v = rotate(v, up, yaw * degrees);
  double len = length(v);
  double elevation = asin(fmax(-1.0, fmin(1.0, dot(v, up) / len)));
  double limit = (90.0 - 1.0) * degrees;
  double target = fmax(-limit, fmin(limit, elevation + pitch * degrees));
  return rotate(v, right_axis(c, v), target - elevation);
}

/* A move that would leave a camera glint does not render (coordinates out
 * of range after scrolling out for long; from and at rounded into one
 * point, or the view onto up, after dollying back in from 1e14) is not
 * made: the view stays where it was, not ending the viewer with an
 * error. */
static void keep_renderable(glint_camera *c, const glint_camera *before) {
  if (glint_camera_check(c, NULL) != GLINT_OK)
    *c = *before;
}

void view_orbit(glint_camera *c, double yaw, double pitch) {
  glint_camera before = *c;
  /* The eye moves on the sphere around at: swing the vector at -> from the
   * other way, so that dragging right turns the scene right. */
  glint_vec3 back = sub(c->from, c->at);
  c->from = add(c->at, swing(c, back, -yaw, -pitch));
  keep_renderable(c, &before);
}

void view_turn(glint_camera *c, double yaw, double pitch) {
  glint_camera before = *c;
  glint_vec3 view = sub(c->at, c->from);
  c->at = add(c->from, swing(c, view, yaw, pitch));
  keep_renderable(c, &before);
}

void view_pan(glint_camera *c, double dx, double dy, double aspect) {
  glint_camera before = *c;
  glint_vec3 view = sub(c->at, c->from);
  double distance = length(view);
  double half_width = distance * tan(0.5 * c->fov_x_degrees * degrees);
  glint_vec3 right = right_axis(c, view);
  glint_vec3 up = normalise(cross(right, view));
  glint_vec3 move = add(scale(right, -dx * 2 * half_width),
                        scale(up, -dy * 2 * half_width / aspect));
  c->from = add(c->from, move);
  c->at = add(c->at, move);
  keep_renderable(c, &before);
}

void view_dolly(glint_camera *c, double factor) {
  glint_camera before = *c;
  glint_vec3 back = sub(c->from, c->at);
  double distance = length(back) * factor;
  if (distance < 1e-3)
    distance = 1e-3;
  c->from = add(c->at, scale(normalise(back), distance));
  keep_renderable(c, &before);
}

void view_fly(glint_camera *c, double forward, double right, double up) {
  glint_camera before = *c;
  glint_vec3 view = normalise(sub(c->at, c->from));
  glint_vec3 move =
      add(add(scale(view, forward), scale(right_axis(c, view), right)),
          scale(normalise(c->up), up));
  c->from = add(c->from, move);
  c->at = add(c->at, move);
  keep_renderable(c, &before);
}

/* x in the fewest digits (15 to 17) that read back as x: the camera
 * printed with 6 read back as another one, or as from and at in one
 * point, far from the origin. */
static const char *exact(double x, char buf[32]) {
  for (int digits = 15; digits < 17; digits++) {
    snprintf(buf, 32, "%.*g", digits, x);
    if (strtod(buf, NULL) == x)
      return buf;
  }
  snprintf(buf, 32, "%.17g", x);
  return buf;
}

void view_camera_json(const glint_camera *c, char *buf, unsigned long size) {
  char n[10][32];
  snprintf(buf, size,
           "\"camera\": {\"from\": [%s, %s, %s], \"at\": [%s, %s, %s], "
           "\"up\": [%s, %s, %s], \"fov\": %s}",
           exact(c->from.x, n[0]), exact(c->from.y, n[1]),
           exact(c->from.z, n[2]), exact(c->at.x, n[3]), exact(c->at.y, n[4]),
           exact(c->at.z, n[5]), exact(c->up.x, n[6]), exact(c->up.y, n[7]),
           exact(c->up.z, n[8]), exact(c->fov_x_degrees, n[9]));
}
