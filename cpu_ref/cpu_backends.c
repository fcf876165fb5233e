/* SPDX-License-Identifier: Apache-2.0 */
/* cpu_backends.c - the two CPU backends behind host/backend/backend.h: "cpu"
 * (the scalar oracle, cpu_render.c) and "packet" (ray packets through wide
 * copies of the BVHs, packet_render.c). Both run on the renderer's pool. */
#include "cpu_backends.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/error.h"
#include "cpu_render.h"
#include "kernel_maths.h"

/* ---- ray queries, shared by both -------------------------------------- */

typedef struct trace_job {
    const rt_cpu_frame *tracers; /* flat, and for packets the wide BVHs and builds */
    int packets;                 /* 0: the scalar oracle */
    const rt_ray *rays;
    const uint32_t *masks; /* NULL: every ray's mask is 0xffffffff */
    rt_hit_d *hits;
    size_t count;
    int any_hit;
    rt_trace_path path;
    atomic_size_t next;
    atomic_ullong packet_rays;
} trace_job;

/* Chunks of whole packets taken in turn, so that neighbouring rays (which
 * callers tend to give in order) share packets and a worker that finishes
 * early takes more. */
enum { TRACE_CHUNK = 16 * RT_PK_LANES };

static void trace_chunk(void *ctx, int worker, int workers) {
    (void)worker;
    (void)workers;
    trace_job *job = ctx;
    uint64_t packet_rays = 0;
    for (;;) {
        size_t first = atomic_fetch_add_explicit(&job->next, TRACE_CHUNK, memory_order_relaxed);
        if (first >= job->count) break;
        size_t n = job->count - first < TRACE_CHUNK ? job->count - first : TRACE_CHUNK;
        rt_counters c = {0, 0, 0};
        const uint32_t *masks = job->masks ? job->masks + first : NULL;
        if (job->packets)
            rt_packet_trace_rays(job->tracers, job->rays + first, masks, n, job->hits + first,
                                 job->any_hit, job->path, &c, &packet_rays);
        else
            rt_cpu_trace_rays(job->tracers->flat, job->rays + first, masks, n, job->hits + first,
                              job->any_hit, &c);
    }
    atomic_fetch_add_explicit(&job->packet_rays, packet_rays, memory_order_relaxed);
}

static void fill_counts(rt_render_stats *stats, const rt_cpu_counts *counts) {
    stats->rays = counts->rays;
    stats->primary_rays = counts->primary_rays;
    stats->box_tests = counts->box_tests;
    stats->tri_tests = counts->tri_tests;
    stats->packets = counts->packets;
    stats->packet_box_tests = counts->packet_box_tests;
    stats->packet_tri_tests = counts->packet_tri_tests;
}

/* One frame on the pool: the scalar oracle, or packets through wide (with
 * the build isa) when wide is given. */
static rt_status render_frame(const rt_backend_layout *layout, const rt_backend_frame *frame,
                              const rt_wide_bvh *wide, const rt_cpu_isa *isa,
                              const rt_wide_bvh *single, int flush, rt_render_stats *stats,
                              rt_error *err) {
    rt_cpu_frame f = {layout->flat,
                      wide,
                      isa,
                      frame->aov,
                      frame->pixels,
                      frame->channels,
                      frame->progress,
                      frame->progress_user,
                      flush,
                      single};
    rt_cpu_counts counts;
    double t0 = rt_now_ms();
    rt_status st = wide ? rt_packet_render(&f, layout->pool, &counts)
                        : rt_cpu_render(&f, layout->pool, &counts);
    if (st != RT_OK) return rt_fail(err, st, "%s: out of memory", wide ? "packet" : "cpu");
    stats->render_ms = rt_now_ms() - t0;
    fill_counts(stats, &counts);
    stats->threads = rt_pool_size(layout->pool);
    /* The CPU backends are the oracle (the packet tracer gives its bits), in
     * IEEE single precision, in the denormal mode asked for. */
    stats->exact = 1;
    stats->math_profile = "ieee";
    stats->denormals = flush ? "flush" : "preserve";
    return RT_OK;
}

/* Ray queries on the pool: the scalar oracle, or (tracers->wide given)
 * packets and single rays as rt_packet_trace_rays chooses. Returns the
 * number of rays that went in packets. */
static uint64_t trace_all(const rt_backend_layout *layout, const rt_cpu_frame *tracers, int flush,
                          const rt_ray *rays, const uint32_t *masks, size_t count, rt_hit_d *hits,
                          int any_hit, rt_trace_path path) {
    trace_job job;
    memset(&job, 0, sizeof job);
    job.tracers = tracers;
    job.packets = tracers->wide != NULL;
    job.rays = rays;
    job.masks = masks;
    job.hits = hits;
    job.count = count;
    job.any_hit = any_hit;
    job.path = path;
    atomic_init(&job.next, 0);
    atomic_init(&job.packet_rays, 0);
    rt_pool_run_fp(layout->pool, trace_chunk, &job, flush);
    return atomic_load(&job.packet_rays);
}

/* "flush" needs a CPU whose denormal mode the backend can set. */
static rt_status check_denormals(const char *name, const rt_backend_config *config, rt_error *err) {
    if (config->flush_denormals && !rt_fp_can_flush())
        return rt_fail(err, RT_ERROR_UNSUPPORTED,
                       "%s: this CPU build cannot set flush-to-zero (denormals 'flush' needs "
                       "x86 SSE or AArch64)",
                       name);
    return RT_OK;
}

static int always_available(rt_error *why) {
    (void)why;
    return 1;
}

/* ---- cpu: the scalar oracle -------------------------------------------- */

/* The oracle keeps one thing, its denormal mode: a state that is NULL
 * preserves denormals, any other pointer flushes them. */
static int cpu_flush_mark;

static rt_status cpu_create(const rt_backend_config *config, void **state, rt_error *err) {
    rt_status st = check_denormals("cpu", config, err);
    if (st != RT_OK) return st;
    *state = config->flush_denormals ? &cpu_flush_mark : NULL;
    return RT_OK;
}

static rt_status cpu_prepare(void *state, const rt_backend_layout *layout, rt_render_stats *stats,
                             rt_error *err) {
    (void)state;
    (void)layout;
    (void)stats;
    (void)err;
    return RT_OK;
}

static rt_status cpu_render(void *state, const rt_backend_layout *layout,
                            const rt_backend_frame *frame, rt_render_stats *stats, rt_error *err) {
    return render_frame(layout, frame, NULL, NULL, NULL, state != NULL, stats, err);
}

static rt_status cpu_trace(void *state, const rt_backend_layout *layout, const rt_ray *rays,
                           const uint32_t *masks, size_t count, rt_hit_d *hits, int any_hit,
                           rt_trace_path path, rt_trace_stats *stats, rt_error *err) {
    (void)err;
    (void)path;
    (void)stats;
    rt_cpu_frame tracers;
    memset(&tracers, 0, sizeof tracers);
    tracers.flat = layout->flat;
    trace_all(layout, &tracers, state != NULL, rays, masks, count, hits, any_hit,
              RT_TRACE_PATH_AUTO);
    return RT_OK;
}

static void cpu_destroy(void *state) {
    (void)state;
}

const rt_backend_ops rt_backend_cpu = {"cpu",      always_available, cpu_create,  cpu_prepare,
                                       cpu_render, cpu_trace,        cpu_destroy, NULL,
                                       NULL};

/* ---- packet: ray packets through wide BVHs ------------------------------ */

/* One of the packet backend's wide trees and the layout generation it
 * was made for. */
typedef struct wide_copy {
    rt_wide_bvh bvh;
    uint32_t generation;
    int have;
} wide_copy;

typedef struct packet_state {
    const rt_cpu_isa *isa; /* the build of both tracers */
    wide_copy packets;     /* the packet tracer's trees (rt_pk_shape) */
    /* The single-ray tracer's trees (rt_sw_shape), for incoherent rays;
     * made when first needed. */
    wide_copy single;
    int flush; /* denormals */
} packet_state;

static rt_status packet_create(const rt_backend_config *config, void **state, rt_error *err) {
    const rt_cpu_isa *isa = rt_cpu_isa_find(config->packet_isa);
    if (!isa) {
        char names[128] = "";
        for (int i = 0; rt_cpu_isa_at(i); i++) {
            if (!rt_cpu_isa_find(rt_cpu_isa_at(i))) continue;
            if (names[0]) strncat(names, ", ", sizeof names - strlen(names) - 1);
            strncat(names, rt_cpu_isa_at(i), sizeof names - strlen(names) - 1);
        }
        return rt_fail(err, RT_ERROR_UNSUPPORTED,
                       "packet: instruction set '%s' is not in this build or not run by this CPU "
                       "(here: %s)",
                       config->packet_isa, names);
    }
    rt_status st = check_denormals("packet", config, err);
    if (st != RT_OK) return st;
    packet_state *s = calloc(1, sizeof *s);
    if (!s) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "packet: out of memory");
    s->isa = isa;
    s->flush = config->flush_denormals;
    *state = s;
    return RT_OK;
}

/* Brings c up to date with the layout: refitted when only refits happened
 * since it was made (the layout rewritten in place from c's generation with
 * every mesh tree's shape kept), else made anew from the layout's nodes.
 * The time counts as build time (stats may be NULL). */
static rt_status wide_update(wide_copy *c, const rt_backend_layout *layout, rt_wide_shape shape,
                             const char *what, rt_render_stats *stats, rt_error *err) {
    if (c->have && c->generation == layout->layout_generation) return RT_OK;
    const double t0 = rt_now_ms();
    rt_status st = RT_ERROR_OUT_OF_MEMORY;
    if (c->have && layout->base_generation && c->generation == layout->base_generation &&
        layout->shapes_kept)
        st = rt_wide_refit(layout->flat, &c->bvh);
    if (st != RT_OK) {
        rt_wide_free(&c->bvh);
        c->have = 0;
        if (rt_wide_build(layout->flat, shape, &c->bvh) != RT_OK)
            return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "packet: out of memory (%s)", what);
    }
    c->have = 1;
    c->generation = layout->layout_generation;
    if (stats) stats->build_ms += rt_now_ms() - t0;
    return RT_OK;
}

static rt_status packet_prepare(void *state, const rt_backend_layout *layout,
                                rt_render_stats *stats, rt_error *err) {
    packet_state *s = state;
    return wide_update(&s->packets, layout, rt_pk_shape(), "wide BVH", stats, err);
}

static rt_status ensure_single(packet_state *s, const rt_backend_layout *layout,
                               rt_render_stats *stats, rt_error *err) {
    return wide_update(&s->single, layout, rt_sw_shape(rt_cpu_isa_width(s->isa)), "single-ray BVH",
                       stats, err);
}

static rt_status packet_render(void *state, const rt_backend_layout *layout,
                               const rt_backend_frame *frame, rt_render_stats *stats,
                               rt_error *err) {
    packet_state *s = state;
    /* Reflections and refractions, and their shadow rays, go one by one
     * through the single-ray tracer. */
    const int secondary = (layout->flat->hdr.flags & RT_SCENE_SECONDARY) != 0;
    if (secondary) {
        rt_status st = ensure_single(s, layout, stats, err);
        if (st != RT_OK) return st;
    }
    rt_status st = render_frame(layout, frame, &s->packets.bvh, s->isa,
                                secondary ? &s->single.bvh : NULL, s->flush, stats, err);
    if (st != RT_OK) return st;
    stats->packet_rays = RT_PK_LANES;
    stats->packet_isa = rt_cpu_isa_name(s->isa);
    stats->packet_vector = rt_cpu_isa_lanes(s->isa);
    return RT_OK;
}

static rt_status packet_trace(void *state, const rt_backend_layout *layout, const rt_ray *rays,
                              const uint32_t *masks, size_t count, rt_hit_d *hits, int any_hit,
                              rt_trace_path path, rt_trace_stats *stats, rt_error *err) {
    packet_state *s = state;
    const double t0 = rt_now_ms();
    rt_status st = ensure_single(s, layout, NULL, err);
    stats->build_ms += rt_now_ms() - t0;
    if (st != RT_OK) return st;
    rt_cpu_frame tracers;
    memset(&tracers, 0, sizeof tracers);
    tracers.flat = layout->flat;
    tracers.wide = &s->packets.bvh;
    tracers.isa = s->isa;
    tracers.single = &s->single.bvh;
    stats->packet_rays =
        trace_all(layout, &tracers, s->flush, rays, masks, count, hits, any_hit, path);
    stats->single_rays = count - stats->packet_rays;
    stats->isa = rt_cpu_isa_name(s->isa);
    return RT_OK;
}

/* A wide tree's bytes: its nodes and their binary sources (for refits),
 * its triangle blocks, its instance roots. */
static uint64_t wide_bytes(const rt_wide_bvh *b) {
    const uint64_t w = (uint64_t)b->shape.width;
    return ((uint64_t)b->node_count * (RT_WIDE_NODE_WORDS(w) + (b->src ? w : 0)) +
            (uint64_t)b->block_count * RT_WIDE_BLOCK_WORDS(w) + b->inst_count) *
           sizeof(uint32_t);
}

/* The packet backend's copies: the packet tracer's trees and, once made,
 * the single-ray tracer's (with their triangle blocks). */
static void packet_memory(void *state, uint64_t *host, uint64_t *device) {
    const packet_state *s = state;
    *device = 0;
    *host = (s->packets.have ? wide_bytes(&s->packets.bvh) : 0) +
            (s->single.have ? wide_bytes(&s->single.bvh) : 0);
}

static void packet_destroy(void *state) {
    packet_state *s = state;
    if (!s) return;
    rt_wide_free(&s->packets.bvh);
    rt_wide_free(&s->single.bvh);
    free(s);
}

const rt_backend_ops rt_backend_packet = {
    "packet",     always_available, packet_create, packet_prepare, packet_render,
    packet_trace, packet_destroy,   NULL,          packet_memory};
