/* Why glint reads meshes itself (issue 4 allows assimp or "a loader of your
 * own if you measure it better"): this times glint's OBJ/PLY reader against
 * assimp's C API on the same files, median of 7 loads each, one thread.
 *
 *   build/glint-mesh-load-bench ../shared/data/bunny.obj FILE.ply ...
 *
 * glint's time includes adding the triangles to a scene; assimp's is
 * aiImportFile with aiProcess_Triangulate only (nothing is built). assimp
 * cannot read .gz files, which glint reads transparently. Built only when
 * Debian's libassimp-dev is installed. */
#include "glint.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define RUNS 7

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static int by_value(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s MESH...\n", argv[0]);
    return 2;
  }
  printf("%-32s %9s %11s %11s %7s\n", "file", "triangles", "assimp ms",
         "glint ms", "ratio");
  for (int i = 1; i < argc; i++) {
    double ta[RUNS], tg[RUNS];
    unsigned triangles = 0;
    const char *problem = NULL;
    for (int r = 0; r < RUNS && !problem; r++) {
      double t0 = now();
      const struct aiScene *s = aiImportFile(argv[i], aiProcess_Triangulate);
      ta[r] = now() - t0;
      if (!s) {
        ta[r] = 0;
      } else {
        triangles = 0;
        for (unsigned m = 0; m < s->mNumMeshes; m++)
          triangles += s->mMeshes[m]->mNumFaces;
        aiReleaseImport(s);
      }
      glint_scene *scene;
      glint_error e;
      glint_material mat;
      uint32_t id;
      if (glint_scene_create(&scene, &e)) {
        fprintf(stderr, "%s\n", e.message);
        return 1;
      }
      glint_material_default(&mat);
      glint_scene_add_material(scene, &mat, &id, &e);
      t0 = now();
      if (glint_scene_add_mesh_file(scene, argv[i], 1, (glint_vec3){0, 0, 0},
                                    id, &e)) {
        fprintf(stderr, "%s\n", e.message);
        problem = "glint failed";
      }
      tg[r] = now() - t0;
      glint_scene_destroy(scene);
    }
    if (problem)
      continue;
    qsort(ta, RUNS, sizeof *ta, by_value);
    qsort(tg, RUNS, sizeof *tg, by_value);
    const char *slash = strrchr(argv[i], '/');
    if (ta[RUNS / 2] > 0)
      printf("%-32s %9u %11.1f %11.1f %6.1fx\n", slash ? slash + 1 : argv[i],
             triangles, ta[RUNS / 2] * 1e3, tg[RUNS / 2] * 1e3,
             ta[RUNS / 2] / tg[RUNS / 2]);
    else
      printf("%-32s %9s %11s %11.1f %7s\n", slash ? slash + 1 : argv[i], "-",
             "cannot", tg[RUNS / 2] * 1e3, "-");
  }
  return 0;
}
