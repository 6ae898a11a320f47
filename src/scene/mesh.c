/* Placeholder until the mesh readers land. */
#include "core/error.h"
#include "scene/scene.h"

glint_status glint_scene_add_mesh_file(glint_scene *scene, const char *path,
                                       double scale, glint_vec3 translate,
                                       uint32_t material_id,
                                       glint_error *error) {
  (void)scene;
  (void)scale;
  (void)translate;
  (void)material_id;
  return glint_fail(error, GLINT_E_UNSUPPORTED,
                    "%s: mesh files are not readable yet", path);
}
