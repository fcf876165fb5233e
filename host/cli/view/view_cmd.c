/* view_cmd.c - 'rtcl view': the command line (built with or without SDL2, so
 * that --help tells the keys and the reason when the viewer is missing). */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "frame_image.h"
#include "view.h"
#include "view_keys.h"

static const char usage_head[] =
    "usage: rtcl view SCENE [--backend B] [--device D] [--width W] [--height H] [--time T]\n"
    "                 [--play] [--keyframe-rate R] [--aov AOV] [--direct] [--frames N]\n"
    "                 [--screenshot FILE] [--script FILE] [--step MS] [--move-scale D]\n"
    "                 [--budget MS] [--threads N] [--help]\n"
    "\n"
    "Opens a window on SCENE (a .json scene, a bare .obj, or builtin:NAME) and renders\n"
    "it continuously, presenting each frame when it is done. Rendering runs on its own\n"
    "thread, so the window answers input while a slow backend renders. While the\n"
    "camera moves (or the timeline plays) frames are rendered at a fraction of the\n"
    "resolution when a full frame would take longer than --budget; a still view\n"
    "refines to full resolution. The window title shows frames per second, the frame\n"
    "time split into update (timeline, BVH builds, layout), render and present,\n"
    "Mrays/s, backend and device, whether the backend promises the CPU oracle's bits,\n"
    "triangles, the resolution divisor, the view, the lighting and the scene time.\n"
    "Options may come before or after SCENE.\n"
    "\n"
    "  --width W, --height H\n"
    "                 resolution (and window size), overriding the scene's camera\n"
    "  --time T       scene time at the start, in seconds [0]\n"
    "  --play         start with the timeline playing (as if Space was pressed)\n"
    "  --keyframe-rate R\n"
    "                 keyframes per second while the timeline plays: objects with\n"
    "                 several keyframes show keyframe (k0 + floor(t R)) mod count,\n"
    "                 k0 the scene file's [10]\n"
    "  --aov AOV      start with an AOV shown: depth, normal, primid, instid,\n"
    "                 boxtests, tritests\n"
    "  --direct       start with direct lighting only (primary and shadow rays)\n"
    "  --frames N     quit after N frames\n"
    "  --screenshot FILE\n"
    "                 at the end, save the last frame at full resolution (a last full\n"
    "                 frame is rendered first if the last one was reduced): .png and\n"
    "                 .ppm 8-bit, .exr 32-bit float (AOVs raw), as 'rtcl render -o'\n"
    "  --script FILE  replay timed input (format below); implies --step 33.333 and\n"
    "                 --move-scale 1 unless they are given, so that a replay is exact\n"
    "  --step MS      advance the camera and the timeline by MS milliseconds per\n"
    "                 frame instead of by the real time (replays exactly)\n"
    "  --move-scale D render at 1/D of the resolution while moving (1: never\n"
    "                 reduce) [automatic: the smallest of 1, 2, 3, 4, 6, 8 that fits\n"
    "                 --budget]\n"
    "  --budget MS    frame time the automatic divisor aims at [40]\n";

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

static void print_usage(FILE *f) {
    fputs(usage_head, f);
    fputs(cli_renderer_usage, f);
    fputs(usage_script, f);
    view_keys_print(f, "  ");
    fputs(usage_script_format, f);
    const char *why;
    if (!view_available(&why)) fprintf(f, "\nNote: %s.\n", why);
}

int cmd_view(int argc, char **argv) {
    view_options o;
    memset(&o, 0, sizeof o);
    cli_renderer_args_init(&o.renderer);
    o.keyframe_rate = 10.0;
    o.budget_ms = 40.0;
    int step_given = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v;
        int taken = cli_renderer_arg(argc, argv, &i, "view", &o.renderer);
        if (taken < 0) return 2;
        if (taken) continue;
        double x;
        int n;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            print_usage(stdout);
            return 0;
        } else if (!strcmp(a, "--width") || !strcmp(a, "--height")) {
            if (!(v = cli_value(argc, argv, &i, "view")) || !cli_int("view", a, v, 1, 16384, &n))
                return 2;
            if (a[2] == 'w')
                o.width = n;
            else
                o.height = n;
        } else if (!strcmp(a, "--time")) {
            if (!(v = cli_value(argc, argv, &i, "view")) || !cli_float("view", a, v, &o.time))
                return 2;
        } else if (!strcmp(a, "--play")) {
            o.play = 1;
        } else if (!strcmp(a, "--keyframe-rate")) {
            if (!(v = cli_value(argc, argv, &i, "view")) || !cli_float("view", a, v, &x)) return 2;
            if (!(x > 0.0 && x <= 1000.0)) {
                cli_error("view", "--keyframe-rate: %s is not in (0, 1000]", v);
                return 2;
            }
            o.keyframe_rate = x;
        } else if (!strcmp(a, "--aov")) {
            if (!(v = cli_value(argc, argv, &i, "view"))) return 2;
            if (!cli_parse_aov(v, &o.aov)) {
                cli_error("view",
                          "unknown AOV '%s' (depth, primid, instid, normal, boxtests, tritests)",
                          v);
                return 2;
            }
        } else if (!strcmp(a, "--direct")) {
            o.direct_only = 1;
        } else if (!strcmp(a, "--frames")) {
            if (!(v = cli_value(argc, argv, &i, "view")) ||
                !cli_int("view", a, v, 1, 100000000, &n))
                return 2;
            o.frames = n;
        } else if (!strcmp(a, "--screenshot")) {
            if (!(o.screenshot = cli_value(argc, argv, &i, "view"))) return 2;
        } else if (!strcmp(a, "--script")) {
            if (!(o.script = cli_value(argc, argv, &i, "view"))) return 2;
        } else if (!strcmp(a, "--step")) {
            if (!(v = cli_value(argc, argv, &i, "view")) || !cli_float("view", a, v, &x)) return 2;
            if (!(x > 0.0 && x <= 10000.0)) {
                cli_error("view", "--step: %s is not in (0, 10000] milliseconds", v);
                return 2;
            }
            o.step_ms = x;
            step_given = 1;
        } else if (!strcmp(a, "--move-scale")) {
            if (!(v = cli_value(argc, argv, &i, "view")) || !cli_int("view", a, v, 1, 16, &n))
                return 2;
            o.move_divisor = n;
        } else if (!strcmp(a, "--budget")) {
            if (!(v = cli_value(argc, argv, &i, "view")) || !cli_float("view", a, v, &x)) return 2;
            if (!(x > 0.0)) {
                cli_error("view", "--budget: %s is not a positive number of milliseconds", v);
                return 2;
            }
            o.budget_ms = x;
        } else if (a[0] == '-' && a[1]) {
            cli_error("view", "unknown option '%s'", a);
            print_usage(stderr);
            return 2;
        } else if (o.scene_path) {
            cli_error("view", "more than one scene given ('%s' and '%s')", o.scene_path, a);
            return 2;
        } else {
            o.scene_path = a;
        }
    }
    if (!o.scene_path) {
        cli_error("view", "no scene given");
        print_usage(stderr);
        return 2;
    }
    /* A script replays exactly: a fixed clock, and no divisor chosen from
     * measured frame times (which would decide which frame is full). */
    if (o.script && !step_given) o.step_ms = 1000.0 / 30.0;
    if (o.script && !o.move_divisor) o.move_divisor = 1;
    return view_run(&o);
}
