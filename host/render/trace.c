/* trace.c - rt_trace_rays: the caller's rays through the same layout and
 * traversal as rendering, split over the pool's workers in chunks. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cpu_render.h"
#include "packet_trace.h"
#include "render/render_internal.h"

typedef struct trace_job {
    const rt_flat *flat;
    const rt_pk_wide *wide;
    const rt_ray_d *rays;
    rt_hit_d *hits;
    size_t count;
    int any_hit, packet;
} trace_job;

static void trace_chunk(void *ctx, int worker, int workers) {
    trace_job *job = ctx;
    /* Contiguous chunks (whole packets). */
    size_t per = (job->count + (size_t)workers - 1) / (size_t)workers;
    per = (per + RT_PK_LANES - 1) / RT_PK_LANES * RT_PK_LANES;
    size_t first = per * (size_t)worker;
    if (first >= job->count) return;
    size_t n = job->count - first < per ? job->count - first : per;
    rt_counters c = {0, 0, 0};
    if (job->packet)
        rt_packet_trace_rays(job->flat, job->wide, job->rays + first, n, job->hits + first,
                             job->any_hit, &c);
    else
        rt_cpu_trace_rays(job->flat, job->rays + first, n, job->hits + first, job->any_hit, &c);
}

static int ray_valid(const rt_ray *r) {
    for (int k = 0; k < 3; k++)
        if (!isfinite(r->org[k]) || !isfinite(r->dir[k])) return 0;
    if (isnan(r->tmin) || isnan(r->tmax)) return 0;
    return r->dir[0] != 0.0f || r->dir[1] != 0.0f || r->dir[2] != 0.0f;
}

rt_status rt_trace_rays(rt_scene *scene, const rt_ray *rays, size_t count, rt_hit *hits,
                        int any_hit, const char *backend) {
    rt_render_options opt = rt_render_options_default();
    opt.backend = backend;
    return rt_trace_rays_with(scene, rays, count, hits, any_hit, &opt);
}

rt_status rt_trace_rays_with(rt_scene *scene, const rt_ray *rays, size_t count, rt_hit *hits,
                             int any_hit, const rt_render_options *options) {
    if (!scene || (count && (!rays || !hits))) return RT_ERROR_INVALID_ARGUMENT;
    rt_render_options opt = options ? *options : rt_render_options_default();
    const char *b = opt.backend ? opt.backend : "cpu";
    int packet = 0;
    const rt_backend_ops *device_ops = NULL;
    const char *device = NULL;
    rt_status st = rt_trace_backend(scene, b, &packet, &device_ops, &device);
    if (st != RT_OK) return st;
    rt_prepared prep;
    st = rt_render_prepare(scene, opt.threads, &prep);
    if (st != RT_OK) return st;
    rt_flat flat;
    st = rt_flat_with_tri_test(scene, prep.flat, opt.tri_test, &flat);
    if (st != RT_OK) return st;
    rt_ray_d *in = malloc(sizeof(rt_ray_d) * (count ? count : 1));
    rt_hit_d *out = malloc(sizeof(rt_hit_d) * (count ? count : 1));
    if (!in || !out) {
        free(in);
        free(out);
        return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    for (size_t i = 0; i < count; i++) {
        memcpy(in[i].org, rays[i].org, sizeof in[i].org);
        memcpy(in[i].dir, rays[i].dir, sizeof in[i].dir);
        in[i].tmin = rays[i].tmin;
        in[i].tmax = rays[i].tmax;
        if (!ray_valid(&rays[i])) { /* an empty range: a miss, whatever the scene */
            in[i].tmin = 1.0f;
            in[i].tmax = 0.0f;
            in[i].dir[0] = 1.0f;
            in[i].dir[1] = in[i].dir[2] = 0.0f;
            for (int k = 0; k < 3; k++) in[i].org[k] = 0.0f;
        }
    }
    if (device_ops) {
        /* The device compiles the triangle test in from the header it is given. */
        rt_prepared with_test = prep;
        with_test.flat = &flat;
        st = device_ops->trace(scene, &with_test, device, opt.device_options, in, count, out,
                               any_hit);
        if (st != RT_OK) {
            free(in);
            free(out);
            return st;
        }
    } else {
        const rt_pk_wide *wide = NULL;
        if (packet && (st = rt_render_wide(scene, &prep, &wide)) != RT_OK) {
            free(in);
            free(out);
            return st;
        }
        trace_job job = {&flat, wide, in, out, count, any_hit, packet};
        rt_pool_run(prep.pool, trace_chunk, &job);
    }
    for (size_t i = 0; i < count; i++) {
        rt_hit *h = &hits[i];
        h->hit = out[i].prim != RT_NO_HIT;
        h->t = h->hit ? out[i].t : INFINITY;
        h->u = h->hit ? out[i].u : 0.0f;
        h->v = h->hit ? out[i].v : 0.0f;
        h->prim = h->hit ? out[i].prim : UINT32_MAX;
        h->inst = h->hit ? out[i].inst : UINT32_MAX;
    }
    free(in);
    free(out);
    return RT_OK;
}
