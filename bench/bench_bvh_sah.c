/* SPDX-License-Identifier: Apache-2.0 */
/* bench_bvh_sah.c - times the fast BVH builder alone on one scene, and
 * prints a checksum of the tree so that variants of the builder can be
 * compared for identical output.
 *
 * usage: bench_bvh_sah SCENE [threads] [reps] [neon 0/1]
 *
 * Built for profiling: with threads 1 and reps 1 under
 * `valgrind --tool=callgrind`, the instruction counts of the builder are
 * repeatable even on a loaded machine (the scene loading is outside the
 * builder and shows separately).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "accel/bvh.h"
#include "accel/bvh_internal.h"
#include "rt.h"
#include "scene/scene.h"
#include "base/thread_pool.h"

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* FNV-1a over the bytes of the nodes and primitive indices. */
static uint64_t checksum(const rt_bvh *bvh) {
    uint64_t h = 1469598103934665603ull;
    const unsigned char *p = (const unsigned char *)bvh->nodes;
    for (size_t i = 0; i < (size_t)bvh->node_count * sizeof *bvh->nodes; i++)
        h = (h ^ p[i]) * 1099511628211ull;
    p = (const unsigned char *)bvh->prim_indices;
    for (size_t i = 0; i < (size_t)bvh->prim_count * sizeof *bvh->prim_indices; i++)
        h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static rt_aabb *triangle_boxes(const rt_scene *scene, uint32_t *count) {
    uint64_t tris = 0;
    for (uint32_t m = 0; m < scene->mesh_count; m++) tris += scene->meshes[m].triangle_count;
    rt_aabb *boxes = malloc(sizeof *boxes * (tris ? tris : 1));
    if (!boxes) return NULL;
    uint32_t t = 0;
    for (uint32_t m = 0; m < scene->mesh_count; m++) {
        const rt_mesh_data *mesh = &scene->meshes[m];
        for (uint32_t i = 0; i < mesh->triangle_count; i++, t++) {
            rt_aabb *b = &boxes[t];
            for (int k = 0; k < 3; k++) {
                b->bmin[k] = mesh->positions[3 * mesh->indices[3 * i] + k];
                b->bmax[k] = b->bmin[k];
            }
            for (int j = 0; j < 3; j++) {
                uint32_t v = mesh->indices[3 * i + j];
                for (int k = 0; k < 3; k++) {
                    float x = mesh->positions[3 * v + k];
                    b->bmin[k] = x < b->bmin[k] ? x : b->bmin[k];
                    b->bmax[k] = x > b->bmax[k] ? x : b->bmax[k];
                }
            }
        }
    }
    *count = t;
    return boxes;
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: bench_bvh_sah SCENE [threads] [reps] [neon 0/1]\n");
        return 2;
    }
    int threads = argc > 2 ? atoi(argv[2]) : 1;
    int reps = argc > 3 ? atoi(argv[3]) : 5;
    int neon = argc > 4 ? atoi(argv[4]) : 1;
    if (threads < 1) threads = 1;
    if (reps < 1) reps = 1;
    rt_scene *scene = NULL;
    rt_error err;
    if (rt_scene_load(argv[1], &scene, &err) != RT_OK) {
        fprintf(stderr, "bench_bvh_sah: %s\n", err.message);
        return 1;
    }
    uint32_t count = 0;
    rt_aabb *boxes = triangle_boxes(scene, &count);
    rt_scene_destroy(scene);
    if (!boxes) return 1;
    rt_pool *pool = threads > 1 ? rt_pool_create(threads) : NULL;
    rt_build_options o = rt_build_options_default();
    o.threads = threads;
    double *times = malloc(sizeof(double) * (size_t)reps);
    uint64_t sum = 0;
    rt_bvh_quality q = {0};
    for (int i = 0; i < reps && times; i++) {
        rt_bvh bvh;
        rt_error msg;
        memset(&msg, 0, sizeof msg);
        double t0 = rt_now_ms();
        rt_status st = rt_bvh_build_sah(boxes, count, &o, pool, neon, &bvh, &msg);
        times[i] = rt_now_ms() - t0;
        if (st != RT_OK) {
            fprintf(stderr, "bench_bvh_sah: %s\n", msg.message);
            return 1;
        }
        if (i == 0) {
            sum = checksum(&bvh);
            q = rt_bvh_measure(&bvh, o.costs);
        }
        rt_bvh_free(&bvh);
    }
    if (!times) return 1;
    qsort(times, (size_t)reps, sizeof *times, cmp_double);
    printf("%u triangles, %d threads, neon %d: min %.2f ms, median %.2f ms, SAH %.4f, nodes %u, "
           "checksum %016llx\n",
           count, threads, neon, times[0], times[reps / 2], q.sah, q.nodes,
           (unsigned long long)sum);
    free(times);
    free(boxes);
    rt_pool_destroy(pool);
    return 0;
}
