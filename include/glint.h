/*
 * glint — a fast Whitted-style CPU ray tracer.
 *
 * This is the library's only public header. Every object is behind an opaque
 * handle with a `glint_` prefix; every fallible call returns a glint_status
 * and, when the caller passes a glint_error, a readable message saying what
 * went wrong (naming the file and line for scene files). The library keeps no
 * global mutable state: two scenes rendered on two threads never interfere.
 * A NULL where a pointer is required is refused like any bad argument
 * (GLINT_E_ARGUMENT, "FUNCTION: ARGUMENT is NULL"); the functions that
 * cannot fail answer it with nothing (0, NULL, an empty glint_scene_info),
 * and the destroy functions accept it. Where a pointer may be NULL, its
 * function says so.
 *
 * The renderer implements the specification distilled from J. Kučera,
 * "Ray-tracing using SSE" (FIT BUT Brno, 2010): the extended Phong (Whitted)
 * model with shadows, reflection, refraction and Beer's law.
 */
#ifndef GLINT_H
#define GLINT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The library is built with hidden symbols: what this header declares is
 * all it exports. */
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

#define GLINT_VERSION_MAJOR 0
#define GLINT_VERSION_MINOR 5
#define GLINT_VERSION_PATCH 0

/* "0.5.0": the version of the library actually linked. */
const char *glint_version(void);

/* ------------------------------------------------------------------------ */
/* Errors                                                                   */
/* ------------------------------------------------------------------------ */

typedef enum glint_status {
  GLINT_OK = 0,
  GLINT_E_ARGUMENT,    /* a parameter is out of range or unknown */
  GLINT_E_UNSUPPORTED, /* this CPU or build lacks what was asked for */
  GLINT_E_IO,          /* a file could not be opened, read or written */
  GLINT_E_PARSE,       /* a scene or mesh file is malformed */
  GLINT_E_MEMORY,      /* an allocation failed */
  GLINT_E_CANCELLED    /* the progress callback asked to stop */
} glint_status;

/* Filled by a failing call when the caller passes one; never required. The
 * message is one line naming the file, line and problem where there is
 * one (control characters it quotes shown as '?'; a message too long for
 * the buffer keeps its start and its end). */
typedef struct glint_error {
  glint_status status;
  char message[1024];
} glint_error;

/* "argument", "unsupported", "io", "parse", "memory", "cancelled", "ok". */
const char *glint_status_name(glint_status status);

/* ------------------------------------------------------------------------ */
/* Scenes                                                                   */
/* ------------------------------------------------------------------------ */

typedef struct glint_scene glint_scene;

typedef struct glint_vec3 {
  double x, y, z;
} glint_vec3;

/* A pinhole camera (docs/specification.md §2): from, at, up and the horizontal
 * field of view. */
typedef struct glint_camera {
  glint_vec3 from, at, up;
  double fov_x_degrees;
} glint_camera;

typedef enum glint_texture {
  GLINT_TEXTURE_NONE = 0,
  /* A checkerboard on the plane through the two world axes least aligned with
   * the surface normal (x and z for a floor): `odd` where
   * floor(a/size) + floor(b/size) is odd, `even` elsewhere. */
  GLINT_TEXTURE_CHECKER_PLANAR,
  /* A 3-D checkerboard in object-local coordinates (a sphere's centre is the
   * origin): `odd` where floor(x/size) + floor(y/size) + floor(z/size) is odd.
   */
  GLINT_TEXTURE_CHECKER_SOLID
} glint_texture;

/* The material of docs/specification.md §4. Colours are linear RGB. */
typedef struct glint_material {
  glint_vec3 color; /* C, when untextured */
  glint_texture texture;
  glint_vec3 checker_odd, checker_even;
  double checker_size;  /* edge of one checker cell, GLINT_MIN_CHECKER..
                         * GLINT_MAX_COORDINATE */
  double ka, kd, ks, h; /* ambient, diffuse, highlight and its exponent */
  double kr, kt, ior;   /* reflection, transmission, index of refraction */
  glint_vec3 absorb;    /* Beer's law absorbance per unit length, per channel */
} glint_material;

/* White opaque matte: C = 1, ka = 0.1, kd = 0.9, h = 1, ior = 1, no
 * texture (a checker, if one is set, of size 1, odd squares white and even
 * ones black); everything else 0. */
void glint_material_default(glint_material *material);

/* An empty scene: the default camera (from 0,0,10 at the origin, fov 60),
 * 640x480, black background, white ambient light, no lights. */
glint_status glint_scene_create(glint_scene **scene, glint_error *error);
void glint_scene_destroy(glint_scene *scene);

/* The thesis's scenes (docs/specification.md §8): "whitted", "giza",
 * "billiard", "phong". */
size_t glint_builtin_scene_count(void);
const char *glint_builtin_scene_name(size_t index);
glint_status glint_scene_builtin(const char *name, glint_scene **scene,
                                 glint_error *error);

/* Loads a scene file, by extension: .nff (Eric Haines's Neutral File Format)
 * or .json (glint's own format), either optionally gzip-compressed (.gz).
 * Errors name the file and line (or JSON path). Built-in scenes are not
 * files: glint_scene_builtin loads them. */
glint_status glint_scene_load(const char *path, glint_scene **scene,
                              glint_error *error);
/* The same from memory: `size` bytes of a scene file's text (not
 * compressed), read as the format of `name`'s extension. `name` stands for
 * the file in messages, and a JSON scene's mesh files are found relative to
 * its folder. */
glint_status glint_scene_load_memory(const void *data, size_t size,
                                     const char *name, glint_scene **scene,
                                     glint_error *error);

/* A scene file and every file it refers to (a JSON scene's meshes), read
 * once into one block of bytes: another process loads the very same scene
 * from it without reading a file (glint-mpi's rank 0 packs, and broadcasts
 * the block to the other ranks). The block holds each file's name and its
 * bytes (gzip undone); it is for glint_scene_load_packed of the same glint
 * version, not a file format. Free it with glint_free. Errors are those of
 * glint_scene_load. */
glint_status glint_scene_pack(const char *path, void **packed, size_t *size,
                              glint_error *error);
/* The scene of a glint_scene_pack block; errors name the packed files as
 * glint_scene_load names the files, and a damaged block (a CRC-32 covers
 * every byte of it) is GLINT_E_PARSE. */
glint_status glint_scene_load_packed(const void *packed, size_t size,
                                     glint_scene **scene, glint_error *error);
/* Frees what glint allocated for the caller (a packed scene). */
void glint_free(void *memory);

glint_status glint_scene_set_camera(glint_scene *scene,
                                    const glint_camera *camera,
                                    glint_error *error);
/* Whether glint renders from `camera`: the checks glint_scene_set_camera
 * and a frame's own camera (glint_frame_settings) make. An application
 * that moves its camera frame by frame keeps the last one that passes (a
 * camera dollied far out and back in can round from and at into one
 * point, or its view onto up). */
glint_status glint_camera_check(const glint_camera *camera, glint_error *error);
glint_status glint_scene_set_resolution(glint_scene *scene, int width,
                                        int height, glint_error *error);
glint_status glint_scene_set_background(glint_scene *scene, glint_vec3 color,
                                        glint_error *error);
glint_status glint_scene_set_ambient(glint_scene *scene, glint_vec3 color,
                                     glint_error *error);
glint_status glint_scene_add_light(glint_scene *scene, glint_vec3 position,
                                   glint_vec3 color, glint_error *error);

/* Materials are referred to by the index this returns in *material_id
 * (which may be NULL: the n-th material added, from 0, is material n). */
glint_status glint_scene_add_material(glint_scene *scene,
                                      const glint_material *material,
                                      uint32_t *material_id,
                                      glint_error *error);

/* Primitives. Each call adds one object; beams split per object
 * (docs/specification.md §6). */
glint_status glint_scene_add_sphere(glint_scene *scene, glint_vec3 center,
                                    double radius, uint32_t material_id,
                                    glint_error *error);
/* The plane through `point` with normal `normal` (need not be unit length). */
glint_status glint_scene_add_plane(glint_scene *scene, glint_vec3 normal,
                                   glint_vec3 point, uint32_t material_id,
                                   glint_error *error);
/* Front side: a, b, c counter-clockwise. Triangles are visible from both
 * sides; the side matters for refraction (entering or leaving). */
glint_status glint_scene_add_triangle(glint_scene *scene, glint_vec3 a,
                                      glint_vec3 b, glint_vec3 c,
                                      uint32_t material_id, glint_error *error);
/* An open cylinder or cone (no end caps) from `base` to `apex`. */
glint_status glint_scene_add_cone(glint_scene *scene, glint_vec3 base,
                                  double base_radius, glint_vec3 apex,
                                  double apex_radius, uint32_t material_id,
                                  glint_error *error);

/* A triangle mesh as one object. `normals` (per vertex, may be NULL) gives
 * smooth shading by interpolation. Indices are 3 per triangle. `positions`
 * and `indices` may be NULL only where their counts are 0. */
typedef struct glint_mesh {
  const glint_vec3 *positions;
  const glint_vec3 *normals;
  size_t vertex_count;
  const uint32_t *indices;
  size_t triangle_count;
} glint_mesh;
glint_status glint_scene_add_mesh(glint_scene *scene, const glint_mesh *mesh,
                                  uint32_t material_id, glint_error *error);

/* Loads an OBJ or PLY file (optionally .gz-compressed) as one mesh object,
 * scaled by `scale` and then moved by `translate`. */
glint_status glint_scene_add_mesh_file(glint_scene *scene, const char *path,
                                       double scale, glint_vec3 translate,
                                       uint32_t material_id,
                                       glint_error *error);

/* What a scene holds. */
typedef struct glint_scene_info {
  glint_camera camera;
  int width, height; /* the scene's own resolution */
  glint_vec3 background, ambient;
  size_t lights, materials, objects;
  size_t spheres, planes, triangles, cones;
  /* Bounds of the spheres, triangles and cones (not planes); min > max when
   * there are none. */
  glint_vec3 bounds_min, bounds_max;
} glint_scene_info;
void glint_scene_get_info(const glint_scene *scene, glint_scene_info *info);
/* Hits nearer than *epsilon to where a ray starts are not seen, so that
 * secondary rays leave their own surface: 1e-4 times the largest
 * coordinate magnitude of the camera and the bounded primitives
 * (docs/specification.md, section 3). *smallest is the size of the
 * smallest bounded object: a sphere's radius, a cone's larger radius or its
 * height where that is less, a
 * triangle object's longest bounding-box side (infinity when there is none;
 * objects of no extent are left out). One far or huge object makes epsilon
 * large for all the others: those not many times larger than it may be
 * missing or wrong. Either pointer may be NULL; a NULL scene gives 0. */
void glint_scene_get_scale(const glint_scene *scene, double *epsilon,
                           double *smallest);

/* ---- Animation (docs/scene-format.md, "animation") ---------------------- */

/* Frames first_frame..last_frame at fps frames a second: frame f shows the
 * scene at time (f - first_frame) / fps seconds. Frame numbers are
 * 0..GLINT_MAX_FRAME (eight digits in a file name), fps GLINT_MIN_FPS..
 * GLINT_MAX_FPS (so that every frame's time is finite: at 5e-324 frames
 * a second, frame 1 was at an infinite time). */
#define GLINT_MAX_FRAME 99999999
#define GLINT_MIN_FPS 1e-6
#define GLINT_MAX_FPS 1e6
typedef struct glint_animation {
  double fps;
  int first_frame, last_frame;
} glint_animation;

glint_status glint_scene_set_animation(glint_scene *scene,
                                       const glint_animation *animation,
                                       glint_error *error);
/* 1 and *animation filled when the scene has an animation, else 0. */
int glint_scene_get_animation(const glint_scene *scene,
                              glint_animation *animation);

typedef enum glint_interpolation {
  GLINT_INTERPOLATE_LINEAR = 0,
  /* A Catmull-Rom spline through the keys: tangents from the neighbouring
   * keys (one-sided at the ends), scaled to the keys' times. */
  GLINT_INTERPOLATE_CATMULL_ROM
} glint_interpolation;

typedef struct glint_camera_key {
  double time; /* seconds */
  glint_camera camera;
} glint_camera_key;

/* The camera through keyframes: at least one, times increasing; before the
 * first key and after the last the camera stays there. from, at, up and
 * fov are interpolated each (up need not stay unit length). */
glint_status glint_scene_set_camera_keys(glint_scene *scene,
                                         const glint_camera_key *keys,
                                         size_t count,
                                         glint_interpolation interpolation,
                                         glint_error *error);
/* The camera circling `center`, looking at it from `radius` away and
 * `height` above, starting on the +z side and turning `degrees` (positive:
 * counter-clockwise seen from above) over the animation's frames, evenly,
 * so that a 360-degree orbit loops; up is +y and the fov the scene camera's.
 * degrees, like the coordinates, within +-GLINT_MAX_COORDINATE. Needs the
 * scene's animation (glint_scene_set_animation, called first:
 * without one the orbit is refused). */
glint_status glint_scene_set_camera_orbit(glint_scene *scene, glint_vec3 center,
                                          double radius, double height,
                                          double degrees, glint_error *error);
/* A rigid motion with a uniform scale: p -> translate + pivot +
 * scale * R (p - pivot), R turning by rotate.x degrees about x, then
 * rotate.y about y, then rotate.z about z (right-handed). Spheres and
 * cones keep their shape (their radii scale); solid textures move with
 * their object but do not turn with it. */
typedef struct glint_transform {
  glint_vec3 translate, rotate, pivot;
  double scale;
} glint_transform;
/* No motion: everything 0, scale 1. */
void glint_transform_identity(glint_transform *transform);

typedef struct glint_transform_key {
  double time; /* seconds */
  glint_transform transform;
} glint_transform_key;

/* Moves object `object` (0 for the first added; glint_scene_info.objects
 * counts them) through keyed transforms, interpolated component by
 * component (translate, rotate, scale, pivot) as camera keys are; one key
 * is a still transform. glint_scene_at_time applies them. Catmull-Rom may
 * overshoot between valid keys (a scale of 1, 0.01 and 3 dips below 0):
 * glint_scene_at_time and glint_world_commit_at then fail at those times
 * only, naming the object, the time and the value (glint render --frames
 * checks every frame's time before it writes one). */
glint_status glint_scene_set_object_motion(glint_scene *scene, uint32_t object,
                                           const glint_transform_key *keys,
                                           size_t count,
                                           glint_interpolation interpolation,
                                           glint_error *error);
/* Whether any object has a motion (a frame then needs its own world). */
int glint_scene_has_motion(const glint_scene *scene);
/* A new, still scene: `scene` at `time` seconds, each moving object where
 * its transform puts it and the camera that of glint_scene_camera_at. */
glint_status glint_scene_at_time(const glint_scene *scene, double time,
                                 glint_scene **still, glint_error *error);

/* The camera at `time` seconds: from the keys or the orbit when the scene
 * has them, else the scene's camera. Fails when the interpolated camera is
 * degenerate (from at at, up along the view). */
glint_status glint_scene_camera_at(const glint_scene *scene, double time,
                                   glint_camera *camera, glint_error *error);

/* ------------------------------------------------------------------------ */
/* Images                                                                   */
/* ------------------------------------------------------------------------ */

/* An 8-bit RGB image, rows top to bottom. */
typedef struct glint_image glint_image;

glint_status glint_image_create(int width, int height, glint_image **image,
                                glint_error *error);
void glint_image_destroy(glint_image *image);
int glint_image_width(const glint_image *image);
int glint_image_height(const glint_image *image);
/* width*height*3 bytes, R G B, top row first. */
uint8_t *glint_image_pixels(glint_image *image);
const uint8_t *glint_image_pixels_const(const glint_image *image);

typedef enum glint_image_format {
  GLINT_FORMAT_UNKNOWN = 0,
  GLINT_FORMAT_PNG,
  GLINT_FORMAT_BMP, /* 24-bit, the thesis's output */
  GLINT_FORMAT_PPM  /* binary P6 */
} glint_image_format;

/* By the extension (.png, .bmp, .ppm; case-insensitive). */
glint_image_format glint_image_format_from_path(const char *path);

/* Checks that `path` has a known extension and that its folder accepts a new
 * file, without leaving anything behind. Call it before a long render. */
glint_status glint_image_check_writable(const char *path, glint_error *error);
/* The file that writing an image or film to `path` replaces: glint's
 * writers write through a symbolic link to the file it names (as a
 * shell's > does, the link staying a link), so two names can lead to one
 * file. `path` itself where it is no link; else where its links lead
 * (realpath(3) where that exists, else the name the last link gives). A
 * string to free with glint_free; NULL out of memory or for a loop of
 * links. */
char *glint_output_file(const char *path);

/* PNG compression: GLINT_PNG_FAST (the default) writes several times faster
 * than zlib's default at a size 10-90% larger (run-length matches on the
 * "sub" filter, chosen by measurement); GLINT_PNG_SMALLEST spends about 10x
 * longer for the smallest file (level 9, every filter). PNGs carry a gAMA
 * chunk for the gamma the image was encoded with (1 unless it came from
 * glint_render or glint_film_to_image with another). */
typedef enum glint_png_compression {
  GLINT_PNG_FAST = 0,
  GLINT_PNG_SMALLEST
} glint_png_compression;

/* Writes atomically, in the format of the extension: into a temporary file
 * beside `path`, then renamed over it. A failure leaves any existing file
 * untouched and no partial file. Where `path` is a symbolic link, the file
 * it names is written (created, if the link dangles) and the link stays, as
 * a shell's > does; only a regular file the caller may write is replaced.
 * Every file glint writes (films, image writers) is written so. */
glint_status glint_image_write_with(const glint_image *image, const char *path,
                                    glint_png_compression compression,
                                    glint_error *error);
glint_status glint_image_write(const glint_image *image, const char *path,
                               glint_error *error);
/* Encodes onto an open stream (standard output, a pipe) in `format`. There
 * is nothing to rename here: a failure midway leaves what was written. */
glint_status glint_image_write_stream(const glint_image *image, FILE *stream,
                                      glint_image_format format,
                                      glint_png_compression compression,
                                      glint_error *error);
/* Reads a PNG, BMP or PPM (by the extension) as 8-bit RGB: a grey or palette
 * PNG expanded, alpha dropped; 16-bit PNG samples and PPM maxvals other
 * than 255 are refused (GLINT_E_PARSE), as are palette indices past the
 * palette. */
glint_status glint_image_read(const char *path, glint_image **image,
                              glint_error *error);
/* An image file's width and height from its header alone, checked as
 * glint_image_read checks it (the pixels are not read: a damaged or short
 * body is found by glint_image_read). */
glint_status glint_image_read_size(const char *path, int *width, int *height,
                                   glint_error *error);

/* Peak signal-to-noise ratio in dB over the R, G and B channels (a read
 * image holds no other: glint_image_read drops alpha); INFINITY when equal,
 * a negative value when the sizes differ. */
double glint_image_psnr(const glint_image *a, const glint_image *b);

/* ------------------------------------------------------------------------ */
/* Rendering                                                                */
/* ------------------------------------------------------------------------ */

typedef enum glint_backend {
  GLINT_BACKEND_AUTO = 0,      /* the fastest for the scene: see _choose */
  GLINT_BACKEND_SCALAR_FLOAT,  /* one ray at a time, float: the reference */
  GLINT_BACKEND_SCALAR_DOUBLE, /* one ray at a time, double */
  GLINT_BACKEND_SSE,           /* 4-wide beams (docs/specification.md §6) */
  GLINT_BACKEND_AVX2,          /* 8-wide beams */
  GLINT_BACKEND_AVX512,        /* 16-wide beams */
  GLINT_BACKEND_STREAM,        /* ray streams, widest ISA */
  GLINT_BACKEND_STREAM_SSE,
  GLINT_BACKEND_STREAM_AVX2,
  GLINT_BACKEND_STREAM_AVX512,
  GLINT_BACKEND_COUNT
} glint_backend;

const char *glint_backend_name(glint_backend backend);
glint_status glint_backend_parse(const char *name, glint_backend *backend,
                                 glint_error *error);
/* Whether this CPU (and this build) can run it: for AUTO, some backend;
 * for STREAM, some stream backend (where there is none, rendering with
 * STREAM is refused, though glint_backend_resolve names scalar-float). */
int glint_backend_supported(glint_backend backend);
/* AUTO and STREAM to the concrete backend they stand for on this CPU,
 * without a scene: AUTO is the widest beams. A concrete backend, or a value
 * outside the enumeration, comes back as it is (glint_backend_supported
 * says 0 for the latter, and rendering with it fails). */
glint_backend glint_backend_resolve(glint_backend backend);
/* Lanes per packet: 1 for scalar backends. */
int glint_backend_width(glint_backend backend);

/* pow and exp in the SIMD backends (docs/specification.md §7). Scalar backends
 * use libm. */
typedef enum glint_math {
  GLINT_MATH_MINIMAX = 0, /* Remez minimax polynomials: the default */
  GLINT_MATH_FAST,        /* IEEE-754 bit manipulation: fast, coarse */
  GLINT_MATH_TAYLOR,      /* Taylor polynomials of lower degree */
  GLINT_MATH_EXACT,       /* libm, lane by lane: the reference */
  GLINT_MATH_COUNT
} glint_math;
const char *glint_math_name(glint_math math);
glint_status glint_math_parse(const char *name, glint_math *math,
                              glint_error *error);

/* The acceleration structure and how rays walk it. The BVH is built by the
 * binned surface area heuristic and kept twice: binary, for packets, and
 * collapsed to eight children a node, for single rays. */
typedef enum glint_accel {
  /* Packets walk the binary tree together and, where few of their lanes
   * remain in a subtree, hand it to those lanes one at a time through the
   * wide tree (hybrid traversal); the scalar backends walk the binary
   * tree. The default. */
  GLINT_ACCEL_BVH = 0,
  GLINT_ACCEL_NONE, /* every ray against every object: the thesis */
  GLINT_ACCEL_BVH2, /* the binary tree only: packets never split */
  /* Every ray alone through the wide tree: the scalar and beam backends
   * (the stream backends walk the binary tree, as with BVH2). */
  GLINT_ACCEL_BVH8,
  GLINT_ACCEL_COUNT
} glint_accel;
const char *glint_accel_name(glint_accel accel);
glint_status glint_accel_parse(const char *name, glint_accel *accel,
                               glint_error *error);

/* Documented limits: anything beyond is rejected with GLINT_E_ARGUMENT. */
#define GLINT_MAX_DEPTH 64
#define GLINT_MAX_SPP 4096
#define GLINT_MAX_DIMENSION 16384
#define GLINT_MAX_THREADS 1024
/* The largest magnitude of a scene's coordinates and sizes (positions,
 * radii, vertices, the camera, lights; also after an animation's
 * transforms): single precision, in which most backends trace, squares
 * distances and multiplies them, and 1e15 keeps every such product far
 * inside its range (3.4e38). A scene beyond it is refused, not rendered
 * black. */
#define GLINT_MAX_COORDINATE 1e15
/* The finest checker cell (glint_material.checker_size): finer ones are
 * below a single-precision coordinate's resolution, and backends tracing
 * in float and in double would colour a point differently. */
#define GLINT_MIN_CHECKER 1e-6
/* The largest colour component (lights, materials, background, ambient,
 * absorbance) and material coefficient (ka, kd, ks, kr, kt) and index of
 * refraction: 1e39 is infinite in single precision, and an infinite light
 * times a zero weight is NaN, which backends met in different places. */
#define GLINT_MAX_COLOR 1e6
/* The gammas an 8-bit image may be encoded with (1: linear; PNG records
 * 1/gamma in 1/100000ths, which needs at least 1e-5). */
#define GLINT_MIN_GAMMA 0.01
#define GLINT_MAX_GAMMA 100.0

/* Called after each finished tile with the fraction done; may be called from
 * any worker thread, but never by two at once. Return non-zero to cancel. */
typedef int (*glint_progress_fn)(void *user, double fraction);

typedef struct glint_render_settings {
  int width, height; /* 0: the scene's own resolution */
  int max_depth;     /* 1 = local shading with shadows; default 5 */
  int spp; /* samples per pixel; default 5 (docs/specification.md §5) */
  glint_backend backend;
  glint_math math;
  int rcp_newton; /* 1: refine rcp by a Newton step (eq. 3.1); 0: the
                     thesis's figure 5.7 without it */
  glint_accel accel;
  /* Render only this window of the frame (pixels of the full width x
   * height image); all four 0 (the default) render it all, and a window
   * needs a width and a height of at least 1. The image returned is
   * region_width x region_height. */
  int region_x, region_y, region_width, region_height;
  int threads;  /* 0: all cores */
  double gamma; /* 1: linear output (the default); else c^(1/gamma) */
  glint_progress_fn progress;
  void *progress_user;
} glint_render_settings;

void glint_render_settings_default(glint_render_settings *settings);

/* The concrete backend that renders `scene` with `settings` (a renderer, or
 * glint_render) when asked for `backend`: AUTO picks the widest beams or the
 * widest streams from the scene's specular surfaces and the depth
 * (src/render/backend_choice.c); any other, or AUTO without a scene or
 * settings (NULL: nothing to choose by), as glint_backend_resolve. */
glint_backend glint_backend_choose(glint_backend backend,
                                   const glint_scene *scene,
                                   const glint_render_settings *settings);

#define GLINT_STATS_MAX_GENERATIONS 16

/* What one render did. Counts are exact; times are wall-clock seconds. */
typedef struct glint_stats {
  glint_backend backend; /* the concrete backend that ran */
  int width, height, spp, max_depth, threads;
  double prepare_seconds; /* scene conversion and acceleration build */
  double render_seconds;  /* tracing and shading, all tiles */
  uint64_t primary_rays, secondary_rays, shadow_rays;
  uint64_t reflected_rays, refracted_rays, total_internal_reflections;
  /* Acceleration structure: the binary BVH, and the 8-wide one collapsed
   * from it for single rays (its nodes, bytes and collapse time; 0 where
   * none was: it is collapsed where packets may hand their last rays to
   * it, 64 or more spheres and cones, or for GLINT_ACCEL_BVH8). */
  uint64_t bvh_nodes, bvh_bytes;
  double bvh_build_seconds;
  uint64_t wide_nodes, wide_bytes;
  double wide_build_seconds;
  uint64_t scene_bytes; /* prepared geometry, materials and BVH */
  /* Packet backends: beams traced, sub-beams they split into, and the
   * active lanes over all packet intersection tests (divide by
   * packet_tests * width for the lane utilisation). */
  uint64_t beams, sub_beams, packet_tests, active_lanes;
  /* Hybrid traversal (GLINT_ACCEL_BVH, BVH8): subtrees that lanes walked
   * alone through the wide BVH, and the tests (wide nodes and primitives)
   * they made. */
  uint64_t alone_walks, alone_tests;
  /* Stream backends, per generation (0 = primary rays). `generations` is
   * how many were traced, up to the depth: it can exceed
   * GLINT_STATS_MAX_GENERATIONS, whose last entries sum every generation
   * from GLINT_STATS_MAX_GENERATIONS - 1 on, so read the arrays up to the
   * smaller of the two. */
  int generations;
  uint64_t gen_rays[GLINT_STATS_MAX_GENERATIONS];
  uint64_t gen_packets[GLINT_STATS_MAX_GENERATIONS];
  uint64_t gen_active_lanes[GLINT_STATS_MAX_GENERATIONS];
  double stage_seconds[4]; /* generation, traversal, shading, compaction */
  uint64_t stream_bytes_per_thread;
} glint_stats;

/* Renders `scene` into a new image. `settings` may be NULL (the defaults,
 * glint_render_settings_default), as may `stats`. */
glint_status glint_render(const glint_scene *scene,
                          const glint_render_settings *settings,
                          glint_image **image, glint_stats *stats,
                          glint_error *error);

/* Casts the frame's primary rays (spp per pixel, the render's sample
 * pattern) and finds their nearest hits without shading: the throughput of
 * the intersection machinery alone, for comparison with Embree's
 * rtcIntersect. *hits receives how many rays hit something; stats the time
 * (render_seconds) and primary_rays. Backends, size and threads as for
 * glint_render; depth, maths and gamma change nothing, though every field
 * is checked as glint_render checks it. */
glint_status glint_trace_primary(const glint_scene *scene,
                                 const glint_render_settings *settings,
                                 uint64_t *hits, glint_stats *stats,
                                 glint_error *error);

/* Cores the renderer would use for threads = 0: the CPUs this process may
 * run on (its affinity mask), at most GLINT_MAX_THREADS. */
int glint_cpu_count(void);

/* The environment variable GLINT_ISA=none|sse|avx2|avx512 caps the
 * instruction sets glint detects (to compare them on one machine or test
 * the fallbacks); it can never add one the CPU lacks. Returns GLINT_OK when
 * it is unset or one of those values, else GLINT_E_ARGUMENT with a message
 * (an unknown value caps nothing). */
glint_status glint_isa_cap_check(glint_error *error);

/* ------------------------------------------------------------------------ */
/* Film: linear floating-point frame buffers                                */
/* ------------------------------------------------------------------------ */

/* Linear RGB as the renderer computes it, before any clamp or gamma: each
 * pixel is the average of its samples, and may exceed 1 (a highlight). It is
 * always finite: a value beyond single precision (materials near the limits
 * of GLINT_MAX_COLOR, many bounces deep) is stored as FLT_MAX, an undefined
 * one as 0. */
typedef struct glint_film glint_film;

glint_status glint_film_create(int width, int height, glint_film **film,
                               glint_error *error);
void glint_film_destroy(glint_film *film);
int glint_film_width(const glint_film *film);
int glint_film_height(const glint_film *film);
/* width*height*3 floats, R G B, top row first. */
float *glint_film_pixels(glint_film *film);
const float *glint_film_pixels_const(const glint_film *film);

/* The 8-bit conversion of docs/specification.md §4: each channel clamped to [0,
 * 1], raised to 1/gamma (gamma 1: linear), written as round(255 c). `image`
 * must have the film's size; nothing is allocated. */
glint_status glint_film_to_image(const glint_film *film, double gamma,
                                 glint_image *image, glint_error *error);

/* Writes the linear film itself, by extension: .pfm (Portable Float Map,
 * 32-bit float RGB) or .exr (OpenEXR, when this build has it). Atomic, like
 * glint_image_write. */
glint_status glint_film_write(const glint_film *film, const char *path,
                              glint_error *error);
/* As glint_image_check_writable, for .pfm and .exr. */
glint_status glint_film_check_writable(const char *path, glint_error *error);

/* ------------------------------------------------------------------------ */
/* Worlds and renderers: commit a scene once, render many frames            */
/* ------------------------------------------------------------------------ */

/* A world is a scene committed for rendering: its geometry and materials
 * converted for the precisions and instruction sets in use, and its
 * acceleration structure built. It is immutable and keeps its own copy of
 * everything: destroying or editing the glint_scene afterwards does not
 * affect it.
 *
 * Thread-safety and lifetimes:
 *  - a world may be shared by any number of renderers on any threads;
 *  - glint_world_destroy drops the caller's reference; each renderer holds
 *    its own, so a world lives until its last renderer is destroyed;
 *  - a renderer renders one frame at a time: calls on one renderer must not
 *    overlap, while different renderers (of one world or several) may render
 *    at the same time on different threads. A render or set_world call that
 *    overlaps another on the same renderer (from a second thread, or from
 *    the frame's own tile or progress callback) fails with GLINT_E_ARGUMENT
 *    and changes nothing; glint_renderer_destroy must not overlap any. */
typedef struct glint_world glint_world;

/* Converts the scene and builds its BVH (the cost of a render that does not
 * depend on the camera). The BVH of a scene of 16 384 primitives or more
 * is built on every core this process may use (glint_cpu_count), as
 * Embree's commit does (glint_render's too, whatever its settings'
 * threads), and is the same tree whatever their number. `stats`, when given,
 * receives prepare_seconds, bvh_nodes, bvh_bytes, bvh_build_seconds and
 * scene_bytes. */
glint_status glint_world_commit(const glint_scene *scene, glint_world **world,
                                glint_stats *stats, glint_error *error);
/* The world of an animated scene at `time` (glint_scene_at_time, committed
 * without a second copy). `previous`, when given, is a world of the same
 * animation (the last frame's): its BVH's tree is kept and refitted to
 * where the objects are now, instead of a new one built, when that costs
 * rays no more (objects that moved without turning); objects that turned
 * get a new tree. The image is the same either way (with the stream
 * backends, a few of a film's floats may differ in their last bit, which
 * 8-bit images do not show). */
glint_status glint_world_commit_at(const glint_scene *scene, double time,
                                   const glint_world *previous,
                                   glint_world **world, glint_stats *stats,
                                   glint_error *error);
void glint_world_destroy(glint_world *world);
/* What the committed scene holds (its camera and resolution included). */
void glint_world_get_info(const glint_world *world, glint_scene_info *info);

/* A renderer owns a pool of worker threads, started once, and their scratch
 * memory. The calling thread works as one of them when it has 1 MiB of
 * stack to spare, else a thread of the pool (8 MiB of stack) works in its
 * place: glint renders from an application's small threads too (loading a
 * scene and committing a world need under 64 KiB of stack). It is created
 * from a world and the settings that stay fixed for its life: backend, math,
 * rcp_newton, accel and threads. Its other fields
 * (size, region, depth, spp, progress) are the defaults of each frame.
 * Every field is checked as glint_render checks it, gamma included, though
 * a renderer's films are linear. `settings` may be NULL:
 * glint_render_settings_default's. */
typedef struct glint_renderer glint_renderer;

glint_status glint_renderer_create(glint_world *world,
                                   const glint_render_settings *settings,
                                   glint_renderer **renderer,
                                   glint_error *error);
void glint_renderer_destroy(glint_renderer *renderer);
/* Renders `world` from now on, keeping the threads and their memory (an
 * animation whose objects move commits a world a frame). The renderer
 * drops its reference to the previous world. */
glint_status glint_renderer_set_world(glint_renderer *renderer,
                                      glint_world *world, glint_error *error);

/* A frame (or its region) is rendered in tiles of GLINT_TILE_SIZE pixels
 * square, from the region's top-left corner. Each pixel's image is the same
 * whatever the threads; the stream backends' also depends on which pixels
 * share its tile (they accumulate a pixel's light in the order its tile's
 * rays come), so a caller that renders one image as several regions gets
 * glint_render's image byte for byte with every backend only when the
 * regions' corners lie on that grid. */
#define GLINT_TILE_SIZE 16

/* One finished tile, handed over while the frame renders: pixels
 * [x, x + width) x [y, y + height) of the frame (region coordinates are
 * frame pixels), linear RGB, already stored in the film. `pixels` points at
 * the tile's top-left pixel in the film (without a film: at the worker's
 * copy of the tile, valid during the callback); rows are `stride` floats
 * apart. */
typedef struct glint_tile {
  int x, y, width, height;
  const float *pixels;
  size_t stride;
} glint_tile;

/* Called once per finished tile, from any worker thread but never by two at
 * once (like glint_progress_fn). Return non-zero to cancel the frame. */
typedef int (*glint_tile_fn)(void *user, const glint_tile *tile);

/* What changes from frame to frame. */
typedef struct glint_frame_settings {
  /* NULL: the world's camera. A frame's own camera renders what the scene
   * with that camera would, its epsilon (docs/specification.md §3, scaled
   * by the camera's distance too) included. */
  const glint_camera *camera;
  int width, height; /* 0: the renderer's (or else the world's) */
  /* A window of the width x height frame; all four 0: the renderer's
   * (itself all of the frame by default), as glint_render_settings. */
  int region_x, region_y, region_width, region_height;
  int max_depth; /* 0: the renderer's */
  int spp;       /* 0: the renderer's */
  /* Progressive rendering: only samples [sample_first, sample_first +
   * sample_count) of the spp-sample pattern (docs/specification.md §5);
   * sample_count = 0: the rest (all from 0). The film receives the mean of
   * this call's samples (it replaces what the film held): the caller
   * accumulates passes, weighting each by its sample count, and the passes
   * over all spp samples then average to the spp-sample image (glint view
   * keeps such a sum). */
  int sample_first, sample_count;
  glint_progress_fn progress; /* NULL: the renderer's */
  void *progress_user;
  glint_tile_fn tile; /* NULL: none */
  void *tile_user;
} glint_frame_settings;

/* All zero: every value from the renderer, the world's camera. */
void glint_frame_settings_default(glint_frame_settings *frame);

/* Renders one frame into `film`, which must have the frame's (or the
 * region's) size. Nothing is converted, built, allocated or started: the
 * frame costs its rendering. (One exception: a frame deeper than any the
 * renderer has rendered grows each thread's stream buffers once, and may
 * then fail with GLINT_E_MEMORY.) A cancelled frame (GLINT_E_CANCELLED) leaves
 * the film partly written. `frame` may be NULL; `stats` may be NULL.
 * `film` may be NULL when the frame has a tile callback: the tiles then go
 * to the callback only (a glint_image_writer, another process), and no
 * frame-sized buffer is needed. */
glint_status glint_renderer_render(glint_renderer *renderer,
                                   const glint_frame_settings *frame,
                                   glint_film *film, glint_stats *stats,
                                   glint_error *error);

/* ------------------------------------------------------------------------ */
/* Image files written while a frame renders                                */
/* ------------------------------------------------------------------------ */

/* An 8-bit image file (.png, .bmp or .ppm, by the extension) filled tile by
 * tile, typically from a glint_tile_fn: each tile is converted as
 * glint_film_to_image converts (clamp, gamma, round), and a PNG or PPM is
 * encoded, on a thread of the writer's own, as soon as the rows above it are
 * complete. The file is therefore finished moments after the last tile
 * instead of an encoding's time later. It appears, atomically, only at
 * glint_image_writer_finish: a writer discarded, or one missing pixels,
 * leaves any existing file untouched and no partial one.
 *
 * Puts may come from any thread (from a tile callback, on the renderer's
 * workers); finish or discard comes once, after the last put, and frees the
 * writer. */
typedef struct glint_image_writer glint_image_writer;

/* Creates the temporary file beside `path` (failing here, before a render,
 * when the folder takes no new file) for a width x height image encoded with
 * `gamma` (1: linear; PNGs record it) and, for PNG, `compression`. */
glint_status glint_image_writer_open(const char *path, int width, int height,
                                     double gamma,
                                     glint_png_compression compression,
                                     glint_image_writer **writer,
                                     glint_error *error);
/* Converts and takes the tile's pixels. tile->x and tile->y are pixels of
 * the image: for a frame's region, subtract the region's origin. Each pixel
 * is put once. Returns an error at once when the tile or its pixels are NULL,
 * it is empty, its stride is shorter than its rows, it lies outside the
 * image, it repeats a pixel, or writing has failed (a full disk): a tile
 * callback then cancels the frame. After a refused tile the image cannot be
 * finished: later puts fail, and so does glint_image_writer_finish. A PNG or
 * PPM writer holds only the rows not yet encoded (a BMP, the whole image): a
 * put that finds 8 MiB of them held while the encoder has complete rows to
 * encode waits for it; tiles out of order never wait. */
glint_status glint_image_writer_put(glint_image_writer *writer,
                                    const glint_tile *tile, glint_error *error);
/* Waits for the encoder, then flushes, syncs and renames the file into
 * place. Fails, writing nothing, when a pixel was never put, a put was
 * refused, or writing failed. Frees the writer either way. */
glint_status glint_image_writer_finish(glint_image_writer *writer,
                                       glint_error *error);
/* Abandons the file (an existing one stays untouched) and frees the writer. */
void glint_image_writer_discard(glint_image_writer *writer);
/* The temporary file beside the path that the writer fills until
 * glint_image_writer_finish renames it into place. For a program that may
 * have to leave at once, from a signal, without the writer: removing this
 * file is then all that is left to do. NULL for a writer into memory, and
 * where the temporary file has no name until it is finished (Linux's
 * O_TMPFILE, used wherever the folder's file system has it): then a process
 * ended by any means, SIGKILL included, leaves nothing behind. */
const char *glint_image_writer_temp_path(const glint_image_writer *writer);

/* The same encoder into memory, for a file to be written elsewhere (by
 * another process: glint-mpi's ranks encode their frames, rank 0 writes
 * them): the bytes are those glint_image_writer_open's file would hold. A
 * writer opened so ends with glint_image_writer_finish_memory (or discard),
 * which hands over the encoded file; free it with glint_free. */
glint_status glint_image_writer_open_memory(glint_image_format format,
                                            int width, int height, double gamma,
                                            glint_png_compression compression,
                                            glint_image_writer **writer,
                                            glint_error *error);
glint_status glint_image_writer_finish_memory(glint_image_writer *writer,
                                              void **bytes, size_t *size,
                                              glint_error *error);
/* Writes an encoded image file's `size` bytes to `path`, atomically as
 * glint_image_write does (path's extension must be .png, .bmp or .ppm).
 * Bytes that do not begin as a file of that format does (its signature)
 * are refused, and nothing is written. */
glint_status glint_image_write_encoded(const char *path, const void *bytes,
                                       size_t size, glint_error *error);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif

#ifdef __cplusplus
}
#endif

#endif /* GLINT_H */
