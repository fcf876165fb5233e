/* SPDX-License-Identifier: Apache-2.0 */
/* bench_build.c - the build and render benchmark of 'rtcl bench'
 * (bench_build.h): BVH build times and tree quality per scene, every
 * builder side by side (and Embree's, when this build has it), then the
 * render part (bench_render.h).
 *
 * Per scene, one BVH is built over the boxes of all triangles of all meshes
 * (as the thesis timed one tree per scene). Each builder runs once as a
 * warm-up (not counted), then reps times; min and median are reported.
 * The timed part is rt_bvh_build (for Embree: rtcBuildBVH alone); computing
 * the triangle boxes is shared input and not timed. */
#include "engines/bench_build.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "accel/kd.h"
#include "base/clock.h"
#include "base/thread_pool.h"
#include "bench_util.h"
#include "engines/bench_print.h"
#include "engines/bench_render.h"
#include "rt.h"
#include "scene/scene.h"
#ifdef RT_HAVE_EMBREE
#include "peer/embree_peer.h"
#endif

enum { MAX_ROWS = 10 };

typedef struct row {
    const char *builder;
    int threads;
    double ms_min, ms_median;
    double sah;
    long nodes;      /* -1 for reference rows (no tree) */
    double bytes;    /* the tree's memory (nodes and leaf entries); 0: not known */
    char error[200]; /* non-empty: this builder failed or is unavailable */
} row;

typedef bench_build_setup bench_args;

static void summarize(row *r, double *times, int n) {
    bench_min_median(times, n, &r->ms_min, &r->ms_median);
}

/* The triangles of every mesh: boxes, and positions/indices for Embree. */
typedef struct tri_input {
    rt_aabb *boxes;
    uint32_t count;
    float *positions;
    uint32_t *indices;
    uint32_t vertex_count;
} tri_input;

static int gather_triangles(const rt_scene *scene, tri_input *in) {
    uint64_t tris = 0, verts = 0;
    for (uint32_t m = 0; m < scene->mesh_count; m++) {
        tris += scene->meshes[m].triangle_count;
        verts += scene->meshes[m].vertex_count;
    }
    if (tris > RT_NODE_COUNT_MASK / 2 || verts > UINT32_MAX) return 0;
    memset(in, 0, sizeof *in);
    in->boxes = malloc(sizeof *in->boxes * (tris ? tris : 1));
    in->positions = malloc(sizeof(float) * 3 * (verts ? verts : 1));
    in->indices = malloc(sizeof(uint32_t) * 3 * (tris ? tris : 1));
    if (!in->boxes || !in->positions || !in->indices) return 0;
    uint32_t t = 0, base = 0;
    for (uint32_t m = 0; m < scene->mesh_count; m++) {
        const rt_mesh_data *mesh = &scene->meshes[m];
        memcpy(in->positions + 3 * (size_t)base, mesh->positions,
               sizeof(float) * 3 * mesh->vertex_count);
        for (uint32_t i = 0; i < mesh->triangle_count; i++, t++) {
            rt_aabb *b = &in->boxes[t];
            for (int k = 0; k < 3; k++) {
                b->bmin[k] = mesh->positions[3 * mesh->indices[3 * i] + k];
                b->bmax[k] = b->bmin[k];
            }
            for (int j = 0; j < 3; j++) {
                uint32_t v = mesh->indices[3 * i + j];
                in->indices[3 * (size_t)t + j] = base + v;
                for (int k = 0; k < 3; k++) {
                    float x = mesh->positions[3 * v + k];
                    b->bmin[k] = x < b->bmin[k] ? x : b->bmin[k];
                    b->bmax[k] = x > b->bmax[k] ? x : b->bmax[k];
                }
            }
        }
        base += mesh->vertex_count;
    }
    in->count = t;
    in->vertex_count = base;
    return 1;
}

static void free_input(tri_input *in) {
    free(in->boxes);
    free(in->positions);
    free(in->indices);
}

static void progress(const bench_args *a, const char *scene, const char *what) {
    if (a->progress) bench_progress_line(scene, what);
}

static void bench_ours(const bench_args *a, const tri_input *in, rt_builder builder, rt_pool *pool,
                       row *r) {
    rt_build_options o = rt_build_options_default();
    o.builder = builder;
    int single = builder == RT_BUILDER_THESIS_SCALAR || builder == RT_BUILDER_THESIS_NEON;
    o.threads = single ? 1 : a->threads;
    r->builder = rt_builder_name(builder);
    r->threads = o.threads;
    r->nodes = 0;
    double *times = malloc(sizeof(double) * (size_t)a->reps);
    if (!times) {
        snprintf(r->error, sizeof r->error, "out of memory");
        return;
    }
    for (int i = -1; i < a->reps; i++) {
        rt_bvh bvh;
        rt_error msg;
        memset(&msg, 0, sizeof msg);
        double t0 = rt_now_ms();
        rt_status st = rt_bvh_build(in->boxes, in->count, &o, single ? NULL : pool, &bvh, &msg);
        double t = rt_now_ms() - t0;
        if (st != RT_OK) {
            snprintf(r->error, sizeof r->error, "%.199s",
                     msg.message[0] ? msg.message : rt_status_string(st));
            free(times);
            return;
        }
        if (i >= 0) times[i] = t;
        if (i == a->reps - 1) {
            rt_bvh_quality q = rt_bvh_measure(&bvh, o.costs);
            r->sah = q.sah;
            r->nodes = q.nodes;
            r->bytes = (double)q.bytes;
        }
        rt_bvh_free(&bvh);
    }
    summarize(r, times, a->reps);
    free(times);
}

/* A kd-tree over all triangles, timed like bench_ours. */
static void bench_kd(const bench_args *a, const tri_input *in, rt_kd_builder builder, rt_pool *pool,
                     row *r) {
    rt_kd_options o = rt_kd_options_default();
    o.builder = builder;
    r->builder = rt_kd_builder_name(builder);
    r->threads = a->threads;
    double *times = malloc(sizeof(double) * (size_t)a->reps);
    if (!times) {
        snprintf(r->error, sizeof r->error, "out of memory");
        return;
    }
    for (int i = -1; i < a->reps; i++) {
        rt_kd kd;
        rt_error msg;
        memset(&msg, 0, sizeof msg);
        double t0 = rt_now_ms();
        rt_status st = rt_kd_build(in->positions, in->vertex_count, in->indices, in->count, &o,
                                   pool, &kd, &msg);
        double t = rt_now_ms() - t0;
        if (st != RT_OK) {
            snprintf(r->error, sizeof r->error, "%.199s",
                     msg.message[0] ? msg.message : rt_status_string(st));
            free(times);
            return;
        }
        if (i >= 0) times[i] = t;
        if (i == a->reps - 1) {
            rt_kd_quality q = rt_kd_measure(&kd, rt_sah_costs_default());
            r->sah = q.sah;
            r->nodes = q.nodes;
            r->bytes = (double)q.bytes;
        }
        rt_kd_free(&kd);
    }
    summarize(r, times, a->reps);
    free(times);
}

#ifdef RT_HAVE_EMBREE
static int bench_embree(const bench_args *a, const tri_input *in, row *rows) {
    rt_embree *em = NULL;
    rt_error msg;
    memset(&msg, 0, sizeof msg);
    row *b = &rows[0], *low = &rows[1], *med = &rows[2];
    b->builder = "embree";
    low->builder = "embree-commit-low";
    med->builder = "embree-commit-medium";
    for (int i = 0; i < 3; i++) rows[i].threads = a->threads;
    low->nodes = med->nodes = -1;
    if (rt_embree_create(a->threads, &em, &msg) != RT_OK) {
        for (int i = 0; i < 3; i++)
            snprintf(rows[i].error, sizeof rows[i].error, "%.199s", msg.message);
        return 3;
    }
    rt_build_options o = rt_build_options_default();
    double *times = malloc(sizeof(double) * (size_t)a->reps * 3);
    if (!times) {
        rt_embree_destroy(em);
        return 0;
    }
    for (int i = -1; i < a->reps && !b->error[0]; i++) {
        rt_bvh bvh;
        double ms;
        if (rt_embree_build_bvh(em, in->boxes, in->count, &o, &bvh, &ms, &msg) != RT_OK) {
            snprintf(b->error, sizeof b->error, "%.199s", msg.message);
            break;
        }
        if (i >= 0) times[i] = ms;
        if (i == a->reps - 1) {
            rt_bvh_quality q = rt_bvh_measure(&bvh, o.costs);
            b->sah = q.sah;
            b->nodes = q.nodes;
            summarize(b, times, a->reps);
        }
        rt_bvh_free(&bvh);
    }
    for (int quality = 0; quality < 2; quality++) {
        row *r = quality ? med : low;
        double *t = times + (size_t)a->reps * (size_t)(1 + quality);
        for (int i = -1; i < a->reps; i++) {
            double ms;
            if (rt_embree_commit_ms(em, in->positions, in->vertex_count, in->indices, in->count,
                                    quality, &ms, &msg) != RT_OK) {
                snprintf(r->error, sizeof r->error, "%.199s", msg.message);
                break;
            }
            if (i >= 0) t[i] = ms;
        }
        if (!r->error[0]) summarize(r, t, a->reps);
    }
    free(times);
    rt_embree_destroy(em);
    return 3;
}
#endif

static void print_json_row(const row *r) {
    printf("{\"builder\": ");
    json_out_string(r->builder);
    printf(", \"threads\": %d", r->threads);
    if (r->error[0]) {
        printf(", \"ms_min\": null, \"ms_median\": null, \"error\": ");
        json_out_string(r->error);
    } else {
        printf(", \"ms_min\": %.4f, \"ms_median\": %.4f", r->ms_min, r->ms_median);
    }
    if (r->nodes >= 0) {
        if (r->error[0])
            printf(", \"sah\": null, \"nodes\": null");
        else
            printf(", \"sah\": %.4f, \"nodes\": %ld", r->sah, r->nodes);
        if (!r->error[0] && r->bytes > 0) printf(", \"bytes\": %.0f", r->bytes);
    }
    putchar('}');
}

static void print_json(const char *path, const tri_input *in, const bench_args *a, const row *rows,
                       int n_build, int n_rows) {
    printf("{\"scene\": ");
    json_out_string(path);
    printf(", \"triangles\": %u, \"reps\": %d, \"warmup\": 1, \"build\": [", in->count, a->reps);
    for (int i = 0; i < n_build; i++) {
        if (i) printf(", ");
        print_json_row(&rows[i]);
    }
    printf("], \"reference\": [");
    for (int i = n_build; i < n_rows; i++) {
        if (i > n_build) printf(", ");
        print_json_row(&rows[i]);
    }
    printf("]");
}

static void print_json_number(const char *key, double v) {
    if (isfinite(v))
        printf(", \"%s\": %.4f", key, v);
    else
        printf(", \"%s\": null", key);
}

static void print_json_render(const bench_args *a, const render_row *rows, int n) {
    printf(", \"render_width\": %d, \"render_height\": %d, \"render\": [", a->width, a->height);
    for (int i = 0; i < n; i++) {
        const render_row *r = &rows[i];
        printf("%s{\"backend\": ", i ? ", " : "");
        json_out_string(r->backend);
        printf(", \"threads\": %d", r->threads);
        if (r->lanes) printf(", \"lanes\": %d", r->lanes);
        if (r->error[0]) {
            printf(", \"ms_min\": null, \"ms_median\": null, \"error\": ");
            json_out_string(r->error);
            putchar('}');
            continue;
        }
        printf(", \"ms_min\": %.4f, \"ms_median\": %.4f, \"mrays\": %.4f, \"rays\": %llu",
               r->ms_min, r->ms_median, r->mrays, (unsigned long long)r->rays);
        print_json_number("box_tests", r->box_tests >= 0 ? r->box_tests : NAN);
        print_json_number("tri_tests", r->tri_tests >= 0 ? r->tri_tests : NAN);
        if (i > 0)
            printf(", \"pixels_differ_from_cpu\": %ld, \"pixels_visibly_differ_from_cpu\": %ld, "
                   "\"max_diff_from_cpu\": %.6g",
                   r->pixels_differ, r->pixels_visible, r->max_diff);
        putchar('}');
    }
    putchar(']');
}

/* Frame times side by side; "rate/embree" is Embree's fastest median frame
 * time over this row's (above 1: faster than Embree). */
static void print_text_render(const bench_args *a, const render_row *rows, int n) {
    const render_row *peer = NULL;
    for (int i = 0; i < n; i++)
        if (!strcmp(rows[i].backend, "embree") && !rows[i].error[0]) peer = &rows[i];
    printf("  render %dx%d, one light, primary + shadow rays, Phong; %d timed frames after 1 "
           "warm-up frame, interleaved over the rows\n",
           a->width, a->height, a->reps);
    printf("  %-15s %7s %10s %10s %8s %9s %9s %19s", "backend", "threads", "min ms", "median ms",
           "Mrays/s", "box/ray", "tri/ray", "px != cpu (visibly)");
    if (peer) printf(" %12s", "rate/embree");
    putchar('\n');
    for (int i = 0; i < n; i++) {
        const render_row *r = &rows[i];
        printf("  %-15s %7d ", r->backend, r->threads);
        if (r->error[0]) {
            printf("unavailable: %s\n", r->error);
            continue;
        }
        printf("%10.2f %10.2f %8.2f ", r->ms_min, r->ms_median, r->mrays);
        if (r->box_tests >= 0)
            printf("%9.2f %9.2f ", r->box_tests, r->tri_tests);
        else
            printf("%9s %9s ", "-", "-");
        if (i > 0)
            printf("%8ld (%8ld)", r->pixels_differ, r->pixels_visible);
        else
            printf("%19s", "(oracle)");
        if (peer) printf(" %12.3f", peer->ms_median / r->ms_median);
        putchar('\n');
    }
}

static void print_text(const char *path, const tri_input *in, const bench_args *a, const row *rows,
                       int n_rows) {
    const row *peer = NULL;
    for (int i = 0; i < n_rows; i++)
        if (!strcmp(rows[i].builder, "embree") && !rows[i].error[0]) peer = &rows[i];
    printf("%s: %u triangles; %d timed runs after 1 warm-up run\n", path, in->count, a->reps);
    printf("  %-22s %7s %10s %10s %9s %9s", "builder", "threads", "min ms", "median ms", "SAH",
           "nodes");
    if (peer) printf("  %12s %9s", "time/embree", "SAH/embree");
    putchar('\n');
    for (int i = 0; i < n_rows; i++) {
        const row *r = &rows[i];
        printf("  %-22s %7d ", r->builder, r->threads);
        if (r->error[0]) {
            printf("unavailable: %s\n", r->error);
            continue;
        }
        printf("%10.2f %10.2f ", r->ms_min, r->ms_median);
        if (r->nodes >= 0)
            printf("%9.2f %9ld", r->sah, r->nodes);
        else
            printf("%9s %9s", "-", "-");
        if (peer) {
            printf("  %12.2f", r->ms_median / peer->ms_median);
            if (r->nodes >= 0) printf(" %9.3f", r->sah / peer->sah);
        }
        putchar('\n');
    }
}

static int bench_scene(const char *path, const bench_args *a, rt_pool *pool) {
    rt_scene *scene = NULL;
    rt_error err;
    progress(a, path, "loading");
    if (rt_scene_open(path, &scene, &err) != RT_OK) {
        if (a->progress) fputc('\n', stderr);
        fprintf(stderr, "%s: %s\n", a->who, err.message);
        return 0;
    }
    tri_input in;
    if (!gather_triangles(scene, &in)) {
        fprintf(stderr, "%s: %s: out of memory or too many triangles\n", a->who, path);
        free_input(&in);
        rt_scene_destroy(scene);
        return 0;
    }
    rt_scene_destroy(scene);
    row rows[MAX_ROWS];
    memset(rows, 0, sizeof rows);
    /* lbvh: the builder of the per-frame "lbvh" update policy (issue 32 item 3). */
    const rt_builder ours[] = {RT_BUILDER_THESIS_SCALAR, RT_BUILDER_THESIS_NEON,
                               RT_BUILDER_THESIS_MT, RT_BUILDER_SAH, RT_BUILDER_LBVH};
    int n = 0;
    for (int i = 0; i < (int)(sizeof ours / sizeof ours[0]); i++) {
        progress(a, path, rt_builder_name(ours[i]));
        bench_ours(a, &in, ours[i], pool, &rows[n++]);
    }
    if (a->accel >= 0 && a->accel != RT_ACCEL_BVH) { /* --accel kd, kd-binned: both kd rows */
        progress(a, path, "kd-exact");
        bench_kd(a, &in, RT_KD_EXACT, pool, &rows[n++]);
        progress(a, path, "kd-binned");
        bench_kd(a, &in, RT_KD_BINNED, pool, &rows[n++]);
    }
    int n_build = n, n_rows = n;
#ifdef RT_HAVE_EMBREE
    progress(a, path, "embree");
    if (bench_embree(a, &in, &rows[n])) {
        n_build = n + 1;
        n_rows = n + 3;
    }
#endif
    free_input(&in);
    render_row rrows[BENCH_RENDER_MAX_ROWS];
    int n_render = 0;
    char why[300] = "";
    if (a->render) {
        bench_render_setup su = {
            a->reps,        a->threads,   a->width, a->height,
            a->device_math, a->denormals, a->accel, a->progress ? bench_progress_line : NULL,
            a->build_log};
        n_render = bench_render(path, &su, rrows, why, sizeof why);
    }
    if (a->progress) fprintf(stderr, "\r\033[K");
    if (a->json) {
        print_json(path, &in, a, rows, n_build, n_rows);
        if (n_render) print_json_render(a, rrows, n_render);
        printf("}\n");
    } else {
        print_text(path, &in, a, rows, n_rows);
        if (n_render) print_text_render(a, rrows, n_render);
    }
    fflush(stdout);
    if (a->render && !n_render) {
        fprintf(stderr, "%s: %s\n", a->who, why);
        return 0;
    }
    return 1;
}

int bench_build_run(const char *const *scenes, int n_scenes, const bench_build_setup *setup) {
    rt_pool *pool = rt_pool_create(setup->threads);
    if (!pool) {
        fprintf(stderr, "%s: cannot create %d threads\n", setup->who, setup->threads);
        return 2;
    }
    int failed = 0;
    for (int i = 0; i < n_scenes; i++) failed |= !bench_scene(scenes[i], setup, pool);
    rt_pool_destroy(pool);
    return failed ? 2 : 0;
}
