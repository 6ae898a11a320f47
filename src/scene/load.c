/* Scene files, dispatched by extension. */
#include "core/error.h"
#include "scene/scene.h"

#include <string.h>
#include <strings.h>

glint_status glint_scene_load(const char *path, glint_scene **out,
                              glint_error *error) {
  const char *slash = strrchr(path, '/');
  const char *dot = strrchr(slash ? slash : path, '.');
  if (dot && strcasecmp(dot, ".nff") == 0)
    return gli_nff_load(path, out, error);
  if (dot && strcasecmp(dot, ".json") == 0)
    return gli_json_load(path, out, error);
  return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: not a built-in scene nor a scene file (.nff or "
                    ".json)",
                    path);
}
