/* SPDX-License-Identifier: Apache-2.0 */
/* incoherent_bench.c - the incoherent-ray benchmark (incoherent_bench.h). */
#include "engines/incoherent_bench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "bench_util.h"
#include "engines/bench_print.h"
#include "layout/flat.h"
#include "ray_sets.h"
#include "render/renderer_internal.h"
#ifdef RT_HAVE_EMBREE
#include "peer/embree_peer.h"
#endif

enum { SETS = 2, QUERIES = 2, TRACERS = 4 };
enum { T_CPU, T_PACKET, T_EMBREE1, T_EMBREE16 };
static const char *const set_names[SETS] = {"diffuse", "random"};
static const char *const query_names[QUERIES] = {"closest", "any"};
static const char *const path_names[QUERIES][TRACERS] = {
    {"cpu", "packet-auto", "rtcIntersect1", "rtcIntersect16"},
    {"cpu", "packet-auto", "rtcOccluded1", "rtcOccluded16"}};

incoh_setup incoh_setup_default(void) {
    incoh_setup s;
    memset(&s, 0, sizeof s);
    s.rays = 1000000;
    s.reps = 5;
    s.threads = 2;
    s.width = 1024;
    s.height = 576;
    s.seed = 7;
    s.whitted = 1;
    return s;
}

const incoh_row *incoh_find(const incoh_result *res, const incoh_row *r, const char *path) {
    for (int i = 0; i < res->n_rows; i++) {
        const incoh_row *x = &res->rows[i];
        if (!strcmp(x->rays, r->rays) && !strcmp(x->query, r->query) && !strcmp(x->path, path))
            return x;
    }
    return NULL;
}

static void progress(const incoh_setup *su, const char *path, const char *what) {
    if (su->progress) su->progress(path, what);
}

/* Whitted frames on cpu and packet, interleaved frame by frame; the first
 * of each (BVH builds) is not counted. */
static void whitted(rt_scene *scene, const incoh_setup *su, incoh_result *out) {
    static const char *const backends[INCOH_WHITTED_ROWS] = {"packet", "cpu"};
    rt_camera cam;
    rt_camera_get(scene, &cam);
    cam.width = su->width;
    cam.height = su->height;
    if (rt_camera_set(scene, &cam) != RT_OK) {
        snprintf(out->whitted_error, sizeof out->whitted_error, "cannot render at %dx%d", su->width,
                 su->height);
        return;
    }
    rt_error err;
    rt_renderer *r[INCOH_WHITTED_ROWS] = {NULL, NULL};
    rt_framebuffer fb[INCOH_WHITTED_ROWS];
    rt_render_stats st[INCOH_WHITTED_ROWS];
    double *ms = malloc(sizeof(double) * (size_t)su->reps * INCOH_WHITTED_ROWS);
    memset(fb, 0, sizeof fb);
    for (int b = 0; b < INCOH_WHITTED_ROWS && ms; b++) {
        rt_renderer_options o = rt_renderer_options_default();
        o.backend = backends[b];
        o.threads = su->threads;
        if (rt_renderer_create(&o, &r[b], &err) != RT_OK) {
            snprintf(out->whitted_error, sizeof out->whitted_error, "%.199s", err.message);
            goto done;
        }
    }
    if (!ms) {
        snprintf(out->whitted_error, sizeof out->whitted_error, "out of memory");
        goto done;
    }
    for (int i = -1; i < su->reps; i++)
        for (int b = 0; b < INCOH_WHITTED_ROWS; b++) {
            rt_render_options o = rt_render_options_default();
            o.stats = &st[b];
            o.reuse_framebuffer = i >= 0;
            if (rt_render(r[b], scene, &o, &fb[b]) != RT_OK) {
                snprintf(out->whitted_error, sizeof out->whitted_error, "%s: %.180s", backends[b],
                         rt_renderer_error(r[b]));
                goto done;
            }
            if (i >= 0) ms[(size_t)b * (size_t)su->reps + (size_t)i] = st[b].render_ms;
        }
    for (int b = 0; b < INCOH_WHITTED_ROWS; b++) {
        incoh_whitted_row *w = &out->whitted[b];
        w->backend = backends[b];
        w->secondary = b == 0 ? "single-ray" : "oracle";
        bench_min_median(ms + (size_t)b * (size_t)su->reps, su->reps, &w->ms_min, &w->ms_median);
        w->rays = st[b].rays;
        w->mrays_median = w->ms_median > 0 ? (double)w->rays / (w->ms_median * 1000.0) : 0.0;
    }
    out->n_whitted = INCOH_WHITTED_ROWS;
done:
    for (int b = 0; b < INCOH_WHITTED_ROWS; b++) {
        rt_framebuffer_free(&fb[b]);
        if (r[b]) rt_renderer_destroy(r[b]);
    }
    free(ms);
}

/* The buffers of one scene's run. */
typedef struct bufs {
    rt_ray *rays[SETS];
    rt_hit *ref, *got;
    rt_hit_d *eh;
    double *ms; /* [SETS][QUERIES][TRACERS][reps] */
} bufs;

static void free_bufs(bufs *b) {
    for (int s = 0; s < SETS; s++) {
        free(b->rays[s]);
    }
    free(b->ref);
    free(b->got);
    free(b->eh);
    free(b->ms);
}

static int trace_ours(rt_renderer *r, rt_scene *scene, const rt_ray *rays, size_t n, int any,
                      rt_hit *hits, double *ms) {
    rt_trace_options o = {any, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO, NULL, NULL};
    double t0 = rt_now_ms();
    rt_status st = rt_trace_rays(r, scene, rays, n, hits, &o);
    *ms = rt_now_ms() - t0;
    return st == RT_OK;
}

int incoh_bench_scene(const char *path, const incoh_setup *su, incoh_result *out, char *err,
                      size_t err_size) {
    memset(out, 0, sizeof *out);
    rt_scene *scene = NULL;
    rt_error e;
    progress(su, path, "loading");
    if (rt_scene_open(path, &scene, &e) != RT_OK) {
        snprintf(err, err_size, "%s", e.message);
        return 0;
    }
    if (su->camera) {
        rt_camera cam;
        rt_camera_get(scene, &cam);
        su->camera(path, &cam);
        rt_camera_set(scene, &cam);
    }
    rt_renderer *ours[2] = {NULL, NULL};
    for (int k = 0; k < 2; k++) {
        rt_renderer_options o = rt_renderer_options_default();
        o.backend = k == T_CPU ? "cpu" : "packet";
        o.threads = su->threads;
        if (rt_renderer_create(&o, &ours[k], &e) != RT_OK) {
            snprintf(err, err_size, "%s", e.message);
            if (ours[0]) rt_renderer_destroy(ours[0]);
            rt_scene_destroy(scene);
            return 0;
        }
    }
    int ok = 0;
    bufs b;
    memset(&b, 0, sizeof b);
    const size_t n = su->rays;
    const size_t per = (size_t)su->reps;
    rt_backend_layout layout;
    double build_ms, sah;
    progress(su, path, "layout and ray sets");
    if (rt_renderer_layout(ours[T_CPU], scene, &layout, &build_ms, &sah) != RT_OK) {
        snprintf(err, err_size, "%s: %s", path, rt_renderer_error(ours[T_CPU]));
        goto done;
    }
    const rt_flat *flat = layout.flat;
    out->triangles = flat->tri_count;
    b.ref = malloc(sizeof(rt_hit) * n);
    b.got = malloc(sizeof(rt_hit) * n);
    b.eh = malloc(sizeof(rt_hit_d) * n);
    b.ms = malloc(sizeof(double) * SETS * QUERIES * TRACERS * per);
    int have_mem = b.ref && b.got && b.eh && b.ms;
    for (int s = 0; s < SETS; s++) {
        b.rays[s] = malloc(sizeof(rt_ray) * n);
        have_mem = have_mem && b.rays[s];
    }
    if (!have_mem) {
        snprintf(err, err_size, "%s: out of memory for %zu rays", path, n);
        goto done;
    }
    for (int s = 0; s < SETS; s++) {
        if (s == 0)
            rt_rays_diffuse(flat, su->seed, n, b.rays[s]);
        else
            rt_rays_random(flat, su->seed, n, b.rays[s]);
    }
    int tracers = 2;
#ifdef RT_HAVE_EMBREE
    rt_embree *em = NULL;
    rt_embree_scene *es = NULL;
    double commit_ms;
    if (rt_embree_create(su->threads, &em, &e) != RT_OK ||
        rt_embree_scene_create(em, flat, &es, &commit_ms, &e) != RT_OK) {
        snprintf(out->embree_absent, sizeof out->embree_absent, "%.199s", e.message);
    } else {
        tracers = TRACERS;
    }
#else
    snprintf(out->embree_absent, sizeof out->embree_absent,
             "this build has no Embree peer (install libembree-dev and reconfigure)");
#endif
    long differ[SETS][QUERIES];
    memset(differ, 0, sizeof differ);
    for (int round = 0; round <= su->reps; round++) {
        char what[64];
        snprintf(what, sizeof what, round ? "round %d of %d" : "warm-up round", round, su->reps);
        progress(su, path, what);
        for (int s = 0; s < SETS; s++)
            for (int q = 0; q < QUERIES; q++)
                for (int t = 0; t < tracers; t++) {
                    double dt = 0.0;
                    if (t == T_CPU || t == T_PACKET) {
                        /* The oracle's hits of the warm-up round are the reference. */
                        rt_hit *hits = t == T_CPU && round == 0 ? b.ref : b.got;
                        if (!trace_ours(ours[t], scene, b.rays[s], n, q, hits, &dt)) {
                            snprintf(err, err_size, "%s: %s", path, rt_renderer_error(ours[t]));
                            goto done_embree;
                        }
                        if (t == T_PACKET && round == 0)
                            for (size_t i = 0; i < n; i++)
                                differ[s][q] += !rt_api_hits_same(&b.got[i], &b.ref[i], q);
                    }
#ifdef RT_HAVE_EMBREE
                    else {
                        rt_embree_trace_rays(es, b.rays[s], n, q, t == T_EMBREE1 ? 1 : 16,
                                             layout.pool, b.eh, &dt);
                    }
#endif
                    if (round > 0)
                        b.ms[((size_t)(s * QUERIES + q) * TRACERS + t) * per + round - 1] = dt;
                }
    }
    for (int s = 0; s < SETS; s++)
        for (int q = 0; q < QUERIES; q++)
            for (int t = 0; t < tracers; t++) {
                incoh_row *r = &out->rows[out->n_rows++];
                r->rays = set_names[s];
                r->query = query_names[q];
                r->engine = t <= T_PACKET ? "rtcl" : "embree";
                r->path = path_names[q][t];
                bench_min_median(b.ms + ((size_t)(s * QUERIES + q) * TRACERS + t) * per, su->reps,
                                 &r->ms_min, &r->ms_median);
                r->mrays_min = r->ms_min > 0 ? (double)n / (r->ms_min * 1000.0) : 0.0;
                r->mrays_median = r->ms_median > 0 ? (double)n / (r->ms_median * 1000.0) : 0.0;
                r->differ = t == T_PACKET ? differ[s][q] : -1;
            }
    ok = 1;
done_embree:
#ifdef RT_HAVE_EMBREE
    if (es) rt_embree_scene_destroy(es);
    if (em) rt_embree_destroy(em);
#endif
    if (ok && su->whitted) {
        progress(su, path, "Whitted frames");
        whitted(scene, su, out);
    }
done:
    free_bufs(&b);
    rt_renderer_destroy(ours[0]);
    rt_renderer_destroy(ours[1]);
    rt_scene_destroy(scene);
    return ok;
}

/* ---- output ---------------------------------------------------------------- */

/* The packet backend's old path for Whitted secondary rays (one by one
 * through the scalar oracle, rt_shade_children) was replaced by the
 * single-ray tracer and cannot be chosen any more. */
static const char *const old_secondary_note =
    "the packet backend with secondary rays one by one through the oracle (before issue 20) "
    "is no longer selectable; docs/BENCHMARKS.md records its frame times";

/* Speed of r against Embree's row of the same rays and query (above 1: r is
 * faster), at the min and at the median; 0 when there is no such row. */
static int ratio(const incoh_result *res, const incoh_row *r, int lanes, double *min,
                 double *median) {
    const char *p = !strcmp(r->query, "closest") ? (lanes == 1 ? "rtcIntersect1" : "rtcIntersect16")
                                                 : (lanes == 1 ? "rtcOccluded1" : "rtcOccluded16");
    const incoh_row *e = incoh_find(res, r, p);
    if (!e || r->ms_min <= 0 || r->ms_median <= 0) return 0;
    *min = e->ms_min / r->ms_min;
    *median = e->ms_median / r->ms_median;
    return 1;
}

static void print_json(const char *path, const incoh_setup *su, const incoh_result *res) {
    printf("{\"scene\": ");
    json_out_string(path);
    printf(", \"triangles\": %u, \"rays_per_set\": %zu, \"seed\": %u, \"reps\": %d, "
           "\"warmup\": 1, \"threads\": %d, \"incoherent\": [",
           res->triangles, su->rays, su->seed, su->reps, su->threads);
    for (int i = 0; i < res->n_rows; i++) {
        const incoh_row *r = &res->rows[i];
        printf("%s{\"scene\": ", i ? ", " : "");
        json_out_string(path);
        printf(", \"rays\": \"%s\", \"query\": \"%s\", \"engine\": \"%s\", \"path\": \"%s\", "
               "\"ms_min\": %.4f, \"ms_median\": %.4f, \"mrays_min\": %.4f, "
               "\"mrays_median\": %.4f",
               r->rays, r->query, r->engine, r->path, r->ms_min, r->ms_median, r->mrays_min,
               r->mrays_median);
        if (r->differ >= 0) printf(", \"differ_from_oracle\": %ld", r->differ);
        double mn, md;
        if (strcmp(r->engine, "embree") && ratio(res, r, 1, &mn, &md))
            printf(", \"vs_embree1_min\": %.4f, \"vs_embree1_median\": %.4f", mn, md);
        if (strcmp(r->engine, "embree") && ratio(res, r, 16, &mn, &md))
            printf(", \"vs_embree16_min\": %.4f, \"vs_embree16_median\": %.4f", mn, md);
        putchar('}');
    }
    putchar(']');
    if (res->embree_absent[0]) {
        printf(", \"embree_absent\": ");
        json_out_string(res->embree_absent);
    }
    if (su->whitted) {
        printf(", \"whitted_width\": %d, \"whitted_height\": %d, \"whitted\": [", su->width,
               su->height);
        for (int i = 0; i < res->n_whitted; i++) {
            const incoh_whitted_row *w = &res->whitted[i];
            printf("%s{\"backend\": \"%s\", \"secondary\": \"%s\", \"ms_min\": %.4f, "
                   "\"ms_median\": %.4f, \"mrays_median\": %.4f, \"rays\": %llu}",
                   i ? ", " : "", w->backend, w->secondary, w->ms_min, w->ms_median,
                   w->mrays_median, (unsigned long long)w->rays);
        }
        putchar(']');
        if (res->whitted_error[0]) {
            printf(", \"whitted_error\": ");
            json_out_string(res->whitted_error);
        }
        printf(", \"whitted_packet_oracle_secondary\": ");
        json_out_string(old_secondary_note);
    }
    printf("}\n");
}

static void print_text(const char *path, const incoh_setup *su, const incoh_result *res) {
    printf("%s: %u triangles; incoherent rays, %zu per set (seed %u), %d threads, %d rounds "
           "after 1 warm-up round, interleaved\n",
           path, res->triangles, su->rays, su->seed, su->threads, su->reps);
    printf("  %-8s %-8s %-7s %-15s %10s %10s %9s %9s %17s %17s %8s\n", "rays", "query", "engine",
           "path", "min ms", "median ms", "Mrays/s", "(median)", "vs Embree 1", "vs Embree 16",
           "differ");
    for (int i = 0; i < res->n_rows; i++) {
        const incoh_row *r = &res->rows[i];
        printf("  %-8s %-8s %-7s %-15s %10.1f %10.1f %9.3f %9.3f", r->rays, r->query, r->engine,
               r->path, r->ms_min, r->ms_median, r->mrays_min, r->mrays_median);
        for (int lanes = 1; lanes <= 16; lanes += 15) {
            double mn, md;
            char cell[32] = "-";
            if (strcmp(r->engine, "embree") && ratio(res, r, lanes, &mn, &md))
                snprintf(cell, sizeof cell, "%.2fx / %.2fx", mn, md);
            printf(" %17s", cell);
        }
        if (r->differ >= 0)
            printf(" %8ld\n", r->differ);
        else
            printf(" %8s\n", "-");
    }
    printf("  (vs Embree: its time over the row's, at the min / at the median; above 1: faster "
           "than Embree. differ: hits unlike the cpu oracle's, bit for bit)\n");
    if (res->embree_absent[0]) printf("  no Embree rows: %s\n", res->embree_absent);
    if (!su->whitted) return;
    printf("  Whitted frames %dx%d, %d threads, min / median of %d frames after 1, interleaved:\n",
           su->width, su->height, su->threads, su->reps);
    if (res->whitted_error[0]) printf("  unavailable: %s\n", res->whitted_error);
    for (int i = 0; i < res->n_whitted; i++) {
        const incoh_whitted_row *w = &res->whitted[i];
        printf("  %-7s secondary rays: %-11s %10.1f / %10.1f ms %8.3f Mrays/s\n", w->backend,
               w->secondary, w->ms_min, w->ms_median, w->mrays_median);
    }
    if (res->n_whitted == 2 && res->whitted[0].ms_median > 0)
        printf("  packet against cpu (the oracle): %.2fx faster at the median\n",
               res->whitted[1].ms_median / res->whitted[0].ms_median);
    printf("  note: %s\n", old_secondary_note);
}

int incoh_run(const char *const *scenes, int n_scenes, const incoh_setup *su, int json,
              const char *who) {
    int failed = 0;
    incoh_result *res = malloc(sizeof *res);
    if (!res) {
        fprintf(stderr, "%s: out of memory\n", who);
        return 2;
    }
    for (int i = 0; i < n_scenes; i++) {
        char err[400];
        int ok = incoh_bench_scene(scenes[i], su, res, err, sizeof err);
        if (su->progress) fprintf(stderr, "\r\033[K");
        if (!ok) {
            fprintf(stderr, "%s: %s\n", who, err);
            failed = 1;
            continue;
        }
        if (json)
            print_json(scenes[i], su, res);
        else
            print_text(scenes[i], su, res);
        fflush(stdout);
    }
    free(res);
    return failed ? 2 : 0;
}
