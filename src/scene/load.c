/* Scene files, dispatched by extension. */
#include "core/error.h"
#include "scene/scene.h"

#include <string.h>
#include <strings.h>

glint_status glint_scene_load(const char *path, glint_scene **out,
                              glint_error *error) {
  (void)out;
  const char *dot = strrchr(path, '.');
  if (dot && (strcasecmp(dot, ".nff") == 0 || strcasecmp(dot, ".json") == 0))
    return glint_fail(error, GLINT_E_UNSUPPORTED,
                      "%s: scene files are not supported yet", path);
  return glint_fail(error, GLINT_E_ARGUMENT,
                    "%s: unknown scene file type (use .nff or .json), or an "
                    "unknown built-in scene",
                    path);
}
