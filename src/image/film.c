/* Linear floating-point films and their 8-bit conversion (docs/specification.md
 * §4: only the average is clamped, then written as round(255 c)). */
#include "image/image.h"

#include "core/error.h"
#include "core/memory.h"

#include <emmintrin.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

glint_status glint_film_create(int w, int h, glint_film **out,
                               glint_error *error) {
  if (w < 1 || h < 1 || w > GLINT_MAX_DIMENSION || h > GLINT_MAX_DIMENSION)
    return gli_fail(error, GLINT_E_ARGUMENT, "film size %dx%d is outside 1..%d",
                    w, h, GLINT_MAX_DIMENSION);
  glint_film *film = malloc(sizeof *film);
  float *rgb = gli_aligned_calloc((size_t)w * (size_t)h * 3, sizeof(float));
  if (!film || !rgb) {
    free(film);
    gli_aligned_free(rgb);
    return gli_fail(error, GLINT_E_MEMORY, "out of memory for a %dx%d film", w,
                    h);
  }
  film->width = w;
  film->height = h;
  film->rgb = rgb;
  *out = film;
  return GLINT_OK;
}

void glint_film_destroy(glint_film *film) {
  if (film) {
    gli_aligned_free(film->rgb);
    free(film);
  }
}

int glint_film_width(const glint_film *film) { return film->width; }
int glint_film_height(const glint_film *film) { return film->height; }
float *glint_film_pixels(glint_film *film) { return film->rgb; }
const float *glint_film_pixels_const(const glint_film *film) {
  return film->rgb;
}

/* round(255 c) of c clamped to [0, 1], as 255 c + 1/2 clamped to
 * [0, 255.5] and truncated: the same bytes, in the order that max/min
 * instructions take (a NaN fails t > 0 and becomes 0). */
static inline uint8_t to_byte(float c) {
  float t = 255.0f * c + 0.5f;
  t = t > 0.0f ? t : 0.0f;
  t = t < 255.5f ? t : 255.5f;
  return (uint8_t)(int)t;
}

/* to_byte for 16 values at a time. Every frame of every backend passes
 * through here, and compilers vectorise the scalar loop poorly (gcc 12
 * spends about 10 instructions a value on it; these take under 2). SSE2 is
 * part of x86-64, so this needs no CPUID dispatch. maxps returns its second
 * operand when the first is NaN, as to_byte does. */
static size_t to_bytes_sse2(const float *src, uint8_t *dst, size_t n) {
  const __m128 scale = _mm_set1_ps(255.0f), half = _mm_set1_ps(0.5f);
  const __m128 zero = _mm_setzero_ps(), top = _mm_set1_ps(255.5f);
  size_t i = 0;
  for (; i + 16 <= n; i += 16) {
    __m128i q[4];
    for (int k = 0; k < 4; k++) {
      __m128 t =
          _mm_add_ps(_mm_mul_ps(_mm_loadu_ps(src + i + 4 * k), scale), half);
      q[k] = _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(t, zero), top));
    }
    __m128i lo = _mm_packs_epi32(q[0], q[1]), hi = _mm_packs_epi32(q[2], q[3]);
    _mm_storeu_si128((__m128i *)(dst + i), _mm_packus_epi16(lo, hi));
  }
  return i;
}

void gli_film_span_to_bytes(const float *src, uint8_t *dst, size_t n,
                            double gamma) {
  if (gamma == 1) {
    for (size_t i = to_bytes_sse2(src, dst, n); i < n; i++)
      dst[i] = to_byte(src[i]);
  } else {
    float inv = (float)(1.0 / gamma);
    for (size_t i = 0; i < n; i++) {
      float c = src[i] > 0 ? src[i] : 0.0f;
      dst[i] = to_byte(c > 0 ? powf(c < 1 ? c : 1.0f, inv) : 0.0f);
    }
  }
}

glint_status gli_gamma_check(double gamma, glint_error *error) {
  if (!(gamma >= GLINT_MIN_GAMMA && gamma <= GLINT_MAX_GAMMA))
    return gli_fail(error, GLINT_E_ARGUMENT, "gamma %g is outside %g..%g",
                    gamma, GLINT_MIN_GAMMA, GLINT_MAX_GAMMA);
  return GLINT_OK;
}

glint_status glint_film_to_image(const glint_film *film, double gamma,
                                 glint_image *image, glint_error *error) {
  if (gli_gamma_check(gamma, error))
    return GLINT_E_ARGUMENT;
  if (image->width != film->width || image->height != film->height)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "a %dx%d film does not fit a %dx%d image", film->width,
                    film->height, image->width, image->height);
  image->gamma = gamma;
  gli_film_span_to_bytes(film->rgb, image->rgb,
                         (size_t)film->width * (size_t)film->height * 3, gamma);
  return GLINT_OK;
}

static int write_pfm(const void *film, FILE *f) {
  return gli_pfm_encode(film, f);
}

#ifdef GLINT_HAVE_EXR
static int write_exr(const void *film, FILE *f) {
  return gli_exr_encode(film, f);
}
#endif

typedef enum film_format { FILM_UNKNOWN, FILM_PFM, FILM_EXR } film_format;

static film_format film_format_of(const char *path) {
  const char *slash = strrchr(path, '/');
  const char *dot = strrchr(slash ? slash : path, '.');
  if (dot && strcasecmp(dot, ".pfm") == 0)
    return FILM_PFM;
  if (dot && strcasecmp(dot, ".exr") == 0)
    return FILM_EXR;
  return FILM_UNKNOWN;
}

/* The format's writer, or an error saying why there is none. */
static glint_status film_writer(const char *path, write_fn *write,
                                glint_error *error) {
  switch (film_format_of(path)) {
  case FILM_PFM: *write = write_pfm; return GLINT_OK;
  case FILM_EXR:
#ifdef GLINT_HAVE_EXR
    *write = write_exr;
    return GLINT_OK;
#else
    return gli_fail(error, GLINT_E_UNSUPPORTED,
                    "%s: this build of glint has no OpenEXR (install "
                    "libopenexr-dev and rebuild, or write .pfm)",
                    path);
#endif
  default:
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "%s: unknown film format (use .pfm or .exr)", path);
  }
}

glint_status glint_film_check_writable(const char *path, glint_error *error) {
  write_fn write = NULL;
  glint_status st = film_writer(path, &write, error);
  return st ? st : gli_check_folder_writable(path, error);
}

glint_status glint_film_write(const glint_film *film, const char *path,
                              glint_error *error) {
  write_fn write = NULL;
  glint_status st = film_writer(path, &write, error);
  return st ? st : gli_write_atomically(path, write, film, error);
}
