/* The canonical scene: what the user described, in double precision, before
 * any backend converts it. Every backend prepares its own copy (float or
 * double, AoS or SoA) from this one. */
#ifndef GLINT_SCENE_SCENE_H
#define GLINT_SCENE_SCENE_H

#include "glint.h"

#include <stddef.h>
#include <stdint.h>

typedef enum glint_shape {
  GLINT_SHAPE_SPHERE = 0,
  GLINT_SHAPE_TRIANGLE = 1, /* one triangle, a polygon or a whole mesh */
  GLINT_SHAPE_CONE = 2,
  GLINT_SHAPE_PLANE = 3
} glint_shape;

/* An object is what the user added in one call: one material, one shape
 * kind, a contiguous range of primitives. Beams split per object. */
typedef struct glint_object {
  uint32_t material;
  uint32_t shape; /* glint_shape */
  uint32_t first, count;
  glint_vec3 origin; /* local-coordinate origin for solid textures */
} glint_object;

typedef struct glint_sphere_prim {
  glint_vec3 center;
  double radius;
  uint32_t object;
} glint_sphere_prim;

typedef struct glint_plane_prim {
  glint_vec3 normal; /* unit length */
  double d;          /* n·X + d = 0 on the plane (eq. 2.3, 2.4) */
  uint32_t object;
} glint_plane_prim;

typedef struct glint_triangle_prim {
  glint_vec3 v[3];
  uint32_t object;
  uint32_t normals; /* index of 3 vertex normals in tri_normals, or NONE */
} glint_triangle_prim;

#define GLINT_NO_NORMALS UINT32_MAX

typedef struct glint_cone_prim {
  glint_vec3 base, apex;
  double base_radius, apex_radius;
  uint32_t object;
} glint_cone_prim;

typedef struct glint_light {
  glint_vec3 position, color;
} glint_light;

struct glint_scene {
  glint_camera camera;
  int width, height;
  glint_vec3 background, ambient;

  glint_light *lights;
  size_t light_count, light_cap;
  glint_material *materials;
  size_t material_count, material_cap;
  glint_object *objects;
  size_t object_count, object_cap;

  glint_sphere_prim *spheres;
  size_t sphere_count, sphere_cap;
  glint_plane_prim *planes;
  size_t plane_count, plane_cap;
  glint_triangle_prim *triangles;
  size_t triangle_count, triangle_cap;
  glint_vec3 *tri_normals;
  size_t tri_normal_count, tri_normal_cap;
  glint_cone_prim *cones;
  size_t cone_count, cone_cap;
};

/* Validation shared by the API and the file loaders. */
int glint_vec3_finite(glint_vec3 v);

/* Appends a triangle to the object being built (the last one added by
 * glint_scene_begin_object). `normals` may be NULL. */
glint_status glint_scene_begin_object(glint_scene *scene, glint_shape shape,
                                      uint32_t material, glint_error *error);
glint_status glint_scene_push_triangle(glint_scene *scene, glint_vec3 a,
                                       glint_vec3 b, glint_vec3 c,
                                       const glint_vec3 normals[3],
                                       glint_error *error);

/* File readers (scene/nff.c, scene/json.c). */
glint_status glint_nff_load(const char *path, glint_scene **out,
                            glint_error *error);
glint_status glint_json_load(const char *path, glint_scene **out,
                             glint_error *error);

/* Checks a camera as glint_scene_set_camera does (finite, 0 < fov < 180,
 * from != at, up not parallel to the view). */
glint_status glint_camera_check(const glint_camera *camera, glint_error *error);

/* A deep copy (scene/copy.c). */
glint_status glint_scene_copy(const glint_scene *scene, glint_scene **copy,
                              glint_error *error);

/* The smallest t a hit may have (SPEC §3): 1e-4 times the scene's scale, the
 * largest coordinate magnitude among the camera and the bounded primitives. */
double glint_scene_epsilon(const glint_scene *scene);

#endif
