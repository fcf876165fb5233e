/* trace.c - rt_trace_rays: the caller's rays through the same layout and
 * traversal as rendering, on the renderer's backend. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/error.h"
#include "render/render_frame.h"

static int ray_valid(const rt_ray *r) {
    for (int k = 0; k < 3; k++)
        if (!isfinite(r->org[k]) || !isfinite(r->dir[k])) return 0;
    if (isnan(r->tmin) || isnan(r->tmax)) return 0;
    return r->dir[0] != 0.0f || r->dir[1] != 0.0f || r->dir[2] != 0.0f;
}

rt_status rt_trace_rays(rt_renderer *r, rt_scene *scene, const rt_ray *rays, size_t count,
                        rt_hit *hits, const rt_trace_options *options) {
    if (!r) return RT_ERROR_INVALID_ARGUMENT;
    rt_error_clear(&r->error);
    if (!scene || (count && (!rays || !hits)))
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT,
                       "rt_trace_rays: scene, rays or hits is NULL");
    rt_trace_options opt;
    memset(&opt, 0, sizeof opt);
    if (options) opt = *options;
    if (opt.packet_path != RT_TRACE_PATH_AUTO && opt.packet_path != RT_TRACE_PATH_PACKETS &&
        opt.packet_path != RT_TRACE_PATH_SINGLE)
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT,
                       "rt_trace_rays: unknown packet path %d", (int)opt.packet_path);
    rt_frame_state fs;
    rt_status st = rt_frame_layout(r, scene, opt.tri_test, 0, &fs);
    if (st != RT_OK) return st;
    /* The backends read the caller's rays as they are (rt_ray is the
     * kernels' ray type); only a call with invalid rays pays for a copy, in
     * which each invalid ray becomes an empty range: a miss, whatever the
     * scene. */
    size_t first_invalid = count;
    for (size_t i = 0; i < count && first_invalid == count; i++)
        if (!ray_valid(&rays[i])) first_invalid = i;
    rt_ray *copy = NULL;
    if (first_invalid < count) {
        copy = malloc(sizeof(rt_ray) * count);
        if (!copy)
            return rt_fail(&r->error, RT_ERROR_OUT_OF_MEMORY, "out of memory for %zu rays", count);
        memcpy(copy, rays, sizeof(rt_ray) * count);
        for (size_t i = first_invalid; i < count; i++)
            if (!ray_valid(&copy[i]))
                copy[i] = (rt_ray){{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 1.0f, 0.0f};
    }
    const rt_ray *in = copy ? copy : rays;
    rt_hit_d *out = malloc(sizeof(rt_hit_d) * (count ? count : 1));
    if (!out) {
        free(copy);
        return rt_fail(&r->error, RT_ERROR_OUT_OF_MEMORY, "out of memory for %zu hits", count);
    }
    rt_render_stats prep;
    memset(&prep, 0, sizeof prep);
    rt_trace_stats ts;
    memset(&ts, 0, sizeof ts);
    ts.backend = fs.ops->name;
    ts.isa = "";
    st = fs.ops->prepare(fs.state, &fs.layout, &prep, &r->error);
    const double t1 = rt_now_ms();
    if (st == RT_OK)
        st = fs.ops->trace(fs.state, &fs.layout, in, count, out, opt.any_hit != 0, opt.packet_path,
                           &ts, &r->error);
    /* The trace alone: the backend's builds inside it are build time. */
    ts.trace_ms = rt_now_ms() - t1 - ts.build_ms;
    ts.build_ms += fs.build_ms + prep.build_ms;
    ts.rays = count;
    if (opt.stats) *opt.stats = ts;
    if (st == RT_OK)
        for (size_t i = 0; i < count; i++) {
            rt_hit *h = &hits[i];
            h->hit = out[i].prim != RT_NO_HIT;
            h->t = h->hit ? out[i].t : INFINITY;
            h->u = h->hit ? out[i].u : 0.0f;
            h->v = h->hit ? out[i].v : 0.0f;
            h->prim = h->hit ? out[i].prim : UINT32_MAX;
            h->inst = h->hit ? out[i].inst : UINT32_MAX;
        }
    free(copy);
    free(out);
    return st;
}
