/* Vectors of W 3-vectors in SoA layout (thesis §4.1, listing 4.5): the
 * 3-D maths of the packet kernels, on top of the SIMD layer (simd/simd.h).
 * Compiled once per ISA with the file that includes it. */
#ifndef GLINT_SIMD_VVEC3_H
#define GLINT_SIMD_VVEC3_H

#include "math/vec3.h"
#include "simd/simd.h"

/* The packet kernels are small functions that must inline into their
 * callers for the compiler to keep the lanes in registers; profiling builds
 * (-DGLINT_PROFILE_NOINLINE) keep them apart to attribute time. */
#ifdef GLINT_PROFILE_NOINLINE
#define ALWAYS_INLINE __attribute__((noinline))
#else
#define ALWAYS_INLINE inline __attribute__((always_inline))
#endif

typedef struct vvec3 {
  vfloat x, y, z;
} vvec3;

static ALWAYS_INLINE vvec3 vv_set1(vec3 a) {
  vvec3 r = {vf_set1(a.x), vf_set1(a.y), vf_set1(a.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_add(vvec3 a, vvec3 b) {
  vvec3 r = {vf_add(a.x, b.x), vf_add(a.y, b.y), vf_add(a.z, b.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_sub(vvec3 a, vvec3 b) {
  vvec3 r = {vf_sub(a.x, b.x), vf_sub(a.y, b.y), vf_sub(a.z, b.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_mul(vvec3 a, vvec3 b) {
  vvec3 r = {vf_mul(a.x, b.x), vf_mul(a.y, b.y), vf_mul(a.z, b.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_scale(vvec3 a, vfloat s) {
  vvec3 r = {vf_mul(a.x, s), vf_mul(a.y, s), vf_mul(a.z, s)};
  return r;
}
/* a + s b */
static ALWAYS_INLINE vvec3 vv_madd(vvec3 a, vfloat s, vvec3 b) {
  vvec3 r = {vf_fmadd(s, b.x, a.x), vf_fmadd(s, b.y, a.y),
             vf_fmadd(s, b.z, a.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_neg(vvec3 a) {
  vvec3 r = {vf_neg(a.x), vf_neg(a.y), vf_neg(a.z)};
  return r;
}
/* The thesis's SoA dot product (listing 4.5), with fused multiply-adds. */
static ALWAYS_INLINE vfloat vv_dot(vvec3 a, vvec3 b) {
  return vf_fmadd(a.x, b.x, vf_fmadd(a.y, b.y, vf_mul(a.z, b.z)));
}
/* a·b + c in three multiply-adds */
static ALWAYS_INLINE vfloat vv_dot_add(vvec3 a, vvec3 b, vfloat c) {
  return vf_fmadd(a.x, b.x, vf_fmadd(a.y, b.y, vf_fmadd(a.z, b.z, c)));
}
static ALWAYS_INLINE vvec3 vv_cross(vvec3 a, vvec3 b) {
  vvec3 r = {vf_sub(vf_mul(a.y, b.z), vf_mul(a.z, b.y)),
             vf_sub(vf_mul(a.z, b.x), vf_mul(a.x, b.z)),
             vf_sub(vf_mul(a.x, b.y), vf_mul(a.y, b.x))};
  return r;
}
static ALWAYS_INLINE vvec3 vv_select(vmask m, vvec3 a, vvec3 b) {
  vvec3 r = {vf_select(m, a.x, b.x), vf_select(m, a.y, b.y),
             vf_select(m, a.z, b.z)};
  return r;
}
static ALWAYS_INLINE vvec3 vv_normalize(vvec3 a, int newton) {
  return vv_scale(a, vf_rsqrt(vv_dot(a, a), newton));
}
/* Three consecutive vscalars (a packet-scene vec3) across lanes. */
static ALWAYS_INLINE vvec3 vv_get(const vscalar *p) {
  vvec3 r = {vs_get(&p[0]), vs_get(&p[1]), vs_get(&p[2])};
  return r;
}

/* A vec3 stored in a record, splat across lanes. It reads one float past
 * the vec3, which every record below has. */
static ALWAYS_INLINE vvec3 vv_splat(const vec3 *p) {
  vvec3 r;
  vfloat unused;
  vf_splat4(&p->x, &r.x, &r.y, &r.z, &unused);
  return r;
}

/* Lane-wise gather of a vec3 field at `offset` floats into records of
 * `stride` floats, indexed by idx. */
static ALWAYS_INLINE vvec3 vv_gather(const float *base, vint idx, int stride,
                                     int offset) {
  vint i = vi_add(vi_mul_const(idx, stride), vi_set1(offset));
  vvec3 r = {vf_gather(base, i), vf_gather(base, vi_add(i, vi_set1(1))),
             vf_gather(base, vi_add(i, vi_set1(2)))};
  return r;
}

/* The lanes of m of a vvec3 stored one after another at x, y and z (three
 * arrays of a stream, as vf_compress_store does one). */
static ALWAYS_INLINE void vv_compress_store(float *x, float *y, float *z,
                                            vmask m, vvec3 a) {
  vf_compress_store(x, m, a.x);
  vf_compress_store(y, m, a.y);
  vf_compress_store(z, m, a.z);
}

#endif
