/* glint_render and glint_trace_primary: one frame through a world and a
 * renderer made for it and dropped afterwards. Only what the settings use is
 * built (the layout of one backend; the BVH unless accel is none). */
#include "core/error.h"
#include "core/timer.h"
#include "image/image.h"
#include "render/renderer.h"
#include "render/world.h"
#include "scene/scene.h"

#include <string.h>

void glint_render_settings_default(glint_render_settings *s) {
  if (!s)
    return;
  memset(s, 0, sizeof *s);
  s->max_depth = 5;
  s->spp = 5;
  s->backend = GLINT_BACKEND_AUTO;
  s->math = GLINT_MATH_MINIMAX;
  s->rcp_newton = 1;
  s->accel = GLINT_ACCEL_BVH;
  s->gamma = 1;
}

/* glint_render writes the 8-bit image tile by tile (no film); primary_only
 * traces without shading and writes nothing. */
static glint_status render_once(const glint_scene *scene,
                                const glint_render_settings *settings,
                                frame_output *out, glint_image **image,
                                glint_stats *stats, glint_error *error) {
  glint_render_settings defaults;
  if (!settings) {
    glint_render_settings_default(&defaults);
    settings = &defaults;
  }
  if (!scene)
    return gli_fail(error, GLINT_E_ARGUMENT, "no scene to render");
  glint_status st =
      gli_render_settings_check(settings, scene->width, scene->height, error);
  if (st)
    return st;

  double t0 = gli_now();
  glint_world *world = NULL;
  glint_renderer *renderer = NULL;
  if ((st = gli_world_create(scene, 1, &world, error)))
    return st;
  st = glint_renderer_create(world, settings, &renderer, error);
  gli_world_release(world); /* the renderer holds its own reference */
  if (st)
    return st;
  double prepare = gli_now() - t0;

  int w = settings->width ? settings->width : scene->width;
  int h = settings->height ? settings->height : scene->height;
  if (settings->region_width)
    w = settings->region_width, h = settings->region_height;
  if (image && (st = glint_image_create(w, h, image, error))) {
    glint_renderer_destroy(renderer);
    return st;
  }
  out->image = image ? *image : NULL;
  if (out->image)
    out->image->gamma = settings->gamma;
  out->gamma = settings->gamma;
  st = gli_renderer_render(renderer, NULL, out, stats, error);
  glint_renderer_destroy(renderer);
  if (st && image) {
    glint_image_destroy(*image);
    *image = NULL;
  }
  if (st == GLINT_OK && stats)
    stats->prepare_seconds = prepare;
  return st;
}

glint_status glint_render(const glint_scene *scene,
                          const glint_render_settings *settings,
                          glint_image **image, glint_stats *stats,
                          glint_error *error) {
  GLI_NOT_NULL(scene, "scene", error);
  GLI_NOT_NULL(image, "image", error);
  glint_image *result = NULL;
  frame_output out = {NULL, NULL, 1, 0, 0};
  glint_status st = render_once(scene, settings, &out, &result, stats, error);
  if (st == GLINT_OK)
    *image = result;
  return st;
}

glint_status glint_trace_primary(const glint_scene *scene,
                                 const glint_render_settings *settings,
                                 uint64_t *hits, glint_stats *stats,
                                 glint_error *error) {
  GLI_NOT_NULL(scene, "scene", error);
  GLI_NOT_NULL(hits, "hits", error);
  frame_output out = {NULL, NULL, 1, 1, 0};
  glint_status st = render_once(scene, settings, &out, NULL, stats, error);
  if (st == GLINT_OK && hits)
    *hits = out.hits;
  return st;
}
