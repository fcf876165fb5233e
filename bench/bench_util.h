/* SPDX-License-Identifier: Apache-2.0 */
/* bench_util.h - what the benchmark programs share: min and median of
 * repeated timings, integer options, the interior views of
 * shared/scenes/VIEWS.md for the bare OBJ files of Sponza and Sibenik, and
 * pinhole primary rays through pixel centres, renderers. Header-only (static inline
 * functions): every bench/bench_*.c is its own program. */
#ifndef RT_BENCH_UTIL_H
#define RT_BENCH_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rt.h"

static inline int bench_cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The integer argument after option argv[*i], in [lo, hi]: advances *i past
 * it; 0 when it is missing, not a number or out of range. */
static inline int bench_arg_int(int argc, char **argv, int *i, int lo, int hi, int *out) {
    if (*i + 1 >= argc) return 0;
    char *end;
    long v = strtol(argv[++*i], &end, 10);
    if (*end || v < lo || v > hi) return 0;
    *out = (int)v;
    return 1;
}

/* A renderer on backend (NULL: cpu) with threads (0: all cores); prints
 * the reason and returns NULL when it cannot be made. */
static inline rt_renderer *bench_renderer(const char *backend, int threads) {
    rt_renderer_options o = rt_renderer_options_default();
    if (backend) o.backend = backend;
    o.threads = threads;
    rt_renderer *r = NULL;
    rt_error err;
    if (rt_renderer_create(&o, &r, &err) != RT_OK) fprintf(stderr, "%s\n", err.message);
    return r;
}

/* Sorts v[0..n) and returns its minimum and median (the mean of the middle
 * two for even n). */
static inline void bench_min_median(double *v, int n, double *min, double *median) {
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    *min = v[0];
    *median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The interior views of VIEWS.md for the architectural scenes, when path is
 * one of their bare OBJ files (the JSON scenes in bench/scenes/ carry them). */
static inline void bench_interior_view(const char *path, rt_camera *cam) {
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

/* Pinhole rays through pixel centres (as the renderer's camera), w x h of
 * them, row-major from the top row. */
static inline void bench_primary_rays(const rt_camera *c, int w, int h, rt_ray *rays) {
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

#endif /* RT_BENCH_UTIL_H */
