/* A mesh file as it was read, before it goes into a scene: what the OBJ and
 * PLY readers (scene/formats/obj.c, ply.c) fill, and what
 * glint_scene_add_mesh_file (mesh.c) pushes into the scene once the whole
 * file has parsed, so that a file that fails leaves the scene as it was. */
#ifndef GLINT_SCENE_MESH_H
#define GLINT_SCENE_MESH_H

#include "glint.h"

#include <stddef.h>
#include <stdint.h>

/* A polygon with more corners than this is a damaged list count, not a
 * real face; the limit keeps a garbage count from allocating gigabytes. */
#define MESH_MAX_FACE_VERTICES (1 << 20)
/* Vertex and triangle indices are uint32_t in the scene. */
#define MESH_MAX_ITEMS ((size_t)UINT32_MAX - 1)
#define MESH_NO_INDEX UINT32_MAX
#define MESH_WHERE_STRIP (UINT32_C(1) << 31) /* see mesh_data.tri_where */

typedef struct tri3 {
  uint32_t v[3];
} tri3;

typedef struct corner {
  uint32_t v, n; /* position and normal index; n = MESH_NO_INDEX: none */
} corner;

/* The first item of a list (vertices, normals) that is not finite. */
typedef struct mesh_nonfinite {
  uint32_t index; /* MESH_NO_INDEX: none */
  char why[1024];
} mesh_nonfinite;

typedef struct mesh_data {
  glint_vec3 *pos;
  size_t npos, pos_cap;
  glint_vec3 *nrm;
  size_t nnrm, nrm_cap;
  tri3 *tri; /* position indices */
  size_t ntri, tri_cap;
  tri3 *tri_nrm; /* OBJ: normal indices, parallel to tri; MESH_NO_INDEX: flat */
  size_t tri_nrm_cap;
  int vertex_normals; /* PLY: nrm[i] belongs to pos[i] */
  /* Where each triangle's face is, for the messages of the checks that run
   * once the file is read: its line (where_is_line: OBJ, ASCII PLY) or its
   * number among the faces (binary PLY, from 0 as PLY counts), as the
   * reader set face_where before gli_mesh_emit_face. first_index is the
   * number the file's faces give its first vertex (OBJ 1, PLY 0). */
  uint32_t *tri_where; /* binary PLY: | MESH_WHERE_STRIP for a strip's */
  size_t tri_where_cap;
  uint32_t face_where;
  int where_is_line, first_index;
  corner *corners; /* the face being read */
  size_t ncorners, corners_cap;
  size_t *ear_tests_left; /* the scene's (scene/polygon.h) */
  /* The first vertex whose position is not a finite number, and the first
   * such normal: scanners write nan for points no face uses, so they are
   * kept (as read) and refused only where a face uses them, with the
   * reader's message; MESH_NO_INDEX while there is none. */
  mesh_nonfinite nonfinite_pos, nonfinite_nrm;
} mesh_data;

/* A reader's note that vertex (or normal) `index` has a coordinate that is
 * not finite, `why` its message (see mesh_data.nonfinite_pos). */
void gli_mesh_nonfinite(mesh_nonfinite *first, size_t index,
                        const glint_error *why);

void gli_mesh_free(mesh_data *m);
/* "PATH: out of memory" */
glint_status gli_mesh_oom(const char *path, glint_error *e);
/* Appends the n - 2 triangles of the face in m->corners: a fan (c0, ci,
 * ci+1) when it is convex, else the ear clipping of polygon.c. `obj` keeps
 * the corners' normal indices beside the triangle (when `with_normals`).
 * Returns 0, -1 (out of memory) or GLI_TRIANGULATE_TOO_COMPLEX. */
int gli_mesh_emit_face(mesh_data *m, int obj, int with_normals);

/* glint_scene_add_mesh_file on a file's bytes already in memory (`size`
 * of them, then a NUL); `name` chooses the reader and names it in
 * messages. */
glint_status gli_scene_add_mesh_data(glint_scene *scene, const char *name,
                                     const char *data, size_t size,
                                     double scale, glint_vec3 translate,
                                     uint32_t material_id, glint_error *error);

/* glint_scene_add_mesh_file with the file from `files` (NULL: the file
 * system). */
struct gli_file_source;
glint_status gli_scene_add_mesh_from(glint_scene *scene,
                                     const struct gli_file_source *files,
                                     const char *path, double scale,
                                     glint_vec3 translate, uint32_t material_id,
                                     glint_error *error);

/* The readers: `data` is the whole file, NUL-terminated after `size`. */
glint_status gli_obj_parse(const char *path, const char *data, size_t size,
                           mesh_data *m, glint_error *e);
glint_status gli_ply_parse(const char *path, const char *data, size_t size,
                           mesh_data *m, glint_error *e);
/* The length of a PLY header whose lines end with a CR alone, through its
 * end_header line, or the whole file where its format line says ascii (or
 * no end_header line ends it, for the reader to refuse): what of such a
 * file is text, to be given LFs before gli_ply_parse reads it. */
size_t gli_ply_text_bytes(const char *data, size_t size);

#endif
