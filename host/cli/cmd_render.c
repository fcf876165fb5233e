/* cmd_render.c - 'rtcl render': a scene to an image or an AOV. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_anim.h"
#include "cli_util.h"
#include "commands.h"
#include "frame_image.h"

static const char usage_head[] =
    "usage: rtcl render SCENE [-o FILE] [--backend B] [--device D] [--width W] [--height H]\n"
    "                   [--aov AOV] [--threads N] [--frames N] [--direct] [--time T]\n"
    "                   [--update P] [--accel A]\n"
    "                   [--cl-options OPTS] [--packet-isa I] [--stats] [--verbose] [--help]\n"
    "\n"
    "Renders SCENE (a .json scene, a bare .obj, or builtin:NAME) with Whitted-style\n"
    "shading (Phong, shadow rays, reflection, refraction). Options may come before or\n"
    "after SCENE.\n"
    "\n"
    "  -o FILE        output image, format by extension: .png, .ppm (8-bit, clamped),\n"
    "                 .exr (32-bit float, linear) [out.png]\n"
    "  --width W, --height H\n"
    "                 resolution, overriding the scene's camera\n"
    "  --aov AOV      write an arbitrary output variable instead of the image:\n"
    "                 depth, primid, instid, normal, boxtests, tritests. In EXR the raw\n"
    "                 values; in PNG/PPM depth and counters scaled to [0,1] by their\n"
    "                 maximum, ids in false colour, normals as 0.5 + 0.5 n\n"
    "  --frames N     render N frames in one process and print the first frame's\n"
    "                 time and the min and median of the others (a benchmark) [1]\n"
    "  --direct       primary and shadow rays only, no reflection or refraction\n"
    "                 (the thesis's benchmark set-up)\n"
    "  --time T       the scene at time T seconds (animation, transform_keys and the\n"
    "                 camera path, docs/SCENE_FORMAT.md) [0]\n"
    "  --update P     every mesh's BVH update policy: sah, refit, lbvh, auto\n"
    "                 (a single frame builds afresh whatever the policy) [the scene's]\n"
    "  --stats        print BVH cost, box and triangle tests per ray and render time;\n"
    "                 for opencl and vulkan also the device, kernel specialisation\n"
    "                 (-D switches, specialization constants), compile, upload\n"
    "                 (bytes), per-kernel (vulkan: timestamp queries) and download\n"
    "                 times\n";

static void print_usage(FILE *f) {
    fputs(usage_head, f);
    fputs(cli_renderer_usage, f);
}

static void print_stats(const rt_render_stats *s, int width, int height) {
    double rays = (double)(s->rays ? s->rays : 1);
    printf("backend          %s, %d threads\n", s->backend ? s->backend : "?", s->threads);
    printf("resolution       %dx%d\n", width, height);
    printf("maths            %s, denormals %s: the CPU oracle's bits %s\n",
           s->math_profile ? s->math_profile : "?", s->denormals ? s->denormals : "?",
           s->exact ? "promised" : "NOT promised");
    printf("BVH cost (SAH)   %.3f (Ct = 1, Ci = 2)\n", s->sah_cost);
    printf("rays             %llu (%llu primary)\n", (unsigned long long)s->rays,
           (unsigned long long)s->primary_rays);
    printf("box tests/ray    %.2f\n", (double)s->box_tests / rays);
    printf("tri tests/ray    %.2f\n", (double)s->tri_tests / rays);
    if (s->packets) {
        printf("packets          %llu of %d rays, vectors of %d lanes (%s)\n",
               (unsigned long long)s->packets, s->packet_rays, s->packet_vector,
               s->packet_isa ? s->packet_isa : "?");
        printf("vector tests     %.2f box and interval, %.2f triangle per primary packet "
               "(with its shadow rays)\n",
               (double)s->packet_box_tests / (double)s->packets,
               (double)s->packet_tri_tests / (double)s->packets);
    }
    if (s->device[0]) {
        printf("device           %s (%s)\n", s->device,
               s->exact ? "bit-exact with the CPU oracle promised"
                        : "exactness with the CPU oracle NOT promised");
        printf("specialisation   %s\n", s->specialisation);
        if (s->device_options[0])
            printf("extra options    %s (--cl-options: the kernels are NOT the exact build; "
                   "results may differ from the CPU oracle)\n",
                   s->device_options);
        printf("kernel compile   %.2f ms\n", s->compile_ms);
        printf("upload           %.2f ms, %llu bytes\n", s->upload_ms,
               (unsigned long long)s->upload_bytes);
        if (s->kernels[0]) printf("kernel path      %s\n", s->kernels);
        if (!strncmp(s->kernels, "vulkan", 6))
            printf("kernels          %.2f ms by timestamp queries (%u dispatches, tiles up to %u "
                   "pixels)\n",
                   s->kernel_ms[1], s->launches, s->tile_pixels);
        else if (!strncmp(s->kernels, "packet", 6))
            printf("kernels          packet %.2f ms (%u launches, tiles up to %u pixels)\n",
                   s->kernel_ms[1], s->launches, s->tile_pixels);
        else
            printf("kernels          camera %.2f ms, trace %.2f ms, shade %.2f ms (%u launches, "
                   "tiles up to %u pixels)\n",
                   s->kernel_ms[0], s->kernel_ms[1], s->kernel_ms[2], s->launches, s->tile_pixels);
        if (s->wave_tiles)
            printf("wavefront        %u tiles (%u redone in one kernel after a queue overflow)\n",
                   s->wave_tiles, s->wave_fallbacks);
        printf("download         %.2f ms\n", s->download_ms);
    }
    printf("build            %.2f ms\n", s->build_ms);
    printf("render           %.2f ms (%.2f Mrays/s)\n", s->render_ms,
           s->render_ms > 0 ? (double)s->rays / (s->render_ms * 1000.0) : 0.0);
}

int cmd_render(int argc, char **argv) {
    const char *scene_path = NULL, *out_path = "out.png";
    rt_render_options opt = rt_render_options_default();
    cli_renderer_args ra;
    cli_renderer_args_init(&ra);
    int width = 0, height = 0, stats = 0, frames = 1, has_time = 0, has_update = 0;
    double time = 0.0;
    rt_update_policy update = RT_UPDATE_SAH;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v;
        int taken = cli_renderer_arg(argc, argv, &i, "render", &ra);
        if (taken < 0) return 2;
        if (taken) continue;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            print_usage(stdout);
            return 0;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (!(out_path = cli_value(argc, argv, &i, "render"))) return 2;
        } else if (!strcmp(a, "--width")) {
            if (!(v = cli_value(argc, argv, &i, "render")) ||
                !cli_int("render", a, v, 1, 32768, &width))
                return 2;
        } else if (!strcmp(a, "--height")) {
            if (!(v = cli_value(argc, argv, &i, "render")) ||
                !cli_int("render", a, v, 1, 32768, &height))
                return 2;
        } else if (!strcmp(a, "--aov")) {
            if (!(v = cli_value(argc, argv, &i, "render"))) return 2;
            if (!cli_parse_aov(v, &opt.aov)) {
                cli_error("render",
                          "unknown AOV '%s' (depth, primid, instid, normal, boxtests, "
                          "tritests)",
                          v);
                return 2;
            }
        } else if (!strcmp(a, "--frames")) {
            if (!(v = cli_value(argc, argv, &i, "render")) ||
                !cli_int("render", a, v, 1, 1000, &frames))
                return 2;
        } else if (!strcmp(a, "--stats")) {
            stats = 1;
        } else if (!strcmp(a, "--time")) {
            if (!(v = cli_value(argc, argv, &i, "render")) || !cli_float("render", a, v, &time))
                return 2;
            has_time = 1;
        } else if (!strcmp(a, "--update")) {
            if (!(v = cli_value(argc, argv, &i, "render")) ||
                !cli_update_policy("render", v, &update))
                return 2;
            has_update = 1;
        } else if (!strcmp(a, "--direct")) {
            opt.direct_only = 1;
        } else if (a[0] == '-' && a[1]) {
            cli_error("render", "unknown option '%s'", a);
            print_usage(stderr);
            return 2;
        } else if (scene_path) {
            cli_error("render", "more than one scene given ('%s' and '%s')", scene_path, a);
            return 2;
        } else {
            scene_path = a;
        }
    }
    if (!scene_path) {
        cli_error("render", "no scene given");
        print_usage(stderr);
        return 2;
    }
    rt_renderer *renderer = cli_renderer_create("render", &ra);
    if (!renderer) return 2;

    rt_scene *scene;
    rt_error err;
    if (cli_load_scene(scene_path, &scene, &err) != RT_OK) {
        cli_error("render", "%s", err.message);
        rt_renderer_destroy(renderer);
        return 2;
    }
    if (!cli_apply_accel("render", &ra, scene)) {
        rt_scene_destroy(scene);
        rt_renderer_destroy(renderer);
        return 2;
    }
    rt_camera cam;
    rt_camera_get(scene, &cam);
    if (width) cam.width = width;
    if (height) cam.height = height;
    if (rt_camera_set(scene, &cam) != RT_OK ||
        (has_time && rt_scene_set_time(scene, time) != RT_OK)) {
        cli_error("render", "%s", rt_scene_error(scene));
        rt_scene_destroy(scene);
        rt_renderer_destroy(renderer);
        return 2;
    }
    if (has_update) cli_apply_update(scene, update);
    rt_render_stats st;
    memset(&st, 0, sizeof st);
    opt.stats = &st;
    opt.progress = cli_progress;
    opt.progress_user = (void *)"render";
    rt_framebuffer fb;
    memset(&fb, 0, sizeof fb);
    rt_status status = rt_render(renderer, scene, &opt, &fb);
    cli_progress_done();
    if (ra.verbose && status == RT_OK) cli_print_build_log("render", renderer);
    if (status != RT_OK) {
        cli_error("render", "%s", rt_renderer_error(renderer));
        rt_scene_destroy(scene);
        rt_renderer_destroy(renderer);
        return 2;
    }
    if (frames > 1) { /* the same frame again: warm caches, uploads done */
        double first_ms = st.render_ms, *ms = malloc(sizeof(double) * (size_t)frames);
        int timed = 0;
        rt_framebuffer again;
        memset(&again, 0, sizeof again);
        opt.reuse_framebuffer = 1; /* as a real-time loop does */
        for (int f = 1; f < frames && ms && status == RT_OK; f++) {
            status = rt_render(renderer, scene, &opt, &again);
            if (status == RT_OK) ms[timed++] = st.render_ms;
        }
        rt_framebuffer_free(&again);
        if (status != RT_OK || !ms) {
            cli_error("render", "%s", ms ? rt_renderer_error(renderer) : "out of memory");
            free(ms);
            rt_framebuffer_free(&fb);
            rt_scene_destroy(scene);
            rt_renderer_destroy(renderer);
            return 2;
        }
        for (int a = 1; a < timed; a++) /* insertion sort: a handful of values */
            for (int b = a; b > 0 && ms[b] < ms[b - 1]; b--) {
                double t = ms[b];
                ms[b] = ms[b - 1];
                ms[b - 1] = t;
            }
        double med = timed % 2 ? ms[timed / 2] : 0.5 * (ms[timed / 2 - 1] + ms[timed / 2]);
        printf("frames           %d: first %.2f ms; next %d: min %.2f ms, median %.2f ms "
               "(%.2f / %.2f Mrays/s)\n",
               frames, first_ms, timed, ms[0], med, (double)st.rays / (ms[0] * 1000.0),
               (double)st.rays / (med * 1000.0));
        free(ms);
    }
    if (st.notice) fprintf(stderr, "rtcl render: notice: %s\n", st.notice);
    status = cli_frame_write(out_path, &fb, opt.aov, &err);
    rt_framebuffer_free(&fb);
    if (status != RT_OK) {
        cli_error("render", "%s", err.message);
        rt_scene_destroy(scene);
        rt_renderer_destroy(renderer);
        return 2;
    }
    if (stats) print_stats(&st, cam.width, cam.height);
    fprintf(stderr, "wrote %s (%dx%d)\n", out_path, cam.width, cam.height);
    rt_scene_destroy(scene);
    rt_renderer_destroy(renderer);
    return 0;
}
