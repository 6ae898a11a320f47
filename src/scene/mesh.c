/* Mesh files: Wavefront OBJ and Stanford PLY (ASCII, binary little- and
 * big-endian), each optionally gzip-compressed, loaded as one mesh object.
 *
 * Why a reader of our own and not assimp: errors must say FILE:LINE (assimp
 * gives no line numbers), .gz must be read transparently (assimp cannot) and
 * the 200k-triangle dragon must load fast.
 *
 * The whole file is read into memory first (zlib's gzread passes plain files
 * through unchanged), then parsed into a mesh_data of our own, and only a
 * file that parsed completely is pushed into the scene. That is how a failed
 * load leaves the scene exactly as it was: nothing reaches the scene until
 * the file is known to be good, and the push itself is rolled back if the
 * scene refuses a triangle.
 *
 * OBJ: v (w and the common r g b colour extension ignored), vn, f with the
 * i, i/t, i//n and i/t/n forms (1-based; negative counts back from the last
 * one defined), convex polygons as fans (v0, vi, vi+1), concave ones by ear
 * clipping (polygon.c). A face whose corners all have normals is smooth, any
 * other face flat. Every other statement of the OBJ specification is accepted
 * and ignored; an unknown keyword is an error, because a typo should not
 * silently drop geometry.
 *
 * PLY: the vertex element's x, y, z (and nx, ny, nz, when all three are
 * there, for smooth shading) and the face element's vertex_indices (or
 * vertex_index) list; every other element and property is skipped by its
 * declared type. ASCII bodies are read line by line (one element per line),
 * so a value too many or too few is reported on its own line instead of
 * shifting every later value. */
#include "core/error.h"
#include "core/memory.h"
#include "scene/file.h"
#include "scene/number.h"
#include "scene/polygon.h"
#include "scene/scene.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* The same limit as the text reader: files beyond it are not meshes we
 * could render anyway, and it keeps sizes well inside size_t arithmetic. */
#define MAX_FILE_BYTES ((size_t)4 << 30)
/* A polygon with more corners than this is a damaged list count, not a
 * real face; the limit keeps a garbage count from allocating gigabytes. */
#define MAX_FACE_VERTICES (1 << 20)
/* Vertex and triangle indices are uint32_t in the scene. */
#define MAX_ITEMS ((size_t)UINT32_MAX - 1)
#define NO_INDEX UINT32_MAX

/* ------------------------------------------------------------------------ */
/* What a file holds, before it goes into the scene                          */
/* ------------------------------------------------------------------------ */

typedef struct tri3 {
  uint32_t v[3];
} tri3;

typedef struct corner {
  uint32_t v, n; /* position and normal index; n = NO_INDEX: none */
} corner;

typedef struct mesh_data {
  glint_vec3 *pos;
  size_t npos, pos_cap;
  glint_vec3 *nrm;
  size_t nnrm, nrm_cap;
  tri3 *tri; /* position indices */
  size_t ntri, tri_cap;
  tri3 *tri_nrm; /* OBJ: normal indices, parallel to tri; NO_INDEX: flat */
  size_t tri_nrm_cap;
  int vertex_normals; /* PLY: nrm[i] belongs to pos[i] */
  corner *corners;    /* the face being read */
  size_t ncorners, corners_cap;
} mesh_data;

static void mesh_free(mesh_data *m) {
  free(m->pos);
  free(m->nrm);
  free(m->tri);
  free(m->tri_nrm);
  free(m->corners);
}

static glint_status oom(const char *path, glint_error *e) {
  return gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
}

typedef struct face_emit {
  mesh_data *m;
  int obj, with_normals;
} face_emit;

/* Appends the triangle of the face's corners a, b, c (room is made by the
 * caller). `with_normals` stores the corners' normal indices too (OBJ),
 * else NO_INDEX. */
static int emit_corners(void *user, size_t a, size_t b, size_t c) {
  face_emit *fe = user;
  mesh_data *m = fe->m;
  const corner *k = m->corners;
  m->tri[m->ntri] = (tri3){{k[a].v, k[b].v, k[c].v}};
  if (fe->obj)
    m->tri_nrm[m->ntri] = fe->with_normals
                              ? (tri3){{k[a].n, k[b].n, k[c].n}}
                              : (tri3){{NO_INDEX, NO_INDEX, NO_INDEX}};
  m->ntri++;
  return 0;
}

/* Appends the n - 2 triangles of the face in m->corners: a fan (c0, ci,
 * ci+1) when it is convex, else the ear clipping of polygon.c (a fan of a
 * concave face would cover what is not the face). Returns 0, -1 (out of
 * memory) or GLINT_TRIANGULATE_TOO_COMPLEX. */
static int emit_face(mesh_data *m, int obj, int with_normals) {
  size_t n = m->ncorners, add = n - 2;
  if (gli_grow((void **)&m->tri, &m->tri_cap, m->ntri + add, sizeof(tri3)))
    return -1;
  if (obj && gli_grow((void **)&m->tri_nrm, &m->tri_nrm_cap, m->ntri + add,
                        sizeof(tri3)))
    return -1;
  face_emit fe = {m, obj, with_normals};
  /* Corners not read yet (a PLY whose faces come before its vertices)
   * cannot be checked: a fan. */
  int known = n > 3;
  for (size_t i = 0; known && i < n; i++)
    known = m->corners[i].v < m->npos;
  glint_vec3 small[16], *v = n <= 16 ? small : malloc(n * sizeof *v);
  if (!v)
    return -1;
  for (size_t i = 0; known && i < n; i++)
    v[i] = m->pos[m->corners[i].v];
  if (!known || gli_polygon_is_convex(v, n)) {
    for (size_t i = 1; i + 1 < n; i++)
      emit_corners(&fe, 0, i, i + 1);
    if (v != small)
      free(v);
    return 0;
  }
  int r = gli_triangulate(v, n, emit_corners, &fe);
  if (v != small)
    free(v);
  return r;
}

/* A piece of the file for an error message: at most about 40 bytes, with
 * anything unprintable as '?', so that binary garbage cannot garble it. */
static const char *quote(char *buf, size_t cap, const char *s, size_t len) {
  size_t max = cap - 4, n = len < max ? len : max;
  for (size_t i = 0; i < n; i++) {
    unsigned char ch = (unsigned char)s[i];
    buf[i] = ch >= 0x20 && ch < 0x7f ? (char)ch : '?';
  }
  if (len > n) {
    memcpy(buf + n, "...", 3);
    n += 3;
  }
  buf[n] = '\0';
  return buf;
}

static int is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

/* A whole number: optional sign and 1..18 digits (enough for any index,
 * and no overflow). Advances *s; -1 when there is none. */
static int parse_whole(const char **s, const char *end, long long *out) {
  const char *p = *s;
  int neg = 0;
  if (p < end && (*p == '-' || *p == '+'))
    neg = *p++ == '-';
  const char *digits = p;
  long long v = 0;
  while (p < end && *p >= '0' && *p <= '9') {
    if (p - digits >= 18)
      return -1;
    v = v * 10 + (*p++ - '0');
  }
  if (p == digits)
    return -1;
  *s = p;
  *out = neg ? -v : v;
  return 0;
}

/* ------------------------------------------------------------------------ */
/* OBJ                                                                      */
/* ------------------------------------------------------------------------ */

typedef struct obj_reader {
  const char *path;
  const char *p; /* the data ends with a NUL and holds no other */
  size_t line;
  size_t ntex; /* vt lines: only counted, to check face references */
  mesh_data *m;
} obj_reader;

static int obj_continuation(const char *p) {
  return p[0] == '\\' && (p[1] == '\n' || (p[1] == '\r' && p[2] == '\n'));
}

/* Skips blanks, '\' line continuations and a comment; stops at a newline. */
static void obj_skip_blanks(obj_reader *r) {
  for (;;) {
    if (is_blank(*r->p)) {
      r->p++;
    } else if (obj_continuation(r->p)) {
      r->p += r->p[1] == '\n' ? 2 : 3;
      r->line++;
    } else if (*r->p == '#') {
      while (*r->p && *r->p != '\n')
        r->p++;
      return;
    } else {
      return;
    }
  }
}

/* The next token on this line; length 0 at the end of the line. */
static const char *obj_token(obj_reader *r, size_t *len) {
  obj_skip_blanks(r);
  const char *t = r->p;
  while (*r->p && *r->p != '\n' && *r->p != '#' && !is_blank(*r->p) &&
         !obj_continuation(r->p))
    r->p++;
  *len = (size_t)(r->p - t);
  return t;
}

static int obj_at_eol(obj_reader *r) {
  obj_skip_blanks(r);
  return *r->p == '\0' || *r->p == '\n';
}

static glint_status obj_number(obj_reader *r, const char *what, double *out,
                               glint_error *e) {
  size_t len;
  const char *t = obj_token(r, &len);
  char q[48];
  if (len == 0)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: expected a number for %s, found the end of "
                      "the line",
                      r->path, r->line, what);
  /* The byte after the token is a blank, '#', a newline or the final NUL,
   * none of which continues a number. */
  double v;
  int parsed = number_parse(t, len, &v);
  if (parsed == NUMBER_BAD)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: expected a number for %s, found '%s'", r->path,
                      r->line, what, quote(q, sizeof q, t, len));
  if (parsed == NUMBER_NOT_FINITE)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: %s is '%s', not a finite number", r->path,
                      r->line, what, quote(q, sizeof q, t, len));
  *out = v;
  return GLINT_OK;
}

static glint_status obj_line_end(obj_reader *r, const char *statement,
                                 glint_error *e) {
  if (obj_at_eol(r))
    return GLINT_OK;
  size_t len;
  const char *t = obj_token(r, &len);
  char q[48];
  return gli_fail(e, GLINT_E_PARSE, "%s:%zu: unexpected '%s' after the %s",
                    r->path, r->line, quote(q, sizeof q, t, len), statement);
}

static glint_status obj_vertex(obj_reader *r, glint_error *e) {
  static const char *const names[3] = {"the vertex's x", "the vertex's y",
                                       "the vertex's z"};
  double v[3], extra;
  glint_status st;
  for (int k = 0; k < 3; k++)
    if ((st = obj_number(r, names[k], &v[k], e)))
      return st;
  /* w, or the r g b of the widespread vertex colour extension: read (so
   * that garbage is still caught) and ignored. */
  for (int k = 0; k < 4 && !obj_at_eol(r); k++)
    if ((st = obj_number(r, k == 0 ? "the vertex's w" : "a vertex colour",
                         &extra, e)))
      return st;
  if ((st = obj_line_end(r, "vertex's coordinates", e)))
    return st;
  mesh_data *m = r->m;
  if (m->npos >= MAX_ITEMS)
    return gli_fail(e, GLINT_E_PARSE, "%s:%zu: too many vertices", r->path,
                      r->line);
  if (GLINT_PUSH(m->pos, m->npos, m->pos_cap, ((glint_vec3){v[0], v[1], v[2]})))
    return oom(r->path, e);
  return GLINT_OK;
}

static glint_status obj_normal(obj_reader *r, glint_error *e) {
  static const char *const names[3] = {"the normal's x", "the normal's y",
                                       "the normal's z"};
  double v[3];
  glint_status st;
  for (int k = 0; k < 3; k++)
    if ((st = obj_number(r, names[k], &v[k], e)))
      return st;
  if ((st = obj_line_end(r, "normal", e)))
    return st;
  mesh_data *m = r->m;
  if (m->nnrm >= MAX_ITEMS)
    return gli_fail(e, GLINT_E_PARSE, "%s:%zu: too many normals", r->path,
                      r->line);
  if (GLINT_PUSH(m->nrm, m->nnrm, m->nrm_cap, ((glint_vec3){v[0], v[1], v[2]})))
    return oom(r->path, e);
  return GLINT_OK;
}

/* An OBJ reference to the `what` list of `count` items, as a 0-based index. */
static glint_status obj_resolve(obj_reader *r, const char *what, long long i,
                                size_t count, uint32_t *out, glint_error *e) {
  if (i == 0)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: face refers to %s 0, but OBJ counts from 1",
                      r->path, r->line, what);
  if (i > 0 && (unsigned long long)i <= count) {
    *out = (uint32_t)(i - 1);
    return GLINT_OK;
  }
  if (i < 0 && (unsigned long long)-i <= count) {
    *out = (uint32_t)((long long)count + i);
    return GLINT_OK;
  }
  return gli_fail(e, GLINT_E_PARSE,
                    "%s:%zu: face refers to %s %lld%s, but only %zu %s "
                    "defined",
                    r->path, r->line, what, i,
                    i < 0 ? " (counting back from the last)" : "", count,
                    count == 1 ? "is" : "are");
}

static glint_status obj_face(obj_reader *r, glint_error *e) {
  mesh_data *m = r->m;
  m->ncorners = 0;
  int smooth = 1;
  char q[48];
  for (;;) {
    size_t len;
    const char *t = obj_token(r, &len);
    if (len == 0)
      break;
    const char *s = t, *end = t + len;
    long long vi, ti, ni;
    int has_t = 0, has_n = 0, bad = parse_whole(&s, end, &vi);
    if (!bad && s < end && *s == '/') {
      s++;
      if (s < end && *s != '/') {
        bad = parse_whole(&s, end, &ti);
        has_t = 1;
      }
      if (!bad && s < end && *s == '/') {
        s++;
        bad = parse_whole(&s, end, &ni);
        has_n = 1;
      } else if (!has_t) {
        bad = 1; /* "i/" */
      }
    }
    if (bad || s != end)
      return gli_fail(e, GLINT_E_PARSE,
                        "%s:%zu: bad face vertex '%s' (expected i, i/t, i//n "
                        "or i/t/n)",
                        r->path, r->line, quote(q, sizeof q, t, len));
    corner c = {0, NO_INDEX};
    uint32_t unused;
    glint_status st;
    if ((st = obj_resolve(r, "vertex", vi, m->npos, &c.v, e)) ||
        (has_t && (st = obj_resolve(r, "texture coordinate", ti, r->ntex,
                                    &unused, e))) ||
        (has_n && (st = obj_resolve(r, "normal", ni, m->nnrm, &c.n, e))))
      return st;
    smooth &= has_n;
    if (m->ncorners >= MAX_FACE_VERTICES)
      return gli_fail(e, GLINT_E_PARSE,
                        "%s:%zu: a face with more than %d vertices", r->path,
                        r->line, MAX_FACE_VERTICES);
    if (GLINT_PUSH(m->corners, m->ncorners, m->corners_cap, c))
      return oom(r->path, e);
  }
  if (m->ncorners < 3)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: a face needs at least 3 vertices, found %zu",
                      r->path, r->line, m->ncorners);
  if (m->ntri + m->ncorners - 2 > MAX_ITEMS)
    return gli_fail(e, GLINT_E_PARSE, "%s:%zu: too many triangles", r->path,
                      r->line);
  switch (emit_face(m, 1, smooth)) {
  case 0: return GLINT_OK;
  case GLINT_TRIANGULATE_TOO_COMPLEX:
    return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: the face of %zu vertices has too many inward "
                      "corners to triangulate",
                      r->path, r->line, m->ncorners);
  default: return oom(r->path, e);
  }
}

/* Statements of the OBJ specification that glint has no use for: texture
 * coordinates, free-form geometry, points and lines, grouping, display and
 * render attributes. They are skipped whole. */
static int obj_ignored(const char *kw, size_t len) {
  static const char *const known[] = {
      "vt",       "vp",    "cstype", "deg",    "bmat",       "step",
      "p",        "l",     "curv",   "curv2",  "surf",       "parm",
      "trim",     "hole",  "scrv",   "sp",     "end",        "con",
      "g",        "s",     "mg",     "o",      "bevel",      "c_interp",
      "d_interp", "lod",   "usemtl", "mtllib", "shadow_obj", "trace_obj",
      "ctech",    "stech", "maplib", "usemap", "call",       "csh"};
  for (size_t i = 0; i < sizeof known / sizeof *known; i++)
    if (strlen(known[i]) == len && memcmp(known[i], kw, len) == 0)
      return 1;
  return 0;
}

static glint_status obj_parse(const char *path, const char *data, size_t size,
                              mesh_data *m, glint_error *e) {
  glint_status st = file_check_text(path, data, size, 1, e);
  if (st)
    return st;
  obj_reader r = {path, data, 1, 0, m};
  /* Some Windows exporters start the file with a UTF-8 byte order mark. */
  if (size >= 3 && memcmp(data, "\xef\xbb\xbf", 3) == 0)
    r.p += 3;
  char q[48];
  while (*r.p) {
    size_t len;
    const char *kw = obj_token(&r, &len);
    if (len == 1 && kw[0] == 'v')
      st = obj_vertex(&r, e);
    else if (len == 2 && kw[0] == 'v' && kw[1] == 'n')
      st = obj_normal(&r, e);
    else if (len == 1 && kw[0] == 'f')
      st = obj_face(&r, e);
    else if (len == 0 || obj_ignored(kw, len)) {
      r.ntex += len == 2 && kw[0] == 'v' && kw[1] == 't';
      while (!obj_at_eol(&r))
        obj_token(&r, &len);
    } else
      st = gli_fail(e, GLINT_E_PARSE, "%s:%zu: unknown keyword '%s'", path,
                      r.line, quote(q, sizeof q, kw, len));
    if (st)
      return st;
    if (*r.p == '\n') {
      r.p++;
      r.line++;
    }
  }
  if (size == 0)
    return gli_fail(e, GLINT_E_PARSE, "%s: the file is empty", path);
  if (m->ntri == 0)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s: no faces (the file has %zu vertices and no 'f' "
                      "statement)",
                      path, m->npos);
  return GLINT_OK;
}

/* ------------------------------------------------------------------------ */
/* PLY                                                                      */
/* ------------------------------------------------------------------------ */

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
  int kind; /* 0, or 1 for "vertex", 2 for "face" */
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
} ply_reader;

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
  snprintf(buf, cap, "'%s' elements", el->label);
  return buf;
}

static glint_status ply_truncated(const ply_reader *r, glint_error *e) {
  char w[1100], pl[64];
  if (r->format == PLY_ASCII)
    snprintf(w, sizeof w, "%s:%zu", r->path, r->line);
  else
    snprintf(w, sizeof w, "%s", r->path);
  return gli_fail(e, GLINT_E_PARSE, "%s: the file ends after %zu of %zu %s",
                    w, r->index, r->el->count,
                    ply_plural(r->el, pl, sizeof pl));
}

/* --- values: ASCII tokens or binary bytes ------------------------------- */

/* ASCII: the next token on the current line; length 0 at its end. */
static const char *ply_token(ply_reader *r, size_t *len) {
  const char *p = (const char *)r->data + r->pos;
  while (is_blank(*p))
    p++;
  const char *t = p;
  while (*p && *p != '\n' && !is_blank(*p))
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

/* The next value as a finite number: a vertex coordinate. */
static glint_status ply_number(ply_reader *r, const ply_property *p,
                               double *out, glint_error *e) {
  char w[1100], q[48];
  ply_type type = p->type;
  const char *what = role_what[p->role];
  if (r->format != PLY_ASCII) {
    if (r->size - r->pos < ply_size[type])
      return ply_truncated(r, e);
    double v = ply_binary_value(r, type);
    if (!isfinite(v))
      return gli_fail(e, GLINT_E_PARSE, "%s: %s is %g, not a finite number",
                        ply_where(r, w, sizeof w), what, v);
    *out = v;
    return GLINT_OK;
  }
  size_t len;
  const char *t = ply_token(r, &len);
  if (len == 0)
    return ply_missing(r, p, 0, e);
  double v;
  int parsed = number_parse(t, len, &v);
  if (parsed == NUMBER_BAD)
    return gli_fail(
        e, GLINT_E_PARSE, "%s: expected a number for %s, found '%s'",
        ply_where(r, w, sizeof w), what, quote(q, sizeof q, t, len));
  if (parsed == NUMBER_NOT_FINITE)
    return gli_fail(e, GLINT_E_PARSE, "%s: %s is '%s', not a finite number",
                      ply_where(r, w, sizeof w), what,
                      quote(q, sizeof q, t, len));
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
  if (parse_whole(&s, t + len, out) || s != t + len) {
    char w[1100], q[48], what[128];
    return gli_fail(
        e, GLINT_E_PARSE, "%s: expected a whole number for %s, found '%s'",
        ply_where(r, w, sizeof w), ply_what(r, p, count, what, sizeof what),
        quote(q, sizeof q, t, len));
  }
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

static glint_status ply_face(ply_reader *r, const ply_property *p, long long n,
                             glint_error *e) {
  char w[1100];
  mesh_data *m = r->m;
  if (n < 3)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s: a face needs at least 3 vertices, found %lld",
                      ply_where(r, w, sizeof w), n);
  if (n > MAX_FACE_VERTICES)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s: a face with %lld vertices (at most %d; the list "
                      "count is probably damaged)",
                      ply_where(r, w, sizeof w), n, MAX_FACE_VERTICES);
  if (r->format != PLY_ASCII &&
      (unsigned long long)n > (r->size - r->pos) / ply_size[p->type])
    return ply_truncated(r, e);
  if (m->ntri + (size_t)n - 2 > MAX_ITEMS)
    return gli_fail(e, GLINT_E_PARSE, "%s: too many triangles",
                      ply_where(r, w, sizeof w));
  if (gli_grow((void **)&m->corners, &m->corners_cap, (size_t)n,
                 sizeof *m->corners))
    return oom(r->path, e);
  m->ncorners = (size_t)n;
  for (long long k = 0; k < n; k++) {
    long long v;
    glint_status st = ply_whole(r, p, 0, &v, e);
    if (st)
      return st;
    if (v < 0 || (unsigned long long)v >= r->vertex_count)
      return gli_fail(e, GLINT_E_PARSE,
                        "%s: face refers to vertex %lld, but only %zu %s "
                        "defined",
                        ply_where(r, w, sizeof w), v, r->vertex_count,
                        r->vertex_count == 1 ? "is" : "are");
    m->corners[k] = (corner){(uint32_t)v, NO_INDEX};
  }
  switch (emit_face(m, 0, 0)) {
  case 0: return GLINT_OK;
  case GLINT_TRIANGULATE_TOO_COMPLEX:
    return gli_fail(e, GLINT_E_PARSE,
                      "%s: the face of %zu vertices has too many inward "
                      "corners to triangulate",
                      ply_where(r, w, sizeof w), m->ncorners);
  default: return oom(r->path, e);
  }
}

/* ASCII: moves to the next non-blank line; 1 at the end of the file. */
static int ply_ascii_begin(ply_reader *r) {
  const char *p = (const char *)r->data + r->pos;
  for (;;) {
    while (is_blank(*p))
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
                      ply_where(r, w, sizeof w), quote(q, sizeof q, t, len),
                      r->el->prop_count, r->el->label);
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
  if (r->format == PLY_ASCII && ply_ascii_begin(r))
    return ply_truncated(r, e);
  for (size_t i = 0; i < el->prop_count && !st; i++) {
    const ply_property *p = &r->props[el->first_prop + i];
    if (!p->is_list) {
      if (p->role >= ROLE_X && p->role <= ROLE_NZ)
        st = ply_number(r, p, &v[p->role - ROLE_X], e);
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
      st = ply_face(r, p, n, e);
    else
      st = ply_skip(r, p, n, e);
  }
  if (!st && r->format == PLY_ASCII)
    st = ply_ascii_end(r, e);
  if (st || el->kind != 1)
    return st;
  mesh_data *m = r->m;
  if (GLINT_PUSH(m->pos, m->npos, m->pos_cap, ((glint_vec3){v[0], v[1], v[2]})))
    return oom(r->path, e);
  if (m->vertex_normals &&
      GLINT_PUSH(m->nrm, m->nnrm, m->nrm_cap, ((glint_vec3){v[3], v[4], v[5]})))
    return oom(r->path, e);
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
      return oom(r->path, e);
  } else if (el->kind == 2) {
    size_t want = el->count < left / 4 + 1 ? el->count : left / 4 + 1;
    if (gli_grow((void **)&m->tri, &m->tri_cap, m->ntri + want,
                   sizeof *m->tri))
      return oom(r->path, e);
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
    while (b < end && is_blank(*b))
      b++;
    if (b == end)
      break;
    const char *s = b;
    while (b < end && !is_blank(*b))
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
    return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: 'property' before any 'element'", r->path, line);
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
  quote(p.label, sizeof p.label, name.s, name.n);
  if (p.is_list && ply_parse_type(tok[2], &p.count_type))
    return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: unsupported property type '%s'", r->path, line,
                      quote(q, sizeof q, tok[2].s, tok[2].n));
  if (ply_parse_type(tok[ntok - 2], &p.type))
    return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: unsupported property type '%s'", r->path, line,
                      quote(q, sizeof q, tok[ntok - 2].s, tok[ntok - 2].n));
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
  } else if (el->kind == 2 &&
             (span_is(name, "vertex_indices") || span_is(name, "vertex_index")))
    p.role = ROLE_INDICES;
  if (p.role != ROLE_NONE) {
    for (size_t i = 0; i < el->prop_count; i++)
      if (r->props[el->first_prop + i].role == p.role)
        return gli_fail(e, GLINT_E_PARSE,
                          "%s:%zu: a second '%s' property in the %s element",
                          r->path, line, p.label, el->label);
    if (p.role == ROLE_INDICES && (!p.is_list || !ply_integer_type(p.type)))
      return gli_fail(e, GLINT_E_PARSE,
                        "%s:%zu: the face's '%s' must be a list of integers",
                        r->path, line, p.label);
    if (p.role != ROLE_INDICES && p.is_list)
      return gli_fail(e, GLINT_E_PARSE,
                        "%s:%zu: the vertex's '%s' must be a number, not a "
                        "list",
                        r->path, line, p.label);
  }
  if (GLINT_PUSH(r->props, r->nprops, r->props_cap, p))
    return oom(r->path, e);
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
  quote(el.label, sizeof el.label, tok[1].s, tok[1].n);
  el.kind = span_is(tok[1], "vertex") ? 1 : span_is(tok[1], "face") ? 2 : 0;
  const char *s = tok[2].s;
  long long count;
  if (parse_whole(&s, tok[2].s + tok[2].n, &count) ||
      s != tok[2].s + tok[2].n || count < 0)
    return gli_fail(
        e, GLINT_E_PARSE, "%s:%zu: expected a count of %s elements, found '%s'",
        r->path, line, el.label, quote(q, sizeof q, tok[2].s, tok[2].n));
  if (el.kind == 1 && (unsigned long long)count > MAX_ITEMS)
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
  if (GLINT_PUSH(r->elements, r->nelements, r->elements_cap, el))
    return oom(r->path, e);
  return GLINT_OK;
}

/* Reads the header up to and including end_header's newline. */
static glint_status ply_header(ply_reader *r, glint_error *e) {
  const char *data = (const char *)r->data, *end = data + r->size;
  const char *b = data;
  size_t line = 1;
  int has_format = 0;
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
      const char *t = le;
      if (t > b && t[-1] == '\r')
        t--;
      if (t - b != 3 || memcmp(b, "ply", 3) != 0)
        return gli_fail(e, GLINT_E_PARSE,
                          "%s:1: not a PLY file (it does not start with a "
                          "'ply' line)",
                          r->path);
      b = nl ? nl + 1 : end;
      continue;
    }
    glint_status st = file_check_text(r->path, b, (size_t)(le - b), line, e);
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
      if (ntok != 3)
        return gli_fail(e, GLINT_E_PARSE,
                          "%s:%zu: expected 'format TYPE 1.0'", r->path, line);
      if (span_is(tok[1], "ascii"))
        r->format = PLY_ASCII;
      else if (span_is(tok[1], "binary_little_endian"))
        r->format = PLY_LE;
      else if (span_is(tok[1], "binary_big_endian"))
        r->format = PLY_BE;
      else
        return gli_fail(e, GLINT_E_PARSE,
                          "%s:%zu: unsupported PLY format '%s'", r->path, line,
                          quote(q, sizeof q, tok[1].s, tok[1].n));
      if (!span_is(tok[2], "1.0"))
        return gli_fail(e, GLINT_E_PARSE,
                          "%s:%zu: unsupported PLY version '%s'", r->path, line,
                          quote(q, sizeof q, tok[2].s, tok[2].n));
      has_format = 1;
    } else if (span_is(tok[0], "element")) {
      if ((st = ply_element_line(r, line, tok, ntok, e)))
        return st;
    } else if (span_is(tok[0], "property")) {
      if ((st = ply_property_line(r, line, tok, ntok < 6 ? ntok : 6, e)))
        return st;
    } else {
      return gli_fail(e, GLINT_E_PARSE, "%s:%zu: unknown header keyword '%s'",
                        r->path, line, quote(q, sizeof q, tok[0].s, tok[0].n));
    }
  }
  if (!has_format)
    return gli_fail(e, GLINT_E_PARSE, "%s: the header has no 'format' line",
                      r->path);
  /* What a mesh needs: vertices with x, y, z and faces with indices. */
  const ply_element *vertex = NULL, *face = NULL;
  for (size_t i = 0; i < r->nelements; i++) {
    if (r->elements[i].kind == 1)
      vertex = &r->elements[i];
    if (r->elements[i].kind == 2)
      face = &r->elements[i];
  }
  if (!vertex)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s: the header has no 'vertex' element", r->path);
  if (!face)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s: the header has no 'face' element (a point cloud is "
                      "not a mesh)",
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
  int has_indices = 0;
  for (size_t i = 0; i < face->prop_count; i++)
    has_indices |= r->props[face->first_prop + i].role == ROLE_INDICES;
  if (!has_indices)
    return gli_fail(e, GLINT_E_PARSE,
                      "%s: the face element has no 'vertex_indices' list",
                      r->path);
  if (r->format == PLY_ASCII)
    return file_check_text(r->path, data + r->pos, r->size - r->pos, r->line,
                           e);
  return GLINT_OK;
}

static glint_status ply_parse(const char *path, const char *data, size_t size,
                              mesh_data *m, glint_error *e) {
  ply_reader r;
  memset(&r, 0, sizeof r);
  r.path = path;
  r.data = (const unsigned char *)data;
  r.size = size;
  r.m = m;
  glint_status st = ply_header(&r, e);
  for (size_t i = 0; i < r.nelements && !st; i++)
    st = ply_read_element(&r, &r.elements[i], e);
  if (!st && r.format == PLY_ASCII && !ply_ascii_begin(&r)) {
    char q[48];
    size_t len;
    const char *t = ply_token(&r, &len);
    st = gli_fail(e, GLINT_E_PARSE,
                    "%s:%zu: unexpected '%s' after the last element (the "
                    "header's counts are too small)",
                    path, r.line, quote(q, sizeof q, t, len));
  }
  /* Binary files may carry padding after the last element: ignored. */
  if (!st && m->ntri == 0)
    st = gli_fail(e, GLINT_E_PARSE,
                    "%s: no faces (the face element is "
                    "empty)",
                    path);
  free(r.elements);
  free(r.props);
  return st;
}

/* ------------------------------------------------------------------------ */
/* Into the scene                                                           */
/* ------------------------------------------------------------------------ */

static glint_status add_to_scene(glint_scene *s, const char *path, mesh_data *m,
                                 double scale, glint_vec3 tr, uint32_t material,
                                 glint_error *e) {
  for (size_t i = 0; i < m->npos; i++) {
    glint_vec3 *p = &m->pos[i];
    *p = (glint_vec3){p->x * scale + tr.x, p->y * scale + tr.y,
                      p->z * scale + tr.z};
  }
  size_t obj0 = s->object_count, tri0 = s->triangle_count,
         nrm0 = s->tri_normal_count;
  glint_status st =
      gli_scene_begin_object(s, GLINT_SHAPE_TRIANGLE, material, e);
  if (st)
    goto fail;
  /* One allocation up front instead of a doubling per power of two. */
  size_t smooth = 0;
  for (size_t i = 0; i < m->ntri; i++)
    smooth +=
        m->vertex_normals || (m->tri_nrm && m->tri_nrm[i].v[0] != NO_INDEX);
  if (gli_grow((void **)&s->triangles, &s->triangle_cap, tri0 + m->ntri,
                 sizeof *s->triangles) ||
      (smooth && gli_grow((void **)&s->tri_normals, &s->tri_normal_cap,
                            nrm0 + 3 * smooth, sizeof *s->tri_normals))) {
    st = oom(path, e);
    goto fail;
  }
  for (size_t i = 0; i < m->ntri; i++) {
    const uint32_t *v = m->tri[i].v;
    glint_vec3 n[3];
    const glint_vec3 *normals = NULL;
    if (m->vertex_normals) {
      for (int k = 0; k < 3; k++)
        n[k] = m->nrm[v[k]];
      normals = n;
    } else if (m->tri_nrm && m->tri_nrm[i].v[0] != NO_INDEX) {
      for (int k = 0; k < 3; k++)
        n[k] = m->nrm[m->tri_nrm[i].v[k]];
      normals = n;
    }
    st = gli_scene_push_triangle(s, m->pos[v[0]], m->pos[v[1]], m->pos[v[2]],
                                   normals, e);
    if (st) {
      /* Only scaling can make a finite file's coordinates infinite. */
      char msg[sizeof e->message];
      snprintf(msg, sizeof msg, "%s", e ? e->message : "");
      st = gli_fail(e, st, "%s: triangle %zu, scaled by %g: %s", path, i,
                      scale, msg);
      goto fail;
    }
  }
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

enum { MESH_UNKNOWN, MESH_OBJ, MESH_PLY };

/* By the extension, after an optional .gz. */
static int mesh_kind(const char *path) {
  const char *slash = strrchr(path, '/');
  const char *base = slash ? slash + 1 : path;
  size_t n = strlen(base);
  if (n > 3 && strcasecmp(base + n - 3, ".gz") == 0)
    n -= 3;
  if (n > 4 && strncasecmp(base + n - 4, ".obj", 4) == 0)
    return MESH_OBJ;
  if (n > 4 && strncasecmp(base + n - 4, ".ply", 4) == 0)
    return MESH_PLY;
  return MESH_UNKNOWN;
}

glint_status glint_scene_add_mesh_file(glint_scene *scene, const char *path,
                                       double scale, glint_vec3 translate,
                                       uint32_t material_id,
                                       glint_error *error) {
  if (!scene || !path)
    return gli_fail(error, GLINT_E_ARGUMENT, "mesh file: missing argument");
  /* Checked before reading so that a bad call costs no parse. A negative
   * scale would mirror the mesh and turn its faces inside out. */
  if (!isfinite(scale) || !(scale > 0))
    return gli_fail(error, GLINT_E_ARGUMENT,
                      "%s: scale %g must be a finite number > 0", path, scale);
  if (!gli_vec3_finite(translate))
    return gli_fail(error, GLINT_E_ARGUMENT,
                      "%s: the translation must be finite", path);
  if (material_id >= scene->material_count)
    return gli_fail(error, GLINT_E_ARGUMENT,
                      "%s: material %u does not exist (the scene has %zu)",
                      path, material_id, scene->material_count);
  int kind = mesh_kind(path);
  if (kind == MESH_UNKNOWN)
    return gli_fail(error, GLINT_E_ARGUMENT,
                      "%s: not a mesh file (.obj or .ply, optionally .gz)",
                      path);
  char *data = NULL;
  size_t size = 0;
  glint_status st = file_read_all(path, MAX_FILE_BYTES, &data, &size, error);
  if (st)
    return st;
  /* Numbers in mesh files always use '.', whatever LC_NUMERIC the host
   * program chose; uselocale changes this thread only, and only for now. */
  number_locale locale = number_locale_begin();
  mesh_data m;
  memset(&m, 0, sizeof m);
  st = kind == MESH_OBJ ? obj_parse(path, data, size, &m, error)
                        : ply_parse(path, data, size, &m, error);
  number_locale_end(locale);
  free(data);
  if (!st)
    st = add_to_scene(scene, path, &m, scale, translate, material_id, error);
  mesh_free(&m);
  return st;
}
