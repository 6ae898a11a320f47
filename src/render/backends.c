/* The backend registry: names, CPU requirements and the ops of every
 * backend and converted layout, and the parsing of backend, maths and
 * acceleration names. */
#include "core/cpu.h"
#include "core/error.h"
#include "render/backend.h"

#include <string.h>

typedef struct backend_entry {
  const char *name;
  int width;
  const gli_backend_ops *ops; /* NULL: not built into this binary */
  int (*cpu_has)(const gli_cpu_features *f);
} backend_entry;

static int cpu_any(const gli_cpu_features *f) {
  (void)f;
  return 1;
}
static int cpu_sse(const gli_cpu_features *f) { return f->sse41; }
static int cpu_avx2(const gli_cpu_features *f) { return f->avx2; }
static int cpu_avx512(const gli_cpu_features *f) { return f->avx512; }

static const backend_entry backends[GLINT_BACKEND_COUNT] = {
    [GLINT_BACKEND_AUTO] = {"auto", 0, NULL, cpu_any},
    [GLINT_BACKEND_SCALAR_FLOAT] = {"scalar-float", 1, &gli_scalar_ops_float,
                                    cpu_any},
    [GLINT_BACKEND_SCALAR_DOUBLE] = {"scalar-double", 1, &gli_scalar_ops_double,
                                     cpu_any},
    [GLINT_BACKEND_SSE] = {"sse", 4, &gli_beam_ops_sse, cpu_sse},
    [GLINT_BACKEND_AVX2] = {"avx2", 8, &gli_beam_ops_avx2, cpu_avx2},
    [GLINT_BACKEND_AVX512] = {"avx512", 16, &gli_beam_ops_avx512, cpu_avx512},
    [GLINT_BACKEND_STREAM] = {"stream", 0, NULL, cpu_any},
    [GLINT_BACKEND_STREAM_SSE] = {"stream-sse", 4, &gli_stream_ops_sse,
                                  cpu_sse},
    [GLINT_BACKEND_STREAM_AVX2] = {"stream-avx2", 8, &gli_stream_ops_avx2,
                                   cpu_avx2},
    [GLINT_BACKEND_STREAM_AVX512] = {"stream-avx512", 16,
                                     &gli_stream_ops_avx512, cpu_avx512},
};

const gli_backend_ops *gli_backend_ops_of(glint_backend b) {
  return (unsigned)b < GLINT_BACKEND_COUNT ? backends[b].ops : NULL;
}

/* The converted layouts, in data_kind order; every backend of a family
 * reads its family's layout. */
static const data_ops *const layouts[DATA_KIND_COUNT] = {
    &gli_scalar_data_float, &gli_scalar_data_double, &gli_packet_data_sse,
    &gli_packet_data_avx2, &gli_packet_data_avx512};

const data_ops *gli_data_ops_of(data_kind kind) {
  return (unsigned)kind < DATA_KIND_COUNT ? layouts[kind] : NULL;
}

const char *glint_backend_name(glint_backend b) {
  return (unsigned)b < GLINT_BACKEND_COUNT ? backends[b].name : "unknown";
}

int glint_backend_supported(glint_backend b) {
  if ((unsigned)b >= GLINT_BACKEND_COUNT)
    return 0;
  if (b == GLINT_BACKEND_AUTO)
    return glint_backend_supported(glint_backend_resolve(b));
  if (b == GLINT_BACKEND_STREAM) /* some stream backend, not a stand-in */
    return glint_backend_resolve(b) != GLINT_BACKEND_SCALAR_FLOAT;
  gli_cpu_features f;
  gli_cpu_detect(&f);
  return backends[b].ops != NULL && backends[b].cpu_has(&f);
}

glint_backend glint_backend_resolve(glint_backend b) {
  static const glint_backend widest_beam[] = {
      GLINT_BACKEND_AVX512, GLINT_BACKEND_AVX2, GLINT_BACKEND_SSE};
  static const glint_backend widest_stream[] = {GLINT_BACKEND_STREAM_AVX512,
                                                GLINT_BACKEND_STREAM_AVX2,
                                                GLINT_BACKEND_STREAM_SSE};
  const glint_backend *order = NULL;
  if (b == GLINT_BACKEND_AUTO)
    order = widest_beam;
  else if (b == GLINT_BACKEND_STREAM)
    order = widest_stream;
  else
    return b;
  for (int i = 0; i < 3; i++)
    if (glint_backend_supported(order[i]))
      return order[i];
  return GLINT_BACKEND_SCALAR_FLOAT;
}

int glint_backend_width(glint_backend b) {
  b = glint_backend_resolve(b);
  return (unsigned)b < GLINT_BACKEND_COUNT ? backends[b].width : 0;
}

static glint_status parse_name(const char *name, const char *const *names,
                               int count, const char *what, int *out,
                               glint_error *error) {
  for (int i = 0; i < count; i++)
    if (names[i] && strcmp(name, names[i]) == 0) {
      *out = i;
      return GLINT_OK;
    }
  char list[256] = "";
  for (int i = 0; i < count; i++)
    if (names[i]) {
      strncat(list, i ? ", " : "", sizeof list - strlen(list) - 1);
      strncat(list, names[i], sizeof list - strlen(list) - 1);
    }
  return gli_fail(error, GLINT_E_ARGUMENT, "unknown %s '%s' (one of: %s)", what,
                  name, list);
}

glint_status glint_backend_parse(const char *name, glint_backend *b,
                                 glint_error *error) {
  GLI_NOT_NULL(name, "name", error);
  GLI_NOT_NULL(b, "backend", error);
  const char *names[GLINT_BACKEND_COUNT];
  for (int i = 0; i < GLINT_BACKEND_COUNT; i++)
    names[i] = backends[i].name;
  int v = 0;
  glint_status st =
      parse_name(name, names, GLINT_BACKEND_COUNT, "backend", &v, error);
  if (st == GLINT_OK)
    *b = (glint_backend)v;
  return st;
}

static const char *const math_names[GLINT_MATH_COUNT] = {"minimax", "fast",
                                                         "taylor", "exact"};

const char *glint_math_name(glint_math m) {
  return (unsigned)m < GLINT_MATH_COUNT ? math_names[m] : "unknown";
}

glint_status glint_math_parse(const char *name, glint_math *m,
                              glint_error *error) {
  GLI_NOT_NULL(name, "name", error);
  GLI_NOT_NULL(m, "math", error);
  int v = 0;
  glint_status st =
      parse_name(name, math_names, GLINT_MATH_COUNT, "math", &v, error);
  if (st == GLINT_OK)
    *m = (glint_math)v;
  return st;
}

static const char *const accel_names[GLINT_ACCEL_COUNT] = {"bvh", "none",
                                                           "bvh2", "bvh8"};

const char *glint_accel_name(glint_accel a) {
  return (unsigned)a < GLINT_ACCEL_COUNT ? accel_names[a] : "unknown";
}

glint_status glint_accel_parse(const char *name, glint_accel *a,
                               glint_error *error) {
  GLI_NOT_NULL(name, "name", error);
  GLI_NOT_NULL(a, "accel", error);
  int v = 0;
  glint_status st = parse_name(name, accel_names, GLINT_ACCEL_COUNT,
                               "acceleration", &v, error);
  if (st == GLINT_OK)
    *a = (glint_accel)v;
  return st;
}
