/* Preparing and querying a scene for the scalar tracer. Compiled once per
 * precision (see math/real.h). */
#include "render/scalar_scene.h"

#include "core/error.h"
#include "core/memory.h"
#include "geometry/intersect.h"
#include "scene/scene.h"

#include <stdlib.h>

static vec3 from_d(glint_vec3 v) { return v3((real)v.x, (real)v.y, (real)v.z); }

/* The two world axes least aligned with n: a planar checker on a floor
 * (n = +y) is indexed by x and z, exactly as SPEC §8 writes it. */
static void planar_axes(glint_vec3 n, int *u, int *v) {
  double ax = fabs(n.x), ay = fabs(n.y), az = fabs(n.z);
  if (ay >= ax && ay >= az)
    *u = 0, *v = 2;
  else if (ax >= az)
    *u = 1, *v = 2;
  else
    *u = 0, *v = 1;
}

glint_status scalar_scene_prepare(const glint_scene *g,
                                  const glint_frame *frame, scene_r **out,
                                  glint_stats *stats, glint_error *error) {
  scene_r *s = calloc(1, sizeof *s);
  if (!s)
    return glint_fail(error, GLINT_E_MEMORY, "out of memory");
  s->sphere_count = g->sphere_count;
  s->plane_count = g->plane_count;
  s->triangle_count = g->triangle_count;
  s->light_count = g->light_count;
  s->spheres = glint_aligned_calloc(g->sphere_count, sizeof *s->spheres);
  s->planes = glint_aligned_calloc(g->plane_count, sizeof *s->planes);
  s->triangles = glint_aligned_calloc(g->triangle_count, sizeof *s->triangles);
  s->normals = glint_aligned_calloc(g->tri_normal_count, sizeof *s->normals);
  s->objects = glint_aligned_calloc(g->object_count, sizeof *s->objects);
  s->materials = glint_aligned_calloc(g->material_count, sizeof *s->materials);
  s->lights = glint_aligned_calloc(g->light_count, sizeof *s->lights);
  if (!s->spheres || !s->planes || !s->triangles || !s->normals ||
      !s->objects || !s->materials || !s->lights) {
    scalar_scene_release(s);
    return glint_fail(error, GLINT_E_MEMORY,
                      "out of memory preparing the "
                      "scene");
  }

  for (size_t i = 0; i < g->sphere_count; i++) {
    const glint_sphere_prim *p = &g->spheres[i];
    s->spheres[i] = (sphere_r){from_d(p->center), (real)(p->radius * p->radius),
                               p->object};
  }
  for (size_t i = 0; i < g->plane_count; i++) {
    const glint_plane_prim *p = &g->planes[i];
    s->planes[i] = (plane_r){from_d(p->normal), (real)p->d, p->object};
  }
  for (size_t i = 0; i < g->triangle_count; i++) {
    const glint_triangle_prim *p = &g->triangles[i];
    /* Edges and normal in double, then rounded once. */
    glint_vec3 a = p->v[0], b = p->v[1], c = p->v[2];
    glint_vec3 e1 = {b.x - a.x, b.y - a.y, b.z - a.z};
    glint_vec3 e2 = {c.x - a.x, c.y - a.y, c.z - a.z};
    glint_vec3 n = {e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                    e1.x * e2.y - e1.y * e2.x};
    double nl = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    triangle_r *t = &s->triangles[i];
    t->a = from_d(a);
    if (nl > 0 && isfinite(nl)) {
      t->e1 = from_d(e1);
      t->e2 = from_d(e2);
      t->ng = v3((real)(n.x / nl), (real)(n.y / nl), (real)(n.z / nl));
      t->n = from_d(n);
    } /* else degenerate: zero edges, never hit */
    t->object = p->object;
    t->normals = p->normals;
  }
  for (size_t i = 0; i < g->tri_normal_count; i++)
    s->normals[i] = from_d(g->tri_normals[i]);
  for (size_t i = 0; i < g->material_count; i++) {
    const glint_material *m = &g->materials[i];
    material_r *r = &s->materials[i];
    r->color = from_d(m->color);
    r->odd = from_d(m->checker_odd);
    r->even = from_d(m->checker_even);
    r->inv_size = (real)(1.0 / m->checker_size);
    r->ka = (real)m->ka, r->kd = (real)m->kd, r->ks = (real)m->ks;
    r->h = (real)m->h, r->kr = (real)m->kr, r->kt = (real)m->kt;
    r->ior = (real)m->ior;
    r->absorb = from_d(m->absorb);
    r->texture = (int)m->texture;
    r->absorbs = m->absorb.x != 0 || m->absorb.y != 0 || m->absorb.z != 0;
  }
  for (size_t i = 0; i < g->object_count; i++) {
    const glint_object *o = &g->objects[i];
    object_r *r = &s->objects[i];
    r->material = o->material;
    r->shape = o->shape;
    r->first = o->first;
    r->count = o->count;
    r->smooth = o->shape == GLINT_SHAPE_TRIANGLE && o->count > 0 &&
                g->triangles[o->first].normals != GLINT_NO_NORMALS;
    r->origin = from_d(o->origin);
    glint_vec3 n = {0, 1, 0};
    if (o->shape == GLINT_SHAPE_PLANE)
      n = g->planes[o->first].normal;
    planar_axes(n, &r->axis_u, &r->axis_v);
  }
  for (size_t i = 0; i < g->light_count; i++)
    s->lights[i] =
        (light_r){from_d(g->lights[i].position), from_d(g->lights[i].color)};

  camera_init(&s->cam, &g->camera, frame->width, frame->height);
  s->background = from_d(g->background);
  s->ambient = from_d(g->ambient);
  s->eps = (real)frame->epsilon;
  s->width = frame->width;
  s->height = frame->height;
  s->spp = frame->spp;
  s->max_depth = frame->max_depth;
  s->samples = frame->samples;
  stats->scene_bytes = sizeof *s + g->sphere_count * sizeof *s->spheres +
                       g->plane_count * sizeof *s->planes +
                       g->triangle_count * sizeof *s->triangles +
                       g->tri_normal_count * sizeof *s->normals +
                       g->object_count * sizeof *s->objects +
                       g->material_count * sizeof *s->materials +
                       g->light_count * sizeof *s->lights;
  *out = s;
  return GLINT_OK;
}

void scalar_scene_release(scene_r *s) {
  if (!s)
    return;
  glint_aligned_free(s->spheres);
  glint_aligned_free(s->planes);
  glint_aligned_free(s->triangles);
  glint_aligned_free(s->normals);
  glint_aligned_free(s->objects);
  glint_aligned_free(s->materials);
  glint_aligned_free(s->lights);
  free(s);
}

/* Every object tested in turn: the thesis's brute force (§4.3). */
int scalar_nearest_hit(const scene_r *s, vec3 o, vec3 d, real tmax,
                       hit_r *hit) {
  int found = 0;
  real t, u, v;
  int inside;
  for (size_t i = 0; i < s->sphere_count; i++)
    if (sphere_hit(s->spheres[i].center, s->spheres[i].r2, o, d, s->eps, tmax,
                   &t, &inside)) {
      tmax = t;
      hit->t = t;
      hit->shape = GLINT_SHAPE_SPHERE;
      hit->prim = (uint32_t)i;
      hit->inside = inside;
      found = 1;
    }
  for (size_t i = 0; i < s->plane_count; i++)
    if (plane_hit(s->planes[i].n, s->planes[i].d, o, d, s->eps, tmax, &t)) {
      tmax = t;
      hit->t = t;
      hit->shape = GLINT_SHAPE_PLANE;
      hit->prim = (uint32_t)i;
      found = 1;
    }
  for (size_t i = 0; i < s->triangle_count; i++) {
    const triangle_r *tr = &s->triangles[i];
    if (triangle_hit(tr->a, tr->e1, tr->e2, o, d, s->eps, tmax, &t, &u, &v)) {
      tmax = t;
      hit->t = t;
      hit->shape = GLINT_SHAPE_TRIANGLE;
      hit->prim = (uint32_t)i;
      hit->u = u;
      hit->v = v;
      found = 1;
    }
  }
  return found;
}

/* The transmission along a shadow ray is a product over crossings, so their
 * order does not matter. The distance travelled inside objects is
 * sum(t_exit) - sum(t_entry) over the crossings on the segment (an object
 * the ray starts inside has no entry; lights are assumed to lie outside
 * transparent objects), so absorption needs no pairing of crossings either:
 * exp(sum over entries of a t - sum over exits of a t). */
typedef struct shadow_acc {
  vec3 kt;       /* product of kt */
  vec3 exponent; /* Beer's law exponent, <= 0 */
} shadow_acc;

/* Returns 0 when the crossing is opaque. */
static inline int cross_surface(const scene_r *s, shadow_acc *acc,
                                uint32_t object, real t, int entering) {
  const material_r *m = &s->materials[s->objects[object].material];
  if (m->kt == 0)
    return 0;
  acc->kt = v3_scale(acc->kt, m->kt);
  if (m->absorbs)
    acc->exponent = v3_madd(acc->exponent, entering ? t : -t, m->absorb);
  return 1;
}

vec3 scalar_transmission(const scene_r *s, vec3 o, vec3 d, real dist) {
  shadow_acc acc = {v3(1, 1, 1), v3(0, 0, 0)};
  const vec3 black = v3(0, 0, 0);
  real eps = s->eps;
  for (size_t i = 0; i < s->sphere_count; i++) {
    real l1, l2;
    const sphere_r *sp = &s->spheres[i];
    if (!sphere_roots(sp->center, sp->r2, o, d, &l1, &l2))
      continue;
    if (l1 > eps && l1 < dist && !cross_surface(s, &acc, sp->object, l1, 1))
      return black;
    if (l2 > eps && l2 < dist && !cross_surface(s, &acc, sp->object, l2, 0))
      return black;
  }
  real t, u, v;
  for (size_t i = 0; i < s->plane_count; i++) {
    const plane_r *p = &s->planes[i];
    if (plane_hit(p->n, p->d, o, d, eps, dist, &t) &&
        !cross_surface(s, &acc, p->object, t, v3_dot(p->n, d) < 0))
      return black;
  }
  for (size_t i = 0; i < s->triangle_count; i++) {
    const triangle_r *tr = &s->triangles[i];
    if (triangle_hit(tr->a, tr->e1, tr->e2, o, d, eps, dist, &t, &u, &v) &&
        !cross_surface(s, &acc, tr->object, t, v3_dot(tr->ng, d) < 0))
      return black;
  }
  if (acc.exponent.x == 0 && acc.exponent.y == 0 && acc.exponent.z == 0)
    return acc.kt;
  return v3_mul(acc.kt, v3(r_exp(r_fmin(acc.exponent.x, 0)),
                           r_exp(r_fmin(acc.exponent.y, 0)),
                           r_exp(r_fmin(acc.exponent.z, 0))));
}
