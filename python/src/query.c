/* SPDX-License-Identifier: Apache-2.0 */
/* query.c - a ray query of the Python package: the caller's arrays read in
 * place, block by block, into the library's rays; the library's hits
 * scattered into the caller's output arrays. Plain C, no Python calls: it
 * runs with the GIL released. */
#include "rtcl_py.h" /* Python.h first, as Python asks */

#include <stdlib.h>
#include <string.h>

/* Rays per library call: big enough that the renderer's workers share each
 * call's rays well, small enough that a block's rays and hits (72 bytes a
 * ray) stay a few MiB whatever the caller's array. */
enum { BLOCK = 1 << 16 };

static void fill_block(const rtcl_query *q, size_t first, size_t n, rt_ray *rays) {
    for (size_t i = 0; i < n; i++) {
        const size_t k = first + i;
        const float *o = q->org + k * q->org_step, *d = q->dir + k * q->dir_step;
        rt_ray *r = &rays[i];
        memcpy(r->org, o, 3 * sizeof(float));
        memcpy(r->dir, d, 3 * sizeof(float));
        r->tmin = q->tmin[k * q->tmin_step];
        r->tmax = q->tmax[k * q->tmax_step];
    }
}

static void scatter_hits(const rtcl_query *q, size_t first, size_t n, const rt_hit *hits) {
    for (size_t i = 0; i < n; i++) {
        const size_t k = first + i;
        const rt_hit *h = &hits[i];
        if (q->kind == RTCL_OCCLUSION) {
            q->occluded[k] = h->hit != 0;
            continue;
        }
        q->t[k] = h->t;
        q->prim[k] = h->prim;
        q->mesh[k] = h->mesh;
        q->inst[k] = h->inst;
        q->uv[2 * k] = h->u;
        q->uv[2 * k + 1] = h->v;
        memcpy(&q->normal[3 * k], h->normal, 3 * sizeof(float));
    }
}

rt_status rtcl_run_query(rt_renderer *renderer, rt_scene *scene, const rtcl_query *q) {
    const size_t block = q->n < BLOCK ? (q->n ? q->n : 1) : BLOCK;
    rt_ray *rays = malloc(block * sizeof *rays);
    rt_hit *hits = q->kind == RTCL_COUNT ? NULL : malloc(block * sizeof *hits);
    rt_status st = RT_OK;
    if (!rays || (q->kind != RTCL_COUNT && !hits)) st = RT_ERROR_OUT_OF_MEMORY;
    rt_trace_options opt;
    memset(&opt, 0, sizeof opt);
    opt.any_hit = q->kind == RTCL_OCCLUSION;
    /* Zero rays still bring the scene's structures up to date (build()). */
    for (size_t first = 0; st == RT_OK && (first < q->n || first == 0); first += block) {
        const size_t n = q->n - first < block ? q->n - first : block;
        fill_block(q, first, n, rays);
        if (q->kind == RTCL_COUNT) {
            st = rt_count_intersections(renderer, scene, rays, n, n ? q->counts + first : NULL);
        } else {
            st = rt_trace_rays(renderer, scene, rays, n, hits, &opt);
            if (st == RT_OK) scatter_hits(q, first, n, hits);
        }
        if (q->n == 0) break;
    }
    free(rays);
    free(hits);
    return st;
}
