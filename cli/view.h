/* glint view's state, shared by its window (cli/view_window.c) and its
 * scripted input (cli/view_script.c). */
#ifndef GLINT_CLI_VIEW_H
#define GLINT_CLI_VIEW_H

#include "cli.h"

#include <glint.h>

#include <SDL.h>
#include <time.h>

typedef struct view_script view_script;

typedef struct viewer {
  const view_options *opt;
  /* The scene: the file's (reloaded when it changes) or a built-in's. */
  glint_scene *scene;
  char stem[CLI_STEM_SIZE];
  int is_file;
  struct timespec mtime;
  char error[sizeof((glint_error *)0)->message]; /* the last reload's message,
                                                    shown until a good one */
  glint_renderer *renderer;
  glint_render_settings rs; /* backend, math, depth, spp as now chosen */
  glint_camera camera, home;
  double speed; /* fly speed multiplier */
  /* The window and what is on it. */
  SDL_Window *window;
  SDL_Renderer *sdl;
  SDL_Texture *texture;
  int win_w, win_h;           /* the window's pixels: the frame size */
  int windowed_w, windowed_h; /* its size before F made it fullscreen */
  double user_scale;          /* [ and ] */
  double auto_scale;          /* lowered while moving to keep the budget */
  int rw, rh;                 /* the size rendered at now */
  /* This pass (then the average of all, once added to the sum); the
   * passes so far, summed. */
  glint_film *pass, *sum;
  glint_image *image; /* the average, 8-bit, at rw x rh */
  uint8_t *screen;    /* the window's pixels with the display on top */
  int samples;        /* passes summed into `sum` */
  int moving;         /* the camera moved since the last frame */
  int osd, help;
  int redraw; /* the display changed: present without rendering */
  double frame_ms, fps, mrays;
  uint64_t rays; /* the last pass's */
  double last_frame_end;
  long frames;                   /* passes rendered since the start */
  double stopped_at, refined_at; /* when the camera last stopped; when the
                                    image then reached spp samples */
  Uint8 held[SDL_NUM_SCANCODES]; /* keys down now, from the events seen */
  view_script *script;           /* --script, or NULL */
} viewer;

/* The image is refined to spp samples and nothing moves: idle. */
int view_idle(const viewer *v);
/* The camera as JSON, on standard output (the P key). */
void view_print_camera(const viewer *v);
/* What the window shows now, as an 8-bit image (NULL before the first
 * frame); the caller destroys it. */
glint_image *view_capture(const viewer *v);
/* The window's new size, as a resize by the user. */
void view_resize(viewer *v, int width, int height);

/* --script FILE: timed input for tests and demonstrations, one command a
 * line (see glint view --help). */
view_script *view_script_load(const char *path);
void view_script_free(view_script *script);
/* Runs what is due before the next frame: pushes input events, prints,
 * captures. 1: more to come; 0: the script has ended; -1: it asks to quit
 * with an error (printed). */
int view_script_step(view_script *script, viewer *v);

#endif
