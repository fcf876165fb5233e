/* SPDX-License-Identifier: Apache-2.0 */
/* cmd_trace.c - 'rtcl trace': rays from a text file through a scene, one hit
 * line per ray (rt_trace_rays). */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "commands.h"
#include "engines/bench_print.h"

typedef struct trace_args {
    const char *rays, *out;
    int tri_test, any_hit, offset, reps, stats, json, packet_path;
    cli_scene_args scene;
    cli_renderer_args renderer;
} trace_args;

static const cli_choice tri_test_choices[] = {{"watertight", RT_TRI_TEST_WATERTIGHT},
                                              {"mt", RT_TRI_TEST_MOLLER},
                                              {"pluecker", RT_TRI_TEST_PLUECKER},
                                              {"badouel", RT_TRI_TEST_BADOUEL},
                                              {NULL, 0}};
static const cli_choice path_choices[] = {{"auto", RT_TRACE_PATH_AUTO},
                                          {"packets", RT_TRACE_PATH_PACKETS},
                                          {"single", RT_TRACE_PATH_SINGLE},
                                          {NULL, 0}};

static const cli_option trace_options[] = {
    {"--rays", 0, CLI_STRING, "RAYS.txt", offsetof(trace_args, rays),
     .flags = CLI_NONEMPTY | CLI_REQUIRED,
     .help = "the rays, one a line: ox oy oz dx dy dz tmin tmax (the ray o + t d for t in "
             "[tmin, tmax], inclusive; d need not be normalised, t is in its units). Blank lines "
             "and lines starting with '#' are skipped. A ray with a NaN or infinite component or "
             "a zero direction is a miss",
     .fallback = "required"},
    {"--out", 'o', CLI_STRING, "HITS.txt", offsetof(trace_args, out),
     .flags = CLI_NONEMPTY | CLI_REQUIRED,
     .help = "the hits, one line per ray: 'hit t u v prim', plus ' inst' when the scene has "
             "more than one object. hit is 1 or 0; p = (1-u-v) v0 + u v1 + v v2; prim is the "
             "0-based triangle index in its mesh's file order; inst the object index. Floats as "
             "%.9g. A miss is '0 inf 0 0 -1' (plus ' -1')",
     .fallback = "required unless --stats or --json"},
    {"--tri-test", 0, CLI_CHOICE, "T", offsetof(trace_args, tri_test), .choices = tri_test_choices,
     .help = "the ray/triangle test: {choices} (watertight: Woop, Benthin, Wald 2013; mt: "
             "Moller-Trumbore; pluecker; badouel)",
     .fallback = "watertight"},
    {"--any-hit", 0, CLI_FLAG, NULL, offsetof(trace_args, any_hit),
     .help = "stop at any hit in range (shadow-ray queries): hit is then exact, t u v prim inst "
             "belong to some hit, not the closest"},
    {"--offset-origins", 0, CLI_FLAG, NULL, offsetof(trace_args, offset),
     .help = "each ray line has 3 more numbers, nx ny nz: the origin is a point on a surface "
             "with that normal, and is moved off it with the engine's offset (as for shadow and "
             "secondary rays), to the side the direction points to"},
    {"--reps", 0, CLI_INT, "N", offsetof(trace_args, reps), 1, 100000,
     .help = "trace the rays N times after one untimed warm-up (the hits written are the last "
             "run's, the same every time)",
     .fallback = "1, no warm-up"},
    {"--stats", 0, CLI_FLAG, NULL, offsetof(trace_args, stats),
     .help = "print the trace time alone (not reading rays, not writing hits, not BVH builds): "
             "min and median ms over the runs, Mrays/s at the min, and the path the rays took "
             "(the packet backend: coherent groups of 64 rays as packets, the others one at a "
             "time through wide BVHs); --out may then be left out"},
    {"--json", 0, CLI_FLAG, NULL, offsetof(trace_args, json),
     .help = "the same as one JSON object on stdout (ms_min, ms_median, mrays, rays, reps, "
             "threads, backend, device, isa, packet_rays, single_rays, build_ms, any_hit)"},
    {"--packet-path", 0, CLI_CHOICE, "P", offsetof(trace_args, packet_path),
     .choices = path_choices,
     .help = "the packet backend's path: {choices} (auto: each group of 64 consecutive rays "
             "that is coherent as a packet, the others one at a time through wide BVHs); the "
             "same hits on every path",
     .fallback = "auto"},
    {NULL}};

static const cli_group trace_groups[] = {
    {NULL, trace_options, 0},
    {CLI_SCENE_TITLE, cli_scene_options, offsetof(trace_args, scene)},
    {CLI_SCENE_TITLE, cli_time_options, offsetof(trace_args, scene)},
    {CLI_RENDERER_TITLE, cli_renderer_options, offsetof(trace_args, renderer)},
    {CLI_KERNEL_TITLE, cli_kernel_options, offsetof(trace_args, renderer)},
    {CLI_TEST_TITLE, cli_test_options, offsetof(trace_args, renderer)},
    {NULL}};

const cli_command cmd_trace_spec = {
    "trace",
    "trace rays from a text file and write their hits",
    "SCENE",
    "scene",
    1,
    1,
    "Traces the rays of RAYS.txt through SCENE (a .json scene, a bare .obj, a .gltf\n"
    "or .glb, or builtin:NAME) and writes one line per ray to HITS.txt.\n",
    trace_groups,
    NULL,
    NULL};

static int cmp_double(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The timing of the runs (ms[0 .. reps-1], trace time alone) and the path
 * of the last one, as text or one JSON object. */
static void print_stats(const rt_trace_stats *ts, double *ms, int reps, double build_ms,
                        int threads, int any_hit, int json) {
    qsort(ms, (size_t)reps, sizeof *ms, cmp_double);
    const double min = ms[0];
    const double median = reps % 2 ? ms[reps / 2] : 0.5 * (ms[reps / 2 - 1] + ms[reps / 2]);
    const double mrays = min > 0.0 ? (double)ts->rays / (min * 1000.0) : 0.0;
    if (json) {
        printf("{\"rays\": %llu, \"reps\": %d, \"threads\": %d, \"any_hit\": %s, \"ms_min\": %.3f, "
               "\"ms_median\": %.3f, \"mrays\": %.3f, \"build_ms\": %.3f, \"backend\": \"%s\", "
               "\"device\": ",
               (unsigned long long)ts->rays, reps, threads, any_hit ? "true" : "false", min, median,
               mrays, build_ms, ts->backend);
        json_out_string(ts->device);
        printf(", \"isa\": \"%s\", \"packet_rays\": %llu, \"single_rays\": %llu}\n", ts->isa,
               (unsigned long long)ts->packet_rays, (unsigned long long)ts->single_rays);
        return;
    }
    printf("trace: %llu rays (%s), %d run%s%s: min %.3f ms, median %.3f ms, %.2f Mrays/s at the "
           "min\n",
           (unsigned long long)ts->rays, any_hit ? "any hit" : "closest hit", reps,
           reps == 1 ? "" : "s", reps > 1 ? " after a warm-up" : "", min, median, mrays);
    if (!strcmp(ts->backend, "packet"))
        printf("path: packet (%s): %llu rays in packets of 64 (coherent groups), %llu one at a "
               "time through wide BVHs\n",
               ts->isa, (unsigned long long)ts->packet_rays, (unsigned long long)ts->single_rays);
    else if (!strcmp(ts->backend, "cpu"))
        printf("path: cpu (the scalar oracle, one ray at a time through the binary BVHs)\n");
    else
        printf("path: %s (%s)\n", ts->backend, ts->device[0] ? ts->device : "?");
    printf("builds: %.3f ms (BVHs and the backend's copies, not in the trace time)\n", build_ms);
}

int cmd_trace(int argc, char **argv) {
    trace_args a;
    memset(&a, 0, sizeof a);
    cli_args_init(NULL, &a.scene, &a.renderer);
    int code;
    if (cli_parse(&cmd_trace_spec, &a, argc, argv, &code) < 0) return code;
    if (!a.rays) {
        cli_usage_error(&cmd_trace_spec, "--rays RAYS.txt is required");
        return 2;
    }
    if (!a.out && !a.stats && !a.json) {
        cli_usage_error(&cmd_trace_spec, "--out HITS.txt is required (or --stats or --json)");
        return 2;
    }
    const char *out_path = a.out;
    /* --reps given (even 1): one untimed warm-up run first. */
    int reps = a.reps ? a.reps : 1, warm_up = a.reps != 0, stats = a.stats, json = a.json;
    rt_trace_options opt;
    memset(&opt, 0, sizeof opt);
    opt.tri_test = (rt_triangle_test)a.tri_test;
    opt.any_hit = a.any_hit;
    opt.packet_path = (rt_trace_path)a.packet_path;
    /* The output is checked before the rays are read and traced. */
    rt_error oerr;
    if (out_path && rt_hits_check_output(out_path, &oerr) != RT_OK) {
        cli_error("trace", "%s", oerr.message);
        return 2;
    }
    /* The rays are read between making the renderer and opening the scene. */
    cli_session held = {cli_renderer_create("trace", &a.renderer), NULL};
    rt_renderer *renderer = held.renderer;
    if (!renderer) return 2;
    rt_ray *rays = NULL;
    size_t n = 0;
    rt_error rerr;
    if (rt_rays_load(a.rays, a.offset, &rays, &n, &rerr) != RT_OK) {
        cli_error("trace", "%s", rerr.message);
        cli_session_close(&held);
        return 2;
    }
    rt_scene *scene = held.scene = cli_scene_open("trace", argv[0], &a.scene, a.renderer.threads);
    if (!scene) {
        free(rays);
        cli_session_close(&held);
        return 2;
    }
    rt_hit *hits = malloc((n ? n : 1) * sizeof *hits);
    double *ms = malloc(sizeof(double) * (size_t)reps);
    rt_trace_stats ts;
    memset(&ts, 0, sizeof ts);
    opt.stats = &ts;
    rt_status st = hits && ms ? RT_OK : RT_ERROR_OUT_OF_MEMORY;
    double build_ms = 0.0;
    for (int run = warm_up ? -1 : 0; st == RT_OK && run < reps; run++) {
        st = rt_trace_rays(renderer, scene, rays, n, hits, &opt);
        build_ms += ts.build_ms;
        if (run >= 0) ms[run] = ts.trace_ms;
    }
    if (a.renderer.verbose && st == RT_OK) cli_print_build_log("trace", renderer);
    if (st != RT_OK) {
        cli_error("trace", "%s", hits && ms ? rt_renderer_error(renderer) : "out of memory");
        free(rays);
        free(hits);
        free(ms);
        cli_session_close(&held);
        return 2;
    }
    cli_print_backend_choice("trace", &a.renderer, ts.backend, ts.device, ts.notice);
    if (stats || json) print_stats(&ts, ms, reps, build_ms, a.renderer.threads, opt.any_hit, json);
    free(ms);
    rt_renderer_destroy(renderer); /* the scene stays for the hits' columns */
    held.renderer = NULL;
    rt_scene_info info;
    rt_scene_describe(scene, &info);
    int with_inst = info.objects > 1;
    if (!out_path) {
        free(rays);
        free(hits);
        cli_session_close(&held);
        return 0;
    }
    rt_error werr;
    int bad = rt_hits_write(out_path, hits, n, with_inst, &werr) != RT_OK;
    if (bad) cli_error("trace", "%s", werr.message);
    free(rays);
    free(hits);
    cli_session_close(&held);
    return bad ? 2 : 0;
}
