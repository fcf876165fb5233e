/* SPDX-License-Identifier: Apache-2.0 */
/* test_gltf_shared.c - the shared glTF files (../shared/scenes) evaluated at
 * the times their OBJ frames were baked at give the baked positions.
 *
 * BrainStem.glb, clip 0 (animation_0) at t = 0.2 k s, against
 * brainstem_k.obj; RobotExpressive.glb, clip Walking at t = k * 0.958333 /
 * 10 s, against robot_walk_k.obj (SOURCES.md: morph targets not applied;
 * the robot has none animated in Walking). Every frame's vertices, in the
 * loader's order (the scene's instances, parents first, their primitives'
 * vertices, each under its object's transform: rigid parts are objects
 * moved by their nodes), must match the OBJ's within 1e-5 of the bounding-box diagonal
 * (float32 rounding of an independent evaluation). And the scene's threads
 * change nothing: both files on 1 and on 4 threads (rt_scene_set_threads)
 * give the same vertices, normals, transforms and versions, bit for bit, at
 * every frame of every clip and between frames. Skips without the shared
 * scenes or without the glTF module. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "scene/scene.h"

/* Every object's world-space positions (its mesh's under its transform),
 * in object order. */
static float *gather(const rt_scene *s, uint32_t *count) {
    uint64_t n = 0;
    for (uint32_t o = 0; o < s->object_count; o++)
        n += s->meshes[rt_object_shown_mesh(&s->objects[o])].vertex_count;
    float *p = malloc(3 * sizeof(float) * (n ? n : 1));
    if (!p) return NULL;
    uint64_t at = 0;
    for (uint32_t o = 0; o < s->object_count; o++) {
        const rt_mesh_data *m = &s->meshes[rt_object_shown_mesh(&s->objects[o])];
        const float *t = s->objects[o].transform;
        for (uint32_t v = 0; v < m->vertex_count; v++, at++) {
            const float *q = m->positions + 3 * (size_t)v;
            for (int r = 0; r < 3; r++)
                p[3 * at + r] = (float)((double)t[4 * r] * q[0] + (double)t[4 * r + 1] * q[1] +
                                        (double)t[4 * r + 2] * q[2] + (double)t[4 * r + 3]);
        }
    }
    *count = (uint32_t)n;
    return p;
}

static double diagonal(const float *p, uint32_t n) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < n; v++)
        for (int k = 0; k < 3; k++) {
            if (p[3 * v + k] < lo[k]) lo[k] = p[3 * v + k];
            if (p[3 * v + k] > hi[k]) hi[k] = p[3 * v + k];
        }
    double d = 0;
    for (int k = 0; k < 3; k++) d += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return sqrt(d);
}

static int compare(const char *dir, const char *glb, const char *clip, const char *stem,
                   double step) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, glb);
    rt_scene *g = NULL;
    rt_error err;
    if (rt_scene_load(path, &g, &err) != RT_OK) {
        if (err.status == RT_ERROR_UNSUPPORTED && strstr(err.message, "glTF")) {
            printf("skipped: %s\n", err.message);
            return 77;
        }
        CHECK_MSG(0, "%s", err.message);
        return 1;
    }
    CHECK(rt_scene_is_animated(g));
    if (clip) CHECK_MSG(rt_scene_select_clip(g, clip) == RT_OK, "%s", rt_scene_error(g));
    for (int k = 0; k < 10; k++) {
        snprintf(path, sizeof path, "%s/%s_%02d.obj", dir, stem, k);
        rt_scene *o = NULL;
        if (rt_scene_load(path, &o, &err) != RT_OK) {
            CHECK_MSG(0, "%s", err.message);
            break;
        }
        CHECK(rt_scene_set_time(g, step * k) == RT_OK);
        uint32_t ng = 0, no = 0;
        float *pg = gather(g, &ng), *po = gather(o, &no);
        CHECK_EQ_INT(ng, no);
        if (pg && po && ng == no) {
            double tol = 1e-5 * diagonal(po, no), worst = 0;
            uint32_t at = 0;
            for (uint32_t v = 0; v < 3 * no; v++) {
                double e = fabs((double)pg[v] - po[v]);
                if (e > worst) worst = e, at = v / 3;
            }
            CHECK_MSG(worst <= tol, "%s frame %d: vertex %u off by %g (tolerance %g)", stem, k, at,
                      worst, tol);
            printf("%s frame %d (t = %.6f s): %u vertices, largest difference %.3g (%.3g of the "
                   "diagonal)\n",
                   stem, k, step * k, no, worst, worst / (tol / 1e-5));
        }
        free(pg);
        free(po);
        rt_scene_destroy(o);
    }
    rt_scene_destroy(g);
    return 0;
}

/* The scene at times t of every clip on one thread and on four: the same
 * bits in every mesh and object, the same versions (the same meshes
 * changed). */
static void threads_agree(const char *path) {
    rt_scene *one = NULL, *four = NULL;
    rt_error err;
    CHECK_MSG(rt_scene_load(path, &one, &err) == RT_OK, "%s", err.message);
    CHECK_MSG(rt_scene_load(path, &four, &err) == RT_OK, "%s", err.message);
    if (!one || !four) {
        rt_scene_destroy(one);
        rt_scene_destroy(four);
        return;
    }
    CHECK(rt_scene_set_threads(one, 1) == RT_OK);
    CHECK(rt_scene_set_threads(four, 4) == RT_OK);
    uint32_t clips = rt_scene_clip_count(one), differing = 0, frames = 0;
    for (uint32_t c = 0; c < clips && !differing; c++) {
        char index[16];
        snprintf(index, sizeof index, "%u", c);
        CHECK(rt_scene_select_clip(one, index) == RT_OK);
        CHECK(rt_scene_select_clip(four, index) == RT_OK);
        for (int k = 0; k < 12 && !differing; k++, frames++) {
            double t = 0.137 * k;
            CHECK(rt_scene_set_time(one, t) == RT_OK);
            CHECK(rt_scene_set_time(four, t) == RT_OK);
            CHECK_EQ_INT(one->version, four->version);
            CHECK_EQ_INT(one->mesh_count, four->mesh_count);
            for (uint32_t m = 0; m < one->mesh_count && m < four->mesh_count; m++) {
                const rt_mesh_data *a = &one->meshes[m], *b = &four->meshes[m];
                size_t n = 3 * sizeof(float) * a->vertex_count;
                if (a->version != b->version || a->vertex_count != b->vertex_count ||
                    memcmp(a->positions, b->positions, n) != 0 ||
                    (a->normals && memcmp(a->normals, b->normals, n) != 0))
                    differing++;
            }
            for (uint32_t o = 0; o < one->object_count && o < four->object_count; o++)
                if (memcmp(one->objects[o].transform, four->objects[o].transform,
                           sizeof one->objects[o].transform) != 0)
                    differing++;
        }
    }
    CHECK_MSG(differing == 0, "%s: %u meshes or objects differ between 1 and 4 threads", path,
              differing);
    printf("%s: %u clips, %u frames on 1 and 4 threads: the same bits\n", path, clips, frames);
    rt_scene_destroy(one);
    rt_scene_destroy(four);
}

int main(void) {
    const char *shared = getenv("RT_SHARED_SCENES");
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/brainstem_anim/BrainStem.glb", shared ? shared : "");
    FILE *f = shared ? fopen(dir, "rb") : NULL;
    if (!f) {
        printf("skipped: the shared scenes (RT_SHARED_SCENES) are not here\n");
        return 77;
    }
    fclose(f);
    snprintf(dir, sizeof dir, "%s/brainstem_anim", shared);
    if (compare(dir, "BrainStem.glb", NULL, "brainstem", 0.2) == 77) return 77;
    snprintf(dir, sizeof dir, "%s/brainstem_anim/BrainStem.glb", shared);
    threads_agree(dir);
    snprintf(dir, sizeof dir, "%s/robot_walk_anim", shared);
    compare(dir, "RobotExpressive.glb", "Walking", "robot_walk", 0.958333 / 10.0);
    snprintf(dir, sizeof dir, "%s/robot_walk_anim/RobotExpressive.glb", shared);
    threads_agree(dir);
    return TEST_END();
}
