/* SPDX-License-Identifier: Apache-2.0 */
/* view_worker.c - the render thread. */
#include "view_worker.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"

enum { IDLE, QUEUED, DONE };

struct view_worker {
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t wake;
    int phase; /* IDLE, QUEUED (job waits or renders), DONE (result not taken) */
    int quit;
    view_job job;
    /* Two results, by the job's parity: the window thread presents one
     * while the worker renders the next into the other. */
    view_result results[2];
    rt_renderer *renderer;
    rt_scene *scene;
    view_timeline *timeline;
    char spec[288]; /* the backend spec in use */
    void (*done)(void *);
    void *user;
};

/* Renders w->job into its result slot (called without the lock: the window
 * thread touches neither the job nor that slot while the phase is QUEUED). */
static void render_job(view_worker *w) {
    view_result *r = &w->results[w->job.seq & 1];
    const view_job *job = &w->job;
    rt_framebuffer fb = r->fb; /* reused from frame to frame */
    memset(r, 0, sizeof *r);
    r->fb = fb;
    r->job = *job;
    r->ok = 1;
    if (strcmp(job->backend, w->spec) != 0) {
        if (rt_renderer_set_backend(w->renderer, job->backend) == RT_OK) {
            snprintf(w->spec, sizeof w->spec, "%s", job->backend);
        } else {
            r->backend_failed = 1;
            snprintf(r->backend_error, sizeof r->backend_error, "%s",
                     rt_renderer_error(w->renderer));
        }
    }
    snprintf(r->backend_spec, sizeof r->backend_spec, "%s", w->spec);

    double t0 = cli_now_ms();
    rt_status st = view_timeline_apply(w->timeline, w->scene, job->time);
    rt_camera cam = job->camera;
    int d = job->divisor > 1 ? job->divisor : 1;
    cam.width = cam.width / d > 0 ? cam.width / d : 1;
    cam.height = cam.height / d > 0 ? cam.height / d : 1;
    /* Set only a camera that changed: every rt_camera_set makes the
     * renderer redo the object BVH and the layout (and a device backend
     * upload it again), which a still view must not pay for. */
    rt_camera now;
    if (st == RT_OK && (rt_camera_get(w->scene, &now) != RT_OK || memcmp(&now, &cam, sizeof cam)))
        st = rt_camera_set(w->scene, &cam);
    if (st != RT_OK) {
        r->ok = 0;
        snprintf(r->error, sizeof r->error, "%s", rt_scene_error(w->scene));
        return;
    }
    double t1 = cli_now_ms();
    rt_render_options opt = rt_render_options_default();
    opt.stats = &r->stats;
    opt.aov = job->aov;
    opt.direct_only = job->direct_only;
    opt.reuse_framebuffer = 1;
    st = rt_render(w->renderer, w->scene, &opt, &r->fb);
    double t2 = cli_now_ms();
    if (st != RT_OK) {
        r->ok = 0;
        snprintf(r->error, sizeof r->error, "%s", rt_renderer_error(w->renderer));
        return;
    }
    r->update_ms = (t1 - t0) + r->stats.build_ms;
    r->render_ms = (t2 - t1) - r->stats.build_ms;
    if (r->render_ms < 0) r->render_ms = 0;
    rt_scene_info info;
    rt_scene_describe(w->scene, &info);
    r->triangles = info.triangles;
}

static void *worker_main(void *arg) {
    view_worker *w = arg;
    pthread_mutex_lock(&w->lock);
    for (;;) {
        while (!w->quit && w->phase != QUEUED) pthread_cond_wait(&w->wake, &w->lock);
        if (w->phase != QUEUED) break; /* quit with nothing to do */
        pthread_mutex_unlock(&w->lock);
        render_job(w);
        pthread_mutex_lock(&w->lock);
        w->phase = DONE;
        pthread_cond_broadcast(&w->wake);
        if (w->done) w->done(w->user);
    }
    pthread_mutex_unlock(&w->lock);
    return NULL;
}

rt_status view_worker_start(view_worker **out, rt_renderer *renderer, rt_scene *scene,
                            view_timeline *timeline, const char *initial_spec, void (*done)(void *),
                            void *user) {
    *out = NULL;
    view_worker *w = calloc(1, sizeof *w);
    if (!w) return RT_ERROR_OUT_OF_MEMORY;
    w->renderer = renderer;
    w->scene = scene;
    w->timeline = timeline;
    w->done = done;
    w->user = user;
    snprintf(w->spec, sizeof w->spec, "%s", initial_spec);
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->wake, NULL);
    if (pthread_create(&w->thread, NULL, worker_main, w) != 0) {
        pthread_cond_destroy(&w->wake);
        pthread_mutex_destroy(&w->lock);
        free(w);
        return RT_ERROR_BACKEND;
    }
    *out = w;
    return RT_OK;
}

int view_worker_post(view_worker *w, const view_job *job) {
    pthread_mutex_lock(&w->lock);
    int idle = w->phase == IDLE;
    if (idle) {
        w->job = *job;
        w->phase = QUEUED;
        pthread_cond_broadcast(&w->wake);
    }
    pthread_mutex_unlock(&w->lock);
    return idle;
}

const view_result *view_worker_take(view_worker *w) {
    pthread_mutex_lock(&w->lock);
    int done = w->phase == DONE;
    if (done) w->phase = IDLE;
    pthread_mutex_unlock(&w->lock);
    return done ? &w->results[w->job.seq & 1] : NULL;
}

void view_worker_stop(view_worker *w) {
    if (!w) return;
    pthread_mutex_lock(&w->lock);
    while (w->phase == QUEUED) pthread_cond_wait(&w->wake, &w->lock);
    w->quit = 1;
    pthread_cond_broadcast(&w->wake);
    pthread_mutex_unlock(&w->lock);
    pthread_join(w->thread, NULL);
    rt_framebuffer_free(&w->results[0].fb);
    rt_framebuffer_free(&w->results[1].fb);
    pthread_cond_destroy(&w->wake);
    pthread_mutex_destroy(&w->lock);
    free(w);
}
