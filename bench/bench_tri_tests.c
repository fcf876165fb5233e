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

#include "clock.h"
#include "rt.h"

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The interior views of VIEWS.md for the architectural scenes. */
static void interior_view(const char *path, rt_camera *cam) {
    static const struct {
        const char *name;
        float eye[3], at[3], fov;
    } views[] = {{"sponza.obj", {-14, 3, 0}, {10, 5, 0}, 75},
                 {"sibenik.obj", {-17, -10, 0}, {10, -7, 0}, 75}};
    for (size_t i = 0; i < sizeof views / sizeof views[0]; i++) {
        if (!strstr(path, views[i].name)) continue;
        memcpy(cam->position, views[i].eye, sizeof cam->position);
        memcpy(cam->look_at, views[i].at, sizeof cam->look_at);
        cam->up[0] = cam->up[2] = 0.0f;
        cam->up[1] = 1.0f;
        cam->hfov_degrees = views[i].fov;
    }
}

/* Pinhole rays through pixel centres (as the renderer's camera). */
static void primary_rays(const rt_camera *c, int w, int h, rt_ray *rays) {
    float f[3], r[3], u[3], len;
    for (int k = 0; k < 3; k++) f[k] = c->look_at[k] - c->position[k];
    len = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int k = 0; k < 3; k++) f[k] /= len;
    r[0] = f[1] * c->up[2] - f[2] * c->up[1];
    r[1] = f[2] * c->up[0] - f[0] * c->up[2];
    r[2] = f[0] * c->up[1] - f[1] * c->up[0];
    len = sqrtf(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int k = 0; k < 3; k++) r[k] /= len;
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    float tx = tanf(c->hfov_degrees * 3.14159265f / 360.0f), ty = tx * (float)h / (float)w;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            rt_ray *ray = &rays[(size_t)y * w + x];
            float sx = (2.0f * (x + 0.5f) / w - 1.0f) * tx,
                  sy = (1.0f - 2.0f * (y + 0.5f) / h) * ty;
            for (int k = 0; k < 3; k++) {
                ray->org[k] = c->position[k];
                ray->dir[k] = f[k] + sx * r[k] + sy * u[k];
            }
            ray->tmin = 0.0f;
            ray->tmax = INFINITY;
        }
}

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
    interior_view(argv[1], &cam);
    size_t n = (size_t)w * h;
    rt_ray *rays = malloc(n * sizeof *rays);
    rt_hit *hits = malloc(n * sizeof *hits);
    if (!rays || !hits) return 1;
    primary_rays(&cam, w, h, rays);
    static const char *names[] = {"watertight", "mt", "pluecker", "badouel"};
    double ms[4][100];
    size_t hit_count[4] = {0};
    rt_render_options opt = rt_render_options_default();
    opt.backend = backend;
    /* One untimed pass builds the BVH and layout. */
    if (rt_trace_rays_with(scene, rays, n, hits, 0, &opt) != RT_OK) {
        fprintf(stderr, "%s\n", rt_scene_error(scene));
        return 1;
    }
    for (int r = 0; r < runs; r++)
        for (int m = 0; m < 4; m++) {
            opt.tri_test = (rt_triangle_test)m;
            double t0 = rt_now_ms();
            rt_trace_rays_with(scene, rays, n, hits, 0, &opt);
            ms[m][r] = rt_now_ms() - t0;
            if (r == 0)
                for (size_t i = 0; i < n; i++) hit_count[m] += hits[i].hit != 0;
        }
    printf("%s, %dx%d primary rays, %d runs, backend %s\n", argv[1], w, h, runs, backend);
    printf("%-11s %9s %9s %9s %9s %8s\n", "test", "min ms", "median ms", "Mrays/s", "vs wt",
           "hits");
    double base = 0;
    for (int m = 0; m < 4; m++) {
        qsort(ms[m], (size_t)runs, sizeof(double), cmp_double);
        double med = ms[m][runs / 2];
        if (m == 0) base = med;
        printf("%-11s %9.2f %9.2f %9.2f %+8.1f%% %8zu\n", names[m], ms[m][0], med,
               (double)n / (ms[m][0] * 1e3), 100.0 * (med - base) / base, hit_count[m]);
    }
    free(rays);
    free(hits);
    rt_scene_destroy(scene);
    return 0;
}
