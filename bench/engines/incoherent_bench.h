/* SPDX-License-Identifier: Apache-2.0 */
/* incoherent_bench.h - the incoherent-ray benchmark (issue 20), shared by
 * 'rtcl bench --incoherent' (host/cli/cmd_bench.c) and the standalone
 * bench/bench_incoherent.c: reproducible ray sets, interleaved timing of our
 * tracers and Embree's on the same rays, and Whitted frames.
 *
 * Per scene two sets of n rays (cpu_ref/ray_sets.h, seed 7): "diffuse",
 * cosine bounces from the closest hits of camera rays, and "random", rays
 * inside the scene's bounds; each traced for the closest hit ("closest")
 * and for any hit ("any") by
 *   rtcl   cpu          rt_trace_rays on the scalar oracle backend
 *   rtcl   packet-auto  rt_trace_rays on the packet backend, path auto
 *   embree rtcIntersect1 / rtcOccluded1 (one ray per call)
 *   embree rtcIntersect16 / rtcOccluded16 (16 consecutive rays per call)
 * (the Embree rows only where this build has the peer, bench/peer/), all
 * with the same thread count. One warm-up round, then reps rounds, each
 * running every (set, query, tracer) once in turn, so that a busy machine
 * slows them alike. Each time is one whole call, the library's copies of
 * rays and hits included. The packet rows' hits are compared with the
 * oracle's in the warm-up round (closest: every bit of t, u, v, prim and
 * inst; any: the flag). */
#ifndef RT_INCOHERENT_BENCH_H
#define RT_INCOHERENT_BENCH_H

#include <stddef.h>
#include <stdint.h>

#include "rt.h"

enum { INCOH_MAX_ROWS = 16, INCOH_WHITTED_ROWS = 2 };

typedef struct incoh_row {
    const char *rays;   /* "diffuse" or "random" */
    const char *query;  /* "closest" or "any" */
    const char *engine; /* "rtcl" or "embree" */
    const char *path;   /* "cpu", "packet-auto", "rtcIntersect1", "rtcOccluded16", ... */
    double ms_min, ms_median;
    double mrays_min, mrays_median; /* Mrays/s at the min and at the median time */
    long differ;                    /* packet-auto: hits unlike the oracle's; else -1 */
} incoh_row;

/* Whitted frames (reflection and refraction rays) of one backend. */
typedef struct incoh_whitted_row {
    const char *backend;   /* "packet" or "cpu" */
    const char *secondary; /* how secondary rays are traced: "single-ray" or "oracle" */
    double ms_min, ms_median;
    double mrays_median; /* all rays of a frame over the median frame */
    uint64_t rays;
} incoh_whitted_row;

typedef struct incoh_setup {
    size_t rays; /* per set */
    int reps;    /* timed rounds (after one warm-up round) */
    int threads;
    int width, height; /* the Whitted frames' resolution */
    uint32_t seed;     /* the ray sets' seed */
    int whitted;       /* 1: also time Whitted frames */
    /* Called with the loaded scene's camera (may change it; NULL: kept). */
    void (*camera)(const char *path, rt_camera *cam);
    /* Progress (NULL: none). */
    void (*progress)(const char *scene, const char *what);
} incoh_setup;

typedef struct incoh_result {
    uint32_t triangles;
    int n_rows;
    incoh_row rows[INCOH_MAX_ROWS];
    int n_whitted;
    incoh_whitted_row whitted[INCOH_WHITTED_ROWS];
    char whitted_error[200]; /* non-empty: the Whitted frames failed */
    /* Why there are no Embree rows ("" when there are). */
    char embree_absent[200];
} incoh_result;

/* The default setup: 10^6 rays, 5 reps, 2 threads, 1024x576, seed 7,
 * Whitted frames on. */
incoh_setup incoh_setup_default(void);

/* Runs the benchmark on the scene file at path into *out. Returns 1, or 0
 * with a message in err when the scene cannot be loaded or traced. */
int incoh_bench_scene(const char *path, const incoh_setup *su, incoh_result *out, char *err,
                      size_t err_size);

/* The row of engine/path for the same rays and query as r, or NULL. */
const incoh_row *incoh_find(const incoh_result *res, const incoh_row *r, const char *path);

/* Runs the benchmark on each scene and prints, per scene, a table (json 0)
 * or one JSON object on one line (json 1; fields in docs/BENCHMARKS.md and
 * 'rtcl bench --help'). Errors go to stderr prefixed with who. Returns 0,
 * or 2 when a scene failed. */
int incoh_run(const char *const *scenes, int n_scenes, const incoh_setup *su, int json,
              const char *who);

#endif /* RT_INCOHERENT_BENCH_H */
