/* glint view --script FILE: input as a user gives it (SDL events pushed
 * into the window's queue, handled by the same code as real ones), plus
 * what a test needs to see (the camera, the state, the window's pixels).
 * The whole file is checked before the window opens; each input command is
 * followed by at least one frame before the next command runs. */
#include "args.h"
#include "files.h"
#include "view.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef enum command_kind {
  CMD_KEY,
  CMD_HOLD,
  CMD_DRAG,
  CMD_WHEEL,
  CMD_RESIZE,
  CMD_WAIT,
  CMD_SLEEP,
  CMD_COPY,
  CMD_PRINT_CAMERA,
  CMD_PRINT_STATE,
  CMD_CAPTURE,
  CMD_QUIT
} command_kind;

typedef struct command {
  command_kind kind;
  int line;
  SDL_Keycode key;
  Uint32 buttons; /* drag */
  int shift;      /* drag with Shift held */
  double a, b;    /* seconds; dx, dy; notches; width, height */
  char *from, *to;
} command;

struct view_script {
  const char *path;
  command *commands;
  int count, next;
  double until;        /* hold or sleep: the time it ends */
  SDL_Keycode release; /* hold: the key to let go of then */
  double wait_start;   /* wait: since when (0: not waiting) */
};

static const double wait_limit = 60;

void view_script_free(view_script *s) {
  if (!s)
    return;
  for (int i = 0; i < s->count; i++) {
    free(s->commands[i].from);
    free(s->commands[i].to);
  }
  free(s->commands);
  free(s);
}

static int script_error(const view_script *s, int line, const char *what,
                        const char *word) {
  /* the word as printable ASCII: a control byte or a byte of a binary file
   * as \xNN, not sent to the terminal */
  char shown[4 * 1024 + 1];
  size_t n = 0;
  for (const unsigned char *p = (const unsigned char *)word;
       *p && n + 5 < sizeof shown; p++)
    n += (size_t)(*p >= 0x20 && *p < 0x7f
                      ? snprintf(shown + n, sizeof shown - n, "%c", *p)
                      : snprintf(shown + n, sizeof shown - n, "\\x%02x", *p));
  shown[n] = '\0';
  cli_error("%s:%d: %s '%s'", s->path, line, what, shown);
  return -1;
}

/* One line into a command; 1 for a command, 0 for nothing, -1 on error. */
static int parse_line(view_script *s, char *text, int line, command *c) {
  char *hash = strchr(text, '#');
  if (hash)
    *hash = '\0';
  char *word[4] = {NULL};
  int n = 0;
  for (char *t = strtok(text, " \t\r\n"); t; t = strtok(NULL, " \t\r\n")) {
    if (n == 4)
      return script_error(s, line, "too many words at", t);
    word[n++] = t;
  }
  if (n == 0)
    return 0;
  memset(c, 0, sizeof *c);
  c->line = line;
  const char *w = word[0];
  int want = 1;
  char *end;
  if (strcmp(w, "key") == 0 || strcmp(w, "hold") == 0) {
    c->kind = w[0] == 'k' ? CMD_KEY : CMD_HOLD;
    want = c->kind == CMD_KEY ? 2 : 3;
    if (n >= 2 && (c->key = SDL_GetKeyFromName(word[1])) == SDLK_UNKNOWN)
      return script_error(s, line, "no key is named", word[1]);
  } else if (strcmp(w, "drag") == 0) {
    c->kind = CMD_DRAG;
    want = 4;
    if (n >= 2) {
      const char *b = word[1];
      c->shift = strcmp(b, "shift-left") == 0;
      c->buttons = strcmp(b, "left") == 0 || c->shift ? SDL_BUTTON_LMASK
                   : strcmp(b, "middle") == 0         ? SDL_BUTTON_MMASK
                   : strcmp(b, "right") == 0          ? SDL_BUTTON_RMASK
                                                      : 0;
      if (!c->buttons)
        return script_error(s, line, "no mouse button is named", b);
    }
  } else if (strcmp(w, "wheel") == 0) {
    c->kind = CMD_WHEEL;
    want = 2;
  } else if (strcmp(w, "resize") == 0) {
    c->kind = CMD_RESIZE;
    want = 3;
  } else if (strcmp(w, "wait") == 0) {
    c->kind = CMD_WAIT;
  } else if (strcmp(w, "sleep") == 0) {
    c->kind = CMD_SLEEP;
    want = 2;
  } else if (strcmp(w, "copy") == 0) {
    c->kind = CMD_COPY;
    want = 3;
  } else if (strcmp(w, "print") == 0) {
    want = 2;
    if (n >= 2 && strcmp(word[1], "camera") == 0)
      c->kind = CMD_PRINT_CAMERA;
    else if (n >= 2 && strcmp(word[1], "state") == 0)
      c->kind = CMD_PRINT_STATE;
    else if (n >= 2)
      return script_error(s, line, "print takes camera or state, not", word[1]);
  } else if (strcmp(w, "capture") == 0) {
    c->kind = CMD_CAPTURE;
    want = 2;
  } else if (strcmp(w, "quit") == 0) {
    c->kind = CMD_QUIT;
  } else {
    return script_error(s, line, "unknown command", w);
  }
  if (n != want) {
    cli_error("%s:%d: '%s' takes %d argument%s", s->path, line, w, want - 1,
              want == 2 ? "" : "s");
    return -1;
  }
  /* Numbers: the seconds of hold and sleep, the pixels of drag and resize,
   * the notches of wheel. */
  int first_number =
      c->kind == CMD_HOLD || c->kind == CMD_DRAG ? 2
      : c->kind == CMD_WHEEL || c->kind == CMD_RESIZE || c->kind == CMD_SLEEP
          ? 1
          : want;
  for (int i = first_number; i < want; i++) {
    double x = strtod(word[i], &end);
    /* (strtod reads hexadecimal, which no other number of glint's is:
     * sleep 0x2 slept 2 s) */
    if (*end || end == word[i] || isnan(x) || strpbrk(word[i], "xX"))
      return script_error(s, line, "not a number:", word[i]);
    /* an underflow (ERANGE) reads as 0, as the options read it */
    /* (a script that waits hours is a typo, not a test) */
    int time = c->kind == CMD_HOLD || c->kind == CMD_SLEEP;
    if (time && !(x >= 0 && x <= 3600))
      return script_error(
          s, line,
          x < 0 ? "a negative time:" : "a time past 3600 seconds:", word[i]);
    if (!(x >= -1e6 && x <= 1e6))
      return script_error(s, line, "a number outside -1e6..1e6:", word[i]);
    /* pixels and the wheel's notches are whole (wheel 0.5 did nothing,
     * resize 1.5 2.7 made a 1x2 window) */
    if (!time && x != floor(x))
      return script_error(s, line, "not a whole number:", word[i]);
    if (i == first_number)
      c->a = x;
    else
      c->b = x;
  }
  if (c->kind == CMD_RESIZE &&
      (c->a < 1 || c->b < 1 || c->a > GLINT_MAX_DIMENSION ||
       c->b > GLINT_MAX_DIMENSION))
    return script_error(s, line, "a window size outside 1..16384:", word[1]);
  if (c->kind == CMD_COPY) {
    c->from = strdup(word[1]);
    c->to = strdup(word[2]);
  } else if (c->kind == CMD_CAPTURE) {
    if (glint_image_format_from_path(word[1]) == GLINT_FORMAT_UNKNOWN)
      return script_error(s, line, "not a .png, .bmp or .ppm name:", word[1]);
    c->to = strdup(word[1]);
  }
  return 1;
}

view_script *view_script_load(const char *path) {
  /* A regular file only: a folder reads as empty, and a FIFO without a
   * writer would block for ever (as the scene readers refuse them). */
  struct stat sb;
  if (stat(path, &sb) != 0) {
    cli_error("--script %s: %s", path, strerror(errno));
    return NULL;
  }
  if (!S_ISREG(sb.st_mode)) {
    cli_error("--script %s: not a regular file", path);
    return NULL;
  }
  FILE *f = fopen(path, "r");
  if (!f) {
    cli_error("--script %s: %s", path, strerror(errno));
    return NULL;
  }
  view_script *s = calloc(1, sizeof *s);
  int capacity = 0, line = 0, bad = !s;
  char text[1024];
  while (!bad && fgets(text, sizeof text, f)) {
    line++;
    /* fgets stops at a newline only: a NUL byte inside the line leaves
     * text shorter than what was read */
    size_t len = strlen(text);
    int whole_line = len > 0 && text[len - 1] == '\n';
    if (len + 1 < sizeof text && !whole_line && !feof(f)) {
      cli_error("%s:%d: a NUL byte (not a text file)", path, line);
      bad = 1;
      break;
    }
    if (!strchr(text, '\n') && !feof(f)) {
      cli_error("%s:%d: a line longer than %d characters", path, line,
                (int)sizeof text - 2);
      bad = 1;
      break;
    }
    if (s->count == capacity) {
      capacity = capacity ? 2 * capacity : 32;
      command *grown = realloc(s->commands, sizeof *grown * (size_t)capacity);
      if (!grown) {
        bad = 1;
        break;
      }
      s->commands = grown;
    }
    s->path = path;
    int r = parse_line(s, text, line, &s->commands[s->count]);
    if (r < 0)
      bad = 1;
    s->count += r > 0;
  }
  fclose(f);
  if (bad) {
    view_script_free(s);
    return NULL;
  }
  s->path = path;
  return s;
}

static void push_key(const viewer *v, SDL_Keycode key, int down) {
  SDL_Event ev;
  memset(&ev, 0, sizeof ev);
  ev.type = down ? SDL_KEYDOWN : SDL_KEYUP;
  ev.key.windowID = SDL_GetWindowID(v->window);
  ev.key.state = down ? SDL_PRESSED : SDL_RELEASED;
  ev.key.keysym.sym = key;
  ev.key.keysym.scancode = SDL_GetScancodeFromKey(key);
  SDL_PushEvent(&ev);
}

/* A drag in ten motion events, the button held throughout. */
static void push_drag(const viewer *v, const command *c) {
  if (c->shift)
    push_key(v, SDLK_LSHIFT, 1);
  int dx = (int)c->a, dy = (int)c->b, done_x = 0, done_y = 0;
  for (int i = 1; i <= 10; i++) {
    SDL_Event ev;
    memset(&ev, 0, sizeof ev);
    ev.type = SDL_MOUSEMOTION;
    ev.motion.windowID = SDL_GetWindowID(v->window);
    ev.motion.state = c->buttons;
    ev.motion.xrel = dx * i / 10 - done_x;
    ev.motion.yrel = dy * i / 10 - done_y;
    done_x += ev.motion.xrel;
    done_y += ev.motion.yrel;
    ev.motion.x = v->win_w / 2 + done_x;
    ev.motion.y = v->win_h / 2 + done_y;
    SDL_PushEvent(&ev);
  }
  if (c->shift)
    push_key(v, SDLK_LSHIFT, 0);
}

static void print_state(const viewer *v) {
  printf("state: frames %ld, samples %d/%d, depth %d, ", v->frames, v->samples,
         v->rs.spp, v->rs.max_depth);
  if (v->rw > 0) /* (before the first frame there is no size: 0x0 said so) */
    printf("%dx%d at scale %.3f, ", v->rw, v->rh, (double)v->rw / v->win_w);
  else
    printf("no frame yet, ");
  printf("%s", glint_backend_name(
                   glint_backend_choose(v->rs.backend, v->scene, &v->rs)));
  if (v->refined_at > v->stopped_at && v->stopped_at > 0)
    printf(", refined %.3f s after the camera stopped",
           v->refined_at - v->stopped_at);
  printf("\n");
  fflush(stdout);
}

/* Copies a regular file onto a regular file (or a new one): a device such
 * as /dev/zero never ends and would fill the disk, a FIFO may block for
 * ever, and a file copied onto itself would be emptied by the open. */
static int copy_file(const view_script *s, const command *c) {
  /* Opened without blocking, so that a FIFO is refused at once rather than
   * waited on (fopen waits for a writer) */
  int fd = open(c->from, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  struct stat st;
  const char *why = NULL;
  if (fd < 0)
    why = strerror(errno);
  else if (fstat(fd, &st) != 0)
    why = strerror(errno);
  else if (!S_ISREG(st.st_mode))
    why = "not a regular file";
  else if (stat(c->to, &st) == 0 && !S_ISREG(st.st_mode))
    why = "the destination is not a regular file";
  else if (same_file(c->from, c->to))
    why = "they are the same file";
  else if (same_file(s->path, c->to))
    why = "the destination is this script";
  /* Into a file beside TO, renamed over it once whole: a failed copy
   * leaves TO as it was, and a viewer watching TO never reads half of it. */
  file_replacement r;
  int saved = why ? 0 : replace_begin(&r, c->to);
  if (!why && !saved) {
    char buf[8192];
    ssize_t n;
    while (!saved && (n = read(fd, buf, sizeof buf)) != 0)
      if (n < 0 && errno != EINTR && errno != EAGAIN)
        saved = errno;
      else if (n > 0)
        saved = replace_write(&r, buf, (size_t)n);
    int ended = replace_end(&r, !saved);
    saved = saved ? saved : ended;
  }
  if (saved)
    why = strerror(saved);
  if (fd >= 0)
    close(fd);
  if (why)
    cli_error("%s:%d: cannot copy %s to %s: %s", s->path, c->line, c->from,
              c->to, why);
  return why ? -1 : 0;
}

int view_script_step(view_script *s, viewer *v) {
  double now = cli_now();
  if (s->until) {
    if (now < s->until)
      return 1;
    s->until = 0;
    if (s->release) {
      push_key(v, s->release, 0);
      s->release = 0;
      return 1;
    }
  }
  if (s->wait_start) {
    if (!view_idle(v)) {
      if (now - s->wait_start < wait_limit)
        return 1;
      cli_error("%s:%d: the image was not refined within %.0f s", s->path,
                s->commands[s->next - 1].line, wait_limit);
      return -1;
    }
    s->wait_start = 0;
  }
  while (s->next < s->count) {
    const command *c = &s->commands[s->next++];
    switch (c->kind) {
    case CMD_KEY:
      push_key(v, c->key, 1);
      push_key(v, c->key, 0);
      return 1;
    case CMD_HOLD:
      push_key(v, c->key, 1);
      s->release = c->key;
      s->until = now + c->a;
      return 1;
    case CMD_DRAG: push_drag(v, c); return 1;
    case CMD_WHEEL: {
      SDL_Event ev;
      memset(&ev, 0, sizeof ev);
      ev.type = SDL_MOUSEWHEEL;
      ev.wheel.windowID = SDL_GetWindowID(v->window);
      ev.wheel.y = (Sint32)c->a;
      SDL_PushEvent(&ev);
      return 1;
    }
    case CMD_RESIZE:
      SDL_SetWindowSize(v->window, (int)c->a, (int)c->b);
      view_resize(v, (int)c->a, (int)c->b);
      return 1;
    case CMD_WAIT: s->wait_start = now; return 1;
    case CMD_SLEEP: s->until = now + c->a; return 1;
    case CMD_COPY:
      if (copy_file(s, c))
        return -1;
      break;
    case CMD_PRINT_CAMERA: view_print_camera(v); break;
    case CMD_PRINT_STATE: print_state(v); break;
    case CMD_CAPTURE: {
      glint_image *image = view_capture(v);
      glint_error err;
      if (!image) {
        cli_error("%s:%d: nothing on the window yet", s->path, c->line);
        return -1;
      }
      /* (checked now, not when the script was read: a link may appear) */
      glint_status st = cli_check_output_format(c->to, NULL, &err);
      if (!st && same_file(s->path, c->to)) { /* it was replaced by a PNG */
        snprintf(err.message, sizeof err.message,
                 "capture %.900s: that is "
                 "this script",
                 c->to);
        st = GLINT_E_ARGUMENT;
      }
      if (!st)
        st = glint_image_write(image, c->to, &err);
      glint_image_destroy(image);
      if (st) {
        cli_error("%s:%d: %s", s->path, c->line, err.message);
        return -1;
      }
      break;
    }
    case CMD_QUIT: {
      SDL_Event ev;
      memset(&ev, 0, sizeof ev);
      ev.type = SDL_QUIT;
      SDL_PushEvent(&ev);
      return 0;
    }
    }
  }
  return 0;
}
