/* SPDX-License-Identifier: Apache-2.0 */
/* render.c - rt_render: one frame of a scene on the renderer's backend. The
 * renderer brings the layout up to date (render/accel_cache.c), the backend
 * brings its copy up to date and renders; statistics are gathered here. */
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

rt_status rt_render(rt_renderer *r, rt_scene *scene, const rt_render_options *options,
                    rt_framebuffer *fb) {
    if (!r) return RT_ERROR_INVALID_ARGUMENT;
    rt_error_clear(&r->error);
    if (!scene || !fb)
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT, "rt_render: scene or fb is NULL");
    rt_render_options opt = options ? *options : rt_render_options_default();
    if (opt.aov < RT_AOV_NONE || opt.aov > RT_AOV_TRI_TESTS)
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT, "unknown AOV %d", (int)opt.aov);
    rt_frame_state fs;
    rt_status st = rt_frame_layout(r, scene, opt.tri_test, opt.direct_only, &fs);
    if (st != RT_OK) return st;

    int channels = (opt.aov == RT_AOV_NONE || opt.aov == RT_AOV_NORMAL) ? 3 : 1;
    st = frame_buffer(r, &fs.flat.hdr, channels, opt.reuse_framebuffer, fb);
    if (st != RT_OK) return st;

    rt_render_stats local;
    rt_render_stats *s = opt.stats ? opt.stats : &local;
    memset(s, 0, sizeof *s);
    rt_backend_frame frame = {opt.aov,           channels,     fb->pixels,
                              opt.stats != NULL, opt.progress, opt.progress_user};
    st = fs.ops->prepare(fs.state, &fs.layout, s, &r->error);
    if (st == RT_OK) st = fs.ops->render(fs.state, &fs.layout, &frame, s, &r->error);
    if (st != RT_OK) {
        rt_framebuffer_free(fb);
        return st;
    }
    s->sah_cost = fs.sah_cost;
    s->build_ms += fs.build_ms;
    s->backend = fs.ops->name;
    s->notice = r->notice[0] ? r->notice : NULL;
    return RT_OK;
}
