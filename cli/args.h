/* Small, strict command-line parsing: every number is checked in full, every
 * problem becomes one message naming the option. */
#ifndef GLINT_CLI_ARGS_H
#define GLINT_CLI_ARGS_H

#include "glint.h"

#include <stddef.h>

/* Exit statuses (see glint --help): memory that could not be had gets 1;
 * bad arguments or input 2; a render stopped by Ctrl-C (or SIGTERM,
 * SIGHUP) 130, as shells report it. */
enum { EXIT_MEMORY = 1, EXIT_USAGE = 2, EXIT_INTERRUPTED = 130 };

/* The exit status of a failed library call. */
static inline int cli_exit_code(glint_status st) {
  return st == GLINT_E_MEMORY ? EXIT_MEMORY : EXIT_USAGE;
}

typedef struct arg_cursor {
  int argc;
  char **argv;
  int i;          /* next argument */
  char *inline_v; /* value after '=' or glued to a short option */
} arg_cursor;

/* If argv[i] is `-s`, `-sVALUE`, `--long` or `--long=VALUE` matching one of
 * the names, consumes the option and returns 1. */
int arg_is(arg_cursor *c, const char *short_name, const char *long_name);

/* The option's value (inline or the next argument), or NULL after printing
 * "glint: OPTION needs a value". */
char *arg_value(arg_cursor *c, const char *option);

/* Whole numbers in [min, max]; on error prints one message and returns -1. */
int parse_int(const char *option, const char *text, long min, long max,
              int *out);
int parse_double(const char *option, const char *text, double min, double *out);
/* A region X,Y,WIDTH,HEIGHT in pixels: four plain decimal numbers (digits
 * only), X and Y from 0, WIDTH and HEIGHT from 1, none above
 * GLINT_MAX_DIMENSION; on error prints one message and returns -1. */
int parse_region(const char *option, const char *text, int out[4]);
/* A gamma within GLINT_MIN_GAMMA..GLINT_MAX_GAMMA. */
int parse_gamma(const char *option, const char *text, double *out);

/* The settings options that render and bench share: -W/--width,
 * -H/--height, -s/--spp, --math, --no-newton and --accel. Returns
 * ARG_NOT_MINE if argv[i] is none of them, ARG_TAKEN once it has set *rs,
 * ARG_BAD after printing what is wrong with the value. */
enum { ARG_NOT_MINE = 0, ARG_TAKEN, ARG_BAD };
int arg_render_setting(arg_cursor *c, glint_render_settings *rs);

/* -b/--backend NAME, which must be one this CPU has; answers as
 * arg_render_setting does. */
int arg_backend(arg_cursor *c, glint_render_settings *rs);

/* A command's own options, answering as arg_render_setting does (so that a
 * command's loop chains them with ||): a value kept as text, a whole number
 * in [min, max] (messages name the long option), a flag set to 1. */
int arg_text(arg_cursor *c, const char *short_name, const char *long_name,
             char **out);
int arg_int(arg_cursor *c, const char *short_name, const char *long_name,
            long min, long max, int *out);
int arg_flag(arg_cursor *c, const char *short_name, const char *long_name,
             int *out);

/* What is left when no option took argv[i]: "--" (what follows it is the
 * scene operand, even if it starts with '-'), an unknown option (an error
 * naming `command`'s --help), else the scene operand, once (a second one
 * is an error). Answers as arg_render_setting does. */
int arg_scene_operand(arg_cursor *c, const char *command, const char **scene);

/* -h or --help. */
int arg_is_help(arg_cursor *c);
/* --help=yes, -h=1: the right option with a value it does not take. */
int arg_is_help_with_value(const char *a);
/* The error for an option no parser took: "unknown option", or, for
 * --help=VALUE, that --help takes none. */
void arg_unknown(const char *option, const char *command);

/* "backend NAME is not supported on this CPU", or, when GLINT_ISA is set,
 * that it hides it. */
void cli_unsupported_backend(const char *name);

/* Prints "glint: <message>" to stderr. */
void cli_error(const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Writes that cannot be done fail with an error glint reports (and its
 * temporary file removed) instead of a signal killing it: EPIPE for a
 * reader that went away (glint render -o - | head), EFBIG for a file past
 * the size limit (ulimit -f); and at exit, text that standard output could
 * not take is reported, with exit status 2. A standard stream that is
 * closed (glint render >&-) is opened on /dev/null, its text discarded:
 * the next file glint opened took its number, and the stream's text went
 * into that file. Called first by every program. */
void cli_write_errors_not_signals(void);
/* Whether standard output was closed at the start (-o - is refused). */
int cli_stdout_closed(void);

/* Raises the stack limit (ulimit -s) to 8 MiB, the usual default, where a
 * lower soft limit allows: the main thread's stack grows on demand up to
 * the limit of the moment, and the commands' deepest paths (the scene
 * loaders, bench's tables) need up to about 128 KiB of it (a process run
 * under ulimit -s 64 crashed). 0; or -1, with why in `why`, when the hard
 * limit is below 512 KiB. Called next by every program. */
int cli_ensure_stack(char *why, size_t size);

/* Splits a comma-separated list in place, empty items included (the
 * caller's parsing refuses them); returns the item count or -1 if there are
 * more than max. */
int split_list(char *text, char **items, int max);

#endif
