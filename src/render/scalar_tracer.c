/* The scalar Whitted tracer: one ray at a time, recursively (thesis §2.2),
 * shading by the extended Phong model of docs/specification.md §4
 * (eq. 2.9–2.13). This source is compiled once per precision; the float and
 * double builds are the reference every faster backend is checked against. */
#include "render/backend.h"
#include "render/scalar_scene.h"
#include "render/camera.h"

#include "geometry/intersect.h"
#include "math/optics.h"
#include "scene/scene.h"

/* A cell's parity without integer conversion, so huge coordinates cannot
 * overflow: floor(a) is odd exactly when floor(a)/2 is not an integer. */
static inline int parity(real a) {
  real f = r_floor(a) * (real)0.5;
  return f != r_floor(f);
}

/* The surface colour C at p (docs/specification.md §4, textures). */
static inline vec3 surface_color(const material_r *m, const object_r *ob,
                                 vec3 p) {
  switch (m->texture) {
  case GLINT_TEXTURE_CHECKER_PLANAR: {
    int odd = parity(v3_get(p, ob->axis_u) * m->inv_size) ^
              parity(v3_get(p, ob->axis_v) * m->inv_size);
    return odd ? m->odd : m->even;
  }
  case GLINT_TEXTURE_CHECKER_SOLID: {
    vec3 q = v3_scale(v3_sub(p, ob->origin), m->inv_size);
    int odd = parity(q.x) ^ parity(q.y) ^ parity(q.z);
    return odd ? m->odd : m->even;
  }
  default: return m->color;
  }
}

/* Where a ray met a surface, with the normal turned to face the ray. */
typedef struct surface {
  vec3 p, n;
  uint32_t object;
  int front; /* hit the outside: the ray enters a closed object */
} surface;

static inline surface surface_at(const scene_r *s, const hit_r *h, vec3 o,
                                 vec3 d) {
  surface f;
  f.p = v3_madd(o, h->t, d);
  vec3 ng;
  switch (h->shape) {
  case GLI_SHAPE_SPHERE: {
    const sphere_r *sp = &s->spheres[h->prim];
    /* Normalised rather than scaled by 1/r: a grazing hit's point can lie
     * off the surface by more than rounding, and a normal that is not unit
     * length lengthens every reflected direction, until V·R > 1 and the
     * highlight's power explodes (seen at depth 15 in Billiard, in float). */
    ng = v3_normalize(v3_sub(f.p, sp->center));
    f.front = !h->inside;
    f.object = sp->object;
    break;
  }
  case GLI_SHAPE_PLANE:
    ng = s->planes[h->prim].n;
    f.front = v3_dot(ng, d) < 0;
    f.object = s->planes[h->prim].object;
    break;
  case GLI_SHAPE_CONE: {
    const cone_r *c = &s->cones[h->prim];
    ng = v3_normalize(cone_normal(c->base, c->axis, c->rb, c->k, f.p));
    f.front = v3_dot(ng, d) < 0;
    f.object = c->object;
    break;
  }
  default: { /* GLI_SHAPE_TRIANGLE */
    const triangle_r *t = &s->triangles[h->prim];
    ng = t->ng;
    f.front = v3_dot(ng, d) < 0;
    f.object = t->object;
    if (t->normals != GLI_NO_NORMALS) {
      /* Interpolated vertex normals (NFF polygonal patches). */
      const vec3 *vn = &s->normals[t->normals];
      vec3 n = v3_madd(v3_madd(v3_scale(vn[0], 1 - h->u - h->v), h->u, vn[1]),
                       h->v, vn[2]);
      real l = v3_len(n);
      if (l > 0) {
        n = v3_scale(n, 1 / l);
        f.n = v3_dot(n, d) < 0 ? n : v3_neg(n);
        return f;
      }
    }
    break;
  }
  }
  f.n = f.front ? ng : v3_neg(ng);
  return f;
}

/* Whether a ray of this weight is traced (GLI_MIN_RAY_WEIGHT). */
static int worth_tracing(vec3 weight) {
  real largest = weight.x > weight.y ? weight.x : weight.y;
  return (largest > weight.z ? largest : weight.z) >= (real)GLI_MIN_RAY_WEIGHT;
}

/* What the ray o + t d sees, for a ray of the given weight (the product of
 * the coefficients that scale what it brings to its pixel). */
static vec3 trace(const scene_r *s, int max_depth, vec3 o, vec3 d, int level,
                  vec3 weight, glint_stats *st) {
  hit_r h;
  if (!scalar_nearest_hit(s, &o, &d, REAL_MAX, &h))
    return s->background;
  surface f = surface_at(s, &h, o, d);
  const object_r *ob = &s->objects[f.object];
  const material_r *m = &s->materials[ob->material];
  vec3 c = surface_color(m, ob, f.p);
  vec3 v = v3_neg(d);

  /* Local shading, eq. 2.9/2.10: C (ka Ia + sum S kd N·L IL) and the
   * highlights sum S ks (V·R)^h IL. */
  vec3 diffuse = v3_scale(s->ambient, m->ka);
  vec3 highlight = v3(0, 0, 0);
  for (size_t j = 0; j < s->light_count; j++) {
    const light_r *li = &s->lights[j];
    vec3 l = v3_sub(li->position, f.p);
    real dist = v3_len(l);
    l = v3_scale(l, 1 / dist);
    real nl = v3_dot(f.n, l);
    if (nl <= 0)
      continue; /* the light is behind the surface: no diffuse, no highlight */
    st->shadow_rays++;
    vec3 sj = scalar_transmission(s, &f.p, &l, dist);
    if (sj.x == 0 && sj.y == 0 && sj.z == 0)
      continue;
    vec3 il = v3_mul(sj, li->color);
    diffuse = v3_madd(diffuse, m->kd * nl, il);
    if (m->ks > 0) {
      vec3 r = v3_madd(v3_neg(l), 2 * nl, f.n); /* R = 2(L·N)N - L */
      real vr = v3_dot(v, r);
      if (vr > 0)
        highlight = v3_madd(highlight, m->ks * r_pow(vr, m->h), il);
    }
  }
  vec3 color = v3_add(v3_mul(c, diffuse), highlight);

  /* Beer's law (eq. 2.11) on a stretch travelled inside an object: it
   * scales what this surface brings, children included. */
  int absorbed = !f.front && m->absorbs;
  vec3 beer_factor = absorbed ? beer(m->absorb, h.t) : v3(1, 1, 1);
  weight = v3_mul(weight, beer_factor);

  /* Secondary rays, one level deeper; beyond the limit, or too faint to
   * matter (GLI_MIN_RAY_WEIGHT), they are black. */
  if (level < max_depth) {
    real kr = m->kr;
    if (m->kt > 0) {
      real eta = f.front ? 1 / m->ior : m->ior;
      vec3 t;
      if (!refract_dir(d, f.n, eta, &t)) {
        /* Total internal reflection: the reflected ray takes kt as well. */
        st->total_internal_reflections++;
        kr += m->kt;
      } else if (worth_tracing(v3_scale(weight, m->kt))) {
        st->secondary_rays++;
        st->refracted_rays++;
        color = v3_madd(color, m->kt,
                        trace(s, max_depth, f.p, t, level + 1,
                              v3_scale(weight, m->kt), st));
      }
    }
    if (kr > 0 && worth_tracing(v3_scale(weight, kr))) {
      st->secondary_rays++;
      st->reflected_rays++;
      color = v3_madd(color, kr,
                      trace(s, max_depth, f.p, reflect_dir(d, f.n), level + 1,
                            v3_scale(weight, kr), st));
    }
  }
  return absorbed ? v3_mul(color, beer_factor) : color;
}

static void render_tile(const void *view, const frame_params *frame,
                        const tile_rect *tile, void *scratch, float *rgb,
                        glint_stats *st) {
  (void)scratch;
  const scene_r *s = view;
  camera cam;
  camera_from_basis(&cam, &frame->camera);
  real inv_spp = (real)1 / (real)frame->spp;
  for (int y = tile->y0; y < tile->y1; y++)
    for (int x = tile->x0; x < tile->x1; x++) {
      vec3 sum = v3(0, 0, 0);
      for (int k = 0; k < frame->spp; k++) {
        real px = (real)x + (real)0.5 + (real)frame->samples[k][0];
        real py = (real)y + (real)0.5 + (real)frame->samples[k][1];
        vec3 d = camera_dir(&cam, px, py);
        sum = v3_add(
            sum, trace(s, frame->max_depth, cam.from, d, 1, v3(1, 1, 1), st));
      }
      float *out =
          rgb +
          ((size_t)(y - tile->y0) * (tile->x1 - tile->x0) + (x - tile->x0)) * 3;
      out[0] = (float)(sum.x * inv_spp);
      out[1] = (float)(sum.y * inv_spp);
      out[2] = (float)(sum.z * inv_spp);
    }
  st->primary_rays += (uint64_t)(tile->x1 - tile->x0) *
                      (uint64_t)(tile->y1 - tile->y0) * (uint64_t)frame->spp;
}

static uint64_t primary_tile(const void *view, const frame_params *frame,
                             const tile_rect *tile, glint_stats *st) {
  const scene_r *s = view;
  camera cam;
  camera_from_basis(&cam, &frame->camera);
  uint64_t hits = 0;
  for (int y = tile->y0; y < tile->y1; y++)
    for (int x = tile->x0; x < tile->x1; x++)
      for (int k = 0; k < frame->spp; k++) {
        real px = (real)x + (real)0.5 + (real)frame->samples[k][0];
        real py = (real)y + (real)0.5 + (real)frame->samples[k][1];
        hit_r h;
        vec3 d = camera_dir(&cam, px, py);
        hits += (uint64_t)scalar_nearest_hit(s, &cam.from, &d, REAL_MAX, &h);
      }
  st->primary_rays += (uint64_t)(tile->x1 - tile->x0) *
                      (uint64_t)(tile->y1 - tile->y0) * (uint64_t)frame->spp;
  return hits;
}

const gli_backend_ops REAL_NAME(gli_scalar_ops) = {
    REAL_IS_DOUBLE ? DATA_SCALAR_DOUBLE : DATA_SCALAR_FLOAT, 1, NULL,
    render_tile, primary_tile};
