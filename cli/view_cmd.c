/* glint view [SCENE] [options]: an interactive window onto a scene (SDL2).
 * This file holds its help and its option parser; the window is the
 * program glint-view (cli/view_main.c, cli/view_window.c), which `glint
 * view` runs, so that the glint program itself does not load SDL2 and the
 * dozens of libraries it brings (they cost every glint command about 7 ms
 * to start).
 *
 * One committed world and one renderer serve every frame (include/glint.h,
 * "Worlds and renderers"). While the camera moves each frame is one sample
 * per pixel (sample 0 of the pattern), at a resolution scale lowered
 * automatically when a frame would overrun its budget; once it stops, the
 * frame refines pass by pass, sample k of the spp-sample pattern
 * (docs/specification.md §5: the first five are the thesis's) averaged in,
 * until spp samples are in, and then nothing is rendered: an idle window
 * waits for events and uses no CPU. Screenshots are rendered by glint_render
 * itself, the path of `glint render`, so they equal what it writes. */
#include "args.h"
#include "cli.h"

#include <glint.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void view_usage(FILE *f) {
  fputs(
      "Usage: glint view [SCENE] [options]\n"
      "\n"
      "Opens SCENE (a built-in scene or a scene file, as for glint render) in\n"
      "a window and renders it while you move around it. A scene file is\n"
      "reloaded whenever it changes on disk, keeping the camera.\n"
      "\n"
      "Options:\n"
      "  -W, --width N        window width in pixels (default: the scene's)\n"
      "  -H, --height N       window height in pixels (default: the "
      "scene's)\n"
      "  -s, --spp N          samples per pixel to refine to, 1..4096\n"
      "                       (default: 5)\n"
      "  -d, --depth N        recursion depth, 1..64 (default: 5)\n"
      "  -b, --backend NAME   as for glint render (default: auto)\n"
      "  -t, --threads N      worker threads; 0 = every CPU (default: 0)\n"
      "      --math NAME      minimax, fast, taylor, exact (default: "
      "minimax)\n"
      "      --no-newton      skip the Newton step after rcp\n"
      "      --accel NAME     bvh, bvh2, bvh8, none (default: bvh)\n"
      "      --gamma G        display and screenshot gamma, 0.01..100\n"
      "                       (default: 1)\n"
      "      --budget MS      frame time while moving before the resolution\n"
      "                       is lowered, more than 1 (default: 40)\n"
      "      --benchmark N    fly the benchmark path for N frames without\n"
      "                       input and print frame-time percentiles, fps and\n"
      "                       Mrays/s (works without a display)\n"
      "      --script FILE    input from FILE, one command a line, before\n"
      "                       the frames it concerns (see below)\n"
      "  -h, --help           this help\n"
      "\n"
      "Controls:\n"
      "  left drag            orbit around the point looked at\n"
      "  middle drag, Shift+left drag   pan\n"
      "  right drag, wheel    dolly towards or away from it\n"
      "  W A S D, Q E         fly forward, left, back, right, down, up\n"
      "  arrows               turn\n"
      "  PgUp PgDn            fly faster, slower\n"
      "  R                    back to the scene's camera\n"
      "  F                    fullscreen on or off\n"
      "  1-9                  depth\n"
      "  B                    next backend this CPU has\n"
      "  M                    next maths variant\n"
      "  [ ]                  lower, raise the resolution scale\n"
      "  H                    on-screen display on or off\n"
      "  F1                   these controls on screen\n"
      "  P                    print the camera as JSON for a scene file\n"
      "  Space, F12           screenshot: SCENE-NNNN.png, rendered as glint\n"
      "                       render renders (never overwrites a file)\n"
      "  Esc, Ctrl+Q          quit (Q alone flies down)\n"
      "\n"
      "Flying moves half the distance to the point looked at per second;\n"
      "dragging across the window's width orbits 0.3 degrees a pixel.\n"
      "\n"
      "A --script FILE holds commands run in order, each before the next\n"
      "frame (# starts a comment):\n"
      "  key NAME             press and release a key (SDL's key names:\n"
      "                       p, space, escape, f1, 3, [, ...)\n"
      "  hold NAME SECONDS    hold a key down (flying, turning; SECONDS\n"
      "                       here and in sleep: 0..3600)\n"
      "  drag BUTTON DX DY    drag by DX, DY pixels with left, middle,\n"
      "                       right or shift-left\n"
      "  wheel N              turn the wheel N notches (away: positive)\n"
      "  resize W H           resize the window (pixels and notches are\n"
      "                       whole numbers)\n"
      "  wait                 until the image is refined to its spp (an\n"
      "                       error after 60 s)\n"
      "  sleep SECONDS        let time pass, frames or not\n"
      "  copy FROM TO         copy a file (to change the scene on disk)\n"
      "  print camera|state   the camera as JSON (as P); or the frames\n"
      "                       rendered, samples, depth, scale, backend\n"
      "  capture FILE         write what the window shows (.png, .bmp, .ppm)\n"
      "  quit                 end, as Esc does (without it the window\n"
      "                       stays, where there is one to show)\n"
      "\n"
      "The benchmark path orbits the scene's look-at point once, at the\n"
      "camera's distance and height, in N equal steps; each frame is one\n"
      "sample per pixel at full resolution, as while flying. Without a\n"
      "display, the benchmark and a script run on SDL's dummy video driver.\n",
      f);
}

int view_parse(int argc, char **argv, view_options *o) {
  memset(o, 0, sizeof *o);
  glint_render_settings_default(&o->settings);
  o->budget_ms = 40;
  glint_render_settings *rs = &o->settings;
  arg_cursor c = {argc, argv, 0, NULL};
  while (c.i < argc) {
    if (arg_is_help(&c)) {
      view_usage(stdout);
      return 0;
    }
    int r;
    if ((r = arg_render_setting(&c, rs)) || (r = arg_backend(&c, rs)) ||
        (r = arg_int(&c, "-d", "--depth", 1, GLINT_MAX_DEPTH,
                     &rs->max_depth)) ||
        (r = arg_int(&c, "-t", "--threads", 0, GLINT_MAX_THREADS,
                     &rs->threads)) ||
        (r = arg_int(&c, NULL, "--benchmark", 1, 1000000,
                     &o->benchmark_frames))) {
      if (r == ARG_BAD)
        return EXIT_USAGE;
      continue;
    }
    if (arg_is(&c, NULL, "--gamma")) {
      if (parse_gamma("--gamma", arg_value(&c, "--gamma"), &rs->gamma))
        return EXIT_USAGE;
    } else if (arg_is(&c, NULL, "--script")) {
      if (!(o->script_path = arg_value(&c, "--script")))
        return EXIT_USAGE;
    } else if (arg_is(&c, NULL, "--budget")) {
      if (parse_double("--budget", arg_value(&c, "--budget"), 1, &o->budget_ms))
        return EXIT_USAGE;
    } else if (arg_scene_operand(&c, "view", &o->scene) == ARG_BAD) {
      return EXIT_USAGE;
    }
  }
  if (o->benchmark_frames && o->script_path) {
    /* the benchmark flies its own orbit: the script was ignored */
    cli_error("--benchmark and --script each drive the view: choose one");
    return EXIT_USAGE;
  }
  if (!o->scene)
    o->scene = "whitted";
  return -1;
}
