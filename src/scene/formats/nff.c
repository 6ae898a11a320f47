/* Eric Haines's Neutral File Format (the NFF description that comes with his
 * Standard Procedural Databases), the SPD scenes' format. Every entity is read:
 *
 *   v   from/at/up/angle/hither/resolution: the camera. NFF's angle spans the
 *       centres of the outer pixel columns; glint's field of view spans the
 *       outer edges, so fov = 2 atan(tan(angle/2) xres / (xres - 1)).
 *       hither is read and ignored (every hit beyond epsilon counts).
 *   b   background colour.
 *   l   a point light, with an optional colour. NFF leaves the intensity of
 *       uncoloured lights open; glint gives each 1/sqrt(number of lights),
 *       the rule Haines suggests so that scenes with many lights are not
 *       washed out. A given colour is used as it is.
 *   f   a material: r g b Kd Ks Shine T ior, mapped onto
 *       docs/specification.md §4 as C = (r, g, b), ka = 0.1 (as Tachyon),
 *       kd = Kd, ks = kr = Ks, h = Shine, kt = T, ior; no absorption.
 *   c   an open cylinder or cone (no end caps).
 *   s   a sphere.
 *   p   a polygon, one object, triangulated by scene/polygon.c (NFF says
 *       convex, but SPD's gears have concave faces: ear clipping down to
 *       a convex rest, then well-shaped triangles by recursive bisection).
 *   pp  a polygonal patch: the same, with vertex normals, shaded smooth.
 *   #   a comment to the end of the line.
 *
 * NFF's negative radii (only the inside visible) are read as their
 * magnitude: glint shows both sides of every surface. */
#include "core/error.h"
#include "scene/file.h"
#include "scene/number.h"
#include "scene/polygon.h"
#include "scene/scene.h"
#include "scene/text.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_POLYGON_VERTICES 1000000

typedef struct nff_reader {
  text_file t;
  glint_scene *scene;
  int has_material;
  uint32_t material;
  size_t uncoloured_lights;
  glint_vec3 *verts, *norms;
  size_t vert_cap;
  /* The last polygon's first vertex line that holds too many numbers or
   * too few (0: none): NFF is read word by word, so a vertex may run over
   * lines, but a file that fails after such a line most likely went wrong
   * there, and is told so. */
  struct {
    long line, polygon_line;
    int too_many, patch;
    long vertex, count;
  } odd;
  /* The lines of the view and the background colour (0: none yet): a file
   * has one of each, and a second would silently replace the first. */
  long view_line, background_line;
} nff_reader;

/* A second view or background colour, at `line`. */
static glint_status second(const nff_reader *r, const char *what, long line,
                           long first, glint_error *e) {
  return gli_fail(e, GLINT_E_PARSE,
                  "%s:%ld: a second %s (the first is on line %ld): a file "
                  "has one",
                  r->t.path, line, what, first);
}

/* The error about the last polygon's odd line (see nff_reader.odd). */
static glint_status odd_vertex_line(const nff_reader *r, glint_error *e) {
  return gli_fail(e, GLINT_E_PARSE,
                  "%s:%ld: %s numbers on the line than a %s vertex takes "
                  "(vertex %ld of %ld of the %s on line %ld)",
                  r->t.path, r->odd.line, r->odd.too_many ? "more" : "fewer",
                  r->odd.patch ? "patch" : "polygon", r->odd.vertex,
                  r->odd.count, r->odd.patch ? "patch" : "polygon",
                  r->odd.polygon_line);
}

/* Whether the token that a number read just failed at was a word (or the
 * file's end), as when vertices and lines have gone out of step; not a
 * number that is not finite, which is its own error. */
static int failed_at_word(const text_file *t) {
  const char *end = t->pos, *start = end;
  while (start > t->data && !isspace((unsigned char)start[-1]))
    start--;
  double unused;
  return start == end ||
         gli_number_parse(start, (size_t)(end - start), &unused) == NUMBER_BAD;
}

static glint_status expect_word(nff_reader *r, const char *word,
                                glint_error *e) {
  char buf[64];
  long last = r->t.token_line; /* the statement the file's end cuts short */
  const char *tok = gli_text_token(&r->t, buf, sizeof buf);
  if (!tok)
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%ld: the file ends where '%s' was expected", r->t.path,
                    last > 0 ? last : r->t.line, word);
  char q[48];
  if (strcmp(tok, word) != 0)
    return gli_fail(e, GLINT_E_PARSE, "%s:%ld: expected '%s', found '%s'",
                    r->t.path, r->t.token_line, word,
                    gli_text_quote(q, sizeof q, tok, strlen(tok)));
  return GLINT_OK;
}

/* A library error about an entity, placed at the entity's line. A value
 * the library refuses is, coming from a file, malformed content. */
static glint_status at_line(nff_reader *r, long line, glint_status st,
                            glint_error *e) {
  if (st == GLINT_E_ARGUMENT)
    st = GLINT_E_PARSE;
  if (st && e) {
    char msg[sizeof e->message];
    snprintf(msg, sizeof msg, "%.900s", e->message);
    gli_fail(e, st, "%s:%ld: %s", r->t.path, line, msg);
  }
  return st;
}

static glint_status read_view(nff_reader *r, glint_error *e) {
  glint_camera cam;
  double angle, hither;
  long w, h;
  glint_status st;
  /* Each value's line (gli_camera_field's order), where an error about it
   * is said. */
  long lines[4];
  if ((st = expect_word(r, "from", e)) ||
      (lines[GLI_CAMERA_FROM] = r->t.token_line,
       st = gli_text_vec3(&r->t, "'from'", &cam.from, e)) ||
      (st = expect_word(r, "at", e)) ||
      (lines[GLI_CAMERA_AT] = r->t.token_line,
       st = gli_text_vec3(&r->t, "'at'", &cam.at, e)) ||
      (st = expect_word(r, "up", e)) ||
      (lines[GLI_CAMERA_UP] = r->t.token_line,
       st = gli_text_vec3(&r->t, "'up'", &cam.up, e)) ||
      (st = expect_word(r, "angle", e)) ||
      (st = gli_text_number(&r->t, "the view angle", &angle, e)))
    return st;
  long angle_line = lines[GLI_CAMERA_FOV] = r->t.token_line;
  if ((st = expect_word(r, "hither", e)) ||
      (st = gli_text_number(&r->t, "hither", &hither, e)) ||
      (st = expect_word(r, "resolution", e)) ||
      (st = gli_text_int(&r->t, "the horizontal resolution", 1,
                         GLINT_MAX_DIMENSION, &w, e)) ||
      (st = gli_text_int(&r->t, "the vertical resolution", 1,
                         GLINT_MAX_DIMENSION, &h, e)))
    return st;
  if (!(angle > 0 && angle < 180))
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%ld: view angle %g is not between 0 and 180", r->t.path,
                    angle_line, angle);
  double half = tan(angle * 3.14159265358979323846 / 360.0);
  if (w > 1)
    half *= (double)w / (double)(w - 1);
  cam.fov_x_degrees = 2 * atan(half) * 180.0 / 3.14159265358979323846;
  if (!(cam.fov_x_degrees > 0)) /* an angle of 5e-324: the file's value */
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%ld: view angle %g is too small to make a view of",
                    r->t.path, angle_line, angle);
  (void)hither;
  gli_camera_field fault;
  if ((st = gli_camera_check_field(&cam, &fault, e)) ||
      (st = glint_scene_set_camera(r->scene, &cam, e)))
    return at_line(r, lines[fault], st, e);
  return at_line(r, r->t.token_line,
                 glint_scene_set_resolution(r->scene, (int)w, (int)h, e), e);
}

static glint_status read_light(nff_reader *r, glint_error *e) {
  long line = r->t.token_line;
  glint_vec3 p, c = {1, 1, 1};
  glint_status st = gli_text_vec3(&r->t, "the light position", &p, e);
  if (st)
    return st;
  int coloured = gli_text_more_on_line(&r->t);
  if (coloured && (st = gli_text_vec3(&r->t, "the light colour", &c, e)))
    return st;
  if ((st = glint_scene_add_light(r->scene, p, c, e)))
    return at_line(r, line, st, e);
  if (!coloured) { /* its intensity is set once all lights are known */
    r->scene->lights[r->scene->light_count - 1].color =
        (glint_vec3){-1, -1, -1};
    r->uncoloured_lights++;
  }
  return GLINT_OK;
}

static glint_status read_material(nff_reader *r, glint_error *e) {
  long line = r->t.token_line;
  static const char *names[8] = {"red", "green", "blue", "Kd",
                                 "Ks",  "Shine", "T",    "index of refraction"};
  double v[8];
  for (int i = 0; i < 8; i++) {
    char what[64];
    snprintf(what, sizeof what, "the material's %s", names[i]);
    glint_status st = gli_text_number(&r->t, what, &v[i], e);
    if (st)
      return st;
  }
  glint_material m;
  glint_material_default(&m);
  m.color = (glint_vec3){v[0], v[1], v[2]};
  m.ka = 0.1;
  m.kd = v[3];
  m.ks = m.kr = v[4];
  m.h = v[5];
  m.kt = v[6];
  /* SPD files write ior 0 for materials that transmit nothing (and only
   * 0: a negative ior is an error however little it transmits). */
  m.ior = v[6] == 0 && v[7] == 0 ? 1 : v[7];
  glint_status st = glint_scene_add_material(r->scene, &m, &r->material, e);
  if (st)
    return at_line(r, line, st, e);
  r->has_material = 1;
  return GLINT_OK;
}

static glint_status need_material(nff_reader *r, const char *entity,
                                  glint_error *e) {
  if (r->has_material)
    return GLINT_OK;
  return gli_fail(e, GLINT_E_PARSE, "%s:%ld: '%s' before any 'f' material line",
                  r->t.path, r->t.token_line, entity);
}

static glint_status read_sphere(nff_reader *r, glint_error *e) {
  long line = r->t.token_line;
  glint_vec3 c;
  double radius;
  glint_status st;
  if ((st = need_material(r, "s", e)) ||
      (st = gli_text_vec3(&r->t, "the sphere's centre", &c, e)) ||
      (st = gli_text_number(&r->t, "the sphere's radius", &radius, e)))
    return st;
  return at_line(
      r, line,
      glint_scene_add_sphere(r->scene, c, fabs(radius), r->material, e), e);
}

static glint_status read_cone(nff_reader *r, glint_error *e) {
  long line = r->t.token_line;
  glint_vec3 base, apex;
  double rb, ra;
  glint_status st;
  if ((st = need_material(r, "c", e)) ||
      (st = gli_text_vec3(&r->t, "the cone's base", &base, e)) ||
      (st = gli_text_number(&r->t, "the cone's base radius", &rb, e)) ||
      (st = gli_text_vec3(&r->t, "the cone's apex", &apex, e)) ||
      (st = gli_text_number(&r->t, "the cone's apex radius", &ra, e)))
    return st;
  if ((rb < 0) != (ra < 0) && rb != 0 && ra != 0)
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%ld: the cone's radii %g and %g have different "
                    "signs",
                    r->t.path, line, rb, ra);
  return at_line(r, line,
                 glint_scene_add_cone(r->scene, base, fabs(rb), apex, fabs(ra),
                                      r->material, e),
                 e);
}

typedef struct polygon_emit {
  nff_reader *r;
  int patch;
  glint_error *e;
} polygon_emit;

static int emit_triangle(void *user, size_t a, size_t b, size_t c) {
  polygon_emit *pe = user;
  const glint_vec3 *v = pe->r->verts;
  if (!pe->patch)
    return (int)gli_scene_push_triangle(pe->r->scene, v[a], v[b], v[c], NULL,
                                        pe->e);
  const glint_vec3 *n = pe->r->norms;
  glint_vec3 nrm[3] = {n[a], n[b], n[c]};
  return (int)gli_scene_push_triangle(pe->r->scene, v[a], v[b], v[c], nrm,
                                      pe->e);
}

/* p and pp: a polygon of n vertices (see polygon.c), as one object. */
static glint_status read_polygon(nff_reader *r, int patch, glint_error *e) {
  long line = r->t.token_line;
  const char *entity = patch ? "pp" : "p";
  long n;
  glint_status st;
  if ((st = need_material(r, entity, e)) ||
      (st = gli_text_int(&r->t, "the vertex count", 3, MAX_POLYGON_VERTICES, &n,
                         e)))
    return st;
  if ((size_t)n > r->vert_cap) {
    glint_vec3 *v = realloc(r->verts, sizeof *v * (size_t)n);
    glint_vec3 *m = v ? realloc(r->norms, sizeof *m * (size_t)n) : NULL;
    if (v)
      r->verts = v;
    if (m)
      r->norms = m;
    if (!v || !m)
      return gli_fail(e, GLINT_E_MEMORY, "%s:%ld: out of memory", r->t.path,
                      line);
    r->vert_cap = (size_t)n;
  }
  r->odd.line = 0;
  long prev_end = line; /* the line of the last number read */
  for (long i = 0; i < n; i++) {
    glint_vec3 *v = &r->verts[i];
    long start = 0;
    if ((st = gli_text_number(&r->t, "a polygon vertex", &v->x, e)) ||
        (start = r->t.token_line,
         st = gli_text_number(&r->t, "a polygon vertex", &v->y, e)) ||
        (st = gli_text_number(&r->t, "a polygon vertex", &v->z, e)) ||
        (patch &&
         (st = gli_text_vec3(&r->t, "a patch normal", &r->norms[i], e)))) {
      if (r->odd.line && failed_at_word(&r->t)) /* where it went wrong */
        return odd_vertex_line(r, e);
      /* Say which vertex of which polygon (the message is built only now,
       * not for every vertex read). */
      if (e) {
        char msg[sizeof e->message];
        snprintf(msg, sizeof msg,
                 "%.900s (vertex %ld of %ld of the %s on line %ld)", e->message,
                 i + 1, n, patch ? "patch" : "polygon", line);
        gli_fail(e, st, "%s", msg);
      }
      return st;
    }
    long end = r->t.token_line;
    if (!r->odd.line && (start == prev_end || end != start)) {
      /* a line shared with the vertex before, or one it runs over */
      r->odd.line = start == prev_end ? prev_end : start;
      r->odd.too_many = start == prev_end;
      r->odd.vertex = start == prev_end && i > 0 ? i : i + 1;
      r->odd.count = n;
      r->odd.polygon_line = line;
      r->odd.patch = patch;
    }
    prev_end = end;
    if (!gli_vec3_in_range(*v))
      return gli_fail(e, GLINT_E_PARSE,
                      "%s:%ld: %s vertex %ld of %ld (of line %ld): coordinates "
                      "must be " GLI_RANGE_TEXT,
                      r->t.path, end, entity, i + 1, n, line);
  }
  if ((st = gli_scene_begin_object(r->scene, GLI_SHAPE_TRIANGLE, r->material,
                                   e)))
    return at_line(r, line, st, e);
  polygon_emit pe = {r, patch, e};
  int res = gli_triangulate(r->verts, (size_t)n, emit_triangle, &pe,
                            &r->scene->ear_tests_left);
  if (res == GLI_TRIANGULATE_NO_MEMORY)
    return gli_fail(e, GLINT_E_MEMORY, "%s:%ld: out of memory", r->t.path,
                    line);
  if (res == GLI_TRIANGULATE_TOO_COMPLEX)
    return gli_fail(e, GLINT_E_PARSE,
                    "%s:%ld: %s: the polygon of %ld vertices has too many "
                    "inward corners to triangulate (" GLI_EAR_LIMIT_TEXT ")",
                    r->t.path, line, entity, n);
  if (res)
    return at_line(r, line, (glint_status)res, e);
  return GLINT_OK;
}

static glint_status read_nff(nff_reader *r, glint_error *e) {
  char buf[64], q[48];
  const char *tok;
  glint_status st = GLINT_OK;
  size_t entities = 0;
  long last = 0; /* the line of the token before */
  while (!st && (last = r->t.token_line,
                 tok = gli_text_token(&r->t, buf, sizeof buf))) {
    entities++;
    long odd = r->odd.line; /* the polygon just read's, if any */
    r->odd.line = 0;
    if (strcmp(tok, "v") == 0) {
      long line = r->t.token_line;
      if (r->view_line)
        st = second(r, "view", line, r->view_line, e);
      else
        st = read_view(r, e);
      r->view_line = line;
    } else if (strcmp(tok, "b") == 0) {
      glint_vec3 c;
      long line = r->t.token_line;
      if (r->background_line)
        st = second(r, "background colour", line, r->background_line, e);
      r->background_line = line;
      if (!st && !(st = gli_text_vec3(&r->t, "the background colour", &c, e)))
        st = at_line(r, line, glint_scene_set_background(r->scene, c, e), e);
    } else if (strcmp(tok, "l") == 0)
      st = read_light(r, e);
    else if (strcmp(tok, "f") == 0)
      st = read_material(r, e);
    else if (strcmp(tok, "s") == 0)
      st = read_sphere(r, e);
    else if (strcmp(tok, "c") == 0)
      st = read_cone(r, e);
    else if (strcmp(tok, "p") == 0)
      st = read_polygon(r, 0, e);
    else if (strcmp(tok, "pp") == 0)
      st = read_polygon(r, 1, e);
    else if (gli_number_parse(tok, strlen(tok), &(double){0}) == NUMBER_OK)
      st = odd ? (r->odd.line = odd, odd_vertex_line(r, e)) /* went wrong */
           : r->t.token_line == last
               ? gli_fail(e, GLINT_E_PARSE,
                          "%s:%ld: unexpected '%s': more numbers on the line "
                          "than its entity takes",
                          r->t.path, r->t.token_line, tok)
               : gli_fail(e, GLINT_E_PARSE,
                          "%s:%ld: expected an entity (v, b, l, f, s, c, p or "
                          "pp), found the number '%s'",
                          r->t.path, r->t.token_line, tok);
    else
      st = gli_fail(e, GLINT_E_PARSE, "%s:%ld: unknown entity '%s'", r->t.path,
                    r->t.token_line,
                    gli_text_quote(q, sizeof q, tok, strlen(tok)));
  }
  if (st)
    return st;
  if (entities == 0) /* a blank picture would hide a wrong or truncated file */
    return gli_fail(e, GLINT_E_PARSE,
                    "%s: no scene: the file holds nothing but white space "
                    "and comments",
                    r->t.path);
  /* Uncoloured lights: 1/sqrt(number of lights) each. */
  double intensity =
      1 / sqrt((double)(r->scene->light_count ? r->scene->light_count : 1));
  for (size_t i = 0; i < r->scene->light_count; i++)
    if (r->scene->lights[i].color.x < 0)
      r->scene->lights[i].color = (glint_vec3){intensity, intensity, intensity};
  return GLINT_OK;
}

glint_status gli_nff_read(const gli_file_source *files, const char *path,
                          const char *data, size_t size, glint_scene **out,
                          glint_error *e) {
  (void)files; /* an NFF file refers to no other */
  nff_reader r;
  memset(&r, 0, sizeof r);
  glint_status st = gli_text_begin(&r.t, path, data, size, '#', e);
  if (st || (st = glint_scene_create(&r.scene, e)))
    return st;
  /* NFF's defaults: black background, white ambient light. */
  number_locale locale = gli_number_locale_begin();
  st = read_nff(&r, e);
  gli_number_locale_end(locale);
  free(r.verts);
  free(r.norms);
  if (st) {
    glint_scene_destroy(r.scene);
    return st;
  }
  *out = r.scene;
  return GLINT_OK;
}
