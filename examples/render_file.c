/* A scene file rendered with a progress bar that Ctrl-C cancels: the
 * render stops at its next tile and nothing is written.
 *
 *   render_file SCENE [OUTPUT]    (default: render_file.png)
 */
#define _POSIX_C_SOURCE 200809L /* sigaction */
#include <glint.h>

#include <signal.h>
#include <stdio.h>
#include <string.h>

/* A signal handler can only reach a variable of static storage. */
static volatile sig_atomic_t interrupted;

static void on_interrupt(int sig) {
  (void)sig;
  interrupted = 1;
}

/* Called after each tile, never by two threads at once; non-zero cancels. */
static int progress(void *user, double fraction) {
  int *last = user;
  int percent = (int)(fraction * 100);
  if (percent != *last) {
    *last = percent;
    fprintf(stderr, "\r%3d%%", percent);
  }
  return interrupted;
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: render_file SCENE [OUTPUT]\n");
    return 2;
  }
  const char *output = argc > 2 ? argv[2] : "render_file.png";
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_interrupt;
  sigaction(SIGINT, &sa, NULL);

  glint_error err;
  glint_scene *scene;
  if (glint_scene_load(argv[1], &scene, &err)) {
    fprintf(stderr, "render_file: %s\n", err.message);
    return 2;
  }
  /* Check the output before a long render, not after. */
  if (glint_image_check_writable(output, &err)) {
    fprintf(stderr, "render_file: %s\n", err.message);
    glint_scene_destroy(scene);
    return 2;
  }
  int last = -1;
  glint_render_settings settings;
  glint_render_settings_default(&settings);
  settings.progress = progress;
  settings.progress_user = &last;
  glint_image *image = NULL;
  glint_stats stats;
  glint_status st = glint_render(scene, &settings, &image, &stats, &err);
  fputc('\n', stderr);
  glint_scene_destroy(scene);
  if (st == GLINT_E_CANCELLED) {
    fprintf(stderr, "render_file: interrupted; nothing written\n");
    return 130;
  }
  if (st || (st = glint_image_write(image, output, &err))) {
    fprintf(stderr, "render_file: %s\n", err.message);
    glint_image_destroy(image);
    return 1;
  }
  glint_image_destroy(image);
  printf("%s: %dx%d in %.3f s\n", output, stats.width, stats.height,
         stats.render_seconds);
  return 0;
}
