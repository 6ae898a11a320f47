/* The viewer's camera moves (cli/view_camera.c): what a mouse drag or a key
 * does to a glint_camera. Angles in degrees; `up` is the scene's, kept as the
 * axis of orbiting and turning so that the horizon stays level. */
#ifndef GLINT_CLI_VIEW_CAMERA_H
#define GLINT_CLI_VIEW_CAMERA_H

#include <glint.h>

/* Orbits `from` around `at`: yaw about up, pitch about the camera's right
 * axis, stopping short of looking straight along up. */
void view_orbit(glint_camera *camera, double yaw, double pitch);
/* Turns the view in place: `at` around `from`, as orbiting does. */
void view_turn(glint_camera *camera, double yaw, double pitch);
/* Moves from and at together along the image plane by a fraction of the
 * visible width (dx, right) and height (dy, up) at the look-at distance. */
void view_pan(glint_camera *camera, double dx, double dy, double aspect);
/* Moves `from` towards `at` (factor < 1) or away (> 1), never onto it. */
void view_dolly(glint_camera *camera, double factor);
/* Flies from and at together: forward along the view, right, and along up,
 * in scene units. */
void view_fly(glint_camera *camera, double forward, double right, double up);
/* The camera as a JSON "camera" object for a scene file (docs/scene-format.md),
 * into buf (at least 512 bytes), each number in the fewest digits that
 * read back as it. */
void view_camera_json(const glint_camera *camera, char *buf,
                      unsigned long size);

#endif
