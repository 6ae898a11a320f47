/* Building the packet scene (see packet_scene.h). Compiled once per ISA. */
#include "render/packet_scene.h"

#include "core/error.h"
#include "core/memory.h"
#include "accel/packet_traverse.h"
#include "render/backend.h"
#include "render/leaf_blocks.h"
#include "scene/scene.h"

#include <stdlib.h>

static void put3(vscalar *dst, vec3 v) {
  dst[0] = vs_make(v.x);
  dst[1] = vs_make(v.y);
  dst[2] = vs_make(v.z);
}

glint_status packet_scene_prepare(const glint_scene *scene, double eps,
                                  packet_scene **out, glint_error *error) {
  packet_scene *ps = gli_aligned_calloc(1, sizeof *ps);
  if (!ps)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  glint_status st = gli_scalar_scene_prepare_float(scene, eps, &ps->s, error);
  if (st) {
    gli_aligned_free(ps);
    return st;
  }
  const scene_r *s = ps->s;
  size_t materials = scene->material_count;
  ps->spheres = gli_aligned_calloc(s->sphere_count, sizeof *ps->spheres);
  ps->planes = gli_aligned_calloc(s->plane_count, sizeof *ps->planes);
  ps->triangles = gli_aligned_calloc(s->triangle_count, sizeof *ps->triangles);
  ps->cones = gli_aligned_calloc(s->cone_count, sizeof *ps->cones);
  ps->materials = gli_aligned_calloc(materials, sizeof *ps->materials);
  ps->lights = gli_aligned_calloc(s->light_count, sizeof *ps->lights);
  if (!ps->spheres || !ps->planes || !ps->triangles || !ps->cones ||
      !ps->materials || !ps->lights) {
    packet_scene_release(ps);
    return gli_fail(error, GLINT_E_MEMORY, "out of memory preparing the scene");
  }
  for (size_t i = 0; i < s->sphere_count; i++) {
    put3(ps->spheres[i].center, s->spheres[i].center);
    ps->spheres[i].r2 = vs_make(s->spheres[i].r2);
    ps->spheres[i].object = (int32_t)s->spheres[i].object;
  }
  for (size_t i = 0; i < s->plane_count; i++) {
    put3(ps->planes[i].n, s->planes[i].n);
    ps->planes[i].d = vs_make(s->planes[i].d);
    ps->planes[i].object = (int32_t)s->planes[i].object;
  }
  for (size_t i = 0; i < s->triangle_count; i++) {
    const triangle_r *t = &s->triangles[i];
    ptriangle *p = &ps->triangles[i];
    put3(p->a, t->a);
    for (int k = 0; k < 3; k++) {
      put3(p->edge[k], t->edge[k]);
      put3(p->moment[k], t->moment[k]);
    }
    put3(p->n, t->n);
    p->object = (int32_t)t->object;
  }
  for (size_t i = 0; i < s->cone_count; i++) {
    const cone_r *c = &s->cones[i];
    pcone *p = &ps->cones[i];
    put3(p->base, c->base);
    put3(p->axis, c->axis);
    p->height = vs_make(c->height);
    p->rb = vs_make(c->rb);
    p->k = vs_make(c->k);
    p->reach2 = vs_make(c->reach2);
    p->object = (int32_t)c->object;
  }
  for (size_t i = 0; i < materials; i++) {
    const material_r *m = &s->materials[i];
    pmaterial *p = &ps->materials[i];
    put3(p->color, m->color);
    put3(p->odd, m->odd);
    put3(p->even, m->even);
    put3(p->ambient, v3_scale(s->ambient, m->ka));
    p->kd = vs_make(m->kd);
    p->ks = vs_make(m->ks);
    p->h = vs_make(m->h);
    p->kr = vs_make(m->kr);
    p->kt = vs_make(m->kt);
    p->kr_tir = vs_make(m->kr + m->kt);
    p->eta_in = vs_make(1 / m->ior);
    p->eta_out = vs_make(m->ior);
    p->ior_value = vs_make(m->ior);
    put3(p->absorb, m->absorb);
    p->inv_size = vs_make(m->inv_size);
  }
  for (size_t i = 0; i < s->light_count; i++) {
    put3(ps->lights[i].position, s->lights[i].position);
    put3(ps->lights[i].color, s->lights[i].color);
  }
  ps->eps = vs_make(s->eps);
  put3(ps->background, s->background);
  put3(ps->tri_origin, s->tri_origin);
  *out = ps;
  return GLINT_OK;
}

void packet_scene_release(packet_scene *ps) {
  if (!ps)
    return;
  gli_scalar_scene_release_float(ps->s);
  gli_aligned_free(ps->spheres);
  gli_aligned_free(ps->planes);
  gli_aligned_free(ps->triangles);
  gli_aligned_free(ps->cones);
  gli_aligned_free(ps->materials);
  gli_aligned_free(ps->lights);
  gli_aligned_free(ps);
}

/* ---- the world's conversion and a renderer's view (render/backend.h) ---- */

static glint_status convert(const glint_scene *g, double eps, void **data,
                            glint_error *error) {
  packet_scene *ps = NULL;
  glint_status st = packet_scene_prepare(g, eps, &ps, error);
  *data = ps;
  return st;
}

static void release(void *data) { packet_scene_release(data); }

static size_t bytes(const void *data) {
  const packet_scene *ps = data;
  const scene_r *s = ps->s;
  return gli_scalar_scene_bytes_float(s) + sizeof *ps +
         s->sphere_count * sizeof *ps->spheres +
         s->plane_count * sizeof *ps->planes +
         s->triangle_count * sizeof *ps->triangles +
         s->cone_count * sizeof *ps->cones +
         s->material_count * sizeof *ps->materials +
         s->light_count * sizeof *ps->lights;
}

/* A view: private copies of the two headers, the arrays shared, and the
 * leaf blocks of its BVH when its packets hand subtrees to single rays. */
typedef struct packet_view {
  packet_scene ps;
  scene_r s;
  leaf_blocks *blocks;
} packet_view;

static glint_status bind(const void *data, const gli_bvh *bvh,
                         glint_accel accel, void **view, glint_error *error) {
  packet_view *v = gli_aligned_calloc(1, sizeof *v);
  if (!v)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory");
  const packet_scene *ps = data;
  v->ps = *ps;
  v->s = *ps->s;
  v->s.bvh = bvh;
  v->ps.s = &v->s;
  v->ps.outside_tests =
      v->s.plane_count +
      (bvh->node_count
           ? 0
           : v->s.sphere_count + v->s.triangle_count + v->s.cone_count);
  /* The wide tree is read only where it was built with the BVH, or for
   * bvh8, by this renderer's gli_world_bvh: another renderer's may be
   * collapsing it now (render/world.h). */
  int hand_over = accel == GLINT_ACCEL_BVH &&
                  gli_wide_may_hand_over(bvh->spheres, bvh->cones) &&
                  bvh->wide.nodes && bvh->wide.hand_overs;
  v->ps.alone_lanes = hand_over ? GLI_HYBRID_LANES
                      : accel == GLINT_ACCEL_BVH8 && bvh->wide.nodes ? LANES
                                                                     : 0;
  v->ps.prefetch =
      bvh->node_count &&
      v->s.triangle_count * sizeof *ps->triangles >= GLI_PREFETCH_BYTES;
  if (v->ps.alone_lanes) {
    glint_status st = leaf_blocks_build(&v->s, bvh, &v->blocks, error);
    if (st) {
      gli_aligned_free(v);
      return st;
    }
    v->ps.blocks = v->blocks;
  }
  *view = &v->ps;
  return GLINT_OK;
}

static void unbind(void *view) {
  packet_view *v = view; /* ps is its first member */
  leaf_blocks_free(v->blocks);
  gli_aligned_free(v);
}

static void set_epsilon(void *view, double eps) {
  packet_view *v = view;
  v->s.eps = (float)eps;
  v->ps.eps = vs_make(v->s.eps);
}

const data_ops ISA_NAME(gli_packet_data) = {convert, release, bytes,
                                            bind,    unbind,  set_epsilon};
