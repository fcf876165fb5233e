/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_threads.c - a renderer's frames on several threads after scene
 * edits give the bits of one thread: the cpu and packet backends on 4 (and
 * 7) workers against the cpu backend on 1, and packet on 5 against cpu on 1
 * with the flush-to-zero policy, frame after frame, while the
 * scene changes between frames (a queued transform, a keyframe switch,
 * triangles added to a mesh, which rebuilds its BVH on the pool's threads)
 * and rays are traced between renders.
 *
 * In the ThreadSanitizer build (RT_TSAN=ON, .ci/run) this is the test of the
 * renderer's threads as a user drives them: the thread pool hands out jobs,
 * the builders and both backends' tiles share the caches. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "oracle_util.h"
#include "rt.h"

enum { W = 67, H = 45, FRAMES = 6 };

static int render(rt_renderer *r, rt_scene *s, rt_framebuffer *fb) {
    rt_status st = rt_render(r, s, NULL, fb);
    CHECK_MSG(st == RT_OK, "%s: %s", rt_renderer_backend(r), rt_renderer_error(r));
    return st == RT_OK;
}

static int same(const rt_framebuffer *a, const rt_framebuffer *b) {
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           memcmp(a->pixels, b->pixels,
                  sizeof(float) * (size_t)a->width * a->height * a->channels) == 0;
}

/* The edit before frame f: the column object turns, switches keyframe, and
 * a small mesh grows (a new BVH for it). */
static void edit(rt_scene *s, int f, uint32_t column, uint32_t grow_mesh) {
    const float c = cosf(0.3f), sn = sinf(0.3f);
    const float turn[16] = {c, 0, sn, 0, 0, 1, 0, 0, -sn, 0, c, 0, 0, 0, 0, 1};
    CHECK(rt_object_transform(s, column, turn) == RT_OK);
    CHECK(rt_object_select_mesh(s, column, (uint32_t)f % 4) == RT_OK);
    const float y = 0.1f * (float)f;
    const float p[9] = {-1.0f, y, -0.5f, 1.0f, y, -0.5f, 0.0f, y + 0.6f, -0.4f};
    const uint32_t t[3] = {0, 1, 2};
    CHECK(rt_mesh_add_triangles(s, grow_mesh, p, NULL, 3, t, 1) == RT_OK);
}

static void check_frames(void) {
    rt_renderer *one = test_renderer("cpu", 1), *cpu4 = test_renderer("cpu", 4),
                *cpu7 = test_renderer("cpu", 7), *pk4 = test_renderer("packet", 4);
    /* The flush-to-zero policy: its workers switch the FP mode per job. */
    rt_renderer_options fo = rt_renderer_options_default();
    fo.denormals = RT_DENORMALS_FLUSH;
    fo.threads = 1;
    rt_error err;
    rt_renderer *one_flush = test_renderer_with(&fo, &err);
    fo.backend = "packet";
    fo.threads = 5;
    rt_renderer *pk5_flush = test_renderer_with(&fo, &err);
    CHECK_MSG(one_flush && pk5_flush, "flushing renderers: %s", err.message);
    if (!one || !cpu4 || !cpu7 || !pk4 || !one_flush || !pk5_flush) return;
    rt_scene *s = test_builtin_scene("cornell", W, H);
    if (!s) return;
    /* The column (the object with keyframes) and a new mesh that grows. */
    uint32_t column = 3, grow_mesh, grow_obj, mat;
    rt_material m = rt_material_default();
    CHECK(rt_material_add(s, &m, &mat) == RT_OK);
    CHECK(rt_mesh_create(s, &grow_mesh) == RT_OK);
    edit(s, 0, column, grow_mesh);
    CHECK(rt_object_create(s, mat, &grow_obj) == RT_OK);
    CHECK(rt_object_add_mesh(s, grow_obj, grow_mesh) == RT_OK);

    rt_renderer *many[3] = {cpu4, cpu7, pk4};
    rt_framebuffer prev = {0, 0, 0, NULL};
    for (int f = 0; f < FRAMES; f++) {
        if (f) edit(s, f, column, grow_mesh);
        rt_framebuffer ref;
        if (!render(one, s, &ref)) break;
        /* The edits show: no two frames alike. */
        if (prev.pixels) CHECK_MSG(!same(&prev, &ref), "frame %d looks like frame %d", f, f - 1);
        for (int k = 0; k < 3; k++) {
            rt_framebuffer fb;
            if (!render(many[k], s, &fb)) continue;
            CHECK_MSG(same(&ref, &fb), "frame %d: %s on many threads differs from cpu on 1", f,
                      rt_renderer_backend(many[k]));
            rt_framebuffer_free(&fb);
        }
        rt_framebuffer_free(&prev);
        prev = ref;
        rt_framebuffer flush_one, flush_many;
        if (render(one_flush, s, &flush_one)) {
            if (render(pk5_flush, s, &flush_many)) {
                CHECK_MSG(same(&flush_one, &flush_many),
                          "frame %d: packet on 5 threads differs from cpu on 1 (flush)", f);
                rt_framebuffer_free(&flush_many);
            }
            rt_framebuffer_free(&flush_one);
        }

        /* Rays between frames, on the same renderers. */
        rt_ray rays[300];
        rt_hit want[300], got[300];
        oracle_rng = 11u + (uint32_t)f;
        for (int i = 0; i < 300; i++) {
            rt_ray *r = &rays[i];
            r->org[0] = 3.0f * (oracle_rnd() - 0.5f);
            r->org[1] = 1.8f * oracle_rnd();
            r->org[2] = 2.0f * (oracle_rnd() - 0.5f);
            for (int k = 0; k < 3; k++) r->dir[k] = oracle_rnd() - 0.5f;
            r->tmin = 0.0f;
            r->tmax = INFINITY;
        }
        CHECK(rt_trace_rays(one, s, rays, 300, want, NULL) == RT_OK);
        for (int k = 0; k < 3; k++) {
            CHECK(rt_trace_rays(many[k], s, rays, 300, got, NULL) == RT_OK);
            CHECK_MSG(memcmp(want, got, sizeof want) == 0, "frame %d: %s rays differ", f,
                      rt_renderer_backend(many[k]));
        }
    }
    rt_framebuffer_free(&prev);
    rt_scene_destroy(s);
}

int main(void) {
    check_frames();
    return TEST_END();
}
