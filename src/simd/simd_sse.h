/* SSE (4 lanes): SSE2 as in the thesis, plus SSE4.1's blendv and floor. */
#ifndef GLINT_SIMD_SSE_H
#define GLINT_SIMD_SSE_H

#include <smmintrin.h>

#define GLI_SIMD_WIDTH 4
/* vf_fmadd is a multiplication and an addition, two roundings */
#define GLI_SIMD_FUSED 0

typedef __m128 vfloat;
typedef __m128 vmask; /* all-ones or all-zeros per lane */
typedef __m128i vint;

/* A scalar stored the way this ISA broadcasts it fastest. SSE has no
 * broadcast load, so scene constants are stored already splat: loading
 * one is a plain (foldable) 16-byte load. */
typedef __m128 vscalar;
static inline vscalar vs_make(float a) { return _mm_set1_ps(a); }
static inline vfloat vs_get(const vscalar *p) { return *p; }

static inline vfloat vf_set1(float a) { return _mm_set1_ps(a); }
static inline vfloat vf_zero(void) { return _mm_setzero_ps(); }
static inline vfloat vf_load(const float *p) { return _mm_load_ps(p); }
static inline vfloat vf_loadu(const float *p) { return _mm_load_ps(p); }
static inline void vf_store(float *p, vfloat a) { _mm_store_ps(p, a); }
static inline vfloat vf_add(vfloat a, vfloat b) { return _mm_add_ps(a, b); }
static inline vfloat vf_sub(vfloat a, vfloat b) { return _mm_sub_ps(a, b); }
static inline vfloat vf_mul(vfloat a, vfloat b) { return _mm_mul_ps(a, b); }
static inline vfloat vf_div(vfloat a, vfloat b) { return _mm_div_ps(a, b); }
/* a*b + c; SSE has no fused multiply-add. */
static inline vfloat vf_fmadd(vfloat a, vfloat b, vfloat c) {
  return _mm_add_ps(_mm_mul_ps(a, b), c);
}
static inline vfloat vf_min(vfloat a, vfloat b) { return _mm_min_ps(a, b); }
static inline vfloat vf_max(vfloat a, vfloat b) { return _mm_max_ps(a, b); }
static inline vfloat vf_sqrt(vfloat a) { return _mm_sqrt_ps(a); }
static inline vfloat vf_rcp_estimate(vfloat a) { return _mm_rcp_ps(a); }
static inline vfloat vf_rsqrt_estimate(vfloat a) { return _mm_rsqrt_ps(a); }
static inline vfloat vf_floor(vfloat a) { return _mm_floor_ps(a); }

static inline vmask vf_lt(vfloat a, vfloat b) { return _mm_cmplt_ps(a, b); }
static inline vmask vf_le(vfloat a, vfloat b) { return _mm_cmple_ps(a, b); }
static inline vmask vf_gt(vfloat a, vfloat b) { return _mm_cmpgt_ps(a, b); }
static inline vmask vf_ge(vfloat a, vfloat b) { return _mm_cmpge_ps(a, b); }
static inline vmask vf_eq(vfloat a, vfloat b) { return _mm_cmpeq_ps(a, b); }
static inline vmask vf_neq(vfloat a, vfloat b) { return _mm_cmpneq_ps(a, b); }
/* m ? a : b (listing 3.2's and/andnot/or, as one instruction) */
static inline vfloat vf_select(vmask m, vfloat a, vfloat b) {
  return _mm_blendv_ps(b, a, m);
}

/* m ? a : 0, a single AND */
static inline vfloat vf_keep(vmask m, vfloat a) { return _mm_and_ps(m, a); }

static inline vmask vm_and(vmask a, vmask b) { return _mm_and_ps(a, b); }
static inline vmask vm_or(vmask a, vmask b) { return _mm_or_ps(a, b); }
static inline vmask vm_xor(vmask a, vmask b) { return _mm_xor_ps(a, b); }
/* a & ~b */
static inline vmask vm_andnot(vmask a, vmask b) { return _mm_andnot_ps(b, a); }
static inline vmask vm_true(void) {
  return _mm_castsi128_ps(_mm_set1_epi32(-1));
}
static inline vmask vm_false(void) { return _mm_setzero_ps(); }
static inline int vm_bits(vmask m) { return _mm_movemask_ps(m); }
/* Active lanes. SSE4.1 CPUs need not have POPCNT: a table of 16. */
static inline int vm_count(vmask m) {
  static const unsigned char bits_set[16] = {0, 1, 1, 2, 1, 2, 2, 3,
                                             1, 2, 2, 3, 2, 3, 3, 4};
  return bits_set[_mm_movemask_ps(m)];
}
static inline vmask vm_from_bits(int bits) {
  __m128i lane = _mm_setr_epi32(1, 2, 4, 8);
  __m128i b = _mm_and_si128(_mm_set1_epi32(bits), lane);
  return _mm_castsi128_ps(_mm_cmpeq_epi32(b, lane));
}

static inline vint vi_set1(int a) { return _mm_set1_epi32(a); }
static inline vint vi_load(const int *p) {
  return _mm_load_si128((const __m128i *)p);
}
static inline void vi_store(int *p, vint a) {
  _mm_store_si128((__m128i *)p, a);
}
static inline vint vi_add(vint a, vint b) { return _mm_add_epi32(a, b); }
static inline vmask vi_eq(vint a, vint b) {
  return _mm_castsi128_ps(_mm_cmpeq_epi32(a, b));
}
static inline vint vi_select(vmask m, vint a, vint b) {
  return _mm_castps_si128(
      _mm_blendv_ps(_mm_castsi128_ps(b), _mm_castsi128_ps(a), m));
}
static inline vint vf_to_vi(vfloat a) { return _mm_cvttps_epi32(a); }
static inline vfloat vi_to_vf(vint a) { return _mm_cvtepi32_ps(a); }
static inline vint vf_bits(vfloat a) { return _mm_castps_si128(a); }
static inline vfloat vi_as_vf(vint a) { return _mm_castsi128_ps(a); }
static inline vint vi_shl(vint a, int n) { return _mm_slli_epi32(a, n); }
static inline vint vi_shr(vint a, int n) { return _mm_srli_epi32(a, n); }
static inline vint vi_sra(vint a, int n) { return _mm_srai_epi32(a, n); }
static inline vint vi_and(vint a, vint b) { return _mm_and_si128(a, b); }
static inline vint vi_or(vint a, vint b) { return _mm_or_si128(a, b); }
static inline vint vi_sub(vint a, vint b) { return _mm_sub_epi32(a, b); }
static inline vint vi_xor(vint a, vint b) { return _mm_xor_si128(a, b); }
static inline vint vi_mul_const(vint a, int k) {
  return _mm_mullo_epi32(a, vi_set1(k));
}

/* Four consecutive floats, each splat across a vector: one load and four
 * shuffles (SSE has no broadcast load; set1 from memory costs two
 * instructions a value). */
static inline void vf_splat4(const float *p, vfloat *a, vfloat *b, vfloat *c,
                             vfloat *d) {
  __m128 v = _mm_loadu_ps(p);
  *a = _mm_shuffle_ps(v, v, 0x00);
  *b = _mm_shuffle_ps(v, v, 0x55);
  *c = _mm_shuffle_ps(v, v, 0xaa);
  *d = _mm_shuffle_ps(v, v, 0xff);
}

/* Stores lanes i of a, b, c, d as 4 consecutive floats each (a 4 x W
 * transpose): 16*W bytes at p. */
static inline void vf_store_quads(float *p, vfloat a, vfloat b, vfloat c,
                                  vfloat d) {
  _MM_TRANSPOSE4_PS(a, b, c, d);
  _mm_store_ps(p, a);
  _mm_store_ps(p + 4, b);
  _mm_store_ps(p + 8, c);
  _mm_store_ps(p + 12, d);
}

/* No gather in SSE: four scalar loads. */
static inline vfloat vf_gather(const float *base, vint idx) {
  int i[4] __attribute__((aligned(16)));
  _mm_store_si128((__m128i *)i, idx);
  return _mm_setr_ps(base[i[0]], base[i[1]], base[i[2]], base[i[3]]);
}

/* Stores the lanes of m contiguously at p (a whole vector is written: the
 * caller leaves room for W floats past the count); returns how many. A byte
 * shuffle (pshufb, SSSE3) from a table of the 16 masks moves them. */
static inline int vf_compress_store(float *p, vmask m, vfloat a) {
#define LANE_BYTES(i) (4 * (i)), (4 * (i) + 1), (4 * (i) + 2), (4 * (i) + 3)
  static const unsigned char table[16][16] __attribute__((aligned(16))) = {
      {LANE_BYTES(0), LANE_BYTES(0), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(0), LANE_BYTES(0), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(1), LANE_BYTES(0), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(0), LANE_BYTES(1), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(2), LANE_BYTES(0), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(0), LANE_BYTES(2), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(1), LANE_BYTES(2), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(0), LANE_BYTES(1), LANE_BYTES(2), LANE_BYTES(0)},
      {LANE_BYTES(3), LANE_BYTES(0), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(0), LANE_BYTES(3), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(1), LANE_BYTES(3), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(0), LANE_BYTES(1), LANE_BYTES(3), LANE_BYTES(0)},
      {LANE_BYTES(2), LANE_BYTES(3), LANE_BYTES(0), LANE_BYTES(0)},
      {LANE_BYTES(0), LANE_BYTES(2), LANE_BYTES(3), LANE_BYTES(0)},
      {LANE_BYTES(1), LANE_BYTES(2), LANE_BYTES(3), LANE_BYTES(0)},
      {LANE_BYTES(0), LANE_BYTES(1), LANE_BYTES(2), LANE_BYTES(3)}};
#undef LANE_BYTES
  int bits = vm_bits(m);
  __m128i shuffled = _mm_shuffle_epi8(
      _mm_castps_si128(a), _mm_load_si128((const __m128i *)table[bits]));
  _mm_storeu_si128((__m128i *)p, shuffled);
  return vm_count(m);
}

/* The children of a wide BVH node (accel/wide_bvh.h) for one ray: four
 * of its eight at a time. */
#define GLI_NODE_LANES 4
typedef __m128 vnode;
static inline vnode vn_load(const float *p) { return _mm_load_ps(p); }
static inline vnode vn_set1(float a) { return _mm_set1_ps(a); }
static inline vnode vn_add(vnode a, vnode b) { return _mm_add_ps(a, b); }
static inline vnode vn_mul(vnode a, vnode b) { return _mm_mul_ps(a, b); }
static inline vnode vn_min(vnode a, vnode b) { return _mm_min_ps(a, b); }
static inline vnode vn_max(vnode a, vnode b) { return _mm_max_ps(a, b); }
static inline void vn_store(float *p, vnode a) { _mm_storeu_ps(p, a); }
/* Bit k: a[k] <= b[k]. */
static inline int vn_le_bits(vnode a, vnode b) {
  return _mm_movemask_ps(_mm_cmple_ps(a, b));
}

/* The primitives of a wide BVH leaf as one ray tests them
 * (render/leaf_blocks.h): four of them, one register. */
#define GLI_BLOCK_LANES 4
static inline vfloat vf_load_block(const float *p) { return _mm_load_ps(p); }

#endif
