/* SPDX-License-Identifier: Apache-2.0 */
/* view_worker.h - the viewer's render thread. It owns the scene and the
 * renderer while it runs: the window's thread never calls the library, so
 * input and presenting never wait for a frame (a slow backend makes frames
 * late, not the window unresponsive). One job at a time: the window's thread
 * posts a job, the worker renders it and calls 'done'. Results alternate
 * between two slots (by the job number's parity), so the window's thread may
 * post job k+1 and then present result k while k+1 renders: a result stays
 * valid until job k+2 is posted. */
#ifndef RTCL_VIEW_WORKER_H
#define RTCL_VIEW_WORKER_H

#include <stdint.h>

#include "rt.h"
#include "view_timeline.h"

typedef struct view_job {
    long seq;          /* numbers the frames, from 0 */
    rt_camera camera;  /* the full resolution */
    int divisor;       /* >= 1: renders camera.width/divisor x camera.height/divisor */
    double time;       /* scene time, seconds (view_timeline_apply) */
    char backend[288]; /* backend spec for rt_renderer_set_backend */
    rt_aov aov;
    int direct_only;
} view_job;

typedef struct view_result {
    view_job job;
    int ok; /* 0: the frame failed, error says why */
    char error[1024];
    int backend_failed; /* the switch to job.backend failed: backend_error says why */
    char backend_error[1024];
    char backend_spec[288]; /* the spec the renderer now renders with */
    rt_framebuffer fb;      /* valid until the job after next is posted */
    rt_render_stats stats;
    double update_ms;   /* timeline, BVH builds, layout (stats.build_ms) */
    double render_ms;   /* the rest of rt_render: uploads, tracing, shading */
    uint64_t triangles; /* in this frame (the selected keyframes) */
} view_result;

typedef struct view_worker view_worker;

/* Starts the thread. The worker uses renderer, scene and timeline (which
 * must outlive it) only between view_worker_post and its 'done' call.
 * initial_spec is the spec the renderer was created with. done(user) is
 * called from the worker thread after each result is ready. */
rt_status view_worker_start(view_worker **out, rt_renderer *renderer, rt_scene *scene,
                            view_timeline *timeline, const char *initial_spec, void (*done)(void *),
                            void *user);

/* Hands a job to an idle worker; returns 0 (and does nothing) when busy. */
int view_worker_post(view_worker *w, const view_job *job);

/* The finished result not yet taken, or NULL (busy, or taken already).
 * Taking it makes the worker idle; the result stays valid while one more job
 * renders. */
const view_result *view_worker_take(view_worker *w);

/* Waits for the job in flight, if any, and stops and frees the worker. */
void view_worker_stop(view_worker *w);

#endif /* RTCL_VIEW_WORKER_H */
