/* SPDX-License-Identifier: Apache-2.0 */
/* test_kd_bunny_tree.c - the SAH kd-trees of the Stanford Bunny
 * (../shared/scenes) are the trees the builders gave before their speed-ups:
 * a hash of every node, leaf entry and the root cell, for the exact and the
 * binned builder with 1 and 2 threads. The speed-ups (kd_offer inline,
 * clipping that skips planes a triangle lies inside of) must not change a
 * tree; a change to the builders that changes the trees on purpose updates
 * the hashes here and says why. Skips without the shared scenes. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/kd.h"
#include "base/thread_pool.h"
#include "check.h"
#include "rt.h"
#include "scene/scene.h"

/* FNV-1a over bytes. */
static uint64_t fnv(uint64_t h, const void *p, size_t n) {
    const unsigned char *c = p;
    for (size_t i = 0; i < n; i++) h = (h ^ c[i]) * 1099511628211ull;
    return h;
}

int main(void) {
    const char *dir = getenv("RT_SHARED_SCENES");
    char path[1024];
    snprintf(path, sizeof path, "%s/stanford_bunny/stanford-bunny.obj", dir ? dir : "");
    FILE *f = dir && dir[0] ? fopen(path, "rb") : NULL;
    if (!f) test_skip("no shared scenes (RT_SHARED_SCENES): the Bunny is not here");
    fclose(f);
    rt_scene *scene;
    rt_error err;
    CHECK_MSG(rt_scene_load(path, &scene, &err) == RT_OK, "%s", err.message);
    if (!scene || scene->mesh_count != 1) return TEST_END();
    const rt_mesh_data *md = &scene->meshes[0];
    /* Recorded with the builders of commit 9bc4c32 (before the speed-ups). */
    static const struct {
        rt_kd_builder builder;
        uint32_t nodes, prims;
        uint64_t hash;
    } want[] = {{RT_KD_EXACT, 419799, 327478, 0xdf159ec8e86e7611ull},
                {RT_KD_BINNED, 405569, 311521, 0x344c8d7fc3f86ef1ull}};
    rt_pool *pool = rt_pool_create(2);
    for (int i = 0; i < 2; i++)
        for (int threads = 1; threads <= 2; threads++) {
            rt_kd_options o = rt_kd_options_default();
            o.builder = want[i].builder;
            rt_kd kd;
            rt_status st =
                rt_kd_build(md->positions, md->vertex_count, md->indices, md->triangle_count, &o,
                            threads > 1 ? pool : NULL, &kd, &err);
            CHECK_MSG(st == RT_OK, "%s", err.message);
            if (st != RT_OK) continue;
            uint64_t h = 1469598103934665603ull;
            h = fnv(h, kd.nodes, sizeof(rt_kd_node) * kd.node_count);
            h = fnv(h, kd.prims, sizeof(uint32_t) * kd.prim_count);
            h = fnv(h, &kd.bounds, sizeof kd.bounds);
            CHECK_MSG(kd.node_count == want[i].nodes && kd.prim_count == want[i].prims &&
                          h == want[i].hash,
                      "%s, %d threads: %u nodes, %u entries, hash %016llx; before: %u, %u, %016llx",
                      rt_kd_builder_name(want[i].builder), threads, kd.node_count, kd.prim_count,
                      (unsigned long long)h, want[i].nodes, want[i].prims,
                      (unsigned long long)want[i].hash);
            rt_kd_free(&kd);
        }
    rt_pool_destroy(pool);
    rt_scene_destroy(scene);
    return TEST_END();
}
