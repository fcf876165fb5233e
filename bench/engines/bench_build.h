/* SPDX-License-Identifier: Apache-2.0 */
/* bench_build.h - 'rtcl bench' without --animate or --incoherent: per
 * scene, BVH build times and tree quality of every builder beside Embree's,
 * then frame times of every backend (bench_render.h). Only rt.h types here:
 * rtcl (host/cli) includes it. */
#ifndef RT_BENCH_BUILD_H
#define RT_BENCH_BUILD_H

#include "rt.h"

typedef struct bench_build_setup {
    const char *who; /* the prefix of error lines: "rtcl bench" */
    int json;        /* 1: one JSON object per scene per line; 0: tables */
    int reps;        /* timed repetitions (builds) and frames, after one warm-up */
    int threads;     /* the threaded builders', the renderers' and Embree's (> 0) */
    int progress;    /* 1: a progress line on stderr (a terminal) */
    int render;      /* 0: builds only */
    int width, height;
    rt_device_math device_math; /* the "opencl" render row's; portable: no opencl-portable row */
    rt_denormals denormals;     /* every render row's */
    int accel; /* an rt_accel for every static mesh of the render part (kd and kd-binned also
                  add the kd build rows), or -1: the scene's own */
    /* Called with the renderer after each backend's warm-up frame (--verbose:
     * the device compiler's messages), or NULL. */
    void (*build_log)(const rt_renderer *renderer);
} bench_build_setup;

/* Runs the benchmark on each scene (a file or builtin:NAME) and prints its
 * table, or its JSON object on one line ("scene", "triangles", "reps",
 * "warmup", "build", "reference" and, when rendering, "render_width",
 * "render_height", "render"). Errors go to stderr after setup->who. Returns
 * 0, or 2 when a scene failed. */
int bench_build_run(const char *const *scenes, int n_scenes, const bench_build_setup *setup);

#endif /* RT_BENCH_BUILD_H */
