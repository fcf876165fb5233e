/* SPDX-License-Identifier: Apache-2.0 */
/* bench_render.h - the render part of 'rtcl bench' (bench_build.h): frame
 * times of every backend on one scene in the thesis's set-up, Embree beside
 * them. */
#ifndef RT_BENCH_RENDER_H
#define RT_BENCH_RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "rt.h"

enum { BENCH_RENDER_MAX_ROWS = 11 };

typedef struct render_row {
    char backend[24]; /* cpu, packet, opencl, embree-1/4/8/16, embree (its best) */
    int threads;
    int lanes; /* embree rows: rays per Embree call; else 0 */
    double ms_min, ms_median;
    double mrays;                /* rays per microsecond of the median frame */
    double box_tests, tri_tests; /* per ray; < 0 when not counted (embree) */
    uint64_t rays;               /* primary plus shadow rays of one frame */
    long pixels_differ;          /* pixels whose colour differs from cpu's */
    long pixels_visible;         /* ... by more than 1/256 in some channel */
    double max_diff;             /* largest channel difference from cpu's */
    char error[200];             /* non-empty: this backend failed or is unavailable */
} render_row;

typedef struct bench_render_setup {
    int reps, threads, width, height;
    int device_math; /* rt_device_math of the "opencl" row */
    int denormals;   /* rt_denormals of every row */
    int accel;       /* rt_accel for every static mesh, or -1: the scene's own */
    void (*progress)(const char *scene, const char *what);
    /* Called with the renderer after each backend's warm-up frame (the
     * device compiler's messages for --verbose), or NULL. */
    void (*build_log)(const rt_renderer *renderer);
} bench_render_setup;

/* Renders the scene at setup->width x height with direct_only (primary plus
 * shadow rays, Phong) on cpu, packet and opencl (in setup->device_math) and,
 * unless that is portable already, opencl-portable (the portable maths
 * profile, for its cost), one warm-up frame each (not
 * counted: it builds the BVHs, compiles and uploads) then reps frames; with
 * Embree in the build, also rtcIntersect1/4/8(/16) frames and a row "embree"
 * for its fastest width. Frames are interleaved round by round (every row's
 * frame i before any row's frame i + 1), so that other work on the machine
 * falls on every row alike and the ratios hold; each timed frame follows an
 * untimed frame of the same row, so that it finds the caches as its own
 * previous frame left them. Returns the number of rows, 0 if the scene could
 * not be loaded (message in err). */
int bench_render(const char *path, const bench_render_setup *setup, render_row *rows, char *err,
                 size_t err_size);

#endif /* RT_BENCH_RENDER_H */
