/* SPDX-License-Identifier: Apache-2.0 */
/* render.c - rt_render: one frame of a scene on the renderer's backend. The
 * renderer brings the layout up to date (render/accel_cache.c), the backend
 * brings its copy up to date and renders; statistics are gathered here. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "render/render_frame.h"
#include "render/renderer_internal.h"

rt_render_options rt_render_options_default(void) {
    rt_render_options o;
    memset(&o, 0, sizeof o);
    return o;
}

void rt_framebuffer_free(rt_framebuffer *fb) {
    if (!fb) return;
    free(fb->pixels);
    fb->pixels = NULL;
}

/* The public enum mirrors the layout's RT_TRI_* numbers. */
_Static_assert(RT_TRI_TEST_WATERTIGHT == RT_TRI_WATERTIGHT && RT_TRI_TEST_MOLLER == RT_TRI_MOLLER &&
                   RT_TRI_TEST_PLUECKER == RT_TRI_PLUECKER && RT_TRI_TEST_BADOUEL == RT_TRI_BADOUEL,
               "rt_triangle_test and RT_TRI_* differ");

rt_status rt_frame_layout(rt_renderer *r, rt_scene *scene, rt_triangle_test test, int direct_only,
                          rt_frame_state *out) {
    memset(out, 0, sizeof *out);
    if ((int)test < RT_TRI_TEST_WATERTIGHT || (int)test > RT_TRI_TEST_BADOUEL)
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT, "unknown triangle test %d", (int)test);
    rt_status st = rt_renderer_layout(r, scene, &out->layout, &out->build_ms, &out->sah_cost);
    if (st != RT_OK) return st;
    /* A shallow copy whose header selects the frame's test and features;
     * the arrays stay the renderer's. */
    out->flat = *out->layout.flat;
    out->flat.hdr.tri_method = (uint32_t)test;
    if (direct_only) out->flat.hdr.flags &= ~(uint32_t)RT_SCENE_SECONDARY;
    out->layout.flat = &out->flat;
    const rt_backend_slot *slot = rt_renderer_slot(r);
    out->ops = slot->ops;
    out->state = slot->state;
    return RT_OK;
}

/* Allocates (or reuses) the framebuffer of the frame's size. */
static rt_status frame_buffer(rt_renderer *r, const rt_scene_header *h, int channels, int reuse,
                              rt_framebuffer *fb) {
    size_t count = (size_t)h->width * (size_t)h->height * (size_t)channels;
    if (reuse && fb->pixels && fb->width == h->width && fb->height == h->height &&
        fb->channels == channels)
        return RT_OK;
    if (reuse) rt_framebuffer_free(fb);
    memset(fb, 0, sizeof *fb);
    fb->pixels = calloc(count, sizeof(float));
    if (!fb->pixels)
        return rt_fail(&r->error, RT_ERROR_OUT_OF_MEMORY, "out of memory for a %dx%d framebuffer",
                       h->width, h->height);
    fb->width = h->width;
    fb->height = h->height;
    fb->channels = channels;
    return RT_OK;
}

/* The point of its pixel that sample i of n puts every primary ray through,
 * in [0, 1)^2 from the pixel's top-left corner: a k x k grid when n = k * k,
 * else column i of n with the row by the base-2 radical inverse of i. */
static void sample_point(int i, int n, double *x, double *y) {
    int k = 1;
    while ((k + 1) * (k + 1) <= n) k++;
    if (k * k == n) {
        *x = ((double)(i % k) + 0.5) / (double)k;
        *y = ((double)(i / k) + 0.5) / (double)k;
        return;
    }
    double inv = 0.0, f = 0.5;
    for (unsigned u = (unsigned)i; u; u >>= 1, f *= 0.5)
        if (u & 1u) inv += f;
    *x = ((double)i + 0.5) / (double)n;
    *y = inv + 0.5 / (double)n;
}

/* Moves the frame's camera so that each pixel's primary ray goes through
 * (x, y) of the pixel instead of its centre: rt_camera_ray's screen point
 * sx moves by 2 (x - 1/2) / width and sy by -2 (y - 1/2) / height, folded
 * into the forward vector once on the host (in double, rounded to float),
 * so that every backend computes the same rays from the same header. */
static void move_camera(rt_scene_header *h, const float forward[3], double x, double y) {
    const double dx = 2.0 * (x - 0.5) / (double)h->width;
    const double dy = -2.0 * (y - 0.5) / (double)h->height;
    for (int k = 0; k < 3; k++)
        h->cam_forward[k] =
            (float)((double)forward[k] + dx * (double)h->cam_right[k] + dy * (double)h->cam_up[k]);
}

/* A pass's progress as a part of all the passes'. */
typedef struct sample_progress {
    void (*progress)(void *user, double done);
    void *user;
    int pass, passes;
} sample_progress;

static void pass_progress(void *user, double done) {
    const sample_progress *p = (const sample_progress *)user;
    p->progress(p->user, ((double)p->pass + done) / (double)p->passes);
}

/* Adds a pass's counts and times to sum. */
static void add_counts(rt_render_stats *sum, const rt_render_stats *s) {
    sum->render_ms += s->render_ms;
    sum->rays += s->rays;
    sum->primary_rays += s->primary_rays;
    sum->box_tests += s->box_tests;
    sum->tri_tests += s->tri_tests;
    sum->packets += s->packets;
    sum->packet_box_tests += s->packet_box_tests;
    sum->packet_tri_tests += s->packet_tri_tests;
    sum->build_ms += s->build_ms;
    sum->compile_ms += s->compile_ms;
    sum->upload_ms += s->upload_ms;
    sum->upload_bytes += s->upload_bytes;
    sum->download_ms += s->download_ms;
    for (int k = 0; k < 3; k++) sum->kernel_ms[k] += s->kernel_ms[k];
    sum->launches += s->launches;
}

/* rt_render_options.samples: the passes, summed in order into fb, then
 * divided by their number; the statistics are the passes' totals. */
static rt_status render_samples(rt_renderer *r, rt_frame_state *fs, rt_backend_frame *frame,
                                int samples, rt_framebuffer *fb, rt_render_stats *s) {
    const size_t count = (size_t)fb->width * (size_t)fb->height * (size_t)fb->channels;
    float *pass = malloc(count * sizeof *pass);
    if (!pass)
        return rt_fail(&r->error, RT_ERROR_OUT_OF_MEMORY, "out of memory for a %dx%d sample pass",
                       fb->width, fb->height);
    float forward[3];
    memcpy(forward, fs->flat.hdr.cam_forward, sizeof forward);
    memset(fb->pixels, 0, count * sizeof *fb->pixels);
    rt_render_stats total;
    memset(&total, 0, sizeof total);
    frame->pixels = pass;
    sample_progress prog = {frame->progress, frame->progress_user, 0, samples};
    if (prog.progress) {
        frame->progress = pass_progress;
        frame->progress_user = &prog;
    }
    rt_status st = RT_OK;
    for (int i = 0; i < samples && st == RT_OK; i++) {
        prog.pass = i;
        double x, y;
        sample_point(i, samples, &x, &y);
        move_camera(&fs->flat.hdr, forward, x, y);
        memset(s, 0, sizeof *s);
        st = fs->ops->prepare(fs->state, &fs->layout, s, &r->error);
        if (st == RT_OK) st = fs->ops->render(fs->state, &fs->layout, frame, s, &r->error);
        if (st != RT_OK) break;
        for (size_t j = 0; j < count; j++) fb->pixels[j] += pass[j];
        if (i == 0)
            total = *s; /* the descriptive fields (backend, device, ...) are the same each pass */
        else
            add_counts(&total, s);
    }
    free(pass);
    frame->pixels = fb->pixels;
    frame->progress = prog.progress;
    frame->progress_user = prog.user;
    if (st != RT_OK) return st;
    const float n = (float)samples;
    for (size_t j = 0; j < count; j++) fb->pixels[j] = fb->pixels[j] / n;
    *s = total;
    return RT_OK;
}

rt_status rt_render(rt_renderer *r, rt_scene *scene, const rt_render_options *options,
                    rt_framebuffer *fb) {
    if (!r) return RT_ERROR_INVALID_ARGUMENT;
    rt_error_clear(&r->error);
    if (!scene || !fb)
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT, "rt_render: scene or fb is NULL");
    rt_render_options opt = options ? *options : rt_render_options_default();
    if (opt.aov < RT_AOV_NONE || opt.aov > RT_AOV_TRI_TESTS)
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT, "unknown AOV %d", (int)opt.aov);
    if (opt.samples < 0 || opt.samples > RT_MAX_SAMPLES)
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT,
                       "samples per pixel %d is out of range (0 to %d)", opt.samples,
                       RT_MAX_SAMPLES);
    if (opt.samples > 1 && opt.aov != RT_AOV_NONE)
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT,
                       "%d samples per pixel: only the shaded image is averaged, not an AOV",
                       opt.samples);
    rt_frame_state fs;
    rt_status st = rt_frame_layout(r, scene, opt.tri_test, opt.direct_only, &fs);
    if (st != RT_OK) return st;

    int channels = (opt.aov == RT_AOV_NONE || opt.aov == RT_AOV_NORMAL) ? 3 : 1;
    st = frame_buffer(r, &fs.flat.hdr, channels, opt.reuse_framebuffer, fb);
    if (st != RT_OK) return st;

    rt_render_stats local;
    rt_render_stats *s = opt.stats ? opt.stats : &local;
    memset(s, 0, sizeof *s);
    const int samples = opt.samples > 1 ? opt.samples : 1;
    rt_backend_frame frame = {opt.aov,           channels,     fb->pixels,
                              opt.stats != NULL, opt.progress, opt.progress_user};
    if (samples == 1) {
        st = fs.ops->prepare(fs.state, &fs.layout, s, &r->error);
        if (st == RT_OK) st = fs.ops->render(fs.state, &fs.layout, &frame, s, &r->error);
    } else {
        st = render_samples(r, &fs, &frame, samples, fb, s);
    }
    if (st != RT_OK) {
        rt_framebuffer_free(fb);
        return st;
    }
    const float ev = rt_scene_exposure(scene);
    if (opt.aov == RT_AOV_NONE && ev != 0.0f) {
        /* After shading, on the host: the same bits on every backend. */
        const float scale = (float)exp2((double)ev);
        const size_t count = (size_t)fb->width * (size_t)fb->height * (size_t)fb->channels;
        for (size_t j = 0; j < count; j++) fb->pixels[j] = fb->pixels[j] * scale;
    }
    s->sah_cost = fs.sah_cost;
    s->build_ms += fs.build_ms;
    s->backend = fs.ops->name;
    s->notice = r->notice[0] ? r->notice : NULL;
    return RT_OK;
}
