/* The Whitted model for W lanes at once (SPEC §4; thesis eq. 2.9-2.13):
 * surfaces, textures, the lights' local part, reflection and refraction,
 * and Beer's law, compiled once per ISA and used by both packet backends
 * (beam_tracer.c, stream_tracer.c). The scalar reference is
 * render/scalar_tracer.c. */
#ifndef GLINT_RENDER_PACKET_SHADING_H
#define GLINT_RENDER_PACKET_SHADING_H

#include "geometry/packet_intersect.h"
#include "render/packet_rays.h"
#include "simd/vmath.h"

#include <float.h>
#include <stddef.h>
#include <x86intrin.h>

/* ---- surfaces and local shading -------------------------------------- */

/* Where the lanes of a sub-beam met one object, with the normal facing the
 * ray. */
typedef struct packet_surface {
  vvec3 p, n;
  vmask front; /* hit the outside: entering a closed object */
} packet_surface;

#define FLOATS_OF(type) ((int)(sizeof(type) / sizeof(float)))
#define FLOAT_OFFSET(type, field) ((int)(offsetof(type, field) / sizeof(float)))

static ALWAYS_INLINE packet_surface packet_surface_at(const packet_scene *ps,
                                                      const object_r *ob,
                                                      const packet_hit *h,
                                                      vvec3 o, vvec3 d,
                                                      int newton) {
  const scene_r *s = ps->s;
  packet_surface f;
  f.p = vv_madd(o, h->t, d);
  vvec3 ng;
  switch (ob->shape) {
  case GLINT_SHAPE_SPHERE:
    /* Normalised, not scaled by 1/r: see surface_at in scalar_tracer.c. */
    ng = vv_normalize(vv_sub(f.p, vv_get(ps->spheres[ob->first].center)),
                      newton);
    f.front = vm_andnot(vm_true(), h->inside);
    break;
  case GLINT_SHAPE_PLANE:
    ng = vv_get(ps->planes[ob->first].n);
    f.front = vf_lt(vv_dot(ng, d), vf_zero());
    break;
  case GLINT_SHAPE_CONE: {
    /* q - h a - k (rb + k h) a: see cone_normal in geometry/intersect.h */
    const pcone *c = &ps->cones[ob->first];
    vvec3 axis = vv_get(c->axis);
    vvec3 q = vv_sub(f.p, vv_get(c->base));
    vfloat hq = vv_dot(q, axis), k = vs_get(&c->k);
    ng = vv_normalize(
        vv_madd(q, vf_neg(vf_fmadd(k, vf_fmadd(k, hq, vs_get(&c->rb)), hq)),
                axis),
        newton);
    f.front = vf_lt(vv_dot(ng, d), vf_zero());
    break;
  }
  default: /* triangles */
    if (ob->count == 1)
      ng = vv_set1(s->triangles[ob->first].ng);
    else
      ng = vv_gather((const float *)s->triangles, h->prim,
                     FLOATS_OF(triangle_r), FLOAT_OFFSET(triangle_r, ng));
    f.front = vf_lt(vv_dot(ng, d), vf_zero());
    if (ob->smooth) {
      /* Interpolated vertex normals (NFF polygonal patches). */
      vint n0 = vf_bits(
          vf_gather((const float *)s->triangles,
                    vi_add(vi_mul_const(h->prim, FLOATS_OF(triangle_r)),
                           vi_set1(FLOAT_OFFSET(triangle_r, normals)))));
      /* Lanes outside the sub-beam may hold a flat triangle's -1. */
      n0 = vi_mul_const(vi_select(vi_eq(n0, vi_set1(-1)), vi_set1(0), n0), 3);
      const float *nb = (const float *)s->normals;
      vvec3 a = vv_gather(nb, n0, 1, 0);
      vvec3 b = vv_gather(nb, n0, 1, 3);
      vvec3 c = vv_gather(nb, n0, 1, 6);
      vfloat w = vf_sub(vf_sub(vf_set1(1), h->u), h->v);
      vvec3 n = vv_madd(vv_madd(vv_scale(a, w), h->u, b), h->v, c);
      n = vv_normalize(n, newton);
      vmask facing = vf_lt(vv_dot(n, d), vf_zero());
      f.n = vv_select(facing, n, vv_neg(n));
      return f;
    }
    break;
  }
  f.n = vv_select(f.front, ng, vv_neg(ng));
  return f;
}

/* floor(a) mod 2, as 0 or 1, without integer conversion (exact while the
 * cell index fits a float's 24 bits; farther out every index is even). */
static ALWAYS_INLINE vfloat vf_parity(vfloat f) {
  return vf_fnmadd(vf_set1(2), vf_floor(vf_mul(f, vf_set1(0.5f))), f);
}

/* The surface colour C (SPEC §4 textures) for one material: the parity of
 * the sum of the cell indices picks the checker colour. */
static ALWAYS_INLINE vvec3 packet_color(const material_r *m,
                                        const pmaterial *pm, const object_r *ob,
                                        vvec3 p) {
  if (m->texture == GLINT_TEXTURE_NONE)
    return vv_get(pm->color);
  vfloat cells;
  vfloat inv = vs_get(&pm->inv_size);
  if (m->texture == GLINT_TEXTURE_CHECKER_PLANAR) {
    vfloat axes[3] = {p.x, p.y, p.z};
    cells = vf_add(vf_floor(vf_mul(axes[ob->axis_u], inv)),
                   vf_floor(vf_mul(axes[ob->axis_v], inv)));
  } else {
    vvec3 q = vv_scale(vv_sub(p, vv_set1(ob->origin)), inv);
    cells = vf_add(vf_add(vf_floor(q.x), vf_floor(q.y)), vf_floor(q.z));
  }
  vmask odd = vf_eq(vf_parity(cells), vf_set1(1));
  return vv_select(odd, vv_get(pm->odd), vv_get(pm->even));
}

/* The unit direction l from p to a light, its distance, and N·l; returns
 * the lanes of m that face the light (the others need no shadow ray). */
static ALWAYS_INLINE vmask packet_toward_light(const plight *li, vvec3 p,
                                               vvec3 n, vmask m, int newton,
                                               vvec3 *l, vfloat *dist,
                                               vfloat *nl) {
  vvec3 v = vv_sub(vv_get(li->position), p);
  vfloat dist2 = vv_dot(v, v);
  vfloat inv = vf_rsqrt(dist2, newton);
  *dist = vf_mul(dist2, inv);
  *l = vv_scale(v, inv);
  *nl = vv_dot(n, *l);
  return vm_and(m, vf_gt(*nl, vf_zero()));
}

/* Eq. 2.9/2.10's local part for the lanes of m, whose coefficients may
 * differ lane by lane (a beam's sub-beams, a stream's mixed packet) or not:
 *   C (ka Ia + sum S kd N·L IL) + sum S ks (V·R)^h IL,
 * one shadow packet per light. `highlights` = 0 says no lane has ks > 0.
 * When `shadow_ticks` is given, the time-stamp cycles spent tracing shadow
 * rays are added to it (the stream tracer's stage timing). */
static ALWAYS_INLINE vvec3 packet_lights(
    const packet_scene *ps, const packet_surface *f, vvec3 d, vmask m, vvec3 c,
    vvec3 ambient, vfloat kd, vfloat ks, vfloat h, int highlights,
    glint_math math, int newton, glint_stats *st, uint64_t *shadow_ticks) {
  const scene_r *s = ps->s;
  vvec3 diffuse = ambient;
  vvec3 highlight = {vf_zero(), vf_zero(), vf_zero()};
  for (size_t j = 0; j < s->light_count; j++) {
    const plight *li = &ps->lights[j];
    vvec3 l;
    vfloat dist, nl;
    vmask lit = packet_toward_light(li, f->p, f->n, m, newton, &l, &dist, &nl);
    if (vm_none(lit))
      continue;
    st->shadow_rays += (uint64_t)vm_count(lit);
    uint64_t t0 = shadow_ticks ? __rdtsc() : 0;
    vvec3 sj = packet_transmission(ps, f->p, l, dist, lit, math, newton, st);
    if (shadow_ticks)
      *shadow_ticks += __rdtsc() - t0;
    vvec3 il = vv_mul(sj, vv_get(li->color));
    diffuse = vv_madd(diffuse, vf_keep(lit, vf_mul(kd, nl)), il);
    if (highlights) {
      /* R = 2(L·N)N - L, and V = -D: V·R = 2(L·N)(-D·N) + D·L */
      vfloat vr =
          vf_fmadd(vf_add(nl, nl), vf_neg(vv_dot(d, f->n)), vv_dot(d, l));
      vmask hl =
          vm_and(vm_and(lit, vf_gt(ks, vf_zero())), vf_gt(vr, vf_zero()));
      if (vm_any(hl)) {
        vfloat p = vm_pow(vf_max(vr, vf_set1(FLT_MIN)), h, math);
        highlight = vv_madd(highlight, vf_keep(hl, vf_mul(ks, p)), il);
      }
    }
  }
  return vv_add(vv_mul(c, diffuse), highlight);
}

/* Eq. 2.12 and 2.13 for the lanes of m. The refracted directions are valid
 * in *refract_mask; lanes with total internal reflection are not in it and
 * their reflection weight is kr + kt. */
static ALWAYS_INLINE void packet_secondary(const material_r *mat,
                                           const pmaterial *pm,
                                           const packet_surface *f, vvec3 d,
                                           vmask m, vvec3 *reflected,
                                           vfloat *kr, vvec3 *refracted,
                                           vmask *refract_mask, vmask *tir) {
  vfloat cosi = vf_neg(vv_dot(d, f->n));
  *reflected = vv_madd(d, vf_add(cosi, cosi), f->n);
  *kr = vs_get(&pm->kr);
  *refract_mask = vm_false();
  *tir = vm_false();
  if (mat->kt > 0) {
    vfloat eta = vf_select(f->front, vs_get(&pm->eta_in), vs_get(&pm->eta_out));
    vfloat k = vf_fnmadd(vf_mul(eta, eta), vf_fnmadd(cosi, cosi, vf_set1(1)),
                         vf_set1(1));
    *tir = vm_and(m, vf_lt(k, vf_zero()));
    *refract_mask = vm_andnot(m, *tir);
    vfloat coef = vf_sub(vf_mul(eta, cosi), vf_sqrt(vf_max(k, vf_zero())));
    *refracted = vv_madd(vv_scale(d, eta), coef, f->n);
    *kr = vf_select(*tir, vs_get(&pm->kr_tir), *kr);
  }
}

/* Beer's law (eq. 2.11) on the lanes that travelled inside the object. */
static ALWAYS_INLINE vvec3 packet_beer(const material_r *mat,
                                       const pmaterial *pm,
                                       const packet_surface *f, vfloat t,
                                       vmask m, vvec3 color, glint_math math) {
  if (!mat->absorbs)
    return color;
  vmask inside = vm_andnot(m, f->front);
  if (vm_none(inside))
    return color;
  vfloat nt = vf_neg(t);
  /* exp(0) = 1: channels that absorb nothing are left alone. */
  if (mat->absorb.x != 0)
    color.x = vf_select(
        inside,
        vf_mul(color.x, vm_exp(vf_mul(vs_get(&pm->absorb[0]), nt), math)),
        color.x);
  if (mat->absorb.y != 0)
    color.y = vf_select(
        inside,
        vf_mul(color.y, vm_exp(vf_mul(vs_get(&pm->absorb[1]), nt), math)),
        color.y);
  if (mat->absorb.z != 0)
    color.z = vf_select(
        inside,
        vf_mul(color.z, vm_exp(vf_mul(vs_get(&pm->absorb[2]), nt), math)),
        color.z);
  return color;
}

#endif
