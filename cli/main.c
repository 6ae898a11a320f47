/* glint: the command-line driver. It uses nothing but <glint.h>. */
#include "args.h"
#include "cli.h"

#include <glint.h>

#include <stdio.h>
#include <string.h>

static void usage(FILE *f) {
  fputs("glint — a fast Whitted-style CPU ray tracer\n"
        "\n"
        "Usage:\n"
        "  glint render [SCENE] [options]  render a built-in scene or a file\n"
        "  glint view [SCENE] [options]    an interactive window onto a "
        "scene\n"
        "  glint bench [options]           time scenes x depths x backends\n"
        "  glint compare A B               PSNR between two images\n"
        "  glint --help                    this help\n"
        "  glint --version                 the version\n"
        "\n"
        "Built-in scenes: whitted, giza, billiard, phong.\n"
        "'glint COMMAND --help' (or 'glint help COMMAND') lists a command's\n"
        "options.\n"
        "\n"
        "Environment:\n"
        "  GLINT_ISA=none|sse|avx2|avx512  use no instruction set beyond\n"
        "                     this one (to compare them on one machine);\n"
        "                     it never enables one the CPU lacks\n"
        "\n"
        "Exit status: 0 done; 1 out of memory; 2 bad arguments or input\n"
        "(nothing is written); 130 interrupted (Ctrl-C).\n",
        f);
}

/* The commands, and whether each renders (a bad GLINT_ISA stops it). */
typedef struct command {
  const char *name;
  int (*run)(int argc, char **argv);
  int renders;
} command;

static const command commands[] = {{"render", cmd_render, 1},
                                   {"bench", cmd_bench, 1},
                                   {"view", cmd_view, 1},
                                   {"compare", cmd_compare, 0}};

static const command *command_named(const char *name) {
  for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
    if (strcmp(commands[i].name, name) == 0)
      return &commands[i];
  return NULL;
}

int main(int argc, char **argv) {
  cli_write_errors_not_signals();
  char why[128];
  if (cli_ensure_stack(why, sizeof why)) {
    cli_error("%s", why);
    return EXIT_MEMORY;
  }
  cli_end_on_stop_signals();
  if (argc < 2) {
    usage(stderr);
    return EXIT_USAGE;
  }
  const char *cmd = argv[1];
  int asks_help = strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 ||
                  strcmp(cmd, "help") == 0;
  int asks_version = strcmp(cmd, "--version") == 0 || strcmp(cmd, "-V") == 0;
  if (strcmp(cmd, "help") == 0 && argc == 3) { /* glint help COMMAND */
    char *help_arg[] = {"--help", NULL};
    const command *of = command_named(argv[2]);
    if (of)
      return of->run(1, help_arg);
    cli_error("help: unknown command '%s' (see glint --help)", argv[2]);
    return EXIT_USAGE;
  }
  if (strcmp(cmd, "help") == 0 && argc > 3) {
    cli_error("help takes one command: '%s' follows '%s'", argv[3], argv[2]);
    return EXIT_USAGE;
  }
  if ((asks_help || asks_version) && argc > 2) {
    cli_error("%s takes nothing after it: '%s'%s", cmd, argv[2],
              asks_help ? " (a command's help: glint COMMAND --help)" : "");
    return EXIT_USAGE;
  }
  if (asks_help) {
    usage(stdout);
    return 0;
  }
  if (asks_version) {
    printf("glint %s\n", glint_version());
    return 0;
  }
  /* A bad GLINT_ISA stops a command that would render, not its --help */
  int help = 0;
  for (int i = 2; i < argc && strcmp(argv[i], "--") != 0; i++)
    help |= strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0;
  glint_error err;
  const command *named = command_named(cmd);
  if (named && named->renders && !help && glint_isa_cap_check(&err)) {
    cli_error("%s", err.message);
    return EXIT_USAGE;
  }
  if (named)
    return named->run(argc - 2, argv + 2);
  if (arg_is_help_with_value(cmd))
    cli_error("--help takes no value: '%s'", cmd);
  else
    cli_error("unknown command '%s' (see glint --help)", cmd);
  return EXIT_USAGE;
}
