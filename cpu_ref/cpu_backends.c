/* cpu_backends.c - the two CPU backends behind host/backend/backend.h: "cpu"
 * (the scalar oracle, cpu_render.c) and "packet" (ray packets through wide
 * copies of the BVHs, packet_render.c). Both run on the renderer's pool. */
#include "cpu_backends.h"

#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/error.h"
#include "cpu_render.h"
#include "rt_fp_mode.h"

/* ---- ray queries, shared by both -------------------------------------- */

typedef struct trace_job {
    const rt_flat *flat;
    const rt_pk_wide *wide; /* NULL: the scalar oracle */
    const rt_pk_variant *isa;
    const rt_ray_d *rays;
    rt_hit_d *hits;
    size_t count;
    int any_hit;
} trace_job;

static void trace_chunk(void *ctx, int worker, int workers) {
    trace_job *job = ctx;
    /* Contiguous chunks of whole packets, so that neighbouring rays (which
     * callers tend to give in order) share packets. */
    size_t per = (job->count + (size_t)workers - 1) / (size_t)workers;
    per = (per + RT_PK_LANES - 1) / RT_PK_LANES * RT_PK_LANES;
    size_t first = per * (size_t)worker;
    if (first >= job->count) return;
    size_t n = job->count - first < per ? job->count - first : per;
    rt_counters c = {0, 0, 0};
    if (job->wide)
        rt_packet_trace_rays(job->flat, job->wide, job->isa, job->rays + first, n,
                             job->hits + first, job->any_hit, &c);
    else
        rt_cpu_trace_rays(job->flat, job->rays + first, n, job->hits + first, job->any_hit, &c);
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
                              const rt_pk_wide *wide, const rt_pk_variant *isa, int flush,
                              rt_render_stats *stats, rt_error *err) {
    rt_cpu_frame f = {layout->flat,
                      wide,
                      isa,
                      frame->aov,
                      frame->pixels,
                      frame->channels,
                      frame->progress,
                      frame->progress_user,
                      flush};
    rt_cpu_counts counts;
    double t0 = rt_now_ms();
    rt_status st = wide ? rt_packet_render(&f, layout->pool, &counts)
                        : rt_cpu_render(&f, layout->pool, &counts);
    if (st != RT_OK) return rt_fail(err, st, "%s: out of memory", wide ? "packet" : "cpu");
    stats->render_ms = rt_now_ms() - t0;
    fill_counts(stats, &counts);
    stats->threads = rt_pool_size(layout->pool);
    stats->exact = 1; /* the oracle, in the denormal mode asked for */
    stats->math_profile = "ieee";
    stats->denormals = flush ? "flush" : "preserve";
    return RT_OK;
}

/* Ray queries on the pool, as render_frame chooses. */
static void trace_all(const rt_backend_layout *layout, const rt_pk_wide *wide,
                      const rt_pk_variant *isa, int flush, const rt_ray_d *rays, size_t count,
                      rt_hit_d *hits, int any_hit) {
    trace_job job = {layout->flat, wide, isa, rays, hits, count, any_hit};
    rt_pool_run_fp(layout->pool, trace_chunk, &job, flush);
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
    return render_frame(layout, frame, NULL, NULL, state != NULL, stats, err);
}

static rt_status cpu_trace(void *state, const rt_backend_layout *layout, const rt_ray_d *rays,
                           size_t count, rt_hit_d *hits, int any_hit, rt_error *err) {
    (void)err;
    trace_all(layout, NULL, NULL, state != NULL, rays, count, hits, any_hit);
    return RT_OK;
}

static void cpu_destroy(void *state) {
    (void)state;
}

const rt_backend_ops rt_backend_cpu = {"cpu",      always_available, cpu_create, cpu_prepare,
                                       cpu_render, cpu_trace,        cpu_destroy};

/* ---- packet: ray packets through wide BVHs ------------------------------ */

typedef struct packet_state {
    const rt_pk_variant *isa;
    rt_pk_wide wide;          /* the wide BVHs of the layout ... */
    uint32_t wide_generation; /* ... of this generation */
    int have_wide;
    int flush; /* denormals */
} packet_state;

static rt_status packet_create(const rt_backend_config *config, void **state, rt_error *err) {
    const rt_pk_variant *isa = rt_pk_variant_find(config->packet_isa);
    if (!isa) {
        char names[128] = "";
        for (int i = 0; rt_pk_isa_name(i); i++) {
            if (!rt_pk_variant_find(rt_pk_isa_name(i))) continue;
            if (names[0]) strncat(names, ", ", sizeof names - strlen(names) - 1);
            strncat(names, rt_pk_isa_name(i), sizeof names - strlen(names) - 1);
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

/* The wide BVHs are made from the layout's nodes: again whenever the layout
 * was remade. Their time counts as build time. */
static rt_status packet_prepare(void *state, const rt_backend_layout *layout,
                                rt_render_stats *stats, rt_error *err) {
    packet_state *s = state;
    if (s->have_wide && s->wide_generation == layout->layout_generation) return RT_OK;
    double t0 = rt_now_ms();
    rt_pk_wide_free(&s->wide);
    s->have_wide = 0;
    if (rt_pk_wide_build(layout->flat, &s->wide) != RT_OK)
        return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "packet: out of memory (wide BVH)");
    s->have_wide = 1;
    s->wide_generation = layout->layout_generation;
    stats->build_ms += rt_now_ms() - t0;
    return RT_OK;
}

static rt_status packet_render(void *state, const rt_backend_layout *layout,
                               const rt_backend_frame *frame, rt_render_stats *stats,
                               rt_error *err) {
    packet_state *s = state;
    rt_status st = render_frame(layout, frame, &s->wide, s->isa, s->flush, stats, err);
    if (st != RT_OK) return st;
    stats->packet_rays = RT_PK_LANES;
    stats->packet_isa = rt_pk_variant_name(s->isa);
    stats->packet_vector = rt_pk_variant_lanes(s->isa);
    return RT_OK;
}

static rt_status packet_trace(void *state, const rt_backend_layout *layout, const rt_ray_d *rays,
                              size_t count, rt_hit_d *hits, int any_hit, rt_error *err) {
    packet_state *s = state;
    (void)err;
    trace_all(layout, &s->wide, s->isa, s->flush, rays, count, hits, any_hit);
    return RT_OK;
}

static void packet_destroy(void *state) {
    packet_state *s = state;
    if (!s) return;
    rt_pk_wide_free(&s->wide);
    free(s);
}

const rt_backend_ops rt_backend_packet = {"packet",       always_available, packet_create,
                                          packet_prepare, packet_render,    packet_trace,
                                          packet_destroy};
