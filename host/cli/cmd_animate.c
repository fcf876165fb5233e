/* SPDX-License-Identifier: Apache-2.0 */
/* cmd_animate.c - 'rtcl animate': the frames of an animated scene, one image
 * each, with the BVHs kept and updated from frame to frame by the meshes'
 * update policies (the way a real-time loop renders). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_anim.h"
#include "cli_util.h"
#include "commands.h"
#include "engines/bench_print.h"
#include "video_out.h"

typedef struct animate_args {
    const char *out, *range;
    double fps, duration;
    int frames, stats, metadata;
    cli_frame_args frame;
    cli_scene_args scene;
    cli_renderer_args renderer;
} animate_args;

static const cli_option animate_options[] = {
    {"--fps", 0, CLI_FLOAT, "F", offsetof(animate_args, fps), 0.0, INFINITY,
     CLI_MIN_OPEN | CLI_REQUIRED, .help = "frames per second: frame k shows time k / F",
     .fallback = "required"},
    {"--duration", 0, CLI_FLOAT, "S", offsetof(animate_args, duration), 0.0, INFINITY, CLI_MIN_OPEN,
     .help = "seconds to render: ceil(S * F) frames; give this or --frames", .fallback = "none"},
    {"--frames", 0, CLI_INT, "N", offsetof(animate_args, frames), 1, 100000000,
     .help = "frames to render (0..N-1); give this or --duration", .fallback = "none"},
    {"--frame-range", 0, CLI_STRING, "A:B", offsetof(animate_args, range),
     .help = "only frames A to B (both included) of those: for splitting a long animation over "
             "machines",
     .fallback = "all"},
    {"--output", 'o', CLI_STRING, "PATTERN|VIDEO", offsetof(animate_args, out),
     .flags = CLI_NONEMPTY | CLI_REQUIRED,
     .help = "output images: a path with one %d conversion (%04d: 4 digits, zero-padded) that "
             "the frame number replaces, format by extension (those of 'rtcl render --help'); or a "
             "path "
             "ending in .mp4, .mkv or .webm: one video of the frames at F frames per second, "
             "encoded by ffmpeg (which must be on PATH; Debian: apt-get install ffmpeg): H.264 "
             "(libx264, CRF 18) in .mp4 and .mkv, else MPEG-4 part 2; VP9 in .webm; 8 bits, "
             "4:2:0 chroma (lossy: use images for exact frames); an odd width or height gets one "
             "black column or row. ffmpeg's messages show only on failure. Checked before any "
             "frame is made; each frame (and the video) is written whole or not at all: a failed "
             "or interrupted write leaves an existing file of that name as it was",
     .fallback = "required"},
    {"--metadata", 0, CLI_FLAG, NULL, offsetof(animate_args, metadata),
     .help = "record the time of writing and the software in PNG and EXR frames (the time "
             "and the file's name in DPX), and the date and a random id in Matroska and WebM "
             "videos (without it equal frames are equal files)"},
    {"--stats", 0, CLI_FLAG, NULL, offsetof(animate_args, stats),
     .help = "one JSON line per frame on stdout: the frame, its time, what each updated mesh's "
             "BVH did (action, ms, SAH cost), object-BVH ms, layout ms and bytes rewritten, "
             "camera_only (true when only the camera moved: no BVH touched, the layout's header "
             "alone rewritten and uploaded), upload bytes (device backends), build ms (all host "
             "work of the frame), render ms, write ms, SAH and backend"},
    {NULL}};

static const cli_group animate_groups[] = {
    {NULL, animate_options, 0},
    {CLI_FRAME_TITLE, cli_frame_options, offsetof(animate_args, frame)},
    {CLI_FRAME_TITLE, cli_sample_options, offsetof(animate_args, frame)},
    {CLI_SCENE_TITLE, cli_scene_options, offsetof(animate_args, scene)},
    {CLI_SCENE_TITLE, cli_update_options, offsetof(animate_args, scene)},
    {CLI_RENDERER_TITLE, cli_renderer_options, offsetof(animate_args, renderer)},
    {CLI_KERNEL_TITLE, cli_kernel_options, offsetof(animate_args, renderer)},
    {CLI_TEST_TITLE, cli_test_options, offsetof(animate_args, renderer)},
    {NULL}};

const cli_command cmd_animate_spec = {
    "animate",
    "render the frames of an animated scene to images or a video",
    "SCENE",
    "scene",
    1,
    1,
    "Renders the frames of an animated scene (docs/SCENE_FORMAT.md, \"Time\"): frame k\n"
    "shows time k / F seconds. One renderer renders them in order, so each frame only\n"
    "updates what moved: the BVHs of meshes whose vertices changed, by their update\n"
    "policy, the object BVH, and the layout in place; a frame where only the camera\n"
    "moved rewrites the camera alone. Every frame is the image that\n"
    "'rtcl render SCENE --time k/F' gives, bit for bit, whatever the policy. A scene\n"
    "without animation is refused (every frame would be the same image).\n"
    "A progress bar appears on stderr when it is a terminal; nothing else is printed\n"
    "unless something fails.\n",
    animate_groups,
    NULL,
    NULL};

/* Checks that pattern has exactly one %d conversion (with an optional 0 flag
 * and width) and no other conversion but %%. */
static int check_pattern(const char *pattern) {
    int conversions = 0;
    for (const char *p = pattern; *p; p++) {
        if (*p != '%') continue;
        if (p[1] == '%') {
            p++;
            continue;
        }
        p++;
        if (*p == '0') p++;
        int digits = 0;
        while (*p >= '0' && *p <= '9' && digits < 3) p++, digits++;
        if (*p != 'd') return 0;
        conversions++;
    }
    return conversions == 1;
}

/* The pattern with its %d replaced by frame (a checked pattern). */
static void frame_name(const char *pattern, int frame, char *out, size_t cap) {
    size_t n = 0;
    for (const char *p = pattern; *p && n + 1 < cap; p++) {
        if (*p != '%') {
            out[n++] = *p;
            continue;
        }
        if (p[1] == '%') {
            out[n++] = '%';
            p++;
            continue;
        }
        p++;
        int zero = 0, width = 0;
        if (*p == '0') zero = 1, p++;
        while (*p >= '0' && *p <= '9') width = width * 10 + (*p++ - '0');
        int w = snprintf(out + n, cap - n, zero ? "%0*d" : "%*d", width, frame);
        if (w > 0) n += (size_t)w < cap - n ? (size_t)w : cap - n - 1;
    }
    out[n < cap ? n : cap - 1] = '\0';
}

static int parse_range(const char *text, int *a, int *b) {
    char *end;
    long x = strtol(text, &end, 10);
    if (end == text || *end != ':' || x < 0 || x > 100000000) return 0;
    const char *q = end + 1;
    long y = strtol(q, &end, 10);
    if (end == q || *end || y < x || y > 100000000) return 0;
    *a = (int)x;
    *b = (int)y;
    return 1;
}

/* The frames to render, from the options: frames 0..count-1 of which
 * first..last, and whether -o names a video. 0 after printing the error. */
typedef struct frame_plan {
    int count, first, last, video;
} frame_plan;

static int plan_frames(const animate_args *a, frame_plan *p) {
    const char *pattern = a->out;
    double fps = a->fps, duration = a->duration > 0.0 ? a->duration : -1.0;
    int frames = a->frames ? a->frames : -1, first = 0, last = -1;
    if (a->range && !parse_range(a->range, &first, &last)) {
        cli_usage_error(&cmd_animate_spec, "--frame-range: '%s' is not A:B with 0 <= A <= B",
                        a->range);
        return 0;
    }
    if (!(fps > 0.0)) {
        cli_usage_error(&cmd_animate_spec, "--fps F is required");
        return 0;
    }
    if ((frames < 0) == (duration < 0.0)) {
        cli_usage_error(&cmd_animate_spec, "give one of --duration S and --frames N");
        return 0;
    }
    if (!pattern) {
        cli_usage_error(&cmd_animate_spec, "-o PATTERN is required (e.g. -o out/frame_%%04d.png)");
        return 0;
    }
    int video = cli_is_video_path(pattern);
    if (video && !cli_have_ffmpeg()) {
        cli_error("animate",
                  "-o %s: writing a video needs ffmpeg, which is not on PATH (Debian: apt-get "
                  "install ffmpeg); or write the frames as images with -o DIR/frame_%%04d.png",
                  pattern);
        return 0;
    }
    if (!video && !check_pattern(pattern)) {
        cli_error("animate",
                  "-o: '%s' must hold exactly one %%d conversion (e.g. frame_%%04d.png) and no "
                  "other %% but %%%%",
                  pattern);
        return 0;
    }
    if (frames < 0) {
        double n = duration * fps;
        frames = n > 100000000.0 ? 100000001 : (int)n;
        if ((double)frames < n) frames++;
        if (frames > 100000000) {
            cli_error("animate", "--duration %g at %g fps is more than 10^8 frames", duration, fps);
            return 0;
        }
    }
    if (last < 0) last = frames - 1;
    if (last >= frames) {
        cli_error("animate", "--frame-range %d:%d: the animation has frames 0..%d", first, last,
                  frames - 1);
        return 0;
    }
    p->count = frames;
    p->first = first;
    p->last = last;
    p->video = video;
    return 1;
}

int cmd_animate(int argc, char **argv) {
    animate_args a;
    memset(&a, 0, sizeof a);
    cli_args_init(&a.frame, &a.scene, &a.renderer);
    int status;
    if (cli_parse(&cmd_animate_spec, &a, argc, argv, &status) < 0) return status;
    frame_plan plan;
    if (!plan_frames(&a, &plan)) return 2;
    const char *scene_path = argv[0], *pattern = a.out;
    const double fps = a.fps;
    const int first = plan.first, last = plan.last, video = plan.video, stats = a.stats;

    /* The output's folder and format are checked before any frame is made. */
    char why[2048], first_name[4096];
    frame_name(pattern, first, first_name, sizeof first_name);
    rt_error oerr;
    if (video ? !cli_video_check(pattern, why, sizeof why)
              : rt_image_check_output(first_name, &oerr) != RT_OK) {
        cli_error("animate", "-o %s: %s", pattern, video ? why : oerr.message);
        return 2;
    }
    /* The frame size is set after the check for an animation, below. */
    cli_session run;
    if (!cli_session_open(&run, "animate", scene_path, &a.renderer, &a.scene, NULL)) return 2;
    rt_renderer *renderer = run.renderer;
    rt_scene *scene = run.scene;
    int code = 0;
    rt_error err;
    if (!rt_scene_is_animated(scene)) {
        cli_error("animate",
                  "%s has no animation (no keyframe rate, transform keys or camera path: "
                  "docs/SCENE_FORMAT.md, \"Time\"), so every frame would be the same image; "
                  "render it once with 'rtcl render'",
                  scene_path);
        code = 2;
    } else if (!cli_apply_frame_size("animate", scene, &a.frame)) {
        code = 2;
    }
    rt_render_options opt = rt_render_options_default();
    opt.direct_only = a.frame.direct;
    opt.samples = a.frame.spp;
    rt_render_stats st;
    opt.stats = &st;
    opt.reuse_framebuffer = 1;
    rt_framebuffer fb;
    memset(&fb, 0, sizeof fb);
    int shown_notice = 0;
    cli_video *vid = NULL;
    for (int k = first; k <= last && !code; k++) {
        double t = (double)k / fps;
        if (rt_scene_set_time(scene, t) != RT_OK) {
            cli_error("animate", "frame %d (time %g s): %s", k, t, rt_scene_error(scene));
            code = 2;
            break;
        }
        if (rt_render(renderer, scene, &opt, &fb) != RT_OK) {
            cli_error("animate", "frame %d: %s", k, rt_renderer_error(renderer));
            code = 2;
            break;
        }
        if (!shown_notice) {
            cli_progress_done();
            cli_print_backend_choice("animate", &a.renderer, st.backend, st.device, st.notice);
            shown_notice = 1;
        }
        double w0 = cli_now_ms();
        if (video) {
            /* The video starts with the first frame, at its size. */
            if (!vid && !(vid = cli_video_open(pattern, fb.width, fb.height, fps, a.metadata, why,
                                               sizeof why))) {
                cli_progress_done();
                cli_error("animate", "-o %s: %s", pattern, why);
                code = 2;
                break;
            }
            if (!cli_video_write(vid, fb.pixels, why, sizeof why)) {
                cli_progress_done();
                cli_error("animate", "-o %s: frame %d: %s", pattern, k, why);
                code = 2;
                break;
            }
        }
        char path[4096];
        frame_name(pattern, k, path, sizeof path);
        rt_image img = {fb.width, fb.height, fb.channels, fb.pixels};
        rt_image_write_options wopt = {a.metadata};
        if (!video && rt_image_write_with(path, &img, &wopt, &err) != RT_OK) {
            cli_progress_done();
            cli_error("animate", "frame %d: %s", k, err.message);
            code = 2;
            break;
        }
        double write_ms = cli_now_ms() - w0;
        if (stats) {
            printf("{\"frame\": %d, \"time\": %.9g, ", k, t);
            cli_print_update_json(renderer, scene);
            printf(", \"upload_bytes\": %llu, \"build_ms\": %.3f, \"render_ms\": %.3f, "
                   "\"write_ms\": %.3f, \"sah\": %.4f, \"backend\": \"%s\", \"device\": ",
                   (unsigned long long)st.upload_bytes, st.build_ms, st.render_ms, write_ms,
                   st.sah_cost, st.backend ? st.backend : "?");
            json_out_string(st.device);
            printf("}\n");
            fflush(stdout);
        }
        cli_progress((void *)"animate", (double)(k - first + 1) / (double)(last - first + 1));
    }
    cli_progress_done();
    if (vid && code == 0 && !cli_video_close(vid, why, sizeof why)) {
        cli_error("animate", "-o %s: %s", pattern, why);
        code = 2;
    } else if (vid && code != 0) {
        cli_video_abort(vid);
    }
    rt_framebuffer_free(&fb);
    cli_session_close(&run);
    return code;
}
