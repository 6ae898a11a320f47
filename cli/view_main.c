/* glint-view: the window of `glint view` (which runs this program, found
 * beside itself), built when SDL2 is found. */
#include "args.h"
#include "cli.h"

#include <glint.h>

int main(int argc, char **argv) {
  cli_write_errors_not_signals();
  char why[128];
  if (cli_ensure_stack(why, sizeof why)) {
    cli_error("%s", why);
    return EXIT_MEMORY;
  }
  cli_end_on_stop_signals();
  glint_error err;
  if (glint_isa_cap_check(&err)) {
    cli_error("%s", err.message);
    return EXIT_USAGE;
  }
  view_options o;
  int status = view_parse(argc - 1, argv + 1, &o);
  if (status >= 0)
    return status;
  return view_run(&o);
}
