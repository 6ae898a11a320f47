/* The thesis's four scenes, exactly as docs/specification.md §8 gives them. */
#include "core/error.h"
#include "scene/scene.h"

#include <math.h>
#include <string.h>

typedef glint_vec3 V;

/* docs/specification.md §8: "Glass" with a per-scene absorbance. */
static glint_material glass(V absorb) {
  glint_material m;
  glint_material_default(&m);
  m.color = (V){1, 1, 1};
  m.ka = 0.01;
  m.kd = 0.01;
  m.ks = 0.9;
  m.h = 80;
  m.kr = 0.1;
  m.kt = 0.9;
  m.ior = 1.5;
  m.absorb = absorb;
  return m;
}

static glint_material matte(V color) {
  glint_material m;
  glint_material_default(&m);
  m.color = color;
  m.ka = 0.1;
  m.kd = 0.9;
  return m;
}

static glint_material checkered(glint_texture texture, V odd, V even,
                                double size) {
  glint_material m = matte(odd);
  m.texture = texture;
  m.checker_odd = odd;
  m.checker_even = even;
  m.checker_size = size;
  return m;
}

/* Shared header of all thesis scenes: camera, one white light, white
 * ambient, 640x480. */
static glint_status setup(glint_scene *s, V from, V at, double fov, V bg,
                          V light, glint_error *e) {
  glint_camera cam = {from, at, {0, 1, 0}, fov};
  glint_status st;
  if ((st = glint_scene_set_camera(s, &cam, e)) ||
      (st = glint_scene_set_background(s, bg, e)) ||
      (st = glint_scene_set_ambient(s, (V){1, 1, 1}, e)) ||
      (st = glint_scene_set_resolution(s, 640, 480, e)))
    return st;
  return glint_scene_add_light(s, light, (V){1, 1, 1}, e);
}

static glint_status add_material(glint_scene *s, glint_material m, uint32_t *id,
                                 glint_error *e) {
  return glint_scene_add_material(s, &m, id, e);
}

/* Scene 1, "Whitted sphere" (§5.1.1). */
static glint_status build_whitted(glint_scene *s, glint_error *e) {
  glint_status st;
  uint32_t floor, sphere;
  if ((st = setup(s, (V){0, 2, 6}, (V){0, 1.25, 0}, 60, (V){0.25, 0.45, 0.85},
                  (V){-4, 8, 6}, e)) ||
      (st = add_material(s,
                         checkered(GLINT_TEXTURE_CHECKER_PLANAR, (V){1, 0, 0},
                                   (V){1, 1, 0}, 1),
                         &floor, e)) ||
      (st = add_material(s, glass((V){0.10, 0.025, 0.0}), &sphere, e)) ||
      (st = glint_scene_add_plane(s, (V){0, 1, 0}, (V){0, 0, 0}, floor, e)))
    return st;
  return glint_scene_add_sphere(s, (V){0, 1.5, 0}, 1, sphere, e);
}

static glint_status add_triangles(glint_scene *s, const double (*v)[3][3],
                                  int count, uint32_t material,
                                  glint_error *e) {
  for (int i = 0; i < count; i++) {
    glint_status st = glint_scene_add_triangle(
        s, (V){v[i][0][0], v[i][0][1], v[i][0][2]},
        (V){v[i][1][0], v[i][1][1], v[i][1][2]},
        (V){v[i][2][0], v[i][2][1], v[i][2][2]}, material, e);
    if (st)
      return st;
  }
  return GLINT_OK;
}

/* Scene 2, "Giza" (§5.1.2): a ground plane, three closed glass pyramids of
 * six triangles each and a palm tree of eight. */
static glint_status build_giza(glint_scene *s, glint_error *e) {
  static const double pyramids[18][3][3] = {
      /* P1 */
      {{-5.25, 1, -1.25}, {-1.75, 1, -1.25}, {-3.5, 3.5, -3}},
      {{-1.75, 1, -1.25}, {-1.75, 1, -4.75}, {-3.5, 3.5, -3}},
      {{-1.75, 1, -4.75}, {-5.25, 1, -4.75}, {-3.5, 3.5, -3}},
      {{-5.25, 1, -4.75}, {-5.25, 1, -1.25}, {-3.5, 3.5, -3}},
      {{-5.25, 1, -1.25}, {-1.75, 1, -4.75}, {-1.75, 1, -1.25}},
      {{-5.25, 1, -1.25}, {-5.25, 1, -4.75}, {-1.75, 1, -4.75}},
      /* P2 */
      {{-1, 1.5, -4.5}, {2, 1.5, -4.5}, {0.5, 3.7, -6}},
      {{2, 1.5, -4.5}, {2, 1.5, -7.5}, {0.5, 3.7, -6}},
      {{2, 1.5, -7.5}, {-1, 1.5, -7.5}, {0.5, 3.7, -6}},
      {{-1, 1.5, -7.5}, {-1, 1.5, -4.5}, {0.5, 3.7, -6}},
      {{-1, 1.5, -4.5}, {2, 1.5, -7.5}, {2, 1.5, -4.5}},
      {{-1, 1.5, -4.5}, {-1, 1.5, -7.5}, {2, 1.5, -7.5}},
      /* P3 */
      {{3, 1, -8}, {5, 1, -8}, {4, 2.4, -9}},
      {{5, 1, -8}, {5, 1, -10}, {4, 2.4, -9}},
      {{5, 1, -10}, {3, 1, -10}, {4, 2.4, -9}},
      {{3, 1, -10}, {3, 1, -8}, {4, 2.4, -9}},
      {{3, 1, -8}, {5, 1, -10}, {5, 1, -8}},
      {{3, 1, -8}, {3, 1, -10}, {5, 1, -10}},
  };
  static const double trunk[3][3][3] = {
      {{3.45, 0, -1}, {3.1, 0, -1.2}, {3.5, 4, -1}},
      {{3.1, 0, -1.2}, {3.1, 0, -0.8}, {3.5, 4, -1}},
      {{3.1, 0, -0.8}, {3.45, 0, -1}, {3.5, 4, -1}},
  };
  static const double leaves[5][3][3] = {
      {{3.5, 4, -1}, {5.695, 3.1, -1.153}, {5.366, 3.1, -2.166}},
      {{3.5, 4, -1}, {4.032, 3.1, -3.135}, {2.968, 3.1, -3.135}},
      {{3.5, 4, -1}, {1.634, 3.1, -2.166}, {1.305, 3.1, -1.153}},
      {{3.5, 4, -1}, {1.815, 3.1, 0.414}, {2.676, 3.1, 1.04}},
      {{3.5, 4, -1}, {4.324, 3.1, 1.04}, {5.185, 3.1, 0.414}},
  };
  glint_status st;
  uint32_t sand, glass_id, bark, leaf;
  if ((st = setup(s, (V){0, 3, 9}, (V){0, 2.2, -4}, 60, (V){0.45, 0.65, 0.95},
                  (V){-10, 20, 10}, e)) ||
      (st = add_material(s,
                         checkered(GLINT_TEXTURE_CHECKER_PLANAR,
                                   (V){0.93, 0.79, 0.50}, (V){0.80, 0.62, 0.35},
                                   2),
                         &sand, e)) ||
      (st = add_material(s, glass((V){0.0, 0.025, 0.10}), &glass_id, e)) ||
      (st = add_material(s, matte((V){0.45, 0.30, 0.15}), &bark, e)) ||
      (st = add_material(s, matte((V){0.10, 0.55, 0.10}), &leaf, e)) ||
      (st = glint_scene_add_plane(s, (V){0, 1, 0}, (V){0, 0, 0}, sand, e)) ||
      (st = add_triangles(s, pyramids, 18, glass_id, e)) ||
      (st = add_triangles(s, trunk, 3, bark, e)))
    return st;
  return add_triangles(s, leaves, 5, leaf, e);
}

/* Scene 3, "Billiard" (§5.1.3): ten unit spheres stacked into a pyramid. */
static glint_status build_billiard(glint_scene *s, glint_error *e) {
  glint_status st;
  uint32_t cloth, glass_id, checker;
  glint_material c = checkered(GLINT_TEXTURE_CHECKER_SOLID, (V){0.9, 0.9, 0.9},
                               (V){0.8, 0.1, 0.1}, 0.5);
  c.kd = 0.7;
  c.ks = 0.6;
  c.h = 40;
  c.kr = 0.3;
  if ((st = setup(s, (V){0, 5, 13}, (V){0, 3, 0}, 55, (V){0.15, 0.2, 0.35},
                  (V){-6, 12, 10}, e)) ||
      (st = add_material(s, matte((V){0.10, 0.45, 0.15}), &cloth, e)) ||
      (st = add_material(s, glass((V){0.10, 0.025, 0.0}), &glass_id, e)) ||
      (st = add_material(s, c, &checker, e)) ||
      (st = glint_scene_add_plane(s, (V){0, 1, 0}, (V){0, 0, 0}, cloth, e)))
    return st;
  const double h = sqrt(3.0);
  const struct {
    double x, y;
    int glass;
  } balls[10] = {{-3, 1, 0},       {-1, 1, 1},         {1, 1, 1},
                 {3, 1, 0},        {-2, 1 + h, 0},     {0, 1 + h, 1},
                 {2, 1 + h, 0},    {-1, 1 + 2 * h, 0}, {1, 1 + 2 * h, 0},
                 {0, 1 + 3 * h, 1}};
  for (int i = 0; i < 10; i++)
    if ((st = glint_scene_add_sphere(s, (V){balls[i].x, balls[i].y, 0}, 1,
                                     balls[i].glass ? glass_id : checker, e)))
      return st;
  return GLINT_OK;
}

/* Scene 4, "Phong" (figure 2.6, after Kurlander): 4x4 spheres, exponent by
 * column, highlight coefficient by row. */
static glint_status build_phong(glint_scene *s, glint_error *e) {
  glint_status st = setup(s, (V){0, 0, 10}, (V){0, 0, 0}, 55, (V){0, 0, 0},
                          (V){-5, 5, 10}, e);
  if (st)
    return st;
  const double xs[4] = {-2.7, -0.9, 0.9, 2.7}, ys[4] = {2.7, 0.9, -0.9, -2.7};
  const double hs[4] = {5, 20, 50, 1000}, kss[4] = {0, 0.1, 0.275, 0.45};
  for (int row = 0; row < 4; row++)
    for (int col = 0; col < 4; col++) {
      glint_material m = matte((V){0.9, 0.2, 0.2});
      m.ka = 0.1;
      m.kd = 0.6;
      m.ks = kss[row];
      m.h = hs[col];
      uint32_t id;
      if ((st = add_material(s, m, &id, e)) ||
          (st =
               glint_scene_add_sphere(s, (V){xs[col], ys[row], 0}, 0.8, id, e)))
        return st;
    }
  return GLINT_OK;
}

static const struct {
  const char *name;
  glint_status (*build)(glint_scene *, glint_error *);
} builtins[] = {{"whitted", build_whitted},
                {"giza", build_giza},
                {"billiard", build_billiard},
                {"phong", build_phong}};

#define BUILTIN_COUNT (sizeof builtins / sizeof builtins[0])

size_t glint_builtin_scene_count(void) { return BUILTIN_COUNT; }

const char *glint_builtin_scene_name(size_t i) {
  return i < BUILTIN_COUNT ? builtins[i].name : NULL;
}

glint_status glint_scene_builtin(const char *name, glint_scene **out,
                                 glint_error *e) {
  GLI_NOT_NULL(name, "name", e);
  GLI_NOT_NULL(out, "scene", e);
  for (size_t i = 0; i < BUILTIN_COUNT; i++)
    if (strcmp(name, builtins[i].name) == 0) {
      glint_scene *s;
      glint_status st = glint_scene_create(&s, e);
      if (st)
        return st;
      if ((st = builtins[i].build(s, e))) {
        glint_scene_destroy(s);
        return st;
      }
      *out = s;
      return GLINT_OK;
    }
  return gli_fail(e, GLINT_E_ARGUMENT,
                  "unknown scene '%s' (built-in scenes: whitted, giza, "
                  "billiard, phong)",
                  name);
}
