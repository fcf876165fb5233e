/* SPDX-License-Identifier: Apache-2.0 */
/* test_render_stats.c - rt_render_stats tells the truth (issue 30, item 7):
 * the CPU backends (the oracle and the packet tracer, which gives its bits)
 * report exact = 1, the maths profile "ieee" and the denormal mode asked
 * for; threads is the real count on every backend: the CPU pool's size as
 * configured, and on the device backends a positive count (on Mesa's
 * lavapipe, llvmpipe's threads from LP_NUM_THREADS). Device backends that
 * this build or machine lacks are skipped with the reason. */
#include <stdlib.h>
#include <string.h>

#include "check.h"

static rt_scene *small_cornell(void) {
    rt_scene *scene = NULL;
    rt_error err;
    if (rt_scene_builtin("cornell", &scene, &err) != RT_OK) {
        fprintf(stderr, "builtin:cornell: %s\n", err.message);
        return NULL;
    }
    rt_camera cam;
    rt_camera_get(scene, &cam);
    cam.width = 24;
    cam.height = 16;
    rt_camera_set(scene, &cam);
    return scene;
}

/* Renders one frame on backend with threads and denormals; 0 when the
 * backend cannot run here (the reason printed). */
static int frame_stats(rt_scene *scene, const char *backend, int threads, rt_denormals denormals,
                       rt_render_stats *stats) {
    rt_renderer_options ro = rt_renderer_options_default();
    ro.backend = backend;
    ro.threads = threads;
    ro.denormals = denormals;
    rt_renderer *r = NULL;
    rt_error err;
    if (rt_renderer_create(&ro, &r, &err) != RT_OK) {
        printf("skipped backend %s: %s\n", backend, err.message);
        return 0;
    }
    rt_render_options opt = rt_render_options_default();
    opt.stats = stats;
    rt_framebuffer fb = {0};
    rt_status st = rt_render(r, scene, &opt, &fb);
    if (st != RT_OK) { /* no device here: skipped; any other failure fails */
        printf("%s backend %s: %s\n", st == RT_ERROR_UNSUPPORTED ? "skipped" : "FAILED", backend,
               rt_renderer_error(r));
        CHECK(st == RT_ERROR_UNSUPPORTED);
        rt_renderer_destroy(r);
        return 0;
    }
    rt_framebuffer_free(&fb);
    rt_renderer_destroy(r);
    return 1;
}

int main(void) {
    rt_scene *scene = small_cornell();
    CHECK(scene != NULL);
    if (!scene) return TEST_END();

    const char *cpu_backends[] = {"cpu", "packet"};
    for (int b = 0; b < 2; b++)
        for (int flush = 0; flush < 2; flush++) {
            rt_render_stats s;
            if (!frame_stats(scene, cpu_backends[b], 3, flush ? RT_DENORMALS_FLUSH : 0, &s))
                continue; /* flush on a CPU that cannot set it */
            CHECK_MSG(s.exact == 1, "%s: exact %d", cpu_backends[b], s.exact);
            CHECK_MSG(s.math_profile && !strcmp(s.math_profile, "ieee"), "%s: profile %s",
                      cpu_backends[b], s.math_profile ? s.math_profile : "NULL");
            CHECK_MSG(s.denormals && !strcmp(s.denormals, flush ? "flush" : "preserve"),
                      "%s: denormals %s", cpu_backends[b], s.denormals ? s.denormals : "NULL");
            CHECK_MSG(s.threads == 3, "%s: %d threads, 3 asked for", cpu_backends[b], s.threads);
            CHECK(s.backend && !strcmp(s.backend, cpu_backends[b]));
        }

    /* The device backends: a maths profile, and a positive thread count. */
    setenv("LP_NUM_THREADS", "3", 1); /* lavapipe reads it when its device opens */
    const char *device_backends[] = {"opencl", "vulkan"};
    for (int b = 0; b < 2; b++) {
        rt_render_stats s;
        if (!frame_stats(scene, device_backends[b], 0, RT_DENORMALS_PRESERVE, &s)) continue;
        printf("%s on %s: %d threads, %s, exact %d\n", device_backends[b], s.device, s.threads,
               s.math_profile ? s.math_profile : "NULL", s.exact);
        CHECK_MSG(s.threads > 0, "%s: %d threads", device_backends[b], s.threads);
        CHECK(s.math_profile &&
              (!strcmp(s.math_profile, "native") || !strcmp(s.math_profile, "portable")));
        CHECK(s.denormals && !strcmp(s.denormals, "preserve"));
        if (b == 1 && strstr(s.device, "llvmpipe"))
            CHECK_MSG(s.threads == 3, "vulkan on lavapipe: %d threads, LP_NUM_THREADS=3",
                      s.threads);
    }
    rt_scene_destroy(scene);
    return TEST_END();
}
