/* PNG, BMP and PPM written and read back pixel by pixel; the atomic write
 * never leaves a partial file nor destroys an existing one. */
#define _DEFAULT_SOURCE /* realpath */
#include "test_util.h"

#include <dirent.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

static char dir[64];

static int setup(void **state) {
  (void)state;
  strcpy(dir, "/tmp/glint-test-image-XXXXXX");
  return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  return system(cmd) == 0 ? 0 : -1;
}

static const char *path(const char *name) {
  static char buf[128];
  snprintf(buf, sizeof buf, "%s/%s", dir, name);
  return buf;
}

/* Odd sizes exercise BMP's row padding. */
static glint_image *pattern(int w, int h) {
  glint_image *im;
  ASSERT_OK(glint_image_create(w, h, &im, &e_));
  uint8_t *p = glint_image_pixels(im);
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++) {
      uint8_t *q = p + ((size_t)y * w + x) * 3;
      q[0] = (uint8_t)(x * 37 + y);
      q[1] = (uint8_t)(y * 91 + 3 * x);
      q[2] = (uint8_t)((x ^ y) * 13);
    }
  return im;
}

static int files_in_dir(void) {
  DIR *d = opendir(dir);
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)))
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
      n++;
  closedir(d);
  return n;
}

static void round_trip(const char *name, int w, int h) {
  glint_image *a = pattern(w, h), *b = NULL;
  char p[128];
  snprintf(p, sizeof p, "%s", path(name));
  ASSERT_OK(glint_image_write(a, p, &e_));
  ASSERT_OK(glint_image_read(p, &b, &e_));
  assert_int_equal(glint_image_width(b), w);
  assert_int_equal(glint_image_height(b), h);
  assert_memory_equal(glint_image_pixels_const(a), glint_image_pixels_const(b),
                      (size_t)w * h * 3);
  assert_true(isinf(glint_image_psnr(a, b)));
  int rw = 0, rh = 0;
  ASSERT_OK(glint_image_read_size(p, &rw, &rh, &e_));
  assert_int_equal(rw, w);
  assert_int_equal(rh, h);
  glint_image_destroy(a);
  glint_image_destroy(b);
}

static void png_round_trip(void **state) {
  (void)state;
  round_trip("a.png", 7, 5);
  round_trip("b.PNG", 1, 1);
}

static void bmp_round_trip(void **state) {
  (void)state;
  round_trip("a.bmp", 7, 5);
  round_trip("b.bmp", 4, 3);
  round_trip("c.bmp", 1, 9);
}

static void ppm_round_trip(void **state) {
  (void)state;
  round_trip("a.ppm", 7, 5);
}

/* The BMP header fields a viewer relies on. */
static void bmp_layout(void **state) {
  (void)state;
  glint_image *a = pattern(3, 2);
  char p[128];
  snprintf(p, sizeof p, "%s", path("layout.bmp"));
  ASSERT_OK(glint_image_write(a, p, &e_));
  FILE *f = fopen(p, "rb");
  uint8_t b[80];
  size_t n = fread(b, 1, sizeof b, f);
  fclose(f);
  assert_int_equal(n, 54 + 2 * 12); /* rows of 9 bytes padded to 12 */
  assert_int_equal(b[0], 'B');
  assert_int_equal(b[1], 'M');
  assert_int_equal(b[28], 24); /* bits per pixel */
  /* Bottom-up: the first stored row is the image's last, in BGR. */
  const uint8_t *last = glint_image_pixels_const(a) + 3 * 3;
  assert_int_equal(b[54], last[2]);
  assert_int_equal(b[55], last[1]);
  assert_int_equal(b[56], last[0]);
  glint_image_destroy(a);
}

static void psnr_of_known_difference(void **state) {
  (void)state;
  glint_image *a = pattern(4, 4), *b = pattern(4, 4), *c = pattern(5, 4);
  /* One channel of one pixel off by 10: MSE = 100 / 48. */
  glint_image_pixels(b)[0] = (uint8_t)(glint_image_pixels(a)[0] + 10);
  double want = 10 * log10(255.0 * 255.0 / (100.0 / 48.0));
  assert_true(fabs(glint_image_psnr(a, b) - want) < 1e-9);
  assert_true(glint_image_psnr(a, c) < 0);
  glint_image_destroy(a);
  glint_image_destroy(b);
  glint_image_destroy(c);
}

static void bad_paths_are_refused(void **state) {
  (void)state;
  glint_image *a = pattern(2, 2);
  glint_error e;
  assert_int_equal(glint_image_write(a, path("x.jpg"), &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "unknown image format"));
  assert_int_equal(glint_image_write(a, path("noext"), &e), GLINT_E_ARGUMENT);
  assert_int_equal(glint_image_check_writable("/nonexistent-dir/x.png", &e),
                   GLINT_E_IO);
  assert_non_null(strstr(e.message, "/nonexistent-dir/x.png"));
  assert_int_equal(glint_image_write(a, "/nonexistent-dir/x.png", &e),
                   GLINT_E_IO);
  /* A folder is not a file. */
  mkdir(path("sub.png"), 0755);
  assert_int_equal(glint_image_check_writable(path("sub.png"), &e), GLINT_E_IO);
  assert_non_null(strstr(e.message, "directory"));
  rmdir(path("sub.png"));
  /* A name longer than the kernel takes in a folder that is not: refused
   * by the check, before a render (the file failed to be named after it). */
  static char deep[PATH_MAX + 256];
  int levels = 0, n = snprintf(deep, sizeof deep, "%s", dir);
  while (n < PATH_MAX - 300) {
    n += snprintf(deep + n, sizeof deep - (size_t)n, "/%0200d", 0);
    assert_int_equal(mkdir(deep, 0755), 0);
    levels++;
  }
  snprintf(deep + n, sizeof deep - (size_t)n, "/%0250d.png", 0);
  assert_int_equal(glint_image_check_writable(deep, &e), GLINT_E_IO);
  assert_non_null(strstr(e.message, "File name too long"));
  for (; levels > 0; levels--) {
    *strrchr(deep, '/') = '\0';
    assert_int_equal(rmdir(deep), 0);
  }
  /* Reading: missing, and not an image. */
  glint_image *r = NULL;
  assert_int_equal(glint_image_read(path("missing.png"), &r, &e), GLINT_E_IO);
  FILE *f = fopen(path("junk.png"), "wb");
  fputs("this is not a png", f);
  fclose(f);
  assert_int_equal(glint_image_read(path("junk.png"), &r, &e), GLINT_E_PARSE);
  f = fopen(path("trunc.ppm"), "wb");
  fputs("P6\n4 4\n255\nabc", f);
  fclose(f);
  assert_int_equal(glint_image_read(path("trunc.ppm"), &r, &e), GLINT_E_PARSE);
  assert_null(r);
  /* Bytes after the pixels: a line break is fine, more is refused (they
   * were ignored). */
  f = fopen(path("long.ppm"), "wb");
  fputs("P6\n1 1\n255\nabc\n", f);
  fclose(f);
  ASSERT_OK(glint_image_read(path("long.ppm"), &r, &e_));
  glint_image_destroy(r);
  r = NULL;
  f = fopen(path("long.ppm"), "ab");
  fputs("P6\n1 1\n255\nabc", f);
  fclose(f);
  assert_int_equal(glint_image_read(path("long.ppm"), &r, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "long.ppm: data after the 1 x 1 pixels"));
  assert_null(r);
  /* The size alone, from the header: a short body is not looked at, a bad
   * header is refused as glint_image_read refuses it. */
  int w = 0, h = 0;
  ASSERT_OK(glint_image_read_size(path("trunc.ppm"), &w, &h, &e_));
  assert_int_equal(w, 4);
  assert_int_equal(h, 4);
  assert_int_equal(glint_image_read_size(path("junk.png"), &w, &h, &e),
                   GLINT_E_PARSE);
  assert_int_equal(glint_image_read_size(path("missing.png"), &w, &h, &e),
                   GLINT_E_IO);
  assert_int_equal(glint_image_read_size(path("trunc.ppm"), NULL, &h, &e),
                   GLINT_E_ARGUMENT);
  glint_image_destroy(a);
}

/* The file at p holds the eight bytes "original", as the test wrote it. */
static void assert_still_original(const char *p) {
  char buf[64] = {0};
  FILE *f = fopen(p, "rb");
  assert_non_null(f);
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  assert_int_equal(n, 8);
  assert_string_equal(buf, "original");
}

/* A write that fails part-way (here: the file-size limit is hit) leaves the
 * existing image byte for byte as it was, and no temporary file. */
static void failed_write_keeps_existing_file(void **state) {
  (void)state;
  int before = files_in_dir();
  char p[128];
  snprintf(p, sizeof p, "%s", path("keep.ppm"));
  FILE *f = fopen(p, "wb");
  fputs("original", f);
  fclose(f);
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit rl = {1000, 1000};
    setrlimit(RLIMIT_FSIZE, &rl);
    glint_image *big = pattern(200, 200); /* 120 kB: cannot fit */
    glint_error e;
    int st = glint_image_write(big, p, &e);
    glint_image_destroy(big);
    _exit(st == GLINT_E_IO && strstr(e.message, "keep.ppm") ? 0 : 1);
  }
  int status;
  waitpid(pid, &status, 0);
  assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  assert_still_original(p);
  assert_int_equal(files_in_dir(), before + 1);
  /* And a successful write replaces it completely. */
  glint_image *small = pattern(3, 3), *back;
  ASSERT_OK(glint_image_write(small, p, &e_));
  ASSERT_OK(glint_image_read(p, &back, &e_));
  assert_memory_equal(glint_image_pixels_const(small),
                      glint_image_pixels_const(back), 27);
  assert_int_equal(files_in_dir(), before + 1);
  glint_image_destroy(small);
  glint_image_destroy(back);
}

/* An image written to a symbolic link goes to the file it names, and the
 * link stays a link (as a shell's > writes). */
static void writes_through_a_link(void **state) {
  (void)state;
  char target[128], link[128];
  snprintf(target, sizeof target, "%s", path("target.ppm"));
  snprintf(link, sizeof link, "%s", path("link.ppm"));
  FILE *f = fopen(target, "wb");
  fputs("original", f);
  fclose(f);
  assert_int_equal(symlink("target.ppm", link), 0);
  /* where a write goes: the link's file, or the name itself */
  char *to = glint_output_file(link), *real = realpath(target, NULL);
  assert_string_equal(to, real);
  glint_free(to);
  free(real);
  to = glint_output_file(target);
  assert_string_equal(to, target);
  glint_free(to);
  glint_image *small = pattern(3, 3), *back;
  ASSERT_OK(glint_image_write(small, link, &e_));
  struct stat sb;
  assert_int_equal(lstat(link, &sb), 0);
  assert_true(S_ISLNK(sb.st_mode));
  ASSERT_OK(glint_image_read(target, &back, &e_));
  assert_memory_equal(glint_image_pixels_const(small),
                      glint_image_pixels_const(back), 27);
  glint_image_destroy(back);
  unlink(link);
  unlink(target);
  /* A link to something other than a regular file is refused, and stays:
   * the rename would have replaced /dev/null. */
  assert_int_equal(symlink("/dev/null", link), 0);
  glint_error e;
  assert_int_equal(glint_image_write(small, link, &e), GLINT_E_IO);
  assert_non_null(strstr(e.message, "link.ppm (a link to /dev/null): not a "
                                    "regular file"));
  struct stat null_sb;
  assert_int_equal(stat("/dev/null", &null_sb), 0);
  assert_true(S_ISCHR(null_sb.st_mode));
  assert_int_equal(lstat(link, &sb), 0);
  assert_true(S_ISLNK(sb.st_mode));
  unlink(link);
  /* A dangling link (through a second one) gets its file, as a shell's >
   * makes it, and stays a link (it was replaced by the file). */
  char middle[128];
  snprintf(middle, sizeof middle, "%s", path("middle.ppm"));
  assert_int_equal(symlink("middle.ppm", link), 0);
  assert_int_equal(symlink("made.ppm", middle), 0);
  ASSERT_OK(glint_image_write(small, link, &e_));
  assert_int_equal(lstat(link, &sb), 0);
  assert_true(S_ISLNK(sb.st_mode));
  ASSERT_OK(glint_image_read(path("made.ppm"), &back, &e_));
  glint_image_destroy(back);
  unlink(path("made.ppm"));
  /* A loop of links is refused, and stays. */
  unlink(middle);
  assert_int_equal(symlink("link.ppm", middle), 0);
  assert_null(glint_output_file(link));
  assert_int_equal(glint_image_write(small, link, &e), GLINT_E_IO);
  assert_non_null(strstr(e.message, "Too many levels of symbolic links"));
  assert_int_equal(lstat(link, &sb), 0);
  assert_true(S_ISLNK(sb.st_mode));
  unlink(middle);
  unlink(link);
  glint_image_destroy(small);
}

/* Runs check(arg) in a child process, which has become nobody where this
 * one is root, with the test folder open to it; returns whether check
 * returned 1. */
static int as_nobody(int (*check)(const void *arg), const void *arg) {
  chmod(dir, 0777);
  pid_t pid = fork();
  if (pid == 0) {
    if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0))
      _exit(2);
    _exit(check(arg) ? 0 : 1);
  }
  int status;
  waitpid(pid, &status, 0);
  chmod(dir, 0700);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

static int read_only_refused(const void *path) {
  glint_image *small = pattern(3, 3);
  glint_error e;
  int st = glint_image_write(small, path, &e);
  glint_image_destroy(small);
  return st == GLINT_E_IO && strstr(e.message, "ro.ppm: cannot write");
}

/* A file its user may not write is refused, not replaced by the rename
 * (which the folder alone allows). As root, the write is tried by a child
 * that has become nobody, on a file of root's. */
static void read_only_file_is_kept(void **state) {
  (void)state;
  char p[128];
  snprintf(p, sizeof p, "%s", path("ro.ppm"));
  FILE *f = fopen(p, "wb");
  fputs("original", f);
  fclose(f);
  chmod(p, 0444);
  assert_true(as_nobody(read_only_refused, p));
  assert_still_original(p);
  unlink(p);
}

/* In a folder with the sticky bit (as /tmp), another user's file is
 * refused before anything is rendered or written, though its mode lets
 * anyone write it: the rename after the render would be refused. Run as
 * root, whose child becomes nobody to write; another user's file cannot be
 * made otherwise: skipped. */
static int others_refused(const void *folder) {
  char theirs[160], mine[160];
  snprintf(theirs, sizeof theirs, "%s/theirs.ppm", (const char *)folder);
  snprintf(mine, sizeof mine, "%s/mine.ppm", (const char *)folder);
  glint_image *small = pattern(3, 3);
  glint_error e;
  int refused = glint_image_check_writable(theirs, &e) == GLINT_E_IO &&
                strstr(e.message, "theirs.ppm: cannot replace: it belongs to "
                                  "another user, in a folder with the sticky "
                                  "bit") &&
                glint_image_write(small, theirs, &e) == GLINT_E_IO;
  /* a new file there, and then replacing one's own, are fine */
  int written = glint_image_write(small, mine, &e) == GLINT_OK &&
                glint_image_write(small, mine, &e) == GLINT_OK;
  glint_image_destroy(small);
  return refused && written;
}

static void sticky_folder_keeps_others_files(void **state) {
  (void)state;
  if (geteuid() != 0)
    skip();
  char folder[128], p[160], mine[160];
  snprintf(folder, sizeof folder, "%s", path("sticky"));
  assert_int_equal(mkdir(folder, 0700), 0);
  assert_int_equal(chmod(folder, 01777), 0);
  snprintf(p, sizeof p, "%s/theirs.ppm", folder);
  snprintf(mine, sizeof mine, "%s/mine.ppm", folder);
  FILE *f = fopen(p, "wb");
  fputs("original", f);
  fclose(f);
  chmod(p, 0666);
  assert_true(as_nobody(others_refused, folder));
  assert_still_original(p);
  unlink(p);
  unlink(mine);
  rmdir(folder);
}

static void write_bytes(const char *name, const void *bytes, size_t size) {
  FILE *f = fopen(name, "wb");
  assert_non_null(f);
  assert_int_equal(fwrite(bytes, 1, size, f), size);
  assert_int_equal(fclose(f), 0);
}

/* A PNG made chunk by chunk: IHDR (w x h, `depth` bits, colour type
 * `type`), a PLTE of `colours` RGB triples when given, the filtered rows
 * `raw` (each row its filter byte, 0, then its samples) in one IDAT. */
static void put_be32(uint8_t *p, uint32_t v) {
  for (int k = 0; k < 4; k++)
    p[k] = (uint8_t)(v >> (24 - 8 * k));
}

static void put_chunk(FILE *f, const char *type, const uint8_t *data,
                      uint32_t size) {
  uint8_t head[8];
  put_be32(head, size);
  memcpy(head + 4, type, 4);
  /* (crc32 of a NULL buffer answers its initial value, not the sum) */
  uLong crc = crc32(0L, head + 4, 4);
  if (size)
    crc = crc32(crc, data, size);
  uint8_t tail[4];
  put_be32(tail, (uint32_t)crc);
  assert_int_equal(fwrite(head, 1, 8, f), 8);
  if (size) /* (fwrite of a NULL buffer is undefined, even of 0 bytes) */
    assert_int_equal(fwrite(data, 1, size, f), size);
  assert_int_equal(fwrite(tail, 1, 4, f), 4);
}

static void write_png_chunks(const char *path, uint32_t w, uint32_t h,
                             int depth, int type, const uint8_t *palette,
                             int colours, const uint8_t *raw, size_t size) {
  FILE *f = fopen(path, "wb");
  assert_non_null(f);
  static const uint8_t signature[8] = {0x89, 'P',  'N',  'G',
                                       '\r', '\n', 0x1a, '\n'};
  assert_int_equal(fwrite(signature, 1, 8, f), 8);
  uint8_t ihdr[13] = {0};
  put_be32(ihdr, w);
  put_be32(ihdr + 4, h);
  ihdr[8] = (uint8_t)depth;
  ihdr[9] = (uint8_t)type;
  put_chunk(f, "IHDR", ihdr, 13);
  if (colours)
    put_chunk(f, "PLTE", palette, (uint32_t)colours * 3);
  uint8_t packed[256];
  uLongf packed_size = sizeof packed;
  assert_int_equal(compress(packed, &packed_size, raw, size), Z_OK);
  put_chunk(f, "IDAT", packed, (uint32_t)packed_size);
  put_chunk(f, "IEND", NULL, 0);
  assert_int_equal(fclose(f), 0);
}

static void expect_pixels(const char *path, const uint8_t *want, int n) {
  glint_image *got;
  ASSERT_OK(glint_image_read(path, &got, &e_));
  assert_memory_equal(glint_image_pixels(got), want, (size_t)n * 3);
  glint_image_destroy(got);
}

/* PNG flavours other than glint's own 8-bit RGB, read as 8-bit RGB: greys
 * and palettes expanded, alpha dropped. 16-bit samples and palette indices
 * past the palette are refused (cut to 8 bits, two images apart in their
 * low bytes compared as identical; an index past the palette was read as
 * black with no word). */
static void png_flavours(void **state) {
  (void)state;
  char path[128];
  snprintf(path, sizeof path, "%s/flavour.png", dir);
  static const uint8_t palette[6] = {10, 20, 30, 200, 100, 50};
  static const uint8_t indices[] = {0, 1, 0}; /* 2x1, 8 bits */
  write_png_chunks(path, 2, 1, 8, 3, palette, 2, indices, sizeof indices);
  static const uint8_t two[6] = {200, 100, 50, 10, 20, 30};
  expect_pixels(path, two, 2);
  /* two rows (each its filter byte): 1 0 / 0 1 */
  static const uint8_t rows[] = {0, 1, 0, 0, 0, 1};
  write_png_chunks(path, 2, 2, 8, 3, palette, 2, rows, sizeof rows);
  static const uint8_t square[12] = {200, 100, 50, 10,  20,  30,
                                     10,  20,  30, 200, 100, 50};
  expect_pixels(path, square, 4);
  static const uint8_t bits[] = {0, 0xa0}; /* 3x1, 1 bit: 1, 0, 1 */
  write_png_chunks(path, 3, 1, 1, 3, palette, 2, bits, sizeof bits);
  static const uint8_t three[9] = {200, 100, 50, 10, 20, 30, 200, 100, 50};
  expect_pixels(path, three, 3);
  static const uint8_t grey[] = {0, 7, 250}; /* 2x1 grey */
  write_png_chunks(path, 2, 1, 8, 0, NULL, 0, grey, sizeof grey);
  static const uint8_t greys[6] = {7, 7, 7, 250, 250, 250};
  expect_pixels(path, greys, 2);
  static const uint8_t rgba[] = {0, 1, 2, 3, 0}; /* 1x1, transparent */
  write_png_chunks(path, 1, 1, 8, 6, NULL, 0, rgba, sizeof rgba);
  static const uint8_t rgb[3] = {1, 2, 3};
  expect_pixels(path, rgb, 1);

  glint_image *got = NULL;
  glint_error e;
  static const uint8_t past[] = {0, 0, 5}; /* index 5 of one colour */
  write_png_chunks(path, 2, 1, 8, 3, palette, 1, past, sizeof past);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "flavour.png: a pixel's palette index 5 "
                                    "is past the palette's 1 colour"));
  static const uint8_t deep[] = {0, 1, 2}; /* 1x1 grey, 16 bits */
  write_png_chunks(path, 1, 1, 16, 0, NULL, 0, deep, sizeof deep);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "flavour.png: a PNG of 16-bit samples"));
  assert_null(got);
  /* A text chunk claiming 2 GiB in a file of 62 bytes: cut short, read
   * without allocating what it claims (libpng allocated and zeroed it:
   * 2 GiB of memory for 62 bytes; the peak would show it). */
  FILE *f = fopen(path, "wb");
  assert_non_null(f);
  static const uint8_t signature[8] = {0x89, 'P',  'N',  'G',
                                       '\r', '\n', 0x1a, '\n'};
  assert_int_equal(fwrite(signature, 1, 8, f), 8);
  uint8_t ihdr[13] = {0, 0, 0, 8, 0, 0, 0, 6, 8, 2};
  put_chunk(f, "IHDR", ihdr, 13);
  static const uint8_t huge_text[] = {0x7f, 0xff, 0xff, 0xff, 't', 'E', 'X',
                                      't',  'k',  0,    'v',  'a', 'l', 'u',
                                      'e',  0,    0,    0,    0,   0,   0};
  assert_int_equal(fwrite(huge_text, 1, sizeof huge_text, f), sizeof huge_text);
  assert_int_equal(fclose(f), 0);
  struct rusage before, after;
  getrusage(RUSAGE_SELF, &before);
  int size[2];
  assert_int_equal(glint_image_read_size(path, &size[0], &size[1], &e),
                   GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "flavour.png: truncated PNG file"));
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  getrusage(RUSAGE_SELF, &after);
  assert_true(after.ru_maxrss - before.ru_maxrss < 256 * 1024); /* KiB */
  /* cut inside its signature: a PNG cut short, not "not a PNG" */
  write_bytes(path, "\x89PNG\r", 5);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "flavour.png: truncated PNG file (5 bytes "
                                    "of its signature)"));
  unlink(path);
}

/* Damaged files found by fuzzing: each is refused with the file's name and
 * what is wrong, without undefined behaviour, a leak or libpng's own lines
 * on stderr. */
static void damaged_files_are_refused(void **state) {
  (void)state;
  char path[128];
  glint_image *im, *got;
  glint_error e;
  /* a BMP whose height is INT32_MIN (no positive twin to flip it to) */
  snprintf(path, sizeof path, "%s/tall.bmp", dir);
  uint8_t bmp[54] = {'B', 'M'};
  bmp[10] = 54;
  bmp[14] = 40;
  bmp[18] = 4;        /* width 4 */
  bmp[22 + 3] = 0x80; /* height 0x80000000 */
  bmp[28] = 24;       /* bits per pixel */
  write_bytes(path, bmp, sizeof bmp);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "tall.bmp: a BMP of 4 x -2147483648"));
  /* the same header saying its pixels start inside it */
  bmp[22 + 3] = 0;
  bmp[22] = 1;
  bmp[10] = 10;
  write_bytes(path, bmp, sizeof bmp);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(
      strstr(e.message, "tall.bmp: the pixels start at byte 10, inside"));
  /* and an OS/2 BMP's 12-byte header */
  bmp[10] = 54;
  bmp[14] = 12;
  write_bytes(path, bmp, sizeof bmp);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "tall.bmp: a BMP with a 12-byte header"));
  /* a header of 2^32 - 1 bytes (14 + it wrapped to 13, and the pixels at
   * 54 were taken) */
  memset(bmp + 14, 0xff, 4);
  write_bytes(path, bmp, sizeof bmp);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "tall.bmp: the pixels start at byte 54"));

  /* PPM headers as netpbm writes them: a comment may follow a number
   * directly (it was refused), and a number ends in white space or a
   * comment ("2x1y255z" was read as 2 x 1, maxval 255) */
  snprintf(path, sizeof path, "%s/c.ppm", dir);
  static const char commented[] = "P6\n2#w\n1\n255#x\n\x01\x02\x03\x04\x05\x06";
  write_bytes(path, commented, sizeof commented - 1);
  ASSERT_OK(glint_image_read(path, &got, &e));
  assert_int_equal(glint_image_width(got), 2);
  assert_int_equal(glint_image_height(got), 1);
  assert_memory_equal(glint_image_pixels(got), "\x01\x02\x03\x04\x05\x06", 6);
  glint_image_destroy(got);
  static const char junk[] = "P6\n2x1y255z\x01\x02\x03\x04\x05\x06";
  write_bytes(path, junk, sizeof junk - 1);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "c.ppm: bad PPM header: the width is not "
                                    "a number"));
  /* The field at fault is named (each said only "bad PPM header"). */
  static const char zero[] = "P6\n2 1\n0\n\x01\x02\x03\x04\x05\x06";
  write_bytes(path, zero, sizeof zero - 1);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "c.ppm: bad PPM header: the maxval is 0"));
  static const char wide[] = "P6\n2 4294967297\n255\n";
  write_bytes(path, wide, sizeof wide - 1);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(
      strstr(e.message, "c.ppm: bad PPM header: the height is too large"));
  /* netpbm's white space after the magic number ("P68 6" was 8 x 6), and
   * a header cut right after a number (said "not a number") */
  static const char joined[] = "P62 1\n255\n\x01\x02\x03\x04\x05\x06";
  write_bytes(path, joined, sizeof joined - 1);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "c.ppm: bad PPM header: P6 is not "
                                    "followed by white space"));
  write_bytes(path, "P6", 2);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "c.ppm: bad PPM header: cut short (the "
                                    "file ends after P6)"));
  write_bytes(path, "P6\n8", 4);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "c.ppm: bad PPM header: the width is cut "
                                    "short (the file ends after it)"));
  static const char deep[] = "P6\n2 1\n65535\n\x01\x02\x03\x04\x05\x06";
  write_bytes(path, deep, sizeof deep - 1);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "c.ppm: a PPM of maxval 65535"));
  unlink(path);

  /* a PNG whose header claims 100000 x 100000 pixels */
  snprintf(path, sizeof path, "%s/huge.png", dir);
  ASSERT_OK(glint_image_create(1, 1, &im, &e));
  ASSERT_OK(glint_image_write(im, path, &e));
  glint_image_destroy(im);
  long size;
  FILE *pf = fopen(path, "rb");
  fseek(pf, 0, SEEK_END);
  size = ftell(pf);
  rewind(pf);
  uint8_t *png = malloc((size_t)size);
  assert_int_equal(fread(png, 1, (size_t)size, pf), (size_t)size);
  fclose(pf);
  const uint8_t huge_side[4] = {0, 1, 0x86, 0xa0}; /* 100000, big-endian */
  memcpy(png + 16, huge_side, 4);                  /* IHDR's width */
  memcpy(png + 20, huge_side, 4);                  /* and height */
  uLong crc = crc32(0L, png + 12, 17);             /* "IHDR" and its data */
  for (int k = 0; k < 4; k++)
    png[29 + k] = (uint8_t)(crc >> (24 - 8 * k));
  write_bytes(path, png, (size_t)size);
  free(png);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "huge.png: a PNG of 100000 x 100000"));
  unlink(path);

  /* a PPM larger than glint reads */
  snprintf(path, sizeof path, "%s/huge.ppm", dir);
  static const char huge_ppm[] = "P6\n100000 100000\n255\n";
  write_bytes(path, huge_ppm, sizeof huge_ppm - 1);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "huge.ppm: a PPM of 100000 x 100000"));
  unlink(path);

  /* a PNG cut short in its pixel data */
  snprintf(path, sizeof path, "%s/cut.png", dir);
  ASSERT_OK(glint_image_create(64, 64, &im, &e));
  uint8_t *px = glint_image_pixels(im);
  for (int i = 0; i < 64 * 64 * 3; i++)
    px[i] = (uint8_t)(i * 7919 >> 3);
  ASSERT_OK(glint_image_write(im, path, &e));
  glint_image_destroy(im);
  struct stat sb;
  assert_int_equal(stat(path, &sb), 0);
  assert_int_equal(truncate(path, sb.st_size / 2), 0);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  /* named as cut short (it was libpng's "Read Error") */
  assert_non_null(strstr(e.message, "cut.png: truncated PNG file"));
  /* an empty file of each format is empty, not some other format */
  const char *const empty_names[] = {"empty.png", "empty.bmp", "empty.ppm"};
  for (int k = 0; k < 3; k++) {
    snprintf(path, sizeof path, "%s/%s", dir, empty_names[k]);
    write_bytes(path, "", 0);
    assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
    if (!strstr(e.message, "the file is empty"))
      fail_msg("%s: '%s'", empty_names[k], e.message);
    unlink(path);
  }
  /* a BMP cut inside its headers (it was "not a BMP file") */
  snprintf(path, sizeof path, "%s/head.bmp", dir);
  static const char head_bmp[] = "BM\x3e\0\0\0\0\0\0\0";
  write_bytes(path, head_bmp, sizeof head_bmp - 1);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "head.bmp: truncated BMP file (10 bytes of "
                                    "its 54-byte header)"));
  unlink(path);
  /* Headers that claim 16384 x 16384 pixels over a few bytes: refused from
   * the file's size, before 805 MB are reserved for the pixels (which a
   * process with little address space could not) */
  unsigned char big_bmp[60] = {'B', 'M'};
  big_bmp[10] = 54, big_bmp[14] = 40, big_bmp[28] = 24;
  big_bmp[19] = big_bmp[23] = 0x40; /* 16384 = 0x4000, little-endian */
  snprintf(path, sizeof path, "%s/claims.bmp", dir);
  write_bytes(path, (const char *)big_bmp, sizeof big_bmp);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message, "claims.bmp: truncated BMP file (60 bytes, "
                                    "where its 16384 x 16384 pixels end at "
                                    "byte 805306422)"));
  unlink(path);
  snprintf(path, sizeof path, "%s/claims.ppm", dir);
  static const char claims_ppm[] = "P6\n16384 16384\n255\nabc";
  write_bytes(path, claims_ppm, sizeof claims_ppm - 1);
  assert_int_equal(glint_image_read(path, &got, &e), GLINT_E_PARSE);
  assert_non_null(strstr(e.message,
                         "claims.ppm: truncated PPM file (3 bytes of "
                         "pixels after its header, where 16384 x "
                         "16384 pixels need 805306368)"));
  unlink(path);
  snprintf(path, sizeof path, "%s/cut.png", dir);
  unlink(path);
  snprintf(path, sizeof path, "%s/tall.bmp", dir);
  unlink(path);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(png_round_trip),
      cmocka_unit_test(bmp_round_trip),
      cmocka_unit_test(ppm_round_trip),
      cmocka_unit_test(bmp_layout),
      cmocka_unit_test(psnr_of_known_difference),
      cmocka_unit_test(bad_paths_are_refused),
      cmocka_unit_test(failed_write_keeps_existing_file),
      cmocka_unit_test(writes_through_a_link),
      cmocka_unit_test(read_only_file_is_kept),
      cmocka_unit_test(sticky_folder_keeps_others_files),
      cmocka_unit_test(damaged_files_are_refused),
      cmocka_unit_test(png_flavours),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
