/* Wavefront OBJ meshes: v (w and the common r g b colour extension
 * ignored), vn, f with the i, i/t, i//n and i/t/n forms (1-based; negative
 * counts back from the last one defined), convex polygons as fans (v0, vi,
 * vi+1), concave ones by ear clipping (scene/polygon.c). A face whose
 * corners all have normals is smooth, any other face flat. Every other
 * statement of the OBJ specification is accepted and ignored; an unknown
 * keyword is an error, because a typo should not silently drop geometry. */
#include "core/error.h"
#include "scene/mesh.h"
#include "scene/number.h"
#include "core/memory.h"
#include "scene/file.h"
#include "scene/polygon.h"
#include "scene/text.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct obj_reader {
  const char *path;
  const char *p; /* the data ends with a NUL and holds no other */
  size_t line;
  size_t ntex; /* vt lines: only counted, to check face references */
  mesh_data *m;
} obj_reader;

/* A '\\' that ends its line, or the file (which joins no next line). */
static int obj_continuation(const char *p) {
  return p[0] == '\\' &&
         (p[1] == '\n' || p[1] == '\0' || (p[1] == '\r' && p[2] == '\n'));
}

/* Skips blanks, '\' line continuations and a comment; stops at a newline. */
static void obj_skip_blanks(obj_reader *r) {
  for (;;) {
    if (gli_text_is_blank(*r->p)) {
      r->p++;
    } else if (obj_continuation(r->p)) {
      r->p += r->p[1] == '\r' ? 3 : r->p[1] ? 2 : 1;
      /* a continuation at the file's end joins no next line */
      if (*r->p)
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
  while (*r->p && *r->p != '\n' && *r->p != '#' && !gli_text_is_blank(*r->p) &&
         !obj_continuation(r->p))
    r->p++;
  *len = (size_t)(r->p - t);
  return t;
}

static int obj_at_eol(obj_reader *r) {
  obj_skip_blanks(r);
  return *r->p == '\0' || *r->p == '\n';
}

/* The next number. One that is not finite fails, or, where `nonfinite` is
 * given, reads as NaN with its message there (a vertex's coordinate: see
 * mesh_data.nonfinite_pos). */
static glint_status obj_number(obj_reader *r, const char *what, double *out,
                               glint_error *nonfinite, glint_error *e) {
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
  int parsed = gli_number_parse(t, len, &v);
  if (parsed == NUMBER_BAD)
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%zu: expected a number for %s, found '%s'", r->path,
                    r->line, what, gli_text_quote(q, sizeof q, t, len));
  if (parsed == NUMBER_NOT_FINITE) {
    glint_status st =
        gli_fail(nonfinite ? nonfinite : e, GLINT_E_PARSE,
                 "%s:%zu: %s is '%s', not a finite number", r->path, r->line,
                 what, gli_text_quote(q, sizeof q, t, len));
    *out = NAN;
    return nonfinite ? GLINT_OK : st;
  }
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
                  r->path, r->line, gli_text_quote(q, sizeof q, t, len),
                  statement);
}

/* x, y and z of a v or vn line, named in errors by `names`; the first
 * that is not finite is told in *nonfinite (its status set), the others
 * read as NaN too. */
static glint_status obj_xyz(obj_reader *r, const char *const names[3],
                            glint_vec3 *out, glint_error *nonfinite,
                            glint_error *e) {
  double v[3];
  glint_status st;
  nonfinite->status = GLINT_OK;
  for (int k = 0; k < 3; k++) {
    /* the first one's message, written where it goes; later ones into
     * `later` (no 1 KiB copy or clearing a number: this is every vertex) */
    glint_error later;
    glint_error *here = nonfinite->status ? &later : nonfinite;
    if ((st = obj_number(r, names[k], &v[k], here, e)))
      return st;
  }
  *out = (glint_vec3){v[0], v[1], v[2]};
  return GLINT_OK;
}

/* Appends v to the mesh's positions or normals (`what` names them). */
static glint_status obj_append(obj_reader *r, const char *what,
                               glint_vec3 **list, size_t *count, size_t *cap,
                               glint_vec3 v, glint_error *e) {
  if (*count >= MESH_MAX_ITEMS)
    return gli_fail(e, GLINT_E_PARSE, "%s:%zu: too many %s", r->path, r->line,
                    what);
  if (GLI_PUSH(*list, *count, *cap, v))
    return gli_mesh_oom(r->path, e);
  return GLINT_OK;
}

static glint_status obj_vertex(obj_reader *r, glint_error *e) {
  static const char *const names[3] = {"the vertex's x", "the vertex's y",
                                       "the vertex's z"};
  glint_vec3 v;
  double extra;
  glint_status st;
  glint_error nonfinite;
  if ((st = obj_xyz(r, names, &v, &nonfinite, e)))
    return st;
  /* w, or the r g b of the widespread vertex colour extension: read (so
   * that garbage is still caught) and ignored. */
  for (int k = 0; k < 4 && !obj_at_eol(r); k++)
    if ((st = obj_number(r, k == 0 ? "the vertex's w" : "a vertex colour",
                         &extra, NULL, e)))
      return st;
  if ((st = obj_line_end(r, "vertex's coordinates", e)))
    return st;
  mesh_data *m = r->m;
  if (nonfinite.status)
    gli_mesh_nonfinite(&m->nonfinite_pos, m->npos, &nonfinite);
  return obj_append(r, "vertices", &m->pos, &m->npos, &m->pos_cap, v, e);
}

static glint_status obj_normal(obj_reader *r, glint_error *e) {
  static const char *const names[3] = {"the normal's x", "the normal's y",
                                       "the normal's z"};
  glint_vec3 v;
  glint_status st;
  glint_error nonfinite;
  if ((st = obj_xyz(r, names, &v, &nonfinite, e)) ||
      (st = obj_line_end(r, "normal", e)))
    return st;
  mesh_data *m = r->m;
  if (nonfinite.status)
    gli_mesh_nonfinite(&m->nonfinite_nrm, m->nnrm, &nonfinite);
  return obj_append(r, "normals", &m->nrm, &m->nnrm, &m->nrm_cap, v, e);
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
    int has_t = 0, has_n = 0, bad = gli_text_parse_whole(&s, end, &vi);
    if (!bad && s < end && *s == '/') {
      s++;
      if (s < end && *s != '/') {
        bad = gli_text_parse_whole(&s, end, &ti);
        has_t = 1;
      }
      if (!bad && s < end && *s == '/') {
        s++;
        bad = gli_text_parse_whole(&s, end, &ni);
        has_n = 1;
      } else if (!has_t) {
        bad = 1; /* "i/" */
      }
    }
    if (bad == GLI_TEXT_TOO_LONG)
      return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: face vertex '%s': an index of more than 18 "
                      "digits, beyond any list",
                      r->path, r->line, gli_text_quote(q, sizeof q, t, len));
    if (bad || s != end)
      return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: bad face vertex '%s' (expected i, i/t, i//n "
                      "or i/t/n)",
                      r->path, r->line, gli_text_quote(q, sizeof q, t, len));
    corner c = {0, MESH_NO_INDEX};
    uint32_t unused;
    glint_status st;
    if ((st = obj_resolve(r, "vertex", vi, m->npos, &c.v, e)) ||
        (has_t && (st = obj_resolve(r, "texture coordinate", ti, r->ntex,
                                    &unused, e))) ||
        (has_n && (st = obj_resolve(r, "normal", ni, m->nnrm, &c.n, e))))
      return st;
    smooth &= has_n;
    if (m->ncorners >= MESH_MAX_FACE_VERTICES)
      return gli_fail(e, GLINT_E_PARSE,
                      "%s:%zu: a face with more than %d vertices", r->path,
                      r->line, MESH_MAX_FACE_VERTICES);
    if (GLI_PUSH(m->corners, m->ncorners, m->corners_cap, c))
      return gli_mesh_oom(r->path, e);
  }
  if (m->ncorners < 3)
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%zu: a face needs at least 3 vertices, found %zu",
                    r->path, r->line, m->ncorners);
  if (m->ntri + m->ncorners - 2 > MESH_MAX_ITEMS)
    return gli_fail(e, GLINT_E_PARSE, "%s:%zu: too many triangles", r->path,
                    r->line);
  m->face_where = r->line < UINT32_MAX ? (uint32_t)r->line : UINT32_MAX;
  switch (gli_mesh_emit_face(m, 1, smooth)) {
  case 0: return GLINT_OK;
  case GLI_TRIANGULATE_TOO_COMPLEX:
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%zu: the face of %zu vertices has too many inward "
                    "corners to triangulate (" GLI_EAR_LIMIT_TEXT ")",
                    r->path, r->line, m->ncorners);
  default: return gli_mesh_oom(r->path, e);
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

glint_status gli_obj_parse(const char *path, const char *data, size_t size,
                           mesh_data *m, glint_error *e) {
  glint_status st = gli_file_check_text(path, data, size, 1, e);
  if (st)
    return st;
  obj_reader r = {path, data, 1, 0, m};
  m->where_is_line = 1;
  m->first_index = 1;
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
                    r.line, gli_text_quote(q, sizeof q, kw, len));
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
