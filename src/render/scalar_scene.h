/* A scene prepared for the scalar tracer, in the translation unit's
 * precision: flat arrays per primitive kind plus the queries the tracer asks
 * of them (nearest hit, shadow transmission). */
#ifndef GLINT_RENDER_SCALAR_SCENE_H
#define GLINT_RENDER_SCALAR_SCENE_H

#include "glint.h"
#include "math/vec3.h"
#include "accel/bvh.h"
#include "render/frame.h"

#include <stdint.h>

typedef struct sphere_r {
  vec3 center;
  real r2;
  uint32_t object;
} sphere_r;

typedef struct plane_r {
  vec3 n;
  real d;
  uint32_t object;
} plane_r;

typedef struct triangle_r {
  vec3 a;
  vec3 edge[3];   /* B - A, C - B, A - C */
  vec3 moment[3]; /* (P - R) x (Q - R) per edge PQ (see triangle_hit) */
  vec3 ng; /* unit geometric normal, front side by counter-clockwise order */
  vec3 n;  /* (B - A) x (C - A), scaled by 2^k to a length in [0.5, 1) */
  uint32_t object;
  uint32_t normals; /* first of 3 vertex normals, or GLI_NO_NORMALS */
} triangle_r;

typedef struct cone_r {
  vec3 base, axis;    /* axis: unit, from base to apex */
  real height, rb, k; /* base radius and slope (apex - base radius) / height */
  real reach2; /* the widest radius squared, widened: see cone_reach_lanes */
  uint32_t object;
} cone_r;

typedef struct material_r {
  vec3 color, odd, even;
  real inv_size;
  real ka, kd, ks, h, kr, kt, ior;
  vec3 absorb;
  int texture;
  int absorbs; /* bit c: absorb's channel c is not 0 */
} material_r;

typedef struct object_r {
  uint32_t material, shape;
  uint32_t first, count; /* primitives of its shape */
  vec3 origin;           /* solid texture origin */
  int axis_u, axis_v;    /* world axes of a planar texture */
  int smooth;            /* triangles with vertex normals */
} object_r;

typedef struct light_r {
  vec3 position, color;
} light_r;

typedef struct scene_r {
  sphere_r *spheres;
  plane_r *planes;
  triangle_r *triangles;
  cone_r *cones;
  vec3 *normals;
  object_r *objects;
  material_r *materials;
  light_r *lights;
  size_t sphere_count, plane_count, triangle_count, cone_count, light_count;
  size_t normal_count, object_count, material_count;
  /* The world's BVH, bound per renderer (render/backend.h); node_count 0:
   * every primitive is tested (--accel none). */
  const gli_bvh *bvh;
  /* Single rays walk the wide tree (bvh->wide, --accel bvh8) rather than
   * the binary one. */
  int walk_wide;
  /* A light may lie inside a transparent absorbing object: shadow rays
   * then count what they enter and do not leave (shadow_acc). */
  int lights_in_absorbers;
  vec3 background, ambient;
  vec3 tri_origin; /* R of triangle_hit: the centre of the triangles */
  real eps;
} scene_r;

/* What the nearest-hit query returns. */
typedef struct hit_r {
  real t;
  uint32_t shape; /* gli_shape */
  uint32_t prim;
  int inside; /* spheres: the ray started inside */
  real u, v;  /* triangles: barycentrics of v[1], v[2] */
} hit_r;

#define scalar_scene_prepare REAL_NAME(gli_scalar_scene_prepare)
#define scalar_scene_release REAL_NAME(gli_scalar_scene_release)
#define scalar_scene_bytes REAL_NAME(gli_scalar_scene_bytes)
#define scalar_nearest_hit REAL_NAME(gli_scalar_nearest_hit)
#define scalar_transmission REAL_NAME(gli_scalar_transmission)

/* Converts the scene (no BVH: s->bvh is an empty one until bound). */
glint_status scalar_scene_prepare(const glint_scene *scene, double eps,
                                  scene_r **out, glint_error *error);
void scalar_scene_release(scene_r *s);
/* The converted arrays' size. */
size_t scalar_scene_bytes(const scene_r *s);

/* Nearest hit along o + t d, eps < t < tmax. The queries take the ray by
 * address: by value, a float vec3 comes in two XMM registers that GCC
 * unpacked through the stack in a way the CPU cannot forward, and the
 * scalar tracer ran 7% slower on Whitted and Billiard (depth 5) than with
 * the ray in memory the callee reads a component at a time. */
int scalar_nearest_hit(const scene_r *s, const vec3 *o, const vec3 *d,
                       real tmax, hit_r *hit);

/* docs/specification.md §4: the fraction of light that travels from o along
 * unit d for a distance dist. An opaque surface on the way gives 0; each
 * transparent surface crossed multiplies by its kt, and each stretch inside an
 * absorbing object by exp(-absorb * length). */
vec3 scalar_transmission(const scene_r *s, const vec3 *o, const vec3 *d,
                         real dist);

#endif
