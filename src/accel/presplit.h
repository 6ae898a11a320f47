/* Pre-splitting of primitive references before the BVH is built ("early
 * split clipping", Ernst and Greiner 2007, "Early split clipping for
 * bounding volume hierarchies"): a long thin cylinder lying across the axes
 * has a box far larger than itself, and every ray through that box visits
 * it. Its reference is replaced by several, each bounding one part of the
 * cylinder along its axis, so the builder can place the parts apart. The
 * references whose boxes lose most surface area are split first, until a
 * piece is about as wide as it is long or a budget of references is spent.
 *
 * Measured (callgrind instruction counts of the renders, 160x160, AVX2
 * beams and streams, scalar-float; the notes of this change in the README's
 * "Performance" section): cylinders split this way cost rings-s4 18-25%
 * fewer instructions and scenes/stress/sticks.json 30-45%; triangles split
 * by clipping them to halved boxes gained at most 1.3% (gears-s4) for twice
 * the build time and lost 2-10% (teapot-s4, mount-s6), so only cones and
 * cylinders are split.
 *
 * Only opaque primitives are split: a ray finds the same closest hit
 * through any of a primitive's references, and an opaque one blocks a
 * shadow ray however often it is met, but a transparent one's crossings
 * multiply a shadow ray's transmission (render/scalar_rays.h) and must be
 * met once. */
#ifndef GLINT_ACCEL_PRESPLIT_H
#define GLINT_ACCEL_PRESPLIT_H

#include "accel/bounds.h"

#include <stddef.h>
#include <stdint.h>

/* The part of its primitive a reference stands for: a cone's between
 * fractions s0 and s1 of the way from base to apex; {0, 1} is all of it,
 * and all of any other shape. Halving makes the fractions dyadic, exact in
 * float. */
typedef struct gli_ref_part {
  float s0, s1;
} gli_ref_part;

/* Extra references pre-splitting may add, per reference. */
#define GLI_PRESPLIT_BUDGET 4

/* The box of `part` of primitive reference `ref`. */
gli_ref_box gli_ref_part_box(const glint_scene *scene, uint32_t ref,
                             gli_ref_part part);

/* refs[0..n) are the primitive references, boxes[0..n) their boxes; the
 * three arrays hold `capacity` entries. Splits references, appending the
 * new ones (a split reference's own entry becomes its first part), fills
 * every reference's part, and returns the new count, at most `capacity`. */
size_t gli_presplit(const glint_scene *scene, uint32_t *refs,
                    gli_ref_box *boxes, gli_ref_part *parts, size_t n,
                    size_t capacity);

#endif
