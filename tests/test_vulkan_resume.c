// SPDX-License-Identifier: Apache-2.0
/* test_vulkan_resume.c - the Vulkan backend answers rays that need more loop
 * iterations than lavapipe runs in one shader invocation (65535 for all
 * loops), by saving their state and resuming in further dispatches
 * (kernels/vulkan/rt_vk_resume.glsl), with the CPU oracle's bits:
 * - fault injection (cheap): every item's first pass spends the budget
 *   (all are re-run alone) and every alone dispatch spends 31,000 of its
 *   iterations first, so that cornell's pixels and rays resume many times
 *   in the object BVH, a mesh BVH, a kd-tree and the shading loop: the
 *   image, the triangle-test AOV (re-run in batches of 50 items) and the
 *   counters, and random closest and any hits, equal the oracle's, on the
 *   BVH and the kd-tree;
 * - a real case, no injection: a 64x64 grid morphed into a copy whose
 *   vertices are scrambled (long crossing slivers; the refitted BVH's boxes
 *   all span the grid, so a ray tests most of its 8,192 triangles): hits and
 *   an image equal to the oracle's. Before resumes it was refused ("needs
 *   more loop iterations");
 * - a floor lit from below by 400 lights (none gives a shadow ray), the
 *   budget spent by injection: each pixel's scan for its next light
 *   resumes; the image is the oracle's.
 * The resumes are lavapipe's (llvmpipe's loop limit); on another device
 * this test says so and skips. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt.h"
#ifdef RT_HAVE_VULKAN
#include "base/clock.h"
#include "vulkan/vk_backend.h"
#include "vulkan/vk_device.h"

static rt_renderer *cpu_r, *vk_r;

static uint32_t lcg(uint32_t *seed) {
    *seed = *seed * 1664525u + 1013904223u;
    return *seed >> 8;
}

static float unit(uint32_t *seed) {
    return (float)lcg(seed) * (1.0f / 16777216.0f);
}

/* Renders aov of s on both renderers: the same bits and counters, and
 * resumes on the Vulkan side (at least want_resumes). */
static void check_render(const char *name, rt_scene *s, rt_aov aov, uint32_t want_resumes) {
    rt_render_options o = rt_render_options_default();
    rt_render_stats cs, vs;
    memset(&cs, 0, sizeof cs);
    memset(&vs, 0, sizeof vs);
    o.aov = aov;
    rt_framebuffer a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    o.stats = &cs;
    CHECK(rt_render(cpu_r, s, &o, &a) == RT_OK);
    o.stats = &vs;
    double t0 = rt_now_ms();
    rt_status st = rt_render(vk_r, s, &o, &b);
    double ms = rt_now_ms() - t0;
    CHECK_MSG(st == RT_OK, "%s: %s", name, rt_renderer_error(vk_r));
    if (st == RT_OK && a.pixels) {
        CHECK_MSG(test_same_fb(&a, &b), "%s (aov %d): the image differs from the oracle's", name,
                  (int)aov);
        CHECK_EQ_INT((long long)vs.rays, (long long)cs.rays);
        CHECK_EQ_INT((long long)vs.box_tests, (long long)cs.box_tests);
        CHECK_EQ_INT((long long)vs.tri_tests, (long long)cs.tri_tests);
        uint32_t items, resumes, dispatches;
        rt_vk_test_reruns(&items, &resumes, &dispatches);
        CHECK_MSG(resumes >= want_resumes, "%s: %u resumes, expected at least %u", name, resumes,
                  want_resumes);
        CHECK_CONTAINS(vs.kernels, "resumed");
        printf("%s render %dx%d: %u px re-run alone, %u resumed, %u dispatches, %.0f ms (%s)\n",
               name, b.width, b.height, items, resumes, dispatches, ms, vs.kernels);
    }
    rt_framebuffer_free(&a);
    rt_framebuffer_free(&b);
}

/* Traces n rays closest and any hit on both renderers: the same hits bit
 * for bit, at least want_hits of them, and resumes on the Vulkan side. */
static void check_trace(const char *name, rt_scene *s, const rt_ray *rays, size_t n,
                        size_t want_hits, uint32_t want_resumes) {
    rt_hit *a = malloc(sizeof *a * n), *b = malloc(sizeof *b * n);
    CHECK(a && b);
    for (int any = 0; any <= 1 && a && b; any++) {
        rt_trace_options q = {any, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO, NULL, NULL};
        CHECK(rt_trace_rays(cpu_r, s, rays, n, a, &q) == RT_OK);
        double t0 = rt_now_ms();
        rt_status st = rt_trace_rays(vk_r, s, rays, n, b, &q);
        double ms = rt_now_ms() - t0;
        CHECK_MSG(st == RT_OK, "%s: %s", name, rt_renderer_error(vk_r));
        if (st != RT_OK) continue;
        size_t differ = 0, hits = 0;
        for (size_t i = 0; i < n; i++) {
            hits += a[i].hit != 0;
            if (a[i].hit != b[i].hit || memcmp(&a[i].t, &b[i].t, 4) ||
                memcmp(&a[i].u, &b[i].u, 4) || memcmp(&a[i].v, &b[i].v, 4) ||
                (a[i].hit && (a[i].prim != b[i].prim || a[i].inst != b[i].inst))) {
                if (!differ)
                    CHECK_MSG(0,
                              "%s %s ray %zu: cpu hit %d t %.9g prim %u, vulkan hit %d t %.9g "
                              "prim %u",
                              name, any ? "any" : "closest", i, a[i].hit, (double)a[i].t, a[i].prim,
                              b[i].hit, (double)b[i].t, b[i].prim);
                differ++;
            }
        }
        CHECK_MSG(differ == 0, "%s %s: %zu of %zu hits differ", name, any ? "any" : "closest",
                  differ, n);
        CHECK_MSG(hits >= want_hits, "%s: only %zu of %zu rays hit: a weak test", name, hits, n);
        uint32_t items, resumes, dispatches;
        rt_vk_test_reruns(&items, &resumes, &dispatches);
        /* Any hit stops at the first hit: it may need no resume. */
        if (!any)
            CHECK_MSG(resumes >= want_resumes, "%s: %u resumes, expected at least %u", name,
                      resumes, want_resumes);
        printf("%s trace %s, %zu rays: %u re-run alone, %u resumed, %u dispatches, %.0f ms\n", name,
               any ? "any" : "closest", n, items, resumes, dispatches, ms);
    }
    free(a);
    free(b);
}

/* n random rays into cornell's box from its camera's side. */
static rt_ray *cornell_rays(size_t n) {
    rt_ray *r = malloc(sizeof *r * n);
    CHECK(r != NULL);
    uint32_t seed = 99u;
    for (size_t i = 0; r && i < n; i++) {
        rt_ray q = {
            {0.0f, 1.0f, 3.0f}, {unit(&seed) - 0.5f, unit(&seed) - 0.5f, -1.0f}, 0.0f, INFINITY};
        r[i] = q;
    }
    return r;
}

/* Fault injection: the budget spent, so that every item resumes. */
static void check_injected(void) {
    rt_vk_test_loop_limit(65000u, 1);
    rt_vk_test_alone_ballast(31000u);
    enum { N = 256 };
    rt_ray *rays = cornell_rays(N);
    for (int kd = 0; kd <= 1 && rays; kd++) {
        rt_scene *s = test_builtin_scene("cornell", 32, 18);
        if (!s) continue;
        if (kd) CHECK(rt_scene_set_static_accel(s, RT_ACCEL_KD) == RT_OK);
        const char *name = kd ? "cornell kd (injected)" : "cornell bvh (injected)";
        check_render(name, s, RT_AOV_NONE, 32u * 18u);
        /* Batches of 50 items: the re-run items of a tile in several. */
        rt_vk_test_slots(50u);
        check_render(name, s, RT_AOV_TRI_TESTS, 32u * 18u);
        rt_vk_test_slots(0u);
        check_trace(name, s, rays, N, N / 2, 1);
        rt_scene_destroy(s);
    }
    free(rays);
    rt_vk_test_alone_ballast(0u);
    rt_vk_test_loop_limit(0u, 1);
}

enum { G = 65 }; /* grid vertices per side: 64 x 64 quads, 8,192 triangles */

/* The grid over [0, 1]^2 in z = 0 (heights within 0.01), two triangles per
 * quad; *idx its triangles. */
static float *grid(uint32_t **idx) {
    float *pos = malloc(sizeof(float) * 3 * G * G);
    *idx = malloc(sizeof(uint32_t) * 6 * (G - 1) * (G - 1));
    CHECK(pos && *idx);
    if (!pos || !*idx) return pos;
    uint32_t seed = 5u, *t = *idx;
    for (uint32_t j = 0; j < G; j++)
        for (uint32_t i = 0; i < G; i++) {
            float *p = pos + 3 * (j * G + i);
            p[0] = (float)i / (G - 1);
            p[1] = (float)j / (G - 1);
            p[2] = 0.01f * unit(&seed);
        }
    for (uint32_t j = 0; j + 1 < G; j++)
        for (uint32_t i = 0; i + 1 < G; i++) {
            uint32_t a = j * G + i, b = a + 1, c = a + G, d = c + 1;
            const uint32_t q[6] = {a, b, d, a, d, c};
            memcpy(t, q, sizeof q);
            t += 6;
        }
    return pos;
}

/* The vertices of pos shuffled (Fisher-Yates): the same triangles now join
 * far-apart points. */
static float *scrambled(const float *pos) {
    float *out = malloc(sizeof(float) * 3 * G * G);
    CHECK(out != NULL);
    if (!out) return NULL;
    memcpy(out, pos, sizeof(float) * 3 * G * G);
    uint32_t seed = 17u;
    for (uint32_t i = G * G - 1; i > 0; i--) {
        uint32_t j = lcg(&seed) % (i + 1), k;
        for (k = 0; k < 3; k++) {
            float x = out[3 * i + k];
            out[3 * i + k] = out[3 * j + k];
            out[3 * j + k] = x;
        }
    }
    return out;
}

/* Rays straight down onto the grid, slightly slanted. */
static rt_ray *down_rays(size_t n) {
    rt_ray *r = malloc(sizeof *r * n);
    CHECK(r != NULL);
    uint32_t seed = 3u;
    for (size_t i = 0; r && i < n; i++) {
        rt_ray q = {{0.1f + 0.8f * unit(&seed), 0.1f + 0.8f * unit(&seed), 1.0f},
                    {0.05f * (unit(&seed) - 0.5f), 0.05f * (unit(&seed) - 0.5f), -1.0f},
                    0.0f,
                    INFINITY};
        r[i] = q;
    }
    return r;
}

/* A camera above the grid looking down, w x h. */
static void look_down(rt_scene *s, int w, int h) {
    rt_camera cam = {{0.5f, 0.5f, 2.0f}, {0.5f, 0.5f, 0.0f}, {0.0f, 1.0f, 0.0f}, 30.0f, w, h};
    CHECK(rt_camera_set(s, &cam) == RT_OK);
}

/* The real case: the morph into the scrambled grid on a refitted BVH. */
static void check_real(void) {
    enum { N = 64 };
    uint32_t *idx = NULL;
    float *pos = grid(&idx), *mix = pos ? scrambled(pos) : NULL;
    rt_ray *rays = down_rays(N);
    if (pos && idx && mix && rays) {
        rt_scene *s = test_mesh_scene(pos, G * G, idx, 2 * (G - 1) * (G - 1));
        if (s) {
            look_down(s, 8, 8);
            CHECK(rt_mesh_set_update(s, 0, RT_UPDATE_REFIT) == RT_OK);
            /* The first frame builds the BVH on the grid, the morph refits it. */
            check_trace("grid", s, rays, N, N, 0);
            CHECK(rt_mesh_set_positions(s, 0, mix, NULL, G * G) == RT_OK);
            check_trace("scrambled morph, refitted bvh", s, rays, N, N / 4, N / 4);
            check_render("scrambled morph, refitted bvh", s, RT_AOV_NONE, 8);
            rt_scene_destroy(s);
        }
    }
    free(pos);
    free(idx);
    free(mix);
    free(rays);
}

/* Many lights that give no shadow ray: a floor lit from below by 400
 * lights, then the one light above it, with the budget spent by fault
 * injection, so that each pixel's scan for its next shadow ray (400 lights
 * of 64 counted iterations or more each) suspends inside the scan. */
static void check_lights(void) {
    const float pos[12] = {-1.0f, 0.0f, -1.0f, 1.0f,  0.0f, -1.0f,
                           1.0f,  0.0f, 1.0f,  -1.0f, 0.0f, 1.0f};
    const uint32_t idx[6] = {0, 2, 1, 0, 3, 2};
    rt_scene *s = test_mesh_scene(pos, 4, idx, 2);
    if (!s) return;
    rt_camera cam = {{0.0f, 2.0f, 0.5f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 40.0f, 8, 8};
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    const float dim[3] = {0.001f, 0.001f, 0.001f};
    for (int k = 0; k < 400; k++) {
        const float below[3] = {0.001f * (float)k, -1.0f - 0.01f * (float)k, 0.0f};
        uint32_t id;
        if (rt_light_add(s, below, dim, &id) != RT_OK) CHECK(0);
    }
    rt_vk_test_loop_limit(65000u, 1);
    rt_vk_test_alone_ballast(31000u);
    check_render("400 lights below a floor (injected)", s, RT_AOV_NONE, 64);
    rt_vk_test_alone_ballast(0u);
    rt_vk_test_loop_limit(0u, 1);
    rt_scene_destroy(s);
}
#endif

int main(void) {
#ifndef RT_HAVE_VULKAN
    test_skip("this build has no Vulkan backend (RT_VULKAN=OFF, or no loader or glslangValidator)");
#else
    rt_vk_device_info *devs;
    int count;
    rt_error err;
    memset(&err, 0, sizeof err);
    if (rt_vk_devices(&devs, &count, &err) != RT_OK) test_skip(err.message);
    int pick = rt_vk_select(devs, count, NULL, &err);
    rt_vk_device_info dev = devs[pick];
    free(devs);
    if (!strstr(dev.name, "llvmpipe"))
        test_skip("the resumes are lavapipe's (llvmpipe's loop limit); the default Vulkan device "
                  "is not lavapipe");
    printf("device: %s (%s)\n", dev.name, dev.driver);
    cpu_r = test_renderer("cpu", 0);
    vk_r = test_renderer("vulkan", 0);
    if (!cpu_r || !vk_r) return TEST_END();
    check_injected();
    check_real();
    check_lights();
    return TEST_END();
#endif
}
