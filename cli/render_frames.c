/* glint render --frames A-B: frames of the scene's animation, a file each.
 *
 * The scene is committed once and every frame rendered by one renderer
 * with the camera of its time (t = (frame - first) / fps, from the whole
 * animation whatever part is rendered); when objects move, each frame
 * commits the scene at its time (a new BVH) and hands that world to the
 * same renderer (threads and memory kept); each file is written atomically
 * while its frame renders (glint_image_writer), so an interrupted run
 * leaves whole frames only, and --resume keeps those and renders the rest. */
#include "args.h"
#include "cli.h"

#include <glint.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Checks an -o pattern: exactly one %d conversion (flags 0 and a width
 * allowed) and %% for a literal %. Returns 1 when it is one, 0 when the
 * name has no % at all, -1 (after a message) when it is malformed. */
static int check_pattern(const char *p) {
  int conversions = 0;
  for (const char *c = strchr(p, '%'); c; c = strchr(c + 1, '%')) {
    if (c[1] == '%') {
      c++;
      continue;
    }
    const char *d = c + 1;
    if (*d == '0')
      d++;
    int width = 0;
    while (*d >= '0' && *d <= '9' && width < 100)
      width = width * 10 + (*d++ - '0');
    if (*d != 'd' || width > 9) {
      cli_error("-o %s: a frame pattern takes one %%d, %%04d or the like "
                "(and %%%% for a %%)",
                p);
      return -1;
    }
    conversions++;
    c = d;
  }
  if (conversions > 1) {
    cli_error("-o %s: a frame pattern takes one number, not %d", p,
              conversions);
    return -1;
  }
  return conversions;
}

/* The file of `frame`: the pattern's, else the number (at least `digits`
 * wide) before the name's extension. */
static int frame_path(char *out, size_t size, const char *name, int pattern,
                      int frame, int digits) {
  int n;
  if (pattern) {
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
#endif
    n = snprintf(out, size, name, frame); /* checked by check_pattern */
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
  } else {
    const char *slash = strrchr(name, '/');
    const char *dot = strrchr(slash ? slash : name, '.');
    if (!dot)
      dot = name + strlen(name);
    n = snprintf(out, size, "%.*s%0*d%s", (int)(dot - name), name, digits,
                 frame, dot);
  }
  if (n < 0 || (size_t)n >= size) {
    cli_error("-o %s: the file name of frame %d is too long", name, frame);
    return -1;
  }
  return 0;
}

static int on_progress(void *user, double fraction) {
  (void)user;
  (void)fraction;
  return cli_stopped(); /* Ctrl-C cancels the frame */
}

/* Makes the folders of `path` that are missing (mkdir -p of its dirname);
 * -1 with a message when one cannot be made. */
static int make_folders(const char *path) {
  char folder[4096];
  snprintf(folder, sizeof folder, "%s", path);
  char *slash = strrchr(folder, '/');
  if (!slash || slash == folder)
    return 0;
  *slash = '\0';
  for (char *p = folder + 1;; p++) {
    if (*p == '/' || *p == '\0') {
      char saved = *p;
      *p = '\0';
      struct stat sb;
      if (stat(folder, &sb) != 0 && mkdir(folder, 0777) != 0 &&
          errno != EEXIST) {
        cli_error("%s: cannot make the folder: %s", folder, strerror(errno));
        return -1;
      }
      *p = saved;
      if (!saved)
        return 0;
    }
  }
}

/* The world of the scene at `time`, committed (its BVH built anew) and
 * given to the renderer. 0 on success. */
static int next_world(const glint_scene *scene, double time,
                      glint_renderer *renderer, glint_error *err) {
  glint_scene *still;
  glint_world *world;
  if (glint_scene_at_time(scene, time, &still, err))
    return -1;
  glint_status st = glint_world_commit(still, &world, NULL, err);
  glint_scene_destroy(still);
  if (st)
    return -1;
  st = glint_renderer_set_world(renderer, world, err);
  glint_world_destroy(world);
  return st ? -1 : 0;
}

static int already_written(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0 && S_ISREG(sb.st_mode) && sb.st_size > 0;
}

int render_frames(glint_scene *scene, const render_options *o,
                  const char *stem) {
  glint_error err;
  glint_animation anim;
  const char *scene_name = o->scene;
  if (!glint_scene_get_animation(scene, &anim)) {
    cli_error("%s has no animation: --frames needs an \"animation\" block "
              "(docs/scene-format.md)",
              scene_name);
    glint_scene_destroy(scene);
    return EXIT_USAGE;
  }
  if (o->first_frame < anim.first_frame || o->last_frame > anim.last_frame) {
    cli_error("--frames %d-%d: %s's animation has frames %d-%d", o->first_frame,
              o->last_frame, scene_name, anim.first_frame, anim.last_frame);
    glint_scene_destroy(scene);
    return EXIT_USAGE;
  }
  char default_name[300];
  const char *name = o->output;
  if (!name) {
    snprintf(default_name, sizeof default_name, "%s.png", stem);
    name = default_name;
  }
  int pattern = check_pattern(name);
  if (pattern < 0) {
    glint_scene_destroy(scene);
    return EXIT_USAGE;
  }
  int digits = snprintf(NULL, 0, "%d", anim.last_frame);
  digits = digits < 4 ? 4 : digits;
  char first_path[4096];
  if (frame_path(first_path, sizeof first_path, name, pattern, o->first_frame,
                 digits)) {
    glint_scene_destroy(scene);
    return EXIT_USAGE;
  }
  if (glint_image_format_from_path(first_path) == GLINT_FORMAT_UNKNOWN) {
    cli_error("%s: --frames writes .png, .bmp or .ppm images", first_path);
    glint_scene_destroy(scene);
    return EXIT_USAGE;
  }
  /* -o out/frame%04d.png makes out/ when it is missing (and a pattern
   * whose number is in a folder's name makes that folder for each frame,
   * below). */
  if (make_folders(first_path)) {
    glint_scene_destroy(scene);
    return EXIT_USAGE;
  }

  const glint_render_settings *rs = &o->settings;
  glint_world *world = NULL;
  glint_renderer *renderer = NULL;
  double t_start = cli_now();
  if (glint_world_commit(scene, &world, NULL, &err) ||
      glint_renderer_create(world, rs, &renderer, &err)) {
    cli_error("%s", err.message);
    glint_world_destroy(world);
    glint_scene_destroy(scene);
    return EXIT_USAGE;
  }
  glint_world_destroy(world);
  glint_scene_info info;
  glint_scene_get_info(scene, &info);
  int w = rs->width ? rs->width : info.width;
  int h = rs->height ? rs->height : info.height;
  if (rs->region_width)
    w = rs->region_width, h = rs->region_height;

  /* Objects that move need a world a frame; a camera alone does not. */
  int moving = glint_scene_has_motion(scene);
  cli_catch_stop_signals();
  int status = 0, rendered = 0, kept = 0;
  double render_seconds = 0, frame_seconds = 0;
  for (int f = o->first_frame; f <= o->last_frame && !status; f++) {
    char path[4096];
    if (frame_path(path, sizeof path, name, pattern, f, digits)) {
      status = EXIT_USAGE;
      break;
    }
    if (pattern && make_folders(path)) { /* a number in a folder's name */
      status = EXIT_USAGE;
      break;
    }
    if (o->resume && already_written(path)) {
      kept++;
      if (!o->quiet)
        printf("frame %d: %s is there, kept (--resume)\n", f, path);
      continue;
    }
    double t0 = cli_now(), time = (double)(f - anim.first_frame) / anim.fps;
    glint_camera camera;
    cli_tile_sink sink = {NULL, rs->region_x, rs->region_y, 0, {0}};
    glint_stats st;
    glint_frame_settings frame;
    glint_frame_settings_default(&frame);
    frame.camera = &camera;
    frame.tile = cli_tile_to_writer;
    frame.tile_user = &sink;
    frame.progress = on_progress;
    if (glint_scene_camera_at(scene, time, &camera, &err) ||
        (moving && next_world(scene, time, renderer, &err)) ||
        glint_image_writer_open(path, w, h, rs->gamma, o->png_compression,
                                &sink.writer, &err)) {
      cli_error("frame %d: %s", f, err.message);
      status = EXIT_USAGE;
      break;
    }
    glint_status rst = glint_renderer_render(renderer, &frame, NULL, &st, &err);
    if (cli_stopped()) {
      glint_image_writer_discard(sink.writer);
      cli_error("interrupted at frame %d, which was not written; frames "
                "written stay, and --resume renders the rest",
                f);
      status = EXIT_INTERRUPTED;
      break;
    }
    if (rst) {
      glint_image_writer_discard(sink.writer);
      cli_error("frame %d: %s", f,
                sink.failed ? sink.error.message : err.message);
      status = EXIT_USAGE;
      break;
    }
    if (glint_image_writer_finish(sink.writer, &err)) {
      cli_error("frame %d: %s", f, err.message);
      status = EXIT_USAGE;
      break;
    }
    double seconds = cli_now() - t0;
    rendered++;
    render_seconds += st.render_seconds;
    frame_seconds += seconds;
    if (!o->quiet)
      printf("frame %d (t = %.3f s): %s, %.3f s\n", f, time, path, seconds);
    fflush(stdout);
  }
  glint_renderer_destroy(renderer);
  glint_scene_destroy(scene);
  if (!status && !o->quiet) {
    double total = cli_now() - t_start;
    printf("%d frame%s written", rendered, rendered == 1 ? "" : "s");
    if (kept)
      printf(", %d kept (--resume)", kept);
    if (rendered)
      printf(" in %.3f s: %.2f ms a frame, of which %.2f ms rendering", total,
             1e3 * frame_seconds / rendered, 1e3 * render_seconds / rendered);
    printf("\n");
  }
  return status;
}
