/* SPDX-License-Identifier: Apache-2.0 */
/* test_oracle_scenes.c - the renderer's traversal (real builders, the layout
 * rt_render uses) against brute force over all triangles, on random and
 * camera rays over the built-in scenes and the shared scenes: identical hits
 * (t bits, u, v, prim, inst) for the scalar oracle and the packet path (every
 * instruction-set build of it that this CPU runs), and any-hit agreeing on
 * occlusion. Ray counts scale down with triangle count
 * (brute force costs rays x triangles), more so under sanitizers. */
#include <stdlib.h>

#include "check.h"
#include "cpu_render.h"
#include "oracle_util.h"
#include "packet_trace.h"
#include "layout/flat.h"
#include "scene/scene.h"
#include "scene/scene_builtin.h"

#if defined(__SANITIZE_ADDRESS__) || !defined(__OPTIMIZE__)
#define TRI_TEST_BUDGET 4e6
#define SLOW_BUILD      1
#else
#define TRI_TEST_BUDGET 1.5e8
#define SLOW_BUILD      0
#endif

static void check_scene(const char *name, rt_scene *scene) {
    const rt_flat *flat = test_layout(scene, 0);
    if (!flat) return;
    rt_scene_view v = rt_flat_view(flat);
    double tris = (double)flat->tri_count + 1.0;
    int rays = (int)(TRI_TEST_BUDGET / tris);
    if (rays > 3000) rays = 3000;
    if (rays < 16) rays = 16;
    float lo[3], hi[3];
    rt_scene_bounds(scene, lo, hi);
    rt_ray *r = malloc(sizeof(rt_ray) * (size_t)rays);
    rt_hit_d *scalar = malloc(sizeof(rt_hit_d) * (size_t)rays);
    rt_hit_d *packet = malloc(sizeof(rt_hit_d) * (size_t)rays);
    rt_hit_d *any = malloc(sizeof(rt_hit_d) * (size_t)rays);
    for (int i = 0; i < rays; i++) oracle_ray(&flat->hdr, lo, hi, i, &r[i]);
    rt_wide_bvh wide;
    CHECK(rt_wide_build(flat, rt_pk_shape(), &wide) == RT_OK);
    rt_counters c = {0, 0, 0};
    rt_cpu_trace_rays(flat, r, NULL, (size_t)rays, scalar, 0, &c);
    rt_hit_d *b = malloc(sizeof(rt_hit_d) * (size_t)rays);
    int bad = 0, hits = 0;
    for (int i = 0; i < rays; i++) {
        oracle_brute_force(&v, &r[i], 0, &b[i]);
        hits += b[i].prim != RT_NO_HIT;
        if (!oracle_same_hit(&scalar[i], &b[i])) {
            if (bad < 3)
                fprintf(stderr,
                        "%s ray %d: bvh t=%.9g prim %u inst %u, brute t=%.9g prim %u inst %u\n",
                        name, i, scalar[i].t, scalar[i].prim, scalar[i].inst, b[i].t, b[i].prim,
                        b[i].inst);
            bad++;
        }
    }
    printf("%s: %d rays, %d hits, %u triangles\n", name, rays, hits, flat->tri_count);
    CHECK_MSG(bad == 0, "%s: %d of %d scalar hits differ from brute force", name, bad, rays);
    CHECK_MSG(hits > 0, "%s: no ray hit anything", name);
    for (int k = 0; rt_cpu_isa_at(k); k++) {
        const char *isa = rt_cpu_isa_at(k);
        const rt_cpu_isa *variant = rt_cpu_isa_find(isa);
        if (!variant) continue;
        /* Every group in packets, then each as the coherence measure
         * decides (packets or the single-ray tracer of the same build). */
        rt_wide_bvh single;
        CHECK(rt_wide_build(flat, rt_sw_shape(rt_cpu_isa_width(variant)), &single) == RT_OK);
        for (int mixed = 0; mixed < 2; mixed++) {
            rt_cpu_frame tracers;
            memset(&tracers, 0, sizeof tracers);
            tracers.flat = flat;
            tracers.wide = &wide;
            tracers.isa = variant;
            tracers.single = mixed ? &single : NULL;
            uint64_t in_packets = 0;
            rt_packet_trace_rays(&tracers, r, NULL, (size_t)rays, packet, 0, RT_TRACE_PATH_AUTO, &c,
                                 &in_packets);
            rt_packet_trace_rays(&tracers, r, NULL, (size_t)rays, any, 1, RT_TRACE_PATH_AUTO, &c,
                                 &in_packets);
            CHECK(mixed || in_packets == 2 * (uint64_t)rays);
            int bad_packet = 0, bad_any = 0;
            for (int i = 0; i < rays; i++) {
                bad_packet += !oracle_same_hit(&packet[i], &b[i]);
                bad_any += (any[i].prim != RT_NO_HIT) != (b[i].prim != RT_NO_HIT);
            }
            CHECK_MSG(bad_packet == 0, "%s: %d of %d packet (%s%s) hits differ", name, bad_packet,
                      rays, isa, mixed ? ", mixed" : "");
            CHECK_MSG(bad_any == 0, "%s: %d of %d any-hit (%s%s) results differ", name, bad_any,
                      rays, isa, mixed ? ", mixed" : "");
        }
        rt_wide_free(&single);
    }
    rt_wide_free(&wide);
    free(b);
    free(r);
    free(scalar);
    free(packet);
    free(any);
}

int main(void) {
    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        rt_scene *s;
        rt_error err;
        CHECK(rt_scene_builtin(rt_builtin_scene_names[i], &s, &err) == RT_OK);
        if (!s) continue;
        check_scene(rt_builtin_scene_names[i], s);
        /* Another keyframe and a moved object: the cache rebuilds what changed. */
        for (uint32_t o = 0; o < s->object_count; o++)
            if (s->objects[o].mesh_count > 1) rt_object_select_mesh(s, o, 0);
        const float turn[16] = {0, -1, 0, 0.1f, 1, 0, 0, 0.2f, 0, 0, 1, 0, 0, 0, 0, 1};
        rt_object_transform(s, s->object_count - 1, turn);
        check_scene(rt_builtin_scene_names[i], s);
        rt_scene_destroy(s);
    }
    static const char *const shared[] = {"cornell_box/CornellBox-Original.obj",
                                         "stanford_bunny/stanford-bunny.obj",
                                         "armadillo_decimated/armadillo.obj",
                                         "robot_walk_anim/robot_walk_00.obj",
                                         "brainstem_anim/brainstem_00.obj",
                                         "sibenik/sibenik.obj",
                                         "sponza_dabrovic/sponza.obj",
                                         "stanford_dragon/dragon_vrip.obj",
                                         NULL};
    int found = 0;
    for (int i = 0; shared[i]; i++) {
        const char *path = test_shared_scene(shared[i]);
        if (!path) continue;
        if (SLOW_BUILD && strstr(shared[i], "dragon")) {
            printf("%s: left out in this (sanitizer or unoptimised) build\n", shared[i]);
            continue;
        }
        found++;
        rt_scene *s;
        rt_error err;
        rt_status st = rt_scene_load(path, &s, &err);
        CHECK_MSG(st == RT_OK, "%s: %s", shared[i], err.message);
        if (st != RT_OK) continue;
        check_scene(shared[i], s);
        rt_scene_destroy(s);
    }
    if (!found) printf("shared scenes not present: built-in scenes only\n");
    return TEST_END();
}
