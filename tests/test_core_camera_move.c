/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_camera_move.c - a camera move touches no geometry.
 *
 * The camera has its own version (rt_camera_set bumps it, not the scene's),
 * so a frame where only the camera moved (a camera path, rt_camera_set,
 * rt_camera_move) rewrites the layout's header and nothing else:
 * - no mesh BVH is updated, the object BVH is not rebuilt, the layout keeps
 *   its generation (the backends keep every array and their wide BVHs) and
 *   only the header's bytes are rewritten; the update stats say so;
 * - every such frame is bit for bit the image of a fresh renderer on a fresh
 *   scene at the same time, on the cpu and packet backends, with instanced
 *   objects and with a kd-tree mesh (whose layout is otherwise made anew);
 * - a frame where the geometry and the camera both changed is made whole,
 *   with the new camera, and camera-only frames after it hold again. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "layout/flat.h"
#include "render/renderer_internal.h"
#include "rt.h"
#include "scene/scene.h"

static const rt_camera_key path[3] = {
    {0.0, {0.3f, 1.6f, 2.8f}, {0, 0.1f, 0}},
    {1.0, {-1.2f, 1.1f, 2.2f}, {0.2f, 0.0f, -0.1f}},
    {2.0, {-2.0f, 2.4f, 0.5f}, {0.1f, 0.3f, 0}},
};

/* A floor (a kd-tree when kd), a sphere-ish fan shown twice (once moved),
 * a light and a camera path. */
static rt_scene *make_scene(int kd) {
    rt_scene *s;
    rt_scene_create(&s);
    rt_material m = rt_material_default();
    uint32_t mat, floor, fan, obj;
    rt_material_add(s, &m, &mat);
    const float fp[12] = {-3, -0.5f, -3, 3, -0.5f, -3, 3, -0.5f, 3, -3, -0.5f, 3};
    const uint32_t fi[6] = {0, 2, 1, 0, 3, 2};
    rt_mesh_create(s, &floor);
    rt_mesh_add_triangles(s, floor, fp, NULL, 4, fi, 2);
    if (kd) rt_mesh_set_accel(s, floor, RT_ACCEL_KD);
    enum { N = 48 };
    float p[3 * (N + 1)];
    uint32_t t[3 * N];
    p[0] = 0.0f, p[1] = 1.0f, p[2] = 0.0f;
    for (int i = 0; i < N; i++) {
        float a = 6.2831853f * (float)i / N;
        p[3 + 3 * i] = 0.6f * cosf(a);
        p[4 + 3 * i] = 0.2f * (float)(i % 3);
        p[5 + 3 * i] = 0.6f * sinf(a);
        t[3 * i] = 0, t[3 * i + 1] = 1 + (uint32_t)i, t[3 * i + 2] = 1 + (uint32_t)((i + 1) % N);
    }
    rt_mesh_create(s, &fan);
    rt_mesh_add_triangles(s, fan, p, NULL, N + 1, t, N);
    rt_object_create(s, mat, &obj);
    rt_object_add_mesh(s, obj, floor);
    rt_object_create(s, mat, &obj);
    rt_object_add_mesh(s, obj, fan);
    rt_object_create(s, mat, &obj);
    rt_object_add_mesh(s, obj, fan);
    const float M[16] = {0, 0, 1, 0.9f, 0, 1, 0, 0.2f, -1, 0, 0, -0.4f, 0, 0, 0, 1};
    rt_object_transform(s, obj, M);
    rt_camera cam = {{0.3f, 1.6f, 2.8f}, {0, 0.1f, 0}, {0, 1, 0}, 60.0f, 48, 32};
    rt_camera_set(s, &cam);
    const float lp[3] = {1, 3, 2}, lc[3] = {1, 1, 1};
    uint32_t light;
    rt_light_add(s, lp, lc, &light);
    CHECK(rt_camera_set_path(s, path, 3) == RT_OK);
    return s;
}

static rt_renderer *new_renderer(const char *backend) {
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = backend;
    o.threads = 2;
    rt_error err;
    rt_renderer *r = NULL;
    CHECK_MSG(rt_renderer_create(&o, &r, &err) == RT_OK, "%s: %s", backend, err.message);
    return r;
}

/* The image a fresh renderer gives of a fresh scene at time t, the camera
 * then moved by (right, up, forward) and the third object moved by dx. */
static rt_framebuffer fresh(const char *backend, int kd, double t, const float move[3], float dx) {
    rt_scene *s = make_scene(kd);
    CHECK(rt_scene_set_time(s, t) == RT_OK);
    if (move) CHECK(rt_camera_move(s, move[0], move[1], move[2]) == RT_OK);
    if (dx != 0.0f) {
        const float T[16] = {1, 0, 0, dx, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        CHECK(rt_object_transform(s, 2, T) == RT_OK);
    }
    rt_renderer *r = new_renderer(backend);
    rt_framebuffer fb;
    memset(&fb, 0, sizeof fb);
    rt_render_options opt = rt_render_options_default();
    CHECK(rt_render(r, s, &opt, &fb) == RT_OK);
    rt_renderer_destroy(r);
    rt_scene_destroy(s);
    return fb;
}

/* The last frame touched no geometry: no mesh update, no object BVH, the
 * layout's generation kept, the header's bytes alone rewritten. */
static void check_camera_only(rt_renderer *r, uint32_t generation, const char *what) {
    rt_update_stats u;
    CHECK(rt_renderer_update_stats(r, &u) == RT_OK);
    CHECK_MSG(u.mesh_count == 0, "%s: %u meshes updated", what, u.mesh_count);
    CHECK_MSG(u.object_bvh_ms == 0.0, "%s: object BVH took %g ms", what, u.object_bvh_ms);
    CHECK_MSG(u.camera_only == 1, "%s: not reported as camera-only", what);
    CHECK_MSG(u.layout_bytes == sizeof(rt_scene_header), "%s: %llu layout bytes rewritten", what,
              (unsigned long long)u.layout_bytes);
    CHECK_MSG(r->accel.layout_generation == generation,
              "%s: the layout was remade or rewritten (generation %u, was %u)", what,
              r->accel.layout_generation, generation);
}

static void check_backend(const char *backend, int kd) {
    char what[96];
    rt_scene *s = make_scene(kd);
    rt_renderer *r = new_renderer(backend);
    rt_render_options opt = rt_render_options_default();
    rt_render_stats st;
    opt.stats = &st;
    rt_framebuffer fb;
    memset(&fb, 0, sizeof fb);
    CHECK(rt_scene_set_time(s, 0.0) == RT_OK);
    CHECK(rt_render(r, s, &opt, &fb) == RT_OK);
    uint32_t generation = r->accel.layout_generation;
    /* Along the camera path: only the camera moves. */
    const double times[] = {0.25, 0.5, 1.0, 1.75, 2.5};
    for (int i = 0; i < 5; i++) {
        snprintf(what, sizeof what, "%s%s: time %g", backend, kd ? " (kd floor)" : "", times[i]);
        CHECK(rt_scene_set_time(s, times[i]) == RT_OK);
        rt_framebuffer_free(&fb);
        CHECK(rt_render(r, s, &opt, &fb) == RT_OK);
        check_camera_only(r, generation, what);
        rt_framebuffer want = fresh(backend, kd, times[i], NULL, 0.0f);
        CHECK_MSG(test_same_fb(&fb, &want), "%s: differs from a fresh render", what);
        rt_framebuffer_free(&want);
    }
    /* rt_camera_set (through rt_camera_move) between frames. */
    const float move[3] = {0.2f, -0.1f, 0.3f};
    CHECK(rt_camera_move(s, move[0], move[1], move[2]) == RT_OK);
    rt_framebuffer_free(&fb);
    CHECK(rt_render(r, s, &opt, &fb) == RT_OK);
    snprintf(what, sizeof what, "%s%s: rt_camera_move", backend, kd ? " (kd floor)" : "");
    check_camera_only(r, generation, what);
    rt_framebuffer want = fresh(backend, kd, 2.5, move, 0.0f);
    CHECK_MSG(test_same_fb(&fb, &want), "%s: differs from a fresh render", what);
    rt_framebuffer_free(&want);
    /* Geometry and camera at once: the layout is brought up to date, with
     * the new camera; then camera-only frames hold again. */
    const float T[16] = {1, 0, 0, 0.25f, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    CHECK(rt_object_transform(s, 2, T) == RT_OK);
    CHECK(rt_scene_set_time(s, 0.5) == RT_OK);
    rt_framebuffer_free(&fb);
    CHECK(rt_render(r, s, &opt, &fb) == RT_OK);
    rt_update_stats u;
    rt_renderer_update_stats(r, &u);
    CHECK_MSG(!u.camera_only && r->accel.layout_generation != generation,
              "%s: a moved object did not update the layout", backend);
    want = fresh(backend, kd, 0.5, NULL, 0.25f);
    CHECK_MSG(test_same_fb(&fb, &want),
              "%s%s: object and camera moved: differs from a fresh render", backend,
              kd ? " (kd floor)" : "");
    rt_framebuffer_free(&want);
    generation = r->accel.layout_generation;
    CHECK(rt_scene_set_time(s, 1.5) == RT_OK);
    rt_framebuffer_free(&fb);
    CHECK(rt_render(r, s, &opt, &fb) == RT_OK);
    snprintf(what, sizeof what, "%s%s: after the object moved", backend, kd ? " (kd floor)" : "");
    check_camera_only(r, generation, what);
    want = fresh(backend, kd, 1.5, NULL, 0.25f);
    CHECK_MSG(test_same_fb(&fb, &want), "%s: differs from a fresh render", what);
    rt_framebuffer_free(&want);
    /* The same time again changes nothing at all. */
    CHECK(rt_scene_set_time(s, 1.5) == RT_OK);
    rt_framebuffer_free(&fb);
    CHECK(rt_render(r, s, &opt, &fb) == RT_OK);
    rt_renderer_update_stats(r, &u);
    CHECK(!u.camera_only && u.layout_bytes == 0 && r->accel.layout_generation == generation);
    rt_framebuffer_free(&fb);
    rt_renderer_destroy(r);
    rt_scene_destroy(s);
}

int main(void) {
    /* A camera change bumps the camera's version, not the scene's. */
    rt_scene *s = make_scene(0);
    uint32_t v = s->version, cv = s->camera_version;
    CHECK(rt_scene_set_time(s, 0.5) == RT_OK);
    CHECK(s->version == v && s->camera_version != cv);
    rt_scene_destroy(s);
    for (int kd = 0; kd < 2; kd++) {
        check_backend("cpu", kd);
        check_backend("packet", kd);
    }
    return TEST_END();
}
