/* The 8-bit encoding of linear values (docs/specification.md §4): clamp to
 * [0, 1], then c^(1/gamma), then round(255 c); a NaN becomes 0. Every
 * frame of every backend passes through here, tile by tile, so neither
 * case may cost much per value:
 *  - gamma 1: 16 values at a time in SSE2;
 *  - any other gamma: powf runs a few times per step of the output, not
 *    once per value. The encoding is monotone, so a value's byte is the
 *    number of thresholds (the least value reaching each byte 1..255) at
 *    or below it; a table indexed by the value's top 16 bits (its exponent
 *    and 7 bits of mantissa) gives the byte at the start of its bin, and
 *    comparisons with the next thresholds finish. Where no bin holds more
 *    than one threshold (gamma 1 to 18, the usual 2.2 included) that is
 *    one comparison, made 4 values at a time without a branch: a branch
 *    on each value's bin mispredicts along every gradient of an image, and
 *    the branching loop took 1.75 ms for a 640x480 frame of Whitted's
 *    scene where this takes 0.9 ms (gamma 2.2, best of 9, Zen 5). The
 *    bytes are those of powf itself: each threshold is found on powf's own
 *    results, from the inverse formula's estimate by doubling steps and
 *    bisection. */
#include "image/image.h"

#include <emmintrin.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* round(255 c) of c clamped to [0, 1], as 255 c + 1/2 clamped to
 * [0, 255.5] and truncated: the same bytes, in the order that max/min
 * instructions take (a NaN fails t > 0 and becomes 0). */
static inline uint8_t to_byte(float c) {
  float t = 255.0f * c + 0.5f;
  t = t > 0.0f ? t : 0.0f;
  t = t < 255.5f ? t : 255.5f;
  return (uint8_t)(int)t;
}

/* to_byte for 16 values at a time (gcc 12 spends about 10 instructions a
 * value on the scalar loop; these take under 2). SSE2 is part of x86-64, so
 * this needs no CPUID dispatch. maxps returns its second operand when the
 * first is NaN, as to_byte does. */
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

static float float_of(uint32_t bits) {
  float f;
  memcpy(&f, &bits, sizeof f);
  return f;
}

static uint32_t bits_of(float f) {
  uint32_t bits;
  memcpy(&bits, &f, sizeof bits);
  return bits;
}

#define ONE_BITS 0x3F800000u /* 1.0f; positive floats order as their bits */
#define BIN_SHIFT 16
#define BELOW_ONE 0x1.fffffep-1f /* the float below 1 */

uint8_t gli_byte_encode_one(float c, double gamma) {
  if (!(c > 0))
    return 0;
  return to_byte(powf(c < 1 ? c : 1.0f, (float)(1.0 / gamma)));
}

/* Whether c (in (0, 1]) encodes as k or more. */
static int reaches(uint32_t bits, int k, double gamma) {
  return gli_byte_encode_one(float_of(bits), gamma) >= k;
}

/* The least float in (lo, ONE_BITS] that encodes as k or more, where lo
 * encodes as less than k (lo may be 0) and 1 as 255. The inverse of the
 * formula, ((k - 1/2) / 255)^gamma, lands within a few ulps of it for
 * every gamma; steps of 1, 2, 4, ... ulps from there bracket it, and
 * bisection closes the bracket: about 2 log2(distance) + 2 powf. */
static uint32_t threshold_bits(int k, double gamma, uint32_t lo) {
  float guess = (float)pow((k - 0.5) / 255.0, gamma);
  uint32_t g = bits_of(guess);
  g = g <= lo ? lo + 1 : g > ONE_BITS ? ONE_BITS : g;
  uint32_t hi;
  if (reaches(g, k, gamma)) {
    hi = g; /* step down until below */
    for (uint32_t step = 1;; step *= 2) {
      uint32_t below = hi - lo > step ? hi - step : lo;
      if (below == lo || !reaches(below, k, gamma)) {
        lo = below;
        break;
      }
      hi = below;
    }
  } else {
    lo = g; /* step up until reached */
    for (uint32_t step = 1;; step *= 2) {
      uint32_t above = ONE_BITS - lo > step ? lo + step : ONE_BITS;
      if (above == ONE_BITS || reaches(above, k, gamma)) {
        hi = above;
        break;
      }
      lo = above;
    }
  }
  while (hi - lo > 1) {
    uint32_t mid = lo + (hi - lo) / 2;
    if (reaches(mid, k, gamma))
      hi = mid;
    else
      lo = mid;
  }
  return hi;
}

void gli_byte_encoding_init(gli_byte_encoding *enc, double gamma) {
  enc->gamma = gamma;
  enc->one_step = 0;
  if (gamma == 1)
    return;
  uint32_t lo = 0;
  for (int k = 1; k <= 255; k++) {
    uint32_t hi = threshold_bits(k, gamma, lo);
    enc->threshold[k] = float_of(hi);
    lo = hi - 1; /* encodes as less than k, so less than k + 1 */
  }
  enc->threshold[0] = 0;
  enc->threshold[256] = INFINITY; /* ends every search at 255 */
  int k = 0;
  for (uint32_t bin = 0; bin < GLI_BYTE_BINS; bin++) {
    float start = float_of(bin << BIN_SHIFT);
    while (k < 255 && enc->threshold[k + 1] <= start)
      k++;
    enc->start[bin] = (uint8_t)k;
  }
  /* One comparison finishes every value when no bin holds two thresholds
   * (a bin's bytes run from its start to the next bin's, 255 at 1) and the
   * float below 1, which stands for every value from 1 up, encodes as
   * 255. */
  int one_step = enc->threshold[255] <= BELOW_ONE;
  for (uint32_t bin = 0; bin < GLI_BYTE_BINS && one_step; bin++) {
    int next = bin + 1 < GLI_BYTE_BINS ? enc->start[bin + 1] : 255;
    one_step = next - enc->start[bin] <= 1;
  }
  enc->one_step = one_step;
}

/* Four values' bytes where no bin holds two thresholds: each value
 * clamped to [0, BELOW_ONE] (maxps takes its second operand for a NaN),
 * its bin's start, and one comparison, 4 values at a time in SSE2 but the
 * two table reads (SSE2 has no gather). No branch: a branch on each
 * value's bin mispredicts along every gradient of an image. The comparison
 * is of the floats' bits (positive floats order as their bits): render
 * workers run with denormals as zero (render/renderer.c), under which a
 * float comparison takes a denormal threshold (gamma above about 14) for 0
 * and encodes 0 as 1. */
static void encode_four(const gli_byte_encoding *enc, const float *src,
                        uint8_t *dst) {
  const __m128 zero = _mm_setzero_ps(), below_one = _mm_set1_ps(BELOW_ONE);
  __m128 c = _mm_min_ps(_mm_max_ps(_mm_loadu_ps(src), zero), below_one);
  uint32_t bin[4];
  _mm_storeu_si128((__m128i *)bin,
                   _mm_srli_epi32(_mm_castps_si128(c), BIN_SHIFT));
  int b[4];
  uint32_t next[4];
  for (int k = 0; k < 4; k++) {
    b[k] = enc->start[bin[k]];
    next[k] = bits_of(enc->threshold[b[k] + 1]);
  }
  /* b + 1 + (c < next), the comparison's mask being -1 */
  __m128i below = _mm_cmpgt_epi32(_mm_loadu_si128((const __m128i *)next),
                                  _mm_castps_si128(c));
  __m128i byte = _mm_add_epi32(
      _mm_add_epi32(_mm_loadu_si128((const __m128i *)b), _mm_set1_epi32(1)),
      below);
  byte = _mm_packs_epi32(byte, byte);
  uint32_t four = (uint32_t)_mm_cvtsi128_si32(_mm_packus_epi16(byte, byte));
  memcpy(dst, &four, sizeof four);
}

void gli_byte_encode(const gli_byte_encoding *enc, const float *src,
                     uint8_t *dst, size_t n) {
  if (enc->gamma == 1) {
    for (size_t i = to_bytes_sse2(src, dst, n); i < n; i++)
      dst[i] = to_byte(src[i]);
    return;
  }
  if (enc->one_step) {
    size_t i = 0;
    for (; i + 4 <= n; i += 4)
      encode_four(enc, src + i, dst + i);
    if (i < n) { /* the last 1-3 values, in a padded four */
      float last[4] = {0, 0, 0, 0};
      uint8_t bytes[4];
      memcpy(last, src + i, (n - i) * sizeof *src);
      encode_four(enc, last, bytes);
      memcpy(dst + i, bytes, n - i);
    }
    return;
  }
  for (size_t i = 0; i < n; i++) {
    float c = src[i];
    if (!(c > 0)) {
      dst[i] = 0;
    } else if (c >= 1) {
      dst[i] = 255;
    } else {
      unsigned b = enc->start[bits_of(c) >> BIN_SHIFT];
      while (c >= enc->threshold[b + 1])
        b++;
      dst[i] = (uint8_t)b;
    }
  }
}
