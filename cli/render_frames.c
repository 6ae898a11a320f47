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

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int on_progress(void *user, double fraction) {
  (void)user;
  (void)fraction;
  return cli_stopped(); /* Ctrl-C cancels the frame */
}

int render_frames(glint_scene *scene, const render_options *o,
                  const char *stem) {
  glint_error err;
  glint_animation anim;
  frame_files files;
  /* Ctrl-C from here: checking 10^5 frames' files takes a while */
  cli_catch_stop_signals();
  int refused = frame_files_init(&files, scene, o, stem, &anim);
  if (refused) {
    glint_scene_destroy(scene);
    return refused;
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
    frame_files_end(&files, 1);
    return cli_exit_code(err.status);
  }
  glint_world_destroy(world);
  int w, h;
  frame_size(scene, rs, &w, &h);

  /* Objects that move need a world a frame; a camera alone does not. */
  int moving = glint_scene_has_motion(scene);
  glint_world *last_world = NULL; /* the last frame's: its BVH is refitted */
  int status = 0, rendered = 0, kept = 0;
  double render_seconds = 0, frame_seconds = 0;
  for (int f = o->first_frame; f <= o->last_frame && !status; f++) {
    char path[4096];
    if (cli_stopped()) { /* (--resume reading the kept frames: ms each) */
      cli_error("interrupted before frame %d; frames written stay, and "
                "--resume renders the rest",
                f);
      status = EXIT_INTERRUPTED;
      break;
    }
    if (frame_files_path(&files, f, path, sizeof path)) {
      status = EXIT_USAGE;
      break;
    }
    if (o->resume && frame_file_kept(path, f, w, h, o->quiet)) {
      kept++;
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
        (moving && cli_world_at(scene, time, renderer, &last_world, &err)) ||
        glint_image_writer_open(path, w, h, rs->gamma, o->png_compression,
                                &sink.writer, &err)) {
      cli_error("frame %d: %s", f, err.message);
      status = cli_exit_code(err.status);
      break;
    }
    cli_remove_on_stop(sink.writer);
    cli_stop_finishing(0);
    glint_status rst = glint_renderer_render(renderer, &frame, NULL, &st, &err);
    cli_stop_finishing(1);
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
      status = cli_exit_code(sink.failed ? sink.error.status : rst);
      break;
    }
    if (glint_image_writer_finish(sink.writer, &err)) {
      cli_error("frame %d: %s", f, err.message);
      status = cli_exit_code(err.status);
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
  glint_world_destroy(last_world);
  glint_scene_destroy(scene);
  frame_files_end(&files, status != 0);
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
