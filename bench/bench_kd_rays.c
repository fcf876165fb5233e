/* SPDX-License-Identifier: Apache-2.0 */
/* bench_kd_rays.c - incoherent ray queries through kd-tree meshes against
 * BVH meshes (issue 18) in one run: the same scene loaded twice, once with
 * BVH meshes and once with every static mesh a kd-tree (exact or binned),
 * and the same rays through both.
 *
 * Per scene two ray sets of N rays (cpu_ref/ray_sets.h, from the BVH
 * layout): diffuse bounces from the camera rays' closest hits, and random
 * rays inside the scene's bounds; each traced for closest hits and for any
 * hit, with rt_trace_rays on the cpu oracle and the packet backend (whose
 * single-ray path hands kd instances to the oracle's traversal). One
 * warm-up round, then R rounds, each running every (set, query, backend,
 * structure) once in turn, so that a busy machine slows them alike; min and
 * median ms, Mrays/s at the median, and the kd/BVH ratio of the medians.
 * Traversal steps (box tests of the BVH; the root box and inner nodes of a
 * kd-tree) and triangle tests per ray come from one pass of the oracle's
 * rt_trace over the layout. The kd closest hits are checked against the
 * BVH's (every bit; any hit: the flag), and the count that differ printed.
 *
 * usage: bench_kd_rays [--rays N] [--reps R] [--threads T] [--binned] [--json] SCENE...
 * (a .json scene or a bare .obj: Sponza and Sibenik get their interior views). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "bench_util.h"
#include "layout/flat.h"
#include "ray_sets.h"
#include "render/renderer_internal.h"
#include "rt.h"

enum { SETS = 2, QUERIES = 2, BACKENDS = 2, ACCELS = 2, MAX_REPS = 64 };
static const char *const set_names[SETS] = {"diffuse", "random"};
static const char *const query_names[QUERIES] = {"closest", "any"};
static const char *const backend_names[BACKENDS] = {"cpu", "packet"};

/* Box (or kd node) and triangle tests per ray of the oracle's traversal. */
static void count_tests(const rt_flat *flat, const rt_ray *rays, size_t n, int any, double *steps,
                        double *tris) {
    rt_scene_view view = rt_flat_view(flat);
    rt_counters c;
    memset(&c, 0, sizeof c);
    for (size_t i = 0; i < n; i++) {
        rt_hit_d h;
        rt_trace(&view, &rays[i], any, &h, &c);
    }
    *steps = (double)c.box_tests / (double)n;
    *tris = (double)c.tri_tests / (double)n;
}

static rt_scene *load(const char *path, rt_accel accel) {
    rt_scene *scene;
    rt_error err;
    if (rt_scene_load(path, &scene, &err) != RT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return NULL;
    }
    if (strstr(path, ".obj")) {
        rt_camera cam;
        rt_camera_get(scene, &cam);
        bench_interior_view(path, &cam);
        rt_camera_set(scene, &cam);
    }
    if (accel != RT_ACCEL_BVH && rt_scene_set_static_accel(scene, accel) != RT_OK) {
        rt_scene_destroy(scene);
        return NULL;
    }
    return scene;
}

static int bench_scene(const char *path, size_t n, int reps, int threads, rt_accel kd, int json) {
    rt_scene *scene[ACCELS] = {load(path, RT_ACCEL_BVH), load(path, kd)};
    rt_renderer *r[BACKENDS][ACCELS];
    int ok = scene[0] && scene[1];
    for (int b = 0; b < BACKENDS; b++)
        for (int a = 0; a < ACCELS; a++) {
            r[b][a] = bench_renderer(backend_names[b], threads);
            ok = ok && r[b][a];
        }
    if (!ok) {
        fprintf(stderr, "%s: cannot load or make the renderers\n", path);
        return 1;
    }
    /* The rays from the BVH layout; the counts from each layout (a layout
     * stays valid until its renderer renders or traces again: counted
     * before any timing, with a renderer of its own). */
    rt_renderer *lr = bench_renderer("cpu", threads);
    rt_backend_layout layout;
    double build_ms, sah;
    rt_ray *rays[SETS];
    double steps[SETS][QUERIES][ACCELS], tris[SETS][QUERIES][ACCELS];
    uint32_t tri_count = 0;
    for (int a = 0; a < ACCELS; a++) {
        if (!lr || rt_renderer_layout(lr, scene[a], &layout, &build_ms, &sah) != RT_OK) {
            fprintf(stderr, "%s: no layout\n", path);
            return 1;
        }
        const rt_flat *flat = layout.flat;
        for (int s = 0; s < SETS; s++) {
            if (a == 0) {
                tri_count = flat->tri_count;
                rays[s] = malloc(sizeof(rt_ray) * n);
                if (!rays[s]) return 1;
                if (s == 0)
                    rt_rays_diffuse(flat, 7, n, rays[s]);
                else
                    rt_rays_random(flat, 7, n, rays[s]);
            }
            for (int q = 0; q < QUERIES; q++)
                count_tests(flat, rays[s], n, q, &steps[s][q][a], &tris[s][q][a]);
        }
    }
    rt_renderer_destroy(lr);
    rt_hit *ref = malloc(sizeof(rt_hit) * n), *got = malloc(sizeof(rt_hit) * n);
    static double ms[SETS][QUERIES][BACKENDS][ACCELS][MAX_REPS];
    long bad[SETS][QUERIES];
    memset(bad, 0, sizeof bad);
    if (!ref || !got) return 1;
    for (int round = 0; round <= reps; round++)
        for (int s = 0; s < SETS; s++)
            for (int q = 0; q < QUERIES; q++)
                for (int b = 0; b < BACKENDS; b++)
                    for (int a = 0; a < ACCELS; a++) {
                        rt_trace_options o = {
                            q, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO, NULL, NULL};
                        rt_hit *out = a == 0 ? ref : got;
                        double t0 = rt_now_ms();
                        rt_status st = rt_trace_rays(r[b][a], scene[a], rays[s], n, out, &o);
                        double dt = rt_now_ms() - t0;
                        if (st != RT_OK) {
                            fprintf(stderr, "%s: %s\n", path, rt_renderer_error(r[b][a]));
                            return 1;
                        }
                        if (round == 0 && a == 1)
                            for (size_t i = 0; i < n; i++)
                                bad[s][q] += !rt_api_hits_same(&got[i], &ref[i], q);
                        if (round > 0) ms[s][q][b][a][round - 1] = dt;
                    }
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    for (int s = 0; s < SETS; s++)
        for (int q = 0; q < QUERIES; q++)
            for (int b = 0; b < BACKENDS; b++) {
                double mn[ACCELS], md[ACCELS];
                for (int a = 0; a < ACCELS; a++)
                    bench_min_median(ms[s][q][b][a], reps, &mn[a], &md[a]);
                if (json) {
                    printf("{\"scene\": \"%s\", \"triangles\": %u, \"rays\": \"%s\", \"query\": "
                           "\"%s\", \"backend\": \"%s\", \"kd\": \"%s\", \"n\": %zu, "
                           "\"threads\": %d, \"bvh_ms_min\": %.3f, \"bvh_ms_median\": %.3f, "
                           "\"kd_ms_min\": %.3f, \"kd_ms_median\": %.3f, \"bvh_mrays\": %.3f, "
                           "\"kd_mrays\": %.3f, \"bvh_steps\": %.2f, \"kd_steps\": %.2f, "
                           "\"bvh_tri_tests\": %.2f, \"kd_tri_tests\": %.2f, \"differ\": %ld}\n",
                           name, tri_count, set_names[s], query_names[q], backend_names[b],
                           rt_accel_name(kd), n, threads, mn[0], md[0], mn[1], md[1],
                           (double)n / (md[0] * 1000.0), (double)n / (md[1] * 1000.0),
                           steps[s][q][0], steps[s][q][1], tris[s][q][0], tris[s][q][1], bad[s][q]);
                    continue;
                }
                printf("%-22s %-8s %-8s %-7s bvh %8.1f / %8.1f ms  %s %8.1f / %8.1f ms  kd/bvh "
                       "%.2fx  steps %.1f / %.1f  tri tests %.1f / %.1f  differ %ld\n",
                       name, set_names[s], query_names[q], backend_names[b], mn[0], md[0],
                       rt_accel_name(kd), mn[1], md[1], md[1] / md[0], steps[s][q][0],
                       steps[s][q][1], tris[s][q][0], tris[s][q][1], bad[s][q]);
            }
    fflush(stdout);
    for (int s = 0; s < SETS; s++) {
        free(rays[s]);
    }
    free(ref);
    free(got);
    for (int b = 0; b < BACKENDS; b++)
        for (int a = 0; a < ACCELS; a++) rt_renderer_destroy(r[b][a]);
    rt_scene_destroy(scene[0]);
    rt_scene_destroy(scene[1]);
    return 0;
}

int main(int argc, char **argv) {
    int rays = 200000, reps = 3, threads = 2, json = 0, bad = 0;
    rt_accel kd = RT_ACCEL_KD;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--rays")) {
            if (!bench_arg_int(argc, argv, &i, 1, 100000000, &rays)) bad = 1;
        } else if (!strcmp(argv[i], "--reps")) {
            if (!bench_arg_int(argc, argv, &i, 1, MAX_REPS, &reps)) bad = 1;
        } else if (!strcmp(argv[i], "--threads")) {
            if (!bench_arg_int(argc, argv, &i, 1, 256, &threads)) bad = 1;
        } else if (!strcmp(argv[i], "--binned")) {
            kd = RT_ACCEL_KD_BINNED;
        } else if (!strcmp(argv[i], "--json")) {
            json = 1;
        } else if (argv[i][0] == '-') {
            bad = 1;
        }
    }
    if (bad) {
        fprintf(stderr, "usage: bench_kd_rays [--rays N] [--reps R] [--threads T] [--binned] "
                        "[--json] SCENE...\n");
        return 2;
    }
    int fails = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--rays") || !strcmp(argv[i], "--reps") ||
            !strcmp(argv[i], "--threads")) {
            i++;
            continue;
        }
        if (argv[i][0] == '-') continue;
        fails += bench_scene(argv[i], (size_t)rays, reps, threads, kd, json);
    }
    return fails ? 1 : 0;
}
