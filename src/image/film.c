/* Linear floating-point films: their pixels, their 8-bit image
 * (docs/specification.md §4: only the average is clamped, then encoded by
 * image/byte_encoding.c) and their linear files (.pfm, .exr). */
#include "image/image.h"

#include "core/error.h"
#include "core/memory.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

glint_status glint_film_create(int w, int h, glint_film **out,
                               glint_error *error) {
  GLI_NOT_NULL(out, "film", error);
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

int glint_film_width(const glint_film *film) { return film ? film->width : 0; }
int glint_film_height(const glint_film *film) {
  return film ? film->height : 0;
}
float *glint_film_pixels(glint_film *film) { return film ? film->rgb : NULL; }
const float *glint_film_pixels_const(const glint_film *film) {
  return film ? film->rgb : NULL;
}

glint_status gli_gamma_check(double gamma, glint_error *error) {
  if (!(gamma >= GLINT_MIN_GAMMA && gamma <= GLINT_MAX_GAMMA))
    return gli_fail(error, GLINT_E_ARGUMENT, "gamma %.10g is outside %g..%g",
                    gamma, GLINT_MIN_GAMMA, GLINT_MAX_GAMMA);
  return GLINT_OK;
}

glint_status glint_film_to_image(const glint_film *film, double gamma,
                                 glint_image *image, glint_error *error) {
  GLI_NOT_NULL(film, "film", error);
  GLI_NOT_NULL(image, "image", error);
  if (gli_gamma_check(gamma, error))
    return GLINT_E_ARGUMENT;
  if (image->width != film->width || image->height != film->height)
    return gli_fail(error, GLINT_E_ARGUMENT,
                    "a %dx%d film does not fit a %dx%d image", film->width,
                    film->height, image->width, image->height);
  gli_byte_encoding *encoding = malloc(sizeof *encoding);
  if (!encoding)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  gli_byte_encoding_init(encoding, gamma);
  image->gamma = gamma;
  gli_byte_encode(encoding, film->rgb, image->rgb,
                  (size_t)film->width * (size_t)film->height * 3);
  free(encoding);
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
  GLI_NOT_NULL(path, "path", error);
  write_fn write = NULL;
  glint_status st = film_writer(path, &write, error);
  return st ? st : gli_check_folder_writable(path, error);
}

glint_status glint_film_write(const glint_film *film, const char *path,
                              glint_error *error) {
  GLI_NOT_NULL(film, "film", error);
  GLI_NOT_NULL(path, "path", error);
  write_fn write = NULL;
  glint_status st = film_writer(path, &write, error);
  return st ? st : gli_write_atomically(path, write, film, error);
}
