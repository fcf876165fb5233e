/* SPDX-License-Identifier: Apache-2.0 */
/* bench_tri_tests.c - what robustness costs: trace speed of the watertight
 * default against the other triangle tests (docs/ROBUSTNESS.md).
 *
 * usage: bench_tri_tests SCENE [width height runs backend]
 * Primary rays of the scene's camera (the bare-OBJ default view; Sponza and
 * Sibenik get the interior views of shared/scenes/VIEWS.md), the same rays
 * for every test, traced 'runs' times each through rt_trace_rays_with on all
 * cores; prints min and median milliseconds and Mrays/s per test. The tests
 * are interleaved run by run so that load drifts hit them alike. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "base/clock.h"
#include "rt.h"

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: %s SCENE [width height runs backend]\n", argv[0]);
        return 2;
    }
    int w = argc > 2 ? atoi(argv[2]) : 512, h = argc > 3 ? atoi(argv[3]) : 288;
    int runs = argc > 4 ? atoi(argv[4]) : 5;
    const char *backend = argc > 5 ? argv[5] : "cpu";
    if (w <= 0 || h <= 0 || runs <= 0 || runs > 100) return 2;
    rt_scene *scene;
    rt_error err;
    if (rt_scene_load(argv[1], &scene, &err) != RT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    rt_camera cam;
    rt_camera_get(scene, &cam);
    bench_interior_view(argv[1], &cam);
    size_t n = (size_t)w * h;
    rt_ray *rays = malloc(n * sizeof *rays);
    rt_hit *hits = malloc(n * sizeof *hits);
    if (!rays || !hits) return 1;
    bench_primary_rays(&cam, w, h, rays);
    static const char *names[] = {"watertight", "mt", "pluecker", "badouel"};
    double ms[4][100];
    size_t hit_count[4] = {0};
    rt_renderer *renderer = bench_renderer(backend, 0);
    if (!renderer) return 1;
    rt_trace_options opt = {0, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO, NULL, NULL};
    /* One untimed pass builds the BVH and layout. */
    if (rt_trace_rays(renderer, scene, rays, n, hits, &opt) != RT_OK) {
        fprintf(stderr, "%s\n", rt_renderer_error(renderer));
        return 1;
    }
    for (int r = 0; r < runs; r++)
        for (int m = 0; m < 4; m++) {
            opt.tri_test = (rt_triangle_test)m;
            double t0 = rt_now_ms();
            rt_trace_rays(renderer, scene, rays, n, hits, &opt);
            ms[m][r] = rt_now_ms() - t0;
            if (r == 0)
                for (size_t i = 0; i < n; i++) hit_count[m] += hits[i].hit != 0;
        }
    printf("%s, %dx%d primary rays, %d runs, backend %s\n", argv[1], w, h, runs, backend);
    printf("%-11s %9s %9s %9s %9s %8s\n", "test", "min ms", "median ms", "Mrays/s", "vs wt",
           "hits");
    double base = 0;
    for (int m = 0; m < 4; m++) {
        double min, med;
        bench_min_median(ms[m], runs, &min, &med);
        if (m == 0) base = med;
        printf("%-11s %9.2f %9.2f %9.2f %+8.1f%% %8zu\n", names[m], min, med,
               (double)n / (min * 1e3), 100.0 * (med - base) / base, hit_count[m]);
    }
    free(rays);
    free(hits);
    rt_renderer_destroy(renderer);
    rt_scene_destroy(scene);
    return 0;
}
