#ifndef GLINT_CLI_CLI_H
#define GLINT_CLI_CLI_H

#include <glint.h>

#include <stddef.h>

/* Each command in two steps: parse its arguments (which reads no file and
 * starts nothing; fuzz/fuzz_cli.c runs them alone), then run. A parser
 * returns -1 to go on, or the exit status to end with (0 after --help; 2
 * after printing what is wrong). */
int cmd_render(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_compare(int argc, char **argv);

typedef struct render_options {
  const char *scene; /* a built-in's name or a file */
  char *output;      /* NULL: SCENE.png; "-": standard output */
  int to_stdout, quiet, stats;
  int frames, first_frame, last_frame; /* --frames A[-B] */
  int resume;                          /* --resume */
  glint_png_compression png_compression;
  int png_compression_given;
  glint_image_format stream_format; /* with -o - */
  glint_render_settings settings;
} render_options;
int render_parse(int argc, char **argv, render_options *options);
/* glint render --frames: the animation's frames, one file each
 * (cli/render_frames.c). Takes the scene. */
int render_frames(struct glint_scene *scene, const render_options *options,
                  const char *stem);

/* The files of an animation's frames (cli/animation_frames.c), for
 * glint render --frames and glint-mpi. */
/* The folders a run made, so that a run that fails can take them away. */
typedef struct made_folders {
  char **paths;
  size_t count, room;
} made_folders;
typedef struct frame_files {
  const char *name; /* -o, or SCENE.png */
  char default_name[300];
  int pattern;       /* name has a %d */
  int digits;        /* without one: the number's width */
  made_folders made; /* by frame_files_init, for frame_files_end */
} frame_files;
/* Checks that `scene` has an animation holding o's --frames, and o's -o (a
 * pattern with one %d, or an image name to put a number in), and makes the
 * output's folder; 0, or after a message the exit status: EXIT_USAGE when
 * something is wrong, EXIT_MEMORY when memory ran out, EXIT_INTERRUPTED
 * when Ctrl-C stopped the check. */
int frame_files_init(frame_files *files, const struct glint_scene *scene,
                     const render_options *o, const char *stem,
                     glint_animation *animation);
/* Ends a run of frames: when it `failed` (an error, Ctrl-C), the folders
 * frame_files_init made that are still empty go (a Ctrl-C left one for
 * each frame of -o out/%d/f.png), the deepest first; those holding a
 * written frame stay. */
void frame_files_end(frame_files *files, int failed);
/* The file of `frame` (making its folder when the number names one); -1
 * after a message when the name is too long or the folder cannot be made. */
int frame_files_path(const frame_files *files, int frame, char *path,
                     size_t size);
/* The size of the frames' images: the region's, else -W/-H or the
 * scene's own. */
void frame_size(const struct glint_scene *scene,
                const glint_render_settings *settings, int *width, int *height);
/* Whether `path` holds a finished frame already (--resume keeps it): an
 * image glint reads, of the frame's size; says which, or why a file there
 * is rendered again. */
int frame_file_kept(const char *path, int frame, int width, int height,
                    int quiet);
/* Commits `scene` at `time` and gives the renderer that world: for
 * animations whose objects move. `*last` is the last frame's world (NULL at
 * first), whose BVH is refitted; it is replaced by this frame's, which the
 * caller destroys after the last frame. 0 on success. */
int cli_world_at(const struct glint_scene *scene, double time,
                 glint_renderer *renderer, glint_world **last,
                 glint_error *error);

typedef struct view_options {
  const char *scene;
  glint_render_settings settings; /* width, height 0: the scene's */
  int benchmark_frames;           /* 0: interactive */
  double budget_ms;               /* a moving frame's time before the
                                     resolution is lowered */
  const char *script_path;        /* --script: input from a file */
} view_options;
int view_parse(int argc, char **argv, view_options *options);
/* The window (cli/view_window.c, in the program glint-view). */
int view_run(const view_options *options);
/* glint view: runs glint-view, from the folder of this program, with the
 * same arguments; returns only when it cannot (saying why). */
int cmd_view(int argc, char **argv);

typedef struct compare_options {
  const char *files[2];
  char *diff_path;
  double min_psnr;
} compare_options;
int compare_parse(int argc, char **argv, compare_options *options);

/* Whether a scene operand names a file: it has a '.' or a '/', or it is no
 * built-in scene's name and a file of that name exists (read as a file, it
 * is refused as one; it was called an unknown built-in scene). */
int cli_scene_is_file(const char *arg);
/* The name a scene's outputs take: the file's base name without its
 * extension, and without .gz before it (scene.json.gz: scene, as for
 * scene.json); a built-in scene's name. */
void cli_scene_stem(const char *arg, char *stem, size_t size);
/* Room for any stem: a file's base name has at most 255 bytes (a stem cut
 * shorter made two scenes one in bench's tables and plots). */
#define CLI_STEM_SIZE 256
/* Loads a built-in scene by name, or a scene file when the argument names
 * one (cli_scene_is_file); prints one message and returns NULL on
 * error, with the exit status in *exit_code (EXIT_MEMORY or EXIT_USAGE).
 * `stem` receives the name to derive an output file from. An animated scene
 * comes still, as its first frame (glint_scene_at_time at 0) ... */
struct glint_scene *cli_load_scene(const char *arg, char *stem,
                                   unsigned long stem_size, int *exit_code);
/* ... or, from this one, with its animation. */
struct glint_scene *cli_load_animation(const char *arg, char *stem,
                                       unsigned long stem_size, int *exit_code);

/* Finished tiles into an image writer, which encodes while the rest of the
 * frame renders (a glint_tile_fn; the origin is the region's, as tiles come
 * in frame pixels). A failed put (a full disk) keeps its error here and
 * cancels the frame. */
typedef struct cli_tile_sink {
  glint_image_writer *writer;
  int origin_x, origin_y;
  int failed;
  glint_error error;
} cli_tile_sink;
int cli_tile_to_writer(void *user, const glint_tile *tile);

/* Whether `path` names a linear film (.pfm, .exr) rather than an 8-bit
 * image. */
int cli_is_film_path(const char *path);
/* Whether `path`'s extension names something glint render writes (an
 * 8-bit image or a film) and it is neither the file `scene` (NULL: none)
 * nor a link to a scene or mesh file (files.h, links_to_input), which the
 * image would replace. Otherwise fills `err` with the choices or the
 * problem. */
glint_status cli_check_output_format(const char *path, const char *scene,
                                     glint_error *err);

/* A note on stderr when the hit tolerance (glint_scene_get_scale) reaches
 * half the smallest object's size: one far or huge object (a sky sphere, a
 * ground sphere of radius 1e5, a distant sun) then hides or spoils the
 * rest, and the image shows it without a word. The SPD scenes reach a
 * quarter (tree-s4), and get none. */
void cli_note_scale(const char *arg, const glint_scene *scene);

/* SIGINT, SIGTERM and SIGHUP end the process at once, with a message and
 * exit status 130, until cli_catch_stop_signals: while a scene loads and
 * its BVH builds (neither can be cancelled) and before any file is
 * created. Called by every program but glint-mpi, which stops its ranks
 * its own way. */
void cli_end_on_stop_signals(void);
/* SIGINT, SIGTERM and SIGHUP only take note from then on; cli_stopped says
 * whether one came (cancel, say so, exit 130). */
void cli_catch_stop_signals(void);
int cli_stopped(void);
/* A stop signal ends the process STOP_GRACE seconds later if the render has
 * not ended by then (cli/render_cmd.c), removing `writer`'s temporary file
 * (NULL: none); while `finishing` (a rendered image being written), it
 * lets the process go on. */
void cli_remove_on_stop(const glint_image_writer *writer);
void cli_stop_finishing(int finishing);

/* Seconds on a monotonic clock, for timing stages. */
double cli_now(void);

/* Peak resident set size of this process, in MiB. */
double cli_peak_rss_mib(void);

#endif
