/* The beam tracer (SPEC §6, thesis chapter 4): W rays traced together in SIMD
 * registers. A beam finds each lane's nearest hit, splits into one sub-beam
 * per object hit (§4.3, after Boulos et al. 2007), shades each sub-beam with
 * its object's material in SIMD, and traces at most one reflected and one
 * refracted beam per sub-beam, recursively. Primary beams come from screen
 * blocks shaped to the width: 2x2 (SSE), 4x2 (AVX2), 4x4 (AVX-512).
 *
 * This file is compiled once per ISA (see simd/simd.h). It is instantiated
 * twice more inside: once with the default maths as compile-time constants
 * (minimax pow/exp, Newton-refined rcp), which is the fast path, and once
 * reading --math and --no-newton at run time, for the experiments of the
 * thesis's §5.4. */
#include "render/backend.h"
#include "render/packet.h"


typedef struct beam_ctx {
  const packet_scene *ps;
  glint_math math;
  int newton;
  glint_stats *st;
} beam_ctx;

/* Rays are passed by pointer: by value, each call would copy six vectors
 * through the stack. */
typedef void (*trace_fn)(const beam_ctx *c, const vvec3 *o, const vvec3 *d,
                         vmask active, int level, vvec3 *color);

/* Shades the sub-beam `sub` (every lane hit `object`) and, below the depth
 * limit, traces its reflected and refracted beams. */
static ALWAYS_INLINE void shade_sub_beam(const beam_ctx *c, vvec3 o, vvec3 d,
                                         const packet_hit *h, int object,
                                         vmask sub, int level, vvec3 *out,
                                         glint_math math, int newton,
                                         trace_fn trace) {
  const packet_scene *ps = c->ps;
  const scene_r *s = ps->s;
  const object_r *ob = &s->objects[object];
  const material_r *mat = &s->materials[ob->material];
  const pmaterial *pm = &ps->materials[ob->material];
  packet_surface f = packet_surface_at(ps, ob, h, o, d, newton);
  vvec3 col = packet_color(mat, pm, ob, f.p);
  vvec3 color = packet_local_shading(ps, mat, pm, col, &f, d, sub, math,
                                     newton, c->st);

  if (level < s->max_depth && (mat->kr > 0 || mat->kt > 0)) {
    vvec3 reflected, refracted;
    vfloat kr;
    vmask refract, tir;
    packet_secondary(mat, pm, &f, d, sub, &reflected, &kr, &refracted,
                     &refract, &tir);
    c->st->total_internal_reflections += (uint64_t)vm_count(tir);
    if (vm_any(refract)) {
      vvec3 ct;
      c->st->secondary_rays += (uint64_t)vm_count(refract);
      c->st->refracted_rays += (uint64_t)vm_count(refract);
      trace(c, &f.p, &refracted, refract, level + 1, &ct);
      vfloat kt = vf_keep(refract, vs_get(&pm->kt));
      color = vv_madd(color, kt, ct);
    }
    vmask reflect = vm_and(sub, vf_gt(kr, vf_zero()));
    if (vm_any(reflect)) {
      vvec3 cr;
      c->st->secondary_rays += (uint64_t)vm_count(reflect);
      c->st->reflected_rays += (uint64_t)vm_count(reflect);
      trace(c, &f.p, &reflected, reflect, level + 1, &cr);
      color = vv_madd(color, vf_keep(reflect, kr), cr);
    }
  }
  color = packet_beer(mat, pm, &f, h->t, sub, color, math);
  *out = vv_select(sub, color, *out);
}

/* One beam: nearest hits, then one sub-beam per object hit. The grouping by
 * object yields the same sub-beams as the thesis's Hit stack (listings
 * 4.1–4.3) without its capacity-W bookkeeping. */
static ALWAYS_INLINE void trace_beam_body(const beam_ctx *c, vvec3 o, vvec3 d,
                                          vmask active, int level,
                                          vvec3 *color, glint_math math,
                                          int newton, trace_fn trace) {
  c->st->beams++;
  packet_hit h;
  packet_nearest(c->ps, o, d, active, newton, &h, c->st);
  *color = vv_get(c->ps->background);
  vmask todo = vm_andnot(active, vi_eq(h.object, vi_set1(-1)));
  if (vm_none(todo))
    return;
  SIMD_ALIGN int objects[W];
  vi_store(objects, h.object);
  while (vm_any(todo)) {
    int object = objects[vm_first(todo)];
    vmask sub = vm_and(todo, vi_eq(h.object, vi_set1(object)));
    todo = vm_andnot(todo, sub);
    c->st->sub_beams++;
    shade_sub_beam(c, o, d, &h, object, sub, level, color, math, newton,
                   trace);
  }
}

static void trace_default(const beam_ctx *c, const vvec3 *o, const vvec3 *d,
                          vmask active, int level, vvec3 *color) {
  trace_beam_body(c, *o, *d, active, level, color, GLINT_MATH_MINIMAX, 1,
                  trace_default);
}

static void trace_generic(const beam_ctx *c, const vvec3 *o, const vvec3 *d,
                          vmask active, int level, vvec3 *color) {
  trace_beam_body(c, *o, *d, active, level, color, c->math, c->newton,
                  trace_generic);
}

/* Block shapes: W lanes as BW x BH pixels. */
#if GLINT_SIMD_WIDTH == 4
#define BW 2
#elif GLINT_SIMD_WIDTH == 8
#define BW 4
#else
#define BW 4
#endif
#define BH (W / BW)

static ALWAYS_INLINE void render_tile_body(const packet_scene *ps,
                                           const glint_tile *tile, float *rgb,
                                           glint_stats *st, int newton,
                                           trace_fn trace) {
  const scene_r *s = ps->s;
  beam_ctx c = {ps, ps->math, ps->newton, st};
  const camera *cam = &s->cam;
  /* Lane i covers pixel (bx + i % BW, by + i / BW). */
  SIMD_ALIGN float lx[W], ly[W];
  for (int i = 0; i < W; i++) {
    lx[i] = (float)(i % BW);
    ly[i] = (float)(i / BW);
  }
  vfloat lane_x = vf_load(lx), lane_y = vf_load(ly);
  /* SPEC §2: x = (2 px / W - 1) tan, y = (1 - 2 py / H) tan_y */
  vfloat sx = vf_set1(2 * cam->tan_x / cam->width), ox = vf_set1(-cam->tan_x);
  vfloat sy = vf_set1(-2 * cam->tan_y / cam->height), oy = vf_set1(cam->tan_y);
  vvec3 from = vv_set1(cam->from), cd = vv_set1(cam->d), cr = vv_set1(cam->r),
        cu = vv_set1(cam->u);
  vfloat inv_spp = vf_set1(1.0f / (float)s->spp);
  int tw = tile->x1 - tile->x0;
  for (int by = tile->y0; by < tile->y1; by += BH)
    for (int bx = tile->x0; bx < tile->x1; bx += BW) {
      vfloat px = vf_add(vf_set1((float)bx), lane_x);
      vfloat py = vf_add(vf_set1((float)by), lane_y);
      vmask valid = vm_and(vf_lt(px, vf_set1((float)tile->x1)),
                           vf_lt(py, vf_set1((float)tile->y1)));
      vvec3 sum = {vf_zero(), vf_zero(), vf_zero()};
      for (int k = 0; k < s->spp; k++) {
        vfloat x = vf_fmadd(
            vf_add(px, vf_set1(0.5f + s->samples[k][0])), sx, ox);
        vfloat y = vf_fmadd(
            vf_add(py, vf_set1(0.5f + s->samples[k][1])), sy, oy);
        vvec3 dir = vv_normalize(vv_madd(vv_madd(cd, x, cr), y, cu), newton);
        vvec3 color;
        trace(&c, &from, &dir, valid, 1, &color);
        sum = vv_add(sum, color);
      }
      st->primary_rays += (uint64_t)vm_count(valid) * (uint64_t)s->spp;
      SIMD_ALIGN float r[W], g[W], bl[W];
      vf_store(r, vf_mul(sum.x, inv_spp));
      vf_store(g, vf_mul(sum.y, inv_spp));
      vf_store(bl, vf_mul(sum.z, inv_spp));
      int bits = vm_bits(valid);
      for (int i = 0; i < W; i++)
        if (bits >> i & 1) {
          int x = bx + i % BW - tile->x0, y = by + i / BW - tile->y0;
          float *out = rgb + ((size_t)y * tw + x) * 3;
          out[0] = r[i];
          out[1] = g[i];
          out[2] = bl[i];
        }
    }
}

static void render_tile(const void *prepared, const glint_tile *tile,
                        void *scratch, float *rgb, glint_stats *st) {
  (void)scratch;
  const packet_scene *ps = prepared;
  if (ps->math == GLINT_MATH_MINIMAX && ps->newton)
    render_tile_body(ps, tile, rgb, st, 1, trace_default);
  else
    render_tile_body(ps, tile, rgb, st, ps->newton, trace_generic);
}

static glint_status prepare(const glint_scene *scene, const glint_frame *frame,
                            void **prepared, glint_stats *stats,
                            glint_error *error) {
  packet_scene *ps;
  glint_status st = packet_scene_prepare(scene, frame, &ps, stats, error);
  *prepared = ps;
  return st;
}

static void release(void *prepared) { packet_scene_release(prepared); }

const glint_backend_ops ISA_NAME(glint_beam_ops) = {prepare, release, NULL,
                                                    render_tile};

/* For the tests: the packet nearest hit of W rays (SoA arrays of W floats),
 * with the default maths. Writes t and object per lane (-1: no hit). */
void ISA_NAME(glint_beam_nearest_hit)(const void *prepared, const float *o,
                                      const float *d, int active_bits,
                                      float *t, int *object) {
  const packet_scene *ps = prepared;
  glint_stats st = {0};
  vvec3 vo = {vf_loadu(o), vf_loadu(o + W), vf_loadu(o + 2 * W)};
  vvec3 vd = {vf_loadu(d), vf_loadu(d + W), vf_loadu(d + 2 * W)};
  packet_hit h;
  packet_nearest(ps, vo, vd, vm_from_bits(active_bits), 1, &h, &st);
  SIMD_ALIGN float tt[W];
  SIMD_ALIGN int ob[W];
  vf_store(tt, h.t);
  vi_store(ob, h.object);
  for (int i = 0; i < W; i++) {
    t[i] = tt[i];
    object[i] = ob[i];
  }
}
