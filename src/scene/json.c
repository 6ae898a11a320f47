/* placeholder until the JSON reader lands */
#include "core/error.h"
#include "scene/scene.h"
glint_status glint_json_load(const char *path, glint_scene **out, glint_error *error) { (void)out; return glint_fail(error, GLINT_E_UNSUPPORTED, "%s: JSON scenes are not readable yet", path); }
