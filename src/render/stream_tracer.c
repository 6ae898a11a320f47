/* The stream tracer: rays traced breadth-first in generations (Wald et al.
 * 2007, "SIMD ray stream tracing", the direction the thesis's §6 points).
 * When beams break apart, the beam tracer's registers run nearly empty
 * (Billiard, depth 15: a sixth of the lanes); here the surviving rays of a
 * whole tile are gathered into a dense stream after every generation and
 * cut into full W-wide packets again, so lanes stay busy however the rays
 * scatter.
 *
 * Each ray carries its pixel and an RGB weight (the product of the kr, kt
 * and Beer factors on its way from the eye), so a generation's rays are
 * independent: nothing waits for a recursive call to return.
 * docs/specification.md §4's formula becomes, for a ray of weight w hitting a
 * surface, pixel += w Beer C ka Ia                          (ambient, at once)
 *   pixel += w Beer S_j (C kd N·L + ks (V·R)^h) I_L   (per light, once its
 *                                                      shadow ray returns S_j)
 *   child rays with weights w Beer kr (reflected) and w Beer kt (refracted),
 * with Beer = exp(-absorb t) for a hit reached from inside an object.
 *
 * Memory is bounded and allocated before the tile starts: each generation
 * level has a buffer of STREAM_CAPACITY rays. A generation is consumed in
 * batches; when the next level's buffer cannot take a batch's children, the
 * tracer descends and drains it first (depth-first at the granularity of
 * whole buffers, with an explicit level cursor, no recursion), so the
 * footprint is capacity x levels whatever the ray tree does. The primary
 * generation's shadow rays need no buffer: a packet's are traced at once,
 * and since the packet is full, so are they. The deeper generations' wait
 * in one buffer, sorted before they are traced (see "shadow rays that
 * wait" below).
 *
 * Coherent rays stay coherent: a child packet with every lane alive (a
 * packet that hit one glass sphere refracts all its rays) skips the stream
 * and is traced next, in registers, as the beam tracer would (packet_child;
 * at most one child per packet, in a loop, while its own children fit).
 * That keeps the stream within about 10% of the beams on coherent scenes,
 * where compaction buys nothing.
 *
 * The buffers, their compaction and the pixels' accumulation are
 * render/ray_stream.h's; this file schedules the generations and shades.
 * Compiled once per ISA, like the beam tracer. */

/* Stream packets walk the binary BVH and never hand rays to the wide one,
 * whatever --accel says (render/packet_rays.h says why). */
#define PACKET_HAND_OVER 0
#define PACKET_NEAREST_APART 1 /* see render/packet_rays.h */
#ifdef GLINT_ISA_SSE
#define PACKET_WALKS_APART 1 /* see render/packet_rays.h */
#endif

#include "render/backend.h"
#include "render/packet_shading.h"
#include "render/primary.h"
#include "render/ray_stream.h"

#include "core/error.h"
#include "core/timer.h"

#include <stdlib.h>
#include <string.h>
#include <x86intrin.h>

/* ---- stage timing ------------------------------------------------------ */

enum { STAGE_GENERATE, STAGE_TRAVERSE, STAGE_SHADE, STAGE_COMPACT };

/* Stage times are sampled: every TIMED_EVERY-th packet is timed in all its
 * stages and the sums are scaled by packets / timed packets. Reading the
 * time-stamp counter around every stage of every packet would itself cost a
 * quarter of a coherent scene's render. */
#define TIMED_EVERY 32

typedef struct tracer {
  const packet_scene *ps;
  const scene_r *s;
  stream_scratch *sc;
  glint_stats *st;
  int max_depth;
  int tile_w;
  int timing;      /* this packet is timed */
  glint_math math; /* the deeper generations' maths (shade_chain_deeper) */
  int newton;
  uint64_t packets, timed;
  uint64_t stage_ticks[4];
  /* the time-stamp cycles of every trace of waiting shadow rays, timed
   * whole (each trace serves many packets): scaled at the tile's end by
   * the share of the packets that were timed */
  uint64_t waiting_ticks;
  int waits; /* the deeper generations' shadow rays wait (wait_lights) */
} tracer;

static ALWAYS_INLINE uint64_t tick(const tracer *t) {
  return t->timing ? __rdtsc() : 0;
}

/* ---- appending rays (the compaction, timed) ----------------------------- */

static ALWAYS_INLINE void append_ray(tracer *t, ray_stream *r, vmask m, vvec3 o,
                                     vvec3 d, vvec3 w, vint pixel) {
  uint64_t t0 = tick(t);
  ray_stream_append(r, m, o, d, w, pixel);
  t->stage_ticks[STAGE_COMPACT] += tick(t) - t0;
}

/* Whether level's two streams can take one more packet's children each. */
static ALWAYS_INLINE int room(const tracer *t, int level) {
  return STREAM(t->sc, level, TRANSMITTED)->count <= STREAM_CAPACITY - LANES &&
         STREAM(t->sc, level, REFLECTED)->count <= STREAM_CAPACITY - LANES;
}

/* Whether any level from `level` down holds rays (chains of full packets
 * can leave a level empty and fill the ones below it). */
static ALWAYS_INLINE int pending(const tracer *t, int level) {
  for (; level < t->max_depth; level++)
    if (STREAM(t->sc, level, TRANSMITTED)->count > 0 ||
        STREAM(t->sc, level, REFLECTED)->count > 0)
      return 1;
  return 0;
}

/* A full child packet (every lane alive) that is traced next, in registers,
 * instead of through its level's stream: coherent scenes keep their beams
 * (a packet that hit one sphere with all its rays refracts all of them),
 * and such a packet needs neither compaction nor its own contributions
 * logged, since it covers the same pixels as its parent. Only one child of
 * a packet continues so (the refracted, else the reflected); the chain is a
 * loop in the caller, not recursion, and only continues while the child's
 * own children fit their streams. */
typedef struct packet_child {
  vvec3 o, d, w;
  int taken;
} packet_child;

static ALWAYS_INLINE void emit_child(tracer *t, int level, int kind, vmask m,
                                     vvec3 o, vvec3 d, vvec3 w, vint pixel,
                                     packet_child *next) {
  if (!next->taken && vm_count(m) == LANES &&
      (level + 2 >= t->max_depth || room(t, level + 2))) {
    next->o = o;
    next->d = d;
    next->w = w;
    next->taken = 1;
    return;
  }
  append_ray(t, STREAM(t->sc, level + 1, kind), m, o, d, w, pixel);
}

/* ---- shadow rays that wait ---------------------------------------------- */

/* The shadow rays of the deeper generations wait in a buffer, and are
 * traced in packets of rays that leave one light in nearly one direction.
 * A packet of a deeper generation holds scattered hits, and its shadow
 * rays, one packet per light, were the costliest rays of the SPD scenes
 * (gears-s4's about 77 ns each against 20 ns for those of the primary
 * hits): their segments from scattered points cross different parts of
 * the tree. Rays that leave the light side by side share their walk from
 * it (Pharr, Kolb, Gershbein and Hanrahan 1997, "Rendering complex scenes
 * with memory-coherent ray tracing", reorder rays so; here the order is
 * a sort on the direction from the light): balls-s4 and rings-s4 render
 * 12-16% faster, gears-s4, whose rays cross its transparent gears to the
 * end, barely. A shadow ray only scales what it brings to its pixel, so it
 * can be traced whenever the buffer fills. The primary generation's shadow
 * rays, from a block of the screen, are coherent already and are traced
 * at once, as are all of a scene's without a BVH or with a small one. */
/* Trees of fewer nodes keep every shadow ray at once: there a walk costs
 * less than waiting does (its copies and sort, about 70 instructions a
 * ray): Giza (9 nodes) and glass-in-glass (23) rendered 5-11% slower with
 * waiting rays, glass-rods (53) 27% faster. */
#define SHADOWS_WAIT_NODES 32
/* A packet's shadow rays towards one light that all leave within about
 * 2.6 degrees of its first lane's direction (cosines above this) are
 * coherent already, and traced at once: mount-s6, whose rays refracted by
 * its glass spheres stay together, rendered 7-13% slower when they waited. */
#define SHADOWS_COHERENT_COS 0.999f

/* The key that groups waiting shadow rays: the light's number (its low
 * four bits) over a Morton code of the ray's direction d from the light,
 * -d, in octahedral coordinates on a 64 x 64 grid (Meyer, Sander,
 * Kosinka and Hansen 2010, "On floating-point normal vectors"). */
static ALWAYS_INLINE vint shadow_key(vvec3 d, int light) {
  vfloat one = vf_set1(1);
  vfloat x = vf_neg(d.x), y = vf_neg(d.y), z = vf_neg(d.z);
  vfloat inv = vf_div(one, vf_add(vf_add(vf_abs(x), vf_abs(y)), vf_abs(z)));
  vfloat u = vf_mul(x, inv), v = vf_mul(y, inv);
  vmask below = vf_lt(z, vf_zero());
  vfloat fu = vf_signed_as(vf_sub(one, vf_abs(v)), u);
  vfloat fv = vf_signed_as(vf_sub(one, vf_abs(u)), v);
  u = vf_select(below, fu, u);
  v = vf_select(below, fv, v);
  vfloat scale = vf_set1(31.99f);
  vint qu = vf_to_vi(vf_max(vf_fmadd(u, scale, scale), vf_zero()));
  vint qv = vf_to_vi(vf_max(vf_fmadd(v, scale, scale), vf_zero()));
  vint key = vi_set1((light & 15) << 12);
  for (int k = 0; k < 2; k++) {
    vint q = k ? qv : qu;
    q = vi_and(vi_or(q, vi_shl(q, 4)), vi_set1(0x0f0f));
    q = vi_and(vi_or(q, vi_shl(q, 2)), vi_set1(0x3333));
    q = vi_and(vi_or(q, vi_shl(q, 1)), vi_set1(0x5555));
    key = vi_or(key, vi_shl(q, k));
  }
  return key;
}

/* One byte of the keys: a stable counting sort of the n rays in `from`
 * into `to` (a radix sort's pass, LSD first). */
static void shadow_sort_pass(const int32_t *key, int shift,
                             const uint16_t *from, uint16_t *to, int n) {
  uint32_t start[256] = {0};
  for (int i = 0; i < n; i++)
    start[key[i] >> shift & 255]++;
  uint32_t sum = 0;
  for (int b = 0; b < 256; b++) {
    uint32_t c = start[b];
    start[b] = sum;
    sum += c;
  }
  for (int i = 0; i < n; i++) {
    uint16_t r = from ? from[i] : (uint16_t)i;
    to[start[key[r] >> shift & 255]++] = r;
  }
}

/* Traces the waiting shadow rays, sorted by key, W at a time, and logs
 * what they bring to their pixels. Returns the time-stamp cycles taken. */
static __attribute__((noinline)) uint64_t trace_shadows(tracer *t) {
  shadow_stream *sh = &t->sc->shadows;
  int n = sh->count;
  if (n == 0)
    return 0;
  uint64_t t0 = __rdtsc();
  shadow_sort_pass(sh->key, 0, NULL, sh->sorted, n);
  shadow_sort_pass(sh->key, 8, sh->sorted, sh->order, n);
  const float *const field[10] = {sh->ox, sh->oy,   sh->oz, sh->dx, sh->dy,
                                  sh->dz, sh->dist, sh->cr, sh->cg, sh->cb};
  for (int i = 0; i < n; i += LANES) {
    int c = n - i < LANES ? n - i : LANES;
    SIMD_ALIGN float lane[10][LANES];
    SIMD_ALIGN int32_t pixel[LANES];
    for (int k = 0; k < LANES; k++) {
      int r = sh->order[i + (k < c ? k : c - 1)];
      for (int f = 0; f < 10; f++)
        lane[f][k] = field[f][r];
      pixel[k] = sh->pixel[r];
    }
    vmask m = vm_from_bits((1 << c) - 1); /* c <= LANES <= 16 */
    vvec3 o = {vf_load(lane[0]), vf_load(lane[1]), vf_load(lane[2])};
    vvec3 d = {vf_load(lane[3]), vf_load(lane[4]), vf_load(lane[5])};
    vvec3 brings = {vf_load(lane[7]), vf_load(lane[8]), vf_load(lane[9])};
    packet_origin po = packet_origin_of(o); /* rays wait only in a BVH */
    vvec3 sj = packet_transmission(t->ps, o, &po, d, vf_load(lane[6]), m,
                                   t->math, t->newton, t->st);
    accumulate(t->sc, m, vi_load(pixel), vv_mul(sj, brings));
  }
  sh->count = 0;
  uint64_t ticks = __rdtsc() - t0;
  t->waiting_ticks += ticks;
  return ticks;
}

/* packet_lights for a deeper generation's packet of weights w: the
 * ambient part at once, and each light's shadow rays left waiting with
 * what they bring unshadowed, unless they leave together already. The
 * packet's pixels get the rest. *waited receives the time-stamp cycles
 * spent tracing shadow rays, which are not the shading's. Apart from the
 * shading that calls it: inlined there, with the tracing of waiting rays,
 * it made the streams 8-12% slower on tree-s4 and Giza even where no ray
 * waited. */
static __attribute__((noinline)) vvec3
wait_lights(tracer *t, const packet_surface *f, vvec3 d, vmask m, vvec3 c,
            vvec3 w, vint pixel, const lane_material *lm, int highlights,
            glint_math math, int newton, uint64_t *waited) {
  const packet_scene *ps = t->ps;
  shadow_stream *sh = &t->sc->shadows;
  vvec3 local = vv_mul(w, vv_mul(c, LANE_VEC3(lm, ambient)));
  packet_origin po;
  int po_made = 0;
  for (size_t j = 0; j < t->s->light_count; j++) {
    const plight *li = &ps->lights[j];
    light_terms lt = packet_light_terms(li, f, d, m, LANE_SCALAR(lm, kd),
                                        LANE_SCALAR(lm, ks), LANE_SCALAR(lm, h),
                                        highlights, math, newton);
    if (vm_none(lt.lit))
      continue;
    t->st->shadow_rays += (uint64_t)vm_count(lt.lit);
    /* what the light brings where nothing blocks it */
    vvec3 intensity = vv_mul(w, vv_get(li->color));
    vvec3 hl = {lt.highlight, lt.highlight, lt.highlight};
    vvec3 brings = vv_mul(intensity, vv_madd(hl, lt.diffuse, c));
    /* rays that leave together already: traced at once */
    SIMD_ALIGN float lx[LANES], ly[LANES], lz[LANES];
    vf_store(lx, lt.l.x), vf_store(ly, lt.l.y), vf_store(lz, lt.l.z);
    int k0 = vm_first(lt.lit);
    vvec3 l0 = {vf_set1(lx[k0]), vf_set1(ly[k0]), vf_set1(lz[k0])};
    vfloat cosk = vv_dot(lt.l, l0);
    if (vm_none(
            vm_andnot(lt.lit, vf_gt(cosk, vf_set1(SHADOWS_COHERENT_COS))))) {
      if (!po_made)
        po = packet_origin_of(f->p), po_made = 1;
      uint64_t dt = 0;
      vvec3 sj = light_transmission(ps, f, &po, &lt, math, newton, t->st,
                                    t->timing ? &dt : NULL);
      t->stage_ticks[STAGE_TRAVERSE] += dt;
      *waited += dt;
      local = vv_add(local, vv_mul(sj, brings));
      continue;
    }
    if (sh->count > SHADOW_CAPACITY - LANES)
      *waited += trace_shadows(t);
    shadow_stream_append(sh, lt.lit, f->p, lt.l, lt.dist, brings, pixel,
                         shadow_key(lt.l, (int)j));
  }
  return local;
}

/* The shading of a packet's hits, once its surface and materials are
 * known (a uniform packet's or a mixed one's: shade_packet inlines this
 * twice, so each form is compiled for what it is). Everything a hit brings
 * is linear in the rays' weights w. */
static ALWAYS_INLINE vvec3 shade_hits(
    tracer *t, int level, int waits, vmask hits, vmask misses, vvec3 bg,
    const packet_hit *hp, vvec3 d, vvec3 w, vint pixel, packet_child *next,
    const packet_surface *fp, const lane_material *lmp, const lane_object *lop,
    uint64_t t1, glint_math math, int newton) {
  const packet_scene *ps = t->ps;
  packet_hit h = *hp;
  packet_surface f = *fp;
  lane_material lm = *lmp;
  lane_object lo = *lop;
  vvec3 c = packet_color(&lm, &lo, f.p, hits);
  /* Beer's law (eq. 2.11) on the stretch just travelled inside. */
  w = packet_beer(&lm, &f, h.t, hits, w, math);

  uint64_t shadow = 0; /* shadow rays: traversal, not shading */
  int highlights =
      lm.uniform ? lm.m->ks > 0 : vm_any(vm_and(hits, vf_gt(lm.ks, vf_zero())));
  vvec3 local;
  if (waits && level > 0) {
    uint64_t waited = 0; /* trace_shadows timed itself */
    local = wait_lights(t, &f, d, hits, c, w, pixel, &lm, highlights, math,
                        newton, &waited);
    t1 += t->timing ? waited : 0;
  } else {
    local = vv_mul(w, packet_lights(ps, &f, d, hits, c, LANE_VEC3(&lm, ambient),
                                    LANE_SCALAR(&lm, kd), LANE_SCALAR(&lm, ks),
                                    LANE_SCALAR(&lm, h), highlights, math,
                                    newton, t->st, t->timing ? &shadow : NULL));
    t->stage_ticks[STAGE_TRAVERSE] += shadow;
    t1 += shadow;
  }
  vvec3 zero = {vf_zero(), vf_zero(), vf_zero()};
  vvec3 brings = vv_select(hits, local, vv_select(misses, bg, zero));

  /* Secondary rays, one level deeper (docs/specification.md §4;
   * eq. 2.12, 2.13). */
  if (level + 1 < t->max_depth &&
      (!lm.uniform || lm.m->kr > 0 || lm.m->kt > 0)) {
    vvec3 reflected, refracted;
    vfloat kr;
    vmask refract, tir;
    packet_secondary(&lm, &f, d, hits, &reflected, &kr, &refracted, &refract,
                     &tir);
    t->st->total_internal_reflections += (uint64_t)vm_count(tir);
    vvec3 wt = packet_child_weight(w, LANE_SCALAR(&lm, kt));
    refract = vm_and(refract, packet_worth_tracing(wt));
    if (vm_any(refract)) {
      t->st->secondary_rays += (uint64_t)vm_count(refract);
      t->st->refracted_rays += (uint64_t)vm_count(refract);
      emit_child(t, level, TRANSMITTED, refract, f.p, refracted, wt, pixel,
                 next);
    }
    vvec3 wr = packet_child_weight(w, kr);
    vmask reflect =
        vm_and(vm_and(hits, vf_gt(kr, vf_zero())), packet_worth_tracing(wr));
    if (vm_any(reflect)) {
      t->st->secondary_rays += (uint64_t)vm_count(reflect);
      t->st->reflected_rays += (uint64_t)vm_count(reflect);
      emit_child(t, level, REFLECTED, reflect, f.p, reflected, wr, pixel, next);
    }
  }
  t->stage_ticks[STAGE_SHADE] += tick(t) - t1;
  return brings;
}

/* One packet of a generation: intersect, shade (its shadow rays traced at
 * once, or left waiting: see wait_lights) and append its child rays. Returns
 * what the packet brings to its pixels (0 in inactive lanes). */
static ALWAYS_INLINE vvec3 shade_packet(tracer *t, int level, int waits,
                                        vmask active, vvec3 o, vvec3 d, vvec3 w,
                                        vint pixel, packet_child *next,
                                        glint_math math, int newton) {
  const packet_scene *ps = t->ps;
  const scene_r *s = t->s;
  uint64_t t0 = tick(t);
  packet_hit h;
  packet_nearest(ps, o, d, active, newton, &h, t->st);
  uint64_t t1 = tick(t);
  t->stage_ticks[STAGE_TRAVERSE] += t1 - t0;
  next->taken = 0;

  vmask hits = vm_andnot(active, vi_eq(h.object, vi_set1(-1)));
  vmask misses = vm_andnot(active, hits);
  vvec3 bg = vv_mul(w, vv_get(ps->background));
  if (vm_none(hits)) {
    t->stage_ticks[STAGE_SHADE] += tick(t) - t1;
    vvec3 z = {vf_zero(), vf_zero(), vf_zero()};
    return vv_select(misses, bg, z);
  }

  /* The surface and the materials: when every lane hit one object
   * (coherent packets, as a beam's sub-beam), as the beams compute them;
   * otherwise lane by lane. */
  SIMD_ALIGN int32_t objs[LANES];
  vi_store(objs, h.object);
  int obj0 = objs[vm_first(hits)];
  if (vm_none(vm_andnot(hits, vi_eq(h.object, vi_set1(obj0))))) {
    const object_r *ob = &s->objects[obj0];
    packet_surface f = packet_surface_object(ps, ob, &h, o, d, newton);
    lane_material lm = lane_material_uniform(ps, ob->material);
    lane_object lo = lane_object_uniform(ob);
    return shade_hits(t, level, waits, hits, misses, bg, &h, d, w, pixel, next,
                      &f, &lm, &lo, t1, math, newton);
  }
  vint mi;
  lane_object lo;
  packet_surface f = packet_surface_lanes(ps, &h, hits, o, d, newton, &mi, &lo);
  lane_material lm =
      lane_material_gather(ps, vi_select(hits, mi, vi_set1(0)), hits);
  return shade_hits(t, level, waits, hits, misses, bg, &h, d, w, pixel, next,
                    &f, &lm, &lo, t1, math, newton);
}

/* Shades a packet at `level` and the chain of full children that follows
 * it in registers; returns what they all bring to the packet's pixels. */
static ALWAYS_INLINE vvec3 shade_chain(tracer *t, int level, int waits,
                                       vmask active, vvec3 o, vvec3 d, vvec3 w,
                                       vint pixel, glint_math math,
                                       int newton) {
  packet_child next;
  vvec3 sum = shade_packet(t, level, waits, active, o, d, w, pixel, &next, math,
                           newton);
  while (next.taken) {
    level++;
    int g = level < GLINT_STATS_MAX_GENERATIONS
                ? level
                : GLINT_STATS_MAX_GENERATIONS - 1;
    t->st->gen_rays[g] += LANES;
    t->st->gen_packets[g]++;
    t->st->gen_active_lanes[g] += LANES;
    if (level + 1 > t->st->generations)
      t->st->generations = level + 1;
    sum = vv_add(sum, shade_packet(t, level, waits, vm_true(), next.o, next.d,
                                   next.w, pixel, &next, math, newton));
  }
  return sum;
}

/* The deeper generations' packets call this copy out of line: the drain
 * loop stays small, while the primary packets keep theirs inlined. It
 * takes the packet where it lies, rays i to i + n - 1 of r, and adds what
 * they bring to their pixels. Its arguments all travel in registers: passed
 * by value, the packet's rays went through the stack, three vectors of three
 * at every call, and Giza at depth 15 rendered 2-3% slower (streams, AVX-512
 * and AVX2). */
static ALWAYS_INLINE void shade_chain_from(tracer *t, int level, int waits,
                                           const ray_stream *r, int i, int n) {
  vmask m = vm_from_bits(n == 32 ? -1 : (int)((1u << n) - 1));
  vvec3 o = {vf_load(r->ox + i), vf_load(r->oy + i), vf_load(r->oz + i)};
  vvec3 d = {vf_load(r->dx + i), vf_load(r->dy + i), vf_load(r->dz + i)};
  vvec3 w = {vf_load(r->wr + i), vf_load(r->wg + i), vf_load(r->wb + i)};
  vint pixel = vi_load(r->pixel + i);
  accumulate(
      t->sc, m, pixel,
      shade_chain(t, level, waits, m, o, d, w, pixel, t->math, t->newton));
}

/* Its two forms: shadow rays traced at once, and left waiting (where the
 * tree is large enough, tracer.waits). Each is compiled for what it does:
 * with the choice made inside, packet by packet, the call to wait_lights
 * alone cost the shading 5% more instructions on Giza at depth 15, where
 * no ray waits. */
static __attribute__((noinline)) void
shade_chain_deeper(tracer *t, int level, const ray_stream *r, int i, int n) {
  shade_chain_from(t, level, 0, r, i, n);
}

static __attribute__((noinline)) void
shade_chain_waiting(tracer *t, int level, const ray_stream *r, int i, int n) {
  shade_chain_from(t, level, 1, r, i, n);
}

/* ---- a tile ------------------------------------------------------------ */

/* Consumes the generations from level `floor` down, depth first at the
 * granularity of buffers: a generation is processed in batches whose
 * children fit the next level's buffer; when that buffer cannot take
 * another packet's children, it is drained first. An explicit level cursor,
 * no recursion. */
static ALWAYS_INLINE void drain(tracer *t, int floor) {
  glint_stats *st = t->st;
  int levels = t->max_depth, level = floor;
  for (;;) {
    /* The level's transmitted rays first, then its reflected ones. */
    ray_stream *r = STREAM(t->sc, level, TRANSMITTED);
    if (r->cursor >= r->count)
      r = STREAM(t->sc, level, REFLECTED);
    if (r->cursor < r->count) {
      int deeper = level + 1 < levels;
      if (deeper && !room(t, level + 1)) {
        level++;
        continue;
      }
      int end = r->count;
      if (deeper) {
        /* A packet has at most W children of each kind. */
        int free_t =
            STREAM_CAPACITY - STREAM(t->sc, level + 1, TRANSMITTED)->count;
        int free_r =
            STREAM_CAPACITY - STREAM(t->sc, level + 1, REFLECTED)->count;
        int budget = (free_t < free_r ? free_t : free_r) / LANES * LANES;
        if (end - r->cursor > budget)
          end = r->cursor + budget;
      }
      int g = level < GLINT_STATS_MAX_GENERATIONS
                  ? level
                  : GLINT_STATS_MAX_GENERATIONS - 1;
      for (int i = r->cursor; i < end; i += LANES) {
        int n = end - i < LANES ? end - i : LANES;
        t->timing = t->packets++ % TIMED_EVERY == 0;
        t->timed += (uint64_t)t->timing;
        st->gen_rays[g] += (uint64_t)n;
        st->gen_packets[g]++;
        st->gen_active_lanes[g] += (uint64_t)n;
        if (t->waits)
          shade_chain_waiting(t, level, r, i, n);
        else
          shade_chain_deeper(t, level, r, i, n);
      }
      if (level + 1 > st->generations)
        st->generations = level + 1;
      r->cursor = end;
      continue;
    }
    /* This generation is done: its children next, then back up to what
     * the parent generation has left. */
    for (int k = 0; k < 2; k++)
      STREAM(t->sc, level, k)->count = STREAM(t->sc, level, k)->cursor = 0;
    if (level + 1 < levels && pending(t, level + 1)) {
      level++;
      continue;
    }
    if (level == floor)
      return;
    level--;
  }
}

/* Primary rays need no buffer: each packet is a BW x BH block of the screen
 * at one sample position, made in registers from the camera (as the beams)
 * and traced at once; only their children enter the stream. */
static ALWAYS_INLINE void render_tile_body(const packet_scene *ps,
                                           const frame_params *frame,
                                           const tile_rect *tile, void *scratch,
                                           float *rgb, glint_stats *st,
                                           glint_math math, int newton) {
  const scene_r *s = ps->s;
  int levels = frame->max_depth;
  tracer t = {ps,
              s,
              carve(scratch, levels),
              st,
              levels,
              tile->x1 - tile->x0,
              0,
              math,
              newton,
              0,
              0,
              {0, 0, 0, 0},
              0,
              s->bvh->node_count >= SHADOWS_WAIT_NODES};
  int tw = tile->x1 - tile->x0;
  int npix = tw * (tile->y1 - tile->y0);
  double tile_start = gli_now();
  memset(t.sc->accum, 0, (size_t)npix * 4 * sizeof(float));
  t.sc->log_count = 0;
  for (int l = 0; l < 2 * levels; l++)
    t.sc->levels[l].count = t.sc->levels[l].cursor = 0;
  t.sc->shadows.count = 0;

  camera cam;
  camera_from_basis(&cam, &frame->camera);
  primary_beams pb = primary_beams_init(&cam);
  vvec3 one = {vf_set1(1), vf_set1(1), vf_set1(1)};
  /* Block by block, its samples innermost: their contributions are summed
   * in registers and written once per block. */
  for (int by = tile->y0; by < tile->y1; by += BLOCK_H)
    for (int bx = tile->x0; bx < tile->x1; bx += BLOCK_W) {
      vfloat px, py;
      vmask valid = primary_block(&pb, tile, bx, by, &px, &py);
      vint pix = vi_add(
          vi_mul_const(vf_to_vi(vf_sub(py, vf_set1((float)tile->y0))), tw),
          vf_to_vi(vf_sub(px, vf_set1((float)tile->x0))));
      int n = vm_count(valid);
      vvec3 sum = {vf_zero(), vf_zero(), vf_zero()};
      for (int k = 0; k < frame->spp; k++) {
        if (levels > 1 && !room(&t, 1))
          drain(&t, 1);
        t.timing = t.packets++ % TIMED_EVERY == 0;
        t.timed += (uint64_t)t.timing;
        uint64_t t0 = tick(&t);
        vvec3 dir = primary_dir(&pb, px, py, frame->samples[k], newton);
        t.stage_ticks[STAGE_GENERATE] += tick(&t) - t0;
        st->primary_rays += (uint64_t)n;
        st->gen_rays[0] += (uint64_t)n;
        st->gen_packets[0]++;
        st->gen_active_lanes[0] += (uint64_t)n;
        sum = vv_add(sum, shade_chain(&t, 0, t.waits, valid, pb.from, dir, one,
                                      pix, math, newton));
      }
      accumulate(t.sc, valid, pix, sum);
    }
  if (st->generations < 1)
    st->generations = 1;
  if (levels > 1)
    drain(&t, 1);
  trace_shadows(&t);

  fold_log(t.sc);
  float inv_spp = 1.0f / (float)frame->spp;
  for (int i = 0; i < npix; i++)
    for (int k = 0; k < 3; k++)
      rgb[3 * i + k] = t.sc->accum[4 * i + k] * inv_spp;
  /* The tile's time, shared among the stages in the proportions the timed
   * packets show (their own timer reads make them slower than the rest):
   * the time-stamp counter gives the proportions, the clock the seconds. */
  double tile_seconds = gli_now() - tile_start;
  if (t.packets)
    t.stage_ticks[STAGE_TRAVERSE] +=
        (uint64_t)((double)t.waiting_ticks * (double)t.timed /
                   (double)t.packets);
  uint64_t sampled =
      t.stage_ticks[0] + t.stage_ticks[1] + t.stage_ticks[2] + t.stage_ticks[3];
  for (int k = 0; k < 4 && sampled; k++)
    st->stage_seconds[k] +=
        tile_seconds * (double)t.stage_ticks[k] / (double)sampled;
}

static void render_tile(const void *view, const frame_params *frame,
                        const tile_rect *tile, void *scratch, float *rgb,
                        glint_stats *st) {
  const packet_scene *ps = view;
  if (frame->math == GLINT_MATH_MINIMAX && frame->rcp_newton)
    render_tile_body(ps, frame, tile, scratch, rgb, st, GLINT_MATH_MINIMAX, 1);
  else
    render_tile_body(ps, frame, tile, scratch, rgb, st, frame->math,
                     frame->rcp_newton);
}

static uint64_t primary_tile(const void *view, const frame_params *frame,
                             const tile_rect *tile, glint_stats *st) {
  /* The primary generation alone is the beam tracer's primary beams. */
  return ISA_NAME(gli_beam_ops).primary_tile(view, frame, tile, st);
}

const gli_backend_ops ISA_NAME(gli_stream_ops) = {
    ISA_DATA_KIND, 0, scratch_bytes, render_tile, primary_tile};
