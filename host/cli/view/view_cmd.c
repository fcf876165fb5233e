/* SPDX-License-Identifier: Apache-2.0 */
/* view_cmd.c - 'rtcl view': the command line (built with or without SDL2, so
 * that --help tells the keys and the reason when the viewer is missing). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "frame_image.h"
#include "view.h"
#include "view_keys.h"

static const cli_option view_table[] = {
    {"--play", 0, CLI_FLAG, NULL, offsetof(view_options, play),
     .help = "start with the timeline playing (as if Space was pressed)"},
    {"--keyframe-rate", 0, CLI_FLOAT, "R", offsetof(view_options, keyframe_rate), 0.0, 1000.0,
     CLI_MIN_OPEN,
     .help = "keyframes per second while the timeline plays a scene without animation of its "
             "own (no keyframe rate, transform keys or camera path): objects with several "
             "keyframes show keyframe (k0 + floor(t R)) mod count, k0 the scene file's",
     .fallback = "10"},
    {"--frames", 0, CLI_INT, "N", offsetof(view_options, frames), 1, 100000000,
     .help = "quit after N frames", .fallback = "never: until the window is closed"},
    {"--screenshot", 0, CLI_STRING, "FILE", offsetof(view_options, screenshot),
     .flags = CLI_NONEMPTY,
     .help = "at the end, save the last frame at full resolution (a last full frame is rendered "
             "first if the last one was reduced), as 'rtcl render -o' writes it",
     .fallback = "none"},
    {"--script", 0, CLI_STRING, "FILE", offsetof(view_options, script), .flags = CLI_NONEMPTY,
     .help = "replay timed input (format below); implies --step 33.333 and --move-scale 1 "
             "unless they are given, so that a replay is exact",
     .fallback = "none"},
    {"--step", 0, CLI_FLOAT, "MS", offsetof(view_options, step_ms), 0.0, 10000.0, CLI_MIN_OPEN,
     .help = "advance the camera and the timeline by MS milliseconds per frame instead of by "
             "the real time (replays exactly)",
     .fallback = "the real time"},
    {"--move-scale", 0, CLI_INT, "D", offsetof(view_options, move_divisor), 1, 16,
     .help = "render at 1/D of the resolution while moving (1: never reduce)",
     .fallback = "automatic: the smallest of 1, 2, 3, 4, 6, 8 that fits --budget"},
    {"--budget", 0, CLI_FLOAT, "MS", offsetof(view_options, budget_ms), 0.0, INFINITY, CLI_MIN_OPEN,
     .help = "the frame time the automatic divisor aims at", .fallback = "40"},
    {NULL}};

static const cli_group view_groups[] = {
    {NULL, view_table, 0},
    {CLI_FRAME_TITLE, cli_frame_options, offsetof(view_options, frame)},
    {CLI_FRAME_TITLE, cli_aov_options, offsetof(view_options, frame)},
    {CLI_SCENE_TITLE, cli_scene_options, offsetof(view_options, scene)},
    {CLI_SCENE_TITLE, cli_time_options, offsetof(view_options, scene)},
    /* The viewer starts on the fastest backend there is: --backend auto. */
    {CLI_RENDERER_TITLE, cli_backend_auto_options, offsetof(view_options, renderer)},
    {CLI_RENDERER_TITLE, cli_renderer_options + 1, offsetof(view_options, renderer)},
    {CLI_KERNEL_TITLE, cli_kernel_options, offsetof(view_options, renderer)},
    {CLI_TEST_TITLE, cli_test_options, offsetof(view_options, renderer)},
    {NULL}};

static void print_keys(FILE *f);

const cli_command cmd_view_spec = {
    "view",
    "fly through a scene in a window, switch backends live (SDL2)",
    "SCENE",
    "scene",
    1,
    1,
    "Opens a window on SCENE (a .json scene, a bare .obj, or builtin:NAME) and renders\n"
    "it continuously, presenting each frame when it is done. Rendering runs on its own\n"
    "thread, so the window answers input while a slow backend renders. While the\n"
    "camera moves (or the timeline plays) frames are rendered at a fraction of the\n"
    "resolution when a full frame would take longer than --budget; a still view\n"
    "refines to full resolution. The window title shows frames per second, the frame\n"
    "time split into update (timeline, BVH builds, layout), render and present,\n"
    "Mrays/s, backend and device, whether the backend promises the CPU oracle's bits,\n"
    "triangles, the resolution divisor, the view, the lighting and the scene time.\n"
    "Options may come before or after SCENE; --width and --height also size the\n"
    "window, and --time is the timeline's start. SCENE may also be a .gltf or .glb\n"
    "file; --animation picks the clip its timeline plays.\n",
    view_groups,
    NULL,
    print_keys};

static const char usage_script[] = "\n"
                                   "Keys:\n";

static const char usage_script_format[] =
    "\n"
    "Script files (--script): one event a line, FRAME ACTION [ARGS]; '#' starts a\n"
    "comment. FRAME is the 0-based frame before which the event happens (frames must\n"
    "not decrease); the clock advances --step per frame. Actions:\n"
    "  down KEY         press KEY and hold it (W, A, S, D, R, F, Q, E, Up, Down, Left,\n"
    "                   Right move and turn while held)\n"
    "  up KEY           release KEY\n"
    "  tap KEY          press and release KEY (Space, 1-4, L, V, F12, C, H, Escape,\n"
    "                   PageUp, PageDown)\n"
    "  drag DX DY       drag with the left mouse button by DX, DY pixels (turns)\n"
    "  wheel N          N notches of the mouse wheel (positive: faster)\n"
    "  screenshot FILE  save the first full-resolution frame from this frame on\n"
    "  quit             end the session\n"
    "Example: '0 down W', '15 up W', '15 drag 40 0', '20 tap 2', '20 screenshot a.exr'.\n"
    "Output: C prints the camera and H the keys on stdout; so do backend switches\n"
    "('backend: NAME'), screenshots ('screenshot: FILE ...') and, at the end, a line\n"
    "with the frame count, frames per second and median frame times.\n";

/* The keys, the script format and, without SDL2, why the viewer is missing. */
static void print_keys(FILE *f) {
    fputs(usage_script, f);
    view_keys_print(f, "  ");
    fputs(usage_script_format, f);
    const char *why;
    if (!view_available(&why)) fprintf(f, "\nNote: %s.\n", why);
}

int cmd_view(int argc, char **argv) {
    view_options o;
    memset(&o, 0, sizeof o);
    cli_args_init(&o.frame, &o.scene, &o.renderer);
    o.renderer.backend = "auto";
    o.keyframe_rate = 10.0;
    o.budget_ms = 40.0;
    int status;
    if (cli_parse(&cmd_view_spec, &o, argc, argv, &status) < 0) return status;
    o.scene_path = argv[0];
    /* A script replays exactly: a fixed clock, and no divisor chosen from
     * measured frame times (which would decide which frame is full). */
    if (o.script && !o.step_ms) o.step_ms = 1000.0 / 30.0;
    if (o.script && !o.move_divisor) o.move_divisor = 1;
    /* The screenshot's folder and format are checked before the window
     * opens, not at the end of the session (issue 31). */
    rt_error oerr;
    if (o.screenshot && cli_frame_check(o.screenshot, &oerr) != RT_OK) {
        cli_error("view", "--screenshot: %s", oerr.message);
        return 2;
    }
    return view_run(&o);
}
