/* The beam tracer (docs/specification.md §6, thesis chapter 4): W rays traced
 * together in SIMD registers. A beam finds each lane's nearest hit, splits into
 * one sub-beam per object hit (§4.3, after Boulos et al. 2007), shades each
 * sub-beam with its object's material in SIMD, and traces at most one reflected
 * and one refracted beam per sub-beam, recursively. Primary beams come from
 * screen blocks shaped to the width: 2x2 (SSE), 4x2 (AVX2), 4x4 (AVX-512).
 *
 * This file is compiled once per ISA (see simd/simd.h). It is instantiated
 * twice more inside: once with the default maths as compile-time constants
 * (minimax pow/exp, Newton-refined rcp), which is the fast path, and once
 * reading --math and --no-newton at run time, for the experiments of the
 * thesis's §5.4.
 *
 * And it is compiled twice per ISA: render/beam_tracer_plain.c includes it
 * with BEAM_PLAIN, for views whose BVH has no hand-over points
 * (accel/packet_traverse.h), whose tiles then take a tracer without the
 * hybrid walks: the walks' mere presence cost the smallest renders 5-10%
 * (Whitted and Giza at depth 1, tetra-s6). */
#ifndef BEAM_PLAIN
#define BEAM_PLAIN 0
#endif
#if BEAM_PLAIN
#define PACKET_HAND_OVER 0
#endif

#include "render/backend.h"
#include "render/packet_shading.h"
#include "render/primary.h"

typedef struct beam_ctx {
  const packet_scene *ps;
  glint_math math;
  int newton;
  int max_depth;
  glint_stats *st;
} beam_ctx;

/* What a traced beam takes in and gives back: `weight`, the product of the
 * coefficients that scale what each lane brings to its pixel
 * (GLI_MIN_RAY_WEIGHT), and the colour it finds. One pointer for both, so
 * that the recursive call's six arguments all travel in registers (as two,
 * the seventh went through the stack: Giza at depth 15 rendered 2-3%
 * slower with AVX-512 and AVX2). */
typedef struct beam_io {
  vvec3 weight, color;
} beam_io;

/* Rays are passed by pointer: by value, each call would copy six vectors
 * through the stack. */
typedef void (*trace_fn)(const beam_ctx *c, const vvec3 *o, const vvec3 *d,
                         vmask active, int level, beam_io *io);

/* The thesis's sub-beam after shading: below the depth limit it traces at
 * most one reflected and one refracted beam (docs/specification.md §6) of
 * the lanes whose weight is worth it, then Beer's law. */
static ALWAYS_INLINE void
finish_sub_beam(const beam_ctx *c, vvec3 d, const packet_hit *h,
                const packet_surface *f, int object, vmask sub, int level,
                const vvec3 *weight, vvec3 color, vvec3 *out, glint_math math,
                trace_fn trace) {
  const packet_scene *ps = c->ps;
  const scene_r *s = ps->s;
  lane_material lm = lane_material_uniform(ps, s->objects[object].material);
  /* Beer's law (eq. 2.11) scales what this surface brings, children
   * included: its factor (1 where nothing is absorbed) once for both. */
  vvec3 w = *weight, beer = {vf_set1(1), vf_set1(1), vf_set1(1)};
  if (lm.m->absorbs) {
    beer = packet_beer(&lm, f, h->t, sub, beer, math);
    w = vv_mul(w, beer);
  }
  if (level < c->max_depth && (lm.m->kr > 0 || lm.m->kt > 0)) {
    vvec3 reflected, refracted;
    vfloat kr;
    vmask refract, tir;
    packet_secondary(&lm, f, d, sub, &reflected, &kr, &refracted, &refract,
                     &tir);
    c->st->total_internal_reflections += (uint64_t)vm_count(tir);
    vvec3 wt = vv_scale(w, LANE_SCALAR(&lm, kt));
    refract = vm_and(refract, packet_worth_tracing(wt));
    if (vm_any(refract)) {
      vvec3 ct;
      c->st->secondary_rays += (uint64_t)vm_count(refract);
      c->st->refracted_rays += (uint64_t)vm_count(refract);
      beam_io io;
      io.weight = wt;
      trace(c, &f->p, &refracted, refract, level + 1, &io);
      ct = io.color;
      vfloat kt = vf_keep(refract, LANE_SCALAR(&lm, kt));
      color = vv_madd(color, kt, ct);
    }
    vvec3 wr = vv_scale(w, kr);
    vmask reflect =
        vm_and(vm_and(sub, vf_gt(kr, vf_zero())), packet_worth_tracing(wr));
    if (vm_any(reflect)) {
      vvec3 cr;
      c->st->secondary_rays += (uint64_t)vm_count(reflect);
      c->st->reflected_rays += (uint64_t)vm_count(reflect);
      beam_io io;
      io.weight = wr;
      trace(c, &f->p, &reflected, reflect, level + 1, &io);
      cr = io.color;
      color = vv_madd(color, vf_keep(reflect, kr), cr);
    }
  }
  if (lm.m->absorbs)
    color = vv_mul(color, beer);
  *out = vv_select(sub, color, *out);
}

/* One beam: nearest hits; one sub-beam per object hit (the thesis's
 * criterion; grouping lanes by object yields the same sub-beams as its Hit
 * stack, listings 4.1–4.3, without the capacity-W bookkeeping); local
 * shading; then each sub-beam's secondary beams.
 *
 * Shadow rays are traced as one beam per light for all the lanes that hit
 * something (docs/specification.md §6: "shadow rays for a beam are traced as a
 * beam too"), not one per sub-beam: a beam that meets many small objects would
 * otherwise cast nearly empty shadow packets. Each lane's material
 * coefficients are gathered from its sub-beam so the light loop runs once. */
static ALWAYS_INLINE void trace_beam_body(const beam_ctx *c, vvec3 o, vvec3 d,
                                          vmask active, int level,
                                          const vvec3 *weight, vvec3 *color,
                                          glint_math math, int newton,
                                          trace_fn trace) {
  const packet_scene *ps = c->ps;
  const scene_r *s = ps->s;
  c->st->beams++;
  packet_hit h;
  packet_nearest(ps, o, d, active, newton, &h, c->st);
  *color = vv_get(ps->background);
  vmask hits = vm_andnot(active, vi_eq(h.object, vi_set1(-1)));
  if (vm_none(hits))
    return;

  /* Split, and per sub-beam: surface, colour and coefficients. */
  int sub_object[LANES];
  vmask sub_mask[LANES];
  int nsub = 0, any_highlight = 0;
  SIMD_ALIGN int objects[LANES];
  vi_store(objects, h.object);
  packet_surface f;
  vvec3 base = {vf_zero(), vf_zero(), vf_zero()}, ambient = base;
  f.p = f.n = base;
  f.front = vm_false();
  vfloat kd = vf_zero(), ks = vf_zero(), hexp = vf_set1(1);
  vmask todo = hits;
  while (vm_any(todo)) {
    int object = objects[vm_first(todo)];
    vmask sub = vm_and(todo, vi_eq(h.object, vi_set1(object)));
    todo = vm_andnot(todo, sub);
    c->st->sub_beams++;
    const object_r *ob = &s->objects[object];
    lane_material lm = lane_material_uniform(ps, ob->material);
    lane_object lo = lane_object_uniform(ob);
    packet_surface fk = packet_surface_object(ps, ob, &h, o, d, newton);
    f.p = vv_select(sub, fk.p, f.p);
    f.n = vv_select(sub, fk.n, f.n);
    f.front = vm_select(sub, fk.front, f.front);
    base = vv_select(sub, packet_color(&lm, &lo, fk.p, sub), base);
    ambient = vv_select(sub, LANE_VEC3(&lm, ambient), ambient);
    kd = vf_select(sub, LANE_SCALAR(&lm, kd), kd);
    if (lm.m->ks > 0) {
      ks = vf_select(sub, LANE_SCALAR(&lm, ks), ks);
      hexp = vf_select(sub, LANE_SCALAR(&lm, h), hexp);
      any_highlight = 1;
    }
    sub_object[nsub] = object;
    sub_mask[nsub++] = sub;
  }

  vvec3 local = packet_lights(ps, &f, d, hits, base, ambient, kd, ks, hexp,
                              any_highlight, math, newton, c->st, NULL);

  for (int k = 0; k < nsub; k++)
    finish_sub_beam(c, d, &h, &f, sub_object[k], sub_mask[k], level, weight,
                    local, color, math, trace);
}

static void trace_default(const beam_ctx *c, const vvec3 *o, const vvec3 *d,
                          vmask active, int level, beam_io *io) {
  trace_beam_body(c, *o, *d, active, level, &io->weight, &io->color,
                  GLINT_MATH_MINIMAX, 1, trace_default);
}

static void trace_generic(const beam_ctx *c, const vvec3 *o, const vvec3 *d,
                          vmask active, int level, beam_io *io) {
  trace_beam_body(c, *o, *d, active, level, &io->weight, &io->color, c->math,
                  c->newton, trace_generic);
}

static ALWAYS_INLINE void render_tile_body(const packet_scene *ps,
                                           const frame_params *frame,
                                           const tile_rect *tile, float *rgb,
                                           glint_stats *st, int newton,
                                           trace_fn trace) {
  beam_ctx c = {ps, frame->math, frame->rcp_newton, frame->max_depth, st};
  camera cam;
  camera_from_basis(&cam, &frame->camera);
  primary_beams pb = primary_beams_init(&cam);
  vfloat inv_spp = vf_set1(1.0f / (float)frame->spp);
  const vvec3 unit = {vf_set1(1), vf_set1(1), vf_set1(1)};
  int tw = tile->x1 - tile->x0;
  for (int by = tile->y0; by < tile->y1; by += BLOCK_H)
    for (int bx = tile->x0; bx < tile->x1; bx += BLOCK_W) {
      vfloat px, py;
      vmask valid = primary_block(&pb, tile, bx, by, &px, &py);
      vvec3 sum = {vf_zero(), vf_zero(), vf_zero()};
      for (int k = 0; k < frame->spp; k++) {
        vvec3 dir = primary_dir(&pb, px, py, frame->samples[k], newton);
        beam_io io;
        io.weight = unit;
        trace(&c, &pb.from, &dir, valid, 1, &io);
        sum = vv_add(sum, io.color);
      }
      st->primary_rays += (uint64_t)vm_count(valid) * (uint64_t)frame->spp;
      primary_block_store(rgb, tw, bx - tile->x0, by - tile->y0, valid,
                          vv_scale(sum, inv_spp));
    }
}

#define render_tile_plain ISA_NAME(gli_beam_render_tile_plain)
void render_tile_plain(const void *view, const frame_params *frame,
                       const tile_rect *tile, void *scratch, float *rgb,
                       glint_stats *st);

#if BEAM_PLAIN
void render_tile_plain(const void *view, const frame_params *frame,
                       const tile_rect *tile, void *scratch, float *rgb,
                       glint_stats *st) {
#else
static void render_tile(const void *view, const frame_params *frame,
                        const tile_rect *tile, void *scratch, float *rgb,
                        glint_stats *st) {
  if (!((const packet_scene *)view)->alone_lanes) {
    render_tile_plain(view, frame, tile, scratch, rgb, st);
    return;
  }
#endif
  (void)scratch;
  const packet_scene *ps = view;
  if (frame->math == GLINT_MATH_MINIMAX && frame->rcp_newton)
    render_tile_body(ps, frame, tile, rgb, st, 1, trace_default);
  else
    render_tile_body(ps, frame, tile, rgb, st, frame->rcp_newton,
                     trace_generic);
}

#if !BEAM_PLAIN
/* Primary beams' nearest hits only, for glint_trace_primary. */
static uint64_t primary_tile(const void *view, const frame_params *frame,
                             const tile_rect *tile, glint_stats *st) {
  const packet_scene *ps = view;
  camera cam;
  camera_from_basis(&cam, &frame->camera);
  primary_beams pb = primary_beams_init(&cam);
  uint64_t hits = 0;
  for (int by = tile->y0; by < tile->y1; by += BLOCK_H)
    for (int bx = tile->x0; bx < tile->x1; bx += BLOCK_W) {
      vfloat px, py;
      vmask valid = primary_block(&pb, tile, bx, by, &px, &py);
      for (int k = 0; k < frame->spp; k++) {
        vvec3 dir = primary_dir(&pb, px, py, frame->samples[k], 1);
        packet_hit h;
        packet_nearest(ps, pb.from, dir, valid, 1, &h, st);
        hits +=
            (uint64_t)vm_count(vm_andnot(valid, vi_eq(h.object, vi_set1(-1))));
      }
      st->primary_rays += (uint64_t)vm_count(valid) * (uint64_t)frame->spp;
    }
  return hits;
}

/* The beams need no scratch: their state lives on the stack. */
const gli_backend_ops ISA_NAME(gli_beam_ops) = {ISA_DATA_KIND, 1, NULL,
                                                render_tile, primary_tile};

/* For the tests: the packet nearest hit of W rays (SoA arrays of W floats),
 * with the default maths. Writes t and object per lane (-1: no hit). */
void ISA_NAME(gli_beam_nearest_hit)(const void *view, const float *o,
                                    const float *d, int active_bits, float *t,
                                    int *object) {
  const packet_scene *ps = view;
  glint_stats st = {0};
  vvec3 vo = {vf_loadu(o), vf_loadu(o + LANES), vf_loadu(o + 2 * LANES)};
  vvec3 vd = {vf_loadu(d), vf_loadu(d + LANES), vf_loadu(d + 2 * LANES)};
  packet_hit h;
  packet_nearest(ps, vo, vd, vm_from_bits(active_bits), 1, &h, &st);
  SIMD_ALIGN float tt[LANES];
  SIMD_ALIGN int ob[LANES];
  vf_store(tt, h.t);
  vi_store(ob, h.object);
  for (int i = 0; i < LANES; i++) {
    t[i] = tt[i];
    object[i] = ob[i];
  }
}
#endif
