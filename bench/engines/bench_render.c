/* SPDX-License-Identifier: Apache-2.0 */
/* bench_render.c - the render part of 'rtcl bench' (bench_render.h).
 *
 * The thesis's set-up (Langr 2016, section 4): 1024x576, one point light,
 * primary plus shadow rays, Phong. Every backend renders the same frame from
 * the same camera with the same thread count; the CPU oracle's image is kept
 * and every other image is compared with it, so that a fast wrong answer
 * shows. Embree traces the same primary and shadow rays and computes the same
 * Phong terms (bench/peer/embree_trace.c); its time includes ray generation
 * and shading like ours. One renderer renders every row, switching backend
 * between frames: the BVHs are built once, as the peer builds its BVH once. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "engines/bench_render.h"
#include "render/renderer_internal.h"
#include "rt.h"
#ifdef RT_HAVE_EMBREE
#include "peer/embree_peer.h"
#endif

static void summarize(render_row *r, double *ms, int n) {
    bench_min_median(ms, n, &r->ms_min, &r->ms_median);
    r->mrays = r->ms_median > 0 ? (double)r->rays / (r->ms_median * 1000.0) : 0.0;
}

/* Pixels of b whose colour differs from the oracle's a (any channel, any
 * bit), those that differ visibly (by more than 1/256 in some channel: a
 * changed hit or shadow, not rounding), and the largest channel difference. */
static void compare_images(const float *a, const float *b, size_t pixels, render_row *r) {
    r->pixels_differ = r->pixels_visible = 0;
    r->max_diff = 0.0;
    for (size_t i = 0; i < pixels; i++) {
        int differ = 0, visible = 0;
        for (int k = 0; k < 3; k++) {
            float x = a[3 * i + k], y = b[3 * i + k];
            if (memcmp(&x, &y, sizeof x) != 0) differ = 1;
            double d = fabs((double)x - (double)y);
            if (d > r->max_diff) r->max_diff = d;
            if (d > 1.0 / 256.0) visible = 1;
        }
        r->pixels_differ += differ;
        r->pixels_visible += visible;
    }
}

/* One row's run: a backend of ours (opt set) or an Embree packet width. */
typedef struct {
    render_row *row;
    const char *backend;   /* ours: the renderer's backend for this row ... */
    rt_renderer *renderer; /* ... on its own renderer (another maths profile), or NULL */
    rt_render_options opt;
    rt_render_stats st;
    rt_framebuffer fb;
    int embree_lanes; /* 0: a backend of ours */
    float *rgb;       /* Embree's image */
    double *ms;       /* the timed frames */
    int failed;
} bench_run;

/* The Embree scene the embree-N runs trace (empty without Embree). */
typedef struct {
#ifdef RT_HAVE_EMBREE
    rt_backend_layout layout; /* the renderer's layout and pool */
    rt_embree *em;
    rt_embree_scene *es;
#else
    int none;
#endif
} embree_peer;

static void run_init(bench_run *r, render_row *row, const bench_render_setup *su) {
    memset(r, 0, sizeof *r);
    r->row = row;
    r->row->threads = su->threads;
    r->ms = malloc(sizeof(double) * (size_t)su->reps);
    if (!r->ms) {
        snprintf(row->error, sizeof row->error, "out of memory");
        r->failed = 1;
    }
}

static void backend_init(bench_run *r, render_row *row, const bench_render_setup *su,
                         const char *backend) {
    run_init(r, row, su);
    snprintf(row->backend, sizeof row->backend, "%s", backend);
    r->backend = backend;
    r->opt = rt_render_options_default();
    r->opt.direct_only = 1;
    r->opt.stats = &r->st;
    /* One framebuffer for every frame, as the Embree peer keeps one. */
    r->opt.reuse_framebuffer = 1;
}

/* Frame i of run r (i < 0: the warm-up frame, not kept). */
static void run_frame(rt_renderer *renderer, rt_scene *scene, const embree_peer *peer, bench_run *r,
                      int i) {
    if (r->failed) return;
    double ms = 0.0;
    if (r->renderer) renderer = r->renderer;
    if (r->embree_lanes) {
#ifdef RT_HAVE_EMBREE
        rt_embree_render(peer->es, r->embree_lanes, peer->layout.pool, r->rgb, &r->row->rays, &ms);
#endif
    } else if (rt_renderer_set_backend(renderer, r->backend) != RT_OK ||
               rt_render(renderer, scene, &r->opt, &r->fb) != RT_OK) {
        snprintf(r->row->error, sizeof r->row->error, "%s", rt_renderer_error(renderer));
        r->failed = 1;
        return;
    } else {
        ms = r->st.render_ms;
    }
    if (i >= 0) r->ms[i] = ms;
}

/* The row's figures once every frame is done; images compared with the
 * oracle's (NULL when the oracle failed). */
static void run_finish(bench_run *r, const bench_render_setup *su, const float *oracle,
                       size_t pixels) {
    render_row *row = r->row;
    if (!r->failed) {
        if (r->embree_lanes) {
            row->box_tests = row->tri_tests = -1.0;
        } else {
            row->threads = r->st.threads ? r->st.threads : su->threads;
            row->rays = r->st.rays;
            row->box_tests = r->st.rays ? (double)r->st.box_tests / (double)r->st.rays : 0.0;
            row->tri_tests = r->st.rays ? (double)r->st.tri_tests / (double)r->st.rays : 0.0;
        }
        const float *image = r->embree_lanes ? r->rgb : r->fb.pixels;
        if (oracle && image != oracle) compare_images(oracle, image, pixels, row);
        summarize(row, r->ms, su->reps);
    }
    free(r->ms);
    free(r->rgb);
    r->ms = NULL;
    r->rgb = NULL;
}

#ifdef RT_HAVE_EMBREE
/* Runs embree-1, -4, -8 (and -16 where Embree traces 16 natively) in rows;
 * returns how many (0 with the reason in rows[0].error when Embree cannot
 * run). */
static int embree_init(rt_renderer *renderer, rt_scene *scene, const bench_render_setup *su,
                       embree_peer *peer, bench_run *runs, render_row *rows) {
    rt_error msg;
    memset(&msg, 0, sizeof msg);
    snprintf(rows[0].backend, sizeof rows[0].backend, "embree");
    rows[0].threads = su->threads;
    double build_ms, sah;
    if (rt_renderer_layout(renderer, scene, &peer->layout, &build_ms, &sah) != RT_OK) {
        snprintf(rows[0].error, sizeof rows[0].error, "%s", rt_renderer_error(renderer));
        return 0;
    }
    if (rt_embree_create(su->threads, &peer->em, &msg) != RT_OK ||
        rt_embree_scene_create(peer->em, peer->layout.flat, &peer->es, &(double){0}, &msg) !=
            RT_OK) {
        snprintf(rows[0].error, sizeof rows[0].error, "%.199s", msg.message);
        return 0;
    }
    size_t px = (size_t)peer->layout.flat->hdr.width * (size_t)peer->layout.flat->hdr.height;
    static const int widths[] = {1, 4, 8, 16};
    int n = 0;
    for (size_t w = 0; w < 4; w++) {
        if (!rt_embree_native_lanes(peer->em, widths[w])) continue;
        bench_run *r = &runs[n];
        run_init(r, &rows[n], su);
        n++;
        snprintf(r->row->backend, sizeof r->row->backend, "embree-%d", widths[w]);
        r->row->threads = rt_pool_size(peer->layout.pool);
        r->row->lanes = r->embree_lanes = widths[w];
        r->rgb = malloc(3 * sizeof(float) * px);
        if (!r->rgb && !r->failed) {
            snprintf(r->row->error, sizeof r->row->error, "out of memory");
            r->failed = 1;
        }
    }
    return n;
}

/* Row "embree" after the width rows: a copy of the fastest by median. */
static int embree_best(render_row *rows, int n) {
    int best = -1;
    for (int i = 0; i < n; i++)
        if (!rows[i].error[0] && (best < 0 || rows[i].ms_median < rows[best].ms_median)) best = i;
    if (best < 0) return n;
    rows[n] = rows[best];
    snprintf(rows[n].backend, sizeof rows[n].backend, "embree");
    return n + 1;
}
#endif

int bench_render(const char *path, const bench_render_setup *su, render_row *rows, char *err,
                 size_t err_size) {
    rt_scene *scene = NULL;
    rt_error e;
    if (su->progress) su->progress(path, "loading for rendering");
    if (rt_scene_open(path, &scene, &e) != RT_OK) {
        snprintf(err, err_size, "%s", e.message);
        return 0;
    }
    if (su->accel >= 0 && rt_scene_set_static_accel(scene, (rt_accel)su->accel) != RT_OK) {
        snprintf(err, err_size, "%s", rt_scene_error(scene));
        rt_scene_destroy(scene);
        return 0;
    }
    rt_camera cam;
    rt_camera_get(scene, &cam);
    cam.width = su->width;
    cam.height = su->height;
    if (rt_camera_set(scene, &cam) != RT_OK) {
        snprintf(err, err_size, "%s", rt_scene_error(scene));
        rt_scene_destroy(scene);
        return 0;
    }
    memset(rows, 0, sizeof(render_row) * BENCH_RENDER_MAX_ROWS);
    rt_renderer_options ro = rt_renderer_options_default();
    ro.threads = su->threads;
    ro.device_math = (rt_device_math)su->device_math;
    ro.denormals = (rt_denormals)su->denormals;
    rt_renderer *renderer = NULL, *portable = NULL;
    rt_error re;
    if (rt_renderer_create(&ro, &renderer, &re) != RT_OK) {
        snprintf(err, err_size, "%s", re.message);
        rt_scene_destroy(scene);
        return 0;
    }
    static const char *backends[] = {"cpu", "packet", "opencl", "opencl"};
    /* The portable profile's cost: a row of its own, on a second renderer
     * (the profile is the renderer's), unless the opencl row runs it. */
    int ours = su->device_math == RT_DEVICE_MATH_PORTABLE ? 3 : 4;
    bench_run runs[BENCH_RENDER_MAX_ROWS];
    embree_peer peer;
    memset(&peer, 0, sizeof peer);
    for (int b = 0; b < ours; b++) backend_init(&runs[b], &rows[b], su, backends[b]);
    if (ours == 4) {
        snprintf(rows[3].backend, sizeof rows[3].backend, "opencl-portable");
        ro.backend = "opencl";
        ro.device_math = RT_DEVICE_MATH_PORTABLE;
        if (rt_renderer_create(&ro, &portable, &re) != RT_OK) {
            snprintf(rows[3].error, sizeof rows[3].error, "%.199s", re.message);
            runs[3].failed = 1;
        }
        runs[3].renderer = portable;
    }
    /* The Vulkan row (always the portable maths profile). */
    backend_init(&runs[ours], &rows[ours], su, "vulkan");
    ours++;
    int n = ours; /* runs */
#ifdef RT_HAVE_EMBREE
    n += embree_init(renderer, scene, su, &peer, &runs[ours], &rows[ours]);
#endif
    /* Frames interleaved round by round, every run's frame i before any run's
     * frame i + 1, so that a disturbance of the shared machine falls on every
     * backend alike and the ratios hold; round -1 is the warm-up. Each timed
     * frame follows an untimed one of the same run, so that it finds the
     * caches as its own previous frame left them (as in a frame loop), not
     * as another backend's, or another Embree width over the same BVH, did. */
    for (int i = -1; i < su->reps; i++) {
        if (su->progress) {
            char what[48];
            snprintf(what, sizeof what, i < 0 ? "warm-up frames" : "frame %d of %d", i + 1,
                     su->reps);
            su->progress(path, what);
        }
        for (int k = 0; k < n; k++) {
            if (i >= 0) run_frame(renderer, scene, &peer, &runs[k], -1);
            run_frame(renderer, scene, &peer, &runs[k], i);
            if (i < 0 && su->build_log && !runs[k].embree_lanes && !runs[k].failed)
                su->build_log(runs[k].renderer ? runs[k].renderer : renderer);
        }
    }
    size_t px = (size_t)su->width * (size_t)su->height;
    const float *oracle = runs[0].failed ? NULL : runs[0].fb.pixels; /* cpu's */
    for (int k = 0; k < n; k++) run_finish(&runs[k], su, oracle, px);
    for (int k = 0; k < ours; k++) rt_framebuffer_free(&runs[k].fb);
#ifdef RT_HAVE_EMBREE
    /* Then row "embree", or the row with the reason Embree cannot run. */
    n = n > ours ? ours + embree_best(&rows[ours], n - ours) : ours + 1;
    rt_embree_scene_destroy(peer.es);
    rt_embree_destroy(peer.em);
#endif
    rt_renderer_destroy(portable);
    rt_renderer_destroy(renderer);
    rt_scene_destroy(scene);
    return n;
}
