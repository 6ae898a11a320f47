/* glint's own scene format: one JSON object (RFC 8259) read with cJSON,
 * described in docs/scene-format.md. The reader is strict so that typing
 * mistakes surface at once instead of as a silently different picture:
 * unknown and repeated fields are errors, every value's type is checked,
 * numbers must be finite, and what the library refuses (a negative radius,
 * a degenerate camera) is reported at the JSON path that produced it.
 *
 * Every message starts with the file's path; a syntax error adds the line
 * and column (columns count UTF-8 characters, from 1), anything else the
 * JSON path of the offending value, as "objects[2].radius". */
#include "core/error.h"
#include "scene/file.h"
#include "scene/mesh.h"
#include "scene/scene.h"

#include <cJSON.h>
#include <errno.h>
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Quoted user text for a message, cut to this many bytes. */
#define QUOTE_LIMIT 64

typedef struct msg_text {
  char s[QUOTE_LIMIT * 6 + 16];
} msg_text;

/* A value's description: a quoted string and a few words. */
typedef struct value_text {
  char s[sizeof(msg_text) + 32];
} value_text;

typedef struct material_entry {
  const char *name; /* borrowed from the cJSON tree */
  size_t index;     /* position in "materials" */
} material_entry;

typedef struct json_reader {
  const char *file; /* as the caller gave it: every message starts with it */
  const gli_file_source *files; /* where mesh files come from */
  glint_scene *scene;
  glint_error *error;
  char path[512]; /* the JSON path of the value being read */
  size_t path_len;
  material_entry *by_name; /* sorted by name */
  uint32_t *material_ids;  /* by position in "materials" */
  size_t material_count;
} json_reader;

/* ---- messages ----------------------------------------------------------- */

/* `s` in double quotes with quotes, backslashes and control characters
 * escaped as JSON would write them, cut on a UTF-8 character boundary. */
static msg_text quoted(const char *s) {
  msg_text t;
  size_t len = strlen(s), cut = len, n = 0;
  if (len > QUOTE_LIMIT) {
    cut = QUOTE_LIMIT;
    while (cut > 0 && ((unsigned char)s[cut] & 0xC0) == 0x80)
      cut--;
  }
  t.s[n++] = '"';
  for (size_t i = 0; i < cut; i++) {
    unsigned char c = (unsigned char)s[i];
    if (c == '"' || c == '\\') {
      t.s[n++] = '\\';
      t.s[n++] = (char)c;
    } else if (c < 0x20 || c == 0x7F) {
      n += (size_t)snprintf(t.s + n, sizeof t.s - n, "\\u%04x", c);
    } else {
      t.s[n++] = (char)c;
    }
  }
  t.s[n++] = '"';
  if (cut < len) {
    memcpy(t.s + n, "...", 3);
    n += 3;
  }
  t.s[n] = '\0';
  return t;
}

/* What a value is, for "expected X, found Y". */
static value_text describe(const cJSON *v) {
  value_text t;
  if (cJSON_IsNull(v))
    snprintf(t.s, sizeof t.s, "null");
  else if (cJSON_IsBool(v))
    snprintf(t.s, sizeof t.s, "a boolean (%s)",
             cJSON_IsTrue(v) ? "true" : "false");
  else if (cJSON_IsNumber(v))
    snprintf(t.s, sizeof t.s, "a number (%g)", v->valuedouble);
  else if (cJSON_IsString(v) && v->valuestring)
    snprintf(t.s, sizeof t.s, "a string (%s)", quoted(v->valuestring).s);
  else if (cJSON_IsArray(v)) {
    size_t count = 0;
    for (const cJSON *c = v->child; c; c = c->next)
      count++;
    snprintf(t.s, sizeof t.s, "an array of %zu element%s", count,
             count == 1 ? "" : "s");
  } else if (cJSON_IsObject(v))
    snprintf(t.s, sizeof t.s, "an object");
  else
    snprintf(t.s, sizeof t.s, "an invalid value");
  return t;
}

/* "FILE: PATH: message", or "FILE: message" at the top level. */
static glint_status fail(json_reader *r, glint_status st, const char *format,
                         ...) GLI_PRINTF(3, 4);
static glint_status fail(json_reader *r, glint_status st, const char *format,
                         ...) {
  char msg[sizeof r->error->message];
  va_list args;
  va_start(args, format);
  vsnprintf(msg, sizeof msg, format, args);
  va_end(args);
  if (r->path_len)
    return gli_fail(r->error, st, "%s: %s: %s", r->file, r->path, msg);
  return gli_fail(r->error, st, "%s: %s", r->file, msg);
}

/* A library call's failure, placed at the current path. What the library
 * refuses came from the file, so an argument error is a parse error here.
 * The library's own prefix is dropped when it repeats the path ("camera:"
 * at "camera"). */
static glint_status lib(json_reader *r, glint_status st) {
  if (st == GLINT_OK)
    return st;
  if (st == GLINT_E_ARGUMENT)
    st = GLINT_E_PARSE;
  if (!r->error)
    return st;
  char msg[sizeof r->error->message];
  memcpy(msg, r->error->message, sizeof msg);
  msg[sizeof msg - 1] = '\0';
  const char *m = msg;
  if (r->path_len && strncmp(m, r->path, r->path_len) == 0 &&
      m[r->path_len] == ':' && m[r->path_len + 1] == ' ')
    m += r->path_len + 2;
  return fail(r, st, "%s", m);
}

/* ---- the JSON path ------------------------------------------------------ */

static void path_append(json_reader *r, const char *format, ...)
    GLI_PRINTF(2, 3);
static void path_append(json_reader *r, const char *format, ...) {
  size_t room = sizeof r->path - r->path_len;
  va_list args;
  va_start(args, format);
  int n = vsnprintf(r->path + r->path_len, room, format, args);
  va_end(args);
  /* A path too long for the buffer stays cut; messages show its start. */
  r->path_len = n < 0               ? r->path_len
                : (size_t)n >= room ? sizeof r->path - 1
                                    : r->path_len + (size_t)n;
}

static int is_identifier(const char *s) {
  if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || *s == '_'))
    return 0;
  for (; *s; s++)
    if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') ||
          (*s >= '0' && *s <= '9') || *s == '_' || *s == '-'))
      return 0;
  return 1;
}

/* Enters member `key`: ".key", or ["key"] when it is not a plain name.
 * Returns what path_pop needs to come back. */
static size_t path_key(json_reader *r, const char *key) {
  size_t mark = r->path_len;
  if (is_identifier(key))
    path_append(r, "%s%s", r->path_len ? "." : "", key);
  else
    path_append(r, "[%s]", quoted(key).s);
  return mark;
}

static size_t path_index(json_reader *r, size_t index) {
  size_t mark = r->path_len;
  path_append(r, "[%zu]", index);
  return mark;
}

static void path_pop(json_reader *r, size_t mark) {
  r->path_len = mark;
  r->path[mark] = '\0';
}

/* ---- values ------------------------------------------------------------- */

static glint_status expect_object(json_reader *r, const cJSON *v) {
  if (cJSON_IsObject(v))
    return GLINT_OK;
  return fail(r, GLINT_E_PARSE, "expected an object, found %s", describe(v).s);
}

static glint_status expect_array(json_reader *r, const cJSON *v) {
  if (cJSON_IsArray(v))
    return GLINT_OK;
  return fail(r, GLINT_E_PARSE, "expected an array, found %s", describe(v).s);
}

/* Every member of `obj` must be one of `fields` (NULL-terminated, at most
 * 32), and appear once: cJSON keeps repeated keys, and a repeated key would
 * silently lose one of its values. */
static glint_status check_fields(json_reader *r, const cJSON *obj,
                                 const char *const *fields) {
  uint32_t seen = 0;
  for (const cJSON *c = obj->child; c; c = c->next) {
    const char *key = c->string ? c->string : "";
    size_t i = 0;
    while (fields[i] && strcmp(fields[i], key) != 0)
      i++;
    if (!fields[i]) {
      char known[256] = "";
      size_t n = 0;
      for (size_t k = 0; fields[k] && n < sizeof known; k++)
        n += (size_t)snprintf(known + n, sizeof known - n, "%s%s",
                              k ? ", " : "", fields[k]);
      return fail(r, GLINT_E_PARSE, "unknown field %s (known: %s)",
                  quoted(key).s, known);
    }
    if (seen & (UINT32_C(1) << i))
      return fail(r, GLINT_E_PARSE, "field %s appears twice", quoted(key).s);
    seen |= UINT32_C(1) << i;
  }
  return GLINT_OK;
}

static glint_status get_number(json_reader *r, const cJSON *v, double *out) {
  if (!cJSON_IsNumber(v))
    return fail(r, GLINT_E_PARSE, "expected a number, found %s", describe(v).s);
  /* JSON has no NaN or Infinity, but cJSON reads 1e999 as an infinity. */
  if (!isfinite(v->valuedouble))
    return fail(r, GLINT_E_PARSE,
                "the number is too large: it is not finite in double "
                "precision");
  *out = v->valuedouble;
  return GLINT_OK;
}

/* d in the fewest digits that read back as d (1e300, not
 * 1.0000000000000001e+300; 2.0000000000000004, not 2). */
static const char *shortest(char buf[32], double d) {
  for (int digits = 15; digits < 17; digits++) {
    snprintf(buf, 32, "%.*g", digits, d);
    if (strtod(buf, NULL) == d)
      return buf;
  }
  snprintf(buf, 32, "%.17g", d);
  return buf;
}

static glint_status get_int(json_reader *r, const cJSON *v, int min, int max,
                            int *out) {
  double d = 0;
  glint_status st = get_number(r, v, &d);
  if (st)
    return st;
  char shown[32];
  if (d != floor(d))
    return fail(r, GLINT_E_PARSE, "expected a whole number, found %s",
                shortest(shown, d));
  if (d < min || d > max)
    return fail(r, GLINT_E_PARSE, "%s is outside %d..%d", shortest(shown, d),
                min, max);
  *out = (int)d;
  return GLINT_OK;
}

static glint_status get_vec3(json_reader *r, const cJSON *v, glint_vec3 *out) {
  const cJSON *c = cJSON_IsArray(v) ? v->child : NULL;
  const cJSON *e[3];
  size_t n = 0;
  for (; c && n < 3; c = c->next)
    e[n++] = c;
  if (!cJSON_IsArray(v) || n != 3 || c)
    return fail(r, GLINT_E_PARSE, "expected an array of 3 numbers, found %s",
                describe(v).s);
  double x[3] = {0, 0, 0};
  for (size_t i = 0; i < 3; i++) {
    size_t mark = path_index(r, i);
    glint_status st = get_number(r, e[i], &x[i]);
    if (st)
      return st;
    path_pop(r, mark);
  }
  *out = (glint_vec3){x[0], x[1], x[2]};
  return GLINT_OK;
}

static glint_status missing(json_reader *r, const char *key) {
  return fail(r, GLINT_E_PARSE, "missing \"%s\"", key);
}

/* Member `key` of `obj` with the error path entered at it (leave it with
 * path_pop(r, *mark)); NULL when absent, and *st then says whether that is
 * an error (`required`) or not (the caller keeps its default). */
static const cJSON *enter_field(json_reader *r, const cJSON *obj,
                                const char *key, int required, size_t *mark,
                                glint_status *st) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  *st = v || !required ? GLINT_OK : missing(r, key);
  if (v)
    *mark = path_key(r, key);
  return v;
}

/* A member that get_number or get_vec3 reads into *out. */
static glint_status value_field(json_reader *r, const cJSON *obj,
                                const char *key, int required, int is_vec3,
                                void *out) {
  size_t mark;
  glint_status st;
  const cJSON *v = enter_field(r, obj, key, required, &mark, &st);
  if (!v)
    return st;
  st = is_vec3 ? get_vec3(r, v, out) : get_number(r, v, out);
  if (st == GLINT_OK)
    path_pop(r, mark);
  return st;
}

static glint_status number_field(json_reader *r, const cJSON *obj,
                                 const char *key, int required, double *out) {
  return value_field(r, obj, key, required, 0, out);
}

static glint_status vec3_field(json_reader *r, const cJSON *obj,
                               const char *key, int required, glint_vec3 *out) {
  return value_field(r, obj, key, required, 1, out);
}

/* A required string member; its path stays entered (pop it with *mark) so
 * that the caller can place an error about the value there. */
static glint_status string_field(json_reader *r, const cJSON *obj,
                                 const char *key, const char **out,
                                 size_t *mark) {
  glint_status st;
  const cJSON *v = enter_field(r, obj, key, 1, mark, &st);
  if (!v)
    return st;
  if (!cJSON_IsString(v) || !v->valuestring)
    return fail(r, GLINT_E_PARSE, "expected a string, found %s", describe(v).s);
  *out = v->valuestring;
  return GLINT_OK;
}

/* ---- the sections ------------------------------------------------------- */

static glint_status read_camera(json_reader *r, const cJSON *v) {
  static const char *const fields[] = {"from", "at", "up", "fov", NULL};
  /* The defaults of glint_scene_create for what may be left out. */
  glint_camera c = {{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 60};
  glint_status st;
  if ((st = expect_object(r, v)) || (st = check_fields(r, v, fields)) ||
      (st = vec3_field(r, v, "from", 1, &c.from)) ||
      (st = vec3_field(r, v, "at", 1, &c.at)) ||
      (st = vec3_field(r, v, "up", 0, &c.up)) ||
      (st = number_field(r, v, "fov", 0, &c.fov_x_degrees)))
    return st;
  return lib(r, glint_scene_set_camera(r->scene, &c, r->error));
}

static glint_status read_image(json_reader *r, const cJSON *v) {
  static const char *const fields[] = {"width", "height", NULL};
  static const char *const keys[2] = {"width", "height"};
  int size[2] = {0, 0};
  glint_status st;
  if ((st = expect_object(r, v)) || (st = check_fields(r, v, fields)))
    return st;
  for (int i = 0; i < 2; i++) {
    const cJSON *m = cJSON_GetObjectItemCaseSensitive(v, keys[i]);
    if (!m)
      return missing(r, keys[i]);
    size_t mark = path_key(r, keys[i]);
    if ((st = get_int(r, m, 1, GLINT_MAX_DIMENSION, &size[i])))
      return st;
    path_pop(r, mark);
  }
  return lib(r,
             glint_scene_set_resolution(r->scene, size[0], size[1], r->error));
}

static glint_status read_lights(json_reader *r, const cJSON *v) {
  static const char *const fields[] = {"position", "color", NULL};
  glint_status st = expect_array(r, v);
  size_t i = 0;
  for (const cJSON *l = v->child; !st && l; l = l->next, i++) {
    size_t mark = path_index(r, i);
    glint_vec3 p = {0, 0, 0}, c = {1, 1, 1};
    if ((st = expect_object(r, l)) || (st = check_fields(r, l, fields)) ||
        (st = vec3_field(r, l, "position", 1, &p)) ||
        (st = vec3_field(r, l, "color", 0, &c)) ||
        (st = lib(r, glint_scene_add_light(r->scene, p, c, r->error))))
      return st;
    path_pop(r, mark);
  }
  return st;
}

static glint_status read_texture(json_reader *r, const cJSON *v,
                                 glint_material *m) {
  static const char *const fields[] = {"type", "odd", "even", "size", NULL};
  const char *type = "";
  size_t mark;
  glint_status st;
  if ((st = expect_object(r, v)) || (st = check_fields(r, v, fields)) ||
      (st = string_field(r, v, "type", &type, &mark)))
    return st;
  if (strcmp(type, "checker-planar") == 0)
    m->texture = GLINT_TEXTURE_CHECKER_PLANAR;
  else if (strcmp(type, "checker-solid") == 0)
    m->texture = GLINT_TEXTURE_CHECKER_SOLID;
  else
    return fail(r, GLINT_E_PARSE,
                "unknown texture type %s (checker-planar, checker-solid)",
                quoted(type).s);
  path_pop(r, mark);
  if ((st = vec3_field(r, v, "odd", 0, &m->checker_odd)) ||
      (st = vec3_field(r, v, "even", 0, &m->checker_even)))
    return st;
  return number_field(r, v, "size", 0, &m->checker_size);
}

static glint_status read_material(json_reader *r, const cJSON *v,
                                  uint32_t *id) {
  static const char *const fields[] = {"color",  "ka",      "kd", "ks",
                                       "h",      "kr",      "kt", "ior",
                                       "absorb", "texture", NULL};
  glint_material m;
  glint_material_default(&m);
  glint_status st;
  if ((st = expect_object(r, v)) || (st = check_fields(r, v, fields)) ||
      (st = vec3_field(r, v, "color", 0, &m.color)) ||
      (st = number_field(r, v, "ka", 0, &m.ka)) ||
      (st = number_field(r, v, "kd", 0, &m.kd)) ||
      (st = number_field(r, v, "ks", 0, &m.ks)) ||
      (st = number_field(r, v, "h", 0, &m.h)) ||
      (st = number_field(r, v, "kr", 0, &m.kr)) ||
      (st = number_field(r, v, "kt", 0, &m.kt)) ||
      (st = number_field(r, v, "ior", 0, &m.ior)) ||
      (st = vec3_field(r, v, "absorb", 0, &m.absorb)))
    return st;
  const cJSON *t = cJSON_GetObjectItemCaseSensitive(v, "texture");
  if (t) {
    size_t mark = path_key(r, "texture");
    if ((st = read_texture(r, t, &m)))
      return st;
    path_pop(r, mark);
  }
  return lib(r, glint_scene_add_material(r->scene, &m, id, r->error));
}

static int entry_order(const void *a, const void *b) {
  const material_entry *x = a, *y = b;
  int c = strcmp(x->name, y->name);
  if (c)
    return c;
  return x->index < y->index ? -1 : x->index > y->index;
}

static int entry_name(const void *key, const void *entry) {
  return strcmp(key, ((const material_entry *)entry)->name);
}

/* Materials are added in the file's order, so their ids are their
 * positions; names are looked up in a sorted table. */
static glint_status read_materials(json_reader *r, const cJSON *v) {
  glint_status st = expect_object(r, v);
  if (st)
    return st;
  size_t count = 0;
  for (const cJSON *c = v->child; c; c = c->next)
    count++;
  if (count == 0)
    return GLINT_OK;
  r->by_name = malloc(count * sizeof *r->by_name);
  r->material_ids = malloc(count * sizeof *r->material_ids);
  if (!r->by_name || !r->material_ids)
    return fail(r, GLINT_E_MEMORY, "out of memory");
  size_t i = 0;
  for (const cJSON *c = v->child; c; c = c->next, i++)
    r->by_name[i] = (material_entry){c->string ? c->string : "", i};
  qsort(r->by_name, count, sizeof *r->by_name, entry_order);
  for (i = 1; i < count; i++)
    if (strcmp(r->by_name[i - 1].name, r->by_name[i].name) == 0) {
      path_key(r, r->by_name[i].name);
      return fail(r, GLINT_E_PARSE, "a second material named %s",
                  quoted(r->by_name[i].name).s);
    }
  i = 0;
  for (const cJSON *c = v->child; c; c = c->next, i++) {
    size_t mark = path_key(r, c->string ? c->string : "");
    if ((st = read_material(r, c, &r->material_ids[i])))
      return st;
    path_pop(r, mark);
  }
  r->material_count = count;
  return GLINT_OK;
}

/* The object's "material": the id of a material defined by name. */
static glint_status object_material(json_reader *r, const cJSON *obj,
                                    uint32_t *id) {
  const char *name = "";
  size_t mark;
  glint_status st = string_field(r, obj, "material", &name, &mark);
  if (st)
    return st;
  const material_entry *e = r->material_count
                                ? bsearch(name, r->by_name, r->material_count,
                                          sizeof *r->by_name, entry_name)
                                : NULL;
  if (!e)
    return fail(r, GLINT_E_PARSE, "no material named %s%s", quoted(name).s,
                r->material_count ? "" : " (the file defines no materials)");
  *id = r->material_ids[e->index];
  path_pop(r, mark);
  return GLINT_OK;
}

static glint_status read_triangle(json_reader *r, const cJSON *obj,
                                  uint32_t material) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "vertices");
  if (!v)
    return missing(r, "vertices");
  size_t mark = path_key(r, "vertices");
  const cJSON *c = cJSON_IsArray(v) ? v->child : NULL;
  glint_vec3 p[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  size_t n = 0;
  for (; c && n < 3; c = c->next, n++) {
    size_t m = path_index(r, n);
    glint_status st = get_vec3(r, c, &p[n]);
    if (st)
      return st;
    path_pop(r, m);
  }
  if (!cJSON_IsArray(v) || n != 3 || c)
    return fail(r, GLINT_E_PARSE,
                "expected an array of 3 vertices ([x, y, z] each), found %s",
                describe(v).s);
  path_pop(r, mark);
  return lib(r, glint_scene_add_triangle(r->scene, p[0], p[1], p[2], material,
                                         r->error));
}

/* "file" is relative to the folder of the scene file, unless absolute. */
static glint_status read_mesh(json_reader *r, const cJSON *obj,
                              uint32_t material) {
  const char *file = "";
  size_t mark;
  double scale = 1;
  glint_vec3 translate = {0, 0, 0};
  glint_status st = string_field(r, obj, "file", &file, &mark);
  if (st)
    return st;
  if (!*file)
    return fail(r, GLINT_E_PARSE, "the file name is empty");
  path_pop(r, mark);
  if ((st = number_field(r, obj, "scale", 0, &scale)))
    return st;
  if (!(scale > 0)) {
    path_key(r, "scale");
    return fail(r, GLINT_E_PARSE, "scale %g must be > 0", scale);
  }
  if ((st = vec3_field(r, obj, "translate", 0, &translate)))
    return st;
  const char *slash = strrchr(r->file, '/');
  size_t dir = file[0] == '/' || !slash ? 0 : (size_t)(slash - r->file) + 1;
  size_t len = strlen(file);
  char *resolved = malloc(dir + len + 1);
  if (!resolved)
    return fail(r, GLINT_E_MEMORY, "out of memory");
  memcpy(resolved, r->file, dir);
  memcpy(resolved + dir, file, len + 1);
  st = gli_scene_add_mesh_from(r->scene, r->files, resolved, scale, translate,
                               material, r->error);
  free(resolved);
  return lib(r, st);
}

typedef enum object_kind { SPHERE, PLANE, TRIANGLE, CONE, MESH } object_kind;

/* "interpolation": "linear" (the default) or "catmull-rom". */
static glint_status read_interpolation(json_reader *r, const cJSON *v,
                                       glint_interpolation *out) {
  const cJSON *how = cJSON_GetObjectItemCaseSensitive(v, "interpolation");
  if (!how)
    return GLINT_OK;
  size_t mark = path_key(r, "interpolation");
  if (cJSON_IsString(how) && strcmp(how->valuestring, "catmull-rom") == 0)
    *out = GLINT_INTERPOLATE_CATMULL_ROM;
  else if (cJSON_IsString(how) && strcmp(how->valuestring, "linear") == 0)
    *out = GLINT_INTERPOLATE_LINEAR;
  else
    return fail(r, GLINT_E_PARSE,
                "expected \"linear\" or \"catmull-rom\", found %s",
                describe(how).s);
  path_pop(r, mark);
  return GLINT_OK;
}

/* The array `keys` (its path entered by the caller) read into a new array
 * of `size`-byte keys, each starting with its time in seconds (as
 * glint_camera_key and glint_transform_key do), by read_one; times must
 * increase. The caller frees *out. */
typedef glint_status (*key_reader)(json_reader *r, const cJSON *v, void *key);

static glint_status read_keys(json_reader *r, const cJSON *keys, size_t size,
                              key_reader read_one, void **out, size_t *count) {
  glint_status st;
  if ((st = expect_array(r, keys)))
    return st;
  size_t n = (size_t)cJSON_GetArraySize(keys);
  if (n == 0)
    return fail(r, GLINT_E_PARSE, "expected at least one key");
  char *k = calloc(n, size);
  if (!k)
    return fail(r, GLINT_E_MEMORY, "out of memory");
  size_t i = 0;
  double before = 0;
  for (const cJSON *c = keys->child; c; c = c->next, i++) {
    size_t mark = path_index(r, i);
    double time;
    if ((st = read_one(r, c, k + i * size))) {
      free(k);
      return st;
    }
    memcpy(&time, k + i * size, sizeof time);
    if (i > 0 && !(time > before)) {
      free(k);
      return fail(r, GLINT_E_PARSE,
                  "time %g does not come after the key before (%g)", time,
                  before);
    }
    before = time;
    path_pop(r, mark);
  }
  *out = k;
  *count = n;
  return GLINT_OK;
}

/* A transform's members (all optional) into *t, which holds the defaults;
 * `time` as well when it is a key. */
/* The fields of a still transform (each key of a moving one has them too). */
static const char *const still_fields[] = {"translate", "rotate", "scale",
                                           "pivot", NULL};

static glint_status read_transform_fields(json_reader *r, const cJSON *v,
                                          int key, glint_transform_key *k) {
  static const char *const key_fields[] = {"time",  "translate", "rotate",
                                           "scale", "pivot",     NULL};
  glint_transform *t = &k->transform;
  glint_status st;
  if ((st = expect_object(r, v)) ||
      (st = check_fields(r, v, key ? key_fields : still_fields)) ||
      (key && (st = number_field(r, v, "time", 1, &k->time))) ||
      (st = vec3_field(r, v, "translate", 0, &t->translate)) ||
      (st = vec3_field(r, v, "rotate", 0, &t->rotate)) ||
      (st = vec3_field(r, v, "pivot", 0, &t->pivot)) ||
      (st = number_field(r, v, "scale", 0, &t->scale)))
    return st;
  if (!(t->scale > 0)) {
    path_key(r, "scale");
    return fail(r, GLINT_E_PARSE, "the scale %g is not positive", t->scale);
  }
  /* Checked here, not only where the transform lands: a pivot of 1e300
   * cancels itself out of translate + pivot + R (p - pivot), and the
   * object would move silently. */
  const struct {
    const char *name;
    int in_range;
  } limits[] = {{"translate", gli_vec3_in_range(t->translate)},
                {"pivot", gli_vec3_in_range(t->pivot)},
                {"scale", gli_in_range(t->scale)}};
  for (size_t i = 0; i < sizeof limits / sizeof *limits; i++)
    if (!limits[i].in_range) {
      path_key(r, limits[i].name);
      return fail(r, GLINT_E_PARSE, "must be " GLI_RANGE_TEXT);
    }
  return GLINT_OK;
}

static glint_status read_transform_key(json_reader *r, const cJSON *v,
                                       void *key) {
  glint_transform_key *k = key;
  glint_transform_identity(&k->transform);
  return read_transform_fields(r, v, 1, k);
}

/* "transform": still ({"translate", "rotate", "scale", "pivot"}, applied
 * now) or moving ({"keys": [{"time", ...}], "interpolation"}). */
static glint_status read_transform(json_reader *r, const cJSON *v) {
  uint32_t object = (uint32_t)(r->scene->object_count - 1);
  glint_status st;
  if ((st = expect_object(r, v)))
    return st;
  const cJSON *keys = cJSON_GetObjectItemCaseSensitive(v, "keys");
  if (!keys) {
    glint_transform_key k = {0, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, 1}};
    if ((st = read_transform_fields(r, v, 0, &k)))
      return st;
    if (gli_object_transform(r->scene, object, &k.transform))
      return fail(r, GLINT_E_PARSE,
                  "the transform moves the object beyond "
                  "coordinates of magnitude 1e15");
    return GLINT_OK;
  }
  static const char *const fields[] = {"keys", "interpolation", NULL};
  for (size_t i = 0; still_fields[i]; i++)
    if (cJSON_GetObjectItemCaseSensitive(v, still_fields[i])) {
      path_key(r, still_fields[i]);
      return fail(r, GLINT_E_PARSE,
                  "a transform with \"keys\" has its %s in each key, not "
                  "beside them",
                  still_fields[i]);
    }
  glint_interpolation how = GLINT_INTERPOLATE_LINEAR;
  if ((st = check_fields(r, v, fields)) ||
      (st = read_interpolation(r, v, &how)))
    return st;
  size_t mark = path_key(r, "keys"), n = 0;
  glint_transform_key *k = NULL;
  if ((st = read_keys(r, keys, sizeof *k, read_transform_key, (void **)&k, &n)))
    return st;
  st = lib(
      r, glint_scene_set_object_motion(r->scene, object, k, n, how, r->error));
  free(k);
  if (st == GLINT_OK)
    path_pop(r, mark);
  return st;
}

static glint_status read_object_shape(json_reader *r, const cJSON *obj);

/* An object, then its transform (which applies to what it added). */
static glint_status read_object(json_reader *r, const cJSON *obj) {
  glint_status st = read_object_shape(r, obj);
  const cJSON *t =
      st ? NULL : cJSON_GetObjectItemCaseSensitive(obj, "transform");
  if (!t)
    return st;
  size_t mark = path_key(r, "transform");
  if ((st = read_transform(r, t)))
    return st;
  path_pop(r, mark);
  return GLINT_OK;
}

static glint_status read_object_shape(json_reader *r, const cJSON *obj) {
  static const char *const types[] = {"sphere", "plane", "triangle", "cone",
                                      "mesh"};
  static const char *const fields[][8] = {
      {"type", "material", "center", "radius", "transform", NULL},
      {"type", "material", "normal", "point", "transform", NULL},
      {"type", "material", "vertices", "transform", NULL},
      {"type", "material", "base", "base_radius", "apex", "apex_radius",
       "transform", NULL},
      {"type", "material", "file", "scale", "translate", "transform", NULL}};
  const char *type = "";
  size_t mark;
  glint_status st;
  if ((st = expect_object(r, obj)) ||
      (st = string_field(r, obj, "type", &type, &mark)))
    return st;
  size_t k = 0;
  while (k < sizeof types / sizeof types[0] && strcmp(types[k], type) != 0)
    k++;
  if (k == sizeof types / sizeof types[0])
    return fail(r, GLINT_E_PARSE,
                "unknown object type %s (sphere, plane, triangle, cone, mesh)",
                quoted(type).s);
  path_pop(r, mark);
  uint32_t material = 0;
  if ((st = check_fields(r, obj, fields[k])) ||
      (st = object_material(r, obj, &material)))
    return st;
  glint_vec3 a = {0, 0, 0}, b = {0, 0, 0};
  double ra = 0, rb = 0;
  switch ((object_kind)k) {
  case SPHERE:
    if ((st = vec3_field(r, obj, "center", 1, &a)) ||
        (st = number_field(r, obj, "radius", 1, &ra)))
      return st;
    return lib(r, glint_scene_add_sphere(r->scene, a, ra, material, r->error));
  case PLANE:
    if ((st = vec3_field(r, obj, "normal", 1, &a)) ||
        (st = vec3_field(r, obj, "point", 1, &b)))
      return st;
    return lib(r, glint_scene_add_plane(r->scene, a, b, material, r->error));
  case TRIANGLE: return read_triangle(r, obj, material);
  case CONE:
    if ((st = vec3_field(r, obj, "base", 1, &a)) ||
        (st = number_field(r, obj, "base_radius", 1, &rb)) ||
        (st = vec3_field(r, obj, "apex", 1, &b)) ||
        (st = number_field(r, obj, "apex_radius", 1, &ra)))
      return st;
    return lib(
        r, glint_scene_add_cone(r->scene, a, rb, b, ra, material, r->error));
  case MESH: return read_mesh(r, obj, material);
  }
  return GLINT_OK;
}

static glint_status read_objects(json_reader *r, const cJSON *v) {
  glint_status st = expect_array(r, v);
  size_t i = 0;
  for (const cJSON *o = v->child; !st && o; o = o->next, i++) {
    size_t mark = path_index(r, i);
    if ((st = read_object(r, o)))
      return st;
    path_pop(r, mark);
  }
  return st;
}

static glint_status
read_color(json_reader *r, const cJSON *root, const char *key,
           glint_status (*set)(glint_scene *, glint_vec3, glint_error *)) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, key);
  if (!v)
    return GLINT_OK;
  size_t mark = path_key(r, key);
  glint_vec3 c = {0, 0, 0};
  glint_status st;
  if ((st = get_vec3(r, v, &c)) || (st = lib(r, set(r->scene, c, r->error))))
    return st;
  path_pop(r, mark);
  return GLINT_OK;
}

/* ---- animation ---------------------------------------------------------- */

/* One camera key: {"time": t, "from", "at", "up", "fov"}, up and fov
 * defaulting as in "camera". */
static glint_status read_camera_key(json_reader *r, const cJSON *v, void *out) {
  glint_camera_key *key = out;
  static const char *const fields[] = {"time", "from", "at", "up", "fov", NULL};
  glint_camera c = {{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 60};
  glint_status st;
  if ((st = expect_object(r, v)) || (st = check_fields(r, v, fields)) ||
      (st = number_field(r, v, "time", 1, &key->time)) ||
      (st = vec3_field(r, v, "from", 1, &c.from)) ||
      (st = vec3_field(r, v, "at", 1, &c.at)) ||
      (st = vec3_field(r, v, "up", 0, &c.up)) ||
      (st = number_field(r, v, "fov", 0, &c.fov_x_degrees)) ||
      (st = lib(r, gli_camera_check(&c, r->error))))
    return st;
  key->camera = c;
  return GLINT_OK;
}

/* "camera": {"keys": [...], "interpolation": "linear"|"catmull-rom"} or
 * {"orbit": {"center", "radius", "height", "degrees"}}. */
static glint_status read_camera_motion(json_reader *r, const cJSON *v) {
  static const char *const fields[] = {"keys", "interpolation", "orbit", NULL};
  glint_status st;
  if ((st = expect_object(r, v)) || (st = check_fields(r, v, fields)))
    return st;
  const cJSON *keys = cJSON_GetObjectItemCaseSensitive(v, "keys");
  const cJSON *orbit = cJSON_GetObjectItemCaseSensitive(v, "orbit");
  if (!keys == !orbit)
    return fail(r, GLINT_E_PARSE, "give either \"keys\" or \"orbit\"");
  if (orbit) {
    static const char *const orbit_fields[] = {"center", "radius", "height",
                                               "degrees", NULL};
    glint_vec3 center = {0, 0, 0};
    double radius = 0, height = 0, degrees = 360;
    size_t mark = path_key(r, "orbit");
    if ((st = expect_object(r, orbit)) ||
        (st = check_fields(r, orbit, orbit_fields)) ||
        (st = vec3_field(r, orbit, "center", 1, &center)) ||
        (st = number_field(r, orbit, "radius", 1, &radius)) ||
        (st = number_field(r, orbit, "height", 0, &height)) ||
        (st = number_field(r, orbit, "degrees", 0, &degrees)) ||
        (st = lib(r, glint_scene_set_camera_orbit(r->scene, center, radius,
                                                  height, degrees, r->error))))
      return st;
    path_pop(r, mark);
    if (cJSON_GetObjectItemCaseSensitive(v, "interpolation"))
      return fail(r, GLINT_E_PARSE, "\"interpolation\" applies to keys");
    return GLINT_OK;
  }
  glint_interpolation interpolation = GLINT_INTERPOLATE_LINEAR;
  if ((st = read_interpolation(r, v, &interpolation)))
    return st;
  size_t mark = path_key(r, "keys"), n = 0;
  glint_camera_key *k = NULL;
  if ((st = read_keys(r, keys, sizeof *k, read_camera_key, (void **)&k, &n)))
    return st;
  st = lib(
      r, glint_scene_set_camera_keys(r->scene, k, n, interpolation, r->error));
  free(k);
  if (st == GLINT_OK)
    path_pop(r, mark);
  return st;
}

/* "animation": {"fps": 24, "frames": [first, last], "camera": {...}}. */
static glint_status read_animation(json_reader *r, const cJSON *v) {
  static const char *const fields[] = {"fps", "frames", "camera", NULL};
  glint_animation a = {24, 0, 0};
  glint_status st;
  if ((st = expect_object(r, v)) || (st = check_fields(r, v, fields)) ||
      (st = number_field(r, v, "fps", 0, &a.fps)))
    return st;
  if (!(a.fps >= GLINT_MIN_FPS && a.fps <= GLINT_MAX_FPS)) {
    path_key(r, "fps");
    return fail(r, GLINT_E_PARSE, "fps %.9g is outside %g..%g", a.fps,
                GLINT_MIN_FPS, GLINT_MAX_FPS);
  }
  const cJSON *frames = cJSON_GetObjectItemCaseSensitive(v, "frames");
  if (!frames)
    return missing(r, "frames");
  size_t mark = path_key(r, "frames");
  if (!cJSON_IsArray(frames) || cJSON_GetArraySize(frames) != 2)
    return fail(r, GLINT_E_PARSE,
                "expected [first, last] frame numbers, found %s",
                describe(frames).s);
  int range[2];
  for (int i = 0; i < 2; i++) {
    size_t m = path_index(r, (size_t)i);
    if ((st = get_int(r, cJSON_GetArrayItem(frames, i), 0, GLINT_MAX_FRAME,
                      &range[i])))
      return st;
    path_pop(r, m);
  }
  if (range[1] < range[0])
    return fail(r, GLINT_E_PARSE, "the last frame %d comes before the first %d",
                range[1], range[0]);
  path_pop(r, mark);
  a.first_frame = range[0];
  a.last_frame = range[1];
  if ((st = lib(r, glint_scene_set_animation(r->scene, &a, r->error))))
    return st;
  const cJSON *camera = cJSON_GetObjectItemCaseSensitive(v, "camera");
  if (camera) {
    mark = path_key(r, "camera");
    if ((st = read_camera_motion(r, camera)))
      return st;
    path_pop(r, mark);
  }
  return GLINT_OK;
}

/* The sections in a fixed order, whatever the file's: materials before the
 * objects that name them. */
static glint_status read_scene(json_reader *r, const cJSON *root) {
  static const char *const fields[] = {"camera",  "image",     "background",
                                       "ambient", "lights",    "materials",
                                       "objects", "animation", NULL};
  static const struct {
    const char *key;
    glint_status (*read)(json_reader *, const cJSON *);
  } sections[] = {{"camera", read_camera},   {"image", read_image},
                  {"lights", read_lights},   {"materials", read_materials},
                  {"objects", read_objects}, {"animation", read_animation}};
  if (!cJSON_IsObject(root))
    return fail(r, GLINT_E_PARSE,
                "expected an object at the top level, found %s",
                describe(root).s);
  glint_status st;
  if ((st = check_fields(r, root, fields)) ||
      (st = read_color(r, root, "background", glint_scene_set_background)) ||
      (st = read_color(r, root, "ambient", glint_scene_set_ambient)))
    return st;
  for (size_t i = 0; i < sizeof sections / sizeof sections[0]; i++) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, sections[i].key);
    if (!v)
      continue;
    size_t mark = path_key(r, sections[i].key);
    if ((st = sections[i].read(r, v)))
      return st;
    path_pop(r, mark);
  }
  return GLINT_OK;
}

static int is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/* The length of a well-formed UTF-8 character (RFC 3629 §4) at p, or 0. */
static int utf8_length(const char *p) {
  const unsigned char *u = (const unsigned char *)p;
  if (u[0] < 0xC2 || u[0] > 0xF4)
    return 0; /* a continuation byte, an overlong lead (C0, C1), or none */
  int n = u[0] >= 0xF0 ? 4 : u[0] >= 0xE0 ? 3 : 2;
  for (int i = 1; i < n; i++)
    if ((u[i] & 0xC0) != 0x80)
      return 0;
  if ((u[0] == 0xE0 && u[1] < 0xA0) || (u[0] == 0xED && u[1] > 0x9F) ||
      (u[0] == 0xF0 && u[1] < 0x90) || (u[0] == 0xF4 && u[1] > 0x8F))
    return 0; /* overlong, a surrogate, or beyond U+10FFFF */
  return n;
}

/* Whether the quote at q opens a string (rather than closing one): the
 * quotes before it, escapes aside, are even in number. */
static int opens_string(const char *data, const char *q) {
  int in_string = 0;
  for (const char *s = data; s < q; s++)
    if (in_string && *s == '\\' && s + 1 < q)
      s++;
    else if (*s == '"')
      in_string = !in_string;
  return !in_string;
}

/* Whether p, in data, holds the last value of a file that ends inside an
 * array or object: a number or literal where a value goes (after '[', ','
 * or ':'), and nothing after it. cJSON points there, at a value it read
 * well. */
static int last_value(const char *data, const char *p) {
  const char *b = p;
  while (b > data && is_space(b[-1]))
    b--;
  if (b == data || !strchr("[,:", b[-1]))
    return 0;
  const char *q = p;
  if (strncmp(p, "true", 4) == 0 || strncmp(p, "null", 4) == 0)
    q = p + 4;
  else if (strncmp(p, "false", 5) == 0)
    q = p + 5;
  else if (*p == '-' || (*p >= '0' && *p <= '9'))
    q = p + strspn(p, "0123456789+-.eE"); /* grammar_problem checked it */
  if (q == p)
    return 0;
  while (*q && is_space(*q))
    q++;
  return !*q;
}

/* What cJSON stopped at, with a hint for the usual mistakes. `*at` may move
 * back to where the problem starts (an unclosed string's quote) or on to
 * where it is (the end of a file that ends inside an array). */
static void syntax_hint(const char *data, const char **at, char *out,
                        size_t size) {
  const char *p = *at;
  const char *q = data;
  while (*q && is_space(*q))
    q++;
  if (!*q) {
    snprintf(out, size,
             q == data ? "the file is empty"
                       : "the file holds nothing but white space");
    return;
  }
  /* cJSON points just after the opening quote of a string that never
   * closes. */
  if (p > data && p[-1] == '"' && opens_string(data, p - 1)) {
    const char *s = p;
    while (*s && *s != '"')
      s += s[0] == '\\' && s[1] ? 2 : 1;
    if (!*s) {
      *at = p - 1;
      snprintf(out, size, "a string that is never closed");
      return;
    }
  }
  if (*p == '\\') {
    snprintf(out, size, "an invalid escape sequence in a string");
    return;
  }
  /* Where a member's name must follow '{' or ',', cJSON points one past
   * what it found instead (its string reader fails past the character
   * that should have been the opening quote). After ',' the container may
   * be an array, so an opening bracket there is taken as found where it
   * is; after '{', a '}' closed an empty object, and what follows it is
   * what was found. */
  if (p > data && !is_space(p[-1]) && p[-1] != '"') {
    const char *b = p - 1;
    while (b > data && is_space(b[-1]))
      b--;
    if (b > data && ((b[-1] == '{' && p[-1] != '}') ||
                     (b[-1] == ',' && p[-1] != '[' && p[-1] != '{')))
      *at = p = p - 1;
  }
  if (!*p || last_value(data, p)) {
    *at = p + strlen(p);
    snprintf(out, size, "the file ends early");
    return;
  }
  const char *prev = p;
  while (prev > data && is_space(prev[-1]))
    prev--;
  unsigned char c = (unsigned char)*p;
  if ((*p == '}' || *p == ']') && prev > data && prev[-1] == ',') {
    snprintf(out, size,
             "found '%c' after a comma (JSON allows no trailing comma)", *p);
  } else if (*p == '/' && (p[1] == '/' || p[1] == '*')) {
    snprintf(out, size, "found a comment (JSON has none)");
  } else if (*p == '\'') {
    snprintf(out, size, "found ' (JSON strings take double quotes)");
  } else if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
             (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' ||
             c == '_') {
    char word[32];
    size_t n = 0;
    while (n + 1 < sizeof word &&
           ((p[n] >= 'a' && p[n] <= 'z') || (p[n] >= 'A' && p[n] <= 'Z') ||
            (p[n] >= '0' && p[n] <= '9') || p[n] == '-' || p[n] == '+' ||
            p[n] == '.' || p[n] == '_')) {
      word[n] = p[n];
      n++;
    }
    word[n] = '\0';
    const char *w = word + (word[0] == '-' || word[0] == '+');
    int special = strcmp(w, "NaN") == 0 || strcmp(w, "nan") == 0 ||
                  strcmp(w, "Infinity") == 0 || strcmp(w, "inf") == 0;
    snprintf(out, size, "found '%s'%s", word,
             special ? " (JSON has no NaN or Infinity)" : "");
  } else if (c > 0x20 && c < 0x7F) {
    snprintf(out, size, "found '%c'", *p);
  } else if (c >= 0xC2 && c <= 0xF4 && utf8_length(p) > 0) {
    /* with its code point: U+FEFF (a second byte-order mark) or U+00A0
     * (a no-break space) look like nothing in a terminal */
    int n = utf8_length(p);
    const unsigned char *u = (const unsigned char *)p;
    unsigned cp = u[0] & (0x7Fu >> n);
    for (int i = 1; i < n; i++)
      cp = cp << 6 | (u[i] & 0x3Fu);
    snprintf(out, size, "found '%.*s' (U+%04X)", n, p, cp);
  } else {
    snprintf(out, size, "found the byte 0x%02x", c);
  }
}

static int is_digit(const char *p, const char *end) {
  return p < end && *p >= '0' && *p <= '9';
}

/* A number at p as RFC 8259 §6 writes it, -? (0 | [1-9][0-9]*) (.[0-9]+)?
 * ([eE][+-]?[0-9]+)? (cJSON's strtod would also take 1. and -.5): where it
 * ends, or where it breaks the grammar with *what set. */
static const char *number_problem(const char *p, const char *end,
                                  const char **what) {
  *what = NULL;
  const char *q = p + (*p == '-');
  if (q < end && *q == '.') {
    *what = "a number without a digit before its decimal point";
    return p;
  }
  if (!is_digit(q, end))
    return q; /* -Infinity, say: cJSON's report names it */
  if (*q == '0' && is_digit(q + 1, end)) {
    *what = "a number with a leading zero (JSON allows none)";
    return p;
  }
  while (is_digit(q, end))
    q++;
  if (q < end && *q == '.') {
    if (!is_digit(++q, end)) {
      *what = "a number without a digit after its decimal point";
      return p;
    }
    while (is_digit(q, end))
      q++;
  }
  if (q < end && (*q == 'e' || *q == 'E')) {
    q++;
    if (q < end && (*q == '+' || *q == '-'))
      q++;
    if (!is_digit(q, end)) {
      *what = "a number whose exponent has no digits";
      return p;
    }
    while (is_digit(q, end))
      q++;
  }
  return q;
}

/* The deepest nesting a scene may have. A scene nests five levels (a
 * mesh's vertex inside its vertices inside an object inside objects inside
 * the scene), and cJSON parses by recursion, about 100 bytes of stack a
 * level: its own limit, 1000 levels, took more than the 64 KiB stack of a
 * process run under ulimit -s 64, which crashed. */
#define JSON_NESTING_LIMIT 100
#define TEXT_OF_(x) #x
#define TEXT_OF(x) TEXT_OF_(x)
#define NESTING_LIMIT_TEXT TEXT_OF(JSON_NESTING_LIMIT)
_Static_assert(JSON_NESTING_LIMIT <= CJSON_NESTING_LIMIT,
               "cJSON must take every nesting glint does");

/* Where the nesting first goes deeper than JSON_NESTING_LIMIT, or NULL;
 * strings are taken as cJSON takes them (to the next unescaped quote,
 * whatever lies between), since their ends decide how deep cJSON goes. A
 * closing bracket with nothing open (which cJSON refuses there) counts for
 * nothing. */
static const char *too_deep(const char *p, const char *end) {
  int in_string = 0;
  long depth = 0;
  for (; p < end; p++) {
    if (in_string) {
      if (*p == '\\')
        p++;
      else if (*p == '"')
        in_string = 0;
    } else if (*p == '"') {
      in_string = 1;
    } else if (*p == '[' || *p == '{') {
      if (++depth > JSON_NESTING_LIMIT)
        return p;
    } else if ((*p == ']' || *p == '}') && depth > 0) {
      depth--;
    }
  }
  return NULL;
}

/* What cJSON reads but JSON (RFC 8259) refuses, found before it parses, so
 * that glint is exactly as strict as the format: an escape other than \"
 * \\ \/ \b \f \n \r \t and \uXXXX (cJSON ends the string at a bad one,
 * silently cutting a name), \u0000 (no name can hold a NUL), a control
 * character inside a string or between tokens (where cJSON skips any byte
 * up to the space), text that is not UTF-8 inside a string, and
 * a number outside JSON's grammar (01, 1., .5, -.5, 1e). NULL when the text is
 * clean, else where the problem is and *what it is. */
static const char *grammar_problem(const char *data, size_t size,
                                   const char **what) {
  const char *p = data, *end = data + size;
  int in_string = 0;
  for (; p < end; p++) {
    unsigned char c = (unsigned char)*p;
    if (in_string) {
      if (c == '"') {
        in_string = 0;
      } else if (c < 0x20) {
        /* a line break too: cJSON reads "a<LF>b" as a name, and a string
         * never closed is cJSON's to report, at the text's end, later */
        *what = "a control character inside a string (write it as an "
                "escape such as \\n)";
        return p;
      } else if (c >= 0x80) {
        int n = utf8_length(p);
        if (n == 0 || p + n > end) {
          *what = "a string that is not UTF-8 text";
          return p;
        }
        p += n - 1;
      } else if (c == '\\') {
        if (p + 1 >= end || !strchr("\"\\/bfnrtu", p[1]) || p[1] == '\0') {
          *what = "an invalid escape sequence in a string";
          return p;
        }
        if (p[1] == 'u') {
          for (int i = 2; i < 6; i++)
            if (p + i >= end || !isxdigit((unsigned char)p[i])) {
              *what = "\\u needs four hexadecimal digits";
              return p;
            }
          if (strncmp(p + 2, "0000", 4) == 0) {
            *what = "\\u0000 (a NUL) inside a string";
            return p;
          }
          p += 5;
        } else {
          p++;
        }
      }
    } else if (c == '"') {
      in_string = 1;
    } else if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') {
      /* cJSON skips every byte up to the space between tokens */
      *what = "a control character between tokens (JSON allows only "
              "spaces, tabs and line breaks there)";
      return p;
    } else if (c == '.') {
      *what = "a number without a digit before its decimal point";
      return p;
    } else if ((c == '-' || (c >= '0' && c <= '9')) &&
               (p == data || !(isalnum((unsigned char)p[-1]) || p[-1] == '-' ||
                               p[-1] == '+'))) {
      const char *q = number_problem(p, end, what);
      if (*what)
        return q;
      p = q - 1; /* on past the number */
    }
  }
  return NULL;
}

static glint_status parse_text(const char *path, const char *data, size_t size,
                               cJSON **out, glint_error *e) {
  glint_status st = gli_file_check_text(path, data, size, 1, e);
  if (st)
    return st;
  /* cJSON skips one byte order mark; columns count from the character
   * after it, and a file of a mark alone is empty. */
  const char *text = data;
  gli_file_skip_bom(&data, &size);
  /* return_parse_end rather than cJSON_GetErrorPtr, which reads a global
   * that another thread's parse may have changed. */
  /* What JSON forbids and cJSON lets pass, nesting too deep among it; the
   * first problem of either kind is the one said. Nesting too deep could
   * overflow the stack in cJSON's recursion, so there cJSON reads only the
   * text before it (to the same end where it meets a problem earlier). */
  const char *what, *bad = grammar_problem(data, size, &what);
  const char *deep = too_deep(data, data + size);
  if (deep && (!bad || deep < bad)) {
    bad = deep;
    what =
        "arrays and objects nested deeper than " NESTING_LIMIT_TEXT " levels";
  }
  const char *end = NULL;
  cJSON *root;
  if (deep) { /* (a copy: cJSON's text ends at a NUL) */
    size_t n = (size_t)(deep - text);
    char *before = malloc(n + 1);
    if (!before)
      return gli_fail(e, GLINT_E_MEMORY, "%s: out of memory", path);
    memcpy(before, text, n);
    before[n] = '\0';
    root = cJSON_ParseWithOpts(before, &end, 1);
    end = end ? text + (end - before) : NULL;
    free(before);
  } else {
    root = cJSON_ParseWithOpts(text, &end, 1);
  }
  char hint[160];
  if (!root) {
    if (!end || end < data || end > data + size)
      end = data + size;
    syntax_hint(data, &end, hint, sizeof hint);
  }
  size_t line, column;
  if (bad && (root || bad <= end)) {
    cJSON_Delete(root);
    gli_text_line_column(data, bad, 1, &line, &column);
    return gli_fail(e, GLINT_E_PARSE, "%s:%zu:%zu: JSON syntax error: %s", path,
                    line, column, what);
  }
  if (root) {
    *out = root;
    return GLINT_OK;
  }
  gli_text_line_column(data, end, 1, &line, &column);
  return gli_fail(e, GLINT_E_PARSE, "%s:%zu:%zu: JSON syntax error: %s", path,
                  line, column, hint);
}

glint_status gli_json_read(const gli_file_source *files, const char *path,
                           const char *data, size_t size, glint_scene **out,
                           glint_error *error) {
  cJSON *root = NULL;
  glint_status st = parse_text(path, data, size, &root, error);
  if (st)
    return st;
  json_reader r;
  memset(&r, 0, sizeof r);
  r.file = path;
  r.files = files;
  r.error = error;
  if ((st = glint_scene_create(&r.scene, error)) == GLINT_OK)
    st = read_scene(&r, root);
  cJSON_Delete(root);
  free(r.by_name);
  free(r.material_ids);
  if (st) {
    glint_scene_destroy(r.scene);
    return st;
  }
  *out = r.scene;
  return GLINT_OK;
}
