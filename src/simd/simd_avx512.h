/* AVX-512F (16 lanes), with DQ/BW/VL. Lane masks are the k registers. */
#ifndef GLINT_SIMD_AVX512_H
#define GLINT_SIMD_AVX512_H

#include <immintrin.h>

#define GLI_SIMD_WIDTH 16
/* vf_fmadd is one instruction, one rounding */
#define GLI_SIMD_FUSED 1

typedef __m512 vfloat;
typedef __mmask16 vmask; /* one bit per lane */
typedef __m512i vint;

/* A scalar stored the way this ISA broadcasts it fastest: a float, which
 * an embedded {1to16} broadcast folds into the instruction using it. */
typedef float vscalar;
static inline vscalar vs_make(float a) { return a; }
static inline vfloat vs_get(const vscalar *p) { return _mm512_set1_ps(*p); }

static inline vfloat vf_set1(float a) { return _mm512_set1_ps(a); }
static inline vfloat vf_zero(void) { return _mm512_setzero_ps(); }
static inline vfloat vf_load(const float *p) { return _mm512_load_ps(p); }
static inline vfloat vf_loadu(const float *p) { return _mm512_loadu_ps(p); }
static inline void vf_store(float *p, vfloat a) { _mm512_store_ps(p, a); }
static inline vfloat vf_add(vfloat a, vfloat b) { return _mm512_add_ps(a, b); }
static inline vfloat vf_sub(vfloat a, vfloat b) { return _mm512_sub_ps(a, b); }
static inline vfloat vf_mul(vfloat a, vfloat b) { return _mm512_mul_ps(a, b); }
static inline vfloat vf_div(vfloat a, vfloat b) { return _mm512_div_ps(a, b); }
static inline vfloat vf_fmadd(vfloat a, vfloat b, vfloat c) {
  return _mm512_fmadd_ps(a, b, c);
}
static inline vfloat vf_min(vfloat a, vfloat b) { return _mm512_min_ps(a, b); }
static inline vfloat vf_max(vfloat a, vfloat b) { return _mm512_max_ps(a, b); }
static inline vfloat vf_sqrt(vfloat a) { return _mm512_sqrt_ps(a); }
/* rcp14: a 14-bit estimate (SSE/AVX2 give about 12). */
static inline vfloat vf_rcp_estimate(vfloat a) { return _mm512_rcp14_ps(a); }
static inline vfloat vf_rsqrt_estimate(vfloat a) {
  return _mm512_rsqrt14_ps(a);
}
static inline vfloat vf_floor(vfloat a) {
  return _mm512_roundscale_ps(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
}

static inline vmask vf_lt(vfloat a, vfloat b) {
  return _mm512_cmp_ps_mask(a, b, _CMP_LT_OQ);
}
static inline vmask vf_le(vfloat a, vfloat b) {
  return _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ);
}
static inline vmask vf_gt(vfloat a, vfloat b) {
  return _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ);
}
static inline vmask vf_ge(vfloat a, vfloat b) {
  return _mm512_cmp_ps_mask(a, b, _CMP_GE_OQ);
}
static inline vmask vf_eq(vfloat a, vfloat b) {
  return _mm512_cmp_ps_mask(a, b, _CMP_EQ_OQ);
}
static inline vmask vf_neq(vfloat a, vfloat b) {
  return _mm512_cmp_ps_mask(a, b, _CMP_NEQ_UQ);
}
static inline vfloat vf_select(vmask m, vfloat a, vfloat b) {
  return _mm512_mask_blend_ps(m, b, a);
}

/* m ? a : 0, a zero-masking move */
static inline vfloat vf_keep(vmask m, vfloat a) {
  return _mm512_maskz_mov_ps(m, a);
}

static inline vmask vm_and(vmask a, vmask b) { return (vmask)(a & b); }
static inline vmask vm_or(vmask a, vmask b) { return (vmask)(a | b); }
static inline vmask vm_xor(vmask a, vmask b) { return (vmask)(a ^ b); }
static inline vmask vm_andnot(vmask a, vmask b) { return (vmask)(a & ~b); }
static inline vmask vm_true(void) { return (vmask)0xffff; }
static inline vmask vm_false(void) { return (vmask)0; }
static inline int vm_bits(vmask m) { return (int)m; }
/* Active lanes (POPCNT: every AVX2 CPU has it; checked by CPUID). */
static inline int vm_count(vmask m) {
  return _mm_popcnt_u32((unsigned)vm_bits(m));
}
static inline vmask vm_from_bits(int bits) { return (vmask)bits; }

static inline vint vi_set1(int a) { return _mm512_set1_epi32(a); }
static inline vint vi_load(const int *p) {
  return _mm512_load_si512((const void *)p);
}
static inline void vi_store(int *p, vint a) {
  _mm512_store_si512((void *)p, a);
}
static inline vint vi_add(vint a, vint b) { return _mm512_add_epi32(a, b); }
static inline vmask vi_eq(vint a, vint b) {
  return _mm512_cmpeq_epi32_mask(a, b);
}
static inline vint vi_select(vmask m, vint a, vint b) {
  return _mm512_mask_blend_epi32(m, b, a);
}
static inline vint vf_to_vi(vfloat a) { return _mm512_cvttps_epi32(a); }
static inline vfloat vi_to_vf(vint a) { return _mm512_cvtepi32_ps(a); }
static inline vint vf_bits(vfloat a) { return _mm512_castps_si512(a); }
static inline vfloat vi_as_vf(vint a) { return _mm512_castsi512_ps(a); }
static inline vint vi_shl(vint a, int n) {
  return _mm512_slli_epi32(a, (unsigned)n);
}
static inline vint vi_shr(vint a, int n) {
  return _mm512_srli_epi32(a, (unsigned)n);
}
static inline vint vi_sra(vint a, int n) {
  return _mm512_srai_epi32(a, (unsigned)n);
}
static inline vint vi_and(vint a, vint b) { return _mm512_and_si512(a, b); }
static inline vint vi_or(vint a, vint b) { return _mm512_or_si512(a, b); }
static inline vint vi_sub(vint a, vint b) { return _mm512_sub_epi32(a, b); }
static inline vint vi_xor(vint a, vint b) { return _mm512_xor_si512(a, b); }
static inline vint vi_mul_const(vint a, int k) {
  return _mm512_mullo_epi32(a, vi_set1(k));
}

/* Four consecutive floats, each broadcast (vbroadcastss from memory). */
static inline void vf_splat4(const float *p, vfloat *a, vfloat *b, vfloat *c,
                             vfloat *d) {
  *a = _mm512_set1_ps(p[0]);
  *b = _mm512_set1_ps(p[1]);
  *c = _mm512_set1_ps(p[2]);
  *d = _mm512_set1_ps(p[3]);
}

/* Stores lanes i of a, b, c, d as 4 consecutive floats each (a 4 x W
 * transpose): 16*W bytes at p. */
static inline void vf_store_quads(float *p, vfloat a, vfloat b, vfloat c,
                                  vfloat d) {
  __m512 t0 = _mm512_unpacklo_ps(a, b), t1 = _mm512_unpackhi_ps(a, b);
  __m512 t2 = _mm512_unpacklo_ps(c, d), t3 = _mm512_unpackhi_ps(c, d);
  /* per 128-bit block k: q0 = lane 4k, q1 = 4k+1, q2 = 4k+2, q3 = 4k+3 */
  __m512 q0 = _mm512_shuffle_ps(t0, t2, 0x44),
         q1 = _mm512_shuffle_ps(t0, t2, 0xee);
  __m512 q2 = _mm512_shuffle_ps(t1, t3, 0x44),
         q3 = _mm512_shuffle_ps(t1, t3, 0xee);
  for (int k = 0; k < 4; k++) {
    /* lanes 4k..4k+3: block k of q0, q1, q2, q3 */
    __m512i sel = _mm512_setr_epi32(
        4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3, 16 + 4 * k, 17 + 4 * k,
        18 + 4 * k, 19 + 4 * k, 4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3,
        16 + 4 * k, 17 + 4 * k, 18 + 4 * k, 19 + 4 * k);
    __m512 lo = _mm512_permutex2var_ps(q0, sel, q1);
    __m512 hi = _mm512_permutex2var_ps(q2, sel, q3);
    _mm512_store_ps(p + 16 * k,
                    _mm512_shuffle_f32x4(lo, hi, _MM_SHUFFLE(1, 0, 1, 0)));
  }
}

static inline vfloat vf_gather(const float *base, vint idx) {
  return _mm512_i32gather_ps(idx, base, 4);
}

/* base[idx[i]] = a[i] for the lanes of m (vscatterdps). */
static inline void vf_scatter(float *base, vint idx, vfloat a, vmask m) {
  _mm512_mask_i32scatter_ps(base, m, idx, a, 4);
}

/* Whether the lanes of m hold pairwise different values (AVX-512CD). */
static inline int vi_distinct(vint a, vmask m) {
  __m512i c = _mm512_maskz_conflict_epi32(m, a);
  return !_mm512_mask_test_epi32_mask(m, c, _mm512_set1_epi32((int)m));
}
#define GLI_HAS_SCATTER 1

/* Stores the lanes of m contiguously at p; returns how many. The compress
 * happens in a register and the whole vector is stored (the caller leaves
 * room for W floats past the count): vcompressps with a memory operand is
 * microcoded and several times slower on Intel cores. */
static inline int vf_compress_store(float *p, vmask m, vfloat a) {
  _mm512_storeu_ps(p, _mm512_maskz_compress_ps(m, a));
  return _mm_popcnt_u32((unsigned)m);
}

/* The children of a wide BVH node (accel/wide_bvh.h) for one ray: all
 * eight in a 256-bit register (AVX-512VL gives its compare a mask). */
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
  return (int)_mm256_cmp_ps_mask(a, b, _CMP_LE_OQ);
}

/* The primitives of a wide BVH leaf as one ray tests them
 * (render/leaf_blocks.h): eight, the lower half of a register (the upper lanes
 * read as zero, and are never active). */
#define GLI_BLOCK_LANES 8
static inline vfloat vf_load_block(const float *p) {
  return _mm512_maskz_loadu_ps(0xff, p);
}

#endif
