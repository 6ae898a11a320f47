/* glint compare A B: the PSNR between two images of the same size, with a
 * threshold to fail on and an image of their differences. */
#include "args.h"
#include "files.h"
#include "cli.h"

#include <glint.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Differences are scaled up so that an error of a few levels shows. */
enum { DIFF_GAIN = 16 };

static void compare_usage(FILE *f) {
  fputs(
      "Usage: glint compare A B [options]\n"
      "\n"
      "Prints the peak signal-to-noise ratio between two images (.png, .bmp\n"
      "or .ppm) of the same size, in dB over the red, green and blue\n"
      "channels ('inf' when they are identical). Images are read at 8 bits\n"
      "a sample, as glint writes them: grey and palette PNGs as RGB, alpha\n"
      "not compared, 16-bit PNGs refused.\n"
      "\n"
      "Options:\n"
      "      --min-psnr DB  exit with status 1 when the PSNR is below DB\n"
      "                     (inf: unless the images are identical)\n"
      "      --diff FILE    write an image of the differences: each\n"
      "                     channel's |A - B| times 16, clamped to 255\n"
      "  -h, --help         this help\n"
      "  --                 the rest are images (a name that starts with -)\n"
      "\n"
      "Exit status: 0 when the images compare (and reach --min-psnr), 1 when\n"
      "they are below it, 2 when an image cannot be read or the sizes\n"
      "differ.\n",
      f);
}

static glint_status write_difference(const glint_image *a, const glint_image *b,
                                     const char *path, glint_error *err) {
  glint_image *d;
  int w = glint_image_width(a), h = glint_image_height(a);
  glint_status st = glint_image_create(w, h, &d, err);
  if (st)
    return st;
  const uint8_t *pa = glint_image_pixels_const(a);
  const uint8_t *pb = glint_image_pixels_const(b);
  uint8_t *pd = glint_image_pixels(d);
  for (size_t i = 0, n = (size_t)w * (size_t)h * 3; i < n; i++) {
    int v = abs((int)pa[i] - (int)pb[i]) * DIFF_GAIN;
    pd[i] = (uint8_t)(v > 255 ? 255 : v);
  }
  st = glint_image_write(d, path, err);
  glint_image_destroy(d);
  return st;
}

int compare_parse(int argc, char **argv, compare_options *o) {
  char *min_text = NULL;
  int nfiles = 0;
  memset(o, 0, sizeof *o);
  o->min_psnr = -INFINITY;
  arg_cursor c = {argc, argv, 0, NULL};
  int options = 1; /* 0 after "--": images only, as glint render takes it */
  while (c.i < argc) {
    const char *a = argv[c.i];
    if (options) {
      if (strcmp(a, "--") == 0) {
        options = 0;
        c.i++;
        continue;
      }
      if (arg_is_help(&c)) {
        compare_usage(stdout);
        return 0;
      }
      int r;
      if ((r = arg_text(&c, NULL, "--diff", &o->diff_path)) ||
          (r = arg_text(&c, NULL, "--min-psnr", &min_text))) {
        if (r == ARG_BAD)
          return EXIT_USAGE;
        continue;
      }
      if (a[0] == '-' && a[1] != '\0') {
        arg_unknown(a, "compare");
        return EXIT_USAGE;
      }
    }
    if (nfiles == 2) {
      cli_error("compare takes two images, not three ('%s')", a);
      return EXIT_USAGE;
    }
    o->files[nfiles++] = a;
    c.i++;
  }
  if (nfiles != 2) {
    cli_error("compare needs two images (see glint compare --help)");
    return EXIT_USAGE;
  }
  /* inf, as compare prints it: only identical images pass */
  if (min_text && strcasecmp(min_text, "inf") == 0)
    o->min_psnr = INFINITY;
  else if (min_text &&
           parse_double("--min-psnr", min_text, -INFINITY, &o->min_psnr))
    return EXIT_USAGE;
  if (o->diff_path &&
      (glint_image_format_from_path(o->diff_path) == GLINT_FORMAT_UNKNOWN)) {
    cli_error("--diff %s: not a .png, .bmp or .ppm file name", o->diff_path);
    return EXIT_USAGE;
  }
  return -1;
}

int cmd_compare(int argc, char **argv) {
  compare_options o;
  int status = compare_parse(argc, argv, &o);
  if (status >= 0)
    return status;
  const char *const *files = o.files;
  const char *diff_path = o.diff_path;
  double min_psnr = o.min_psnr;
  glint_image *a = NULL, *b = NULL;
  glint_error err;
  /* As glint render does with -o: a --diff that cannot be written fails
   * before any work, not after the result. */
  if (diff_path && cli_check_output_format(diff_path, NULL, &err)) {
    cli_error("--diff %s", err.message);
    return EXIT_USAGE;
  }
  if (diff_path && glint_image_check_writable(diff_path, &err)) {
    cli_error("%s", err.message);
    return EXIT_USAGE;
  }
  for (int i = 0; diff_path && i < 2; i++)
    if (same_file(files[i], diff_path)) {
      cli_error("--diff %s: that is %s, an image being compared", diff_path,
                files[i]);
      return EXIT_USAGE;
    }
  /* The sizes first, from the headers: images that cannot compare are
   * told so before either is decoded (a 16384 x 16384 PNG takes seconds
   * and 800 MB). */
  int w[2], h[2];
  for (int i = 0; i < 2; i++)
    if (glint_image_read_size(files[i], &w[i], &h[i], &err)) {
      cli_error("%s", err.message);
      return EXIT_USAGE;
    }
  if (w[0] != w[1] || h[0] != h[1]) {
    cli_error("%s is %dx%d but %s is %dx%d", files[0], w[0], h[0], files[1],
              w[1], h[1]);
    return EXIT_USAGE;
  }
  if (glint_image_read(files[0], &a, &err) ||
      glint_image_read(files[1], &b, &err)) {
    cli_error("%s", err.message);
    glint_image_destroy(a);
    return EXIT_USAGE;
  }
  double psnr = glint_image_psnr(a, b);
  status = 0;
  if (psnr < 0) { /* a file changed between the two reads */
    cli_error("%s is %dx%d but %s is %dx%d", files[0], glint_image_width(a),
              glint_image_height(a), files[1], glint_image_width(b),
              glint_image_height(b));
    status = EXIT_USAGE;
  } else {
    if (isinf(psnr))
      printf("PSNR inf dB (identical)\n");
    else
      printf("PSNR %.2f dB\n", psnr);
    if (diff_path && write_difference(a, b, diff_path, &err)) {
      cli_error("%s", err.message);
      status = EXIT_USAGE;
    } else if (psnr < min_psnr) {
      /* with as many decimals as tell the two apart: 29.999998 was "PSNR
       * 30.00 dB is below --min-psnr 30" */
      char shown[2][64];
      int digits = 2;
      for (;; digits++) {
        snprintf(shown[0], sizeof shown[0], "%.*f", digits, psnr);
        snprintf(shown[1], sizeof shown[1], "%.*f", digits, min_psnr);
        if (digits == 17 || strcmp(shown[0], shown[1]) != 0)
          break;
      }
      if (digits == 2)
        cli_error("PSNR %s dB is below --min-psnr %g", shown[0], min_psnr);
      else
        cli_error("PSNR %s dB is below --min-psnr %s", shown[0], shown[1]);
      status = 1;
    }
  }
  glint_image_destroy(a);
  glint_image_destroy(b);
  return status;
}
