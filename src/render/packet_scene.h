/* The scene as the packet kernels read it: every constant a kernel
 * broadcasts across its lanes (primitive fields, material coefficients,
 * light positions) stored as a vscalar, the form the ISA broadcasts fastest
 * (pre-splat on SSE, a plain float on AVX2 and AVX-512; see simd/simd.h).
 * Built once per world from the float scalar scene, which it keeps for
 * everything read as scalars (object table, flags) or gathered per lane
 * (triangle normals). Compiled once per ISA. */
#ifndef GLINT_RENDER_PACKET_SCENE_H
#define GLINT_RENDER_PACKET_SCENE_H

#ifndef GLINT_REAL_FLOAT
#define GLINT_REAL_FLOAT
#endif
#include "render/backend.h"
#include "render/frame.h"
#include "render/scalar_scene.h"
#include "simd/simd.h"

typedef struct psphere {
  vscalar center[3], r2;
  int32_t object;
} psphere;

typedef struct pplane {
  vscalar n[3], d;
  int32_t object;
} pplane;

typedef struct ptriangle {
  vscalar a[3];
  vscalar edge[3][3], moment[3][3]; /* see triangle_hit, geometry/intersect.h */
  vscalar n[3]; /* (B - A) x (C - A), scaled to a length in [0.5, 1) */
  int32_t object;
} ptriangle;

typedef struct pcone {
  vscalar base[3], axis[3];
  vscalar height, rb, k; /* see cone_roots in geometry/intersect.h */
  vscalar reach2;        /* see cone_reach_lanes */
  int32_t object;
} pcone;

typedef struct pmaterial {
  vscalar color[3], odd[3], even[3];
  vscalar ambient[3]; /* ka Ia */
  vscalar kd, ks, h, kr, kt;
  vscalar kr_tir;          /* kr + kt: reflection's weight under TIR */
  vscalar eta_in, eta_out; /* 1/ior entering, ior leaving */
  vscalar ior_value;
  vscalar absorb[3], inv_size;
} pmaterial;

typedef struct plight {
  vscalar position[3], color[3];
} plight;

typedef struct packet_scene {
  scene_r *s;
  psphere *spheres;
  pplane *planes;
  ptriangle *triangles;
  pcone *cones;
  pmaterial *materials;
  plight *lights;
  vscalar eps, background[3];
  vscalar tri_origin[3]; /* R of triangle_hit */
  /* A packet hands a subtree to its lanes one at a time through the wide
   * BVH when at most this many of them enter it (0: never; LANES: from the
   * root on: accel/packet_traverse.h). */
  int alone_lanes;
  /* The walks prefetch a leaf's triangles (render/packet_rays.h): where
   * their records outgrow the caches, GLI_PREFETCH_BYTES or more. */
  int prefetch;
  /* The tests a query makes beside the BVH's walks: the planes, and every
   * primitive when there is no BVH (the statistics' count). */
  size_t outside_tests;
  const struct leaf_blocks *blocks; /* what they test (render/leaf_blocks.h) */
} packet_scene;

#define GLI_PREFETCH_BYTES (4u << 20)

/* The converted layout this ISA's backends share (render/backend.h). */
#if defined(GLINT_ISA_SSE)
#define ISA_DATA_KIND DATA_PACKET_SSE
#elif defined(GLINT_ISA_AVX2)
#define ISA_DATA_KIND DATA_PACKET_AVX2
#else
#define ISA_DATA_KIND DATA_PACKET_AVX512
#endif

#define packet_scene_prepare ISA_NAME(gli_packet_scene_prepare)
#define packet_scene_release ISA_NAME(gli_packet_scene_release)

glint_status packet_scene_prepare(const glint_scene *scene, double eps,
                                  packet_scene **out, glint_error *error);
void packet_scene_release(packet_scene *ps);

#endif
