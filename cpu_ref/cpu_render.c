/* SPDX-License-Identifier: Apache-2.0 */
/* cpu_render.c - the scalar oracle: one ray at a time through the shared
 * header, threads over interleaved rows. Each pixel depends only on its own
 * rays, so the image does not depend on the thread count. */
#include "cpu_render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void rt_cpu_finish_pixel(const rt_cpu_frame *f, const rt_scene_view *v, int x, int y,
                         const rt_ray *ray, const rt_hit_d *hit, rt_counters *c) {
    size_t i = ((size_t)y * (size_t)v->hdr->width + (size_t)x) * (size_t)f->channels;
    float *out = f->pixels + i;
    int hit_any = hit->prim != RT_NO_HIT;
    switch (f->aov) {
    case RT_AOV_DEPTH:
        out[0] = hit_any ? hit->t : INFINITY;
        return;
    case RT_AOV_PRIMID:
        out[0] = hit_any ? (float)hit->prim : -1.0f;
        return;
    case RT_AOV_INSTID:
        out[0] = hit_any ? (float)hit->inst : -1.0f;
        return;
    case RT_AOV_NORMAL:
        out[0] = out[1] = out[2] = 0.0f;
        if (hit_any) {
            rt_surface sf;
            rt_surface_at(v, ray, hit, &sf);
            memcpy(out, sf.ns, 3 * sizeof(float));
        }
        return;
    default:
        break;
    }
    float rgb[3];
    rt_shade_hit(v, ray, hit, c, rgb);
    if (f->aov == RT_AOV_NONE) memcpy(out, rgb, sizeof rgb);
}

typedef struct cpu_job {
    const rt_cpu_frame *frame;
    rt_cpu_counts per_worker[256];
} cpu_job;

static void add_counts(rt_cpu_counts *dst, const rt_counters *c) {
    dst->rays += c->rays;
    dst->box_tests += c->box_tests;
    dst->tri_tests += c->tri_tests;
}

static void cpu_rows(void *ctx, int worker, int workers) {
    cpu_job *job = ctx;
    const rt_cpu_frame *f = job->frame;
    rt_scene_view v = rt_flat_view(f->flat);
    const int w = v.hdr->width, h = v.hdr->height;
    rt_cpu_counts *total = &job->per_worker[worker];
    for (int y = worker; y < h; y += workers) {
        for (int x = 0; x < w; x++) {
            rt_counters c = {0, 0, 0};
            rt_ray ray;
            rt_hit_d hit;
            rt_camera_ray(v.hdr, x, y, &ray);
            rt_trace(&v, &ray, 0, &hit, &c);
            rt_cpu_finish_pixel(f, &v, x, y, &ray, &hit, &c);
            if (f->aov == RT_AOV_BOX_TESTS) f->pixels[(size_t)y * w + x] = (float)c.box_tests;
            if (f->aov == RT_AOV_TRI_TESTS) f->pixels[(size_t)y * w + x] = (float)c.tri_tests;
            add_counts(total, &c);
        }
        total->primary_rays += (uint64_t)w;
        if (worker == 0 && f->progress) f->progress(f->progress_user, (double)(y + 1) / h);
    }
}

rt_status rt_cpu_render(const rt_cpu_frame *frame, rt_pool *pool, rt_cpu_counts *counts) {
    cpu_job *job = calloc(1, sizeof *job);
    if (!job) return RT_ERROR_OUT_OF_MEMORY;
    job->frame = frame;
    /* Counts are kept for at most 256 workers; beyond, one thread renders. */
    rt_pool_run_fp(pool && rt_pool_size(pool) <= 256 ? pool : NULL, cpu_rows, job,
                   frame->flush_denormals);
    memset(counts, 0, sizeof *counts);
    for (int i = 0; i < 256; i++) {
        counts->rays += job->per_worker[i].rays;
        counts->primary_rays += job->per_worker[i].primary_rays;
        counts->box_tests += job->per_worker[i].box_tests;
        counts->tri_tests += job->per_worker[i].tri_tests;
    }
    free(job);
    return RT_OK;
}

void rt_cpu_trace_rays(const rt_flat *flat, const rt_ray *rays, const uint32_t *masks, size_t n,
                       rt_hit_d *hits, int any_hit, rt_counters *c) {
    rt_scene_view v = rt_flat_view(flat);
    for (size_t i = 0; i < n; i++)
        rt_trace_masked(&v, &rays[i], masks ? masks[i] : 0xffffffffu, any_hit, &hits[i], c);
}
