/* The renderer of include/glint.h ("Worlds and renderers"), with the two
 * outputs glint_render and glint_trace_primary need beside the public film:
 * an 8-bit image converted tile by tile on the workers, and primary hits. */
#ifndef GLINT_RENDER_RENDERER_H
#define GLINT_RENDER_RENDERER_H

#include "glint.h"

#include <stdint.h>

typedef struct frame_output {
  glint_film *film;   /* the frame's linear pixels; may be NULL if image is set
                         or primary_only */
  glint_image *image; /* NULL, or 8-bit pixels written as each tile finishes */
  double gamma;       /* of `image` */
  int primary_only;   /* nearest hits of the primary rays only */
  uint64_t hits;      /* primary_only: how many hit */
} frame_output;

glint_status gli_renderer_render(glint_renderer *renderer,
                                 const glint_frame_settings *frame,
                                 frame_output *out, glint_stats *stats,
                                 glint_error *error);

/* The checks of glint_render_settings that do not depend on the scene
 * (size, depth, spp, region are frame checks: see renderer.c). */
glint_status gli_render_settings_check(const glint_render_settings *settings,
                                       int scene_width, int scene_height,
                                       glint_error *error);

#endif
