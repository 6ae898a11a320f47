/* glint view in a build without SDL2: it says what is missing. */
#include "args.h"
#include "cli.h"

int view_run(const view_options *options) {
  (void)options;
  cli_error("view: this glint was built without SDL2; install libsdl2-dev "
            "(scripts/install-deps.sh does) and build again");
  return EXIT_USAGE;
}
