/* AVX2 + FMA (8 lanes). */
#ifndef GLINT_SIMD_AVX2_H
#define GLINT_SIMD_AVX2_H

#include <immintrin.h>
#include <stdint.h>

#define GLI_SIMD_WIDTH 8
/* vf_fmadd is one instruction, one rounding */
#define GLI_SIMD_FUSED 1

typedef __m256 vfloat;
typedef __m256 vmask; /* all-ones or all-zeros per lane */
typedef __m256i vint;

/* A scalar stored the way this ISA broadcasts it fastest: a float, which
 * vbroadcastss loads into every lane in one instruction. */
typedef float vscalar;
static inline vscalar vs_make(float a) { return a; }
/* A set1 of a load rather than _mm256_broadcast_ss: GCC keeps an unused
 * broadcast builtin (it reads memory) but removes an unused set1; both
 * compile to one vbroadcastss from memory. */
static inline vfloat vs_get(const vscalar *p) { return _mm256_set1_ps(*p); }

static inline vfloat vf_set1(float a) { return _mm256_set1_ps(a); }
static inline vfloat vf_zero(void) { return _mm256_setzero_ps(); }
static inline vfloat vf_load(const float *p) { return _mm256_load_ps(p); }
static inline vfloat vf_loadu(const float *p) { return _mm256_loadu_ps(p); }
static inline void vf_store(float *p, vfloat a) { _mm256_store_ps(p, a); }
static inline vfloat vf_add(vfloat a, vfloat b) { return _mm256_add_ps(a, b); }
static inline vfloat vf_sub(vfloat a, vfloat b) { return _mm256_sub_ps(a, b); }
static inline vfloat vf_mul(vfloat a, vfloat b) { return _mm256_mul_ps(a, b); }
static inline vfloat vf_div(vfloat a, vfloat b) { return _mm256_div_ps(a, b); }
static inline vfloat vf_fmadd(vfloat a, vfloat b, vfloat c) {
  return _mm256_fmadd_ps(a, b, c);
}
static inline vfloat vf_min(vfloat a, vfloat b) { return _mm256_min_ps(a, b); }
static inline vfloat vf_max(vfloat a, vfloat b) { return _mm256_max_ps(a, b); }
static inline vfloat vf_sqrt(vfloat a) { return _mm256_sqrt_ps(a); }
static inline vfloat vf_rcp_estimate(vfloat a) { return _mm256_rcp_ps(a); }
static inline vfloat vf_rsqrt_estimate(vfloat a) { return _mm256_rsqrt_ps(a); }
static inline vfloat vf_floor(vfloat a) { return _mm256_floor_ps(a); }

static inline vmask vf_lt(vfloat a, vfloat b) {
  return _mm256_cmp_ps(a, b, _CMP_LT_OQ);
}
static inline vmask vf_le(vfloat a, vfloat b) {
  return _mm256_cmp_ps(a, b, _CMP_LE_OQ);
}
static inline vmask vf_gt(vfloat a, vfloat b) {
  return _mm256_cmp_ps(a, b, _CMP_GT_OQ);
}
static inline vmask vf_ge(vfloat a, vfloat b) {
  return _mm256_cmp_ps(a, b, _CMP_GE_OQ);
}
static inline vmask vf_eq(vfloat a, vfloat b) {
  return _mm256_cmp_ps(a, b, _CMP_EQ_OQ);
}
static inline vmask vf_neq(vfloat a, vfloat b) {
  return _mm256_cmp_ps(a, b, _CMP_NEQ_UQ);
}
static inline vfloat vf_select(vmask m, vfloat a, vfloat b) {
  return _mm256_blendv_ps(b, a, m);
}

/* m ? a : 0, a single AND */
static inline vfloat vf_keep(vmask m, vfloat a) { return _mm256_and_ps(m, a); }

static inline vmask vm_and(vmask a, vmask b) { return _mm256_and_ps(a, b); }
static inline vmask vm_or(vmask a, vmask b) { return _mm256_or_ps(a, b); }
static inline vmask vm_xor(vmask a, vmask b) { return _mm256_xor_ps(a, b); }
static inline vmask vm_andnot(vmask a, vmask b) {
  return _mm256_andnot_ps(b, a);
}
static inline vmask vm_true(void) {
  return _mm256_castsi256_ps(_mm256_set1_epi32(-1));
}
static inline vmask vm_false(void) { return _mm256_setzero_ps(); }
static inline int vm_bits(vmask m) { return _mm256_movemask_ps(m); }
/* Active lanes (POPCNT: every AVX2 CPU has it; checked by CPUID). */
static inline int vm_count(vmask m) {
  return _mm_popcnt_u32((unsigned)vm_bits(m));
}
static inline vmask vm_from_bits(int bits) {
  __m256i lane = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  __m256i b = _mm256_and_si256(_mm256_set1_epi32(bits), lane);
  return _mm256_castsi256_ps(_mm256_cmpeq_epi32(b, lane));
}

static inline vint vi_set1(int a) { return _mm256_set1_epi32(a); }
static inline vint vi_load(const int *p) {
  return _mm256_load_si256((const __m256i *)p);
}
static inline void vi_store(int *p, vint a) {
  _mm256_store_si256((__m256i *)p, a);
}
static inline vint vi_add(vint a, vint b) { return _mm256_add_epi32(a, b); }
static inline vmask vi_eq(vint a, vint b) {
  return _mm256_castsi256_ps(_mm256_cmpeq_epi32(a, b));
}
static inline vint vi_select(vmask m, vint a, vint b) {
  return _mm256_castps_si256(
      _mm256_blendv_ps(_mm256_castsi256_ps(b), _mm256_castsi256_ps(a), m));
}
static inline vint vf_to_vi(vfloat a) { return _mm256_cvttps_epi32(a); }
static inline vfloat vi_to_vf(vint a) { return _mm256_cvtepi32_ps(a); }
static inline vint vf_bits(vfloat a) { return _mm256_castps_si256(a); }
static inline vfloat vi_as_vf(vint a) { return _mm256_castsi256_ps(a); }
static inline vint vi_shl(vint a, int n) { return _mm256_slli_epi32(a, n); }
static inline vint vi_shr(vint a, int n) { return _mm256_srli_epi32(a, n); }
static inline vint vi_sra(vint a, int n) { return _mm256_srai_epi32(a, n); }
static inline vint vi_and(vint a, vint b) { return _mm256_and_si256(a, b); }
static inline vint vi_or(vint a, vint b) { return _mm256_or_si256(a, b); }
static inline vint vi_sub(vint a, vint b) { return _mm256_sub_epi32(a, b); }
static inline vint vi_xor(vint a, vint b) { return _mm256_xor_si256(a, b); }
static inline vint vi_mul_const(vint a, int k) {
  return _mm256_mullo_epi32(a, vi_set1(k));
}

/* Four consecutive floats, each broadcast (vbroadcastss from memory). */
static inline void vf_splat4(const float *p, vfloat *a, vfloat *b, vfloat *c,
                             vfloat *d) {
  *a = _mm256_broadcast_ss(p);
  *b = _mm256_broadcast_ss(p + 1);
  *c = _mm256_broadcast_ss(p + 2);
  *d = _mm256_broadcast_ss(p + 3);
}

/* Stores lanes i of a, b, c, d as 4 consecutive floats each (a 4 x W
 * transpose): 16*W bytes at p. */
static inline void vf_store_quads(float *p, vfloat a, vfloat b, vfloat c,
                                  vfloat d) {
  __m256 t0 = _mm256_unpacklo_ps(a, b), t1 = _mm256_unpackhi_ps(a, b);
  __m256 t2 = _mm256_unpacklo_ps(c, d), t3 = _mm256_unpackhi_ps(c, d);
  __m256 q0 = _mm256_shuffle_ps(t0, t2, 0x44),
         q1 = _mm256_shuffle_ps(t0, t2, 0xee);
  __m256 q2 = _mm256_shuffle_ps(t1, t3, 0x44),
         q3 = _mm256_shuffle_ps(t1, t3, 0xee);
  /* q0..q3 hold lanes (0,4) (1,5) (2,6) (3,7) as 128-bit halves */
  _mm256_store_ps(p, _mm256_permute2f128_ps(q0, q1, 0x20));
  _mm256_store_ps(p + 8, _mm256_permute2f128_ps(q2, q3, 0x20));
  _mm256_store_ps(p + 16, _mm256_permute2f128_ps(q0, q1, 0x31));
  _mm256_store_ps(p + 24, _mm256_permute2f128_ps(q2, q3, 0x31));
}

static inline vfloat vf_gather(const float *base, vint idx) {
  return _mm256_i32gather_ps(base, idx, 4);
}

/* The permutation that moves the lanes set in an 8-bit mask to the front,
 * as 8 indices of 3 bits packed in a 32-bit word: built once, at first use
 * by the compiler (a constant table of 256 words). */
static inline __m256i gli_compress_perm(int bits) {
  /* Generated: for each mask, the indices of its set bits in order. */
  static const uint32_t table[256] = {
#define COMPRESS_ENTRY(x) x,
#include "simd/compress8.inc"
#undef COMPRESS_ENTRY
  };
  uint32_t packed = table[bits];
  __m256i shifts = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  return _mm256_and_si256(
      _mm256_srlv_epi32(_mm256_set1_epi32((int)packed), shifts),
      _mm256_set1_epi32(7));
}

/* Stores the lanes of m contiguously at p (a whole vector is written: the
 * caller leaves room for W floats past the count); returns how many. AVX2
 * has no compress instruction: a table permutation does it. */
static inline int vf_compress_store(float *p, vmask m, vfloat a) {
  int bits = vm_bits(m);
  _mm256_storeu_ps(p, _mm256_permutevar8x32_ps(a, gli_compress_perm(bits)));
  return _mm_popcnt_u32((unsigned)bits);
}

/* The children of a wide BVH node (accel/wide_bvh.h) for one ray: all
 * eight in one register. */
#define GLI_NODE_LANES 8
typedef __m256 vnode;
static inline vnode vn_load(const float *p) { return _mm256_load_ps(p); }
static inline vnode vn_set1(float a) { return _mm256_set1_ps(a); }
static inline vnode vn_fmadd(vnode a, vnode b, vnode c) {
  return _mm256_fmadd_ps(a, b, c);
}
static inline vnode vn_mul(vnode a, vnode b) { return _mm256_mul_ps(a, b); }
static inline vnode vn_min(vnode a, vnode b) { return _mm256_min_ps(a, b); }
static inline vnode vn_max(vnode a, vnode b) { return _mm256_max_ps(a, b); }
static inline void vn_store(float *p, vnode a) { _mm256_storeu_ps(p, a); }
/* Bit k: a[k] <= b[k]. */
static inline int vn_le_bits(vnode a, vnode b) {
  return _mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_LE_OQ));
}

/* The primitives of a wide BVH leaf as one ray tests them
 * (render/leaf_blocks.h): eight, one register. */
#define GLI_BLOCK_LANES 8
static inline vfloat vf_load_block(const float *p) { return _mm256_load_ps(p); }

#endif
