/* Stanford PLY meshes, ASCII and binary little- and big-endian: the vertex
 * element's x, y, z (and nx, ny, nz, when all three are there, for smooth
 * shading), the face element's vertex_indices (or vertex_index) list and
 * the tristrips element's (triangle strips, -1 ending a strip, as the
 * Georgia Tech models and Greg Turk's PLY library write them); every
 * other element and property is skipped by its declared type. ASCII
 * bodies are read line by line (one element per line), so a value too many
 * or too few is reported on its own line instead of shifting every later
 * value. */
#include "core/error.h"
#include "core/memory.h"
#include "scene/mesh.h"
#include "scene/number.h"
#include "scene/file.h"
#include "scene/polygon.h"
#include "scene/text.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef enum ply_type {
  PLY_INT8,
  PLY_UINT8,
  PLY_INT16,
  PLY_UINT16,
  PLY_INT32,
  PLY_UINT32,
  PLY_FLOAT32,
  PLY_FLOAT64
} ply_type;

static const unsigned char ply_size[] = {1, 1, 2, 2, 4, 4, 4, 8};
/* The integer types' ranges, for values written as text. */
static const long long ply_least[] = {-128, 0, -32768, 0, -2147483648LL, 0};
static const long long ply_most[] = {127,   255,        32767,
                                     65535, 2147483647, 4294967295LL};
static const char *const ply_type_name[] = {"char",   "uchar", "short",
                                            "ushort", "int",   "uint"};

typedef enum ply_format { PLY_ASCII, PLY_LE, PLY_BE } ply_format;

/* What a property is to us. */
enum {
  ROLE_NONE = 0,
  ROLE_X,
  ROLE_Y,
  ROLE_Z,
  ROLE_NX,
  ROLE_NY,
  ROLE_NZ,
  ROLE_INDICES
};

static const char *const role_what[] = {"",
                                        "the vertex's x",
                                        "the vertex's y",
                                        "the vertex's z",
                                        "the vertex's nx",
                                        "the vertex's ny",
                                        "the vertex's nz",
                                        "a face's vertex index"};

typedef struct ply_property {
  char label[48]; /* the name, printable */
  int is_list, role;
  ply_type type, count_type;
} ply_property;

typedef struct ply_element {
  char label[48];
  int kind; /* 0, or 1 for "vertex", 2 for "face", 3 for "tristrips" */
  size_t count, first_prop, prop_count;
} ply_element;

typedef struct ply_reader {
  const char *path;
  const unsigned char *data; /* NUL-terminated */
  size_t size, pos;
  size_t line; /* ASCII: the line at pos */
  ply_format format;
  ply_element *elements;
  size_t nelements, elements_cap;
  ply_property *props;
  size_t nprops, props_cap;
  const ply_element *el; /* the element being read, and its number */
  size_t index;
  size_t vertex_count; /* declared: faces are checked against it */
  mesh_data *m;
  /* Faces of more than 3 corners read before their vertices (a file may
   * order its elements so): each its count, where it is (face_where), then
   * its indices, cut into
   * triangles once the vertices are read (ply_late_faces), as a concave
   * one cannot be cut before. */
  uint32_t *late;
  size_t nlate, late_cap;
} ply_reader;

/* The face being read as mesh_data.face_where has it: its line (ASCII) or
 * its number among its element's (binary; a triangle strip's marked). */
static uint32_t ply_face_where(const ply_reader *r) {
  if (r->format == PLY_ASCII)
    return r->line < UINT32_MAX ? (uint32_t)r->line : UINT32_MAX;
  uint32_t w = r->index < MESH_WHERE_STRIP - 1 ? (uint32_t)r->index
                                               : MESH_WHERE_STRIP - 1;
  return r->el->kind == 3 ? w | MESH_WHERE_STRIP : w;
}

/* Where an error is: FILE:LINE for ASCII, FILE: vertex 12 for binary. */
static const char *ply_where(const ply_reader *r, char *buf, size_t cap) {
  if (r->format == PLY_ASCII)
    snprintf(buf, cap, "%s:%zu", r->path, r->line);
  else
    snprintf(buf, cap, "%s: %s %zu", r->path, r->el->label, r->index);
  return buf;
}

static const char *ply_plural(const ply_element *el, char *buf, size_t cap) {
  if (el->kind == 1)
    return "vertices";
  if (el->kind == 2)
    return "faces";
  if (el->kind == 3)
    return "triangle strips";
  snprintf(buf, cap, "'%s' elements", el->label);
  return buf;
}

static glint_status ply_truncated(const ply_reader *r, glint_error *e) {
  char w[1100], pl[64];
  if (r->format == PLY_ASCII)
    snprintf(w, sizeof w, "%s:%zu", r->path, r->line);
  else
    snprintf(w, sizeof w, "%s", r->path);
  return gli_fail(e, GLINT_E_PARSE, "%s: the file ends after %zu of %zu %s", w,
                  r->index, r->el->count, ply_plural(r->el, pl, sizeof pl));
}

/* --- values: ASCII tokens or binary bytes ------------------------------- */

/* ASCII: the next token on the current line; length 0 at its end. */
static const char *ply_token(ply_reader *r, size_t *len) {
  const char *p = (const char *)r->data + r->pos;
  while (gli_text_is_blank(*p))
    p++;
  const char *t = p;
  while (*p && *p != '\n' && !gli_text_is_blank(*p))
    p++;
  *len = (size_t)(p - t);
  r->pos = (size_t)(p - (const char *)r->data);
  return t;
}

/* What a value is, for an error message: built only when one is needed. */
static const char *ply_what(const ply_reader *r, const ply_property *p,
                            int count, char *buf, size_t cap) {
  if (count)
    snprintf(buf, cap, "the count of the %s's list '%s'", r->el->label,
             p->label);
  else if (p->role != ROLE_NONE)
    return role_what[p->role];
  else
    snprintf(buf, cap, "the %s's '%s'", r->el->label, p->label);
  return buf;
}

static glint_status ply_missing(ply_reader *r, const ply_property *p, int count,
                                glint_error *e) {
  if (r->pos >= r->size) /* the last line is cut short */
    return ply_truncated(r, e);
  char w[1100], what[128];
  return gli_fail(e, GLINT_E_PARSE,
                  "%s: expected a number for %s, found the end of the line",
                  ply_where(r, w, sizeof w),
                  ply_what(r, p, count, what, sizeof what));
}

/* Binary: `n` bytes as an unsigned number in the file's byte order, so the
 * result does not depend on the host's. */
static uint64_t ply_load(const unsigned char *p, unsigned n, int big) {
  uint64_t v = 0;
  if (big)
    for (unsigned i = 0; i < n; i++)
      v = v << 8 | p[i];
  else
    for (unsigned i = n; i-- > 0;)
      v = v << 8 | p[i];
  return v;
}

/* Binary: one value of `type` at pos as a double (exact for every type). */
static double ply_binary_value(ply_reader *r, ply_type type) {
  unsigned n = ply_size[type];
  uint64_t u = ply_load(r->data + r->pos, n, r->format == PLY_BE);
  r->pos += n;
  switch (type) {
  case PLY_INT8:
  case PLY_INT16:
  case PLY_INT32: { /* sign extension without implementation-defined casts */
    uint64_t sign = (uint64_t)1 << (8 * n - 1);
    return (double)((int64_t)(u ^ sign) - (int64_t)sign);
  }
  case PLY_FLOAT32: {
    uint32_t bits = (uint32_t)u;
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
  }
  case PLY_FLOAT64: {
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
  }
  default: return (double)u;
  }
}

static glint_status ply_whole(ply_reader *r, const ply_property *p, int count,
                              long long *out, glint_error *e);
static int ply_integer_type(ply_type t);

/* The next value as a number: a vertex coordinate. One that is not finite
 * reads as NaN, its message in *nonfinite unless that has one already (see
 * mesh_data.nonfinite_pos). */
static glint_status ply_number(ply_reader *r, const ply_property *p,
                               double *out, glint_error *nonfinite,
                               glint_error *e) {
  char w[1100], q[48];
  ply_type type = p->type;
  const char *what = role_what[p->role];
  if (r->format != PLY_ASCII) {
    if (r->size - r->pos < ply_size[type])
      return ply_truncated(r, e);
    double v = ply_binary_value(r, type);
    if (!isfinite(v)) {
      if (!nonfinite->status)
        gli_fail(nonfinite, GLINT_E_PARSE, "%s: %s is %g, not a finite number",
                 ply_where(r, w, sizeof w), what, v);
      v = NAN;
    }
    *out = v;
    return GLINT_OK;
  }
  /* A coordinate the header calls an integer is a whole number in the
   * type's range, as a binary file's would be. */
  if (ply_integer_type(type)) {
    long long whole = 0;
    glint_status st = ply_whole(r, p, 0, &whole, e);
    *out = (double)whole;
    return st;
  }
  size_t len;
  const char *t = ply_token(r, &len);
  if (len == 0)
    return ply_missing(r, p, 0, e);
  double v;
  int parsed = gli_number_parse(t, len, &v);
  if (parsed == NUMBER_BAD)
    return gli_fail(
        e, GLINT_E_PARSE, "%s: expected a number for %s, found '%s'",
        ply_where(r, w, sizeof w), what, gli_text_quote(q, sizeof q, t, len));
  if (parsed == NUMBER_NOT_FINITE) {
    if (!nonfinite->status)
      gli_fail(nonfinite, GLINT_E_PARSE, "%s: %s is '%s', not a finite number",
               ply_where(r, w, sizeof w), what,
               gli_text_quote(q, sizeof q, t, len));
    v = NAN;
  }
  *out = v;
  return GLINT_OK;
}

/* The next value as a whole number: a list count or a vertex index. The
 * header made sure `type` is an integer type. */
static glint_status ply_whole(ply_reader *r, const ply_property *p, int count,
                              long long *out, glint_error *e) {
  ply_type type = count ? p->count_type : p->type;
  if (r->format != PLY_ASCII) {
    if (r->size - r->pos < ply_size[type])
      return ply_truncated(r, e);
    *out = (long long)ply_binary_value(r, type);
    return GLINT_OK;
  }
  size_t len;
  const char *t = ply_token(r, &len), *s = t;
  if (len == 0)
    return ply_missing(r, p, count, e);
  char w[1100], q[48], what[128];
  if (gli_text_parse_whole(&s, t + len, out) || s != t + len)
    return gli_fail(
        e, GLINT_E_PARSE, "%s: expected a whole number for %s, found '%s'",
        ply_where(r, w, sizeof w), ply_what(r, p, count, what, sizeof what),
        gli_text_quote(q, sizeof q, t, len));
  if (*out < ply_least[type] || *out > ply_most[type])
    return gli_fail(e, GLINT_E_PARSE,
                    "%s: %s is %lld, outside the %s type the header gives it "
                    "(%lld..%lld)",
                    ply_where(r, w, sizeof w),
                    ply_what(r, p, count, what, sizeof what), *out,
                    ply_type_name[type], ply_least[type], ply_most[type]);
  return GLINT_OK;
}

/* Skips `n` values of `type` we have no use for. */
static glint_status ply_skip(ply_reader *r, const ply_property *p, long long n,
                             glint_error *e) {
  ply_type type = p->type;
  if (r->format != PLY_ASCII) {
    if ((unsigned long long)n > (r->size - r->pos) / ply_size[type])
      return ply_truncated(r, e);
    r->pos += (size_t)n * ply_size[type];
    return GLINT_OK;
  }
  /* Each value must be on the line, so a huge n ends at the line's end. */
  for (long long i = 0; i < n; i++) {
    size_t len;
    ply_token(r, &len);
    if (len == 0)
      return ply_missing(r, p, 0, e);
  }
  return GLINT_OK;
}

/* --- elements ------------------------------------------------------------ */

static glint_status ply_emit(ply_reader *r, int late, glint_error *e);

/* Whether v is the index of a declared vertex; `what` refers to it. */
static glint_status ply_vertex_index(const ply_reader *r, const char *what,
                                     long long v, glint_error *e) {
  if (v >= 0 && (unsigned long long)v < r->vertex_count)
    return GLINT_OK;
  char w[1100];
  return gli_fail(e, GLINT_E_PARSE,
                  "%s: %s refers to vertex %lld, but only %zu %s defined",
                  ply_where(r, w, sizeof w), what, v, r->vertex_count,
                  r->vertex_count == 1 ? "is" : "are");
}

static glint_status ply_face(ply_reader *r, const ply_property *p, long long n,
                             glint_error *e) {
  char w[1100];
  mesh_data *m = r->m;
  if (n < 3)
    return gli_fail(e, GLINT_E_PARSE,
                    "%s: a face needs at least 3 vertices, found %lld",
                    ply_where(r, w, sizeof w), n);
  if (n > MESH_MAX_FACE_VERTICES)
    return gli_fail(e, GLINT_E_PARSE,
                    "%s: a face with %lld vertices (at most %d; the list "
                    "count is probably damaged)",
                    ply_where(r, w, sizeof w), n, MESH_MAX_FACE_VERTICES);
  if (r->format != PLY_ASCII &&
      (unsigned long long)n > (r->size - r->pos) / ply_size[p->type])
    return ply_truncated(r, e);
  if (m->ntri + (size_t)n - 2 > MESH_MAX_ITEMS)
    return gli_fail(e, GLINT_E_PARSE, "%s: too many triangles",
                    ply_where(r, w, sizeof w));
  if (gli_grow((void **)&m->corners, &m->corners_cap, (size_t)n,
               sizeof *m->corners))
    return gli_mesh_oom(r->path, e);
  m->ncorners = (size_t)n;
  for (long long k = 0; k < n; k++) {
    long long v;
    glint_status st = ply_whole(r, p, 0, &v, e);
    if (st)
      return st;
    if ((st = ply_vertex_index(r, "face", v, e)))
      return st;
    m->corners[k] = (corner){(uint32_t)v, MESH_NO_INDEX};
  }
  int read = 1;
  for (long long k = 0; k < n && read; k++)
    read = m->corners[k].v < m->npos;
  if (n > 3 && !read) {
    if (gli_grow((void **)&r->late, &r->late_cap, r->nlate + 2 + (size_t)n,
                 sizeof *r->late))
      return gli_mesh_oom(r->path, e);
    r->late[r->nlate++] = (uint32_t)n;
    r->late[r->nlate++] = ply_face_where(r);
    for (long long k = 0; k < n; k++)
      r->late[r->nlate++] = m->corners[k].v;
    return GLINT_OK;
  }
  return ply_emit(r, 0, e);
}

/* The triangles of the face in m->corners: the one being read, or (late)
 * one read before the vertices, which the error names so. The location is
 * written only for an error: once a face, snprintf was a third of the
 * dragon's parse. */
static glint_status ply_emit(ply_reader *r, int late, glint_error *e) {
  char where[1100];
  if (!late)
    r->m->face_where = ply_face_where(r);
  switch (gli_mesh_emit_face(r->m, 0, 0)) {
  case 0: return GLINT_OK;
  case GLI_TRIANGULATE_TOO_COMPLEX:
    if (late)
      snprintf(where, sizeof where, "%s: a face listed before the vertices",
               r->path);
    else
      ply_where(r, where, sizeof where);
    return gli_fail(e, GLINT_E_PARSE,
                    "%s: the face of %zu vertices has too many inward "
                    "corners to triangulate (" GLI_EAR_LIMIT_TEXT ")",
                    where, r->m->ncorners);
  default: return gli_mesh_oom(r->path, e);
  }
}

/* A triangle strip of n indices: each index after the first two makes a
 * triangle with the two before it, every other one turned so that all
 * face the strip's first way; -1 ends a strip and the next begins. A
 * triangle that repeats a vertex (a strip turning) is none. */
static glint_status ply_strip(ply_reader *r, const ply_property *p, long long n,
                              glint_error *e) {
  char w[1100];
  mesh_data *m = r->m;
  if (r->format != PLY_ASCII &&
      (unsigned long long)n > (r->size - r->pos) / ply_size[p->type])
    return ply_truncated(r, e);
  if (gli_grow((void **)&m->corners, &m->corners_cap, 3, sizeof *m->corners))
    return gli_mesh_oom(r->path, e);
  long long a = -1, b = -1; /* the strip's last two vertices */
  int odd = 0;
  for (long long k = 0; k < n; k++) {
    long long v;
    glint_status st = ply_whole(r, p, 0, &v, e);
    if (st)
      return st;
    if (v == -1) {
      a = b = -1;
      odd = 0;
      continue;
    }
    if ((st = ply_vertex_index(r, "triangle strip", v, e)))
      return st;
    if (a >= 0 && a != b && b != v && a != v) {
      if (m->ntri + 1 > MESH_MAX_ITEMS)
        return gli_fail(e, GLINT_E_PARSE, "%s: too many triangles",
                        ply_where(r, w, sizeof w));
      m->ncorners = 3;
      m->corners[0] = (corner){(uint32_t)(odd ? b : a), MESH_NO_INDEX};
      m->corners[1] = (corner){(uint32_t)(odd ? a : b), MESH_NO_INDEX};
      m->corners[2] = (corner){(uint32_t)v, MESH_NO_INDEX};
      if ((st = ply_emit(r, 0, e)))
        return st;
    }
    if (a >= 0)
      odd = !odd;
    a = b;
    b = v;
  }
  return GLINT_OK;
}

/* The faces read before their vertices (ply_reader.late), now. */
static glint_status ply_late_faces(ply_reader *r, glint_error *e) {
  mesh_data *m = r->m;
  for (size_t i = 0; i < r->nlate; i += 2 + r->late[i]) {
    m->ncorners = r->late[i];
    m->face_where = r->late[i + 1];
    for (size_t k = 0; k < m->ncorners; k++)
      m->corners[k] = (corner){r->late[i + 2 + k], MESH_NO_INDEX};
    glint_status st = ply_emit(r, 1, e);
    if (st)
      return st;
  }
  return GLINT_OK;
}

/* ASCII: moves to the next non-blank line; 1 at the end of the file. */
static int ply_ascii_begin(ply_reader *r) {
  const char *p = (const char *)r->data + r->pos;
  for (;;) {
    while (gli_text_is_blank(*p))
      p++;
    if (*p != '\n')
      break;
    p++;
    r->line++;
  }
  r->pos = (size_t)(p - (const char *)r->data);
  return *p == '\0';
}

static glint_status ply_ascii_end(ply_reader *r, glint_error *e) {
  size_t len;
  const char *t = ply_token(r, &len);
  if (len) {
    char w[1100], q[48];
    return gli_fail(e, GLINT_E_PARSE,
                    "%s: unexpected '%s' after the %zu properties of the "
                    "%s",
                    ply_where(r, w, sizeof w),
                    gli_text_quote(q, sizeof q, t, len), r->el->prop_count,
                    r->el->label);
  }
  if (r->data[r->pos] == '\n') {
    r->pos++;
    r->line++;
  }
  return GLINT_OK;
}

static glint_status ply_element_body(ply_reader *r, glint_error *e) {
  const ply_element *el = r->el;
  double v[6] = {0, 0, 0, 0, 0, 0};
  glint_status st = GLINT_OK;
  glint_error nonfinite[2]; /* the position's, the normal's */
  nonfinite[0].status = nonfinite[1].status = GLINT_OK;
  if (r->format == PLY_ASCII && ply_ascii_begin(r))
    return ply_truncated(r, e);
  for (size_t i = 0; i < el->prop_count && !st; i++) {
    const ply_property *p = &r->props[el->first_prop + i];
    if (!p->is_list) {
      if (p->role >= ROLE_X && p->role <= ROLE_NZ)
        st = ply_number(r, p, &v[p->role - ROLE_X],
                        &nonfinite[p->role >= ROLE_NX], e);
      else
        st = ply_skip(r, p, 1, e);
      continue;
    }
    long long n;
    if ((st = ply_whole(r, p, 1, &n, e)))
      break;
    if (n < 0) {
      char w[1100], what[128];
      return gli_fail(e, GLINT_E_PARSE, "%s: %s is %lld, less than 0",
                      ply_where(r, w, sizeof w),
                      ply_what(r, p, 1, what, sizeof what), n);
    }
    if (p->role == ROLE_INDICES)
      st = el->kind == 3 ? ply_strip(r, p, n, e) : ply_face(r, p, n, e);
    else
      st = ply_skip(r, p, n, e);
  }
  if (!st && r->format == PLY_ASCII)
    st = ply_ascii_end(r, e);
  if (st || el->kind != 1)
    return st;
  mesh_data *m = r->m;
  if (nonfinite[0].status)
    gli_mesh_nonfinite(&m->nonfinite_pos, m->npos, &nonfinite[0]);
  if (nonfinite[1].status && m->vertex_normals)
    gli_mesh_nonfinite(&m->nonfinite_nrm, m->nnrm, &nonfinite[1]);
  if (GLI_PUSH(m->pos, m->npos, m->pos_cap, ((glint_vec3){v[0], v[1], v[2]})))
    return gli_mesh_oom(r->path, e);
  if (m->vertex_normals &&
      GLI_PUSH(m->nrm, m->nnrm, m->nrm_cap, ((glint_vec3){v[3], v[4], v[5]})))
    return gli_mesh_oom(r->path, e);
  return GLINT_OK;
}

static glint_status ply_read_element(ply_reader *r, const ply_element *el,
                                     glint_error *e) {
  r->el = el;
  r->index = 0;
  if (el->prop_count == 0) /* takes no bytes, whatever its count */
    return GLINT_OK;
  size_t fixed = 0; /* bytes per element when it has no lists */
  for (size_t i = 0; i < el->prop_count && fixed != SIZE_MAX; i++) {
    const ply_property *p = &r->props[el->first_prop + i];
    fixed = p->is_list ? SIZE_MAX : fixed + ply_size[p->type];
  }
  if (el->kind == 0 && r->format != PLY_ASCII && fixed != SIZE_MAX) {
    /* Nothing to read from it: skip all of it at once. */
    size_t whole = (r->size - r->pos) / fixed;
    if (el->count > whole) {
      r->index = whole;
      return ply_truncated(r, e);
    }
    r->pos += el->count * fixed;
    return GLINT_OK;
  }
  /* Reserve what the file can hold at most (every vertex takes 3 bytes or
   * more, every triangle 4), not what a damaged count claims. */
  mesh_data *m = r->m;
  size_t left = r->size - r->pos;
  if (el->kind == 1) {
    size_t want = el->count < left / 3 + 1 ? el->count : left / 3 + 1;
    if (gli_grow((void **)&m->pos, &m->pos_cap, want, sizeof *m->pos) ||
        (m->vertex_normals &&
         gli_grow((void **)&m->nrm, &m->nrm_cap, want, sizeof *m->nrm)))
      return gli_mesh_oom(r->path, e);
  } else if (el->kind == 2) {
    size_t want = el->count < left / 4 + 1 ? el->count : left / 4 + 1;
    if (gli_grow((void **)&m->tri, &m->tri_cap, m->ntri + want,
                 sizeof *m->tri) ||
        gli_grow((void **)&m->tri_where, &m->tri_where_cap, m->ntri + want,
                 sizeof *m->tri_where))
      return gli_mesh_oom(r->path, e);
  }
  for (; r->index < el->count; r->index++) {
    glint_status st = ply_element_body(r, e);
    if (st)
      return st;
  }
  return GLINT_OK;
}

/* --- the header ---------------------------------------------------------- */

typedef struct span {
  const char *s;
  size_t n;
} span;

static int span_is(span t, const char *word) {
  return t.n == strlen(word) && memcmp(t.s, word, t.n) == 0;
}

/* Splits [b, end) at blanks; returns the number of tokens (even beyond max). */
static size_t split(const char *b, const char *end, span *tok, size_t max) {
  size_t n = 0;
  while (b < end) {
    while (b < end && gli_text_is_blank(*b))
      b++;
    if (b == end)
      break;
    const char *s = b;
    while (b < end && !gli_text_is_blank(*b))
      b++;
    if (n < max)
      tok[n] = (span){s, (size_t)(b - s)};
    n++;
  }
  return n;
}

static int ply_parse_type(span t, ply_type *out) {
  static const struct {
    const char *name;
    ply_type type;
  } names[] = {{"char", PLY_INT8},      {"int8", PLY_INT8},
               {"uchar", PLY_UINT8},    {"uint8", PLY_UINT8},
               {"short", PLY_INT16},    {"int16", PLY_INT16},
               {"ushort", PLY_UINT16},  {"uint16", PLY_UINT16},
               {"int", PLY_INT32},      {"int32", PLY_INT32},
               {"uint", PLY_UINT32},    {"uint32", PLY_UINT32},
               {"float", PLY_FLOAT32},  {"float32", PLY_FLOAT32},
               {"double", PLY_FLOAT64}, {"float64", PLY_FLOAT64}};
  for (size_t i = 0; i < sizeof names / sizeof *names; i++)
    if (span_is(t, names[i].name)) {
      *out = names[i].type;
      return 0;
    }
  return -1;
}

static int ply_integer_type(ply_type t) {
  return t != PLY_FLOAT32 && t != PLY_FLOAT64;
}

static glint_status ply_property_line(ply_reader *r, size_t line,
                                      const span *tok, size_t ntok,
                                      glint_error *e) {
  char q[48];
  if (r->nelements == 0)
    return gli_fail(e, GLINT_E_PARSE, "%s:%zu: 'property' before any 'element'",
                    r->path, line);
  ply_element *el = &r->elements[r->nelements - 1];
  ply_property p;
  memset(&p, 0, sizeof p);
  p.is_list = ntok >= 2 && span_is(tok[1], "list");
  if (ntok != (p.is_list ? 5u : 3u))
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%zu: expected 'property TYPE NAME' or 'property "
                    "list COUNTTYPE ITEMTYPE NAME'",
                    r->path, line);
  span name = tok[ntok - 1];
  gli_text_quote(p.label, sizeof p.label, name.s, name.n);
  if (p.is_list && ply_parse_type(tok[2], &p.count_type))
    return gli_fail(e, GLINT_E_PARSE, "%s:%zu: unsupported property type '%s'",
                    r->path, line,
                    gli_text_quote(q, sizeof q, tok[2].s, tok[2].n));
  if (ply_parse_type(tok[ntok - 2], &p.type))
    return gli_fail(
        e, GLINT_E_PARSE, "%s:%zu: unsupported property type '%s'", r->path,
        line, gli_text_quote(q, sizeof q, tok[ntok - 2].s, tok[ntok - 2].n));
  if (p.is_list && !ply_integer_type(p.count_type))
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%zu: the count of the list '%s' must have an "
                    "integer type",
                    r->path, line, p.label);
  if (el->kind == 1) {
    static const char *const names[] = {"x", "y", "z", "nx", "ny", "nz"};
    for (int k = 0; k < 6; k++)
      if (span_is(name, names[k]))
        p.role = ROLE_X + k;
  } else if ((el->kind == 2 || el->kind == 3) &&
             (span_is(name, "vertex_indices") || span_is(name, "vertex_index")))
    p.role = ROLE_INDICES;
  if (p.role != ROLE_NONE) {
    for (size_t i = 0; i < el->prop_count; i++)
      if (r->props[el->first_prop + i].role == p.role)
        return gli_fail(e, GLINT_E_PARSE,
                        "%s:%zu: a second '%s' property in the %s element",
                        r->path, line, p.label, el->label);
    if (p.role == ROLE_INDICES && (!p.is_list || !ply_integer_type(p.type)))
      return gli_fail(
          e, GLINT_E_PARSE, "%s:%zu: the %s's '%s' must be a list of integers",
          r->path, line, el->kind == 3 ? "triangle strip" : "face", p.label);
    if (p.role != ROLE_INDICES && p.is_list)
      return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: the vertex's '%s' must be a number, not a "
                      "list",
                      r->path, line, p.label);
  }
  if (GLI_PUSH(r->props, r->nprops, r->props_cap, p))
    return gli_mesh_oom(r->path, e);
  el->prop_count++;
  return GLINT_OK;
}

static glint_status ply_element_line(ply_reader *r, size_t line,
                                     const span *tok, size_t ntok,
                                     glint_error *e) {
  char q[48];
  if (ntok != 3)
    return gli_fail(e, GLINT_E_PARSE, "%s:%zu: expected 'element NAME COUNT'",
                    r->path, line);
  ply_element el;
  memset(&el, 0, sizeof el);
  gli_text_quote(el.label, sizeof el.label, tok[1].s, tok[1].n);
  el.kind = span_is(tok[1], "vertex")      ? 1
            : span_is(tok[1], "face")      ? 2
            : span_is(tok[1], "tristrips") ? 3
                                           : 0;
  const char *s = tok[2].s;
  long long count;
  if (gli_text_parse_whole(&s, tok[2].s + tok[2].n, &count) ||
      s != tok[2].s + tok[2].n || count < 0)
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%zu: expected a count of %s elements, found '%s'",
                    r->path, line, el.label,
                    gli_text_quote(q, sizeof q, tok[2].s, tok[2].n));
  if (el.kind == 1 && (unsigned long long)count > MESH_MAX_ITEMS)
    return gli_fail(e, GLINT_E_PARSE, "%s:%zu: %lld vertices are too many",
                    r->path, line, count);
  el.count = (size_t)count;
  el.first_prop = r->nprops;
  for (size_t i = 0; i < r->nelements; i++)
    if (el.kind && r->elements[i].kind == el.kind)
      return gli_fail(e, GLINT_E_PARSE, "%s:%zu: a second '%s' element",
                      r->path, line, el.label);
  if (el.kind == 1)
    r->vertex_count = el.count;
  if (GLI_PUSH(r->elements, r->nelements, r->elements_cap, el))
    return gli_mesh_oom(r->path, e);
  return GLINT_OK;
}

/* Lines are split into words as ply_header splits them, so a comment that
 * mentions "format ascii" or "end_header" is a comment. */
size_t gli_ply_text_bytes(const char *data, size_t size) {
  for (const char *b = data, *end = data + size; b < end;) {
    const char *cr = memchr(b, '\r', (size_t)(end - b));
    const char *le = cr ? cr : end;
    span tok[2];
    size_t ntok = split(b, le, tok, 2);
    if (ntok >= 1 && span_is(tok[0], "end_header"))
      return cr ? (size_t)(cr - data) + 1 : size;
    if (ntok >= 2 && span_is(tok[0], "format") && span_is(tok[1], "ascii"))
      return size;
    b = cr ? cr + 1 : end;
  }
  return size;
}

/* Reads the header up to and including end_header's newline. */
static glint_status ply_header(ply_reader *r, glint_error *e) {
  const char *data = (const char *)r->data, *end = data + r->size;
  const char *b = data;
  size_t line = 1;
  size_t has_format = 0; /* the format line's number */
  char q[48];
  if (r->size == 0)
    return gli_fail(e, GLINT_E_PARSE, "%s: the file is empty", r->path);
  for (;; line++) {
    if (b >= end)
      return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: the file ends inside the header (no "
                      "'end_header')",
                      r->path, line - 1);
    const char *nl = memchr(b, '\n', (size_t)(end - b));
    const char *le = nl ? nl : end;
    if (line == 1) { /* the magic number, before anything else is trusted */
      const char *t = le; /* trailing blanks and CR aside, as elsewhere */
      while (t > b + 3 && (t[-1] == '\r' || t[-1] == ' ' || t[-1] == '\t'))
        t--;
      if (t - b != 3 || memcmp(b, "ply", 3) != 0)
        return gli_fail(e, GLINT_E_PARSE,
                        "%s:1: not a PLY file (it does not start with a "
                        "'ply' line)",
                        r->path);
      b = nl ? nl + 1 : end;
      continue;
    }
    glint_status st =
        gli_file_check_text(r->path, b, (size_t)(le - b), line, e);
    if (st)
      return st;
    span tok[6];
    size_t ntok = split(b, le, tok, 6);
    b = nl ? nl + 1 : end;
    if (ntok == 0)
      continue;
    if (span_is(tok[0], "comment") || span_is(tok[0], "obj_info"))
      continue;
    if (span_is(tok[0], "end_header")) {
      r->pos = (size_t)(b - data);
      r->line = line + 1;
      break;
    }
    if (span_is(tok[0], "format")) {
      /* one format: a second replaced the first without a word, and its
       * body was then read as the other */
      if (has_format)
        return gli_fail(e, GLINT_E_PARSE,
                        "%s:%zu: a second format line (the first is on line "
                        "%zu): a file has one",
                        r->path, line, has_format);
      if (ntok != 3)
        return gli_fail(e, GLINT_E_PARSE, "%s:%zu: expected 'format TYPE 1.0'",
                        r->path, line);
      if (span_is(tok[1], "ascii"))
        r->format = PLY_ASCII;
      else if (span_is(tok[1], "binary_little_endian"))
        r->format = PLY_LE;
      else if (span_is(tok[1], "binary_big_endian"))
        r->format = PLY_BE;
      else
        return gli_fail(e, GLINT_E_PARSE, "%s:%zu: unsupported PLY format '%s'",
                        r->path, line,
                        gli_text_quote(q, sizeof q, tok[1].s, tok[1].n));
      if (!span_is(tok[2], "1.0"))
        return gli_fail(e, GLINT_E_PARSE,
                        "%s:%zu: unsupported PLY version '%s'", r->path, line,
                        gli_text_quote(q, sizeof q, tok[2].s, tok[2].n));
      has_format = line;
    } else if (span_is(tok[0], "element")) {
      if ((st = ply_element_line(r, line, tok, ntok, e)))
        return st;
    } else if (span_is(tok[0], "property")) {
      if ((st = ply_property_line(r, line, tok, ntok < 6 ? ntok : 6, e)))
        return st;
    } else {
      return gli_fail(e, GLINT_E_PARSE, "%s:%zu: unknown header keyword '%s'",
                      r->path, line,
                      gli_text_quote(q, sizeof q, tok[0].s, tok[0].n));
    }
  }
  if (!has_format)
    return gli_fail(e, GLINT_E_PARSE, "%s: the header has no 'format' line",
                    r->path);
  /* What a mesh needs: vertices with x, y, z, and faces or triangle strips
   * with indices. */
  const ply_element *vertex = NULL;
  int faces = 0;
  for (size_t i = 0; i < r->nelements; i++) {
    const ply_element *el = &r->elements[i];
    if (el->kind == 1)
      vertex = el;
    if (el->kind < 2)
      continue;
    faces = 1;
    int has_indices = 0;
    for (size_t k = 0; k < el->prop_count; k++)
      has_indices |= r->props[el->first_prop + k].role == ROLE_INDICES;
    if (!has_indices)
      return gli_fail(e, GLINT_E_PARSE,
                      "%s: the %s element has no 'vertex_indices' list",
                      r->path, el->label);
  }
  if (!vertex)
    return gli_fail(e, GLINT_E_PARSE, "%s: the header has no 'vertex' element",
                    r->path);
  if (!faces)
    return gli_fail(e, GLINT_E_PARSE,
                    "%s: the header has no 'face' element, nor 'tristrips' (a "
                    "point cloud is not a mesh)",
                    r->path);
  int roles = 0;
  for (size_t i = 0; i < vertex->prop_count; i++)
    roles |= 1 << r->props[vertex->first_prop + i].role;
  for (int k = ROLE_X; k <= ROLE_Z; k++)
    if (!(roles & 1 << k))
      return gli_fail(e, GLINT_E_PARSE,
                      "%s: the vertex element has no '%s' property", r->path,
                      role_what[k] + strlen("the vertex's "));
  int normal_roles = 1 << ROLE_NX | 1 << ROLE_NY | 1 << ROLE_NZ;
  r->m->vertex_normals = (roles & normal_roles) == normal_roles;
  if (r->format == PLY_ASCII)
    return gli_file_check_text(r->path, data + r->pos, r->size - r->pos,
                               r->line, e);
  return GLINT_OK;
}

glint_status gli_ply_parse(const char *path, const char *data, size_t size,
                           mesh_data *m, glint_error *e) {
  ply_reader r;
  memset(&r, 0, sizeof r);
  r.path = path;
  r.data = (const unsigned char *)data;
  r.size = size;
  r.m = m;
  glint_status st = ply_header(&r, e);
  m->where_is_line = r.format == PLY_ASCII;
  for (size_t i = 0; i < r.nelements && !st; i++)
    st = ply_read_element(&r, &r.elements[i], e);
  if (!st)
    st = ply_late_faces(&r, e);
  if (!st && r.format == PLY_ASCII && !ply_ascii_begin(&r)) {
    char q[48];
    size_t len;
    const char *t = ply_token(&r, &len);
    st = gli_fail(e, GLINT_E_PARSE,
                  "%s:%zu: unexpected '%s' after the last element (the "
                  "header's counts are too small)",
                  path, r.line, gli_text_quote(q, sizeof q, t, len));
  }
  /* A binary file may end with a line break or blanks after its last
   * element; anything else there is data the header did not count (a
   * count too small), which would be lost without a word. */
  if (!st && r.format != PLY_ASCII) {
    size_t end = r.pos;
    while (end < r.size && strchr(" \t\r\n", r.data[end]) && r.data[end])
      end++;
    if (end < r.size)
      st = gli_fail(e, GLINT_E_PARSE,
                    "%s: %zu bytes after the last element (the header's "
                    "counts are too small)",
                    path, r.size - r.pos);
  }
  if (!st && m->ntri == 0)
    st = gli_fail(e, GLINT_E_PARSE,
                  "%s: no faces (its faces and strips make no triangle)", path);
  free(r.elements);
  free(r.props);
  free(r.late);
  return st;
}
