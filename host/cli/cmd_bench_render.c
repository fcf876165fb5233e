/* cmd_bench_render.c - the render part of 'rtcl bench' (bench_render.h).
 *
 * The thesis's set-up (Langr 2016, section 4): 1024x576, one point light,
 * primary plus shadow rays, Phong. Every backend renders the same frame from
 * the same camera with the same thread count; the CPU oracle's image is kept
 * and every other image is compared with it, so that a fast wrong answer
 * shows. Embree traces the same primary and shadow rays and computes the same
 * Phong terms (host/embree_trace.c); its time includes ray generation and
 * shading like ours. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_render.h"
#include "render_internal.h"
#include "rt.h"
#ifdef RT_HAVE_EMBREE
#include "embree_peer.h"
#endif

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void summarize(render_row *r, double *ms, int n) {
    qsort(ms, (size_t)n, sizeof *ms, cmp_double);
    r->ms_min = ms[0];
    r->ms_median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
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

static void bench_backend(rt_scene *scene, const bench_render_setup *su, const char *backend,
                          const float *oracle, float **image_out, render_row *r) {
    snprintf(r->backend, sizeof r->backend, "%s", backend);
    rt_render_stats st;
    rt_render_options opt = rt_render_options_default();
    opt.backend = backend;
    opt.threads = su->threads;
    opt.direct_only = 1;
    opt.stats = &st;
    /* One framebuffer for every frame, as the Embree peer keeps one. */
    opt.reuse_framebuffer = 1;
    rt_framebuffer fb;
    memset(&fb, 0, sizeof fb);
    double *ms = malloc(sizeof(double) * (size_t)su->reps);
    if (!ms) {
        snprintf(r->error, sizeof r->error, "out of memory");
        return;
    }
    for (int i = -1; i < su->reps; i++) {
        if (rt_render(scene, &opt, &fb) != RT_OK) {
            snprintf(r->error, sizeof r->error, "%s", rt_scene_error(scene));
            rt_framebuffer_free(&fb);
            free(ms);
            return;
        }
        if (i >= 0) ms[i] = st.render_ms;
    }
    size_t px = (size_t)fb.width * (size_t)fb.height;
    if (oracle) compare_images(oracle, fb.pixels, px, r);
    if (image_out) {
        *image_out = fb.pixels;
        fb.pixels = NULL;
    }
    rt_framebuffer_free(&fb);
    r->threads = st.threads ? st.threads : su->threads;
    r->rays = st.rays;
    r->box_tests = st.rays ? (double)st.box_tests / (double)st.rays : 0.0;
    r->tri_tests = st.rays ? (double)st.tri_tests / (double)st.rays : 0.0;
    summarize(r, ms, su->reps);
    free(ms);
}

#ifdef RT_HAVE_EMBREE
/* Rows embree-1, -4, -8 (and -16 where Embree traces 16 natively), then
 * "embree": a copy of the fastest by median. */
static int bench_embree(rt_scene *scene, const char *path, const bench_render_setup *su,
                        const float *oracle, render_row *rows) {
    int n = 0;
    rt_prepared prep;
    char msg[200] = "";
    rt_embree *em = NULL;
    rt_embree_scene *es = NULL;
    render_row *first = rows;
    snprintf(first->backend, sizeof first->backend, "embree");
    first->threads = su->threads;
    double setup_ms;
    if (rt_render_prepare(scene, su->threads, &prep) != RT_OK) {
        snprintf(first->error, sizeof first->error, "%s", rt_scene_error(scene));
        return 1;
    }
    if (rt_embree_create(su->threads, &em, msg, sizeof msg) != RT_OK ||
        rt_embree_scene_create(em, prep.flat, &es, &setup_ms, msg, sizeof msg) != RT_OK) {
        snprintf(first->error, sizeof first->error, "%s", msg);
        rt_embree_destroy(em);
        return 1;
    }
    size_t px = (size_t)prep.flat->hdr.width * (size_t)prep.flat->hdr.height;
    float *rgb = malloc(3 * sizeof(float) * px);
    double *ms = malloc(sizeof(double) * (size_t)su->reps);
    static const int widths[] = {1, 4, 8, 16};
    for (size_t w = 0; w < 4 && rgb && ms; w++) {
        if (!rt_embree_native_lanes(em, widths[w])) continue;
        render_row *r = &rows[n++];
        memset(r, 0, sizeof *r);
        snprintf(r->backend, sizeof r->backend, "embree-%d", widths[w]);
        char what[32];
        snprintf(what, sizeof what, "%s", r->backend);
        if (su->progress) su->progress(path, what);
        r->threads = rt_pool_size(prep.pool);
        r->lanes = widths[w];
        r->box_tests = r->tri_tests = -1.0;
        for (int i = -1; i < su->reps; i++) {
            double t;
            rt_embree_render(es, widths[w], prep.pool, rgb, &r->rays, &t);
            if (i >= 0) ms[i] = t;
        }
        summarize(r, ms, su->reps);
        if (oracle) compare_images(oracle, rgb, px, r);
    }
    if (!rgb || !ms) snprintf(first->error, sizeof first->error, "out of memory");
    free(rgb);
    free(ms);
    rt_embree_scene_destroy(es);
    rt_embree_destroy(em);
    if (n == 0) return 1;
    int best = 0;
    for (int i = 1; i < n; i++)
        if (rows[i].ms_median < rows[best].ms_median) best = i;
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
    if (rt_scene_load(path, &scene, &e) != RT_OK) {
        snprintf(err, err_size, "%s", e.message);
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
    static const char *backends[] = {"cpu", "packet", "opencl"};
    float *oracle = NULL;
    int n = 0;
    for (int b = 0; b < 3; b++) {
        if (su->progress) su->progress(path, backends[b]);
        bench_backend(scene, su, backends[b], oracle, b == 0 ? &oracle : NULL, &rows[n++]);
    }
#ifdef RT_HAVE_EMBREE
    n += bench_embree(scene, path, su, oracle, &rows[n]);
#endif
    free(oracle);
    rt_scene_destroy(scene);
    return n;
}
