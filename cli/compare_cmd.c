/* glint compare A B: the PSNR between two images of the same size. */
#include "args.h"
#include "cli.h"

#include <glint.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

int cmd_compare(int argc, char **argv) {
  if (argc == 1 &&
      (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0)) {
    puts(
        "Usage: glint compare A B\n\n"
        "Prints the peak signal-to-noise ratio between two images (.png, .bmp\n"
        "or .ppm) of the same size, in dB over all channels ('inf' when they\n"
        "are identical).");
    return 0;
  }
  if (argc != 2) {
    cli_error("compare needs two images (see glint compare --help)");
    return EXIT_USAGE;
  }
  glint_image *a = NULL, *b = NULL;
  glint_error err;
  if (glint_image_read(argv[0], &a, &err) ||
      glint_image_read(argv[1], &b, &err)) {
    cli_error("%s", err.message);
    glint_image_destroy(a);
    return EXIT_USAGE;
  }
  double psnr = glint_image_psnr(a, b);
  int status = 0;
  if (psnr < 0) {
    cli_error("%s is %dx%d but %s is %dx%d", argv[0], glint_image_width(a),
              glint_image_height(a), argv[1], glint_image_width(b),
              glint_image_height(b));
    status = EXIT_USAGE;
  } else if (isinf(psnr)) {
    printf("PSNR inf dB (identical)\n");
  } else {
    printf("PSNR %.2f dB\n", psnr);
  }
  glint_image_destroy(a);
  glint_image_destroy(b);
  return status;
}
