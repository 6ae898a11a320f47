/* A deep copy of a scene: what a committed world keeps, so that the caller
 * may edit or destroy the original afterwards (include/glint.h, Worlds). */
#include "scene/scene.h"

#include "core/error.h"
#include "core/memory.h"

#include <stdlib.h>
#include <string.h>

/* A copy of count elements of size bytes, with capacity exactly count;
 * 0 when out of memory. */
static int copy_array(void **dst, const void *src, size_t count, size_t size,
                      size_t *cap) {
  *dst = NULL;
  *cap = 0;
  if (count == 0)
    return 1;
  *dst = malloc(count * size);
  if (!*dst)
    return 0;
  gli_advise_huge(*dst, count * size);
  memcpy(*dst, src, count * size);
  *cap = count;
  return 1;
}

glint_status gli_scene_copy(const glint_scene *src, glint_scene **out,
                            glint_error *error) {
  glint_scene *s = calloc(1, sizeof *s);
  if (!s)
    return gli_fail(error, GLINT_E_MEMORY, "out of memory copying the scene");
  *s = *src;
  /* Bitwise & so that every call runs and replaces its pointer (with a
   * copy or NULL): none of src's arrays may be left for destroy to free. */
  int ok =
      copy_array((void **)&s->lights, src->lights, src->light_count,
                 sizeof *s->lights, &s->light_cap) &
      copy_array((void **)&s->materials, src->materials, src->material_count,
                 sizeof *s->materials, &s->material_cap) &
      copy_array((void **)&s->objects, src->objects, src->object_count,
                 sizeof *s->objects, &s->object_cap) &
      copy_array((void **)&s->spheres, src->spheres, src->sphere_count,
                 sizeof *s->spheres, &s->sphere_cap) &
      copy_array((void **)&s->planes, src->planes, src->plane_count,
                 sizeof *s->planes, &s->plane_cap) &
      copy_array((void **)&s->triangles, src->triangles, src->triangle_count,
                 sizeof *s->triangles, &s->triangle_cap) &
      copy_array((void **)&s->tri_normals, src->tri_normals,
                 src->tri_normal_count, sizeof *s->tri_normals,
                 &s->tri_normal_cap) &
      copy_array((void **)&s->cones, src->cones, src->cone_count,
                 sizeof *s->cones, &s->cone_cap) &
      gli_animation_copy(&s->animation, &src->animation);
  if (!ok) {
    glint_scene_destroy(s);
    return gli_fail(error, GLINT_E_MEMORY, "out of memory copying the scene");
  }
  *out = s;
  return GLINT_OK;
}
