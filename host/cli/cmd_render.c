/* SPDX-License-Identifier: Apache-2.0 */
/* cmd_render.c - 'rtcl render': a scene to an image or an AOV. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "commands.h"
#include "frame_image.h"

typedef struct render_args {
    const char *out;
    int frames, stats, metadata;
    cli_frame_args frame;
    cli_scene_args scene;
    cli_renderer_args renderer;
} render_args;

static const cli_option render_options[] = {
    {"--output", 'o', CLI_STRING, "FILE", offsetof(render_args, out), .flags = CLI_NONEMPTY,
     .help = "the image, its format by the extension: {formats}; checked before the frame is "
             "made, and written whole or not at all (a failed write leaves an existing FILE as "
             "it was)",
     .dynamic_help = cli_image_formats_help, .fallback = "out.png"},
    {"--metadata", 0, CLI_FLAG, NULL, offsetof(render_args, metadata),
     .help = "record the time of writing and the software in PNG and EXR files, and the time "
             "and the file's name in DPX (without it equal images are equal files, under any "
             "name)"},
    {"--frames", 0, CLI_INT, "N", offsetof(render_args, frames), 1, 1000,
     .help = "render N frames in one process and print the first frame's time and the min and "
             "median of the others (a benchmark); the image written is the first frame's",
     .fallback = "1"},
    {"--stats", 0, CLI_FLAG, NULL, offsetof(render_args, stats),
     .help = "print BVH cost, box and triangle tests per ray, render time and the memory held "
             "(scene, BVHs, layout, the backend's copies, per triangle); for opencl and "
             "vulkan also the device, kernel specialisation (-D switches, specialization "
             "constants), compile, upload (bytes), per-kernel (vulkan: timestamp queries) and "
             "download times"},
    {NULL}};

static const cli_group render_groups[] = {
    {NULL, render_options, 0},
    {CLI_FRAME_TITLE, cli_frame_options, offsetof(render_args, frame)},
    {CLI_FRAME_TITLE, cli_aov_options, offsetof(render_args, frame)},
    {CLI_FRAME_TITLE, cli_sample_options, offsetof(render_args, frame)},
    {CLI_SCENE_TITLE, cli_scene_options, offsetof(render_args, scene)},
    {CLI_SCENE_TITLE, cli_time_options, offsetof(render_args, scene)},
    {CLI_SCENE_TITLE, cli_update_options, offsetof(render_args, scene)},
    {CLI_RENDERER_TITLE, cli_renderer_options, offsetof(render_args, renderer)},
    {CLI_KERNEL_TITLE, cli_kernel_options, offsetof(render_args, renderer)},
    {CLI_TEST_TITLE, cli_test_options, offsetof(render_args, renderer)},
    {NULL}};

const cli_command cmd_render_spec = {
    "render",
    "render a scene to an image (PNG, EXR, PPM, PFM) or an AOV",
    "SCENE",
    "scene",
    1,
    1,
    "Renders SCENE (a .json scene, a bare .obj, a .gltf or .glb, or builtin:NAME)\n"
    "with Whitted-style shading (Phong, shadow rays, reflection, refraction).\n"
    "Options may come before or after SCENE.\n",
    render_groups,
    NULL,
    NULL};

/* What the scene and the renderer hold, in MB and bytes per triangle. */
static void print_memory(const rt_renderer *r, const rt_scene *scene) {
    rt_memory_stats m;
    if (rt_renderer_memory(r, scene, &m) != RT_OK) return;
    double t = (double)(m.triangles ? m.triangles : 1);
    uint64_t all = m.scene + m.mesh_bvhs + m.object_bvh + m.kept + m.layout + m.backend;
    printf("memory           %.1f MB, %.1f bytes/triangle: scene %.1f, BVHs %.1f, kept %.1f, "
           "layout %.1f, backend %.1f\n",
           (double)all / 1e6, (double)all / t, (double)m.scene / t,
           (double)(m.mesh_bvhs + m.object_bvh) / t, (double)m.kept / t, (double)m.layout / t,
           (double)m.backend / t);
    if (m.device) printf("device memory    %.1f MB\n", (double)m.device / 1e6);
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
    render_args a;
    memset(&a, 0, sizeof a);
    a.out = "out.png";
    a.frames = 1;
    cli_args_init(&a.frame, &a.scene, &a.renderer);
    int code;
    if (cli_parse(&cmd_render_spec, &a, argc, argv, &code) < 0) return code;
    const char *out_path = a.out;
    int frames = a.frames, stats = a.stats;
    rt_render_options opt = rt_render_options_default();
    opt.aov = (rt_aov)a.frame.aov;
    opt.direct_only = a.frame.direct;
    opt.samples = a.frame.spp;

    /* The output's folder and format are checked before the frame is made. */
    rt_error oerr;
    if (cli_frame_check(out_path, &oerr) != RT_OK) {
        cli_error("render", "%s", oerr.message);
        return 2;
    }
    cli_session run;
    if (!cli_session_open(&run, "render", argv[0], &a.renderer, &a.scene, &a.frame)) return 2;
    rt_renderer *renderer = run.renderer;
    rt_scene *scene = run.scene;
    rt_error err;
    rt_camera cam;
    rt_camera_get(scene, &cam);
    rt_render_stats st;
    memset(&st, 0, sizeof st);
    opt.stats = &st;
    opt.progress = cli_progress;
    opt.progress_user = (void *)"render";
    rt_framebuffer fb;
    memset(&fb, 0, sizeof fb);
    rt_status status = rt_render(renderer, scene, &opt, &fb);
    cli_progress_done();
    if (a.renderer.verbose && status == RT_OK) cli_print_build_log("render", renderer);
    if (status != RT_OK) {
        cli_error("render", "%s", rt_renderer_error(renderer));
        cli_session_close(&run);
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
            cli_session_close(&run);
            return 2;
        }
        for (int i = 1; i < timed; i++) /* insertion sort: a handful of values */
            for (int b = i; b > 0 && ms[b] < ms[b - 1]; b--) {
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
    cli_print_backend_choice("render", &a.renderer, st.backend, st.device, st.notice);
    status = cli_frame_write(out_path, &fb, opt.aov, a.metadata, &err);
    rt_framebuffer_free(&fb);
    if (status != RT_OK) {
        cli_error("render", "%s", err.message);
        cli_session_close(&run);
        return 2;
    }
    if (stats) {
        print_stats(&st, cam.width, cam.height);
        print_memory(renderer, scene);
    }
    /* The result line names the backend that ran (what --backend auto
     * chose, issue 30 item 10) rather than a line of its own. */
    char ran[192];
    fprintf(stderr, "wrote %s (%dx%d, %s)\n", out_path, cam.width, cam.height,
            cli_backend_text(st.backend, st.device, ran, sizeof ran));
    cli_session_close(&run);
    return 0;
}
