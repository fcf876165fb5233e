/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_scene.c - the scene model's operations and their validation. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "scene/scene.h"
#include "scene/scene_default_view.h"

static void test_mesh_and_objects(void) {
    rt_scene *s;
    CHECK(rt_scene_create(&s) == RT_OK);
    uint32_t mesh, mat, obj, light;
    CHECK(rt_mesh_create(s, &mesh) == RT_OK);
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t idx[3] = {0, 1, 2};
    CHECK(rt_mesh_add_triangles(s, mesh, pos, NULL, 3, idx, 1) == RT_OK);
    CHECK(rt_mesh_add_triangles(s, mesh, pos, NULL, 3, idx, 1) == RT_OK);
    CHECK_EQ_INT(s->meshes[mesh].triangle_count, 2);
    CHECK_EQ_INT(s->meshes[mesh].indices[3], 3); /* second block is offset */

    const uint32_t bad_idx[3] = {0, 1, 3};
    CHECK(rt_mesh_add_triangles(s, mesh, pos, NULL, 3, bad_idx, 1) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "refers to vertex 3 of 3");
    CHECK_EQ_INT(s->meshes[mesh].triangle_count, 2); /* nothing half-added */

    float nan_pos[9] = {0, 0, 0, 1, 0, 0, 0, NAN, 0};
    CHECK(rt_mesh_add_triangles(s, mesh, nan_pos, NULL, 3, idx, 1) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "NaN");
    CHECK(rt_mesh_add_triangles(s, mesh, pos, pos, 3, idx, 1) == RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_mesh_add_triangles(s, 7, pos, NULL, 3, idx, 1) == RT_ERROR_INVALID_ARGUMENT);

    rt_material m = rt_material_default();
    CHECK(rt_object_create(s, 0, &obj) == RT_ERROR_INVALID_ARGUMENT); /* no material yet */
    CHECK(rt_material_add(s, &m, &mat) == RT_OK);
    m.ior = 0.0f;
    CHECK(rt_material_add(s, &m, &mat) == RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_object_create(s, 0, &obj) == RT_OK);
    CHECK(rt_object_add_mesh(s, obj, mesh) == RT_OK);
    CHECK(rt_object_add_mesh(s, obj, 5) == RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_object_select_mesh(s, obj, 1) == RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_object_select_mesh(s, obj, 0) == RT_OK);
    CHECK_EQ_INT(rt_scene_triangle_count(s), 2);

    const float p[3] = {1, 2, 3}, c[3] = {1, 1, 1};
    CHECK(rt_light_add(s, p, c, &light) == RT_OK);
    const float inf_p[3] = {1, INFINITY, 3};
    CHECK(rt_light_add(s, inf_p, c, &light) == RT_ERROR_INVALID_ARGUMENT);
    rt_scene_destroy(s);
}

static void test_queued_transforms(void) {
    rt_scene *s;
    rt_scene_create(&s);
    uint32_t mat, obj;
    rt_material m = rt_material_default();
    rt_material_add(s, &m, &mat);
    rt_object_create(s, mat, &obj);
    float t1[16], t2[16];
    rt_mat4_identity(t1);
    rt_mat4_identity(t2);
    t1[3] = 1.0f; /* translate x by 1 */
    t2[7] = 2.0f; /* translate y by 2 */
    CHECK(rt_object_transform(s, obj, t1) == RT_OK);
    CHECK(rt_object_transform(s, obj, t2) == RT_OK);
    CHECK(s->objects[obj].transform[3] == 0.0f); /* queued, not applied */
    CHECK(rt_scene_commit(s) == RT_OK);
    CHECK(s->objects[obj].transform[3] == 1.0f);
    CHECK(s->objects[obj].transform[7] == 2.0f);
    float singular[16] = {0};
    singular[15] = 1.0f;
    CHECK(rt_object_transform(s, obj, singular) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "singular");
    float projective[16];
    rt_mat4_identity(projective);
    projective[14] = 0.5f;
    CHECK(rt_object_transform(s, obj, projective) == RT_ERROR_INVALID_ARGUMENT);
    rt_scene_destroy(s);
}

static void test_camera(void) {
    rt_scene *s;
    rt_scene_create(&s);
    rt_camera c = {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 60.0f, 64, 32};
    CHECK(rt_camera_set(s, &c) == RT_OK);
    rt_camera bad = c;
    bad.up[0] = 0, bad.up[1] = 0, bad.up[2] = 1; /* parallel to the view */
    CHECK(rt_camera_set(s, &bad) == RT_ERROR_INVALID_ARGUMENT);
    bad = c;
    bad.hfov_degrees = 180.0f;
    CHECK(rt_camera_set(s, &bad) == RT_ERROR_INVALID_ARGUMENT);
    /* Up exactly opposite the view direction: the float check saw a tiny
     * side vector, the layout's double frame an exact zero (NaN rays). */
    rt_camera opp = {{0, 0, 0}, {-0.5f, -1.5f, -2.79999995f}, {1, 3, 5.5999999f}, 60.0f, 64, 32};
    CHECK(rt_camera_set(s, &opp) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "parallel to the view direction");
    /* Any camera accepted gives a finite frame, as the layout computes it:
     * up a multiple of the view direction, or nearly so. */
    uint32_t seed = 99;
    int accepted = 0, refused = 0;
    for (int i = 0; i < 20000; i++) {
        float q[7];
        for (int k = 0; k < 7; k++) {
            seed = seed * 1664525u + 1013904223u;
            q[k] = (float)(seed >> 8) / 16777216.0f * 20.0f - 10.0f;
        }
        rt_camera cc = c;
        for (int k = 0; k < 3; k++) {
            cc.position[k] = q[k];
            cc.look_at[k] = q[k] + q[k + 3];
            cc.up[k] = q[6] * q[k + 3] * (i % 2 ? 1.0f : 1.0f + 1e-7f * (float)k);
        }
        if (rt_camera_set(s, &cc) != RT_OK) {
            refused++;
            continue;
        }
        accepted++;
        double f[3], r[3], u[3];
        CHECK(rt_camera_frame_d(&cc, f, r, u));
        int finite = 1;
        for (int k = 0; k < 3; k++) finite &= isfinite(f[k]) && isfinite(r[k]) && isfinite(u[k]);
        CHECK_MSG(finite, "camera %d accepted with a non-finite frame", i);
    }
    CHECK(refused > 0);
    /* issue 31: a camera 1e38 from its look-at point is no "look-at point
     * equals the position" (the float length overflowed): it is accepted,
     * with a finite frame; equal points and a length that underflows are
     * refused, each with its own reason and the values. */
    rt_camera far = {{1e38f, 0, 0}, {0, 0, 0}, {0, 1, 0}, 60.0f, 64, 32};
    CHECK_MSG(rt_camera_set(s, &far) == RT_OK, "%s", rt_scene_error(s));
    rt_camera same = {{1, 2, 3}, {1, 2, 3}, {0, 1, 0}, 60.0f, 64, 32};
    CHECK(rt_camera_set(s, &same) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "the look-at point equals the position (1, 2, 3)");
    rt_camera tiny = {{0, 0, 0}, {1e-30f, 0, 0}, {0, 1, 0}, 60.0f, 64, 32};
    CHECK(rt_camera_set(s, &tiny) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "is too short for a float");
    CHECK(rt_camera_set(s, &c) == RT_OK);
    CHECK(rt_camera_move(s, 0, 0, 1) == RT_OK); /* forward is -z */
    rt_camera got;
    rt_camera_get(s, &got);
    CHECK(fabsf(got.position[2] - 4.0f) < 1e-6f && fabsf(got.look_at[2] + 1.0f) < 1e-6f);
    CHECK(rt_camera_rotate(s, 90.0f, 0.0f) == RT_OK); /* now looks along -x */
    rt_camera_get(s, &got);
    CHECK(got.look_at[0] - got.position[0] < -4.9f);
    rt_scene_destroy(s);
}

static void test_default_view(void) {
    rt_scene *s;
    rt_scene_create(&s);
    CHECK(rt_scene_apply_default_view(s, 0, 0) == RT_ERROR_INVALID_ARGUMENT); /* empty */
    uint32_t mesh, mat, obj;
    rt_mesh_create(s, &mesh);
    const float pos[9] = {0, 0, 0, 2, 0, 0, 0, 2, 0};
    const uint32_t idx[3] = {0, 1, 2};
    rt_mesh_add_triangles(s, mesh, pos, NULL, 3, idx, 1);
    rt_material m = rt_material_default();
    rt_material_add(s, &m, &mat);
    rt_object_create(s, mat, &obj);
    rt_object_add_mesh(s, obj, mesh);
    CHECK(rt_scene_apply_default_view(s, 0, 0) == RT_OK);
    CHECK_EQ_INT(s->camera.width, 1024);
    CHECK_EQ_INT(s->camera.height, 576);
    CHECK(s->camera.look_at[0] == 1.0f && s->camera.look_at[1] == 1.0f);
    CHECK_EQ_INT(s->light_count, 1);
    /* eye = c + normalize(0.3, 0.35, 1) * 0.9 d, d = |(2,2,0)| */
    float d = sqrtf(8.0f), n = sqrtf(0.09f + 0.1225f + 1.0f);
    CHECK(fabsf(s->camera.position[2] - 1.0f / n * 0.9f * d) < 1e-5f);
    /* issue 31: an object scaled by 1e30 (an extent whose square overflows
     * a float) still gets a default view, not "camera: vectors must be
     * finite"; bounds whose extent is no float are refused as such. */
    const float huge[16] = {1e30f, 0, 0, 0, 0, 1e30f, 0, 0, 0, 0, 1e30f, 0, 0, 0, 0, 1};
    CHECK(rt_object_transform(s, obj, huge) == RT_OK && rt_scene_commit(s) == RT_OK);
    CHECK_MSG(rt_scene_apply_default_view(s, 0, 0) == RT_OK, "%s", rt_scene_error(s));
    CHECK(isfinite(s->camera.position[0]) && s->camera.position[2] > 1e30f);
    const float beyond[16] = {3e8f, 0, 0, 0, 0, 3e8f, 0, 0, 0, 0, 3e8f, 0, 0, 0, 0, 1};
    const float away[16] = {1, 0, 0, -3e38f, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    uint32_t obj2;
    rt_object_create(s, mat, &obj2);
    rt_object_add_mesh(s, obj2, mesh);
    CHECK(rt_object_transform(s, obj, beyond) == RT_OK &&
          rt_object_transform(s, obj2, away) == RT_OK && rt_scene_commit(s) == RT_OK);
    CHECK(rt_scene_apply_default_view(s, 0, 0) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s),
                   "are too large for a default camera: give the scene a camera");
    rt_scene_destroy(s);
}

/* The documented limits (docs/ROBUSTNESS.md, "Limits"), each refused before
 * anything is read or allocated: the arrays passed are far shorter than the
 * counts claim, so a read would be caught (AddressSanitizer) or crash. */
static void test_limits(void) {
    rt_scene *s;
    CHECK(rt_scene_create(&s) == RT_OK);
    uint32_t mesh;
    CHECK(rt_mesh_create(s, &mesh) == RT_OK);
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t idx[3] = {0, 1, 2};
    CHECK(rt_mesh_add_triangles(s, mesh, pos, NULL, 3, idx, (uint32_t)RT_MAX_MESH_TRIANGLES + 1) ==
          RT_ERROR_UNSUPPORTED);
    CHECK_CONTAINS(rt_scene_error(s), "exceed the limit of 268435456 triangles per mesh");
    CHECK(rt_mesh_add_triangles(s, mesh, pos, NULL, (uint32_t)RT_MAX_MESH_VERTICES + 1, idx, 1) ==
          RT_ERROR_UNSUPPORTED);
    CHECK_CONTAINS(rt_scene_error(s), "exceed the limit of 268435456 vertices per mesh");
    CHECK(rt_mesh_add_triangles(s, mesh, pos, NULL, 3, idx, 1) == RT_OK); /* within: fine */
    /* Image size: a side beyond RT_MAX_IMAGE_SIDE is refused at the camera,
     * before any framebuffer exists; the largest accepted one fits size_t. */
    rt_camera c = {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 60.0f, 100000, 100000};
    CHECK(rt_camera_set(s, &c) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "outside 1..32768 (the image size limit)");
    c.width = RT_MAX_IMAGE_SIDE + 1, c.height = 16;
    CHECK(rt_camera_set(s, &c) == RT_ERROR_INVALID_ARGUMENT);
    c.width = c.height = RT_MAX_IMAGE_SIDE;
    CHECK(rt_camera_set(s, &c) == RT_OK);
    CHECK((uint64_t)c.width * (uint64_t)c.height * 4u * sizeof(float) <= (uint64_t)SIZE_MAX);
    rt_scene_destroy(s);
}

int main(void) {
    test_mesh_and_objects();
    test_queued_transforms();
    test_camera();
    test_limits();
    test_default_view();
    return TEST_END();
}
