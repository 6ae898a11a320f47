/* Tests that read ../shared (the SPD scenes, the meshes) say so when it is
 * missing and exit with ctest's SKIPPED code rather than pass silently.
 *
 * A test file that mixes such tests with others names the former *_shared
 * and runs through glint_run_tests: ctest runs the file twice, as NAME (the
 * tests that need nothing) and NAME_shared (--shared: only the *_shared ones,
 * SKIPPED as a whole when the folder is missing), so a missing folder never
 * hides the tests that could run. */
#ifndef GLINT_TEST_SHARED_H
#define GLINT_TEST_SHARED_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

/* Runs the tests named *_shared with --shared, the others without; setup
 * and teardown are the group's (or NULL). */
#define glint_run_tests(tests, argc, argv, setup, teardown)                    \
  glint_run_tests_((tests), sizeof(tests) / sizeof *(tests), (argc), (argv),   \
                   (setup), (teardown))

static inline int glint_run_tests_(const struct CMUnitTest *tests, size_t n,
                                   int argc, char **argv,
                                   CMFixtureFunction setup,
                                   CMFixtureFunction teardown) {
  int shared = argc > 1 && strcmp(argv[1], "--shared") == 0;
  if (shared) {
    shared_path("");
    cmocka_set_test_filter("*_shared");
  } else {
    cmocka_set_skip_filter("*_shared");
  }
  return _cmocka_run_group_tests(shared ? "needing ../shared" : "own", tests, n,
                                 setup, teardown);
}

#endif
