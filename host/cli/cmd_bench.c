/* cmd_bench.c - 'rtcl bench': BVH build times and tree quality per scene (and
 * the render part, cmd_bench_render.c),
 * every builder side by side (and Embree's, when this build has it).
 *
 * Per scene, one BVH is built over the boxes of all triangles of all meshes
 * (as the thesis timed one tree per scene). Each builder runs once as a
 * warm-up (not counted), then --reps times; min and median are reported.
 * The timed part is rt_bvh_build (for Embree: rtcBuildBVH alone); computing
 * the triangle boxes is shared input and not timed.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_animate.h"
#include "json_out.h"
#include "bench_render.h"
#include "cli_util.h"
#include "incoherent_bench.h"
#include "accel/bvh.h"
#include "accel/kd.h"
#include "base/clock.h"
#include "commands.h"
#include "rt.h"
#include "scene/scene.h"
#include "base/thread_pool.h"
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

typedef struct bench_args {
    int json, reps, threads, progress, render, width, height;
    rt_device_math device_math;
    rt_denormals denormals;
    int accel;   /* --accel: rt_accel, or -1 */
    int verbose; /* --verbose: the OpenCL build log on stderr */
    /* --animate (bench_animate.h): the keyframe benchmark instead */
    int animate, anim_frames, anim_series;
    double anim_fps;
    int incoherent, rays; /* --incoherent, --rays (incoherent_bench.h) */
} bench_args;

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void summarize(row *r, double *times, int n) {
    qsort(times, (size_t)n, sizeof *times, cmp_double);
    r->ms_min = times[0];
    r->ms_median = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
}

static void usage(FILE *f) {
    fprintf(f, "usage: rtcl bench SCENE... [--json] [--reps N] [--threads N] [--no-render]\n"
               "                 [--width W] [--height H] [--device-math M] [--denormals P]\n"
               "                 [--accel A]\n"
               "                 [--verbose]\n"
               "       rtcl bench --animate SCENE... [--json] [--reps N] [--threads N]\n"
               "                 [--width W] [--height H] [--frames K] [--fps F] [--series]\n"
               "       rtcl bench --incoherent SCENE... [--json] [--reps N] [--threads N]\n"
               "                 [--rays N] [--width W] [--height H] [--no-render]\n"
               "\n"
               "Build: one BVH over all triangles of each scene with every builder\n"
               "(thesis-scalar, thesis-neon, thesis-mt, fast, and embree when available):\n"
               "min and median build time over N repetitions (after one warm-up run that\n"
               "is not counted), SAH cost and node count. Embree's rtcCommitScene at low\n"
               "and medium quality is shown for reference.\n"
               "Render: the thesis's set-up (one point light, primary plus shadow rays,\n"
               "Phong) on the backends cpu, packet, opencl, opencl-portable (the\n"
               "portable maths profile: software divide and sqrt) and vulkan (always the\n"
               "portable profile), and Embree tracing the same\n"
               "rays (rtcIntersect1, packets of 4, 8 and 16 where native, rtcOccluded for\n"
               "shadow rays) with the same thread count: min and median frame time over N\n"
               "frames after one warm-up frame (frames interleaved round by round over\n"
               "every backend and width, so that a busy machine slows them alike; each\n"
               "timed frame follows an untimed one of its own, for its own warm caches),\n"
               "Mrays/s, box and triangle tests per ray, pixels that differ from the cpu\n"
               "oracle's image, and each rate against Embree's fastest packet width.\n"
               "  --json       one JSON object per scene per line (\"build\", \"reference\",\n"
               "               \"render\" arrays)\n"
               "  --reps N     timed repetitions and frames (default 5)\n"
               "  --threads N  threads for the threaded builders, the renderers and Embree\n"
               "               (default: all cores; PoCL uses its own pool of all cores)\n"
               "  --no-render  build only\n"
               "  --device-math M\n"
               "               the opencl row's maths profile: auto, native or portable\n"
               "               [auto]; with portable there is no separate opencl-portable row\n"
               "  --denormals P\n"
               "               preserve or flush, for every row [preserve]\n"
               "  --width W, --height H\n"
               "               render resolution [1024x576, the thesis's]\n"
               "  --accel A    bvh, kd or kd-binned: the structure of every static mesh in\n"
               "               the render part; kd and kd-binned also add the build rows\n"
               "               kd-exact and kd-binned (one SAH kd-tree over all triangles,\n"
               "               SAH with Ct = 1, Ci = 2 as for the BVH rows, and bytes)\n"
               "  --verbose    print the OpenCL compiler's messages (build log) on stderr\n"
               "  --animate    the keyframe benchmark instead (Langr 2016, section 4.1):\n"
               "               each SCENE's first morphing object played frame by frame,\n"
               "               frame k at time k/F, on the packet backend with the update\n"
               "               policies sah, refit, lbvh and auto, beside Embree (when\n"
               "               built with it) updating and tracing the same frames at build\n"
               "               quality REFIT, LOW and MEDIUM (its widest packets); N runs,\n"
               "               rows interleaved frame by frame; per row the mesh update, trace and "
               "whole-frame\n"
               "               ms (the update included), each a mean over the frames (min\n"
               "               and median over the runs), the SAH cost (Embree's: of\n"
               "               rtcBuildBVH's trees of that quality) and whether every\n"
               "               frame's image is the sah policy's, bit for bit; with --json a\n"
               "               \"dynamic\" array per scene. Frame 0 (the first build) is\n"
               "               not counted.\n"
               "  --frames K   with --animate: frames after frame 0 [one per keyframe]\n"
               "  --fps F      with --animate: frames per second [the keyframe rate]\n"
               "  --series     with --animate --json: each row's per-frame medians too\n"
               "  --incoherent the incoherent-ray benchmark instead: per SCENE two sets of\n"
               "               rays (diffuse bounces from the camera rays' closest hits,\n"
               "               random rays inside the scene; fixed seed 7), each traced for\n"
               "               the closest hit and for any hit by rt_trace_rays on cpu (the\n"
               "               oracle) and packet (auto path), and by Embree's\n"
               "               rtcIntersect1/rtcOccluded1 and rtcIntersect16/rtcOccluded16 (16\n"
               "               consecutive rays per call) where this build has Embree (else\n"
               "               the output says why its rows are absent), same thread count;\n"
               "               min and median ms and Mrays/s over N rounds after a warm-up\n"
               "               round (interleaved), speed against Embree, packet hits unlike\n"
               "               the oracle's; then Whitted frames (W x H) on packet and cpu\n"
               "               (--no-render: none). With --json an \"incoherent\" array of\n"
               "               {scene, rays, query, engine, path, ms_min, ms_median,\n"
               "               mrays_min, mrays_median, ...} and a \"whitted\" array per scene.\n"
               "  --rays N     rays per set [1000000]\n");
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
    if (a->progress) fprintf(stderr, "\r\033[K%s: %s", scene, what);
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

static void render_progress(const char *scene, const char *what) {
    fprintf(stderr, "\r\033[K%s: %s", scene, what);
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
    if (rt_scene_load(path, &scene, &err) != RT_OK) {
        if (a->progress) fputc('\n', stderr);
        fprintf(stderr, "rtcl bench: %s\n", err.message);
        return 0;
    }
    tri_input in;
    if (!gather_triangles(scene, &in)) {
        fprintf(stderr, "rtcl bench: %s: out of memory or too many triangles\n", path);
        free_input(&in);
        rt_scene_destroy(scene);
        return 0;
    }
    rt_scene_destroy(scene);
    row rows[MAX_ROWS];
    memset(rows, 0, sizeof rows);
    const rt_builder ours[] = {RT_BUILDER_THESIS_SCALAR, RT_BUILDER_THESIS_NEON,
                               RT_BUILDER_THESIS_MT, RT_BUILDER_SAH};
    int n = 0;
    for (int i = 0; i < 4; i++) {
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
            a->device_math, a->denormals, a->accel, a->progress ? render_progress : NULL,
            a->verbose};
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
        fprintf(stderr, "rtcl bench: %s\n", why);
        return 0;
    }
    return 1;
}

static void animate_progress(const char *scene, const char *what) {
    fprintf(stderr, "\r\033[K%s: %s", scene, what);
}

/* rtcl bench --animate: one scene's keyframe benchmark (bench_animate.h). */
static int animate_scene(const char *path, const bench_args *a) {
    bench_anim_setup su = {a->reps,
                           a->anim_frames,
                           a->anim_fps,
                           a->threads,
                           a->width,
                           a->height,
                           "packet",
                           1,
                           a->progress ? animate_progress : NULL};
    bench_anim_result res;
    char why[400] = "";
    int ok = bench_animate(path, &su, &res, why, sizeof why);
    if (a->progress) fprintf(stderr, "\r\033[K");
    if (!ok) {
        fprintf(stderr, "rtcl bench: %s\n", why);
        return 0;
    }
    if (a->json) {
        printf("{\"scene\": ");
        json_out_string(path);
        printf(", \"threads\": %d, \"width\": %d, \"height\": %d", a->threads, a->width, a->height);
        bench_anim_print_json(path, &res, a->anim_series);
        printf("}\n");
    } else {
        bench_anim_print_text(path, &res);
    }
    fflush(stdout);
    bench_anim_free(&res);
    return 1;
}

static int parse_int(const char *s, int lo, int hi, int *out) {
    char *end;
    long v = strtol(s, &end, 10);
    if (!*s || *end || v < lo || v > hi) return 0;
    *out = (int)v;
    return 1;
}

int cmd_bench(int argc, char **argv) {
    bench_args a = {
        0, 5, 0, isatty(2), 1,   1024, 576, RT_DEVICE_MATH_AUTO, RT_DENORMALS_PRESERVE, -1,
        0, 0, 0, 0,         0.0, 0,    0};
    const char **scenes = calloc((size_t)argc, sizeof *scenes);
    int n_scenes = 0;
    if (!scenes) return 2;
    for (int i = 1, m; i < argc; i++) {
        const char *s = argv[i];
        if (!strcmp(s, "--help") || !strcmp(s, "-h")) {
            usage(stdout);
            free(scenes);
            return 0;
        } else if (!strcmp(s, "--json")) {
            a.json = 1;
        } else if (!strcmp(s, "--no-render")) {
            a.render = 0;
        } else if (!strcmp(s, "--accel")) {
            rt_accel acc;
            if (i + 1 >= argc || !rt_accel_parse(argv[i + 1], &acc)) {
                fprintf(stderr, "rtcl bench: --accel takes bvh, kd or kd-binned\n");
                free(scenes);
                return 2;
            }
            a.accel = (int)acc;
            i++;
        } else if (!strcmp(s, "--incoherent")) {
            a.incoherent = 1;
        } else if (!strcmp(s, "--rays")) {
            if (i + 1 >= argc || !parse_int(argv[i + 1], 1, 100000000, &a.rays)) {
                fprintf(stderr, "rtcl bench: --rays needs a number from 1 to 100000000\n");
                free(scenes);
                return 2;
            }
            i++;
        } else if (!strcmp(s, "--verbose")) {
            a.verbose = 1;
        } else if (!strcmp(s, "--animate")) {
            a.animate = 1;
        } else if (!strcmp(s, "--series")) {
            a.anim_series = 1;
        } else if (!strcmp(s, "--frames") || !strcmp(s, "--fps")) {
            int v;
            if (i + 1 >= argc || !parse_int(argv[i + 1], 1, 100000, &v)) {
                fprintf(stderr, "rtcl bench: %s needs a number from 1 to 100000\n", s);
                free(scenes);
                return 2;
            }
            if (s[3] == 'r')
                a.anim_frames = v;
            else
                a.anim_fps = v;
            i++;
        } else if ((m = cli_maths_arg(argc, argv, &i, "bench", &a.device_math, &a.denormals))) {
            if (m < 0) {
                free(scenes);
                return 2;
            }
        } else if (!strcmp(s, "--reps") || !strcmp(s, "--threads") || !strcmp(s, "--width") ||
                   !strcmp(s, "--height")) {
            int *dst = s[2] == 'r'   ? &a.reps
                       : s[2] == 't' ? &a.threads
                       : s[2] == 'w' ? &a.width
                                     : &a.height;
            int hi = s[2] == 'w' || s[2] == 'h' ? 32768 : 1000;
            if (i + 1 >= argc || !parse_int(argv[i + 1], 1, hi, dst)) {
                fprintf(stderr, "rtcl bench: %s needs a number from 1 to %d\n", s, hi);
                free(scenes);
                return 2;
            }
            i++;
        } else if (s[0] == '-' && s[1]) {
            fprintf(stderr, "rtcl bench: unknown option %s\n", s);
            usage(stderr);
            free(scenes);
            return 2;
        } else {
            scenes[n_scenes++] = s;
        }
    }
    if (!n_scenes) {
        usage(stderr);
        free(scenes);
        return 2;
    }
    /* Options of one mode given to the other would be ignored: say so. */
    const char *odd = NULL;
    if (a.animate && a.incoherent)
        odd = "--animate and --incoherent are two benchmarks: run one at a time";
    else if (a.animate && a.accel >= 0)
        odd = "--accel does not apply to --animate (morphing meshes keep BVHs)";
    else if (a.animate && !a.render)
        odd = "--no-render does not apply to --animate (it renders every frame)";
    else if (a.animate &&
             (a.device_math != RT_DEVICE_MATH_AUTO || a.denormals != RT_DENORMALS_PRESERVE))
        odd =
            "--device-math and --denormals do not apply to --animate (it runs the packet backend)";
    else if (!a.animate && (a.anim_frames || a.anim_fps || a.anim_series))
        odd = "--frames, --fps and --series need --animate";
    else if (a.incoherent && a.accel >= 0)
        odd = "--accel does not apply to --incoherent (it traces the scene's own structures)";
    else if (a.incoherent &&
             (a.device_math != RT_DEVICE_MATH_AUTO || a.denormals != RT_DENORMALS_PRESERVE))
        odd = "--device-math and --denormals do not apply to --incoherent (it runs the CPU "
              "backends)";
    else if (a.rays && !a.incoherent)
        odd = "--rays applies to --incoherent only";
    if (odd) {
        fprintf(stderr, "rtcl bench: %s\n", odd);
        free(scenes);
        return 2;
    }
    if (a.threads <= 0) a.threads = rt_cpu_count();
    if (a.incoherent) {
        incoh_setup su = incoh_setup_default();
        if (a.rays) su.rays = (size_t)a.rays;
        su.reps = a.reps;
        su.threads = a.threads;
        su.width = a.width;
        su.height = a.height;
        su.whitted = a.render;
        su.progress = a.progress ? render_progress : NULL;
        int rc = incoh_run(scenes, n_scenes, &su, a.json, "rtcl bench");
        free(scenes);
        return rc;
    }
    rt_pool *pool = rt_pool_create(a.threads);
    if (!pool) {
        fprintf(stderr, "rtcl bench: cannot create %d threads\n", a.threads);
        free(scenes);
        return 2;
    }
    int failed = 0;
    for (int i = 0; i < n_scenes; i++)
        failed |= a.animate ? !animate_scene(scenes[i], &a) : !bench_scene(scenes[i], &a, pool);
    rt_pool_destroy(pool);
    free(scenes);
    return failed ? 2 : 0;
}
