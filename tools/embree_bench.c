/* glint-embree-bench: Embree 3's rtcIntersect16 on exactly the primary rays
 * glint's trace-primary benchmark casts, for a side-by-side comparison
 * (glint bench --meshes runs it). Optional: built only when Debian's
 * libembree-dev is installed.
 *
 *   glint-embree-bench MESH FROM AT UP FOV WIDTH HEIGHT RUNS
 *
 * The mesh is loaded with glint's own reader and the rays are made by
 * glint's camera (render/camera.h, float), one per pixel centre, in 4x4
 * packets like glint's AVX-512 beams. Prints the median Mrays/s of RUNS
 * passes over the frame, one thread, BVH build excluded, and the hit count
 * (which must equal glint's). */
#define GLINT_REAL_FLOAT
#include "glint.h"
#include "render/camera.h"
#include "scene/scene.h"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int parse3(const char *s, glint_vec3 *v) {
  return sscanf(s, "%lf,%lf,%lf", &v->x, &v->y, &v->z) == 3 ? 0 : -1;
}

static int cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  if (argc != 9) {
    fprintf(stderr, "usage: glint-embree-bench MESH FROM AT UP FOV WIDTH "
                    "HEIGHT RUNS (vectors as x,y,z)\n");
    return 2;
  }
  glint_camera cam;
  int w = atoi(argv[6]), h = atoi(argv[7]), runs = atoi(argv[8]);
  cam.fov_x_degrees = atof(argv[5]);
  if (parse3(argv[2], &cam.from) || parse3(argv[3], &cam.at) ||
      parse3(argv[4], &cam.up) || w < 4 || h < 4 || runs < 1 || runs > 100) {
    fprintf(stderr, "glint-embree-bench: bad arguments\n");
    return 2;
  }
  glint_scene *scene;
  glint_error err;
  glint_material m;
  uint32_t mat;
  glint_material_default(&m);
  if (glint_scene_create(&scene, &err) ||
      glint_scene_add_material(scene, &m, &mat, &err) ||
      glint_scene_add_mesh_file(scene, argv[1], 1, (glint_vec3){0, 0, 0}, mat,
                                &err)) {
    fprintf(stderr, "glint-embree-bench: %s\n", err.message);
    return 2;
  }

  /* Embree asks for flush-to-zero and denormals-are-zero (as glint's
   * render threads set them): without them it crawls. */
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  RTCDevice device = rtcNewDevice(NULL);
  RTCScene rs = rtcNewScene(device);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  size_t n = scene->triangle_count;
  float *vb =
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                              RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n);
  unsigned *ib =
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), n);
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      glint_vec3 v = scene->triangles[i].v[k];
      vb[9 * i + 3 * k + 0] = (float)v.x;
      vb[9 * i + 3 * k + 1] = (float)v.y;
      vb[9 * i + 3 * k + 2] = (float)v.z;
      ib[3 * i + k] = (unsigned)(3 * i + (size_t)k);
    }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(rs, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(rs);

  camera c;
  camera_init(&c, &cam, w, h);
  float tnear = (float)gli_scene_epsilon(scene); /* glint's, for the
                                                     same hits */
  double *times = malloc(sizeof *times * (size_t)runs);
  unsigned long long hits = 0;
  for (int r = 0; r < runs; r++) {
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    hits = 0;
    double t0 = now();
    for (int by = 0; by < h; by += 4)
      for (int bx = 0; bx < w; bx += 4) {
        struct RTCRayHit16 rh __attribute__((aligned(64)));
        int valid[16] __attribute__((aligned(64)));
        for (int i = 0; i < 16; i++) {
          int x = bx + i % 4, y = by + i / 4;
          valid[i] = x < w && y < h ? -1 : 0;
          vec3 d = camera_dir(&c, (float)x + 0.5f, (float)y + 0.5f);
          rh.ray.org_x[i] = c.from.x;
          rh.ray.org_y[i] = c.from.y;
          rh.ray.org_z[i] = c.from.z;
          rh.ray.dir_x[i] = d.x;
          rh.ray.dir_y[i] = d.y;
          rh.ray.dir_z[i] = d.z;
          rh.ray.tnear[i] = tnear;
          rh.ray.tfar[i] = FLT_MAX;
          rh.ray.time[i] = 0;
          rh.ray.mask[i] = ~0u;
          rh.ray.id[i] = (unsigned)i;
          rh.ray.flags[i] = 0;
          rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, rs, &ctx, &rh);
        for (int i = 0; i < 16; i++)
          hits += valid[i] && rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
      }
    times[r] = now() - t0;
  }
  qsort(times, (size_t)runs, sizeof *times, cmp);
  double med = runs % 2 ? times[runs / 2]
                        : 0.5 * (times[runs / 2 - 1] + times[runs / 2]);
  printf(
      "embree %d.%d.%d rtcIntersect16: %.3f Mrays/s, %.6f s, %llu hits, "
      "native ray16 %s\n",
      RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH,
      (double)w * h / med / 1e6, med, hits,
      rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)
          ? "yes"
          : "no");
  free(times);
  rtcReleaseScene(rs);
  rtcReleaseDevice(device);
  glint_scene_destroy(scene);
  return 0;
}
