/* The Whitted model for W lanes at once (docs/specification.md §4; thesis
 * eq. 2.9-2.13): surfaces, textures, the lights' local part, reflection and
 * refraction, and Beer's law, compiled once per ISA and used by both packet
 * backends (beam_tracer.c, stream_tracer.c). The scalar reference is
 * render/scalar_tracer.c. */
#ifndef GLINT_RENDER_PACKET_SHADING_H
#define GLINT_RENDER_PACKET_SHADING_H

#include "geometry/packet_intersect.h"
#include "render/frame.h"
#include "render/packet_rays.h"
#include "simd/vmath.h"

#include <float.h>
#include <stddef.h>
#include <x86intrin.h>

/* ---- per-lane materials and objects ----------------------------------- */

#define FLOATS_OF(type) ((int)(sizeof(type) / sizeof(float)))
#define FLOAT_OFFSET(type, field) ((int)(offsetof(type, field) / sizeof(float)))

static ALWAYS_INLINE vfloat gather_f(const void *base, vint index, int stride,
                                     int offset) {
  return vf_gather((const float *)base,
                   vi_add(vi_mul_const(index, stride), vi_set1(offset)));
}

static ALWAYS_INLINE vint gather_i(const void *base, vint index, int stride,
                                   int offset) {
  return vf_bits(gather_f(base, index, stride, offset));
}

/* The material coefficients of each lane. The shading functions below read
 * only these, so one implementation serves a packet that hit one material
 * (a beam's sub-beam, most of a stream's packets: the values broadcast) and
 * a packet whose lanes hit different ones (gathered per lane). */
typedef struct lane_material {
  /* Uniform: the one material, read (broadcast) where it is used, so a
   * beam pays only for the coefficients it needs. */
  int uniform;
  const material_r *m; /* NULL when mixed */
  const pmaterial *pm;
  /* Mixed: the gathered coefficients. */
  vvec3 color, odd, even, ambient, absorb;
  vfloat inv_size, kd, ks, h, kr, kt, kr_tir, eta_in, eta_out;
  vint texture;
} lane_material;

/* A coefficient of every lane, whichever form the packet has. */
#define LANE_SCALAR(lm, field)                                                 \
  ((lm)->uniform ? vs_get(&(lm)->pm->field) : (lm)->field)
#define LANE_VEC3(lm, field)                                                   \
  ((lm)->uniform ? vv_get((lm)->pm->field) : (lm)->field)

/* Where a lane's textures are anchored: the object's solid-texture origin
 * and the world axes of its planar texture. */
typedef struct lane_object {
  vvec3 origin;
  vint axis_u, axis_v;
  const object_r *ob; /* a uniform packet's one object; NULL: mixed */
} lane_object;

static ALWAYS_INLINE lane_material lane_material_uniform(const packet_scene *ps,
                                                         uint32_t id) {
  lane_material lm;
  lm.uniform = 1;
  lm.m = &ps->s->materials[id];
  lm.pm = &ps->materials[id];
  return lm;
}

/* Material mi[lane] for the lanes of `hits` (the others read material 0):
 * broadcast when they all hit one material, gathered otherwise. */
static ALWAYS_INLINE lane_material lane_material_gather(const packet_scene *ps,
                                                        vint mi, vmask hits) {
  SIMD_ALIGN int32_t ids[LANES];
  vi_store(ids, mi);
  int id = ids[vm_first(hits)];
  if (vm_none(vm_andnot(hits, vi_eq(mi, vi_set1(id)))))
    return lane_material_uniform(ps, (uint32_t)id);
  const scene_r *s = ps->s;
  const material_r *mb = s->materials;
  const int stride = FLOATS_OF(material_r);
  lane_material lm;
  lm.uniform = 0;
  lm.m = NULL;
  lm.pm = NULL;
  lm.color =
      vv_gather((const float *)mb, mi, stride, FLOAT_OFFSET(material_r, color));
  lm.odd =
      vv_gather((const float *)mb, mi, stride, FLOAT_OFFSET(material_r, odd));
  lm.even =
      vv_gather((const float *)mb, mi, stride, FLOAT_OFFSET(material_r, even));
  lm.absorb = vv_gather((const float *)mb, mi, stride,
                        FLOAT_OFFSET(material_r, absorb));
  lm.inv_size = gather_f(mb, mi, stride, FLOAT_OFFSET(material_r, inv_size));
  vfloat ka = gather_f(mb, mi, stride, FLOAT_OFFSET(material_r, ka));
  lm.ambient = vv_scale(vv_set1(s->ambient), ka);
  lm.kd = gather_f(mb, mi, stride, FLOAT_OFFSET(material_r, kd));
  lm.ks = gather_f(mb, mi, stride, FLOAT_OFFSET(material_r, ks));
  lm.h = gather_f(mb, mi, stride, FLOAT_OFFSET(material_r, h));
  lm.kr = gather_f(mb, mi, stride, FLOAT_OFFSET(material_r, kr));
  lm.kt = gather_f(mb, mi, stride, FLOAT_OFFSET(material_r, kt));
  lm.kr_tir = vf_add(lm.kr, lm.kt);
  /* As packet_scene.c computes them: 1/ior entering, ior leaving. */
  lm.eta_out = gather_f(mb, mi, stride, FLOAT_OFFSET(material_r, ior));
  lm.eta_in = vf_div(vf_set1(1), lm.eta_out);
  lm.texture = gather_i(mb, mi, stride, FLOAT_OFFSET(material_r, texture));
  return lm;
}

static ALWAYS_INLINE lane_object lane_object_uniform(const object_r *ob) {
  lane_object lo = {vv_set1(ob->origin), vi_set1(ob->axis_u),
                    vi_set1(ob->axis_v), ob};
  return lo;
}

/* ---- surfaces ----------------------------------------------------------- */

/* Where the lanes met their surfaces, with the normal facing the ray. */
typedef struct packet_surface {
  vvec3 p, n;
  vmask front; /* hit the outside: entering a closed object */
} packet_surface;

/* Interpolated vertex normals (NFF polygonal patches) of the triangles
 * whose first normal index is n0 (x3 floats), facing the ray; where they
 * cancel (zero normals in the file, or opposite ones), the geometric normal
 * `flat`, already facing the ray, as the scalar tracer does. */
static ALWAYS_INLINE vvec3 packet_smooth_normal(const scene_r *s, vint n0,
                                                const packet_hit *h, vvec3 d,
                                                vvec3 flat, int newton) {
  const float *nb = (const float *)s->normals;
  vvec3 a = vv_gather(nb, n0, 1, 0);
  vvec3 b = vv_gather(nb, n0, 1, 3);
  vvec3 c = vv_gather(nb, n0, 1, 6);
  vfloat w = vf_sub(vf_sub(vf_set1(1), h->u), h->v);
  vvec3 m = vv_madd(vv_madd(vv_scale(a, w), h->u, b), h->v, c);
  vmask some = vf_gt(vv_dot(m, m), vf_zero());
  vvec3 n = vv_normalize(vv_select(some, m, flat), newton);
  vvec3 facing = vv_select(vf_lt(vv_dot(n, d), vf_zero()), n, vv_neg(n));
  return vv_select(some, facing, flat);
}

/* The surface of lanes that all hit one object. */
static ALWAYS_INLINE packet_surface
packet_surface_object(const packet_scene *ps, const object_r *ob,
                      const packet_hit *h, vvec3 o, vvec3 d, int newton) {
  const scene_r *s = ps->s;
  packet_surface f;
  f.p = vv_madd(o, h->t, d);
  vvec3 ng;
  switch (ob->shape) {
  case GLI_SHAPE_SPHERE:
    ng = packet_sphere_normal(vv_get(ps->spheres[ob->first].center), f.p,
                              newton);
    f.front = vm_andnot(vm_true(), h->inside);
    break;
  case GLI_SHAPE_PLANE:
    ng = vv_get(ps->planes[ob->first].n);
    f.front = vf_lt(vv_dot(ng, d), vf_zero());
    break;
  case GLI_SHAPE_CONE: {
    const pcone *c = &ps->cones[ob->first];
    ng = vv_normalize(packet_cone_normal(vv_get(c->base), vv_get(c->axis),
                                         vs_get(&c->rb), vs_get(&c->k), f.p),
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
      vint n0 = gather_i(s->triangles, h->prim, FLOATS_OF(triangle_r),
                         FLOAT_OFFSET(triangle_r, normals));
      /* Lanes outside the sub-beam may hold a flat triangle's -1. */
      n0 = vi_mul_const(vi_select(vi_eq(n0, vi_set1(-1)), vi_set1(0), n0), 3);
      f.n = packet_smooth_normal(s, n0, h, d,
                                 vv_select(f.front, ng, vv_neg(ng)), newton);
      return f;
    }
    break;
  }
  f.n = vv_select(f.front, ng, vv_neg(ng));
  return f;
}

/* The surface of lanes that hit different objects (a stream's mixed
 * packet): each shape's lanes computed under a mask. Also gives each lane's
 * material index and texture anchor. */
static ALWAYS_INLINE packet_surface packet_surface_lanes(
    const packet_scene *ps, const packet_hit *h, vmask hits, vvec3 o, vvec3 d,
    int newton, vint *material, lane_object *lo) {
  const scene_r *s = ps->s;
  packet_surface f;
  f.p = vv_madd(o, h->t, d);
  vint obj = vi_select(hits, h->object, vi_set1(0)); /* misses: object 0 */
  const object_r *ob = s->objects;
  const int os = FLOATS_OF(object_r);
  vint shape = gather_i(ob, obj, os, FLOAT_OFFSET(object_r, shape));
  vint first = gather_i(ob, obj, os, FLOAT_OFFSET(object_r, first));
  /* Each shape's gathers index its own array with the lanes of that shape
   * only; the others read element 0, never past an array's end. */
  const vint none = vi_set1(0);
  *material = gather_i(ob, obj, os, FLOAT_OFFSET(object_r, material));
  lo->origin =
      vv_gather((const float *)ob, obj, os, FLOAT_OFFSET(object_r, origin));
  lo->axis_u = gather_i(ob, obj, os, FLOAT_OFFSET(object_r, axis_u));
  lo->axis_v = gather_i(ob, obj, os, FLOAT_OFFSET(object_r, axis_v));
  lo->ob = NULL;
  vvec3 zero = {vf_zero(), vf_zero(), vf_zero()};
  vvec3 ng = zero, n = zero;
  f.front = vm_false();
  vmask smooth_done = vm_false();

  vmask sph = vm_and(hits, vi_eq(shape, vi_set1(GLI_SHAPE_SPHERE)));
  if (vm_any(sph)) {
    vvec3 c = vv_gather((const float *)s->spheres, vi_select(sph, first, none),
                        FLOATS_OF(sphere_r), FLOAT_OFFSET(sphere_r, center));
    ng = vv_select(sph, packet_sphere_normal(c, f.p, newton), ng);
    f.front = vm_select(sph, vm_andnot(vm_true(), h->inside), f.front);
  }
  vmask pla = vm_and(hits, vi_eq(shape, vi_set1(GLI_SHAPE_PLANE)));
  if (vm_any(pla)) {
    vvec3 g = vv_gather((const float *)s->planes, vi_select(pla, first, none),
                        FLOATS_OF(plane_r), FLOAT_OFFSET(plane_r, n));
    ng = vv_select(pla, g, ng);
    f.front = vm_select(pla, vf_lt(vv_dot(g, d), vf_zero()), f.front);
  }
  vmask tri = vm_and(hits, vi_eq(shape, vi_set1(GLI_SHAPE_TRIANGLE)));
  if (vm_any(tri)) {
    vint prim = vi_select(tri, h->prim, none);
    vvec3 g = vv_gather((const float *)s->triangles, prim,
                        FLOATS_OF(triangle_r), FLOAT_OFFSET(triangle_r, ng));
    ng = vv_select(tri, g, ng);
    f.front = vm_select(tri, vf_lt(vv_dot(g, d), vf_zero()), f.front);
    vint nidx = gather_i(s->triangles, prim, FLOATS_OF(triangle_r),
                         FLOAT_OFFSET(triangle_r, normals));
    vmask smooth = vm_andnot(tri, vi_eq(nidx, vi_set1(-1)));
    if (vm_any(smooth)) {
      vint n0 = vi_mul_const(vi_select(smooth, nidx, none), 3);
      vvec3 flat = vv_select(f.front, ng, vv_neg(ng));
      n = vv_select(smooth, packet_smooth_normal(s, n0, h, d, flat, newton), n);
      smooth_done = smooth;
    }
  }
  vmask con = vm_and(hits, vi_eq(shape, vi_set1(GLI_SHAPE_CONE)));
  if (vm_any(con)) {
    const float *cb = (const float *)s->cones;
    int stride = FLOATS_OF(cone_r);
    first = vi_select(con, first, none);
    vvec3 g = vv_normalize(
        packet_cone_normal(
            vv_gather(cb, first, stride, FLOAT_OFFSET(cone_r, base)),
            vv_gather(cb, first, stride, FLOAT_OFFSET(cone_r, axis)),
            gather_f(cb, first, stride, FLOAT_OFFSET(cone_r, rb)),
            gather_f(cb, first, stride, FLOAT_OFFSET(cone_r, k)), f.p),
        newton);
    ng = vv_select(con, g, ng);
    f.front = vm_select(con, vf_lt(vv_dot(g, d), vf_zero()), f.front);
  }
  f.n = vv_select(smooth_done, n, vv_select(f.front, ng, vv_neg(ng)));
  return f;
}

/* ---- textures ----------------------------------------------------------- */

/* floor(a) mod 2, as 0 or 1, without integer conversion (exact while the
 * cell index fits a float's 24 bits; farther out every index is even). */
static ALWAYS_INLINE vfloat vf_parity(vfloat f) {
  return vf_fnmadd(vf_set1(2), vf_floor(vf_mul(f, vf_set1(0.5f))), f);
}

/* Component `axis` (0, 1, 2 per lane) of p. */
static ALWAYS_INLINE vfloat vv_component(vvec3 p, vint axis) {
  return vf_select(vi_eq(axis, vi_set1(0)), p.x,
                   vf_select(vi_eq(axis, vi_set1(1)), p.y, p.z));
}

/* The surface colour C per lane (docs/specification.md §4 textures): the parity
 * of the sum of the checker cell indices picks the odd or even colour. */
static ALWAYS_INLINE vfloat checker_cells_planar(vfloat u, vfloat v,
                                                 vfloat inv_size) {
  return vf_add(vf_floor(vf_mul(u, inv_size)), vf_floor(vf_mul(v, inv_size)));
}

static ALWAYS_INLINE vfloat checker_cells_solid(vvec3 p, vvec3 origin,
                                                vfloat inv_size) {
  vvec3 q = vv_scale(vv_sub(p, origin), inv_size);
  return vf_add(vf_add(vf_floor(q.x), vf_floor(q.y)), vf_floor(q.z));
}

static ALWAYS_INLINE vvec3 checker_pick(const lane_material *lm, vfloat cells) {
  vmask odd = vf_eq(vf_parity(cells), vf_set1(1));
  return vv_select(odd, LANE_VEC3(lm, odd), LANE_VEC3(lm, even));
}

static ALWAYS_INLINE vvec3 packet_color(const lane_material *lm,
                                        const lane_object *lo, vvec3 p,
                                        vmask hits) {
  if (lm->uniform && lo->ob) { /* one material on one object */
    switch (lm->m->texture) {
    case GLINT_TEXTURE_CHECKER_PLANAR: {
      vfloat axes[3] = {p.x, p.y, p.z};
      return checker_pick(lm, checker_cells_planar(axes[lo->ob->axis_u],
                                                   axes[lo->ob->axis_v],
                                                   vs_get(&lm->pm->inv_size)));
    }
    case GLINT_TEXTURE_CHECKER_SOLID:
      return checker_pick(
          lm, checker_cells_solid(p, lo->origin, vs_get(&lm->pm->inv_size)));
    default: return vv_get(lm->pm->color);
    }
  }
  vint texture = lm->uniform ? vi_set1(lm->m->texture) : lm->texture;
  vmask planar =
      vm_and(hits, vi_eq(texture, vi_set1(GLINT_TEXTURE_CHECKER_PLANAR)));
  vmask solid =
      vm_and(hits, vi_eq(texture, vi_set1(GLINT_TEXTURE_CHECKER_SOLID)));
  if (vm_none(vm_or(planar, solid)))
    return LANE_VEC3(lm, color);
  vfloat cells = vf_zero();
  if (vm_any(planar))
    cells = vf_select(planar,
                      checker_cells_planar(vv_component(p, lo->axis_u),
                                           vv_component(p, lo->axis_v),
                                           LANE_SCALAR(lm, inv_size)),
                      cells);
  if (vm_any(solid))
    cells = vf_select(
        solid, checker_cells_solid(p, lo->origin, LANE_SCALAR(lm, inv_size)),
        cells);
  return vv_select(vm_or(planar, solid), checker_pick(lm, cells),
                   LANE_VEC3(lm, color));
}

/* ---- the lights: local shading ------------------------------------------- */

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

/* Light li's unshadowed terms in eq. 2.9/2.10 for the lanes of m, whose
 * coefficients may differ lane by lane (a beam's sub-beams, a stream's
 * mixed packet) or not: the lanes it lights, the direction and distance to
 * it, and the weights of its intensity S IL, kd N·L on the surface colour
 * and ks (V·R)^h beside it (zero where `highlights` = 0, which says no lane
 * has ks > 0). */
typedef struct light_terms {
  vmask lit;
  vvec3 l;
  vfloat dist, diffuse, highlight;
} light_terms;

static ALWAYS_INLINE light_terms packet_light_terms(
    const plight *li, const packet_surface *f, vvec3 d, vmask m, vfloat kd,
    vfloat ks, vfloat h, int highlights, glint_math math, int newton) {
  light_terms r;
  vfloat nl;
  r.lit = packet_toward_light(li, f->p, f->n, m, newton, &r.l, &r.dist, &nl);
  r.diffuse = vf_keep(r.lit, vf_mul(kd, nl));
  r.highlight = vf_zero();
  if (highlights) {
    /* R = 2(L·N)N - L, and V = -D: V·R = 2(L·N)(-D·N) + D·L */
    vfloat vr =
        vf_fmadd(vf_add(nl, nl), vf_neg(vv_dot(d, f->n)), vv_dot(d, r.l));
    vmask hl =
        vm_and(vm_and(r.lit, vf_gt(ks, vf_zero())), vf_gt(vr, vf_zero()));
    if (vm_any(hl)) {
      vfloat p = vm_pow(vf_max(vr, vf_set1(FLT_MIN)), h, math);
      r.highlight = vf_keep(hl, vf_mul(ks, p));
    }
  }
  return r;
}

/* The transmission S of a light's shadow rays (the lanes lt->lit of
 * packet_light_terms), traced at once from the surface's points, with
 * their origins' slab terms po. When `ticks` is given, the time-stamp
 * cycles the trace took are added to it. */
static ALWAYS_INLINE vvec3 light_transmission(
    const packet_scene *ps, const packet_surface *f, const packet_origin *po,
    const light_terms *lt, glint_math math, int newton, glint_stats *st,
    uint64_t *ticks) {
  uint64_t t0 = ticks ? __rdtsc() : 0;
  vvec3 sj = packet_transmission(ps, f->p, po, lt->l, lt->dist, lt->lit, math,
                                 newton, st);
  if (ticks)
    *ticks += __rdtsc() - t0;
  return sj;
}

/* Eq. 2.9/2.10's local part for the lanes of m,
 *   C (ka Ia + sum S kd N·L IL) + sum S ks (V·R)^h IL,
 * one shadow packet per light (packet_light_terms says what the arguments
 * are). When `shadow_ticks` is given, the time-stamp cycles spent tracing
 * shadow rays are added to it (the stream tracer's stage timing). */
static ALWAYS_INLINE vvec3 packet_lights(
    const packet_scene *ps, const packet_surface *f, vvec3 d, vmask m, vvec3 c,
    vvec3 ambient, vfloat kd, vfloat ks, vfloat h, int highlights,
    glint_math math, int newton, glint_stats *st, uint64_t *shadow_ticks) {
  const scene_r *s = ps->s;
  vvec3 diffuse = ambient;
  vvec3 highlight = {vf_zero(), vf_zero(), vf_zero()};
  /* only the BVH's walks read it */
  packet_origin po;
  if (s->bvh->node_count)
    po = packet_origin_of(f->p);
  for (size_t j = 0; j < s->light_count; j++) {
    const plight *li = &ps->lights[j];
    light_terms lt =
        packet_light_terms(li, f, d, m, kd, ks, h, highlights, math, newton);
    if (vm_none(lt.lit))
      continue;
    st->shadow_rays += (uint64_t)vm_count(lt.lit);
    vvec3 sj =
        light_transmission(ps, f, &po, &lt, math, newton, st, shadow_ticks);
    vvec3 il = vv_mul(sj, vv_get(li->color));
    diffuse = vv_madd(diffuse, lt.diffuse, il);
    if (highlights)
      highlight = vv_madd(highlight, lt.highlight, il);
  }
  return vv_add(vv_mul(c, diffuse), highlight);
}

/* ---- secondary rays and Beer's law --------------------------------------- */

/* Eq. 2.12 and 2.13 for the lanes of m. The refracted directions are valid
 * in *refract_mask; lanes with total internal reflection are not in it and
 * their reflection weight is kr + kt. */
static ALWAYS_INLINE void packet_secondary(const lane_material *lm,
                                           const packet_surface *f, vvec3 d,
                                           vmask m, vvec3 *reflected,
                                           vfloat *kr, vvec3 *refracted,
                                           vmask *refract_mask, vmask *tir) {
  vfloat cosi = vf_neg(vv_dot(d, f->n));
  *reflected = vv_madd(d, vf_add(cosi, cosi), f->n);
  *kr = LANE_SCALAR(lm, kr);
  *refract_mask = vm_false();
  *tir = vm_false();
  vmask transparent = lm->uniform ? (lm->m->kt > 0 ? m : vm_false())
                                  : vm_and(m, vf_gt(lm->kt, vf_zero()));
  if (vm_none(transparent)) {
    *refracted = d; /* defined, for the callers' masked stores */
    return;
  }
  vfloat eta =
      vf_select(f->front, LANE_SCALAR(lm, eta_in), LANE_SCALAR(lm, eta_out));
  vfloat k = vf_fnmadd(vf_mul(eta, eta), vf_fnmadd(cosi, cosi, vf_set1(1)),
                       vf_set1(1));
  *tir = vm_and(transparent, vf_lt(k, vf_zero()));
  *refract_mask = vm_andnot(transparent, *tir);
  vfloat coef = vf_sub(vf_mul(eta, cosi), vf_sqrt(vf_max(k, vf_zero())));
  *refracted = vv_madd(vv_scale(d, eta), coef, f->n);
  *kr = vf_select(*tir, LANE_SCALAR(lm, kr_tir), *kr);
}

/* The lanes whose ray weight is worth tracing (GLI_MIN_RAY_WEIGHT in
 * render/frame.h): its largest channel at least 2^-24. */
static ALWAYS_INLINE vmask packet_worth_tracing(vvec3 w) {
  return vf_ge(vf_max(vf_max(w.x, w.y), w.z), vf_set1(GLI_MIN_RAY_WEIGHT));
}

/* A child ray's weight, w k, held at GLI_MAX_RAY_WEIGHT (render/frame.h). */
static ALWAYS_INLINE vvec3 packet_child_weight(vvec3 w, vfloat k) {
  vfloat cap = vf_set1(GLI_MAX_RAY_WEIGHT);
  vvec3 c = vv_scale(w, k);
  c.x = vf_min(c.x, cap), c.y = vf_min(c.y, cap), c.z = vf_min(c.z, cap);
  return c;
}

/* Beer's law (eq. 2.11) on the lanes of m that travelled inside their
 * object: color exp(-a t) per channel. */
static ALWAYS_INLINE vvec3 packet_beer(const lane_material *lm,
                                       const packet_surface *f, vfloat t,
                                       vmask m, vvec3 color, glint_math math) {
  if (lm->uniform && !lm->m->absorbs)
    return color;
  vmask inside = vm_andnot(m, f->front);
  if (vm_none(inside))
    return color;
  vfloat nt = vf_neg(t);
  vvec3 absorb = LANE_VEC3(lm, absorb);
  /* exp(0) = 1: a uniform material's channels that absorb nothing are left
   * alone. */
  if (!lm->uniform || lm->m->absorb.x != 0)
    color.x = vf_select(
        inside, vf_mul(color.x, vm_beer(vf_mul(absorb.x, nt), math)), color.x);
  if (!lm->uniform || lm->m->absorb.y != 0)
    color.y = vf_select(
        inside, vf_mul(color.y, vm_beer(vf_mul(absorb.y, nt), math)), color.y);
  if (!lm->uniform || lm->m->absorb.z != 0)
    color.z = vf_select(
        inside, vf_mul(color.z, vm_beer(vf_mul(absorb.z, nt), math)), color.z);
  return color;
}

#endif
