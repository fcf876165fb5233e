/* SPDX-License-Identifier: Apache-2.0 */
/* trace.c - rt_trace_rays: the caller's rays (with their masks, when given)
 * through the same layout and traversal as rendering, on the renderer's
 * backend; then each hit's geometric normal, mesh and ray id, on the host,
 * the same for every backend. */
#include <math.h>
#include <stdatomic.h>
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

rt_status rt_frame_query_begin(rt_renderer *r, const char *what, const rt_scene *scene,
                               const rt_ray *rays, size_t count, const void *out,
                               const char *out_name) {
    rt_error_clear(&r->error);
    if (!scene || (count && (!rays || !out)))
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT, "%s: scene, rays or %s is NULL", what,
                       out_name);
    return RT_OK;
}

rt_status rt_frame_rays(rt_renderer *r, const rt_ray *rays, size_t count, const rt_ray **in,
                        rt_ray **copy) {
    *in = rays;
    *copy = NULL;
    /* The backends read the caller's rays as they are (rt_ray is the
     * kernels' ray type); only a call with invalid rays pays for a copy, in
     * which each invalid ray becomes an empty range: a miss, whatever the
     * scene. */
    size_t first_invalid = count;
    for (size_t i = 0; i < count && first_invalid == count; i++)
        if (!ray_valid(&rays[i])) first_invalid = i;
    if (first_invalid == count) return RT_OK;
    rt_ray *c = malloc(sizeof(rt_ray) * count);
    if (!c) return rt_fail(&r->error, RT_ERROR_OUT_OF_MEMORY, "out of memory for %zu rays", count);
    memcpy(c, rays, sizeof(rt_ray) * count);
    for (size_t i = first_invalid; i < count; i++)
        if (!ray_valid(&c[i])) c[i] = (rt_ray){{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 1.0f, 0.0f};
    *in = c;
    *copy = c;
    return RT_OK;
}

/* The unit geometric normal of triangle prim of the instance's mesh, in
 * world space: rt.h's rt_hit gives the operations and their order. Zero
 * for a triangle of zero area (which no test hits). */
static void hit_normal(const rt_scene *scene, const rt_instance *in, uint32_t prim, float out[3]) {
    const rt_mesh_data *m = &scene->meshes[in->mesh];
    const uint32_t *idx = m->indices + 3 * (size_t)prim;
    const float *p0 = m->positions + 3 * (size_t)idx[0];
    const float *p1 = m->positions + 3 * (size_t)idx[1];
    const float *p2 = m->positions + 3 * (size_t)idx[2];
    double e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)p1[k] - (double)p0[k];
        e2[k] = (double)p2[k] - (double)p0[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    if (!(in->flags & RT_INST_IDENTITY)) {
        const float *w = in->world_to_object; /* rows 0..2, 4 floats each */
        double t[3];
        for (int j = 0; j < 3; j++)
            t[j] = ((double)w[j] * n[0] + (double)w[4 + j] * n[1]) + (double)w[8 + j] * n[2];
        memcpy(n, t, sizeof n);
    }
    double big = fabs(n[0]);
    if (fabs(n[1]) > big) big = fabs(n[1]);
    if (fabs(n[2]) > big) big = fabs(n[2]);
    if (!(big > 0.0) || !isfinite(big)) {
        out[0] = out[1] = out[2] = 0.0f;
        return;
    }
    for (int k = 0; k < 3; k++) n[k] = n[k] / big;
    const double len = sqrt((n[0] * n[0] + n[1] * n[1]) + n[2] * n[2]);
    for (int k = 0; k < 3; k++) out[k] = (float)(n[k] / len);
}

/* The backend's hits into the caller's, with normals, meshes and ray ids,
 * in chunks on the renderer's workers. */
typedef struct finish_job {
    const rt_scene *scene;
    const rt_flat *flat;
    const rt_hit_d *in;
    const uint32_t *ids; /* rt_trace_options.ray_ids (NULL: the index) */
    rt_hit *out;
    size_t count;
    atomic_size_t next;
} finish_job;

enum { FINISH_CHUNK = 4096 };

static void finish_chunk(void *ctx, int worker, int workers) {
    (void)worker;
    (void)workers;
    finish_job *job = ctx;
    for (;;) {
        size_t first = atomic_fetch_add_explicit(&job->next, FINISH_CHUNK, memory_order_relaxed);
        if (first >= job->count) break;
        size_t end = job->count - first < FINISH_CHUNK ? job->count : first + FINISH_CHUNK;
        for (size_t i = first; i < end; i++) {
            const rt_hit_d *d = &job->in[i];
            rt_hit *h = &job->out[i];
            h->hit = d->prim != RT_NO_HIT;
            const uint32_t id = job->ids ? job->ids[i] : (uint32_t)i;
            if (!h->hit) {
                *h = (rt_hit){INFINITY,           0.0f,       0.0f, UINT32_MAX, UINT32_MAX, 0,
                              {0.0f, 0.0f, 0.0f}, UINT32_MAX, id};
                continue;
            }
            h->ray_id = id;
            h->t = d->t;
            h->u = d->u;
            h->v = d->v;
            h->prim = d->prim;
            h->inst = d->inst;
            /* An any-hit answer of the packet path names no triangle (inst
             * RT_NO_HIT: only that the packet found a hit): no normal then. */
            const rt_instance *in =
                d->inst < job->flat->hdr.instance_count ? &job->flat->instances[d->inst] : NULL;
            if (!in || d->prim >= job->scene->meshes[in->mesh].triangle_count) {
                h->mesh = UINT32_MAX;
                h->normal[0] = h->normal[1] = h->normal[2] = 0.0f;
                continue;
            }
            h->mesh = in->mesh;
            hit_normal(job->scene, in, d->prim, h->normal);
        }
    }
}

rt_status rt_trace_rays(rt_renderer *r, rt_scene *scene, const rt_ray *rays, size_t count,
                        rt_hit *hits, const rt_trace_options *options) {
    if (!r) return RT_ERROR_INVALID_ARGUMENT;
    rt_status st = rt_frame_query_begin(r, "rt_trace_rays", scene, rays, count, hits, "hits");
    if (st != RT_OK) return st;
    rt_trace_options opt;
    memset(&opt, 0, sizeof opt);
    if (options) opt = *options;
    if (opt.packet_path != RT_TRACE_PATH_AUTO && opt.packet_path != RT_TRACE_PATH_PACKETS &&
        opt.packet_path != RT_TRACE_PATH_SINGLE)
        return rt_fail(&r->error, RT_ERROR_INVALID_ARGUMENT,
                       "rt_trace_rays: unknown packet path %d", (int)opt.packet_path);
    rt_frame_state fs;
    st = rt_frame_layout(r, scene, opt.tri_test, 0, &fs);
    if (st != RT_OK) return st;
    const rt_ray *in;
    rt_ray *copy;
    st = rt_frame_rays(r, rays, count, &in, &copy);
    if (st != RT_OK) return st;
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
        st = fs.ops->trace(fs.state, &fs.layout, in, opt.ray_masks, count, out, opt.any_hit != 0,
                           opt.packet_path, &ts, &r->error);
    /* The trace alone: the backend's builds inside it are build time. */
    ts.trace_ms = rt_now_ms() - t1 - ts.build_ms;
    ts.build_ms += fs.build_ms + prep.build_ms;
    ts.rays = count;
    memcpy(ts.device, prep.device, sizeof ts.device);
    ts.notice = r->notice[0] ? r->notice : NULL;
    if (opt.stats) *opt.stats = ts;
    if (st == RT_OK && count) {
        finish_job job;
        job.scene = scene;
        job.flat = &fs.flat;
        job.in = out;
        job.ids = opt.ray_ids;
        job.out = hits;
        job.count = count;
        atomic_init(&job.next, 0);
        rt_pool_run(fs.layout.pool, finish_chunk, &job);
    }
    free(copy);
    free(out);
    return st;
}
