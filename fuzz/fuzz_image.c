/* libFuzzer target: the image reader behind `glint compare` for one format
 * (FUZZ_FILE_NAME: image.png, image.bmp or image.ppm), on arbitrary bytes
 * written to a temporary file; an image that reads is compared with itself
 * and written back. Build and run with scripts/fuzz.sh. */
/* mkstemps is a BSD/GNU extension */
#define _DEFAULT_SOURCE
#include <glint.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef FUZZ_FILE_NAME
#error "define FUZZ_FILE_NAME, e.g. \"image.png\""
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *dot = strrchr(FUZZ_FILE_NAME, '.');
  /* Writing back syncs the file (the atomic write): on a disk that can take
   * over a second, which libFuzzer reports as a hang of a 1 ms input; in
   * memory (tmpfs), where there is one, it costs nothing. */
  const char *folder = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
  char path[64];
  snprintf(path, sizeof path, "%s/glint-fuzz-XXXXXX%s", folder, dot);
  int fd = mkstemps(path, (int)strlen(dot));
  if (fd < 0)
    abort();
  if (write(fd, data, size) != (ssize_t)size)
    abort();
  close(fd);
  glint_image *image;
  glint_error e;
  if (glint_image_read(path, &image, &e) == GLINT_OK) {
    if (glint_image_psnr(image, image) >= 0 && glint_image_width(image) <= 64 &&
        glint_image_height(image) <= 64)
      glint_image_write(image, path, &e); /* the encoder, on what decoded */
    glint_image_destroy(image);
  }
  unlink(path);
  return 0;
}
