/* Films: the 8-bit conversion against hand-computed bytes, and the linear
 * writers read back: PFM parsed by hand (header, little-endian floats,
 * bottom row first), OpenEXR through OpenEXRCore's reader (SKIPPED in
 * builds without OpenEXR); every error a user can meet. */
#include "test_util.h"

#include "image/image.h"

#include <math.h>
#include <pmmintrin.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef GLINT_HAVE_EXR
#include <openexr.h>
#endif

#define FW 5
#define FH 3

static glint_film *ramp(void) {
  glint_film *film;
  ASSERT_OK(glint_film_create(FW, FH, &film, &e_));
  float *p = glint_film_pixels(film);
  for (int i = 0; i < FW * FH * 3; i++)
    p[i] = (float)i * 0.125f - 1.0f; /* negative, in range and above 1 */
  return film;
}

static char *temp_path(const char *name) {
  static char path[256];
  snprintf(path, sizeof path, "%s/glint-film-%d-%s",
           getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid(), name);
  return path;
}

static void converts_to_bytes(void **state) {
  (void)state;
  glint_film *film = ramp();
  glint_image *image;
  ASSERT_OK(glint_image_create(FW, FH, &image, &e_));
  ASSERT_OK(glint_film_to_image(film, 1, image, &e_));
  const float *p = glint_film_pixels(film);
  for (int i = 0; i < FW * FH * 3; i++)
    assert_int_equal(glint_image_pixels(image)[i], expected_byte(p[i]));
  ASSERT_OK(glint_film_to_image(film, 2.2, image, &e_));
  for (int i = 0; i < FW * FH * 3; i++)
    assert_int_equal(
        glint_image_pixels(image)[i],
        expected_byte(p[i] > 0 ? pow(p[i] < 1 ? p[i] : 1, 1 / 2.2) : 0));
  glint_error e;
  assert_int_equal(glint_film_to_image(film, 0, image, &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "gamma"));
  glint_image *small;
  ASSERT_OK(glint_image_create(FW, FH + 1, &small, &e_));
  assert_int_equal(glint_film_to_image(film, 1, small, &e), GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "does not fit"));
  glint_image_destroy(small);
  glint_image_destroy(image);
  glint_film_destroy(film);
}

/* The bytes of the conversion's definition, in float as glint computes
 * them: round(255 c) of c clamped to [0, 1], and 0 for a NaN. */
static int byte_of(float c) {
  if (!(c > 0))
    return 0;
  if (c >= 1)
    return 255;
  return (int)(255.0f * c + 0.5f);
}

/* Values where a conversion can go wrong (NaN, infinities, signed zeros,
 * denormals, the rounding boundaries of the first and last steps, floats
 * too large for an int), 23 of them cycled through 105 pixels' channels:
 * each lands in every lane of the 16-wide SIMD loop and in the scalar
 * tail, so the two paths must agree with the definition everywhere. */
static void converts_special_values(void **state) {
  (void)state;
  const float b0 = 0.5f / 255, b1 = 254.5f / 255;
  const float special[23] = {NAN,
                             -NAN,
                             -INFINITY,
                             INFINITY,
                             -0.0f,
                             0.0f,
                             1e-45f,
                             1e-30f,
                             nextafterf(b0, 0),
                             b0,
                             nextafterf(b0, 1),
                             nextafterf(b1, 0),
                             b1,
                             nextafterf(b1, 1),
                             nextafterf(1, 0),
                             1.0f,
                             nextafterf(1, 2),
                             3e9f,
                             1e30f,
                             3.4e38f,
                             -1e30f,
                             0.25f,
                             0.75f};
  glint_film *film;
  glint_image *image;
  ASSERT_OK(glint_film_create(7, 5, &film, &e_));
  ASSERT_OK(glint_image_create(7, 5, &image, &e_));
  float *p = glint_film_pixels(film);
  for (int i = 0; i < 7 * 5 * 3; i++)
    p[i] = special[i % 23];
  ASSERT_OK(glint_film_to_image(film, 1, image, &e_));
  for (int i = 0; i < 7 * 5 * 3; i++)
    assert_int_equal(glint_image_pixels(image)[i], byte_of(special[i % 23]));
  /* The definition against hand-computed bytes: 255 x 0.25 + 0.5 = 64.25,
   * 255 x 0.75 + 0.5 = 191.75, and 255 b1 + 0.5 = 255 (b1 is the last
   * step's lower edge, 254.5/255). */
  assert_int_equal(byte_of(0.25f), 64);
  assert_int_equal(byte_of(0.75f), 191);
  assert_int_equal(byte_of(b1), 255);
  assert_int_equal(byte_of(NAN), 0);
  glint_image_destroy(image);
  glint_film_destroy(film);
}

/* gli_byte_encode against the formula (powf for every value) for gammas
 * from 0.01 to 100: every float within 2048 steps of each threshold, where
 * a wrong table shows first, and every 4096th float in [0, 1]. */
static void encoding_matches_the_formula(void **state) {
  (void)state;
  static const double gammas[] = {2.2, 1 / 2.2, 1.8, 3.7, 0.37, 0.01, 100};
  static gli_byte_encoding enc;
  enum { SPAN = 4096 };
  static float values[SPAN + 1];
  static uint8_t bytes[SPAN + 1];
  for (size_t g = 0; g < sizeof gammas / sizeof *gammas; g++) {
    gli_byte_encoding_init(&enc, gammas[g]);
    for (int k = 0; k <= 256; k++) {
      uint32_t from = 0;
      if (k >= 1 && k <= 255) {
        float t = enc.threshold[k];
        memcpy(&from, &t, sizeof from);
        from = from > SPAN / 2 ? from - SPAN / 2 : 0;
      }
      for (int i = 0; i <= SPAN; i++) {
        /* k 0 and 256: the sparse sweep of [0, 1] instead. */
        uint32_t bits = k == 0     ? (uint32_t)i * 0x3F800u
                        : k == 256 ? (uint32_t)i * 0x3F800u + 0x1234u
                                   : from + (uint32_t)i;
        memcpy(&values[i], &bits, sizeof bits);
      }
      gli_byte_encode(&enc, values, bytes, SPAN + 1);
      for (int i = 0; i <= SPAN; i++)
        if (bytes[i] != gli_byte_encode_one(values[i], gammas[g]))
          fail_msg("gamma %g: %a encodes as %d, the formula says %d", gammas[g],
                   (double)values[i], bytes[i],
                   gli_byte_encode_one(values[i], gammas[g]));
    }
    const float edge[] = {NAN, -INFINITY, -1, -0.0f, 0, 1, 2, INFINITY};
    uint8_t out[8];
    gli_byte_encode(&enc, edge, out, 8);
    const uint8_t want[] = {0, 0, 0, 0, 0, 255, 255, 255};
    assert_memory_equal(out, want, 8);
    for (int i = 0; i < 8; i++) { /* one at a time: the scalar tail */
      gli_byte_encode(&enc, edge + i, out + i, 1);
      assert_int_equal(out[i], want[i]);
    }
  }
  /* The one-comparison path is the one the usual gammas take (the sweeps
   * above test it for 2.2, 1.8 and 3.7, and the general loop for the
   * others). */
  gli_byte_encoding_init(&enc, 2.2);
  assert_true(enc.one_step);
  gli_byte_encoding_init(&enc, 0.37);
  assert_false(enc.one_step);
}

/* Render workers run with denormals as zero and flushed to zero (DAZ and
 * FTZ, render/renderer.c), and encode their tiles so: the bytes must be
 * those encoded without. At gamma 16 the first thresholds are denormals,
 * which a float comparison under DAZ takes for 0 (0 became 1). */
static void encoding_is_the_same_with_denormals_as_zero(void **state) {
  (void)state;
  static gli_byte_encoding enc;
  enum { N = 4099 }; /* not a multiple of 4: the scalar tail too */
  static float values[N];
  static uint8_t plain[N], daz[N];
  for (int i = 0; i < N; i++) /* normal floats of [0, 1.5), zeros, NaN */
    values[i] = i % 5 == 0 ? 0.0f : i % 7 == 0 ? NAN : 1.5f * i / N;
  const double gammas[] = {16, 2.2, 0.37};
  for (size_t g = 0; g < sizeof gammas / sizeof *gammas; g++) {
    gli_byte_encoding_init(&enc, gammas[g]);
    gli_byte_encode(&enc, values, plain, N);
    unsigned saved = _mm_getcsr();
    _mm_setcsr(saved | _MM_FLUSH_ZERO_ON | _MM_DENORMALS_ZERO_ON);
    gli_byte_encode(&enc, values, daz, N);
    _mm_setcsr(saved);
    for (int i = 0; i < N; i++)
      if (plain[i] != daz[i])
        fail_msg("gamma %g: %a encodes as %d, with DAZ as %d", gammas[g],
                 (double)values[i], plain[i], daz[i]);
    assert_int_equal(plain[0], 0);
  }
}

static void writes_pfm(void **state) {
  (void)state;
  glint_film *film = ramp();
  const char *path = temp_path("a.pfm");
  ASSERT_OK(glint_film_write(film, path, &e_));
  FILE *f = fopen(path, "rb");
  assert_non_null(f);
  char magic[3] = {0};
  int w = 0, h = 0;
  double scale = 0;
  assert_int_equal(fscanf(f, "%2s %d %d %lf", magic, &w, &h, &scale), 4);
  assert_string_equal(magic, "PF");
  assert_int_equal(w, FW);
  assert_int_equal(h, FH);
  assert_true(scale < 0); /* little-endian */
  assert_int_equal(fgetc(f), '\n');
  const float *p = glint_film_pixels(film);
  for (int y = FH - 1; y >= 0; y--) /* bottom row first */
    for (int i = 0; i < FW * 3; i++) {
      unsigned char b[4];
      assert_int_equal(fread(b, 1, 4, f), 4);
      uint32_t bits = (uint32_t)b[0] | (uint32_t)b[1] << 8 |
                      (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
      float v;
      memcpy(&v, &bits, 4);
      assert_true(v == p[(size_t)y * FW * 3 + i]);
    }
  assert_int_equal(fgetc(f), EOF);
  fclose(f);
  unlink(path);
  glint_film_destroy(film);
}

static void writes_exr(void **state) {
  (void)state;
#ifndef GLINT_HAVE_EXR
  skip();
#else
  glint_film *film = ramp();
  const char *path = temp_path("b.exr");
  ASSERT_OK(glint_film_write(film, path, &e_));
  exr_context_t ctx;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  assert_int_equal(exr_start_read(&ctx, path, &init), EXR_ERR_SUCCESS);
  exr_attr_box2i_t box;
  assert_int_equal(exr_get_data_window(ctx, 0, &box), EXR_ERR_SUCCESS);
  assert_int_equal(box.max.x - box.min.x + 1, FW);
  assert_int_equal(box.max.y - box.min.y + 1, FH);
  int lines;
  assert_int_equal(exr_get_scanlines_per_chunk(ctx, 0, &lines),
                   EXR_ERR_SUCCESS);
  float back[FW * FH * 3];
  memset(back, 0, sizeof back);
  exr_decode_pipeline_t dec;
  int started = 0;
  for (int y = 0; y < FH; y += lines) {
    exr_chunk_info_t chunk;
    assert_int_equal(
        exr_read_scanline_chunk_info(ctx, 0, box.min.y + y, &chunk),
        EXR_ERR_SUCCESS);
    assert_int_equal(started ? exr_decoding_update(ctx, 0, &chunk, &dec)
                             : exr_decoding_initialize(ctx, 0, &chunk, &dec),
                     EXR_ERR_SUCCESS);
    assert_int_equal(dec.channel_count, 3);
    for (int c = 0; c < 3; c++) {
      exr_coding_channel_info_t *ch = &dec.channels[c];
      int k = ch->channel_name[0] == 'R'   ? 0
              : ch->channel_name[0] == 'G' ? 1
                                           : 2;
      ch->decode_to_ptr = (uint8_t *)(back + (size_t)y * FW * 3 + k);
      ch->user_pixel_stride = 3 * sizeof(float);
      ch->user_line_stride = FW * 3 * sizeof(float);
      ch->user_bytes_per_element = sizeof(float);
      ch->user_data_type = EXR_PIXEL_FLOAT;
    }
    if (!started)
      assert_int_equal(exr_decoding_choose_default_routines(ctx, 0, &dec),
                       EXR_ERR_SUCCESS);
    started = 1;
    assert_int_equal(exr_decoding_run(ctx, 0, &dec), EXR_ERR_SUCCESS);
  }
  exr_decoding_destroy(ctx, &dec);
  exr_finish(&ctx);
  assert_memory_equal(back, glint_film_pixels(film), sizeof back);
  unlink(path);
  glint_film_destroy(film);
#endif
}

static void expect_write_error(const glint_film *film, const char *path,
                               const char *words) {
  glint_error e;
  assert_int_not_equal(glint_film_write(film, path, &e), GLINT_OK);
  if (!strstr(e.message, words))
    fail_msg("'%s': message '%s' lacks '%s'", path, e.message, words);
}

static void refuses_bad_paths(void **state) {
  (void)state;
  glint_film *film = ramp();
  expect_write_error(film, temp_path("c.tiff"), "unknown film format");
  expect_write_error(film, "/nonexistent-folder/d.pfm", "cannot write here");
  char dir[256];
  snprintf(dir, sizeof dir, "%s", temp_path("dir.pfm"));
  mkdir(dir, 0755);
  expect_write_error(film, dir, "is a directory");
  rmdir(dir);
  glint_error e;
  glint_film *none;
  assert_int_equal(glint_film_create(GLINT_MAX_DIMENSION + 1, 1, &none, &e),
                   GLINT_E_ARGUMENT);
  assert_non_null(strstr(e.message, "film size"));
  glint_film_destroy(film);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(converts_to_bytes),
      cmocka_unit_test(converts_special_values),
      cmocka_unit_test(encoding_matches_the_formula),
      cmocka_unit_test(encoding_is_the_same_with_denormals_as_zero),
      cmocka_unit_test(writes_pfm),
      cmocka_unit_test(writes_exr),
      cmocka_unit_test(refuses_bad_paths),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
