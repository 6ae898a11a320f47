/* Tests that read ../shared (the SPD scenes, the meshes) say so when it is
 * missing and exit with ctest's SKIPPED code rather than pass silently. */
#ifndef GLINT_TEST_SHARED_H
#define GLINT_TEST_SHARED_H

#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

#define SKIP_EXIT 77

/* GLINT_SHARED_DIR "/" sub, or exits 77 with a message if absent. */
static inline const char *shared_path(const char *sub) {
  static char buf[4096];
  snprintf(buf, sizeof buf, "%s/%s", GLINT_SHARED_DIR, sub);
  struct stat sb;
  if (stat(buf, &sb) != 0) {
    fprintf(stderr,
            "SKIPPED: %s is missing: this test needs the shared folder "
            "(configure with -DGLINT_SHARED_DIR=...)\n",
            buf);
    exit(SKIP_EXIT);
  }
  return buf;
}

#endif
