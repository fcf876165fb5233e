/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_memory.c - memory per triangle (issue 31), counted by
 * rt_renderer_memory: a static mesh's tree is held once (in the layout; its
 * BVH keeps the root node), no build scratch is kept, and the layout is the
 * size its arrays say; the bytes per triangle of a 120,000-triangle height
 * field stay within bounds. When the layout must be made anew (an object
 * added), the parked tree comes back out of the old layout: the image is
 * then bit for bit a fresh renderer's, on the scalar and packet backends. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "layout/flatten.h"
#include "render/renderer_internal.h"
#include "scene/scene.h"

/* A height field of 2 n^2 triangles, one object, a camera and a light. */
static rt_scene *grid(uint32_t n, uint32_t *mesh_out, uint32_t *mat_out) {
    uint32_t nv = (n + 1) * (n + 1), nt = 2 * n * n;
    float *pos = malloc(sizeof *pos * 3 * nv);
    uint32_t *idx = malloc(sizeof *idx * 3 * nt);
    rt_scene *s = NULL;
    CHECK(pos && idx && rt_scene_create(&s) == RT_OK);
    if (!s) return NULL;
    for (uint32_t y = 0; y <= n; y++)
        for (uint32_t x = 0; x <= n; x++) {
            float *p = pos + 3 * (y * (n + 1) + x);
            p[0] = 2.0f * (float)x / (float)n - 1.0f;
            p[2] = 2.0f * (float)y / (float)n - 1.0f;
            p[1] = 0.1f * sinf(9.0f * p[0]) * cosf(7.0f * p[2]);
        }
    for (uint32_t y = 0, k = 0; y < n; y++)
        for (uint32_t x = 0; x < n; x++, k += 6) {
            uint32_t a = y * (n + 1) + x, c = a + n + 1;
            uint32_t q[6] = {a, c, a + 1, a + 1, c, c + 1};
            memcpy(idx + k, q, sizeof q);
        }
    uint32_t obj, light;
    rt_material m = rt_material_default();
    const float lp[3] = {0, 4, 1}, white[3] = {1, 1, 1};
    rt_camera cam = {{0, 1.5f, 2.5f}, {0, 0, 0}, {0, 1, 0}, 60.0f, 48, 32};
    CHECK(rt_mesh_create(s, mesh_out) == RT_OK &&
          rt_mesh_add_triangles(s, *mesh_out, pos, NULL, nv, idx, nt) == RT_OK &&
          rt_material_add(s, &m, mat_out) == RT_OK &&
          rt_object_create(s, *mat_out, &obj) == RT_OK &&
          rt_object_add_mesh(s, obj, *mesh_out) == RT_OK && rt_camera_set(s, &cam) == RT_OK &&
          rt_light_add(s, lp, white, &light) == RT_OK);
    free(pos);
    free(idx);
    return s;
}

static rt_renderer *renderer(const char *backend) {
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = backend;
    o.threads = 2;
    rt_renderer *r = NULL;
    rt_error err;
    CHECK_MSG(rt_renderer_create(&o, &r, &err) == RT_OK, "%s", err.message);
    return r;
}

static int render(rt_renderer *r, rt_scene *s, rt_framebuffer *fb) {
    rt_render_options opt = rt_render_options_default();
    memset(fb, 0, sizeof *fb);
    rt_status st = rt_render(r, s, &opt, fb);
    CHECK_MSG(st == RT_OK, "%s", rt_renderer_error(r));
    return st == RT_OK;
}

static void test_backend(const char *backend) {
    uint32_t mesh, mat;
    rt_scene *s = grid(245, &mesh, &mat); /* 120,050 triangles */
    rt_renderer *r = renderer(backend);
    if (!s || !r) return;
    rt_framebuffer fb, fresh_fb;
    if (!render(r, s, &fb)) return;
    rt_memory_stats m;
    CHECK(rt_renderer_memory(r, s, &m) == RT_OK);
    const double t = (double)m.triangles;
    CHECK_EQ_INT(m.triangles, 120050);
    CHECK_EQ_INT(m.scene, 120050 * 12 + 246 * 246 * 12);
    /* The tree lives in the layout alone: the mesh BVH is its root node. */
    CHECK_MSG(m.mesh_bvhs == sizeof(rt_node), "%s: mesh BVHs hold %llu bytes", backend,
              (unsigned long long)m.mesh_bvhs);
    CHECK_MSG(m.kept == 0, "%s: %llu bytes kept between frames", backend,
              (unsigned long long)m.kept);
    CHECK_EQ_INT(m.layout, rt_flat_bytes(&r->accel.flat));
    /* Nodes (32 bytes, at most 2 per triangle), a triangle (36) and its id. */
    CHECK_MSG(m.layout / t < 2 * 32 + 40 + 1, "%s: layout %.1f bytes per triangle", backend,
              m.layout / t);

    /* A second object: the layout is made anew from the parked tree. */
    uint32_t obj;
    const float move[16] = {1, 0, 0, 0.5f, 0, 1, 0, 0.2f, 0, 0, 1, -0.5f, 0, 0, 0, 1};
    CHECK(rt_object_create(s, mat, &obj) == RT_OK && rt_object_add_mesh(s, obj, mesh) == RT_OK &&
          rt_object_transform(s, obj, move) == RT_OK);
    rt_framebuffer again;
    if (!render(r, s, &again)) return;
    rt_renderer *fresh = renderer(backend);
    if (fresh && render(fresh, s, &fresh_fb)) {
        CHECK_MSG(test_same_fb(&again, &fresh_fb),
                  "%s: the image after the layout was remade from "
                  "the parked tree differs from a fresh renderer's",
                  backend);
        rt_framebuffer_free(&fresh_fb);
    }
    CHECK(rt_renderer_memory(r, s, &m) == RT_OK && m.mesh_bvhs == sizeof(rt_node));
    rt_renderer_destroy(fresh);
    rt_framebuffer_free(&fb);
    rt_framebuffer_free(&again);
    rt_renderer_destroy(r);
    rt_scene_destroy(s);
}

int main(void) {
    test_backend("cpu");
    test_backend("packet");
    return TEST_END();
}
