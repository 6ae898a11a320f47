/* The frames of an animation, as glint render --frames and glint-mpi write
 * them: the -o pattern (or the number put before the extension), each
 * frame's file and its folder, and the world at a frame's time. */
#include "args.h"
#include "cli.h"
#include "files.h"

#include <glint.h>

#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Checks an -o pattern: exactly one %d conversion (flags 0 and a width
 * allowed) and %% for a literal %. Returns 1 when it is one, 0 when the
 * name has no number (nor any % but %%), -1 (after a message) when it is
 * malformed. */
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
    if (*d != 'd') {
      cli_error("-o %s: a frame pattern takes one %%d, %%04d or the like "
                "(and %%%% for a %%)",
                p);
      return -1;
    }
    if (width > 9) {
      cli_error("-o %s: a frame number's width is at most 9 (%%09d)", p);
      return -1;
    }
    conversions++;
    /* x%d/../f.png would put every frame in one file: the folders after
     * the number's may not climb out of it */
    int depth = 0;
    for (const char *part = strchr(d, '/'); part; part = strchr(part, '/')) {
      size_t len = strcspn(++part, "/");
      if (len == 2 && part[0] == '.' && part[1] == '.')
        depth--;
      else if (len > 0 && !(len == 1 && part[0] == '.'))
        depth++;
      if (depth < 0) {
        cli_error("-o %s: the '..' after the number's folder would put every "
                  "frame in one file",
                  p);
        return -1;
      }
    }
    c = d;
  }
  if (conversions > 1) {
    cli_error("-o %s: a frame pattern takes one number, not %d", p,
              conversions);
    return -1;
  }
  return conversions;
}

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
    /* No number in the name, so any % in it came as %% (check_pattern):
     * the number goes before the extension of the name with %% as %. */
    char plain[4096];
    size_t len = 0;
    for (const char *c = name; *c && len + 1 < sizeof plain; c++) {
      plain[len++] = *c;
      if (c[0] == '%' && c[1] == '%')
        c++;
    }
    plain[len] = '\0';
    const char *slash = strrchr(plain, '/');
    const char *dot = strrchr(slash ? slash : plain, '.');
    if (!dot)
      dot = plain + len;
    n = len + 1 < sizeof plain
            ? snprintf(out, size, "%.*s%0*d%s", (int)(dot - plain), plain,
                       digits, frame, dot)
            : -1;
  }
  if (n < 0 || (size_t)n >= size) {
    cli_error("-o %s: the file name of frame %d is too long", name, frame);
    return -1;
  }
  return 0;
}

/* Forgets the folders in `made`, first removing those still empty (the
 * deepest first) when `remove`. */
static void forget_made_folders(made_folders *made, int remove) {
  while (made->count > 0) {
    char *folder = made->paths[--made->count];
    if (remove)
      rmdir(folder); /* one not empty stays */
    free(folder);
  }
  free(made->paths);
  made->paths = NULL;
  made->room = 0;
}

/* Notes `folder` in `made` (short of memory, it is not noted, and stays). */
static void note_made(made_folders *made, const char *folder) {
  if (!made)
    return;
  if (made->count == made->room) { /* doubling: a folder a frame, 10^5 */
    size_t room = made->room ? 2 * made->room : 16;
    char **grown = realloc(made->paths, room * sizeof *grown);
    if (!grown)
      return;
    made->paths = grown;
    made->room = room;
  }
  if ((made->paths[made->count] = strdup(folder)) != NULL)
    made->count++;
}

/* Makes the folders of `path` that are missing (mkdir -p of its dirname),
 * noting in `made` (when not NULL) each one made (short of memory, one is
 * not noted, and stays); -1 with a message when one cannot be made. */
static int make_folders(const char *path, made_folders *made) {
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
      if (stat(folder, &sb) != 0) {
        if (mkdir(folder, 0777) == 0) {
          note_made(made, folder);
        } else if (errno != EEXIST) {
          cli_error("%s: cannot make the folder: %s", folder, strerror(errno));
          return -1;
        }
      }
      *p = saved;
      if (!saved)
        return 0;
    }
  }
}

int cli_world_at(const glint_scene *scene, double time,
                 glint_renderer *renderer, glint_world **last,
                 glint_error *err) {
  glint_world *world;
  if (glint_world_commit_at(scene, time, *last, &world, NULL, err))
    return -1;
  glint_status st = glint_renderer_set_world(renderer, world, err);
  glint_world_destroy(*last);
  *last = world; /* the next frame refits its BVH */
  return st ? -1 : 0;
}

void frame_size(const glint_scene *scene, const glint_render_settings *rs,
                int *width, int *height) {
  glint_scene_info info;
  glint_scene_get_info(scene, &info);
  *width = rs->region_width ? rs->region_width
           : rs->width      ? rs->width
                            : info.width;
  *height = rs->region_width ? rs->region_height
            : rs->height     ? rs->height
                             : info.height;
}

/* Whether the existing `path` is a finished frame: frames are written whole
 * (a temporary file renamed), but what is under the name may be another
 * run's size, another program's file or damaged: only an image of this
 * frame's size counts as done. If not, err says why. */
static int finished_frame(const char *path, const struct stat *sb, int width,
                          int height, glint_error *err) {
  glint_image *image = NULL;
  int done = 0;
  if (!S_ISREG(sb->st_mode))
    snprintf(err->message, sizeof err->message, "%.900s: not a regular file",
             path);
  else if (glint_image_read(path, &image, err) == GLINT_OK) {
    done = glint_image_width(image) == width &&
           glint_image_height(image) == height;
    if (!done)
      snprintf(err->message, sizeof err->message, "%.900s: a %dx%d image", path,
               glint_image_width(image), glint_image_height(image));
    glint_image_destroy(image);
  }
  return done;
}

int frame_file_kept(const char *path, int frame, int width, int height,
                    int quiet) {
  struct stat sb;
  if (stat(path, &sb) != 0)
    return 0;
  glint_error err;
  int kept = finished_frame(path, &sb, width, height, &err);
  if (kept && !quiet)
    printf("frame %d: %s is there, kept (--resume)\n", frame, path);
  if (!kept)
    cli_error("frame %d: %s, not a finished %dx%d frame: rendered again "
              "(--resume)",
              frame, err.message, width, height);
  return kept;
}

/* Every frame's camera and objects, before any is rendered: a spline can
 * overshoot between valid keys (a scale below 0, a field of view over 180
 * degrees), and a run that found it at frame 2 had written frames 0 and 1
 * over what was there. */
static int check_frames(const glint_scene *scene, const char *scene_name,
                        int first, int last, const glint_animation *anim) {
  int moving = glint_scene_has_motion(scene);
  for (int f = first; f <= last; f++) {
    if (cli_stopped()) { /* (a scene a frame: seconds for 10^4 frames) */
      cli_error("interrupted while checking the frames; no frame was "
                "written");
      return -1;
    }
    double time = (double)(f - anim->first_frame) / anim->fps;
    glint_error err;
    glint_camera camera;
    glint_scene *still = NULL;
    glint_status st = moving
                          ? glint_scene_at_time(scene, time, &still, &err)
                          : glint_scene_camera_at(scene, time, &camera, &err);
    glint_scene_destroy(still);
    if (st) {
      cli_error("%s: frame %d (t = %g s): %s; no frame was written", scene_name,
                f, time, err.message);
      return -1;
    }
  }
  return 0;
}

/* The frames' files told apart by written_file: a table of `room` (a power
 * of two) slots, each a file and the frame written to it (NULL: empty). */
typedef struct frame_target {
  char *file;
  int frame;
} frame_target;

typedef struct frame_targets {
  frame_target *slot;
  size_t room;
} frame_targets;

static uint64_t name_hash(const char *s) {
  uint64_t h = 1469598103934665603u; /* FNV-1a */
  for (; *s; s++)
    h = (h ^ (unsigned char)*s) * 1099511628211u;
  return h;
}

/* Notes that frame f is written to `file`: the table takes it, and
 * INT_MIN; or the earlier frame written there (file stays the caller's). */
static int note_target(frame_targets *t, int f, char *file) {
  size_t i = name_hash(file) & (t->room - 1);
  for (; t->slot[i].file; i = (i + 1) & (t->room - 1))
    if (strcmp(t->slot[i].file, file) == 0)
      return t->slot[i].frame;
  t->slot[i] = (frame_target){file, f};
  return INT_MIN;
}

static void targets_free(frame_targets *t) {
  for (size_t i = 0; t->slot && i < t->room; i++)
    free(t->slot[i].file);
  free(t->slot);
}

/* frame_files_path, noting in `made` the folders it makes. */
static int frame_file(const frame_files *files, int frame, char *path,
                      size_t size, made_folders *made) {
  if (frame_path(path, size, files->name, files->pattern, frame, files->digits))
    return -1;
  return files->pattern ? make_folders(path, made) : 0;
}

/* A refused run's exit status: `status`, or EXIT_INTERRUPTED where Ctrl-C
 * stopped the check. */
static int refusal(int status) {
  return cli_stopped() ? EXIT_INTERRUPTED : status;
}

int frame_files_init(frame_files *files, const glint_scene *scene,
                     const render_options *o, const char *stem,
                     glint_animation *anim) {
  const char *scene_name = o->scene;
  if (!glint_scene_get_animation(scene, anim)) {
    cli_error("%s has no animation: --frames needs an \"animation\" block "
              "(docs/scene-format.md)",
              scene_name);
    return refusal(EXIT_USAGE);
  }
  if (o->first_frame < anim->first_frame || o->last_frame > anim->last_frame) {
    cli_error("--frames %d-%d: %s's animation has frames %d-%d", o->first_frame,
              o->last_frame, scene_name, anim->first_frame, anim->last_frame);
    return refusal(EXIT_USAGE);
  }
  if (check_frames(scene, scene_name, o->first_frame, o->last_frame, anim))
    return refusal(EXIT_USAGE);
  files->name = o->output;
  if (!files->name) {
    /* SCENE.png, read as a pattern: a % of the scene's name as %% */
    size_t n = 0;
    for (const char *c = stem; *c && n + 6 < sizeof files->default_name; c++) {
      if (*c == '%')
        files->default_name[n++] = '%';
      files->default_name[n++] = *c;
    }
    snprintf(files->default_name + n, sizeof files->default_name - n, ".png");
    files->name = files->default_name;
  }
  files->pattern = check_pattern(files->name);
  if (files->pattern < 0)
    return refusal(EXIT_USAGE);
  int digits = snprintf(NULL, 0, "%d", anim->last_frame);
  files->digits = digits < 4 ? 4 : digits;
  char first_path[4096];
  if (frame_path(first_path, sizeof first_path, files->name, files->pattern,
                 o->first_frame, files->digits))
    return refusal(EXIT_USAGE);
  if (glint_image_format_from_path(first_path) == GLINT_FORMAT_UNKNOWN) {
    cli_error("%s: --frames writes .png, .bmp or .ppm images", first_path);
    return refusal(EXIT_USAGE);
  }
  /* -o out/frame%04d.png makes out/ when it is missing (and a pattern
   * whose number is in a folder's name makes that folder for each frame,
   * in frame_files_path). A run refused below takes away the folders it
   * made. */
  made_folders *made = &files->made;
  *made = (made_folders){NULL, 0, 0};
  int refused = make_folders(first_path, made), status = EXIT_USAGE;
  /* Every frame's file can be written, before any is: a folder or a pipe
   * under frame 2's name had frames 0 and 1 written over what was there
   * before the run stopped. A frame --resume keeps is not written; one it
   * renders again (of another size, damaged) is, and was not checked. */
  int width, height;
  frame_size(scene, &o->settings, &width, &height);
  frame_targets targets = {NULL, 16};
  while (targets.room < 2 * ((size_t)o->last_frame - o->first_frame + 1))
    targets.room *= 2;
  if (!refused &&
      !(targets.slot = calloc(targets.room, sizeof *targets.slot))) {
    cli_error("out of memory checking %d frames' files",
              o->last_frame - o->first_frame + 1);
    refused = 1, status = EXIT_MEMORY;
  }
  for (int f = o->first_frame; f <= o->last_frame && !refused; f++) {
    char path[4096];
    struct stat sb;
    glint_error err, why;
    if (cli_stopped()) {
      cli_error("interrupted while checking the frames' files; no frame was "
                "written");
      refused = 1;
      break;
    }
    refused = frame_file(files, f, path, sizeof path, made);
    char *target = refused ? NULL : written_file(path);
    if (!refused && !target) {
      cli_error("out of memory checking frame %d's file", f);
      refused = 1, status = EXIT_MEMORY;
      break;
    }
    int earlier = refused ? INT_MIN : note_target(&targets, f, target);
    if (earlier != INT_MIN) {
      char first[4096];
      if (frame_path(first, sizeof first, files->name, files->pattern, earlier,
                     files->digits) == 0)
        cli_error("frames %d and %d would both be written to %s (as %s and "
                  "%s, through a link); no frame was written",
                  earlier, f, target, first, path);
      free(target);
      refused = 1;
    } else if (!refused && cli_check_output_format(path, scene_name, &err)) {
      cli_error("frame %d: %s; no frame was written", f, err.message);
      refused = 1;
    } else if (!refused && glint_image_check_writable(path, &err) &&
               !(o->resume && stat(path, &sb) == 0 &&
                 finished_frame(path, &sb, width, height, &why))) {
      cli_error("frame %d: %s; no frame was written", f, err.message);
      refused = 1;
    }
  }
  targets_free(&targets);
  if (refused)
    forget_made_folders(made, 1);
  return refused ? refusal(status) : 0;
}

void frame_files_end(frame_files *files, int failed) {
  forget_made_folders(&files->made, failed);
}

int frame_files_path(const frame_files *files, int frame, char *path,
                     size_t size) {
  return frame_file(files, frame, path, size, NULL);
}
