/* Binary PPM (P6, maxval 255). */
#include "image/image.h"

#include "core/error.h"

#include <ctype.h>

int gli_ppm_header(FILE *f, int width, int height) {
  return fprintf(f, "P6\n%d %d\n255\n", width, height) < 0 ? -1 : 0;
}

int gli_ppm_encode(const glint_image *im, FILE *f) {
  if (gli_ppm_header(f, im->width, im->height))
    return -1;
  size_t n = (size_t)im->width * im->height * 3;
  return fwrite(im->rgb, 1, n, f) == n ? 0 : -1;
}

/* A # comment's rest, through its line's end. */
static void skip_comment(FILE *f) {
  int c;
  do
    c = fgetc(f);
  while (c != '\n' && c != '\r' && c != EOF);
}

/* The next header number, skipping white space and # comments; -1 if none,
 * or if it does not end in white space or a comment (netpbm's grammar:
 * "2x1" is no width and height), -2 past PPM_LARGEST, -3 where the file
 * ends before it, -4 where it ends right after its digits. The white-space
 * character after it, or the comment with its line's end, is consumed: after
 * the maxval, the pixels begin there. */
#define PPM_LARGEST 1000000
static long ppm_number(FILE *f) {
  int c;
  for (;;) {
    c = fgetc(f);
    if (c == '#')
      skip_comment(f);
    else if (!isspace(c))
      break;
  }
  if (c == EOF)
    return -3;
  if (!isdigit(c))
    return -1;
  long v = 0;
  while (isdigit(c)) {
    v = v * 10 + (c - '0');
    if (v > PPM_LARGEST)
      return -2;
    c = fgetc(f);
  }
  if (c == EOF)
    return -4;
  if (c == '#')
    skip_comment(f);
  else if (!isspace(c))
    return -1;
  return v;
}

glint_status gli_ppm_decode(FILE *f, const char *path, glint_image **out,
                            int size[2], glint_error *error) {
  if (fgetc(f) != 'P' || fgetc(f) != '6')
    return gli_fail(error, GLINT_E_PARSE, "%s: not a binary PPM (P6) file",
                    path);
  int after = fgetc(f); /* white space or a comment, as after each number */
  if (after == EOF)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: bad PPM header: cut short (the file ends after P6)",
                    path);
  if (after != '#' && !isspace(after))
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: bad PPM header: P6 is not followed by white space",
                    path);
  ungetc(after, f);
  static const char *const field[3] = {"width", "height", "maxval"};
  long v[3];
  for (int i = 0; i < 3; i++)
    if ((v[i] = ppm_number(f)) < 1)
      return gli_fail(error, GLINT_E_PARSE,
                      "%s: bad PPM header: the %s is %s (P6, then width, "
                      "height and maxval, each a whole number followed by "
                      "white space)",
                      path, field[i],
                      v[i] == 0    ? "0"
                      : v[i] == -2 ? "too large"
                      : v[i] == -3 ? "missing (the file ends)"
                      : v[i] == -4 ? "cut short (the file ends after it)"
                                   : "not a number followed by white space");
  long w = v[0], h = v[1], maxval = v[2];
  if (maxval != 255)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: a PPM of maxval %ld (glint reads maxval 255: 8 bits "
                    "a channel)",
                    path, maxval);
  if (w > GLINT_MAX_DIMENSION || h > GLINT_MAX_DIMENSION)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: a PPM of %ld x %ld pixels (glint reads 1 to %d a "
                    "side)",
                    path, w, h, GLINT_MAX_DIMENSION);
  size[0] = (int)w;
  size[1] = (int)h;
  if (!out)
    return GLINT_OK;
  size_t n = (size_t)w * (size_t)h * 3;
  long long bytes = gli_file_size(f), here = ftell(f);
  if (bytes >= 0 && here >= 0 && (unsigned long long)(bytes - here) < n)
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: truncated PPM file (%lld bytes of pixels after its "
                    "header, where %ld x %ld pixels need %zu)",
                    path, bytes - here, w, h, n);
  glint_image *im;
  glint_status st = gli_image_create_for(path, (int)w, (int)h, &im, error);
  if (st)
    return st;
  if (fread(im->rgb, 1, n, f) != n) {
    glint_image_destroy(im);
    return gli_fail(error, GLINT_E_PARSE, "%s: truncated PPM file", path);
  }
  /* A line break may follow the pixels; more is a second image or a
   * header whose size is too small, which reading on would hide. */
  int c;
  while ((c = fgetc(f)) == '\n' || c == '\r' || c == ' ' || c == '\t')
    ;
  if (c != EOF) {
    glint_image_destroy(im);
    return gli_fail(error, GLINT_E_PARSE,
                    "%s: data after the %ld x %ld pixels the PPM header gives "
                    "(a second image, or a wrong size)",
                    path, w, h);
  }
  *out = im;
  return GLINT_OK;
}
