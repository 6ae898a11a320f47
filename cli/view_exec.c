/* glint view: the window is the program glint-view beside glint (see
 * cli/view_cmd.c for why); this checks the arguments and runs it with
 * them. */
#include "args.h"
#include "cli.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int cmd_view(int argc, char **argv) {
  /* The help and the options' errors here, with or without glint-view
   * (glint help view said "glint-view is missing") */
  view_options options;
  int status = view_parse(argc, argv, &options);
  if (status >= 0)
    return status;
  char self[PATH_MAX], path[PATH_MAX + 16];
  ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) {
    cli_error("view: cannot find this program's folder: %s", strerror(errno));
    return EXIT_USAGE;
  }
  self[n] = '\0';
  char *slash = strrchr(self, '/');
  snprintf(path, sizeof path, "%.*s/glint-view",
           slash ? (int)(slash - self) : 0, self);
  char **args = malloc(sizeof *args * (size_t)(argc + 2));
  if (!args) {
    cli_error("out of memory");
    return 1;
  }
  args[0] = path;
  for (int i = 0; i < argc; i++)
    args[i + 1] = argv[i];
  args[argc + 1] = NULL;
  execv(path, args);
  int saved = errno;
  free(args);
  if (saved == ENOENT)
    cli_error("view: %s is missing: glint view is built when SDL2 is found "
              "(install libsdl2-dev, which scripts/install-deps.sh does, and "
              "build again)",
              path);
  else
    cli_error("view: cannot run %s: %s", path, strerror(saved));
  return EXIT_USAGE;
}
