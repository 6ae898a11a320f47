/* Which reader a file goes to: scene files (NFF, JSON) and mesh files (OBJ,
 * PLY), each format one file in this folder, chosen by the file's extension
 * (case-insensitive; a mesh may add .gz). */
#ifndef GLINT_SCENE_FORMATS_REGISTRY_H
#define GLINT_SCENE_FORMATS_REGISTRY_H

#include "scene/mesh.h"

typedef glint_status (*gli_mesh_reader)(const char *path, const char *data,
                                        size_t size, mesh_data *m,
                                        glint_error *e);

/* The reader of the mesh file `path`, or NULL when it is none we read. */
gli_mesh_reader gli_mesh_reader_for(const char *path);

#endif
