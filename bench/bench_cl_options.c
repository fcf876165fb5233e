/* SPDX-License-Identifier: Apache-2.0 */
/* bench_cl_options.c - OpenCL kernel build options against image error
 * (issue 7, study c; bench/study_opencl_options.sh runs it).
 *
 * usage: bench_cl_options SCENE --out DIR [--width W] [--height H] [--frames N]
 *                         [--threads T] [--device D] OPTIONS...
 * Each OPTIONS argument is one variant's extra kernel build options
 * (rt_render_options.device_options, rtcl render --cl-options); "" is the
 * exact build.
 *
 * The scene is loaded once per variant (and once for the CPU oracle), so each
 * keeps its own compiled program and device buffers and no variant is
 * recompiled inside the timed loop. Every variant (and the oracle, backend
 * cpu with T threads) renders one warm-up frame (BVH build, kernel build or
 * cache load, upload; not counted), then N frames, variants interleaved frame
 * by frame; the frame time is rt_render_stats.render_ms (for OpenCL the
 * launches and read-backs of the frame, for the CPU the trace and shading).
 * The last frame of each goes to DIR/NAME.exr (float) and DIR/NAME.png
 * (8-bit), NAME = oracle or v1, v2, ... in argument order, for rtcl compare.
 *
 * Output: a header line, then one tab-separated line per variant (the oracle
 * first): name options exact compile_ms min_ms median_ms rays device. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "formats/image.h"
#include "rt.h"

enum { MAX_VARIANTS = 16, MAX_FRAMES = 50 };

typedef struct variant {
    char name[16];
    const char *options; /* NULL for the oracle */
    rt_scene *scene;
    rt_renderer *renderer; /* one per variant: the options are the renderer's */
    double ms[MAX_FRAMES];
    double compile_ms;
    int exact;
    uint64_t rays;
    char device[128];
    rt_framebuffer fb;
} variant;

static int render(variant *v, double *ms) {
    rt_render_options o = rt_render_options_default();
    rt_render_stats st;
    o.stats = &st;
    rt_framebuffer_free(&v->fb);
    if (rt_render(v->renderer, v->scene, &o, &v->fb) != RT_OK) {
        fprintf(stderr, "bench_cl_options: %s (%s): %s\n", v->name,
                v->options ? v->options : "cpu oracle", rt_renderer_error(v->renderer));
        return 0;
    }
    v->compile_ms += st.compile_ms;
    v->exact = v->options ? st.exact : 1;
    v->rays = st.rays;
    snprintf(v->device, sizeof v->device, "%s", v->options ? st.device : "cpu");
    *ms = st.render_ms;
    return 1;
}

int main(int argc, char **argv) {
    const char *path = NULL, *out = NULL, *device = NULL;
    int w = 0, h = 0, frames = 5, threads = 2, count = 1;
    static variant vs[MAX_VARIANTS];
    snprintf(vs[0].name, sizeof vs[0].name, "oracle");
    for (int i = 1; i < argc; i++) {
        int ok = 1;
        if (!strcmp(argv[i], "--width"))
            ok = bench_arg_int(argc, argv, &i, 1, 16384, &w);
        else if (!strcmp(argv[i], "--height"))
            ok = bench_arg_int(argc, argv, &i, 1, 16384, &h);
        else if (!strcmp(argv[i], "--frames"))
            ok = bench_arg_int(argc, argv, &i, 1, MAX_FRAMES, &frames);
        else if (!strcmp(argv[i], "--threads"))
            ok = bench_arg_int(argc, argv, &i, 1, 256, &threads);
        else if (!strcmp(argv[i], "--out"))
            ok = i + 1 < argc && (out = argv[++i]);
        else if (!strcmp(argv[i], "--device"))
            ok = i + 1 < argc && (device = argv[++i]);
        else if (!path)
            path = argv[i];
        else if (count < MAX_VARIANTS) {
            vs[count].options = argv[i];
            snprintf(vs[count].name, sizeof vs[count].name, "v%d", count);
            count++;
        } else
            ok = 0;
        if (!ok) {
            fprintf(stderr, "bench_cl_options: bad argument '%s'\n", argv[i]);
            return 2;
        }
    }
    if (!path || !out || count < 2) {
        fprintf(stderr, "usage: bench_cl_options SCENE --out DIR [--width W] [--height H] "
                        "[--frames N] [--threads T] [--device D] OPTIONS...\n");
        return 2;
    }
    /* The output folder is checked before anything is rendered. */
    for (int k = 0; k < count; k++) {
        char file[1024];
        rt_error err;
        int len = snprintf(file, sizeof file, "%s/%s.exr", out, vs[k].name);
        if (len < 0 || (size_t)len >= sizeof file) {
            fprintf(stderr, "bench_cl_options: output path too long\n");
            return 2;
        }
        if (rt_image_check_output(file, &err) != RT_OK) {
            fprintf(stderr, "bench_cl_options: %s\n", err.message);
            return 2;
        }
    }
    char backend[160];
    snprintf(backend, sizeof backend, "opencl%s%s", device ? ":" : "", device ? device : "");
    for (int k = 0; k < count; k++) {
        rt_error err;
        if (rt_scene_load(path, &vs[k].scene, &err) != RT_OK) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        rt_camera cam;
        rt_camera_get(vs[k].scene, &cam);
        bench_interior_view(path, &cam);
        if (w) cam.width = w;
        if (h) cam.height = h;
        if (rt_camera_set(vs[k].scene, &cam) != RT_OK) return 1;
        rt_renderer_options ro = rt_renderer_options_default();
        ro.backend = vs[k].options ? backend : "cpu";
        ro.threads = threads;
        ro.device_options = vs[k].options;
        if (rt_renderer_create(&ro, &vs[k].renderer, &err) != RT_OK) {
            fprintf(stderr, "bench_cl_options: %s\n", err.message);
            return 1;
        }
    }
    for (int f = -1; f < frames; f++) /* f = -1: the warm-up frame, not counted */
        for (int k = 0; k < count; k++) {
            double ms;
            if (!render(&vs[k], &ms)) return 1;
            if (f >= 0) vs[k].ms[f] = ms;
        }
    printf("name\toptions\texact\tcompile_ms\tmin_ms\tmedian_ms\trays\tdevice\n");
    for (int k = 0; k < count; k++) {
        variant *v = &vs[k];
        char file[1024];
        const char *ext[2] = {"exr", "png"};
        for (int e = 0; e < 2; e++) {
            int len = snprintf(file, sizeof file, "%s/%s.%s", out, v->name, ext[e]);
            if (len < 0 || (size_t)len >= sizeof file) {
                fprintf(stderr, "bench_cl_options: output path too long\n");
                return 2;
            }
            rt_image img = {v->fb.width, v->fb.height, v->fb.channels, v->fb.pixels};
            rt_error err;
            if (rt_image_write(file, &img, &err) != RT_OK) {
                fprintf(stderr, "%s\n", err.message);
                return 1;
            }
        }
        double min, med;
        bench_min_median(v->ms, frames, &min, &med);
        printf("%s\t%s\t%d\t%.1f\t%.2f\t%.2f\t%llu\t%s\n", v->name,
               v->options ? (v->options[0] ? v->options : "(exact build)") : "(cpu oracle)",
               v->exact, v->compile_ms, min, med, (unsigned long long)v->rays, v->device);
        rt_framebuffer_free(&v->fb);
        rt_renderer_destroy(v->renderer);
        rt_scene_destroy(v->scene);
    }
    return 0;
}
