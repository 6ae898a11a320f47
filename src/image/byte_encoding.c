/* The 8-bit encoding of linear values (docs/specification.md §4): clamp to
 * [0, 1], then c^(1/gamma), then round(255 c); a NaN becomes 0. Every
 * frame of every backend passes through here, tile by tile, so neither
 * case may cost much per value:
 *  - gamma 1: 16 values at a time in SSE2;
 *  - any other gamma: powf runs once per step of the output, not once per
 *    value. The encoding is monotone, so a value's byte is the number of
 *    thresholds (the least value reaching each byte 1..255) at or below
 *    it; a table indexed by the value's top 16 bits (its exponent and 7
 *    bits of mantissa) gives the byte at the start of its bin, and a step
 *    or two of comparison finishes. The bytes are those of powf itself:
 *    each threshold is found by bisection on powf's own results. */
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

uint8_t gli_byte_encode_one(float c, double gamma) {
  if (!(c > 0))
    return 0;
  return to_byte(powf(c < 1 ? c : 1.0f, (float)(1.0 / gamma)));
}

void gli_byte_encoding_init(gli_byte_encoding *enc, double gamma) {
  enc->gamma = gamma;
  if (gamma == 1)
    return;
  /* threshold[k]: the least float in (0, 1] encoded as k or more, found by
   * bisection between the last threshold and 1 (which encodes as 255). */
  uint32_t lo = 0;
  for (int k = 1; k <= 255; k++) {
    uint32_t hi = ONE_BITS;
    while (hi - lo > 1) {
      uint32_t mid = lo + (hi - lo) / 2;
      if (gli_byte_encode_one(float_of(mid), gamma) >= k)
        hi = mid;
      else
        lo = mid;
    }
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
}

void gli_byte_encode(const gli_byte_encoding *enc, const float *src,
                     uint8_t *dst, size_t n) {
  if (enc->gamma == 1) {
    for (size_t i = to_bytes_sse2(src, dst, n); i < n; i++)
      dst[i] = to_byte(src[i]);
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
