/* Mesh files into the scene: the file is read whole (zlib passes plain files
 * through), parsed by its format's reader (scene/formats/obj.c, ply.c) into a
 * mesh_data, and only a file that parsed completely is pushed into the
 * scene, the push itself rolled back if the scene refuses a triangle. That
 * is how a failed load leaves the scene exactly as it was.
 *
 * Why readers of our own and not assimp: errors must say FILE:LINE (assimp
 * gives no line numbers), .gz must be read transparently (assimp cannot) and
 * the 200k-triangle dragon must load fast. */
#include "scene/mesh.h"

#include "core/error.h"
#include "core/memory.h"
#include "scene/file.h"
#include "scene/formats/registry.h"
#include "scene/number.h"
#include "scene/polygon.h"
#include "scene/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The same limit as the text reader: files beyond it are not meshes we
 * could render anyway, and it keeps sizes well inside size_t arithmetic. */
#define MAX_FILE_BYTES ((size_t)4 << 30)

void gli_mesh_free(mesh_data *m) {
  free(m->pos);
  free(m->nrm);
  free(m->tri);
  free(m->tri_nrm);
  free(m->tri_where);
  free(m->corners);
}

glint_status gli_mesh_oom(const char *path, glint_error *e) {
  return gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
}

typedef struct face_emit {
  mesh_data *m;
  int obj, with_normals;
} face_emit;

/* Appends the triangle of the face's corners a, b, c (room is made by the
 * caller). `with_normals` stores the corners' normal indices too (OBJ),
 * else MESH_NO_INDEX. */
static int emit_corners(void *user, size_t a, size_t b, size_t c) {
  face_emit *fe = user;
  mesh_data *m = fe->m;
  const corner *k = m->corners;
  m->tri[m->ntri] = (tri3){{k[a].v, k[b].v, k[c].v}};
  if (fe->obj)
    m->tri_nrm[m->ntri] =
        fe->with_normals
            ? (tri3){{k[a].n, k[b].n, k[c].n}}
            : (tri3){{MESH_NO_INDEX, MESH_NO_INDEX, MESH_NO_INDEX}};
  m->tri_where[m->ntri] = m->face_where;
  m->ntri++;
  return 0;
}

void gli_mesh_nonfinite(mesh_nonfinite *first, size_t index,
                        const glint_error *why) {
  if (first->index != MESH_NO_INDEX)
    return;
  first->index = (uint32_t)index;
  snprintf(first->why, sizeof first->why, "%s", why->message);
}

static int finite_point(glint_vec3 p) {
  return isfinite(p.x) && isfinite(p.y) && isfinite(p.z);
}

/* A fan of a concave face would cover what is not the face: those are
 * clipped by ears instead. */
int gli_mesh_emit_face(mesh_data *m, int obj, int with_normals) {
  size_t n = m->ncorners, add = n - 2;
  if (gli_grow((void **)&m->tri, &m->tri_cap, m->ntri + add, sizeof(tri3)) ||
      gli_grow((void **)&m->tri_where, &m->tri_where_cap, m->ntri + add,
               sizeof *m->tri_where))
    return -1;
  if (obj && gli_grow((void **)&m->tri_nrm, &m->tri_nrm_cap, m->ntri + add,
                      sizeof(tri3)))
    return -1;
  face_emit fe = {m, obj, with_normals};
  /* Corners not read yet (a triangle of a PLY whose faces come before its
   * vertices; larger faces wait for them, scene/formats/ply.c) or not
   * finite (refused once the file is read) cannot be checked: a fan. */
  int known = n > 3;
  for (size_t i = 0; known && i < n; i++)
    known = m->corners[i].v < m->npos && finite_point(m->pos[m->corners[i].v]);
  glint_vec3 small[16], *v = n <= 16 ? small : malloc(n * sizeof *v);
  if (!v)
    return -1;
  for (size_t i = 0; known && i < n; i++)
    v[i] = m->pos[m->corners[i].v];
  /* A convex face of more than four corners is bisected, not fanned
   * (gli_triangulate): a fan of a large face is a spray of slivers, each
   * with a box as large as the face's, and a 4096-corner disc rendered
   * 18-40 times slower as one than bisected. */
  if (!known || (n <= 4 && gli_polygon_is_convex(v, n))) {
    for (size_t i = 1; i + 1 < n; i++)
      emit_corners(&fe, 0, i, i + 1);
    if (v != small)
      free(v);
    return 0;
  }
  int r = gli_triangulate(v, n, emit_corners, &fe, m->ear_tests_left);
  if (v != small)
    free(v);
  return r;
}

/* The indices of triangle i's vertex normals, or NULL where it has none. */
static const uint32_t *normal_indices(const mesh_data *m, size_t i) {
  return m->vertex_normals                                   ? m->tri[i].v
         : m->tri_nrm && m->tri_nrm[i].v[0] != MESH_NO_INDEX ? m->tri_nrm[i].v
                                                             : NULL;
}

/* Triangle i's vertex normals in n, or NULL where it has none. */
static const glint_vec3 *triangle_normals(const mesh_data *m, size_t i,
                                          glint_vec3 n[3]) {
  const uint32_t *v = normal_indices(m, i);
  if (!v)
    return NULL;
  for (int k = 0; k < 3; k++)
    n[k] = m->nrm[v[k]];
  return n;
}

/* Triangle i's face as a message's tail names it: "the face on line N",
 * or in a binary PLY "face N" or "triangle strip N". */
static const char *face_named(const mesh_data *m, size_t i, char *buf,
                              size_t cap) {
  uint32_t w = m->tri_where[i];
  if (m->where_is_line)
    snprintf(buf, cap, "the face on line %u", w);
  else
    snprintf(buf, cap, "%s %u",
             w & MESH_WHERE_STRIP ? "triangle strip" : "face",
             w & ~MESH_WHERE_STRIP);
  return buf;
}

/* The same as a message starts: "FILE:LINE", or "FILE: face N". */
static void face_of(const char *path, const mesh_data *m, size_t i, char *buf,
                    size_t cap) {
  char named[48];
  if (m->where_is_line)
    snprintf(buf, cap, "%.1000s:%u", path, m->tri_where[i]);
  else
    snprintf(buf, cap, "%.1000s: %s", path,
             face_named(m, i, named, sizeof named));
}

/* A vertex or a normal that is not finite is refused where a face uses
 * it: `normals` chooses which, `list` and `first` are its. */
static glint_status check_used(const char *path, const mesh_data *m,
                               int normals, const glint_vec3 *list,
                               const mesh_nonfinite *first, glint_error *e) {
  if (first->index == MESH_NO_INDEX)
    return GLINT_OK;
  for (size_t i = 0; i < m->ntri; i++) {
    const uint32_t *v = normals ? normal_indices(m, i) : m->tri[i].v;
    for (int k = 0; v && k < 3; k++) {
      if (finite_point(list[v[k]]))
        continue;
      char face[1100];
      face_of(path, m, i, face, sizeof face);
      if (v[k] == first->index) /* the reader's message names the vertex */
        return gli_fail(e, GLINT_E_PARSE, "%s (and %s uses it)", first->why,
                        face_named(m, i, face, sizeof face));
      return gli_fail(
          e, GLINT_E_PARSE, "%s: the face uses %s %u, which is not a finite %s",
          face, normals ? "normal" : "vertex", v[k] + (uint32_t)m->first_index,
          normals ? "direction" : "point");
    }
  }
  return GLINT_OK;
}

static glint_status check_used_vertices(const char *path, const mesh_data *m,
                                        glint_error *e) {
  glint_status st = check_used(path, m, 0, m->pos, &m->nonfinite_pos, e);
  return st ? st : check_used(path, m, 1, m->nrm, &m->nonfinite_nrm, e);
}

static glint_status add_to_scene(glint_scene *s, const char *path, mesh_data *m,
                                 double scale, glint_vec3 tr, uint32_t material,
                                 glint_error *e) {
  glint_status checked = check_used_vertices(path, m, e);
  if (checked)
    return checked;
  for (size_t i = 0; i < m->npos; i++) {
    glint_vec3 *p = &m->pos[i];
    *p = (glint_vec3){p->x * scale + tr.x, p->y * scale + tr.y,
                      p->z * scale + tr.z};
  }
  size_t obj0 = s->object_count, tri0 = s->triangle_count,
         nrm0 = s->tri_normal_count;
  glint_status st = gli_scene_begin_object(s, GLI_SHAPE_TRIANGLE, material, e);
  if (st)
    goto fail;
  /* One allocation up front instead of a doubling per power of two. */
  size_t smooth = 0;
  for (size_t i = 0; i < m->ntri; i++)
    smooth += normal_indices(m, i) != NULL;
  if (gli_grow((void **)&s->triangles, &s->triangle_cap, tri0 + m->ntri,
               sizeof *s->triangles) ||
      (smooth && gli_grow((void **)&s->tri_normals, &s->tri_normal_cap,
                          nrm0 + 3 * smooth, sizeof *s->tri_normals))) {
    st = gli_mesh_oom(path, e);
    goto fail;
  }
  /* Checked in the file's order, so that a message names the file's first
   * bad triangle; added in a Morton order (gli_morton_order). */
  for (size_t i = 0; i < m->ntri; i++) {
    glint_vec3 n[3];
    const uint32_t *v = m->tri[i].v;
    st = gli_scene_check_triangle(m->pos[v[0]], m->pos[v[1]], m->pos[v[2]],
                                  triangle_normals(m, i, n), e);
    if (st) {
      /* A coordinate beyond GLINT_MAX_COORDINATE, in the file or once
       * scaled and moved:
       * named by the vertex's number, as the file's faces name it. */
      char msg[sizeof e->message];
      snprintf(msg, sizeof msg, "%s", e ? e->message : "");
      /* how the file's coordinates were placed: the scale, and the move
       * where there is one (a far translate was blamed on a scale of 1) */
      char placed[160];
      if (tr.x != 0 || tr.y != 0 || tr.z != 0)
        snprintf(placed, sizeof placed,
                 "scaled by %g and moved by (%g, %g, %g)", scale, tr.x, tr.y,
                 tr.z);
      else
        snprintf(placed, sizeof placed, "scaled by %g", scale);
      int k = 0;
      while (k < 2 && gli_vec3_in_range(m->pos[v[k]]))
        k++;
      char face[1100];
      face_of(path, m, i, face, sizeof face);
      if (!gli_vec3_in_range(m->pos[v[k]]))
        st = gli_fail(e, st, "%s: vertex %u, %s: %s", face,
                      v[k] + (uint32_t)m->first_index, placed, msg);
      else /* a normal's: not scaled nor moved */
        st = gli_fail(e, st, "%s: %s", face, msg);
      goto fail;
    }
  }
  _Static_assert(sizeof(tri3) == 3 * sizeof(uint32_t), "tri3 is 3 indices");
  uint32_t *order =
      gli_morton_order(m->pos, m->ntri ? m->tri[0].v : NULL, m->ntri);
  for (size_t k = 0; k < m->ntri && !st; k++) {
    size_t i = order ? order[k] : k;
    glint_vec3 n[3];
    const uint32_t *v = m->tri[i].v;
    st = gli_scene_append_triangle(s, m->pos[v[0]], m->pos[v[1]], m->pos[v[2]],
                                   triangle_normals(m, i, n), e);
  }
  free(order);
  if (st)
    goto fail;
  /* Solid textures are in object-local coordinates: the file's origin,
   * wherever the translation put it. */
  s->objects[obj0].origin = tr;
  return GLINT_OK;
fail: /* leave the scene as it was */
  s->object_count = obj0;
  s->triangle_count = tri0;
  s->tri_normal_count = nrm0;
  return st;
}

/* What both entries check before reading a byte, so that a bad call costs
 * no parse. A negative scale would mirror the mesh and turn its faces
 * inside out. */
static glint_status check_mesh_call(const glint_scene *scene, const char *path,
                                    double scale, glint_vec3 translate,
                                    uint32_t material_id, gli_mesh_reader *read,
                                    glint_error *error) {
  if (!scene || !path)
    return gli_fail(error, GLINT_E_ARGUMENT, "mesh file: missing argument");
  if (!isfinite(scale) || !(scale > 0))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: scale %g must be a finite number > 0", path, scale);
  if (!gli_vec3_finite(translate))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: the translation must be finite", path);
  if (material_id >= scene->material_count)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: material %u does not exist (the scene has %zu)", path,
                    material_id, scene->material_count);
  if (!(*read = gli_mesh_reader_for(path)))
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: not a mesh file (.obj or .ply, optionally .gz)", path);
  return GLINT_OK;
}

/* Files from old Macs end their lines with a CR alone, which the readers,
 * like most, do not take for a line end: such a file gets LFs, in a copy
 * (*copy stays NULL when the file's first line ends otherwise). A binary
 * PLY's body is not text and keeps its bytes. Returns -1 when out of
 * memory. */
static int with_lf_line_ends(const char *data, size_t size, int is_ply,
                             char **copy) {
  *copy = NULL;
  const char *cr = memchr(data, '\r', size), *lf = memchr(data, '\n', size);
  if (!cr || (lf && lf < cr) || (cr + 1 < data + size && cr[1] == '\n'))
    return 0;
  char *c = malloc(size + 1);
  if (!c)
    return -1;
  memcpy(c, data, size);
  c[size] = '\0';
  size_t limit = is_ply ? gli_ply_text_bytes(data, size) : size;
  for (size_t i = 0; i < limit; i++)
    if (c[i] == '\r' && (i + 1 == size || c[i + 1] != '\n'))
      c[i] = '\n';
  *copy = c;
  return 0;
}

static glint_status add_mesh_text(glint_scene *scene, const char *path,
                                  gli_mesh_reader read, const char *data,
                                  size_t size, double scale,
                                  glint_vec3 translate, uint32_t material_id,
                                  glint_error *error) {
  /* Numbers in mesh files always use '.', whatever LC_NUMERIC the host
   * program chose; uselocale changes this thread only, and only for now. */
  gli_file_skip_bom(&data, &size);
  char *lf;
  if (with_lf_line_ends(data, size, read == gli_ply_parse, &lf))
    return gli_fail(error, GLINT_E_MEMORY, "%s: out of memory", path);
  number_locale locale = gli_number_locale_begin();
  mesh_data m;
  memset(&m, 0, sizeof m);
  m.ear_tests_left = &scene->ear_tests_left;
  m.nonfinite_pos.index = m.nonfinite_nrm.index = MESH_NO_INDEX;
  glint_status st = read(path, lf ? lf : data, size, &m, error);
  gli_number_locale_end(locale);
  free(lf);
  if (!st)
    st = add_to_scene(scene, path, &m, scale, translate, material_id, error);
  gli_mesh_free(&m);
  return st;
}

glint_status glint_scene_add_mesh_file(glint_scene *scene, const char *path,
                                       double scale, glint_vec3 translate,
                                       uint32_t material_id,
                                       glint_error *error) {
  GLI_NOT_NULL(scene, "scene", error);
  GLI_NOT_NULL(path, "path", error);
  return gli_scene_add_mesh_from(scene, NULL, path, scale, translate,
                                 material_id, error);
}

glint_status gli_scene_add_mesh_from(glint_scene *scene,
                                     const gli_file_source *files,
                                     const char *path, double scale,
                                     glint_vec3 translate, uint32_t material_id,
                                     glint_error *error) {
  gli_mesh_reader read;
  glint_status st =
      check_mesh_call(scene, path, scale, translate, material_id, &read, error);
  if (st)
    return st;
  char *data = NULL;
  size_t size = 0;
  int text = read != gli_ply_parse; /* a PLY's body may be binary */
  if ((st = gli_file_source_read(files, path, MAX_FILE_BYTES, text, &data,
                                 &size, error)))
    return st;
  st = add_mesh_text(scene, path, read, data, size, scale, translate,
                     material_id, error);
  free(data);
  return st;
}

glint_status gli_scene_add_mesh_data(glint_scene *scene, const char *name,
                                     const char *data, size_t size,
                                     double scale, glint_vec3 translate,
                                     uint32_t material_id, glint_error *error) {
  gli_mesh_reader read;
  glint_status st =
      check_mesh_call(scene, name, scale, translate, material_id, &read, error);
  if (st)
    return st;
  return add_mesh_text(scene, name, read, data, size, scale, translate,
                       material_id, error);
}
