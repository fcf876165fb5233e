/* cmd_trace.c - 'rtcl trace': rays from a text file through a scene, one hit
 * line per ray (rt_trace_rays). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "commands.h"
#include "formats/ray_file.h"
#include "scene/scene.h"

static const char usage_head[] =
    "usage: rtcl trace SCENE --rays RAYS.txt --out HITS.txt [--backend B] [--device D]\n"
    "                  [--tri-test T] [--any-hit] [--offset-origins] [--threads N]\n"
    "                  [--accel A] [--reps N] [--stats] [--json] [--packet-path P]\n"
    "                  [--cl-options OPTS] [--packet-isa I] [--verbose] [--help]\n"
    "\n"
    "Traces the rays of RAYS.txt through SCENE (a .json scene, a bare .obj, or\n"
    "builtin:NAME) and writes one line per ray to HITS.txt.\n"
    "\n"
    "RAYS.txt   one ray per line: ox oy oz dx dy dz tmin tmax (the ray o + t d for\n"
    "           t in [tmin, tmax], inclusive; d need not be normalised, t is in its\n"
    "           units). Blank lines and lines starting with '#' are skipped. A ray\n"
    "           with a NaN or infinite component or a zero direction is a miss.\n"
    "HITS.txt   per ray: 'hit t u v prim', plus ' inst' when the scene has more\n"
    "           than one object. hit is 1 or 0; p = (1-u-v) v0 + u v1 + v v2; prim is\n"
    "           the 0-based triangle index in its mesh's file order; inst the object\n"
    "           index. Floats as %.9g. A miss is '0 inf 0 0 -1' (plus ' -1').\n"
    "\n"
    "  --tri-test T the ray/triangle test: watertight (Woop, Benthin, Wald 2013),\n"
    "               mt (Moller-Trumbore), pluecker or badouel [watertight]\n"
    "  --any-hit    stop at any hit in range (shadow-ray queries): hit is then\n"
    "               exact, t u v prim inst belong to some hit, not the closest\n"
    "  --offset-origins  each ray line has 3 more numbers, nx ny nz: the origin\n"
    "               is a point on a surface with that normal, and is moved off it\n"
    "               with the engine's offset (as for shadow and secondary rays),\n"
    "               to the side the direction points to\n"
    "  --reps N     trace the rays N times after one untimed warm-up (the hits\n"
    "               written are the last run's, the same every time) [1, no warm-up]\n"
    "  --stats      print the trace time alone (not reading rays, not writing\n"
    "               hits, not BVH builds): min and median ms over the runs, Mrays/s\n"
    "               at the min, and the path the rays took (the packet backend:\n"
    "               coherent groups of 64 rays as packets, the others one at a time\n"
    "               through wide BVHs); --out may then be left out\n"
    "  --packet-path P  the packet backend's path: auto (each group of 64\n"
    "               consecutive rays that is coherent as a packet, the others one\n"
    "               at a time through wide BVHs), packets, or single; the same hits\n"
    "               on every path [auto]\n"
    "  --json       the same as one JSON object on stdout (ms_min, ms_median,\n"
    "               mrays, rays, reps, threads, backend, isa, packet_rays,\n"
    "               single_rays, build_ms, any_hit)\n";

static void print_usage(FILE *f) {
    fputs(usage_head, f);
    fputs(cli_renderer_usage, f);
}

static const char *const tri_test_names[] = {"watertight", "mt", "pluecker", "badouel"};

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
               "\"isa\": \"%s\", \"packet_rays\": %llu, \"single_rays\": %llu}\n",
               (unsigned long long)ts->rays, reps, threads, any_hit ? "true" : "false", min, median,
               mrays, build_ms, ts->backend, ts->isa, (unsigned long long)ts->packet_rays,
               (unsigned long long)ts->single_rays);
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
    else
        printf("path: %s\n", !strcmp(ts->backend, "cpu") ? "cpu (the scalar oracle, one ray at a "
                                                           "time through the binary BVHs)"
                                                         : ts->backend);
    printf("builds: %.3f ms (BVHs and the backend's copies, not in the trace time)\n", build_ms);
}

int cmd_trace(int argc, char **argv) {
    const char *scene_path = NULL, *rays_path = NULL, *out_path = NULL;
    int offset = 0, reps = 1, warm_up = 0, stats = 0, json = 0;
    rt_trace_options opt;
    memset(&opt, 0, sizeof opt);
    cli_renderer_args ra;
    cli_renderer_args_init(&ra);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int taken = cli_renderer_arg(argc, argv, &i, "trace", &ra);
        if (taken < 0) return 2;
        if (taken) continue;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            print_usage(stdout);
            return 0;
        } else if (!strcmp(a, "--rays")) {
            if (!(rays_path = cli_value(argc, argv, &i, "trace"))) return 2;
        } else if (!strcmp(a, "--out") || !strcmp(a, "-o")) {
            if (!(out_path = cli_value(argc, argv, &i, "trace"))) return 2;
        } else if (!strcmp(a, "--tri-test")) {
            const char *name = cli_value(argc, argv, &i, "trace");
            if (!name) return 2;
            int found = -1;
            for (int k = 0; k < 4; k++)
                if (!strcmp(name, tri_test_names[k])) found = k;
            if (found < 0) {
                cli_error("trace", "unknown triangle test '%s' (watertight, mt, pluecker, badouel)",
                          name);
                return 2;
            }
            opt.tri_test = (rt_triangle_test)found;
        } else if (!strcmp(a, "--offset-origins")) {
            offset = 1;
        } else if (!strcmp(a, "--any-hit")) {
            opt.any_hit = 1;
        } else if (!strcmp(a, "--reps")) {
            const char *v = cli_value(argc, argv, &i, "trace");
            if (!v || !cli_int("trace", "--reps", v, 1, 100000, &reps)) return 2;
            warm_up = 1;
        } else if (!strcmp(a, "--packet-path")) {
            const char *v = cli_value(argc, argv, &i, "trace");
            if (!v) return 2;
            if (!strcmp(v, "auto")) {
                opt.packet_path = RT_TRACE_PATH_AUTO;
            } else if (!strcmp(v, "packets")) {
                opt.packet_path = RT_TRACE_PATH_PACKETS;
            } else if (!strcmp(v, "single")) {
                opt.packet_path = RT_TRACE_PATH_SINGLE;
            } else {
                cli_error("trace", "unknown packet path '%s' (auto, packets, single)", v);
                return 2;
            }
        } else if (!strcmp(a, "--stats")) {
            stats = 1;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (a[0] == '-' && a[1]) {
            cli_error("trace", "unknown option '%s'", a);
            print_usage(stderr);
            return 2;
        } else if (scene_path) {
            cli_error("trace", "more than one scene given ('%s' and '%s')", scene_path, a);
            return 2;
        } else {
            scene_path = a;
        }
    }
    if (!scene_path || !rays_path || (!out_path && !stats && !json)) {
        cli_error("trace", "need SCENE, --rays and --out (or --stats or --json)");
        print_usage(stderr);
        return 2;
    }
    /* The output is checked before the rays are read and traced. */
    rt_error oerr;
    if (out_path && rt_hits_check_output(out_path, &oerr) != RT_OK) {
        cli_error("trace", "%s", oerr.message);
        return 2;
    }
    rt_renderer *renderer = cli_renderer_create("trace", &ra);
    if (!renderer) return 2;
    rt_ray *rays = NULL;
    size_t n = 0;
    rt_error rerr;
    if (rt_rays_load(rays_path, offset, &rays, &n, &rerr) != RT_OK) {
        cli_error("trace", "%s", rerr.message);
        rt_renderer_destroy(renderer);
        return 2;
    }
    rt_scene *scene;
    rt_error err;
    if (cli_load_scene(scene_path, &scene, &err) != RT_OK) {
        cli_error("trace", "%s", err.message);
        free(rays);
        rt_renderer_destroy(renderer);
        return 2;
    }
    if (!cli_apply_accel("trace", &ra, scene)) {
        rt_scene_destroy(scene);
        free(rays);
        rt_renderer_destroy(renderer);
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
    if (ra.verbose && st == RT_OK) cli_print_build_log("trace", renderer);
    if (st != RT_OK) {
        cli_error("trace", "%s", hits && ms ? rt_renderer_error(renderer) : "out of memory");
        free(rays);
        free(hits);
        free(ms);
        rt_scene_destroy(scene);
        rt_renderer_destroy(renderer);
        return 2;
    }
    if (stats || json) print_stats(&ts, ms, reps, build_ms, ra.opt.threads, opt.any_hit, json);
    free(ms);
    rt_renderer_destroy(renderer);
    int with_inst = scene->object_count > 1;
    if (!out_path) {
        free(rays);
        free(hits);
        rt_scene_destroy(scene);
        return 0;
    }
    rt_error werr;
    int bad = rt_hits_write(out_path, hits, n, with_inst, &werr) != RT_OK;
    if (bad) cli_error("trace", "%s", werr.message);
    free(rays);
    free(hits);
    rt_scene_destroy(scene);
    return bad ? 2 : 0;
}
