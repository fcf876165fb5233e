/* cmd_animate.c - 'rtcl animate': the frames of an animated scene, one image
 * each, with the BVHs kept and updated from frame to frame by the meshes'
 * update policies (the way a real-time loop renders). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "cli_anim.h"
#include "cli_util.h"
#include "commands.h"
#include "formats/image.h"
#include "video_out.h"

static const char usage_head[] =
    "usage: rtcl animate SCENE --fps F (--duration S | --frames N) [--frame-range A:B]\n"
    "                    -o DIR/frame_%04d.png|VIDEO.mp4 [--update P] [--backend B] [--width W]\n"
    "                    [--height H] [--direct] [--stats] [--help]\n"
    "\n"
    "Renders the frames of an animated scene (docs/SCENE_FORMAT.md, \"Time\"): frame k\n"
    "shows time k / F seconds. One renderer renders them in order, so each frame only\n"
    "updates what moved: the BVHs of meshes whose vertices changed, by their update\n"
    "policy, the object BVH, and the layout in place; a frame where only the camera\n"
    "moved rewrites the camera alone. Every frame is the image that\n"
    "'rtcl render SCENE --time k/F' gives, bit for bit, whatever the policy.\n"
    "\n"
    "  --fps F        frames per second (> 0)\n"
    "  --duration S   seconds to render: ceil(S * F) frames\n"
    "  --frames N     frames to render (0..N-1)\n"
    "  --frame-range A:B\n"
    "                 only frames A to B (both included) of those: for splitting a long\n"
    "                 animation over machines [all]\n"
    "  -o PATTERN     output images, a path with one %d conversion (%04d: 4 digits,\n"
    "                 zero-padded) that the frame number replaces; format by extension\n"
    "  -o VIDEO       a path ending in .mp4, .mkv or .webm: one video of the frames at\n"
    "                 F frames per second, encoded by ffmpeg (which must be on PATH;\n"
    "                 Debian: apt-get install ffmpeg): H.264 (libx264, CRF 18) in .mp4\n"
    "                 and .mkv, else MPEG-4 part 2; VP9 in .webm; 8 bits, 4:2:0 chroma\n"
    "                 (lossy: use images for exact frames); an odd width or height gets\n"
    "                 one black column or row. ffmpeg's messages show only on failure\n"
    "  --update P     every mesh's BVH update policy: sah, refit, lbvh, auto\n"
    "                 [the scene's, sah where it says none]\n"
    "  --width W, --height H\n"
    "                 resolution, overriding the scene's camera\n"
    "  --direct       primary and shadow rays only, no reflection or refraction\n"
    "  --stats        one JSON line per frame on stdout: the frame, its time, what\n"
    "                 each updated mesh's BVH did (action, ms, SAH cost), object-BVH ms,\n"
    "                 layout ms and bytes rewritten, camera_only (true when only the\n"
    "                 camera moved: no BVH touched, the layout's header alone rewritten\n"
    "                 and uploaded), upload bytes (device backends), build ms (all host\n"
    "                 work of the frame), render ms\n"
    "A progress bar appears on stderr when it is a terminal; nothing else is printed\n"
    "unless something fails.\n";

static void print_usage(FILE *f) {
    fputs(usage_head, f);
    fputs(cli_renderer_usage, f);
}

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

int cmd_animate(int argc, char **argv) {
    const char *scene_path = NULL, *pattern = NULL, *v;
    rt_render_options opt = rt_render_options_default();
    cli_renderer_args ra;
    cli_renderer_args_init(&ra);
    int width = 0, height = 0, stats = 0, frames = -1, first = 0, last = -1, has_update = 0;
    double fps = 0.0, duration = -1.0;
    rt_update_policy update = RT_UPDATE_SAH;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int taken = cli_renderer_arg(argc, argv, &i, "animate", &ra);
        if (taken < 0) return 2;
        if (taken) continue;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            print_usage(stdout);
            return 0;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (!(pattern = cli_value(argc, argv, &i, "animate"))) return 2;
        } else if (!strcmp(a, "--fps")) {
            if (!(v = cli_value(argc, argv, &i, "animate")) || !cli_float("animate", a, v, &fps))
                return 2;
            if (!(fps > 0.0)) {
                cli_error("animate", "--fps: must be > 0, found %s", v);
                return 2;
            }
        } else if (!strcmp(a, "--duration")) {
            if (!(v = cli_value(argc, argv, &i, "animate")) ||
                !cli_float("animate", a, v, &duration))
                return 2;
            if (!(duration > 0.0)) {
                cli_error("animate", "--duration: must be > 0, found %s", v);
                return 2;
            }
        } else if (!strcmp(a, "--frames")) {
            if (!(v = cli_value(argc, argv, &i, "animate")) ||
                !cli_int("animate", a, v, 1, 100000000, &frames))
                return 2;
        } else if (!strcmp(a, "--frame-range")) {
            if (!(v = cli_value(argc, argv, &i, "animate"))) return 2;
            if (!parse_range(v, &first, &last)) {
                cli_error("animate", "--frame-range: '%s' is not A:B with 0 <= A <= B", v);
                return 2;
            }
        } else if (!strcmp(a, "--update")) {
            if (!(v = cli_value(argc, argv, &i, "animate")) ||
                !cli_update_policy("animate", v, &update))
                return 2;
            has_update = 1;
        } else if (!strcmp(a, "--width")) {
            if (!(v = cli_value(argc, argv, &i, "animate")) ||
                !cli_int("animate", a, v, 1, 32768, &width))
                return 2;
        } else if (!strcmp(a, "--height")) {
            if (!(v = cli_value(argc, argv, &i, "animate")) ||
                !cli_int("animate", a, v, 1, 32768, &height))
                return 2;
        } else if (!strcmp(a, "--direct")) {
            opt.direct_only = 1;
        } else if (!strcmp(a, "--stats")) {
            stats = 1;
        } else if (a[0] == '-' && a[1]) {
            cli_error("animate", "unknown option '%s'", a);
            print_usage(stderr);
            return 2;
        } else if (scene_path) {
            cli_error("animate", "more than one scene given ('%s' and '%s')", scene_path, a);
            return 2;
        } else {
            scene_path = a;
        }
    }
    if (!scene_path) {
        cli_error("animate", "no scene given");
        print_usage(stderr);
        return 2;
    }
    if (!(fps > 0.0)) {
        cli_error("animate", "--fps F is required");
        return 2;
    }
    if ((frames < 0) == (duration < 0.0)) {
        cli_error("animate", "give one of --duration S and --frames N");
        return 2;
    }
    if (!pattern) {
        cli_error("animate", "-o PATTERN is required (e.g. -o out/frame_%%04d.png)");
        return 2;
    }
    int video = cli_is_video_path(pattern);
    if (video && !cli_have_ffmpeg()) {
        cli_error("animate",
                  "-o %s: writing a video needs ffmpeg, which is not on PATH (Debian: apt-get "
                  "install ffmpeg); or write the frames as images with -o DIR/frame_%%04d.png",
                  pattern);
        return 2;
    }
    if (!video && !check_pattern(pattern)) {
        cli_error("animate",
                  "-o: '%s' must hold exactly one %%d conversion (e.g. frame_%%04d.png) and no "
                  "other %% but %%%%",
                  pattern);
        return 2;
    }
    if (frames < 0) {
        double n = duration * fps;
        frames = n > 100000000.0 ? 100000001 : (int)n;
        if ((double)frames < n) frames++;
        if (frames > 100000000) {
            cli_error("animate", "--duration %g at %g fps is more than 10^8 frames", duration, fps);
            return 2;
        }
    }
    if (last < 0) last = frames - 1;
    if (last >= frames) {
        cli_error("animate", "--frame-range %d:%d: the animation has frames 0..%d", first, last,
                  frames - 1);
        return 2;
    }

    rt_renderer *renderer = cli_renderer_create("animate", &ra);
    if (!renderer) return 2;
    rt_scene *scene;
    rt_error err;
    if (cli_load_scene(scene_path, &scene, &err) != RT_OK) {
        cli_error("animate", "%s", err.message);
        rt_renderer_destroy(renderer);
        return 2;
    }
    int code = 0;
    rt_camera cam;
    rt_camera_get(scene, &cam);
    if (width) cam.width = width;
    if (height) cam.height = height;
    if (rt_camera_set(scene, &cam) != RT_OK) {
        cli_error("animate", "%s", rt_scene_error(scene));
        code = 2;
    }
    if (has_update) cli_apply_update(scene, update);
    rt_render_stats st;
    opt.stats = &st;
    opt.reuse_framebuffer = 1;
    rt_framebuffer fb;
    memset(&fb, 0, sizeof fb);
    int shown_notice = 0;
    cli_video *vid = NULL;
    char why[2048];
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
        if (st.notice && !shown_notice) {
            cli_progress_done();
            fprintf(stderr, "rtcl animate: notice: %s\n", st.notice);
            shown_notice = 1;
        }
        double w0 = rt_now_ms();
        if (video) {
            /* The video starts with the first frame, at its size. */
            if (!vid &&
                !(vid = cli_video_open(pattern, fb.width, fb.height, fps, why, sizeof why))) {
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
        if (!video && rt_image_write(path, &img, &err) != RT_OK) {
            cli_progress_done();
            cli_error("animate", "frame %d: %s", k, err.message);
            code = 2;
            break;
        }
        double write_ms = rt_now_ms() - w0;
        if (stats) {
            printf("{\"frame\": %d, \"time\": %.9g, ", k, t);
            cli_print_update_json(renderer, scene);
            printf(", \"upload_bytes\": %llu, \"build_ms\": %.3f, \"render_ms\": %.3f, "
                   "\"write_ms\": %.3f, \"sah\": %.4f, \"backend\": \"%s\"}\n",
                   (unsigned long long)st.upload_bytes, st.build_ms, st.render_ms, write_ms,
                   st.sah_cost, st.backend ? st.backend : "?");
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
    rt_scene_destroy(scene);
    rt_renderer_destroy(renderer);
    return code;
}
