/* The canonical scene: what the user described, in double precision, before
 * any backend converts it. Every backend prepares its own copy (float or
 * double, AoS or SoA) from this one. */
#ifndef GLINT_SCENE_SCENE_H
#define GLINT_SCENE_SCENE_H

#include "glint.h"

#include <stddef.h>
#include <stdint.h>

typedef enum gli_shape {
  GLI_SHAPE_SPHERE = 0,
  GLI_SHAPE_TRIANGLE = 1, /* one triangle, a polygon or a whole mesh */
  GLI_SHAPE_CONE = 2,
  GLI_SHAPE_PLANE = 3
} gli_shape;

/* An object is what the user added in one call: one material, one shape
 * kind, a contiguous range of primitives. Beams split per object. */
typedef struct gli_object {
  uint32_t material;
  uint32_t shape; /* gli_shape */
  uint32_t first, count;
  glint_vec3 origin; /* local-coordinate origin for solid textures */
} gli_object;

typedef struct gli_sphere_prim {
  glint_vec3 center;
  double radius;
  uint32_t object;
} gli_sphere_prim;

typedef struct gli_plane_prim {
  glint_vec3 normal; /* unit length */
  double d;          /* n·X + d = 0 on the plane (eq. 2.3, 2.4) */
  uint32_t object;
} gli_plane_prim;

typedef struct gli_triangle_prim {
  glint_vec3 v[3];
  uint32_t object;
  uint32_t normals; /* index of 3 vertex normals in tri_normals, or NONE */
} gli_triangle_prim;

#define GLI_NO_NORMALS UINT32_MAX

typedef struct gli_cone_prim {
  glint_vec3 base, apex;
  double base_radius, apex_radius;
  uint32_t object;
} gli_cone_prim;

typedef struct gli_light {
  glint_vec3 position, color;
} gli_light;

/* Keyframes of `width` numbers each (scene/animation.c): times[count] and
 * values[count * width], interpolated component by component. */
typedef struct gli_track {
  glint_interpolation interpolation;
  size_t count, width;
  double *times, *values;
} gli_track;

/* An object moved by keyed transforms (10 numbers a key: translate,
 * rotate, pivot, scale). */
typedef struct gli_motion {
  uint32_t object;
  gli_track track;
} gli_motion;

/* The scene's animation (scene/animation.c): its frames, how the camera
 * moves (camera_mode STILL keeps it) and which objects move. */
typedef enum gli_camera_mode {
  GLI_CAMERA_STILL = 0,
  GLI_CAMERA_KEYS,
  GLI_CAMERA_ORBIT
} gli_camera_mode;

typedef struct gli_animation {
  int present;
  glint_animation frames;
  gli_camera_mode camera_mode;
  gli_track camera_keys; /* 10 numbers a key: from, at, up, fov */
  glint_vec3 orbit_center;
  double orbit_radius, orbit_height, orbit_degrees;
  gli_motion *motions;
  size_t motion_count;
} gli_animation;

/* Deep copy and release of the animation's arrays (scene/animation.c). */
int gli_animation_copy(gli_animation *dst, const gli_animation *src);
void gli_animation_free(gli_animation *animation);
/* Applies `t` to object `object`'s primitives (scene/transform.c); -1 when
 * a moved coordinate or radius leaves GLINT_MAX_COORDINATE's range (the
 * scene is then not to be used). */
int gli_object_transform(glint_scene *scene, uint32_t object,
                         const glint_transform *t);

struct glint_scene {
  glint_camera camera;
  gli_animation animation;
  int width, height;
  glint_vec3 background, ambient;

  gli_light *lights;
  size_t light_count, light_cap;
  glint_material *materials;
  size_t material_count, material_cap;
  gli_object *objects;
  size_t object_count, object_cap;

  gli_sphere_prim *spheres;
  size_t sphere_count, sphere_cap;
  gli_plane_prim *planes;
  size_t plane_count, plane_cap;
  gli_triangle_prim *triangles;
  size_t triangle_count, triangle_cap;
  glint_vec3 *tri_normals;
  size_t tri_normal_count, tri_normal_cap;
  gli_cone_prim *cones;
  size_t cone_count, cone_cap;

  size_t ear_tests_left; /* of GLI_SCENE_EAR_TESTS (scene/polygon.h) */
};

/* Validation shared by the API and the file loaders. */
int gli_vec3_finite(glint_vec3 v);
/* Finite and of magnitude at most GLINT_MAX_COORDINATE (a scene's
 * coordinates and sizes); GLI_RANGE_TEXT says so in messages. */
int gli_in_range(double x);
int gli_vec3_in_range(glint_vec3 v);
#define GLI_RANGE_TEXT "finite numbers of magnitude at most 1e15"

/* Appends a triangle to the object being built (the last one added by
 * gli_scene_begin_object). `normals` may be NULL. */
glint_status gli_scene_begin_object(glint_scene *scene, gli_shape shape,
                                    uint32_t material, glint_error *error);
glint_status gli_scene_push_triangle(glint_scene *scene, glint_vec3 a,
                                     glint_vec3 b, glint_vec3 c,
                                     const glint_vec3 normals[3],
                                     glint_error *error);
/* What gli_scene_push_triangle checks of a triangle's own values: its
 * coordinates and normals (NULL: none) within range. */
glint_status gli_scene_check_triangle(glint_vec3 a, glint_vec3 b, glint_vec3 c,
                                      const glint_vec3 normals[3],
                                      glint_error *error);
/* gli_scene_push_triangle for a triangle already checked. */
glint_status gli_scene_append_triangle(glint_scene *scene, glint_vec3 a,
                                       glint_vec3 b, glint_vec3 c,
                                       const glint_vec3 normals[3],
                                       glint_error *error);

/* The order in which to add a mesh's `count` triangles (vertex indices
 * `triples`, three a triangle, into `pos`): along a Morton curve through
 * their centroids (scene.c). Free it; NULL: the given order, for a mesh of
 * fewer than GLI_MORTON_MIN_TRIANGLES (whose records a cache holds in any
 * order) or without memory. */
#define GLI_MORTON_MIN_TRIANGLES 1024
uint32_t *gli_morton_order(const glint_vec3 *pos, const uint32_t *triples,
                           size_t count);

/* The scene file readers (scene/formats/nff.c, json.c): `data` is the
 * file's `size` bytes followed by a NUL; `path` names it in messages and
 * places the files it refers to (a JSON scene's meshes), which come from
 * `files` (NULL: the file system). */
struct gli_file_source;
glint_status gli_nff_read(const struct gli_file_source *files, const char *path,
                          const char *data, size_t size, glint_scene **out,
                          glint_error *error);
glint_status gli_json_read(const struct gli_file_source *files,
                           const char *path, const char *data, size_t size,
                           glint_scene **out, glint_error *error);

/* glint_scene_load with its files from `files` (scene/formats/registry.c). */
glint_status gli_scene_load_from(const struct gli_file_source *files,
                                 const char *path, glint_scene **out,
                                 glint_error *error);

/* Checks a camera as glint_scene_set_camera does (finite, 0 < fov < 180,
 * from != at, up not parallel to the view). */
glint_status gli_camera_check(const glint_camera *camera, glint_error *error);

/* A camera's values, as gli_camera_check_field names the one at fault
 * ('from' and 'at' together too close: 'at'). */
typedef enum gli_camera_field {
  GLI_CAMERA_FROM,
  GLI_CAMERA_AT,
  GLI_CAMERA_UP,
  GLI_CAMERA_FOV
} gli_camera_field;

/* gli_camera_check, which on failure also sets *field. */
glint_status gli_camera_check_field(const glint_camera *camera,
                                    gli_camera_field *field,
                                    glint_error *error);

/* A deep copy (scene/copy.c). */
glint_status gli_scene_copy(const glint_scene *scene, glint_scene **copy,
                            glint_error *error);

/* The smallest t a hit may have (docs/specification.md §3): 1e-4 times the
 * scene's scale, the largest coordinate magnitude among the camera and the
 * bounded primitives. */
double gli_scene_epsilon(const glint_scene *scene);
/* The same in two steps, for a camera other than the scene's (a frame's
 * own): the bounded primitives' largest coordinate magnitude, and the
 * epsilon of that extent seen from `eye`. */
double gli_scene_extent(const glint_scene *scene);
double gli_epsilon_at(double extent, glint_vec3 eye);

/* The lesser and the greater of v and m, and [lo, hi] grown to hold the
 * cube of half-size r about p. Comparisons, not fmin and fmax: those are
 * calls, millions of them over a large mesh's vertices (the 200k-triangle
 * dragon's bounds and epsilon: 5.4 million). A NaN v is passed over, as
 * fmin and fmax do. */
static inline double gli_lower(double v, double m) { return v < m ? v : m; }
static inline double gli_higher(double v, double m) { return v > m ? v : m; }

static inline void gli_bounds_grow(glint_vec3 *lo, glint_vec3 *hi, glint_vec3 p,
                                   double r) {
  lo->x = gli_lower(p.x - r, lo->x), hi->x = gli_higher(p.x + r, hi->x);
  lo->y = gli_lower(p.y - r, lo->y), hi->y = gli_higher(p.y + r, hi->y);
  lo->z = gli_lower(p.z - r, lo->z), hi->z = gli_higher(p.z + r, hi->z);
}

#endif
