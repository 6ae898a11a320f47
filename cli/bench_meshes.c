/* glint bench --meshes DIR: primary-ray throughput on the Stanford bunny and
 * the 200k-triangle dragon, one thread, for every backend asked for, and
 * Embree 3's rtcIntersect16 on the same rays in the same run when the
 * optional glint-embree-bench program was built (it sits next to glint).
 * Only nearest hits are found: no shading, as rtcIntersect does. */
#include "args.h"
#include "bench.h"
#include "cli.h"

#include <glint.h>

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *const meshes[] = {"bunny.obj", "dragon_vrip_res2.ply.gz"};
#define MESH_COUNT (sizeof meshes / sizeof *meshes)
#define FOV 40.0

/* The program beside the running glint, if it is there. */
static int sibling(const char *name, char *out, size_t size) {
  char self[PATH_MAX];
  ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0)
    return 0;
  self[n] = '\0';
  char *slash = strrchr(self, '/');
  if (!slash)
    return 0;
  *slash = '\0';
  if (strlen(self) + 1 + strlen(name) + 1 > size)
    return 0;
  strcpy(out, self);
  strcat(out, "/");
  strcat(out, name);
  return access(out, X_OK) == 0;
}

/* A camera that frames the mesh's bounding sphere, from the front right
 * and a little above. */
static glint_camera frame(const glint_scene_info *info) {
  glint_vec3 lo = info->bounds_min, hi = info->bounds_max;
  glint_vec3 c = {(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
  double r =
      0.5 * sqrt((hi.x - lo.x) * (hi.x - lo.x) + (hi.y - lo.y) * (hi.y - lo.y) +
                 (hi.z - lo.z) * (hi.z - lo.z));
  double dist = r / sin(FOV * 3.14159265358979323846 / 360.0);
  double d[3] = {0.35, 0.25, 1}, l = sqrt(0.35 * 0.35 + 0.25 * 0.25 + 1);
  glint_camera cam = {
      {c.x + dist * d[0] / l, c.y + dist * d[1] / l, c.z + dist * d[2] / l},
      c,
      {0, 1, 0},
      FOV};
  return cam;
}

int bench_meshes(const char *dir, const glint_render_settings *base,
                 const glint_backend *backends, int nbackends, int runs) {
  char embree[PATH_MAX];
  int have_embree = sibling("glint-embree-bench", embree, sizeof embree);
  int w = base->width ? base->width : 1024,
      h = base->height ? base->height : 1024;
  /* Both meshes must be there before anything is printed or timed. */
  for (size_t m = 0; m < MESH_COUNT; m++) {
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", dir, meshes[m]);
    if (access(path, R_OK) != 0) {
      cli_error("--meshes: %s: %s", path, strerror(errno));
      return EXIT_USAGE;
    }
  }
  printf("glint %s bench --meshes: primary rays only (nearest hits, no "
         "shading), %dx%d, 1 ray per pixel, 1 thread, median of %d runs\n",
         glint_version(), w, h, runs);
  if (!have_embree)
    printf("(glint-embree-bench was not built: install libembree-dev and "
           "rebuild to compare with Embree 3)\n");
  printf("%-26s %9s %9s %8s", "mesh (Mrays/s)", "triangles", "build ms",
         "B/tri");
  for (int b = 0; b < nbackends; b++)
    printf(" %13s", glint_backend_name(backends[b]));
  if (have_embree)
    printf(" %13s %11s", "embree", "best/embree");
  printf("\n");
  int status = 0;
  for (size_t m = 0; m < MESH_COUNT && !status; m++) {
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", dir, meshes[m]);
    glint_scene *scene = NULL;
    glint_error err;
    glint_material mat;
    uint32_t id;
    glint_material_default(&mat);
    if (glint_scene_create(&scene, &err) ||
        glint_scene_add_material(scene, &mat, &id, &err) ||
        glint_scene_add_mesh_file(scene, path, 1, (glint_vec3){0, 0, 0}, id,
                                  &err)) {
      cli_error("--meshes: %s", err.message);
      glint_scene_destroy(scene);
      return cli_exit_code(err.status);
    }
    glint_scene_info info;
    glint_scene_get_info(scene, &info);
    glint_camera cam = frame(&info);
    glint_scene_set_camera(scene, &cam, &err);

    double mrays[GLINT_BACKEND_COUNT], best = 0, build_ms = 0;
    uint64_t hits[GLINT_BACKEND_COUNT], bytes = 0;
    glint_render_settings rs = *base;
    rs.width = w;
    rs.height = h;
    rs.spp = 1;
    rs.threads = 1;
    for (int b = 0; b < nbackends && !status; b++) {
      double t[256];
      rs.backend = backends[b];
      glint_stats st;
      for (int r = 0; r < runs; r++) {
        if (glint_trace_primary(scene, &rs, &hits[b], &st, &err)) {
          cli_error("%s: %s", meshes[m], err.message);
          status = cli_exit_code(err.status);
          break;
        }
        t[r] = st.render_seconds;
      }
      mrays[b] = (double)w * h / bench_median(t, runs) / 1e6;
      best = fmax(best, mrays[b]);
      build_ms = st.bvh_build_seconds * 1e3;
      bytes = st.bvh_bytes;
    }
    if (status) {
      glint_scene_destroy(scene);
      break;
    }
    printf("%-26s %9zu %9.1f %8.1f", meshes[m], info.triangles, build_ms,
           (double)bytes / (double)info.triangles);
    for (int b = 0; b < nbackends; b++)
      printf(" %13.2f", mrays[b]);
    if (have_embree) {
      char args[5][128], out[4096];
      snprintf(args[0], sizeof args[0], "%.17g,%.17g,%.17g", cam.from.x,
               cam.from.y, cam.from.z);
      snprintf(args[1], sizeof args[1], "%.17g,%.17g,%.17g", cam.at.x, cam.at.y,
               cam.at.z);
      snprintf(args[2], sizeof args[2], "%.17g,%.17g,%.17g", cam.up.x, cam.up.y,
               cam.up.z);
      snprintf(args[3], sizeof args[3], "%d", w);
      snprintf(args[4], sizeof args[4], "%d", h);
      char fov[32], nruns[16];
      snprintf(fov, sizeof fov, "%.17g", cam.fov_x_degrees);
      snprintf(nruns, sizeof nruns, "%d", runs);
      char *argv[] = {embree, path,    args[0], args[1], args[2],
                      fov,    args[3], args[4], nruns,   NULL};
      double e = 0;
      unsigned long long ehits = 0;
      const char *p;
      if (bench_run_capture(argv, out, sizeof out) == 0 &&
          (p = strstr(out, "rtcIntersect16:")) &&
          sscanf(p, "rtcIntersect16: %lf Mrays/s, %*f s, %llu hits", &e,
                 &ehits) == 2)
        printf(" %13.2f %10.2fx", e, best / e);
      else
        printf(" %13s %11s", "failed", "-");
      printf("\n%-26s hits: glint %llu, embree %llu\n", "",
             (unsigned long long)hits[nbackends - 1], ehits);
    } else {
      printf("\n");
    }
    glint_scene_destroy(scene);
  }
  return status;
}
