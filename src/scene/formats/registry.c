#include "scene/formats/registry.h"

#include "core/error.h"
#include "scene/file.h"
#include "scene/scene.h"

#include <stdlib.h>

#include <string.h>
#include <strings.h>

typedef struct scene_format {
  const char *extension;
  /* Larger files are refused: they are not scenes we could render anyway,
   * and cJSON needs several times the text's size for its tree (large
   * geometry belongs in mesh files). */
  size_t max_bytes;
  glint_status (*read)(const gli_file_source *files, const char *path,
                       const char *data, size_t size, glint_scene **out,
                       glint_error *error);
} scene_format;

static const scene_format scene_formats[] = {
    {".nff", (size_t)4 << 30, gli_nff_read},
    {".json", (size_t)1 << 30, gli_json_read},
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

/* Whether the file name ends in `extension`, before an optional .gz (gzip
 * is undone by the file reader, whatever the name). */
static int has_extension(const char *path, const char *extension) {
  const char *slash = strrchr(path, '/');
  const char *base = slash ? slash + 1 : path;
  size_t n = strlen(base);
  if (ends_with(base, n, ".gz"))
    n -= 3;
  return ends_with(base, n, extension);
}

static const scene_format *scene_format_of(const char *name) {
  for (size_t i = 0; i < sizeof scene_formats / sizeof *scene_formats; i++)
    if (has_extension(name, scene_formats[i].extension))
      return &scene_formats[i];
  return NULL;
}

static glint_status not_a_scene(const char *name, glint_error *error) {
  return gli_fail(error, GLINT_E_ARGUMENT,
                  "%s: not a scene file (.nff or .json, optionally .gz)", name);
}

glint_status glint_scene_load(const char *path, glint_scene **out,
                              glint_error *error) {
  GLI_NOT_NULL(path, "path", error);
  GLI_NOT_NULL(out, "scene", error);
  return gli_scene_load_from(NULL, path, out, error);
}

glint_status gli_scene_load_from(const gli_file_source *files, const char *path,
                                 glint_scene **out, glint_error *error) {
  if (!path || !out)
    return gli_fail(error, GLINT_E_ARGUMENT, "scene file: missing argument");
  const scene_format *f = scene_format_of(path);
  if (!f)
    return not_a_scene(path, error);
  char *data;
  size_t size;
  glint_status st =
      gli_file_source_read(files, path, f->max_bytes, 1, &data, &size, error);
  if (st)
    return st;
  st = f->read(files, path, data, size, out, error);
  free(data);
  return st;
}

glint_status glint_scene_load_memory(const void *data, size_t size,
                                     const char *name, glint_scene **out,
                                     glint_error *error) {
  GLI_NOT_NULL(data, "data", error); /* even for 0 bytes: "" is empty */
  GLI_NOT_NULL(name, "name", error);
  GLI_NOT_NULL(out, "scene", error);
  const scene_format *f = scene_format_of(name);
  if (!f)
    return not_a_scene(name, error);
  if (size > f->max_bytes)
    return gli_fail(error, GLINT_E_IO, "%s: larger than %zu bytes", name,
                    f->max_bytes);
  /* The readers want a NUL after the last byte. */
  char *copy = malloc(size + 1);
  if (!copy)
    return gli_fail(error, GLINT_E_MEMORY, "%s: out of memory", name);
  if (size)
    memcpy(copy, data, size);
  copy[size] = '\0';
  glint_status st = f->read(NULL, name, copy, size, out, error);
  free(copy);
  return st;
}

gli_mesh_reader gli_mesh_reader_for(const char *path) {
  for (size_t i = 0; i < sizeof mesh_formats / sizeof *mesh_formats; i++)
    if (has_extension(path, mesh_formats[i].extension))
      return mesh_formats[i].read;
  return NULL;
}
