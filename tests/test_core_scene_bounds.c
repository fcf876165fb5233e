/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_scene_bounds.c - rt_scene_bounds' shortcut for objects with the
 * identity transform gives the same floats, bit for bit, as transforming each
 * vertex with the matrix (the general path, written out here as the scene
 * code had it): signed zeros, subnormals, huge and tiny values. The bounds
 * set the default camera of bare OBJ files, so they must not move. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "scene/scene.h"

/* The bounds by the general path: every used vertex through the matrix. */
static void reference_bounds(const rt_scene *s, float bmin[3], float bmax[3]) {
    for (int k = 0; k < 3; k++) bmin[k] = INFINITY, bmax[k] = -INFINITY;
    for (uint32_t i = 0; i < s->object_count; i++) {
        const rt_object_data *o = &s->objects[i];
        const rt_mesh_data *m = &s->meshes[o->meshes[o->selected]];
        const float *x = o->transform;
        for (uint64_t t = 0; t < 3 * (uint64_t)m->triangle_count; t++) {
            const float *v = m->positions + 3 * (size_t)m->indices[t];
            for (int r = 0; r < 3; r++) {
                float p =
                    x[r * 4 + 0] * v[0] + x[r * 4 + 1] * v[1] + x[r * 4 + 2] * v[2] + x[r * 4 + 3];
                if (p < bmin[r]) bmin[r] = p;
                if (p > bmax[r]) bmax[r] = p;
            }
        }
    }
}

static void check_same(const rt_scene *s, const char *what) {
    float lo[3], hi[3], rlo[3], rhi[3];
    CHECK(rt_scene_bounds(s, lo, hi));
    reference_bounds(s, rlo, rhi);
    CHECK_MSG(memcmp(lo, rlo, sizeof lo) == 0 && memcmp(hi, rhi, sizeof hi) == 0,
              "%s: (%a %a %a)..(%a %a %a), expected (%a %a %a)..(%a %a %a)", what, lo[0], lo[1],
              lo[2], hi[0], hi[1], hi[2], rlo[0], rlo[1], rlo[2], rhi[0], rhi[1], rhi[2]);
}

int main(void) {
    /* Vertices whose coordinates are zeros of both signs first, so that the
     * zero's sign is what the bounds keep, then other awkward values. */
    const float v[][3] = {{-0.0f, -0.0f, -0.0f},       {0.0f, -0.0f, 0.0f},
                          {-0.0f, 0.0f, -0.0f},        {FLT_TRUE_MIN, -FLT_TRUE_MIN, 0.0f},
                          {-FLT_MAX, FLT_MAX, 1e-30f}, {3.0f, -2.5f, -0.0f}};
    const uint32_t sets[][3] = {{0, 1, 2}, {0, 0, 0}, {2, 2, 2}, {3, 4, 5}, {0, 3, 5}};
    for (size_t n = 0; n < sizeof sets / sizeof sets[0]; n++) {
        rt_scene *s;
        CHECK(rt_scene_create(&s) == RT_OK);
        uint32_t mesh, mat, obj, obj2;
        rt_material white = rt_material_default();
        CHECK(rt_mesh_create(s, &mesh) == RT_OK);
        CHECK(rt_mesh_add_triangles(s, mesh, &v[0][0], NULL, 6, sets[n], 1) == RT_OK);
        CHECK(rt_material_add(s, &white, &mat) == RT_OK);
        CHECK(rt_object_create(s, mat, &obj) == RT_OK);
        CHECK(rt_object_add_mesh(s, obj, mesh) == RT_OK);
        check_same(s, "identity");
        /* A second object, moved: the general path beside the shortcut. */
        const float move[16] = {0, -1, 0, 0.5f, 1, 0, 0, -0.0f, 0, 0, 1, 2, 0, 0, 0, 1};
        CHECK(rt_object_create(s, mat, &obj2) == RT_OK);
        CHECK(rt_object_add_mesh(s, obj2, mesh) == RT_OK);
        CHECK(rt_object_transform(s, obj2, move) == RT_OK);
        CHECK(rt_scene_commit(s) == RT_OK);
        check_same(s, "identity and a moved object");
        rt_scene_destroy(s);
    }
    return TEST_END();
}
