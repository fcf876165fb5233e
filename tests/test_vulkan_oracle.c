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

static void check_hits(const char *name, rt_scene *s) {
    const rt_flat *flat = test_layout(s, 0);
    if (!flat) return;
    const rt_scene_header *h = &flat->hdr;
    float lo[3], hi[3];
    CHECK(rt_scene_bounds(s, lo, hi));
    enum { N = 20000 };
    rt_ray *rays = malloc(sizeof *rays * N);
    rt_hit *a = malloc(sizeof *a * N), *b = malloc(sizeof *b * N);
    CHECK(rays && a && b);
    for (int i = 0; rays && i < N; i++) {
        rt_ray_d r;
        oracle_ray(h, lo, hi, i, &r);
        memcpy(rays[i].org, r.org, sizeof r.org);
        memcpy(rays[i].dir, r.dir, sizeof r.dir);
        rays[i].tmin = r.tmin;
        rays[i].tmax = r.tmax;
    }
    for (int any = 0; any <= 1 && rays && a && b; any++) {
        rt_trace_options q = {any, RT_TRI_TEST_WATERTIGHT};
        CHECK(rt_trace_rays(cpu_r, s, rays, N, a, &q) == RT_OK);
        rt_status st = rt_trace_rays(vk_r, s, rays, N, b, &q);
        CHECK_MSG(st == RT_OK, "%s", rt_renderer_error(vk_r));
        int hits = 0;
        for (int i = 0; i < N && st == RT_OK; i++) {
            hits += a[i].hit;
            if (a[i].hit != b[i].hit || memcmp(&a[i].t, &b[i].t, 4) ||
                memcmp(&a[i].u, &b[i].u, 4) || memcmp(&a[i].v, &b[i].v, 4) ||
                a[i].prim != b[i].prim || a[i].inst != b[i].inst) {
                CHECK_MSG(0,
                          "%s %s ray %d: cpu hit %d t %.9g u %.9g v %.9g prim %u inst %u; vulkan "
                          "hit %d t %.9g u %.9g v %.9g prim %u inst %u",
                          name, any ? "any-hit" : "closest", i, a[i].hit, (double)a[i].t,
                          (double)a[i].u, (double)a[i].v, a[i].prim, a[i].inst, b[i].hit,
                          (double)b[i].t, (double)b[i].u, (double)b[i].v, b[i].prim, b[i].inst);
                break;
            }
        }
        CHECK_MSG(hits > N / 10, "%s: only %d of %d rays hit: a weak test", name, hits, N);
    }
    free(rays);
    free(a);
    free(b);
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
    printf("device: %s (%s, %s)\n", devs[pick].name, devs[pick].driver,
           rt_vk_exactness_note(&devs[pick]));
    free(devs);
    check_soft_math();
    cpu_r = test_renderer("cpu", 0);
    vk_r = test_renderer("vulkan", 0);
    if (!cpu_r || !vk_r) return TEST_END();
    static const char *const shipped[] = {"cornell", "keyframes"};
    for (int i = 0; i < 2; i++) check_scene(shipped[i]);
    check_uploads();
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
