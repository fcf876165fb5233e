/* SPDX-License-Identifier: Apache-2.0 */
/* test_vulkan_oracle.c - the Vulkan backend against the CPU oracle, on a
 * Vulkan device (lavapipe in CI):
 * - the GLSL mirror of the soft maths (kernels/vulkan/rt_vk_soft_math.glsl)
 *   against kernels/rt_soft_math.h, bit for bit (NaN payloads included), on
 *   every pair of special values and 10^5 random operand sets, with and
 *   without flush to zero;
 * - on every shipped scene (the JSON scenes in scenes/): the float framebuffer of the
 *   image and of every AOV, and the 8-bit PNG, in Whitted and direct mode,
 *   identical to the oracle's, with the same ray and test counts; the
 *   other triangle tests on cornell (image and depth); an object turned
 *   about an oblique axis and a second, coloured light;
 * - 20,000 random ray queries per scene (closest and any hit): t, u, v bits,
 *   prim and inst identical;
 * - later frames upload nothing, a moved object only the per-frame part;
 * - --denormals flush: cornell's image and hits are the flushing oracle's;
 *   on a scene 1e-13 across (denormal t numerators) the device is held to
 *   the oracle of each policy it promises (float controls), and what it
 *   gives elsewhere is printed;
 * - kd-tree meshes (--accel kd, kd-binned; kernels/vulkan/rt_vk_kd.glsl): on
 *   every shipped scene the image and every AOV with the same ray and test
 *   counts as the oracle's kd traversal, the image, depth and primitive ids
 *   as the BVH's, random ray queries, an instance turned about an oblique
 *   axis; the traversal stack's private overflow (the shaders keep 21 cells
 *   in shared memory, more than these trees need) run by keeping 0 and 2
 *   cells there instead, on random rays;
 * - the driver's loop limit: 3000 diverging rays through 3000 thin slabs
 *   give the oracle's hits; on lavapipe, with the loop budget spent by
 *   fault injection, the canary's marked items are an error without
 *   re-runs and the oracle's hits and image with them;
 * - a device that does not exist is an error with a reason.
 * Skips only when the build has no Vulkan backend or no Vulkan device
 * exists. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt.h"
#ifdef RT_HAVE_VULKAN
#include "formats/image.h"
#include "layout/flat.h"
#include "oracle_util.h"
#include "scene/scene.h"
#include "soft_math_cases.h"
#include "vulkan/vk_backend.h"
#include "vulkan/vk_device.h"

static const char *const aov_names[] = {"image",  "depth",    "primid",  "instid",
                                        "normal", "boxtests", "tritests"};
static const char *const tri_names[] = {"watertight", "moller", "pluecker", "badouel"};

static rt_renderer *cpu_r, *vk_r;

static rt_status render_with(rt_renderer *r, rt_scene *s, rt_aov aov, int direct,
                             rt_triangle_test tri, rt_framebuffer *fb, rt_render_stats *stats) {
    rt_render_options o = rt_render_options_default();
    o.aov = aov;
    o.stats = stats;
    o.direct_only = direct;
    o.tri_test = tri;
    return rt_render(r, s, &o, fb);
}

static int same_pixels(const char *scene, const char *what, const rt_framebuffer *a,
                       const rt_framebuffer *b) {
    CHECK_MSG(a->width == b->width && a->height == b->height && a->channels == b->channels,
              "%s %s: sizes differ", scene, what);
    size_t n = (size_t)a->width * a->height * a->channels;
    for (size_t i = 0; i < n; i++) {
        if (memcmp(&a->pixels[i], &b->pixels[i], sizeof(float)) != 0) {
            size_t px = i / (size_t)a->channels;
            CHECK_MSG(
                0, "%s %s: first difference at pixel (%zu, %zu) channel %zu: cpu %.9g vulkan %.9g",
                scene, what, px % (size_t)a->width, px / (size_t)a->width, i % (size_t)a->channels,
                (double)a->pixels[i], (double)b->pixels[i]);
            return 0;
        }
    }
    test_checks++;
    return 1;
}

static int same_file(const char *a, const char *b) {
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    int same = fa && fb;
    while (same) {
        int ca = fgetc(fa), cb = fgetc(fb);
        if (ca != cb) same = 0;
        if (ca == EOF || cb == EOF) break;
    }
    if (fa) fclose(fa);
    if (fb) fclose(fb);
    return same;
}

/* The AOVs from first to last (the image is RT_AOV_NONE) in one mode. */
static void check_images(const char *name, rt_scene *s, int direct, rt_triangle_test tri, int first,
                         int last) {
    for (int aov = first; aov <= last; aov++) {
        rt_framebuffer cpu, vk;
        rt_render_stats cs, st;
        CHECK(render_with(cpu_r, s, (rt_aov)aov, direct, tri, &cpu, &cs) == RT_OK);
        rt_status status = render_with(vk_r, s, (rt_aov)aov, direct, tri, &vk, &st);
        CHECK_MSG(status == RT_OK, "%s: %s", name, rt_renderer_error(vk_r));
        if (status != RT_OK) {
            rt_framebuffer_free(&cpu);
            continue;
        }
        char label[160];
        snprintf(label, sizeof label, "%s (%s, %dx%d, %s)", aov_names[aov],
                 direct ? "direct" : "Whitted", cpu.width, cpu.height, tri_names[tri]);
        CHECK(strcmp(st.backend, "vulkan") == 0 && st.device[0]);
        CHECK_CONTAINS(st.specialisation, "specialization constants");
        CHECK(st.primary_rays == (uint64_t)cpu.width * (uint64_t)cpu.height);
        CHECK_EQ_INT((long long)st.rays, (long long)cs.rays);
        CHECK_EQ_INT((long long)st.box_tests, (long long)cs.box_tests);
        CHECK_EQ_INT((long long)st.tri_tests, (long long)cs.tri_tests);
        same_pixels(name, label, &cpu, &vk);
        if (aov == RT_AOV_NONE) { /* the 8-bit image too */
            char pa[64], pb[64], a[512], b[512];
            snprintf(pa, sizeof pa, "%s_cpu.png", name);
            snprintf(pb, sizeof pb, "%s_vk.png", name);
            snprintf(a, sizeof a, "%s", test_write_temp(pa, ""));
            snprintf(b, sizeof b, "%s", test_write_temp(pb, ""));
            rt_image ia = {cpu.width, cpu.height, 3, cpu.pixels};
            rt_image ib = {vk.width, vk.height, 3, vk.pixels};
            rt_error err;
            CHECK(rt_image_write(a, &ia, &err) == RT_OK);
            CHECK(rt_image_write(b, &ib, &err) == RT_OK);
            CHECK_MSG(same_file(a, b), "%s %s: the 8-bit PNGs differ", name, label);
        }
        rt_framebuffer_free(&cpu);
        rt_framebuffer_free(&vk);
    }
}

typedef void (*ray_maker)(const rt_scene_header *h, const float lo[3], const float hi[3], int i,
                          rt_ray *r);

/* Rays from random points of the bounds in random directions of length
 * about 1 (for the denormal scene, whose camera rays would be huge). */
static void unit_ray(const rt_scene_header *h, const float lo[3], const float hi[3], int i,
                     rt_ray *r) {
    (void)h;
    (void)i;
    for (int k = 0; k < 3; k++) {
        r->org[k] = lo[k] + (hi[k] - lo[k]) * oracle_rnd();
        r->dir[k] = oracle_rnd() - 0.5f;
    }
    r->tmin = 0.0f;
    r->tmax = INFINITY;
}

/* n rays of a maker over the scene's bounds. */
static rt_ray *make_rays(rt_scene *s, ray_maker make, int n) {
    const rt_flat *flat = test_layout(s, 0);
    rt_ray *rays = flat ? malloc(sizeof *rays * (size_t)n) : NULL;
    if (!rays) return NULL;
    float lo[3], hi[3];
    CHECK(rt_scene_bounds(s, lo, hi));
    for (int i = 0; i < n; i++) {
        rt_ray r;
        make(&flat->hdr, lo, hi, i, &r);
        memcpy(rays[i].org, r.org, sizeof r.org);
        memcpy(rays[i].dir, r.dir, sizeof r.dir);
        rays[i].tmin = r.tmin;
        rays[i].tmax = r.tmax;
    }
    return rays;
}

static int same_hit(const rt_hit *a, const rt_hit *b) {
    return a->hit == b->hit && !memcmp(&a->t, &b->t, 4) && !memcmp(&a->u, &b->u, 4) &&
           !memcmp(&a->v, &b->v, 4) && a->prim == b->prim && a->inst == b->inst;
}

/* Closest or any hits of n rays on two renderers; returns how many differ
 * (-1 when a trace failed), and *hits the hits of the first. */
static int differing_hits(rt_renderer *ra, rt_renderer *rb, rt_scene *s, const rt_ray *rays, int n,
                          int any, int *hits, char *first, size_t first_size) {
    rt_hit *a = malloc(sizeof *a * (size_t)n), *b = malloc(sizeof *b * (size_t)n);
    rt_trace_options q = {any, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO, NULL, NULL};
    int differ = -1;
    *hits = 0;
    if (a && b && rt_trace_rays(ra, s, rays, (size_t)n, a, &q) == RT_OK) {
        rt_status st = rt_trace_rays(rb, s, rays, (size_t)n, b, &q);
        CHECK_MSG(st == RT_OK, "%s", rt_renderer_error(rb));
        if (st == RT_OK) differ = 0;
        for (int i = 0; i < n && st == RT_OK; i++) {
            *hits += a[i].hit;
            if (same_hit(&a[i], &b[i])) continue;
            if (!differ++)
                snprintf(first, first_size,
                         "ray %d: cpu hit %d t %.9g u %.9g v %.9g prim %u inst %u; vulkan hit %d t "
                         "%.9g u %.9g v %.9g prim %u inst %u",
                         i, a[i].hit, (double)a[i].t, (double)a[i].u, (double)a[i].v, a[i].prim,
                         a[i].inst, b[i].hit, (double)b[i].t, (double)b[i].u, (double)b[i].v,
                         b[i].prim, b[i].inst);
        }
    }
    free(a);
    free(b);
    return differ;
}

/* 20,000 random rays, closest and any hit, identical on the two renderers. */
static void check_hits_on(const char *name, rt_renderer *ra, rt_renderer *rb, rt_scene *s) {
    enum { N = 20000 };
    rt_ray *rays = make_rays(s, oracle_ray, N);
    CHECK(rays != NULL);
    for (int any = 0; any <= 1 && rays; any++) {
        char first[400] = "";
        int hits;
        int differ = differing_hits(ra, rb, s, rays, N, any, &hits, first, sizeof first);
        CHECK_MSG(differ == 0, "%s %s: %d of %d hits differ; first: %s", name,
                  any ? "any-hit" : "closest", differ, N, first);
        CHECK_MSG(hits > N / 10, "%s: only %d of %d rays hit: a weak test", name, hits, N);
    }
    free(rays);
}

static void check_hits(const char *name, rt_scene *s) {
    check_hits_on(name, cpu_r, vk_r, s);
}

/* Turns object obj by 0.5 rad about the oblique axis (1, 2, 3) through c
 * (an instance transform with no zero entry), as test_opencl_oracle does. */
static void oblique_turn(rt_scene *s, uint32_t obj, const float c[3]) {
    double a[3] = {1.0, 2.0, 3.0}, len = sqrt(14.0), t = 0.5, co = cos(t), si = sin(t), r[3][3];
    for (int i = 0; i < 3; i++) a[i] /= len;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double cross = 0.0;
            if (i != j) {
                int k = 3 - i - j;
                double sign = ((i + 1) % 3 == j) ? -1.0 : 1.0;
                cross = sign * a[k] * si;
            }
            r[i][j] = (i == j ? co : 0.0) + (1.0 - co) * a[i] * a[j] + cross;
        }
    float m[16] = {0};
    for (int i = 0; i < 3; i++) {
        double tr = c[i];
        for (int j = 0; j < 3; j++) {
            m[4 * i + j] = (float)r[i][j];
            tr -= r[i][j] * c[j];
        }
        m[4 * i + 3] = (float)tr;
    }
    m[15] = 1.0f;
    CHECK(rt_object_transform(s, obj, m) == RT_OK);
}

static void check_scene(const char *name) {
    char rel[256];
    snprintf(rel, sizeof rel, "scenes/%s.json", name);
    rt_scene *s;
    rt_error err;
    rt_status st = rt_scene_load(test_source_path(rel), &s, &err);
    CHECK_MSG(st == RT_OK, "%s: %s", rel, err.message);
    if (st != RT_OK) return;
    rt_camera cam;
    rt_camera_get(s, &cam);
    cam.width = 96; /* small: lavapipe on a shared CPU */
    cam.height = 54;
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    check_images(name, s, 0, RT_TRI_TEST_WATERTIGHT, RT_AOV_NONE, RT_AOV_TRI_TESTS);
    check_images(name, s, 1, RT_TRI_TEST_WATERTIGHT, RT_AOV_NONE, RT_AOV_NORMAL);
    check_hits(name, s);
    /* An object turned about an oblique axis, a second, coloured light, an
     * odd size (a partial work group). */
    int cornell = strcmp(name, "cornell") == 0;
    const float centre_cornell[3] = {-0.8f, 0.4f, -0.2f}, centre_keyframes[3] = {0.5f, 1.0f, 0.0f};
    oblique_turn(s, cornell ? 4 : 1, cornell ? centre_cornell : centre_keyframes);
    float lo[3], hi[3], pos[3];
    CHECK(rt_scene_bounds(s, lo, hi));
    for (int k = 0; k < 3; k++) pos[k] = lo[k] + (hi[k] - lo[k]) * (k == 1 ? 0.85f : 0.3f);
    const float color[3] = {0.7f, 0.45f, 0.9f};
    uint32_t light;
    CHECK(rt_light_add(s, pos, color, &light) == RT_OK);
    cam.width = 97;
    cam.height = 61;
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    check_images(name, s, 0, RT_TRI_TEST_WATERTIGHT, RT_AOV_NONE, RT_AOV_TRI_TESTS);
    if (cornell)
        for (int t = RT_TRI_TEST_MOLLER; t <= RT_TRI_TEST_BADOUEL; t++)
            check_images(name, s, 0, (rt_triangle_test)t, RT_AOV_NONE, RT_AOV_DEPTH);
    check_hits(name, s);
    rt_scene_destroy(s);
}

/* Frame 2 uploads nothing; after moving an object only the per-frame part,
 * and the image is still the oracle's. */
static void check_uploads(void) {
    rt_scene *s = test_builtin_scene("keyframes", 64, 36);
    if (!s) return;
    rt_framebuffer fb, cpu;
    rt_render_stats first, again, moved;
    CHECK(render_with(vk_r, s, RT_AOV_NONE, 0, RT_TRI_TEST_WATERTIGHT, &fb, &first) == RT_OK);
    rt_framebuffer_free(&fb);
    CHECK(render_with(vk_r, s, RT_AOV_NONE, 0, RT_TRI_TEST_WATERTIGHT, &fb, &again) == RT_OK);
    rt_framebuffer_free(&fb);
    CHECK_EQ_INT(again.upload_bytes, 0);
    float m[16] = {1, 0, 0, 0.05f, 0, 1, 0, 0, 0, 0, 1, -0.1f, 0, 0, 0, 1};
    CHECK(rt_object_transform(s, 0, m) == RT_OK);
    CHECK(render_with(vk_r, s, RT_AOV_NONE, 0, RT_TRI_TEST_WATERTIGHT, &fb, &moved) == RT_OK);
    CHECK_MSG(moved.upload_bytes > 0 && moved.upload_bytes < first.upload_bytes,
              "upload after a move: %llu bytes (first frame %llu)",
              (unsigned long long)moved.upload_bytes, (unsigned long long)first.upload_bytes);
    CHECK(render_with(cpu_r, s, RT_AOV_NONE, 0, RT_TRI_TEST_WATERTIGHT, &cpu, NULL) == RT_OK);
    same_pixels("keyframes (moved)", "image", &cpu, &fb);
    rt_framebuffer_free(&fb);
    rt_framebuffer_free(&cpu);
    rt_scene_destroy(s);
}

/* Random triangles in a box a few 1e-13 across (test_opencl_oracle's
 * denormal scene): edge functions near 1e-26 and t's numerator near 1e-39,
 * below the smallest normal float, so the denormal policy decides many bits
 * of t. */
static rt_scene *denormal_scene(void) {
    enum { TRIS = 200 };
    float pos[9 * TRIS];
    uint32_t seed = 12345u;
    for (int i = 0; i < 9 * TRIS; i++) {
        seed = seed * 1664525u + 1013904223u;
        pos[i] = (float)(seed >> 8) * (1e-13f / 16777216.0f);
    }
    return test_soup_scene(pos, TRIS);
}

static rt_renderer *flushing(const char *backend) {
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = backend;
    o.denormals = RT_DENORMALS_FLUSH;
    rt_error err;
    rt_renderer *r = test_renderer_with(&o, &err);
    CHECK_MSG(r != NULL, "%s with --denormals flush: %s", backend, r ? "" : err.message);
    return r;
}

/* The flush policy: the shipped cornell (no denormal occurs there) gives
 * the flushing oracle's image and hits. On the denormal scene the device is
 * held to the oracle of a policy only where it promises that policy
 * (float controls); elsewhere the count of differing hits is printed. */
static void check_denormals(const rt_vk_device_info *dev) {
    rt_renderer *cpu_f = flushing("cpu"), *vk_f = flushing("vulkan");
    if (!cpu_f || !vk_f) return;
    rt_scene *s = NULL;
    rt_error err;
    CHECK_MSG(rt_scene_load(test_source_path("scenes/cornell.json"), &s, &err) == RT_OK, "%s",
              err.message);
    if (s) {
        rt_camera cam;
        rt_camera_get(s, &cam);
        cam.width = 64;
        cam.height = 36;
        CHECK(rt_camera_set(s, &cam) == RT_OK);
        rt_framebuffer a, b;
        rt_render_stats st;
        CHECK(render_with(cpu_f, s, RT_AOV_NONE, 0, RT_TRI_TEST_WATERTIGHT, &a, NULL) == RT_OK);
        rt_status status = render_with(vk_f, s, RT_AOV_NONE, 0, RT_TRI_TEST_WATERTIGHT, &b, &st);
        CHECK_MSG(status == RT_OK, "%s", rt_renderer_error(vk_f));
        if (status == RT_OK) {
            CHECK(st.denormals && strcmp(st.denormals, "flush") == 0);
            CHECK(st.math_profile && strcmp(st.math_profile, "portable") == 0);
            CHECK_CONTAINS(st.specialisation, "denormal_flush=1");
            CHECK_EQ_INT(st.exact, dev->exact_flush);
            same_pixels("cornell (flush)", "image", &a, &b);
            rt_framebuffer_free(&b);
        }
        rt_framebuffer_free(&a);
        check_hits_on("cornell (flush)", cpu_f, vk_f, s);
        rt_scene_destroy(s);
    }
    s = denormal_scene();
    if (!s) return;
    enum { N = 4000 };
    rt_ray *rays = make_rays(s, unit_ray, N);
    int hits, policies, keep, flush;
    char first[400] = "", ignored[400];
    policies = rays ? differing_hits(cpu_r, cpu_f, s, rays, N, 0, &hits, ignored, 400) : -1;
    CHECK_MSG(policies > 0, "the denormal scene gives the same hits in both policies");
    keep = rays ? differing_hits(cpu_r, vk_r, s, rays, N, 0, &hits, first, sizeof first) : -1;
    if (dev->exact)
        CHECK_MSG(keep == 0, "denormal scene: %d hits differ from the oracle; first: %s", keep,
                  first);
    flush = rays ? differing_hits(cpu_f, vk_f, s, rays, N, 0, &hits, first, sizeof first) : -1;
    if (dev->exact_flush)
        CHECK_MSG(flush == 0,
                  "denormal scene (flush): %d hits differ from the flushing oracle; "
                  "first: %s",
                  flush, first);
    printf("denormal scene, %d rays: the oracle's two policies differ on %d; vulkan differs from "
           "the preserving oracle on %d (%s), from the flushing oracle on %d (%s)\n",
           N, policies, keep, dev->exact ? "promised, checked" : "not promised", flush,
           dev->exact_flush ? "promised, checked" : "not promised");
    free(rays);
    rt_scene_destroy(s);
}

/* ---- kd-tree meshes ---------------------------------------------------- */

/* The image, depth and primitive ids of s on the Vulkan renderer equal the
 * BVH oracle's (bvh: the same scene with BVH meshes). */
static void same_as_bvh(const char *label, rt_scene *kd, rt_scene *bvh) {
    for (int aov = RT_AOV_NONE; aov <= RT_AOV_PRIMID; aov++) {
        rt_framebuffer a, b;
        CHECK(render_with(cpu_r, bvh, (rt_aov)aov, 0, RT_TRI_TEST_WATERTIGHT, &a, NULL) == RT_OK);
        if (render_with(vk_r, kd, (rt_aov)aov, 0, RT_TRI_TEST_WATERTIGHT, &b, NULL) == RT_OK) {
            char what[64];
            snprintf(what, sizeof what, "%s against the BVH", aov_names[aov]);
            same_pixels(label, what, &a, &b);
            rt_framebuffer_free(&b);
        } else {
            CHECK_MSG(0, "%s: %s", label, rt_renderer_error(vk_r));
        }
        rt_framebuffer_free(&a);
    }
}

static rt_scene *load_shipped(const char *name, int width, int height) {
    char rel[256];
    snprintf(rel, sizeof rel, "scenes/%s.json", name);
    rt_scene *s = NULL;
    rt_error err;
    rt_status st = rt_scene_load(test_source_path(rel), &s, &err);
    CHECK_MSG(st == RT_OK, "%s: %s", rel, err.message);
    if (st != RT_OK) return NULL;
    rt_camera cam;
    rt_camera_get(s, &cam);
    cam.width = width;
    cam.height = height;
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    return s;
}

/* A shipped scene with every static mesh a kd-tree of the given builder:
 * Vulkan against the oracle's kd traversal (every AOV, counts included;
 * with full 0 the image only: the binned trees go through the same code),
 * against the BVH, random rays; then an oblique instance transform. */
static void check_kd_scene(const char *name, rt_accel accel, int full) {
    rt_scene *s = load_shipped(name, 96, 54), *bvh = load_shipped(name, 96, 54);
    if (s && bvh) {
        CHECK(rt_scene_set_static_accel(s, accel) == RT_OK);
        char label[96];
        snprintf(label, sizeof label, "%s --accel %s", name, rt_accel_name(accel));
        rt_framebuffer fb;
        rt_render_stats st;
        CHECK(render_with(vk_r, s, RT_AOV_DEPTH, 0, RT_TRI_TEST_WATERTIGHT, &fb, &st) == RT_OK);
        rt_framebuffer_free(&fb);
        CHECK_CONTAINS(st.specialisation, "kd=yes");
        check_images(label, s, 0, RT_TRI_TEST_WATERTIGHT, RT_AOV_NONE,
                     full ? RT_AOV_TRI_TESTS : RT_AOV_NONE);
        if (full) check_images(label, s, 1, RT_TRI_TEST_WATERTIGHT, RT_AOV_NONE, RT_AOV_NONE);
        same_as_bvh(label, s, bvh);
        check_hits(label, s);
        int cornell = strcmp(name, "cornell") == 0;
        const float centre_cornell[3] = {-0.8f, 0.4f, -0.2f},
                    centre_keyframes[3] = {0.5f, 1.0f, 0.0f};
        oblique_turn(s, cornell ? 4 : 1, cornell ? centre_cornell : centre_keyframes);
        oblique_turn(bvh, cornell ? 4 : 1, cornell ? centre_cornell : centre_keyframes);
        snprintf(label, sizeof label, "%s --accel %s (turned)", name, rt_accel_name(accel));
        check_images(label, s, 0, RT_TRI_TEST_WATERTIGHT, RT_AOV_NONE,
                     full ? RT_AOV_TRI_TESTS : RT_AOV_NONE);
        if (full) same_as_bvh(label, s, bvh);
        check_hits(label, s);
    }
    if (s) rt_scene_destroy(s);
    if (bvh) rt_scene_destroy(bvh);
}

/* The kd stack's overflow path: random rays through cornell with kd meshes
 * (a pool of cells reaches about 5 deep) on the Vulkan traversal keeping 0
 * cells (every cell private), 2 (both paths in one traversal) and 21 (the
 * backend's choice) in shared memory, each hit the oracle's. */
static void check_kd_stack(void) {
    rt_scene *s = load_shipped("cornell", 32, 18);
    if (!s) return;
    CHECK(rt_scene_set_static_accel(s, RT_ACCEL_KD) == RT_OK);
    enum { N = 20000 };
    rt_ray *rays = make_rays(s, oracle_ray, N);
    rt_hit *want = malloc(sizeof *want * N);
    rt_ray *rd = malloc(sizeof *rd * N);
    rt_hit_d *got = malloc(sizeof *got * N);
    CHECK(rays && want && rd && got);
    for (int any = 0; any <= 1 && rays && want && rd && got; any++) {
        rt_trace_options q = {any, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO, NULL, NULL};
        CHECK(rt_trace_rays(cpu_r, s, rays, N, want, &q) == RT_OK);
        for (int i = 0; i < N; i++) {
            memcpy(rd[i].org, rays[i].org, sizeof rd[i].org);
            memcpy(rd[i].dir, rays[i].dir, sizeof rd[i].dir);
            rd[i].tmin = rays[i].tmin;
            rd[i].tmax = rays[i].tmax;
        }
        const rt_flat *flat = test_layout(s, 0);
        CHECK(flat && flat->kd_node_count > 0);
        if (!flat) break;
        static const uint32_t cells[] = {0, 2, 21};
        for (int c = 0; c < 3; c++) {
            rt_error err;
            memset(&err, 0, sizeof err);
            rt_status st = rt_vk_trace_kd_stack(NULL, flat, rd, N, any, cells[c], got, &err);
            CHECK_MSG(st == RT_OK, "kd stack with %u shared cells: %s", cells[c], err.message);
            if (st != RT_OK) continue;
            int differ = 0, hits = 0, first = -1;
            for (int i = 0; i < N; i++) {
                int hit = got[i].prim != RT_NO_HIT;
                hits += hit;
                int same = hit == want[i].hit &&
                           (!hit || (!memcmp(&got[i].t, &want[i].t, 4) &&
                                     !memcmp(&got[i].u, &want[i].u, 4) &&
                                     !memcmp(&got[i].v, &want[i].v, 4) &&
                                     got[i].prim == want[i].prim && got[i].inst == want[i].inst));
                if (!same && !differ++) first = i;
            }
            /* Any hit: whether the ray hits (which hit in range may differ). */
            if (any) {
                differ = 0;
                for (int i = 0; i < N; i++) differ += (got[i].prim != RT_NO_HIT) != want[i].hit;
            }
            CHECK_MSG(differ == 0,
                      "kd stack with %u shared cells, %s: %d of %d hits differ (first ray %d)",
                      cells[c], any ? "any hit" : "closest", differ, N, first);
            CHECK_MSG(hits > N / 10, "kd stack: only %d of %d rays hit", hits, N);
        }
    }
    free(rays);
    free(want);
    free(rd);
    free(got);
    rt_scene_destroy(s);
}

/* The GLSL soft maths against the C header, bit for bit. */
static void check_soft_math(void) {
    uint32_t sp[512];
    int ns = sm_specials(sp);
    size_t n = (size_t)ns * (size_t)ns + 100000;
    uint32_t *in = malloc(n * 4 * sizeof *in), *out = malloc(n * 3 * sizeof *out);
    CHECK(in && out);
    if (!in || !out) {
        free(in);
        free(out);
        return;
    }
    size_t k = 0;
    for (int i = 0; i < ns; i++)
        for (int j = 0; j < ns; j++, k++) {
            uint32_t *q = in + 4 * k;
            q[0] = sp[i], q[1] = sp[j], q[2] = sp[(i * 7 + j) % ns], q[3] = sp[(j * 13 + i) % ns];
        }
    uint64_t seed = 0x243f6a8885a308d3ull;
    for (; k < n; k++) {
        uint32_t *q = in + 4 * k;
        if (k % 3 == 0) {
            sm_dop_quad(&seed, q);
        } else if (k % 3 == 1) {
            sm_div_pair(&seed, &q[0], &q[1]);
            q[2] = sm_operand(&seed), q[3] = sm_operand(&seed);
        } else {
            for (int j = 0; j < 4; j++) q[j] = sm_rand(&seed);
        }
    }
    for (int ftz = 0; ftz <= 1; ftz++) {
        rt_error err;
        memset(&err, 0, sizeof err);
        rt_status st = rt_vk_soft_math_run(NULL, in, n, ftz, out, &err);
        CHECK_MSG(st == RT_OK, "soft maths on the device: %s", err.message);
        if (st != RT_OK) continue;
        long bad = 0;
        for (size_t i = 0; i < n; i++) {
            const uint32_t *q = in + 4 * i;
            uint32_t want[3] = {rt_sm_div_bits_(q[0], q[1], ftz), rt_sm_sqrt_bits_(q[0], ftz),
                                rt_sm_dop_bits_(q[0], q[1], q[2], q[3], ftz)};
            static const char *const fn[3] = {"div", "sqrt", "diff_of_products"};
            for (int j = 0; j < 3; j++)
                if (out[3 * i + j] != want[j] && bad++ < 5)
                    CHECK_MSG(0, "%s%s(%08x, %08x, %08x, %08x): glsl %08x, C %08x", fn[j],
                              ftz ? "_ftz" : "", q[0], q[1], q[2], q[3], out[3 * i + j], want[j]);
        }
        CHECK_MSG(bad == 0, "soft maths%s: %ld results differ from rt_soft_math.h",
                  ftz ? " (ftz)" : "", bad);
        printf("soft maths%s: %zu operand sets x 3 functions, %ld differ\n", ftz ? " (ftz)" : "", n,
               bad);
    }
    free(in);
    free(out);
}
/* The driver's loop limit (rt_vk_main.comp's canary). A stack of 3000 thin
 * triangles, 0.01 across, in the planes x = 0.995^k, and 3000 rays from
 * x = -1 at a slant: each ray opens hundreds of boxes and tests thousands
 * of triangles, and the rays of a SIMD group diverge. Lavapipe lost 130 of
 * 3000 closest hits on this input when every software division was a loop
 * of 24 iterations: the group spent the driver's 65535 loop iterations and
 * the traversal loops stopped early. The same triangles all in the plane
 * x = 0 (hits tied at t = 1, the lowest triangle wins): 810 of 3000
 * differed there. */
static rt_scene *slab_scene(int tied) {
    enum { TRIS = 3000 };
    float *pos = malloc(sizeof(float) * 9 * TRIS);
    CHECK(pos != NULL);
    if (!pos) return NULL;
    float x = 1.0f;
    for (int i = 0; i < TRIS; i++, x *= 0.995f) {
        /* tied: every triangle in the plane x = 0, sizes 0.01 .. 0.02, so
         * that each ray has hundreds of hits at exactly one t. */
        float px = tied ? 0.0f : x, w = tied ? 0.01f + 0.01f * (float)i / TRIS : 0.01f;
        const float v[9] = {px, 0.0f, 0.0f, px, w, 0.0f, px, 0.0f, w};
        memcpy(pos + 9 * i, v, sizeof v);
    }
    rt_scene *s = test_soup_scene(pos, TRIS);
    free(pos);
    return s;
}

static float slab_unit(uint32_t *seed) {
    *seed = *seed * 1664525u + 1013904223u;
    return (float)(*seed >> 8) * (1.0f / 16777216.0f);
}

/* Every ray's hit on the slabs equals the oracle's; then, on lavapipe, the
 * canary's fault injection: with 65,000 loop iterations spent before each
 * item, a trace that may not re-run the marked items must fail with the
 * reason (the canary saw the cut), and one that may must give the oracle's
 * hits and image. */
static void check_loop_limit(const rt_vk_device_info *dev) {
    enum { N = 3000 };
    rt_scene *s = slab_scene(0), *tied = slab_scene(1);
    rt_ray *rays = malloc(sizeof *rays * N);
    CHECK(rays != NULL);
    uint32_t seed = 777u;
    for (int i = 0; s && rays && i < N; i++) {
        rt_ray r = {{-1.0f, 0.01f * slab_unit(&seed), 0.01f * slab_unit(&seed)},
                    {1.0f, 0.004f * slab_unit(&seed) - 0.002f, 0.004f * slab_unit(&seed) - 0.002f},
                    0.0f,
                    INFINITY};
        rays[i] = r;
    }
    for (int any = 0; any <= 1 && s && rays; any++) {
        char first[400] = "";
        int hits;
        int differ = differing_hits(cpu_r, vk_r, s, rays, N, any, &hits, first, sizeof first);
        CHECK_MSG(differ == 0, "slabs %s: %d of %d hits differ; first: %s",
                  any ? "any-hit" : "closest", differ, N, first);
        CHECK_MSG(hits > N / 3, "slabs: only %d of %d rays hit: a weak test", hits, N);
        if (!tied) continue;
        differ = differing_hits(cpu_r, vk_r, tied, rays, N, any, &hits, first, sizeof first);
        CHECK_MSG(differ == 0, "tied slabs %s: %d of %d hits differ; first: %s",
                  any ? "any-hit" : "closest", differ, N, first);
        CHECK_MSG(hits > N / 3, "tied slabs: only %d of %d rays hit: a weak test", hits, N);
    }
    int llvmpipe = strstr(dev->name, "llvmpipe") != NULL;
    if (!llvmpipe)
        printf("loop-limit fault injection: the cut and its error are lavapipe's (gallivm's); "
               "device '%s' has no such limit, so only the re-run results are checked\n",
               dev->name);
    if (s && rays && llvmpipe) {
        rt_vk_test_loop_limit(65000u, 0);
        rt_hit *h = malloc(sizeof *h * N);
        rt_trace_options q = {0, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO, NULL, NULL};
        CHECK(h != NULL);
        if (h) {
            CHECK(rt_trace_rays(vk_r, s, rays, N, h, &q) == RT_ERROR_BACKEND);
            CHECK_CONTAINS(rt_renderer_error(vk_r), "needs more loop iterations");
        }
        free(h);
    }
    rt_vk_test_loop_limit(65000u, 1);
    for (int any = 0; any <= 1 && s && rays; any++) {
        char first[400] = "";
        int hits;
        int differ = differing_hits(cpu_r, vk_r, s, rays, N, any, &hits, first, sizeof first);
        CHECK_MSG(differ == 0, "slabs after re-runs %s: %d of %d hits differ; first: %s",
                  any ? "any-hit" : "closest", differ, N, first);
    }
    rt_scene *c = test_builtin_scene("cornell", 96, 54);
    if (c) {
        rt_framebuffer a, b;
        rt_render_stats st;
        memset(&st, 0, sizeof st);
        CHECK(render_with(cpu_r, c, RT_AOV_NONE, 0, RT_TRI_TEST_WATERTIGHT, &a, NULL) == RT_OK);
        CHECK(render_with(vk_r, c, RT_AOV_NONE, 0, RT_TRI_TEST_WATERTIGHT, &b, &st) == RT_OK);
        CHECK(same_pixels("cornell", "image after re-runs", &a, &b));
        if (llvmpipe) CHECK_CONTAINS(st.kernels, "re-run alone");
        rt_framebuffer_free(&a);
        rt_framebuffer_free(&b);
        rt_scene_destroy(c);
    }
    rt_vk_test_loop_limit(0u, 1);
    free(rays);
    if (s) rt_scene_destroy(s);
    if (tied) rt_scene_destroy(tied);
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
    printf("device: %s (%s, %s)\n", dev.name, dev.driver, rt_vk_exactness_note(&dev, 0));
    check_soft_math();
    cpu_r = test_renderer("cpu", 0);
    vk_r = test_renderer("vulkan", 0);
    if (!cpu_r || !vk_r) return TEST_END();
    static const char *const shipped[] = {"cornell", "keyframes"};
    for (int i = 0; i < 2; i++) check_scene(shipped[i]);
    check_uploads();
    check_denormals(&dev);
    for (int i = 0; i < 2; i++) {
        check_kd_scene(shipped[i], RT_ACCEL_KD, 1);
        check_kd_scene(shipped[i], RT_ACCEL_KD_BINNED, 0);
    }
    check_kd_stack();
    check_loop_limit(&dev);
    /* A device that does not exist is an error with a reason. */
    rt_scene *s = test_builtin_scene("cornell", 32, 18);
    rt_renderer *bad = test_renderer("vulkan:99", 0);
    if (s && bad) {
        rt_framebuffer fb;
        CHECK(render_with(bad, s, RT_AOV_NONE, 0, RT_TRI_TEST_WATERTIGHT, &fb, NULL) ==
              RT_ERROR_INVALID_ARGUMENT);
        CHECK_CONTAINS(rt_renderer_error(bad), "no Vulkan device 99");
    }
    if (s) rt_scene_destroy(s);
    return TEST_END();
#endif
}
