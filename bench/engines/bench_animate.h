/* SPDX-License-Identifier: Apache-2.0 */
/* bench_animate.h - the keyframe benchmark of Langr 2016 (section 4.1) for
 * deforming meshes, 'rtcl bench --animate' and bench/bench_dynamic: an
 * animated scene played frame by frame with each update policy of ours on
 * the packet backend, beside Embree updating and tracing the same frames at
 * build quality REFIT, LOW (Morton) and MEDIUM (binned SAH). */
#ifndef RT_BENCH_ANIMATE_H
#define RT_BENCH_ANIMATE_H

#include <stddef.h>
#include <stdint.h>

#include "rt.h"

enum { BENCH_ANIM_MAX_ROWS = 7 };

typedef struct bench_anim_setup {
    int runs;            /* runs: every row plays every frame once per run */
    int frames;          /* frames after frame 0 (the first build, not timed); 0: one per
                            keyframe of the first morphing object (the thesis's method) */
    double fps;          /* frame k shows time k / fps; 0: the object's keyframe rate */
    int threads;         /* our renderer's threads, Embree's device and its tracing pool */
    int width, height;   /* the frame */
    const char *backend; /* ours (NULL: "packet") */
    int embree;          /* 0: leave the Embree rows out */
    void (*progress)(const char *scene, const char *what);
    /* A glTF scene's clip (rt_scene_select_clip), or NULL: its first. A
     * scene with clips and no morphing object plays its clip: every mesh
     * may deform; frames 0: 10, fps 0: 5. */
    const char *animation;
} bench_anim_setup;

/* One engine and policy. Samples are kept per run and frame: index
 * run * frames + k, k = 0 .. frames (k = 0, the first build, is kept but
 * never counted). */
typedef struct bench_anim_row {
    char engine[8];  /* "rtcl" or "embree" */
    char policy[16]; /* rebuild, refit, fast, auto; embree: refit, low, medium */
    int lanes;       /* embree: rays per packet; ours: 0 */
    /* Min and median over the runs of the per-run mean over the frames. */
    double update_ms_min, update_ms_median; /* mesh BVH updates (Embree: its commit) */
    double frame_ms_min, frame_ms_median;   /* the whole frame, update included */
    double trace_ms_min, trace_ms_median;   /* rays and shading alone */
    double sah;       /* mean SAH of the mesh BVHs over the frames (Ct 1, Ci 2); NAN: unknown */
    int images_match; /* ours: 1 when every frame's image is rebuild's, bit for bit; -1:
                         not compared (Embree) */
    double *update, *frame, *trace, *sah_f, *tests; /* samples; tests: box + 2 x tri tests */
    char error[200];                                /* non-empty: the row failed */
} bench_anim_row;

typedef struct bench_anim_result {
    bench_anim_row rows[BENCH_ANIM_MAX_ROWS];
    int n_rows;
    int runs, frames; /* frames counted (frame 0 not among them) */
    double fps;
    uint32_t keyframes, morph_triangles, triangles; /* morphing object, whole frame */
    /* rt_scene_set_time per counted frame (keyframe blending, a glTF clip's
     * posing, skinning and morphing): min and median over the runs of the
     * per-run mean. Not part of any row's frame. */
    double scene_ms_min, scene_ms_median;
    char embree_note[200]; /* when there are no Embree rows: why */
} bench_anim_result;

/* Plays the scene at path: frame k (0 .. frames) at time k / fps, each row
 * on a renderer of its own (ours: a fresh renderer with every mesh's update
 * policy set; Embree: a dynamic scene at the row's quality, updated from our
 * layout of the frame and traced with its widest native packets), rows
 * interleaved frame by frame (every row's frame k before any row's frame
 * k + 1) so that the machine's noise falls on all alike.
 * Returns 1, or 0 with the reason in err (the scene could not be loaded, or
 * nothing in it morphs). Free the result with bench_anim_free. */
int bench_animate(const char *path, const bench_anim_setup *setup, bench_anim_result *res,
                  char *err, size_t err_size);
void bench_anim_free(bench_anim_result *res);

/* Row r's sample of run run, frame k (1 .. frames). */
static inline size_t bench_anim_index(const bench_anim_result *res, int run, int k) {
    return (size_t)run * (size_t)(res->frames + 1) + (size_t)k;
}

/* The "dynamic" member of rtcl bench's JSON object (", \"dynamic\": [...]"
 * and its settings) on stdout; with series, each row's per-frame medians
 * over the runs ("series": {"update_ms", "trace_ms", "frame_ms", "sah"}). */
void bench_anim_print_json(const char *path, const bench_anim_result *res, int series);

/* The same as a table. */
void bench_anim_print_text(const char *path, const bench_anim_result *res);

/* 'rtcl bench --animate': bench_animate on each scene (a file or
 * builtin:NAME) with setup, printing its table or (json 1) one JSON object a
 * line: "scene",
 * "threads", "width", "height" and bench_anim_print_json's members (series:
 * the per-frame medians too). Errors go to stderr after who. Returns 0, or 2
 * when a scene failed. */
int bench_anim_run(const char *const *scenes, int n_scenes, const bench_anim_setup *setup, int json,
                   int series, const char *who);

#endif /* RT_BENCH_ANIMATE_H */
