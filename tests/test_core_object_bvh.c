/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_object_bvh.c - the object BVH over transformed objects: a valid tree
 * whose leaf boxes contain every transformed vertex of their object, rebuilt
 * after objects move. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh_validate.h"
#include "check.h"
#include "scene/scene.h"
#include "accel/object_bvh.h"

/* The library's error of the last call a check prints. */
static rt_error lib_err;

enum { OBJECTS = 40 };

/* A small closed mesh: an octahedron scaled by s. */
static uint32_t add_octahedron(rt_scene *scene, float s) {
    const float p[18] = {s, 0, 0, -s, 0, 0, 0, s, 0, 0, -s, 0, 0, 0, s, 0, 0, -s};
    const uint32_t idx[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                              2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    uint32_t mesh;
    CHECK(rt_mesh_create(scene, &mesh) == RT_OK);
    CHECK(rt_mesh_add_triangles(scene, mesh, p, NULL, 6, idx, 8) == RT_OK);
    return mesh;
}

static void rotation_translation(float angle, float tx, float ty, float tz, float m[16]) {
    float c = cosf(angle), s = sinf(angle);
    const float r[16] = {c, 0, s, tx, 0, 1, 0, ty, -s, 0, c, tz, 0, 0, 0, 1};
    memcpy(m, r, sizeof r);
}

static int build_mesh_bvhs(const rt_scene *scene, rt_bvh *bvhs) {
    for (uint32_t m = 0; m < scene->mesh_count; m++) {
        const rt_mesh_data *mesh = &scene->meshes[m];
        rt_aabb *boxes = malloc(sizeof *boxes * mesh->triangle_count);
        for (uint32_t t = 0; t < mesh->triangle_count; t++) {
            float v[9];
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++)
                    v[3 * j + k] = mesh->positions[3 * mesh->indices[3 * t + j] + k];
            boxes[t] = bvh_test_tri_box(v);
        }
        rt_status st = rt_bvh_build(boxes, mesh->triangle_count, NULL, NULL, &bvhs[m], NULL);
        free(boxes);
        if (st != RT_OK) return 0;
    }
    return 1;
}

/* Every vertex of every object, transformed, lies in its leaf's box. */
static void check_object_bvh(const rt_scene *scene, const rt_bvh *bvhs, const char *what) {
    rt_bvh obvh;
    char msg[256] = "";
    rt_status st = rt_object_bvh_build(scene, bvhs, NULL, NULL, &obvh, &lib_err);
    CHECK_MSG(st == RT_OK, "%s: %s", what, lib_err.message);
    if (st != RT_OK) return;
    CHECK_EQ_INT(obvh.prim_count, scene->object_count);
    rt_aabb world[OBJECTS];
    for (uint32_t o = 0; o < scene->object_count; o++) {
        const rt_object_data *obj = &scene->objects[o];
        rt_aabb local;
        memcpy(local.bmin, bvhs[rt_object_shown_mesh(obj)].nodes[0].bmin, sizeof local.bmin);
        memcpy(local.bmax, bvhs[rt_object_shown_mesh(obj)].nodes[0].bmax, sizeof local.bmax);
        world[o] = rt_aabb_transform(&local, obj->transform);
    }
    CHECK_MSG(bvh_validate(&obvh, world, scene->object_count, 1, 0, msg, sizeof msg), "%s: %s",
              what, msg);
    for (uint32_t i = 0; i < obvh.node_count; i++) {
        const rt_node *n = &obvh.nodes[i];
        if (!(n->b & RT_NODE_LEAF_FLAG)) continue;
        for (uint32_t e = n->a; e < n->a + (n->b & RT_NODE_COUNT_MASK); e++) {
            const rt_object_data *obj = &scene->objects[obvh.prim_indices[e]];
            const rt_mesh_data *mesh = &scene->meshes[rt_object_shown_mesh(obj)];
            const float *m = obj->transform;
            for (uint32_t v = 0; v < mesh->vertex_count; v++) {
                const float *p = &mesh->positions[3 * v];
                for (int r = 0; r < 3; r++) {
                    float q =
                        m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
                    /* The corner transform and a vertex transform round the
                     * same way for this exactly representable data; allow
                     * one ulp-scale slack for the general case. */
                    float slack = 1e-5f * (1.0f + fabsf(q));
                    CHECK_MSG(q >= n->bmin[r] - slack && q <= n->bmax[r] + slack,
                              "%s: object %u vertex %u outside its leaf box", what,
                              obvh.prim_indices[e], v);
                }
            }
        }
    }
    rt_bvh_free(&obvh);
}

int main(void) {
    rt_scene *scene;
    CHECK(rt_scene_create(&scene) == RT_OK);
    rt_material mat = rt_material_default();
    uint32_t mat_id, small, big;
    CHECK(rt_material_add(scene, &mat, &mat_id) == RT_OK);
    small = add_octahedron(scene, 1.0f);
    big = add_octahedron(scene, 3.0f);
    for (uint32_t o = 0; o < OBJECTS; o++) {
        uint32_t id;
        CHECK(rt_object_create(scene, mat_id, &id) == RT_OK);
        CHECK(rt_object_add_mesh(scene, id, o % 3 ? small : big) == RT_OK);
        if (o % 4 == 0) CHECK(rt_object_add_mesh(scene, id, small) == RT_OK);
        float m[16];
        rotation_translation(0.3f * (float)o, 10.0f * (float)(o % 7), (float)o, -5.0f * (o % 5), m);
        CHECK(rt_object_transform(scene, id, m) == RT_OK);
    }
    CHECK(rt_scene_commit(scene) == RT_OK);
    rt_bvh bvhs[2];
    CHECK(build_mesh_bvhs(scene, bvhs));
    check_object_bvh(scene, bvhs, "initial placement");

    /* The rotated box is larger than the mesh box: the 8 corners are used. */
    {
        rt_aabb unit = {{-1, -1, -1}, {1, 1, 1}};
        float m[16];
        rotation_translation(0.7853982f, 5, 0, 0, m);
        rt_aabb w = rt_aabb_transform(&unit, m);
        CHECK(w.bmax[0] > 5.0f + 1.4f && w.bmin[0] < 5.0f - 1.4f);
        CHECK(w.bmin[1] == -1.0f && w.bmax[1] == 1.0f);
    }

    /* Move some objects and switch keyframes; rebuild. */
    for (uint32_t o = 0; o < OBJECTS; o += 3) {
        float m[16];
        rotation_translation(1.1f, -20.0f, 3.0f, 7.0f, m);
        CHECK(rt_object_transform(scene, o, m) == RT_OK);
    }
    CHECK(rt_object_select_mesh(scene, 4, 1) == RT_OK);
    CHECK(rt_scene_commit(scene) == RT_OK);
    check_object_bvh(scene, bvhs, "after moving");

    /* A scene without objects gives the empty tree. */
    rt_scene *empty;
    CHECK(rt_scene_create(&empty) == RT_OK);
    rt_bvh t;
    CHECK(rt_object_bvh_build(empty, NULL, NULL, NULL, &t, NULL) == RT_OK);
    CHECK(t.node_count == 0 && t.prim_count == 0);
    rt_scene_destroy(empty);

    rt_bvh_free(&bvhs[0]);
    rt_bvh_free(&bvhs[1]);
    rt_scene_destroy(scene);
    return TEST_END();
}
