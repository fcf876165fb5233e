/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_traverse.c - single- and two-level BVH traversal of
 * kernels/rt_trace.h against brute force over all triangles: identical hits
 * (t bits, u, v, prim, inst) on random rays over the built-in scenes, for every
 * triangle test and two different trees; any-hit agrees on occlusion; ties go
 * to the lower instance, then the lower triangle. The trees come from a small
 * median-split builder in the test, independent of the library's builders. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/scene_boxes.h"
#include "check.h"
#include "layout/flatten.h"
#include "rt_fp_mode.h"
#include "rt_shared.h"
#include "scene/scene.h"
#include "scene/scene_builtin.h"
#include "oracle_util.h"
#include "test_bvh_simple.h"

/* The library's error of the last call a check prints. */
static rt_error lib_err;

/* Builds every mesh BVH and the object BVH with the test builder. */
static int build_flat(const rt_scene *scene, int leaf_size, uint32_t method, rt_flat *flat) {
    rt_bvh *bvhs = calloc(scene->mesh_count, sizeof(rt_bvh));
    rt_bvh top;
    memset(&top, 0, sizeof top);
    for (uint32_t m = 0; m < scene->mesh_count; m++) {
        const rt_mesh_data *md = &scene->meshes[m];
        if (!md->triangle_count) continue;
        rt_aabb *boxes = malloc(sizeof(rt_aabb) * md->triangle_count);
        rt_mesh_tri_boxes(md, boxes);
        simple_bvh_build(boxes, md->triangle_count, leaf_size, &bvhs[m]);
        free(boxes);
    }
    if (scene->object_count) {
        rt_aabb *boxes = malloc(sizeof(rt_aabb) * scene->object_count);
        for (uint32_t o = 0; o < scene->object_count; o++) rt_object_world_box(scene, o, &boxes[o]);
        /* One object per leaf in both trees: an instance's acceptance box is
         * its object BVH leaf's (rt_hit_accepted), which two trees must share
         * for their hits to be comparable bit for bit on every ray. */
        simple_bvh_build(boxes, scene->object_count, 1, &top);
        free(boxes);
    }
    rt_flat_options opt = rt_flat_options_default();
    opt.tri_method = method;
    rt_status st = rt_flatten(scene, bvhs, &top, &opt, flat, &lib_err);
    CHECK_MSG(st == RT_OK, "flatten: %s", lib_err.message);
    for (uint32_t m = 0; m < scene->mesh_count; m++) rt_bvh_free(&bvhs[m]);
    free(bvhs);
    rt_bvh_free(&top);
    return st == RT_OK;
}

/* A random ray: from inside the scene's (grown) bounds towards a random point
 * of them, sometimes with a limited t range. */
static void random_ray(const float lo[3], const float hi[3], rt_ray *r) {
    for (int k = 0; k < 3; k++) {
        float ext = hi[k] - lo[k];
        r->org[k] = lo[k] - 0.25f * ext + 1.5f * ext * oracle_rnd();
        r->dir[k] = (lo[k] + ext * oracle_rnd()) - r->org[k];
    }
    r->tmin = oracle_rnd() < 0.2f ? 0.5f * oracle_rnd() : 0.0f;
    r->tmax = oracle_rnd() < 0.2f ? 0.3f + oracle_rnd() : INFINITY;
}

/* Traces rays through the scene's flattened layout and compares with brute
 * force; returns the mismatches. */
static int compare_scene(const char *name, const rt_scene *scene, int leaf_size, uint32_t method,
                         int rays) {
    rt_flat flat, flat2;
    if (!build_flat(scene, leaf_size, method, &flat)) return 1;
    if (!build_flat(scene, leaf_size == 1 ? 6 : 1, method, &flat2)) return 1;
    rt_scene_view v = rt_flat_view(&flat), v2 = rt_flat_view(&flat2);
    float lo[3], hi[3];
    rt_scene_bounds(scene, lo, hi);
    int bad = 0, hits = 0;
    for (int i = 0; i < rays; i++) {
        rt_ray r;
        if (i % 4 == 3) {
            oracle_vertex_ray(&v, lo, hi, &r);
        } else if (i % 2) {
            random_ray(lo, hi, &r);
        } else { /* camera rays: coherent, many grazing and edge cases */
            int px = (int)(oracle_rnd() * (float)flat.hdr.width),
                py = (int)(oracle_rnd() * (float)flat.hdr.height);
            rt_camera_ray(&flat.hdr, px, py, &r);
        }
        rt_hit_d a, b, c, d, e;
        rt_counters cnt = {0, 0, 0};
        rt_trace(&v, &r, 0, &a, &cnt);
        rt_trace(&v2, &r, 0, &c, &cnt);
        oracle_brute_force(&v, &r, 0, &b);
        hits += a.prim != RT_NO_HIT;
        if (!oracle_same_hit(&a, &b) || !oracle_same_hit(&a, &c)) {
            if (bad < 5)
                fprintf(stderr,
                        "%s (leaf %d, method %u) ray %d: bvh t=%.9g prim %u inst %u, other tree "
                        "t=%.9g prim %u, brute t=%.9g prim %u inst %u\n",
                        name, leaf_size, method, i, a.t, a.prim, a.inst, c.t, c.prim, b.t, b.prim,
                        b.inst);
            bad++;
        }
        int occluded = rt_trace(&v, &r, 1, &d, &cnt);
        oracle_brute_force(&v, &r, 1, &e);
        if (occluded != (e.prim != RT_NO_HIT) || occluded != (a.prim != RT_NO_HIT)) bad++;
    }
    CHECK_MSG(hits > rays / 10, "%s: only %d of %d rays hit", name, hits, rays);
    rt_flat_free(&flat);
    rt_flat_free(&flat2);
    return bad;
}

/* Two objects showing the same triangles: the lower instance wins the tie;
 * within one mesh, duplicate triangles go to the lower index. */
static void tie_cases(void) {
    rt_scene *s;
    rt_scene_create(&s);
    const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t idx[] = {0, 1, 2, 0, 1, 2, 2, 1, 0};
    uint32_t mesh, mat, o0, o1, o2;
    rt_material m = rt_material_default();
    rt_material_add(s, &m, &mat);
    rt_mesh_create(s, &mesh);
    rt_mesh_add_triangles(s, mesh, pos, NULL, 3, idx, 3);
    rt_object_create(s, mat, &o0);
    rt_object_add_mesh(s, o0, mesh);
    rt_object_create(s, mat, &o1);
    rt_object_add_mesh(s, o1, mesh);
    rt_object_create(s, mat, &o2);
    rt_object_add_mesh(s, o2, mesh);
    /* Object 0 moved away; objects 1 and 2 coincide. */
    const float away[16] = {1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    rt_object_transform(s, o0, away);
    rt_scene_commit(s);
    rt_camera cam = {{0.2f, 0.2f, 1}, {0.2f, 0.2f, 0}, {0, 1, 0}, 40, 8, 8};
    rt_camera_set(s, &cam);
    for (int leaf = 1; leaf <= 4; leaf += 3) {
        rt_flat flat;
        if (!build_flat(s, leaf, RT_TRI_WATERTIGHT, &flat)) break;
        rt_scene_view v = rt_flat_view(&flat);
        rt_ray r = {{0.2f, 0.2f, 1}, {0, 0, -1}, 0, INFINITY};
        rt_hit_d h;
        rt_counters c = {0, 0, 0};
        CHECK(rt_trace(&v, &r, 0, &h, &c));
        CHECK_EQ_INT(h.inst, 1);
        CHECK_EQ_INT(h.prim, 0);
        CHECK(h.t == 1.0f);
        CHECK(c.box_tests > 0 && c.tri_tests >= 3);
        rt_flat_free(&flat);
    }
    rt_scene_destroy(s);
}

/* One identity object: the object BVH is skipped. */
static void single_instance(void) {
    rt_scene *s;
    rt_error err;
    CHECK(rt_scene_builtin("cornell", &s, &err) == RT_OK);
    /* Keep only the first object (the room, identity transform). */
    uint32_t objects = s->object_count;
    s->object_count = 1;
    rt_flat flat;
    if (build_flat(s, 2, RT_TRI_WATERTIGHT, &flat)) {
        CHECK(flat.hdr.flags & RT_SCENE_SINGLE);
        CHECK(flat.instances[0].flags & RT_INST_IDENTITY);
        rt_flat_free(&flat);
    }
    CHECK_EQ_INT(compare_scene("cornell-room-only", s, 2, RT_TRI_WATERTIGHT, 2000), 0);
    s->object_count = objects;
    rt_scene_destroy(s);
}

/* The hits of nasty rays with flushed denormals (as the 'flush' policy
 * traces): brute force and both trees must still agree. */
static void flushed(void) {
    if (!rt_fp_can_flush()) {
        printf("flush-to-zero: not settable on this CPU, not tested\n");
        return;
    }
    rt_fp_saved saved = rt_fp_set_flush(1);
    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        rt_scene *s;
        rt_error err;
        CHECK(rt_scene_builtin(rt_builtin_scene_names[i], &s, &err) == RT_OK);
        if (!s) continue;
        CHECK_EQ_INT(compare_scene(rt_builtin_scene_names[i], s, 4, RT_TRI_WATERTIGHT, 2000), 0);
        CHECK_EQ_INT(compare_scene(rt_builtin_scene_names[i], s, 1, RT_TRI_PLUECKER, 1000), 0);
        rt_scene_destroy(s);
    }
    rt_fp_restore(saved);
}

int main(void) {
    tie_cases();
    single_instance();
    flushed();
    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        rt_scene *s;
        rt_error err;
        CHECK(rt_scene_builtin(rt_builtin_scene_names[i], &s, &err) == RT_OK);
        if (!s) continue;
        CHECK_EQ_INT(compare_scene(rt_builtin_scene_names[i], s, 4, RT_TRI_WATERTIGHT, 3000), 0);
        for (uint32_t m = RT_TRI_MOLLER; m <= RT_TRI_BADOUEL; m++)
            CHECK_EQ_INT(compare_scene(rt_builtin_scene_names[i], s, 1, m, 1000), 0);
        rt_scene_destroy(s);
    }
    return TEST_END();
}
