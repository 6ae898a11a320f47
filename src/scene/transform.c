/* An object's primitives moved by a glint_transform: points by
 * p -> translate + pivot + scale R (p - pivot), directions (normals) by R,
 * lengths (radii) by scale. R = Rz Ry Rx, each a right-handed rotation by
 * the given degrees (include/glint.h, glint_transform). */
#include "scene/scene.h"

#include <math.h>

static const double degrees = 3.14159265358979323846 / 180;

typedef struct rigid {
  double r[3][3];
  glint_vec3 translate, pivot;
  double scale;
} rigid;

static rigid rigid_of(const glint_transform *t) {
  double cx = cos(t->rotate.x * degrees), sx = sin(t->rotate.x * degrees);
  double cy = cos(t->rotate.y * degrees), sy = sin(t->rotate.y * degrees);
  double cz = cos(t->rotate.z * degrees), sz = sin(t->rotate.z * degrees);
  /* Rz Ry Rx, written out. */
  rigid m = {{{cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
              {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
              {-sy, cy * sx, cy * cx}},
             t->translate,
             t->pivot,
             t->scale};
  return m;
}

static glint_vec3 turn(const rigid *m, glint_vec3 v) {
  return (glint_vec3){m->r[0][0] * v.x + m->r[0][1] * v.y + m->r[0][2] * v.z,
                      m->r[1][0] * v.x + m->r[1][1] * v.y + m->r[1][2] * v.z,
                      m->r[2][0] * v.x + m->r[2][1] * v.y + m->r[2][2] * v.z};
}

static glint_vec3 move(const rigid *m, glint_vec3 p) {
  glint_vec3 d = turn(
      m, (glint_vec3){p.x - m->pivot.x, p.y - m->pivot.y, p.z - m->pivot.z});
  return (glint_vec3){m->translate.x + m->pivot.x + m->scale * d.x,
                      m->translate.y + m->pivot.y + m->scale * d.y,
                      m->translate.z + m->pivot.z + m->scale * d.z};
}

int gli_object_transform(glint_scene *s, uint32_t object,
                         const glint_transform *t) {
  int finite = 1; /* and within GLINT_MAX_COORDINATE */
  rigid m = rigid_of(t);
  gli_object *o = &s->objects[object];
  o->origin = move(&m, o->origin);
  for (uint32_t i = o->first; i < o->first + o->count; i++) {
    switch ((gli_shape)o->shape) {
    case GLI_SHAPE_SPHERE:
      s->spheres[i].center = move(&m, s->spheres[i].center);
      s->spheres[i].radius *= m.scale;
      finite &= gli_vec3_in_range(s->spheres[i].center) &
                gli_in_range(s->spheres[i].radius);
      break;
    case GLI_SHAPE_PLANE: {
      /* n.X + d = 0: move the point -d n and turn the normal. */
      gli_plane_prim *p = &s->planes[i];
      glint_vec3 point = {-p->d * p->normal.x, -p->d * p->normal.y,
                          -p->d * p->normal.z};
      point = move(&m, point);
      p->normal = turn(&m, p->normal);
      p->d = -(p->normal.x * point.x + p->normal.y * point.y +
               p->normal.z * point.z);
      finite &= gli_vec3_finite(p->normal) & gli_in_range(p->d);
      break;
    }
    case GLI_SHAPE_TRIANGLE: {
      gli_triangle_prim *tr = &s->triangles[i];
      for (int k = 0; k < 3; k++) {
        tr->v[k] = move(&m, tr->v[k]);
        finite &= gli_vec3_in_range(tr->v[k]);
      }
      if (tr->normals != GLI_NO_NORMALS)
        for (int k = 0; k < 3; k++)
          s->tri_normals[tr->normals + (uint32_t)k] =
              turn(&m, s->tri_normals[tr->normals + (uint32_t)k]);
      break;
    }
    case GLI_SHAPE_CONE:
      s->cones[i].base = move(&m, s->cones[i].base);
      s->cones[i].apex = move(&m, s->cones[i].apex);
      s->cones[i].base_radius *= m.scale;
      s->cones[i].apex_radius *= m.scale;
      finite &= gli_vec3_in_range(s->cones[i].base) &
                gli_vec3_in_range(s->cones[i].apex) &
                gli_in_range(s->cones[i].base_radius) &
                gli_in_range(s->cones[i].apex_radius);
      break;
    }
  }
  return finite ? 0 : -1;
}
