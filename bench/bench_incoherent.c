/* bench_incoherent.c - incoherent ray queries: rt_trace_rays on the packet
 * backend (incoherent groups through the single-ray tracer) beside Embree's
 * rtcIntersect1/rtcOccluded1 and its 16-wide packets used as streams
 * (rtcIntersect16/rtcOccluded16 on 16 consecutive rays) on the same rays in
 * the same run, with the same thread count.
 *
 * Per scene two ray sets of N rays (cpu_ref/ray_sets.h): diffuse bounces
 * from the camera rays' closest hits, and random rays inside the scene's
 * bounds; each traced for closest hits and for any hit. One warm-up round,
 * then R rounds, each running every (set, query, tracer) once in turn, so
 * that a busy machine slows them alike; min and median time per
 * combination; Mrays/s at the min and the ratio of ours to Embree's at the
 * min and the median. Our hits are compared with the scalar oracle's
 * (closest: every bit of t, u, v, prim, inst; any: the flag).
 *
 * usage: bench_incoherent [--rays N] [--reps R] [--threads T] [--json] SCENE...
 * (a .json scene, a bare .obj: Sponza and Sibenik get their interior views). */
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
#ifdef RT_HAVE_EMBREE
#include "peer/embree_peer.h"
#endif

enum { SETS = 2, QUERIES = 2, TRACERS = 3, MAX_REPS = 64 };
static const char *const set_names[SETS] = {"diffuse", "random"};
static const char *const query_names[QUERIES] = {"closest", "any"};

static void to_api(const rt_ray_d *in, size_t n, rt_ray *out) {
    for (size_t i = 0; i < n; i++) {
        memcpy(out[i].org, in[i].org, sizeof out[i].org);
        memcpy(out[i].dir, in[i].dir, sizeof out[i].dir);
        out[i].tmin = in[i].tmin;
        out[i].tmax = in[i].tmax;
    }
}

static int same_hit(const rt_hit *a, const rt_hit *b, int any) {
    if (a->hit != b->hit) return 0;
    if (any || !a->hit) return 1;
    return memcmp(&a->t, &b->t, sizeof a->t) == 0 && memcmp(&a->u, &b->u, sizeof a->u) == 0 &&
           memcmp(&a->v, &b->v, sizeof a->v) == 0 && a->prim == b->prim && a->inst == b->inst;
}

static int bench_scene(const char *path, size_t n, int reps, int threads, int json) {
    rt_scene *scene;
    rt_error err;
    if (rt_scene_load(path, &scene, &err) != RT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    if (strstr(path, ".obj")) {
        rt_camera cam;
        rt_camera_get(scene, &cam);
        bench_interior_view(path, &cam);
        rt_camera_set(scene, &cam);
    }
    rt_renderer *oracle = bench_renderer("cpu", threads),
                *packet = bench_renderer("packet", threads);
    rt_backend_layout layout;
    double build_ms, sah;
    if (!oracle || !packet ||
        rt_renderer_layout(oracle, scene, &layout, &build_ms, &sah) != RT_OK) {
        fprintf(stderr, "%s: no layout\n", path);
        return 1;
    }
    const rt_flat *flat = layout.flat;
    rt_ray_d *rd[SETS];
    rt_ray *rays[SETS];
    rt_hit *ref[SETS][QUERIES], *got = malloc(sizeof(rt_hit) * n);
    rt_hit_d *eh = malloc(sizeof(rt_hit_d) * n);
    for (int s = 0; s < SETS; s++) {
        rays[s] = malloc(sizeof(rt_ray) * n);
        rd[s] = malloc(sizeof(rt_ray_d) * n);
        if (s == 0)
            rt_rays_diffuse(flat, 7, n, rd[s]);
        else
            rt_rays_random(flat, 7, n, rd[s]);
        to_api(rd[s], n, rays[s]);
        for (int q = 0; q < QUERIES; q++) {
            ref[s][q] = malloc(sizeof(rt_hit) * n);
            rt_trace_options o = {q, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO};
            rt_trace_rays(oracle, scene, rays[s], n, ref[s][q], &o);
        }
    }
#ifdef RT_HAVE_EMBREE
    rt_embree *em = NULL;
    rt_embree_scene *es = NULL;
    double commit_ms;
    if (rt_embree_create(threads, &em, &err) != RT_OK ||
        rt_embree_scene_create(em, flat, &es, &commit_ms, &err) != RT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
#endif
    double ms[SETS][QUERIES][TRACERS][MAX_REPS];
    long bad[SETS][QUERIES];
    memset(bad, 0, sizeof bad);
    for (int round = 0; round <= reps; round++)
        for (int s = 0; s < SETS; s++)
            for (int q = 0; q < QUERIES; q++)
                for (int t = 0; t < TRACERS; t++) {
                    double dt = -1.0;
                    if (t == 0) {
                        rt_trace_options o = {q, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO};
                        double t0 = rt_now_ms();
                        rt_trace_rays(packet, scene, rays[s], n, got, &o);
                        dt = rt_now_ms() - t0;
                        if (round == 0)
                            for (size_t i = 0; i < n; i++)
                                bad[s][q] += !same_hit(&got[i], &ref[s][q][i], q);
                    }
#ifdef RT_HAVE_EMBREE
                    else {
                        rt_embree_trace_rays(es, rd[s], n, q, t == 1 ? 1 : 16, layout.pool, eh,
                                             &dt);
                    }
#endif
                    if (round > 0) ms[s][q][t][round - 1] = dt;
                }
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    for (int s = 0; s < SETS; s++)
        for (int q = 0; q < QUERIES; q++) {
            double mn[TRACERS], md[TRACERS];
            for (int t = 0; t < TRACERS; t++) bench_min_median(ms[s][q][t], reps, &mn[t], &md[t]);
            const double mr = (double)n / (mn[0] * 1000.0);
            if (json) {
                printf(
                    "{\"scene\": \"%s\", \"triangles\": %u, \"rays\": \"%s\", \"query\": \"%s\", "
                    "\"n\": %zu, \"threads\": %d, \"ms_min\": %.3f, \"ms_median\": %.3f, "
                    "\"mrays\": %.3f, \"embree1_ms_min\": %.3f, \"embree1_ms_median\": %.3f, "
                    "\"embree16_ms_min\": %.3f, \"embree16_ms_median\": %.3f, "
                    "\"differ\": %ld}\n",
                    name, flat->tri_count, set_names[s], query_names[q], n, threads, mn[0], md[0],
                    mr, mn[1], md[1], mn[2], md[2], bad[s][q]);
                continue;
            }
            printf("%-22s %8u %-8s %-8s packet %8.1f / %8.1f ms (%6.2f Mrays/s)  embree1 %8.1f / "
                   "%8.1f ms  embree16 %8.1f / %8.1f ms  vs embree1 %.2fx / %.2fx  vs embree16 "
                   "%.2fx / %.2fx  differ %ld\n",
                   name, flat->tri_count, set_names[s], query_names[q], mn[0], md[0], mr, mn[1],
                   md[1], mn[2], md[2], mn[1] / mn[0], md[1] / md[0], mn[2] / mn[0], md[2] / md[0],
                   bad[s][q]);
        }
    fflush(stdout);
#ifdef RT_HAVE_EMBREE
    rt_embree_scene_destroy(es);
    rt_embree_destroy(em);
#endif
    for (int s = 0; s < SETS; s++) {
        free(rays[s]);
        free(rd[s]);
        for (int q = 0; q < QUERIES; q++) free(ref[s][q]);
    }
    free(got);
    free(eh);
    rt_renderer_destroy(oracle);
    rt_renderer_destroy(packet);
    rt_scene_destroy(scene);
    return 0;
}

int main(int argc, char **argv) {
    int rays = 1000000, reps = 5, threads = 2, json = 0, bad = 0, scenes = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--rays")) {
            if (!bench_arg_int(argc, argv, &i, 1, 100000000, &rays)) bad = 1;
        } else if (!strcmp(argv[i], "--reps")) {
            if (!bench_arg_int(argc, argv, &i, 1, MAX_REPS, &reps)) bad = 1;
        } else if (!strcmp(argv[i], "--threads")) {
            if (!bench_arg_int(argc, argv, &i, 1, 256, &threads)) bad = 1;
        } else if (!strcmp(argv[i], "--json")) {
            json = 1;
        } else if (argv[i][0] == '-') {
            bad = 1;
        }
    }
    if (bad) {
        fprintf(stderr, "usage: bench_incoherent [--rays N] [--reps R] [--threads T] [--json] "
                        "SCENE...\n");
        return 2;
    }
#ifndef RT_HAVE_EMBREE
    fprintf(stderr, "bench_incoherent: this build has no Embree peer (install libembree-dev)\n");
    return 2;
#endif
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--rays") || !strcmp(argv[i], "--reps") ||
            !strcmp(argv[i], "--threads")) {
            i++;
            continue;
        }
        if (argv[i][0] == '-') continue;
        scenes++;
        if (bench_scene(argv[i], (size_t)rays, reps, threads, json)) return 1;
    }
    return scenes ? 0 : 2;
}
