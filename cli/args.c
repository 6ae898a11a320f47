#define _GNU_SOURCE /* program_invocation_short_name */
#include "args.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

/* What it quotes (a file name, an option's value) may hold control
 * characters: an escape sequence would reach the terminal as a command, so
 * each is shown as '?' (line breaks stay: some messages quote a failed
 * program's output). */
void cli_error(const char *format, ...) {
  va_list args, again;
  va_start(args, format);
  va_copy(again, args);
  char line[1024], *text = line;
  int n = vsnprintf(line, sizeof line, format, args);
  if (n >= (int)sizeof line && (text = malloc((size_t)n + 1)))
    vsnprintf(text, (size_t)n + 1, format, again);
  else if (!text)
    text = line; /* cut, rather than nothing */
  va_end(again);
  va_end(args);
  /* glint-mpi's messages are its own; glint-view speaks for glint view */
  fputs(strcmp(program_invocation_short_name, "glint-mpi") == 0 ? "glint-mpi: "
                                                                : "glint: ",
        stderr);
  for (const unsigned char *p = (const unsigned char *)text; *p; p++)
    fputc((*p < 0x20 && *p != '\n' && *p != '\t') || *p == 0x7f ? '?' : *p,
          stderr);
  fputc('\n', stderr);
  if (text != line)
    free(text);
}

void cli_unsupported_backend(const char *name) {
  const char *cap = getenv("GLINT_ISA");
  if (cap && *cap)
    cli_error("backend '%s' is not available with GLINT_ISA=%s (or on this "
              "CPU)",
              name, cap);
  else
    cli_error("backend '%s' is not supported on this CPU", name);
}

int arg_is(arg_cursor *c, const char *short_name, const char *long_name) {
  char *a = c->argv[c->i];
  if (short_name && strncmp(a, short_name, 2) == 0 && a[0] == '-' &&
      a[1] != '-') {
    /* -W800, -W=800 and -W 800 alike */
    c->inline_v = a[2] == '=' ? a + 3 : a[2] ? a + 2 : NULL;
    c->i++;
    return 1;
  }
  if (long_name) {
    size_t n = strlen(long_name);
    if (strncmp(a, long_name, n) == 0 && (a[n] == '\0' || a[n] == '=')) {
      c->inline_v = a[n] == '=' ? a + n + 1 : NULL;
      c->i++;
      return 1;
    }
  }
  return 0;
}

char *arg_value(arg_cursor *c, const char *option) {
  if (c->inline_v)
    return c->inline_v;
  if (c->i < c->argc)
    return c->argv[c->i++];
  cli_error("%s needs a value", option);
  return NULL;
}

int parse_int(const char *option, const char *text, long min, long max,
              int *out) {
  if (!text)
    return -1;
  char *end;
  errno = 0;
  long v = strtol(text, &end, 10);
  /* strtol skips leading blanks; a trailing one is refused, so both are */
  if (end == text || *end != '\0' || isspace((unsigned char)*text)) {
    cli_error("%s: '%s' is not a whole number", option, text);
    return -1;
  }
  if (errno == ERANGE) { /* a whole number, past any limit */
    cli_error("%s: %s is outside %ld..%ld", option, text, min, max);
    return -1;
  }
  if (v < min || v > max) {
    cli_error("%s: %ld is outside %ld..%ld", option, v, min, max);
    return -1;
  }
  *out = (int)v;
  return 0;
}

int parse_region(const char *option, const char *text, int out[4]) {
  if (!text)
    return -1;
  const char *p = text;
  for (int k = 0; k < 4; k++) {
    long v = 0;
    int digits = 0;
    if (*p == '+') /* as parse_int's strtol takes one (-s +4) */
      p++;
    /* digits only, and at most what GLINT_MAX_DIMENSION needs: no wrap */
    for (; *p >= '0' && *p <= '9' && v <= GLINT_MAX_DIMENSION; p++, digits++)
      v = v * 10 + (*p - '0');
    if (!digits || *p != (k < 3 ? ',' : '\0') || v > GLINT_MAX_DIMENSION ||
        (k >= 2 && v < 1)) {
      cli_error("%s: '%s' is not X,Y,WIDTH,HEIGHT in pixels (whole numbers, "
                "X and Y from 0, WIDTH and HEIGHT from 1, each at most %d)",
                option, text, GLINT_MAX_DIMENSION);
      return -1;
    }
    out[k] = (int)v;
    p++;
  }
  return 0;
}

int parse_double(const char *option, const char *text, double min,
                 double *out) {
  if (!text)
    return -1;
  char *end;
  errno = 0;
  double v = strtod(text, &end);
  /* strtod skips leading blanks, refused as parse_int refuses them, and
   * reads hexadecimal (0x10 is 16), which no other number of glint's is */
  if (end == text || *end != '\0' || isspace((unsigned char)*text) ||
      strpbrk(text, "xX")) {
    cli_error("%s: '%s' is not a number", option, text);
    return -1;
  }
  if (!isfinite(v)) { /* inf, nan, 1e999 */
    cli_error("%s: '%s' is not a finite number", option, text);
    return -1;
  }
  /* The user's own words: 1e-400 reads as 0 */
  if (!(v > min)) {
    cli_error("%s: %s must be greater than %g", option, text, min);
    return -1;
  }
  *out = v;
  return 0;
}

int parse_gamma(const char *option, const char *text, double *out) {
  double v;
  if (parse_double(option, text, -INFINITY, &v))
    return -1;
  if (v < GLINT_MIN_GAMMA || v > GLINT_MAX_GAMMA) {
    cli_error("%s: %s is outside %g..%g", option, text, GLINT_MIN_GAMMA,
              GLINT_MAX_GAMMA);
    return -1;
  }
  *out = v;
  return 0;
}

int split_list(char *text, char **items, int max) {
  if (!*text)
    return 0;
  int n = 0;
  for (char *p = text;;) {
    char *comma = strchr(p, ',');
    if (comma)
      *comma = '\0';
    if (n == max)
      return -1;
    items[n++] = p; /* an empty one too (1,,2), for the caller to refuse */
    if (!comma)
      return n;
    p = comma + 1;
  }
}

int arg_text(arg_cursor *c, const char *short_name, const char *long_name,
             char **out) {
  if (!arg_is(c, short_name, long_name))
    return ARG_NOT_MINE;
  char *v = arg_value(c, long_name);
  if (!v)
    return ARG_BAD;
  *out = v;
  return ARG_TAKEN;
}

int arg_int(arg_cursor *c, const char *short_name, const char *long_name,
            long min, long max, int *out) {
  if (!arg_is(c, short_name, long_name))
    return ARG_NOT_MINE;
  return parse_int(long_name, arg_value(c, long_name), min, max, out)
             ? ARG_BAD
             : ARG_TAKEN;
}

int arg_flag(arg_cursor *c, const char *short_name, const char *long_name,
             int *out) {
  if (!arg_is(c, short_name, long_name))
    return ARG_NOT_MINE;
  /* --quiet=no, -qfoo: a value here is a mistake (taken as the flag, it
   * turned --no-newton=0 into --no-newton) */
  if (c->inline_v) {
    cli_error("%s takes no value: '%s'", long_name ? long_name : short_name,
              c->argv[c->i - 1]);
    return ARG_BAD;
  }
  *out = 1;
  return ARG_TAKEN;
}

int arg_is_help_with_value(const char *a) {
  return strncmp(a, "--help=", 7) == 0 || strncmp(a, "-h=", 3) == 0;
}

void arg_unknown(const char *option, const char *command) {
  if (arg_is_help_with_value(option))
    cli_error("--help takes no value: '%s'", option);
  else
    cli_error("unknown option '%s' (see glint %s --help)", option, command);
}

int arg_is_help(arg_cursor *c) {
  if (!arg_is(c, "-h", "--help"))
    return 0;
  if (c->inline_v) { /* -hello is no help: left to be refused as unknown */
    c->i--;
    return 0;
  }
  return 1;
}

int arg_render_setting(arg_cursor *c, glint_render_settings *rs) {
  char *v = NULL;
  glint_error err;
  int r;
  if ((r = arg_int(c, "-W", "--width", 1, GLINT_MAX_DIMENSION, &rs->width)) ||
      (r = arg_int(c, "-H", "--height", 1, GLINT_MAX_DIMENSION, &rs->height)) ||
      (r = arg_int(c, "-s", "--spp", 1, GLINT_MAX_SPP, &rs->spp)))
    return r;
  int no_newton = 0;
  if ((r = arg_flag(c, NULL, "--no-newton", &no_newton))) {
    rs->rcp_newton = 0;
    return r;
  }
  if ((r = arg_text(c, NULL, "--math", &v)) == ARG_TAKEN &&
      glint_math_parse(v, &rs->math, &err)) {
    cli_error("--math: %s", err.message);
    return ARG_BAD;
  }
  if (r)
    return r;
  if ((r = arg_text(c, NULL, "--accel", &v)) == ARG_TAKEN &&
      glint_accel_parse(v, &rs->accel, &err)) {
    cli_error("--accel: %s", err.message);
    return ARG_BAD;
  }
  return r;
}

int arg_backend(arg_cursor *c, glint_render_settings *rs) {
  char *v = NULL;
  glint_error err;
  int r = arg_text(c, "-b", "--backend", &v);
  if (r != ARG_TAKEN)
    return r;
  if (glint_backend_parse(v, &rs->backend, &err)) {
    cli_error("--backend: %s", err.message);
    return ARG_BAD;
  }
  if (!glint_backend_supported(rs->backend)) {
    cli_unsupported_backend(v);
    return ARG_BAD;
  }
  return ARG_TAKEN;
}

int arg_scene_operand(arg_cursor *c, const char *command, const char **scene) {
  const char *a = c->argv[c->i];
  if (strcmp(a, "--") == 0) { /* the rest are operands: a scene named -x */
    c->i++;
    if (c->i < c->argc && !*scene)
      *scene = c->argv[c->i++];
    if (c->i < c->argc) {
      cli_error("more than one scene given ('%s' and '%s')", *scene,
                c->argv[c->i]);
      return ARG_BAD;
    }
    return ARG_TAKEN;
  }
  if (a[0] == '-' && a[1] != '\0') {
    arg_unknown(a, command);
    return ARG_BAD;
  }
  if (*scene) {
    cli_error("more than one scene given ('%s' and '%s')", *scene, a);
    return ARG_BAD;
  }
  *scene = a;
  c->i++;
  return ARG_TAKEN;
}

/* At exit: what standard output could not take is an error (glint compare
 * > /dev/full lost its PSNR line and exited 0). A reader that went away
 * (| head) is not: it wanted no more. */
static void check_stdout(void) {
  errno = 0;
  int failed = fflush(stdout) != 0 || ferror(stdout);
  int why = errno;
  if (!failed || why == EPIPE)
    return;
  if (why)
    cli_error("writing to standard output failed: %s", strerror(why));
  else
    cli_error("writing to standard output failed");
  _exit(EXIT_USAGE);
}

/* Whether standard output was closed when the program started. */
static int stdout_closed;

int cli_stdout_closed(void) { return stdout_closed; }

void cli_write_errors_not_signals(void) {
  for (int fd = STDIN_FILENO; fd <= STDERR_FILENO; fd++) {
    if (fcntl(fd, F_GETFD) >= 0 || errno != EBADF)
      continue;
    stdout_closed |= fd == STDOUT_FILENO;
    int null = open("/dev/null", fd == STDIN_FILENO ? O_RDONLY : O_WRONLY);
    if (null >= 0 && null != fd) {
      dup2(null, fd);
      close(null);
    }
  }
  signal(SIGPIPE, SIG_IGN);
  signal(SIGXFSZ, SIG_IGN);
  atexit(check_stdout);
}

int cli_ensure_stack(char *why, size_t size) {
  const rlim_t wanted = (rlim_t)8 << 20, needed = (rlim_t)512 << 10;
  struct rlimit stack;
  if (getrlimit(RLIMIT_STACK, &stack) != 0 || stack.rlim_cur == RLIM_INFINITY ||
      stack.rlim_cur >= wanted)
    return 0;
  rlim_t most = stack.rlim_max == RLIM_INFINITY || stack.rlim_max > wanted
                    ? wanted
                    : stack.rlim_max;
  if (most > stack.rlim_cur) {
    stack.rlim_cur = most;
    setrlimit(RLIMIT_STACK, &stack);
  }
  if (getrlimit(RLIMIT_STACK, &stack) == 0 && stack.rlim_cur < needed) {
    snprintf(why, size,
             "the stack limit (ulimit -s) is %llu KiB; glint needs at least "
             "%llu KiB",
             (unsigned long long)stack.rlim_cur >> 10,
             (unsigned long long)needed >> 10);
    return -1;
  }
  return 0;
}
