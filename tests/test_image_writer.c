/* Image files written while a frame renders (include/glint.h,
 * glint_image_writer), through the public API alone:
 *  - a frame rendered without a film, its tiles put into a writer, is the
 *    file glint_render and glint_image_write_with make, byte for byte, for
 *    PNG (gamma 1 and 2.2, both compressions), BMP and PPM;
 *  - tiles of any size in any order give the image glint_film_to_image
 *    gives, and a PNG is held in bands of rows, not whole;
 *  - a writer missing pixels, or discarded, writes nothing, leaves the
 *    existing file as it was and no temporary file beside it;
 *  - writing that fails part-way (a full disk) is reported and keeps the
 *    existing file;
 *  - a writer into memory encodes the same bytes, which
 *    glint_image_write_encoded writes whole;
 *  - refused tiles (outside the image, repeated, empty, without pixels or
 *    rows), and bad paths, sizes and gammas,
 *    are refused with a message. */
#include "test_util.h"

#include <dirent.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define W 83 /* not a multiple of the tile size: partial tiles at the edges */
#define H 61

static char folder[256];

static int make_folder(void **state) {
  (void)state;
  snprintf(folder, sizeof folder, "%s/glint-writer-%d",
           getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid());
  return mkdir(folder, 0755);
}

static int remove_folder(void **state) {
  (void)state;
  DIR *d = opendir(folder);
  struct dirent *ent;
  char path[512];
  while (d && (ent = readdir(d)))
    if (ent->d_name[0] != '.' ||
        (strcmp(ent->d_name, ".") != 0 && strcmp(ent->d_name, "..") != 0)) {
      snprintf(path, sizeof path, "%s/%s", folder, ent->d_name);
      unlink(path);
    }
  if (d)
    closedir(d);
  return rmdir(folder);
}

static const char *in_folder(const char *name) {
  static char path[512];
  snprintf(path, sizeof path, "%s/%s", folder, name);
  return path;
}

/* The whole file, NUL-terminated; *size its length. */
static char *slurp(const char *path, long *size) {
  FILE *f = fopen(path, "rb");
  assert_non_null(f);
  fseek(f, 0, SEEK_END);
  *size = ftell(f);
  rewind(f);
  char *data = malloc((size_t)*size + 1);
  assert_int_equal(fread(data, 1, (size_t)*size, f), (size_t)*size);
  data[*size] = '\0';
  fclose(f);
  return data;
}

static void assert_same_file(const char *a, const char *b) {
  long na, nb;
  char *da = slurp(a, &na), *db = slurp(b, &nb);
  assert_int_equal(na, nb);
  assert_memory_equal(da, db, (size_t)na);
  free(da);
  free(db);
}

/* Files in the folder whose names start with '.': temporary files left. */
static int leftovers(void) {
  DIR *d = opendir(folder);
  struct dirent *ent;
  int n = 0;
  while ((ent = readdir(d)))
    n += ent->d_name[0] == '.' && strcmp(ent->d_name, ".") != 0 &&
         strcmp(ent->d_name, "..") != 0;
  closedir(d);
  return n;
}

static int put_tile(void *user, const glint_tile *tile) {
  glint_error e;
  return glint_image_writer_put(user, tile, &e) != GLINT_OK;
}

static void same_file_as_glint_render(void **state) {
  (void)state;
  glint_scene *scene;
  ASSERT_OK(glint_scene_builtin("whitted", &scene, &e_));
  struct {
    const char *name;
    double gamma;
    glint_png_compression compression;
  } cases[] = {{"a.png", 1, GLINT_PNG_FAST},
               {"b.png", 2.2, GLINT_PNG_FAST},
               {"c.png", 1, GLINT_PNG_SMALLEST},
               {"d.bmp", 1, GLINT_PNG_FAST},
               {"e.ppm", 2.2, GLINT_PNG_FAST}};
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    glint_render_settings rs;
    glint_render_settings_default(&rs);
    rs.width = W;
    rs.height = H;
    rs.threads = 2;
    rs.gamma = cases[i].gamma;
    glint_image *image;
    ASSERT_OK(glint_render(scene, &rs, &image, NULL, &e_));
    char reference[512], name[64];
    snprintf(name, sizeof name, "reference-%s", cases[i].name);
    snprintf(reference, sizeof reference, "%s", in_folder(name));
    ASSERT_OK(
        glint_image_write_with(image, reference, cases[i].compression, &e_));
    glint_image_destroy(image);

    glint_world *world;
    glint_renderer *renderer;
    ASSERT_OK(glint_world_commit(scene, &world, NULL, &e_));
    ASSERT_OK(glint_renderer_create(world, &rs, &renderer, &e_));
    glint_world_destroy(world);
    glint_image_writer *writer;
    ASSERT_OK(glint_image_writer_open(in_folder(cases[i].name), W, H,
                                      cases[i].gamma, cases[i].compression,
                                      &writer, &e_));
    glint_frame_settings frame;
    glint_frame_settings_default(&frame);
    frame.tile = put_tile;
    frame.tile_user = writer;
    ASSERT_OK(glint_renderer_render(renderer, &frame, NULL, NULL, &e_));
    ASSERT_OK(glint_image_writer_finish(writer, &e_));
    assert_same_file(in_folder(cases[i].name), reference);
    glint_renderer_destroy(renderer);
  }
  assert_int_equal(leftovers(), 0);
  glint_scene_destroy(scene);
}

/* A film of every kind of value: below 0, in range, above 1, NaN. */
static glint_film *pattern(void) {
  glint_film *film;
  ASSERT_OK(glint_film_create(W, H, &film, &e_));
  float *p = glint_film_pixels(film);
  for (int i = 0; i < W * H * 3; i++)
    p[i] = i % 97 == 0 ? NAN : (float)(i % 131) / 100.0f - 0.15f;
  return film;
}

/* Puts the film's rectangle as a tile with the film's stride. */
static glint_status put_rect(glint_image_writer *writer, const glint_film *film,
                             int x, int y, int w, int h, glint_error *error) {
  glint_tile t = {x, y, w, h, NULL, (size_t)W * 3};
  t.pixels = glint_film_pixels_const(film) + ((size_t)y * W + x) * 3;
  return glint_image_writer_put(writer, &t, error);
}

static void tiles_in_any_order(void **state) {
  (void)state;
  glint_film *film = pattern();
  for (double gamma = 1; gamma < 3; gamma += 1.2) {
    const char *path = in_folder(gamma == 1 ? "order.png" : "order.ppm");
    glint_image_writer *writer;
    ASSERT_OK(glint_image_writer_open(path, W, H, gamma, GLINT_PNG_FAST,
                                      &writer, &e_));
    /* Bottom band first, in columns of uneven width, then the rest in rows
     * of varying height from the bottom up. */
    int split = 40;
    for (int x = 0; x < W; x += 30)
      ASSERT_OK(put_rect(writer, film, x, split, x + 30 <= W ? 30 : W - x,
                         H - split, &e_));
    for (int y = split; y > 0;) {
      int h = y >= 7 ? 7 : y;
      y -= h;
      ASSERT_OK(put_rect(writer, film, 0, y, W, h, &e_));
    }
    ASSERT_OK(glint_image_writer_finish(writer, &e_));
    glint_image *expected, *written;
    ASSERT_OK(glint_image_create(W, H, &expected, &e_));
    ASSERT_OK(glint_film_to_image(film, gamma, expected, &e_));
    ASSERT_OK(glint_image_read(path, &written, &e_));
    assert_memory_equal(glint_image_pixels(written),
                        glint_image_pixels(expected), (size_t)W * H * 3);
    glint_image_destroy(expected);
    glint_image_destroy(written);
  }
  glint_film_destroy(film);
}

/* Threads putting tiles at once, in about the order a renderer finishes
 * them, into an image of more bands than a writer holds before a put waits
 * for its encoder: every byte is the one glint_film_to_image gives. (A put
 * that waited once took a band another put had taken meanwhile, and that
 * put's pixels were lost: 4 runs in 30 went wrong.) */
enum { SW = 2048, SH = 2048, STILE = 32 };
typedef struct stress_job {
  glint_image_writer *writer;
  const float *pixels;
  atomic_int next; /* the next tile, row by row */
  atomic_int failed;
} stress_job;

static void *put_tiles(void *arg) {
  stress_job *job = arg;
  int columns = SW / STILE, count = columns * (SH / STILE);
  for (int i; (i = atomic_fetch_add(&job->next, 1)) < count;) {
    int x = i % columns * STILE, y = i / columns * STILE;
    glint_tile t = {x,
                    y,
                    STILE,
                    STILE,
                    job->pixels + ((size_t)y * SW + x) * 3,
                    (size_t)SW * 3};
    glint_error e;
    if (glint_image_writer_put(job->writer, &t, &e))
      atomic_store(&job->failed, 1);
  }
  return NULL;
}

static void threads_put_at_once(void **state) {
  (void)state;
  glint_film *film;
  ASSERT_OK(glint_film_create(SW, SH, &film, &e_));
  float *p = glint_film_pixels(film);
  for (size_t i = 0; i < (size_t)SW * SH * 3; i++)
    p[i] = (float)(i % 251) / 250.0f;
  glint_image *expected;
  ASSERT_OK(glint_image_create(SW, SH, &expected, &e_));
  ASSERT_OK(glint_film_to_image(film, 1, expected, &e_));
  enum { THREADS = 6 };
  for (int run = 0; run < 4; run++) {
    stress_job job = {NULL, p, 0, 0};
    ASSERT_OK(glint_image_writer_open_memory(GLINT_FORMAT_PPM, SW, SH, 1,
                                             GLINT_PNG_FAST, &job.writer, &e_));
    pthread_t threads[THREADS];
    for (int k = 0; k < THREADS; k++)
      assert_int_equal(pthread_create(&threads[k], NULL, put_tiles, &job), 0);
    for (int k = 0; k < THREADS; k++)
      pthread_join(threads[k], NULL);
    assert_false(atomic_load(&job.failed));
    void *bytes;
    size_t size;
    ASSERT_OK(glint_image_writer_finish_memory(job.writer, &bytes, &size, &e_));
    size_t pixels = (size_t)SW * SH * 3;
    assert_true(size > pixels);
    const uint8_t *got = (const uint8_t *)bytes + (size - pixels);
    const uint8_t *want = glint_image_pixels(expected);
    for (size_t i = 0; i < pixels; i++)
      if (got[i] != want[i])
        fail_msg("run %d: byte %zu of row %zu is %d, not %d", run, i,
                 i / (SW * 3), got[i], want[i]);
    glint_free(bytes);
  }
  glint_image_destroy(expected);
  glint_film_destroy(film);
}

/* A writer into memory encodes the bytes a writer of a file writes, and
 * glint_image_write_encoded puts them in a file whole; each writer ends
 * only its own way, and one missing pixels hands over nothing. */
static void memory_holds_the_file(void **state) {
  (void)state;
  glint_film *film = pattern();
  const char *names[] = {"mem.png", "mem.bmp", "mem.ppm"};
  const glint_image_format formats[] = {GLINT_FORMAT_PNG, GLINT_FORMAT_BMP,
                                        GLINT_FORMAT_PPM};
  for (int i = 0; i < 3; i++) {
    char file[512], copy[600];
    snprintf(file, sizeof file, "%s", in_folder(names[i]));
    snprintf(copy, sizeof copy, "%s.copy.%s", file, names[i] + 4);
    glint_image_writer *writer;
    ASSERT_OK(
        glint_image_writer_open(file, W, H, 2.2, GLINT_PNG_FAST, &writer, &e_));
    ASSERT_OK(put_rect(writer, film, 0, 0, W, H, &e_));
    ASSERT_OK(glint_image_writer_finish(writer, &e_));
    ASSERT_OK(glint_image_writer_open_memory(formats[i], W, H, 2.2,
                                             GLINT_PNG_FAST, &writer, &e_));
    ASSERT_OK(put_rect(writer, film, 0, 30, W, H - 30, &e_));
    ASSERT_OK(put_rect(writer, film, 0, 0, W, 30, &e_));
    void *bytes = NULL;
    size_t size = 0;
    ASSERT_OK(glint_image_writer_finish_memory(writer, &bytes, &size, &e_));
    ASSERT_OK(glint_image_write_encoded(copy, bytes, size, &e_));
    glint_free(bytes);
    assert_same_file(file, copy);
    unlink(file);
    unlink(copy);
  }
  glint_error e;
  glint_image_writer *writer;
  ASSERT_OK(glint_image_writer_open_memory(GLINT_FORMAT_PNG, W, H, 1,
                                           GLINT_PNG_FAST, &writer, &e_));
  ASSERT_OK(put_rect(writer, film, 0, 0, W, H - 1, &e_));
  void *bytes = NULL;
  size_t size = 0;
  assert_int_equal(glint_image_writer_finish_memory(writer, &bytes, &size, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "only 60 of the image's 61 rows"));
  assert_null(bytes);
  ASSERT_OK(glint_image_writer_open_memory(GLINT_FORMAT_PPM, W, H, 1,
                                           GLINT_PNG_FAST, &writer, &e_));
  assert_int_equal(glint_image_writer_finish(writer, &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "glint_image_writer_finish_memory"));
  ASSERT_OK(glint_image_writer_open(in_folder("mem.bmp"), W, H, 1,
                                    GLINT_PNG_FAST, &writer, &e_));
  assert_int_equal(glint_image_writer_finish_memory(writer, &bytes, &size, &e),
                   GLINT_E_ARGUMENT);
  assert_int_equal(glint_image_writer_open_memory(GLINT_FORMAT_UNKNOWN, W, H, 1,
                                                  GLINT_PNG_FAST, &writer, &e),
                   GLINT_E_ARGUMENT);
  assert_int_equal(glint_image_write_encoded(in_folder("x.txt"), "a", 1, &e),
                   GLINT_E_ARGUMENT);
  /* Bytes that are not a file of the extension's format (none, another
   * format's, a damaged start) do not replace the file there. */
  char kept[600], kbmp[600], kppm[600];
  snprintf(kept, sizeof kept, "%s", in_folder("kept.png"));
  snprintf(kbmp, sizeof kbmp, "%s", in_folder("k.bmp"));
  snprintf(kppm, sizeof kppm, "%s", in_folder("k.ppm"));
  FILE *f = fopen(kept, "wb");
  fputs("the user's file", f);
  fclose(f);
  static const char bmp[] = "BM\x3e\0\0\0\0\0";
  const struct {
    const char *path, *bytes;
    size_t size;
    const char *want;
  } bad[] = {
      {kept, "", 0, "kept.png: the 0 bytes given are not a PNG file"},
      {kept, bmp, 8, "kept.png: the 8 bytes given are not a PNG file"},
      {kept, "\x89PNG\r\n\x1a", 7, "the 7 bytes given are not a PNG"},
      {kbmp, "\x89PNG\r\n\x1a\n\0", 9, "not a BMP file"},
      {kppm, "P3\n1 1\n", 7, "not a binary PPM file"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    assert_int_equal(
        glint_image_write_encoded(bad[i].path, bad[i].bytes, bad[i].size, &e),
        GLINT_E_ARGUMENT);
    if (!strstr(e.message, bad[i].want))
      fail_msg("'%s' lacks '%s'", e.message, bad[i].want);
  }
  assert_int_equal(glint_image_write_encoded(kept, NULL, 0, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "bytes is NULL"));
  char buf[32] = "";
  f = fopen(kept, "rb");
  assert_non_null(fgets(buf, sizeof buf, f));
  fclose(f);
  assert_string_equal(buf, "the user's file");
  unlink(kept);
  assert_int_equal(leftovers(), 0);
  glint_film_destroy(film);
}

static void incomplete_writes_nothing(void **state) {
  (void)state;
  glint_film *film = pattern();
  const char *path = in_folder("keep.png");
  FILE *f = fopen(path, "wb");
  fputs("the user's file", f);
  fclose(f);
  glint_image_writer *writer;
  glint_error e;

  /* Missing rows: finish refuses and says how many were complete. */
  ASSERT_OK(
      glint_image_writer_open(path, W, H, 1, GLINT_PNG_FAST, &writer, &e_));
  ASSERT_OK(put_rect(writer, film, 0, 0, W, 20, &e_));
  ASSERT_OK(put_rect(writer, film, 0, 21, W, H - 21, &e_));
  assert_int_equal(glint_image_writer_finish(writer, &e), GLINT_E_ARGUMENT);
  /* all the complete rows, not those above the first gap (it said 20) */
  assert_non_null(strstr(e.message, "only 60 of the image's 61 rows"));
  assert_non_null(strstr(e.message, "keep.png"));

  /* A row short of one pixel. */
  ASSERT_OK(
      glint_image_writer_open(path, W, H, 1, GLINT_PNG_FAST, &writer, &e_));
  ASSERT_OK(put_rect(writer, film, 0, 0, W - 1, H, &e_));
  assert_int_equal(glint_image_writer_finish(writer, &e), GLINT_E_ARGUMENT);

  /* Discarded, complete or not. */
  ASSERT_OK(
      glint_image_writer_open(path, W, H, 1, GLINT_PNG_FAST, &writer, &e_));
  ASSERT_OK(put_rect(writer, film, 0, 0, W, H, &e_));
  glint_image_writer_discard(writer);
  ASSERT_OK(
      glint_image_writer_open(path, W, H, 1, GLINT_PNG_FAST, &writer, &e_));
  glint_image_writer_discard(writer);
  glint_image_writer_discard(NULL);

  long size;
  char *kept = slurp(path, &size);
  assert_string_equal(kept, "the user's file");
  free(kept);
  assert_int_equal(leftovers(), 0);
  glint_film_destroy(film);
}

/* Writing that fails part-way (the file-size limit is hit while the encoder
 * runs) is reported by finish (and by the puts after it, which lets a tile
 * callback cancel the frame), and leaves the existing file as it was. */
static void failed_writing_keeps_existing_file(void **state) {
  (void)state;
  const char *formats[] = {"limit.png", "limit.ppm", "limit.bmp"};
  for (int i = 0; i < 3; i++) {
    const char *path = in_folder(formats[i]);
    FILE *f = fopen(path, "wb");
    fputs("original", f);
    fclose(f);
    pid_t pid = fork();
    if (pid == 0) {
      signal(SIGXFSZ, SIG_IGN);
      struct rlimit rl = {1000, 1000};
      setrlimit(RLIMIT_FSIZE, &rl);
      glint_film *film = pattern();
      glint_image_writer *writer;
      glint_error e;
      if (glint_image_writer_open(path, W, H, 1, GLINT_PNG_FAST, &writer, &e))
        _exit(2);
      for (int y = 0; y < H; y++)
        put_rect(writer, film, 0, y, W, 1, &e);
      glint_status st = glint_image_writer_finish(writer, &e);
      glint_film_destroy(film);
      _exit(st == GLINT_E_IO && strstr(e.message, formats[i]) &&
                    strstr(e.message, "writing failed")
                ? 0
                : 1);
    }
    int status;
    waitpid(pid, &status, 0);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    long size;
    char *kept = slurp(path, &size);
    assert_string_equal(kept, "original");
    free(kept);
  }
  assert_int_equal(leftovers(), 0);
}

static void refuses_bad_tiles(void **state) {
  (void)state;
  glint_film *film = pattern();
  glint_image_writer *writer;
  glint_error e;
  const char *path = in_folder("bad.png");
  ASSERT_OK(
      glint_image_writer_open(path, W, H, 1, GLINT_PNG_FAST, &writer, &e_));
  glint_tile outside = {W - 4, 0, 8, 8, glint_film_pixels_const(film), W * 3};
  assert_int_equal(glint_image_writer_put(writer, &outside, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "outside the 83x61 image"));
  glint_tile negative = {-1, 0, 4, 4, glint_film_pixels_const(film), W * 3};
  assert_int_equal(glint_image_writer_put(writer, &negative, &e),
                   GLINT_E_ARGUMENT);
  assert_int_equal(glint_image_writer_put(writer, NULL, &e), GLINT_E_ARGUMENT);
  glint_tile no_pixels = {0, 0, 4, 4, NULL, W * 3};
  assert_int_equal(glint_image_writer_put(writer, &no_pixels, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "the tile's pixels are NULL"));
  glint_tile empty = {1, 1, 0, 0, glint_film_pixels_const(film), W * 3};
  assert_int_equal(glint_image_writer_put(writer, &empty, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "tile 0x0 at (1, 1) is empty"));
  glint_tile narrow = {0, 0, 4, 4, glint_film_pixels_const(film), 3};
  assert_int_equal(glint_image_writer_put(writer, &narrow, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "stride 3 is less than its 12 floats"));
  /* (its floats counted without overflow) */
  glint_tile wide = {6, 0, INT_MAX, 2, glint_film_pixels_const(film), 6};
  assert_int_equal(glint_image_writer_put(writer, &wide, &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "stride 6 is less than its 6442450941"));
  assert_int_equal(glint_image_writer_finish(writer, &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "a tile was refused, so the image cannot"));

  /* Every refusal spoils the image, a bad stride or no pixels as much as
   * a tile outside it (those two let the image be finished, without the
   * tile the caller meant to give). */
  for (int bad = 0; bad < 3; bad++) {
    ASSERT_OK(
        glint_image_writer_open(path, W, H, 1, GLINT_PNG_FAST, &writer, &e_));
    glint_tile tile = {0, 0, W, H, glint_film_pixels_const(film), W * 3};
    if (bad == 0)
      tile.stride = 3;
    else if (bad == 1)
      tile.pixels = NULL;
    assert_int_equal(
        glint_image_writer_put(writer, bad == 2 ? NULL : &tile, &e),
        GLINT_E_ARGUMENT);
    tile.stride = W * 3;
    tile.pixels = glint_film_pixels_const(film);
    assert_int_equal(glint_image_writer_put(writer, &tile, &e),
                     GLINT_E_ARGUMENT);
    assert_non_null(strstr(e.message, "an earlier tile was refused"));
    assert_int_equal(glint_image_writer_finish(writer, &e), GLINT_E_ARGUMENT);
    assert_int_equal(access(path, F_OK), -1);
  }

  ASSERT_OK(
      glint_image_writer_open(path, W, H, 1, GLINT_PNG_FAST, &writer, &e_));
  ASSERT_OK(put_rect(writer, film, 0, 0, W, 10, &e_));
  assert_int_equal(put_rect(writer, film, 5, 5, 10, 10, &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "tile 10x10 at (5, 5) repeats pixels"));
  /* The writer stays failed: later puts and finish say so. */
  assert_int_equal(put_rect(writer, film, 0, 10, W, H - 10, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "an earlier tile was refused"));
  assert_int_equal(glint_image_writer_finish(writer, &e), GLINT_E_ARGUMENT);
  assert_int_equal(access(path, F_OK), -1);

  /* The left half of every row twice is not a whole image (counted by
   * pixels a row, it passed for one, and the right half's unset bytes
   * were written). */
  ASSERT_OK(
      glint_image_writer_open(path, W, H, 1, GLINT_PNG_FAST, &writer, &e_));
  ASSERT_OK(put_rect(writer, film, 0, 0, W / 2, H, &e_));
  assert_int_equal(put_rect(writer, film, 0, 0, W / 2, H, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "repeats pixels"));
  assert_int_equal(put_rect(writer, film, W / 2, 0, W - W / 2, H, &e),
                   GLINT_E_ARGUMENT);
  assert_int_equal(glint_image_writer_finish(writer, &e), GLINT_E_ARGUMENT);
  assert_int_equal(access(path, F_OK), -1);
  assert_int_equal(leftovers(), 0);
  assert_int_equal(glint_image_writer_finish(NULL, &e), GLINT_E_ARGUMENT);
  glint_film_destroy(film);
}

static void expect_open_error(const char *path, int w, int h, double gamma,
                              int compression, const char *words) {
  glint_image_writer *writer = NULL;
  glint_error e;
  assert_int_not_equal(
      glint_image_writer_open(path, w, h, gamma,
                              (glint_png_compression)compression, &writer, &e),
      GLINT_OK);
  if (!strstr(e.message, words))
    fail_msg("'%s' %dx%d gamma %g: message '%s' lacks '%s'",
             path ? path : "(null)", w, h, gamma, e.message, words);
}

static void refuses_bad_opens(void **state) {
  (void)state;
  /* (not the enum's number: the path's extension is the user's word) */
  expect_open_error(in_folder("x.tiff"), W, H, 1, 0,
                    "x.tiff: unknown image format (use .png, .bmp or .ppm)");
  expect_open_error(NULL, W, H, 1, 0, "glint_image_writer_open: path is NULL");
  /* named as the caller called it (it said glint_image_write_with) */
  glint_error null_e;
  assert_int_equal(glint_image_write(NULL, in_folder("n.png"), &null_e),
                   GLINT_E_ARGUMENT);
  assert_string_equal(null_e.message, "glint_image_write: image is NULL");
  expect_open_error("/nonexistent-folder/x.png", W, H, 1, 0,
                    "cannot write here");
  expect_open_error(folder, W, H, 1, 0, "unknown image format");
  char dir[512];
  snprintf(dir, sizeof dir, "%s", in_folder("dir.png"));
  mkdir(dir, 0755);
  expect_open_error(dir, W, H, 1, 0, "is a directory");
  rmdir(dir);
  expect_open_error(in_folder("x.png"), 0, H, 1, 0, "image size 0x61");
  expect_open_error(in_folder("x.png"), W, GLINT_MAX_DIMENSION + 1, 1, 0,
                    "outside 1..16384");
  expect_open_error(in_folder("x.png"), W, H, 0, 0, "gamma");
  expect_open_error(in_folder("x.png"), W, H, NAN, 0, "gamma");
  /* libpng cannot record 1/1e-308, and 1e308 made every byte 0 or 255 */
  expect_open_error(in_folder("x.png"), W, H, 1e-308, 0,
                    "gamma 1e-308 is outside 0.01..100");
  expect_open_error(in_folder("x.ppm"), W, H, 1e308, 0,
                    "gamma 1e+308 is outside 0.01..100");
  /* not rounded into the range it is outside of (it said "gamma 100") */
  expect_open_error(in_folder("x.ppm"), W, H, 100.0001, 0,
                    "gamma 100.0001 is outside 0.01..100");
  expect_open_error(in_folder("x.png"), W, H, 1, 7, "unknown PNG compression");
  /* into memory: a format that is none of the three */
  glint_image_writer *writer = NULL;
  glint_error e;
  assert_int_equal(glint_image_writer_open_memory((glint_image_format)42, W, H,
                                                  1, GLINT_PNG_FAST, &writer,
                                                  &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "unknown image format 42"));
  assert_null(writer);
  assert_int_equal(leftovers(), 0);
}

/* A PNG is held in bands of rows while it is written, not whole: writing
 * an image of 192 MiB of 8-bit pixels leaves the process's peak memory a
 * fraction of that. (This test runs first, so that no other test's memory
 * is the peak.) */
static void a_png_holds_bands_not_the_image(void **state) {
  (void)state;
  enum { BW = 8192, BH = 8192, ROWS = 32 };
  float *rows = malloc(sizeof(float) * BW * ROWS * 3);
  assert_non_null(rows);
  for (int i = 0; i < BW * ROWS * 3; i++)
    rows[i] = (float)(i % (BW * 3)) / (BW * 3);
  const char *path = in_folder("big.png");
  glint_image_writer *writer;
  ASSERT_OK(
      glint_image_writer_open(path, BW, BH, 2.2, GLINT_PNG_FAST, &writer, &e_));
  for (int y = 0; y < BH; y += ROWS) {
    glint_tile t = {0, y, BW, ROWS, rows, (size_t)BW * 3};
    ASSERT_OK(glint_image_writer_put(writer, &t, &e_));
  }
  ASSERT_OK(glint_image_writer_finish(writer, &e_));
  free(rows);
  struct rusage usage;
  assert_int_equal(getrusage(RUSAGE_SELF, &usage), 0);
  long image_kib = (long)BW * BH * 3 / 1024;
  if (usage.ru_maxrss >= image_kib / 4)
    fail_msg("peak memory %ld KiB for an image of %ld KiB", usage.ru_maxrss,
             image_kib);
  struct stat sb;
  assert_int_equal(stat(path, &sb), 0);
  assert_true(sb.st_size > 0);
  unlink(path);
}

/* A renderer needs somewhere to put the frame: a film or a tile callback. */
static void needs_a_film_or_tiles(void **state) {
  (void)state;
  glint_scene *scene;
  glint_world *world;
  glint_renderer *renderer;
  ASSERT_OK(glint_scene_builtin("whitted", &scene, &e_));
  ASSERT_OK(glint_world_commit(scene, &world, NULL, &e_));
  glint_scene_destroy(scene);
  ASSERT_OK(glint_renderer_create(world, NULL, &renderer, &e_));
  glint_world_destroy(world);
  glint_error e;
  assert_int_equal(glint_renderer_render(renderer, NULL, NULL, NULL, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "no film to render into"));
  glint_renderer_destroy(renderer);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(a_png_holds_bands_not_the_image),
      cmocka_unit_test(same_file_as_glint_render),
      cmocka_unit_test(tiles_in_any_order),
      cmocka_unit_test(threads_put_at_once),
      cmocka_unit_test(memory_holds_the_file),
      cmocka_unit_test(incomplete_writes_nothing),
      cmocka_unit_test(failed_writing_keeps_existing_file),
      cmocka_unit_test(refuses_bad_tiles),
      cmocka_unit_test(refuses_bad_opens),
      cmocka_unit_test(needs_a_film_or_tiles),
  };
  return cmocka_run_group_tests(tests, make_folder, remove_folder);
}
