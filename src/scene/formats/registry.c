#include "scene/formats/registry.h"

#include "core/error.h"
#include "scene/scene.h"

#include <string.h>
#include <strings.h>

typedef struct scene_format {
  const char *extension;
  glint_status (*load)(const char *path, glint_scene **out, glint_error *error);
} scene_format;

static const scene_format scene_formats[] = {
    {".nff", gli_nff_load},
    {".json", gli_json_load},
};

typedef struct mesh_format {
  const char *extension;
  gli_mesh_reader read;
} mesh_format;

static const mesh_format mesh_formats[] = {
    {".obj", gli_obj_parse},
    {".ply", gli_ply_parse},
};

/* Whether the file name's first n characters end in `extension`. */
static int ends_with(const char *name, size_t n, const char *extension) {
  size_t e = strlen(extension);
  return n > e && strncasecmp(name + n - e, extension, e) == 0;
}

static const char *base_name(const char *path) {
  const char *slash = strrchr(path, '/');
  return slash ? slash + 1 : path;
}

glint_status glint_scene_load(const char *path, glint_scene **out,
                              glint_error *error) {
  const char *base = base_name(path);
  for (size_t i = 0; i < sizeof scene_formats / sizeof *scene_formats; i++)
    if (ends_with(base, strlen(base), scene_formats[i].extension))
      return scene_formats[i].load(path, out, error);
  return gli_fail(error, GLINT_E_ARGUMENT,
                  "%s: not a built-in scene nor a scene file (.nff or "
                  ".json)",
                  path);
}

gli_mesh_reader gli_mesh_reader_for(const char *path) {
  const char *base = base_name(path);
  size_t n = strlen(base);
  if (ends_with(base, n, ".gz"))
    n -= 3;
  for (size_t i = 0; i < sizeof mesh_formats / sizeof *mesh_formats; i++)
    if (ends_with(base, n, mesh_formats[i].extension))
      return mesh_formats[i].read;
  return NULL;
}
