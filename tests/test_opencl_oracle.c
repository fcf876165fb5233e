/* SPDX-License-Identifier: Apache-2.0 */
/* test_opencl_oracle.c - the OpenCL backend against the CPU oracle: on every
 * built-in scene, the hit buffers of ray queries (t, u, v as bits, prim,
 * inst; closest and any hit) and the rendered images (float framebuffer of
 * the image and of every AOV, and the 8-bit PNG) are identical. The first
 * difference is reported with both values. Also: uploads on later frames are
 * only what changed, and a bad --device is an error. Skips only when there is
 * no OpenCL device (or the build has no OpenCL). The wavefront (reflection
 * and refraction as passes over ray queues) is checked on cornell, also with
 * queues too small so every tile takes the fallback. Extra build options
 * (device_options, the speed-versus-error study) reach the compiler, are
 * reported and void the exactness promise, and the program cache keys on them:
 * the default build after a variant is the oracle's bits again.
 *
 * On a CPU device frames and closest-hit ray queries run the packet kernels
 * (kernels/rt_ray_packet.cl; the hit buffers above check rt_k_packet_trace): its
 * images and AOVs are checked in Whitted and direct mode, at an odd size
 * (partial blocks), with every triangle test and every block size; its test
 * counters count per lane (they differ from the oracle's), so they are
 * checked for consistency instead, and exactly with the one-ray kernels (rt_opencl_tuning)
 * (the one-ray kernels, which must stay exact too). All of it runs again with
 * every static mesh a kd-tree (the packet kernel's pk_kd_mesh), but for the
 * other triangle tests, plus 20,000 rays from the half-unit grid along -1, 0
 * and 1 (in, along and from split planes: grid_ray).
 *
 * Maths profiles (docs/PORTABLE_MATH.md): RT_TEST_DEVICE_MATH=portable runs
 * the OpenCL side in the portable profile (software divide and sqrt) and
 * RT_TEST_DENORMALS=flush both sides with denormals flushed (the oracle with
 * FTZ/DAZ); ctest runs those as test_opencl_oracle_portable and
 * test_opencl_oracle_portable_flush: every AOV of every built-in and shipped
 * scene with the packet and the one-ray kernels, and 20,000 ray queries per
 * scene; the built-in scenes again with kd meshes, and grid-aligned rays. Then a scene 1e-13 across
 * traced with rays of unit directions (t's numerator in the denormal range), on which the flushing
 * and the IEEE oracle disagree (so the denormal policy is seen to matter), must still match in both
 * policies. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt.h"
#include "scene/scene_builtin.h"
#ifdef RT_HAVE_OPENCL
#include "opencl/cl_device.h"
#include "formats/image.h"
#include "oracle_util.h"
#include "layout/flat.h"
#include "scene/scene.h"

/* The library's error of the last call a check prints. */
static rt_error lib_err;

static const char *const aov_names[] = {"image",  "depth",    "primid",  "instid",
                                        "normal", "boxtests", "tritests"};
static const char *const tri_names[] = {"watertight", "moller", "pluecker", "badouel"};

/* How a frame is rendered: Whitted or direct only, and the triangle test. */
typedef struct mode {
    int direct;
    rt_triangle_test tri;
} mode;
static const mode whitted = {0, RT_TRI_TEST_WATERTIGHT};

/* The OpenCL kernel choices the checks run with now (rt_opencl_tuning). */
static rt_opencl_tuning cl_tune;

/* The maths profile of the OpenCL side and the denormal policy of both
 * (RT_TEST_DEVICE_MATH, RT_TEST_DENORMALS). */
static rt_device_math cl_math = RT_DEVICE_MATH_AUTO;
static rt_denormals denormals = RT_DENORMALS_PRESERVE;

/* The renderer of a backend: "cpu", or "opencl" with the current kernel
 * choices (one renderer per choice, kept: its device state is reused). */
static rt_renderer *renderer_for(const char *backend) {
    if (strcmp(backend, "cpu") == 0 && denormals == RT_DENORMALS_FLUSH) {
        static rt_renderer *flushing;
        if (!flushing) {
            rt_renderer_options o = rt_renderer_options_default();
            o.denormals = denormals;
            rt_error err;
            flushing = test_renderer_with(&o, &err);
            CHECK_MSG(flushing != NULL, "flushing cpu renderer: %s", err.message);
        }
        return flushing;
    }
    if (strcmp(backend, "opencl") != 0) return test_renderer(backend, 0);
    static struct {
        rt_opencl_tuning tune;
        rt_renderer *r;
    } made[8];
    static int count;
    for (int i = 0; i < count; i++)
        if (memcmp(&made[i].tune, &cl_tune, sizeof cl_tune) == 0) return made[i].r;
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = "opencl";
    o.opencl = cl_tune;
    o.device_math = cl_math;
    o.denormals = denormals;
    rt_error err;
    rt_renderer *r = count < 8 ? test_renderer_with(&o, &err) : NULL;
    CHECK_MSG(r != NULL, "opencl renderer: %s", count < 8 ? err.message : "too many");
    if (r) {
        made[count].tune = cl_tune;
        made[count++].r = r;
    }
    return r;
}

/* The last error of the renderer of a backend. */
static const char *error_of(const char *backend) {
    rt_renderer *r = renderer_for(backend);
    return r ? rt_renderer_error(r) : "no renderer";
}

/* Renders with a backend at a small size; returns the status. */
static rt_status render_mode(rt_scene *s, const char *backend, rt_aov aov, mode m,
                             rt_framebuffer *fb, rt_render_stats *stats) {
    rt_render_options o = rt_render_options_default();
    o.aov = aov;
    o.stats = stats;
    o.direct_only = m.direct;
    o.tri_test = m.tri;
    rt_renderer *r = renderer_for(backend);
    return r ? rt_render(r, s, &o, fb) : RT_ERROR_BACKEND;
}

static rt_status render(rt_scene *s, const char *backend, rt_aov aov, rt_framebuffer *fb,
                        rt_render_stats *stats) {
    return render_mode(s, backend, aov, whitted, fb, stats);
}

/* The kernels the checks render with on the default device: the packet
 * kernel on a CPU device unless the one-ray kernels are chosen. */
static int expect_packet(void) {
    static int cpu = -1;
    if (cpu < 0) {
        rt_cl_device_info *devs;
        int count;
        cpu = 0;
        if (rt_cl_devices(&devs, &count, &lib_err) == RT_OK) {
            int pick = rt_cl_select(devs, count, NULL, &lib_err);
            cpu = pick >= 0 && devs[pick].cpu;
            free(devs);
        }
    }
    return cpu && !cl_tune.one_ray_kernels;
}

/* Bitwise comparison of two framebuffers; reports the first difference. */
static void same_pixels(const char *scene, const char *what, const rt_framebuffer *a,
                        const rt_framebuffer *b) {
    CHECK_MSG(a->width == b->width && a->height == b->height && a->channels == b->channels,
              "%s %s: sizes differ", scene, what);
    size_t n = (size_t)a->width * a->height * a->channels;
    for (size_t i = 0; i < n; i++) {
        if (memcmp(&a->pixels[i], &b->pixels[i], sizeof(float)) != 0) {
            size_t px = i / (size_t)a->channels;
            CHECK_MSG(
                0, "%s %s: first difference at pixel (%zu, %zu) channel %zu: cpu %.9g opencl %.9g",
                scene, what, px % (size_t)a->width, px / (size_t)a->width, i % (size_t)a->channels,
                (double)a->pixels[i], (double)b->pixels[i]);
            return;
        }
    }
    test_checks++;
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

/* The packet kernel's counter AOV: one value per pixel, a whole number, at
 * least one box test per pixel (the primary ray's root), and the pixels add
 * up to the frame's count in the statistics (counted per lane). */
static void check_counter_aov(const char *name, const char *what, const rt_framebuffer *fb,
                              uint64_t total, int boxes) {
    size_t n = (size_t)fb->width * fb->height;
    double sum = 0.0;
    size_t bad = n;
    for (size_t i = 0; i < n && bad == n; i++) {
        float v = fb->pixels[i];
        if (!(v >= (boxes ? 1.0f : 0.0f)) || v != floorf(v)) bad = i;
        sum += (double)v;
    }
    CHECK_MSG(fb->channels == 1 && bad == n, "%s %s: pixel %zu is %g", name, what, bad,
              bad < n ? (double)fb->pixels[bad] : 0.0);
    CHECK_MSG(sum == (double)total, "%s %s: pixels add up to %.0f, the statistics say %llu", name,
              what, sum, (unsigned long long)total);
}

/* Every AOV and the image (with its 8-bit PNG) in mode m against the
 * oracle; with the packet kernel the counter AOVs are checked for
 * consistency (see check_counter_aov) and the rays traced exactly. */
static void check_images_mode(const char *name, rt_scene *s, mode m) {
    int packet = expect_packet();
    char label[160];
    for (int aov = RT_AOV_NONE; aov <= RT_AOV_TRI_TESTS; aov++) {
        rt_framebuffer cpu, cl;
        rt_render_stats st, cs;
        CHECK(render_mode(s, "cpu", (rt_aov)aov, m, &cpu, &cs) == RT_OK);
        rt_status status = render_mode(s, "opencl", (rt_aov)aov, m, &cl, &st);
        CHECK_MSG(status == RT_OK, "%s: %s", name, error_of("opencl"));
        if (status != RT_OK) {
            rt_framebuffer_free(&cpu);
            continue;
        }
        snprintf(label, sizeof label, "%s (%s%s, %dx%d, %s)", aov_names[aov],
                 m.direct ? "direct" : "Whitted", packet ? ", packet" : "", cpu.width, cpu.height,
                 tri_names[m.tri]);
        CHECK(strcmp(st.backend, "opencl") == 0 && st.device[0] && st.exact);
        CHECK_MSG(
            strcmp(st.math_profile, cl_math == RT_DEVICE_MATH_PORTABLE ? "portable" : "native") ==
                    0 &&
                strcmp(st.denormals, denormals == RT_DENORMALS_FLUSH ? "flush" : "preserve") == 0,
            "%s: profile %s, denormals %s", name, st.math_profile, st.denormals);
        CHECK(st.primary_rays == (uint64_t)cpu.width * (uint64_t)cpu.height);
        CHECK_MSG((strncmp(st.kernels, "packet", 6) == 0) == packet, "%s %s: kernels '%s'", name,
                  label, st.kernels);
        CHECK_EQ_INT((long long)st.rays, (long long)cs.rays);
        if (packet && (aov == RT_AOV_BOX_TESTS || aov == RT_AOV_TRI_TESTS))
            check_counter_aov(name, label, &cl,
                              aov == RT_AOV_BOX_TESTS ? st.box_tests : st.tri_tests,
                              aov == RT_AOV_BOX_TESTS);
        else
            same_pixels(name, label, &cpu, &cl);
        if (aov == RT_AOV_NONE) { /* the 8-bit image too */
            char pa[64], pb[64];
            snprintf(pa, sizeof pa, "%s_cpu.png", name);
            snprintf(pb, sizeof pb, "%s_cl.png", name);
            for (char *c = pa; *c; c++) *c = *c == '/' ? '_' : *c;
            for (char *c = pb; *c; c++) *c = *c == '/' ? '_' : *c;
            char a[512], b[512];
            snprintf(a, sizeof a, "%s", test_write_temp(pa, ""));
            snprintf(b, sizeof b, "%s", test_write_temp(pb, ""));
            rt_image ia = {cpu.width, cpu.height, 3, cpu.pixels};
            rt_image ib = {cl.width, cl.height, 3, cl.pixels};
            rt_error err;
            CHECK(rt_image_write(a, &ia, &err) == RT_OK);
            CHECK(rt_image_write(b, &ib, &err) == RT_OK);
            CHECK_MSG(same_file(a, b), "%s: the 8-bit PNGs differ", name);
        }
        rt_framebuffer_free(&cpu);
        rt_framebuffer_free(&cl);
    }
}

static void check_images(const char *name, rt_scene *s) {
    check_images_mode(name, s, whitted);
}

/* The image alone (Whitted and direct) and the depth AOV in mode m. */
static void check_image_mode(const char *name, rt_scene *s, mode m) {
    for (int aov = RT_AOV_NONE; aov <= RT_AOV_DEPTH; aov++) {
        rt_framebuffer cpu, cl;
        CHECK(render_mode(s, "cpu", (rt_aov)aov, m, &cpu, NULL) == RT_OK);
        rt_status status = render_mode(s, "opencl", (rt_aov)aov, m, &cl, NULL);
        CHECK_MSG(status == RT_OK, "%s: %s", name, error_of("opencl"));
        if (status == RT_OK) {
            char label[160];
            snprintf(label, sizeof label, "%s (%s, %dx%d, %s, packet lanes %d)", aov_names[aov],
                     m.direct ? "direct" : "Whitted", cpu.width, cpu.height, tri_names[m.tri],
                     cl_tune.packet_lanes);
            same_pixels(name, label, &cpu, &cl);
            rt_framebuffer_free(&cl);
        }
        rt_framebuffer_free(&cpu);
    }
}

/* The packet kernel in every configuration at an odd size (97x61: blocks cut
 * at the right and bottom edges), with an object turned about an oblique
 * axis and a second, coloured light: every AOV in direct mode; image and depth
 * with every triangle test, both modes; every block size (4, 8, 16 lanes).
 * Then the one-ray kernels (rt_opencl_tuning.one_ray_kernels): every AOV including
 * the counters exactly, both modes. */
/* Turns object obj by 0.5 rad about the oblique axis (1, 2, 3) through c: an
 * instance transform with no zero entry (so a sum in another order shows). */
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

/* all_tests: also every triangle test (skipped for kd meshes: the leaves'
 * triangle tests are the BVH path's). */
static void check_packet(const char *name, rt_scene *s, int all_tests) {
    /* An object turned about an oblique axis (cornell: the mirror sphere,
     * which has vertex normals), and a second, coloured light: two lights
     * per pixel, light colours other than 1 (so a product in another order
     * shows). Kept for the later checks of this scene, which compare with the
     * oracle too. */
    int cornell = strncmp(name, "cornell", 7) == 0; /* also "cornell (kd)" */
    const float centre_cornell[3] = {-0.8f, 0.4f, -0.2f}, centre_keyframes[3] = {0.5f, 1.0f, 0.0f};
    oblique_turn(s, cornell ? 4 : 1, cornell ? centre_cornell : centre_keyframes);
    float lo[3], hi[3], pos[3];
    CHECK(rt_scene_bounds(s, lo, hi));
    for (int k = 0; k < 3; k++) pos[k] = lo[k] + (hi[k] - lo[k]) * (k == 1 ? 0.85f : 0.3f);
    const float color[3] = {0.7f, 0.45f, 0.9f};
    uint32_t light;
    CHECK(rt_light_add(s, pos, color, &light) == RT_OK);
    rt_camera cam, odd;
    rt_camera_get(s, &cam);
    odd = cam;
    odd.width = 97;
    odd.height = 61;
    CHECK(rt_camera_set(s, &odd) == RT_OK);
    mode direct = {1, RT_TRI_TEST_WATERTIGHT};
    check_images_mode(name, s, direct);
    check_images_mode(name, s, whitted);
    for (int t = RT_TRI_TEST_MOLLER; t <= RT_TRI_TEST_BADOUEL && all_tests; t++)
        for (int d = 0; d < 2; d++) check_image_mode(name, s, (mode){d, (rt_triangle_test)t});
    static const int lanes[] = {4, 8};
    for (int i = 0; i < 2; i++) {
        cl_tune.packet_lanes = lanes[i];
        check_image_mode(name, s, direct);
        check_image_mode(name, s, whitted);
        cl_tune.packet_lanes = 0;
    }
    if (expect_packet()) {
        cl_tune.one_ray_kernels = 1;
        check_images_mode(name, s, direct);
        check_images_mode(name, s, whitted);
        cl_tune.one_ray_kernels = 0;
    }
    CHECK(rt_camera_set(s, &cam) == RT_OK);
}

/* The image of a scene with reflection and refraction goes through the
 * wavefront passes (ray queues between launches): the same float pixels and
 * ray/test counts as the oracle; with queues of one entry every tile
 * overflows and is redone with the stack kernel, still the same bits. */
static void check_wavefront(rt_scene *s) {
    rt_framebuffer cpu, cl;
    rt_render_stats cs, st;
    /* A CPU device runs the packet kernel, not the wavefront: force it. */
    cl_tune.one_ray_kernels = 1;
    CHECK(render(s, "cpu", RT_AOV_NONE, &cpu, &cs) == RT_OK);
    for (int forced = 0; forced < 2; forced++) {
        if (forced) cl_tune.wave_queue_cap = 1;
        rt_status status = render(s, "opencl", RT_AOV_NONE, &cl, &st);
        CHECK_MSG(status == RT_OK, "wavefront: %s", error_of("opencl"));
        cl_tune.wave_queue_cap = 0;
        if (status != RT_OK) continue;
        CHECK_MSG(st.wave_tiles > 0, "cornell: the image did not use the wavefront");
        if (forced)
            CHECK_EQ_INT((long long)st.wave_fallbacks, (long long)st.wave_tiles);
        else
            CHECK_EQ_INT((long long)st.wave_fallbacks, 0);
        CHECK_EQ_INT((long long)st.rays, (long long)cs.rays);
        CHECK_EQ_INT((long long)st.box_tests, (long long)cs.box_tests);
        CHECK_EQ_INT((long long)st.tri_tests, (long long)cs.tri_tests);
        same_pixels("cornell", forced ? "image (queues overflowing)" : "image (wavefront)", &cpu,
                    &cl);
        rt_framebuffer_free(&cl);
    }
    rt_framebuffer_free(&cpu);
    cl_tune.one_ray_kernels = 0;
}

/* Makes ray i of a test over a scene of bounds lo..hi. */
typedef void (*ray_maker)(const rt_scene_header *h, const float lo[3], const float hi[3], int i,
                          rt_ray *r);

/* Rays from inside the bounds in directions of unit size, whatever the
 * scene's size (the denormal scene's edge functions times z then fall below
 * the smallest normal float). */
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

/* Even i: a ray from a point of the half-unit grid (on the built-in scenes'
 * walls and on many kd split planes) along directions of -1, 0 and 1 (in
 * split planes, parallel to them, starting on them); odd i: oracle_ray. */
static void grid_ray(const rt_scene_header *h, const float lo[3], const float hi[3], int i,
                     rt_ray *r) {
    if (i % 2) {
        oracle_ray(h, lo, hi, i, r);
        return;
    }
    static const float org[6] = {-1.0f, -0.5f, 0.0f, 0.5f, 1.0f, 1.5f}, dir[4] = {-1, 0, 0, 1};
    for (int k = 0; k < 3; k++) {
        r->org[k] = org[(int)(oracle_rnd() * 6.0f) % 6];
        r->dir[k] = dir[(int)(oracle_rnd() * 4.0f) % 4];
    }
    if (r->dir[0] == 0.0f && r->dir[1] == 0.0f && r->dir[2] == 0.0f) r->dir[2] = -1.0f;
    r->tmin = 0.0f;
    r->tmax = INFINITY;
}

static void check_hits_with(const char *name, rt_scene *s, ray_maker make) {
    const rt_flat *flat = test_layout(s, 0);
    if (!flat) return;
    const rt_scene_header *h = &flat->hdr;
    float lo[3], hi[3];
    CHECK(rt_scene_bounds(s, lo, hi));
    enum { N = 20000 };
    rt_ray *rays = malloc(sizeof *rays * N);
    rt_hit *a = malloc(sizeof *a * N), *b = malloc(sizeof *b * N);
    for (int i = 0; i < N; i++) {
        rt_ray r;
        make(h, lo, hi, i, &r);
        memcpy(rays[i].org, r.org, sizeof r.org);
        memcpy(rays[i].dir, r.dir, sizeof r.dir);
        rays[i].tmin = r.tmin;
        rays[i].tmax = r.tmax;
    }
    for (int any = 0; any <= 1; any++) {
        rt_trace_options q = {any, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO, NULL, NULL};
        CHECK(rt_trace_rays(renderer_for("cpu"), s, rays, N, a, &q) == RT_OK);
        rt_status st = rt_trace_rays(renderer_for("opencl"), s, rays, N, b, &q);
        CHECK_MSG(st == RT_OK, "%s", error_of("opencl"));
        int hits = 0;
        for (int i = 0; i < N && st == RT_OK; i++) {
            hits += a[i].hit;
            if (a[i].hit != b[i].hit || memcmp(&a[i].t, &b[i].t, 4) ||
                memcmp(&a[i].u, &b[i].u, 4) || memcmp(&a[i].v, &b[i].v, 4) ||
                a[i].prim != b[i].prim || a[i].inst != b[i].inst) {
                CHECK_MSG(0,
                          "%s %s ray %d: cpu hit %d t %.9g u %.9g v %.9g prim %u inst %u; opencl "
                          "hit %d t %.9g u %.9g v %.9g prim %u inst %u",
                          name, any ? "any-hit" : "closest", i, a[i].hit, (double)a[i].t,
                          (double)a[i].u, (double)a[i].v, a[i].prim, a[i].inst, b[i].hit,
                          (double)b[i].t, (double)b[i].u, (double)b[i].v, b[i].prim, b[i].inst);
                break;
            }
        }
        /* Flushed, most of the denormal scene's edge functions are zero. */
        int want = denormals == RT_DENORMALS_FLUSH && strstr(name, "denormal") ? N / 1000 : N / 10;
        CHECK_MSG(hits > want, "%s: only %d of %d rays hit: a weak test", name, hits, N);
    }
    free(rays);
    free(a);
    free(b);
}

static void check_hits(const char *name, rt_scene *s) {
    check_hits_with(name, s, oracle_ray);
}

/* device_options: appended to the build (a bad option fails the build and
 * the error names it, for renders and ray queries), reported in the
 * statistics with exact 0; the cache keys on them, so the exact build comes
 * back, bit for bit, after a variant. On PoCL -cl-fast-relaxed-math changes
 * pixels (it does not have to elsewhere: then only a note is printed). */
static void check_device_options(void) {
    rt_scene *s = test_builtin_scene("cornell", 96, 54);
    if (!s) return;
    rt_framebuffer cpu, fast, exact, bad;
    rt_render_stats st;
    CHECK(render(s, "cpu", RT_AOV_NONE, &cpu, NULL) == RT_OK);
    rt_render_options o = rt_render_options_default();
    o.stats = &st;
    rt_renderer_options ro = rt_renderer_options_default();
    ro.backend = "opencl";
    ro.device_options = "-cl-fast-relaxed-math"; /* a study variant's option */
    rt_error err;
    rt_renderer *variant = test_renderer_with(&ro, &err);
    CHECK_MSG(variant != NULL, "%s", err.message);
    rt_status status = variant ? rt_render(variant, s, &o, &fast) : RT_ERROR_BACKEND;
    CHECK_MSG(status == RT_OK, "fast-relaxed-math option: %s",
              variant ? rt_renderer_error(variant) : "");
    if (status != RT_OK) {
        rt_framebuffer_free(&cpu);
        rt_scene_destroy(s);
        return;
    }
    CHECK(st.exact == 0);
    CHECK_CONTAINS(st.device_options, "-cl-fast-relaxed-math");
    size_t n = (size_t)cpu.width * cpu.height * 3, differ = 0;
    for (size_t i = 0; i < n; i++) differ += memcmp(&cpu.pixels[i], &fast.pixels[i], 4) != 0;
    if (!differ) printf("note: this device's fast-relaxed-math build gives the oracle's bits\n");
    if (strstr(st.device, "pthread") || strstr(st.device, "cpu"))
        CHECK_MSG(differ > 0, "PoCL: the fast-relaxed-math option changed no channel");
    /* The exact build again, after the variant on the same device: PoCL's
     * program cache must not hand back the variant. */
    CHECK(rt_render(renderer_for("opencl"), s, &o, &exact) == RT_OK);
    CHECK(st.exact == 1 && st.device_options[0] == 0);
    same_pixels("cornell", "image (exact build after a study option variant)", &cpu, &exact);
    /* The options reach the compiler: an unknown one fails with its name. */
    ro.device_options = "-DRT_STUDY_OPTION=1 -cl-no-such-option";
    rt_renderer *broken = test_renderer_with(&ro, &err);
    CHECK_MSG(broken != NULL, "%s", err.message);
    if (broken) {
        CHECK(rt_render(broken, s, &o, &bad) == RT_ERROR_BACKEND);
        CHECK_CONTAINS(rt_renderer_error(broken), "-cl-no-such-option");
        rt_ray ray = {{0, 1, 3}, {0, 0, -1}, 0, INFINITY};
        rt_hit hit;
        CHECK(rt_trace_rays(broken, s, &ray, 1, &hit, NULL) == RT_ERROR_BACKEND);
        CHECK_CONTAINS(rt_renderer_error(broken), "-cl-no-such-option");
        CHECK(rt_trace_rays(renderer_for("opencl"), s, &ray, 1, &hit, NULL) == RT_OK && hit.hit);
    }
    /* Too long an option string is refused before any build. */
    char lengthy[400];
    memset(lengthy, 'x', sizeof lengthy - 1);
    lengthy[0] = '-';
    lengthy[sizeof lengthy - 1] = 0;
    ro.device_options = lengthy;
    rt_renderer *refused = NULL;
    CHECK(rt_renderer_create(&ro, &refused, &err) == RT_ERROR_INVALID_ARGUMENT && !refused);
    CHECK_CONTAINS(err.message, "longer than");
    rt_framebuffer_free(&cpu);
    rt_framebuffer_free(&fast);
    rt_framebuffer_free(&exact);
    rt_scene_destroy(s);
}

/* Frame 2 uploads nothing; after moving an object only the per-frame part
 * (object BVH, instances, header), and the image is still the oracle's. */
static void check_uploads(void) {
    rt_scene *s;
    rt_error err;
    CHECK(rt_scene_builtin("keyframes", &s, &err) == RT_OK);
    rt_camera cam;
    rt_camera_get(s, &cam);
    cam.width = 96;
    cam.height = 54;
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    rt_framebuffer fb;
    rt_render_stats first, again, moved;
    CHECK(render(s, "opencl", RT_AOV_NONE, &fb, &first) == RT_OK);
    rt_framebuffer_free(&fb);
    CHECK(render(s, "opencl", RT_AOV_NONE, &fb, &again) == RT_OK);
    rt_framebuffer_free(&fb);
    CHECK_EQ_INT(again.upload_bytes, 0);
    float m[16] = {1, 0, 0, 0.05f, 0, 1, 0, 0, 0, 0, 1, -0.1f, 0, 0, 0, 1};
    CHECK(rt_object_transform(s, 0, m) == RT_OK);
    CHECK(render(s, "opencl", RT_AOV_NONE, &fb, &moved) == RT_OK);
    CHECK_MSG(moved.upload_bytes > 0 && moved.upload_bytes < first.upload_bytes,
              "upload after a move: %llu bytes (first frame %llu)",
              (unsigned long long)moved.upload_bytes, (unsigned long long)first.upload_bytes);
    rt_framebuffer cpu;
    CHECK(render(s, "cpu", RT_AOV_NONE, &cpu, NULL) == RT_OK);
    same_pixels("keyframes (moved)", "image", &cpu, &fb);
    rt_framebuffer_free(&fb);
    rt_framebuffer_free(&cpu);
    rt_scene_destroy(s);
}
#endif

/* Random triangles in a box a few 1e-13 across: edge functions near 1e-26
 * and their products with z (t's numerator) near 1e-39, below the smallest
 * normal float, so the denormal policy decides many bits of t. */
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

/* Every AOV with the packet and the one-ray kernels, and ray queries. */
static void check_scene_profile(const char *name, rt_scene *s) {
    cl_tune.one_ray_kernels = 0;
    check_images(name, s);
    cl_tune.one_ray_kernels = 1;
    check_images(name, s);
    cl_tune.one_ray_kernels = 0;
    check_hits(name, s);
}

/* Closest hits of the oracle in the other denormal policy: some differ on
 * the denormal scene, or that scene would not test the policy. */
static void check_policy_matters(rt_scene *s) {
    enum { N = 4000 };
    const rt_flat *flat = test_layout(s, 0);
    if (!flat) return;
    float lo[3], hi[3];
    CHECK(rt_scene_bounds(s, lo, hi));
    rt_ray *rays = malloc(sizeof *rays * N);
    rt_hit *a = malloc(sizeof *a * N), *b = malloc(sizeof *b * N);
    for (int i = 0; i < N; i++) {
        rt_ray r;
        unit_ray(&flat->hdr, lo, hi, i, &r);
        memcpy(rays[i].org, r.org, sizeof r.org);
        memcpy(rays[i].dir, r.dir, sizeof r.dir);
        rays[i].tmin = r.tmin;
        rays[i].tmax = r.tmax;
    }
    rt_renderer_options o = rt_renderer_options_default();
    o.denormals = denormals == RT_DENORMALS_FLUSH ? RT_DENORMALS_PRESERVE : RT_DENORMALS_FLUSH;
    rt_error err;
    rt_renderer *other = test_renderer_with(&o, &err);
    rt_trace_options q = {0, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO, NULL, NULL};
    int differ = 0;
    if (other && rt_trace_rays(renderer_for("cpu"), s, rays, N, a, &q) == RT_OK &&
        rt_trace_rays(other, s, rays, N, b, &q) == RT_OK)
        for (int i = 0; i < N; i++)
            differ += a[i].hit != b[i].hit || memcmp(&a[i].t, &b[i].t, 4) != 0;
    CHECK_MSG(differ > 0, "the denormal scene gives the same hits in both policies");
    printf("denormal scene: %d of %d closest hits differ between the policies\n", differ, N);
    free(rays);
    free(a);
    free(b);
}

/* The profile run (RT_TEST_DEVICE_MATH / RT_TEST_DENORMALS). */
static void check_profile(void) {
    for (int kd = 0; kd < 2; kd++) /* BVH meshes, then kd-trees */
        for (int i = 0; rt_builtin_scene_names[i]; i++) {
            rt_scene *s = test_builtin_scene(rt_builtin_scene_names[i], 96, 54);
            if (!s) continue;
            char label[64];
            snprintf(label, sizeof label, "%s%s", rt_builtin_scene_names[i], kd ? " (kd)" : "");
            if (kd) CHECK(rt_scene_set_static_accel(s, RT_ACCEL_KD) == RT_OK);
            check_scene_profile(label, s);
            if (kd) check_hits_with(label, s, grid_ray);
            rt_scene_destroy(s);
        }
    static const char *const shipped[] = {"scenes/cornell.json", "scenes/keyframes.json"};
    for (int i = 0; i < 2; i++) {
        rt_scene *s = NULL;
        rt_error err;
        CHECK_MSG(rt_scene_load(test_source_path(shipped[i]), &s, &err) == RT_OK, "%s",
                  err.message);
        if (!s) continue;
        rt_camera cam;
        rt_camera_get(s, &cam);
        cam.width = 96;
        cam.height = 54;
        CHECK(rt_camera_set(s, &cam) == RT_OK);
        check_scene_profile(shipped[i], s);
        rt_scene_destroy(s);
    }
    /* Flushing on this scene breaks what makes the closest hit independent
     * of traversal order: a triangle's t numerator flushed to zero gives
     * t = 0 in a box whose entry distance is positive, so which of several
     * such triangles wins depends on which box is opened first. The one-ray
     * kernels traverse in the oracle's order and must match it; the packet
     * kernels are held to it only where denormals are kept
     * (docs/PORTABLE_MATH.md, "Flushing"). */
    rt_scene *s = denormal_scene();
    if (s) {
        cl_tune.one_ray_kernels = 1;
        check_hits_with("denormal scene (one-ray kernels)", s, unit_ray);
        cl_tune.one_ray_kernels = 0;
        if (denormals == RT_DENORMALS_PRESERVE) check_hits_with("denormal scene", s, unit_ray);
        check_policy_matters(s);
    }
    rt_scene_destroy(s);
}

int main(void) {
#ifndef RT_HAVE_OPENCL
    test_skip("this build has no OpenCL backend (RT_OPENCL=OFF or no ICD loader)");
#else
    rt_cl_device_info *devs;
    int count;
    if (rt_cl_devices(&devs, &count, &lib_err) != RT_OK) test_skip(lib_err.message);
    free(devs);
    const char *math = getenv("RT_TEST_DEVICE_MATH"), *dn = getenv("RT_TEST_DENORMALS");
    if (math && strcmp(math, "portable") == 0) cl_math = RT_DEVICE_MATH_PORTABLE;
    if (dn && strcmp(dn, "flush") == 0) denormals = RT_DENORMALS_FLUSH;
    if (cl_math != RT_DEVICE_MATH_AUTO || denormals != RT_DENORMALS_PRESERVE) {
        printf("profile: device maths %s, denormals %s\n", math, dn ? dn : "preserve");
        check_profile();
        return TEST_END();
    }
    /* BVH meshes, then every static mesh a kd-tree (the packet kernel's
     * pk_kd_mesh on a CPU device, the one-ray kernels' rt_kd_trace_mesh). */
    for (int kd = 0; kd < 2; kd++)
        for (int i = 0; rt_builtin_scene_names[i]; i++) {
            const char *name = rt_builtin_scene_names[i];
            char label[64];
            snprintf(label, sizeof label, "%s%s", name, kd ? " (kd)" : "");
            rt_scene *s;
            rt_error err;
            CHECK(rt_scene_builtin(name, &s, &err) == RT_OK);
            if (kd) CHECK(rt_scene_set_static_accel(s, RT_ACCEL_KD) == RT_OK);
            rt_camera cam;
            rt_camera_get(s, &cam);
            cam.width = 192; /* small: PoCL on a shared CPU */
            cam.height = 108;
            CHECK(rt_camera_set(s, &cam) == RT_OK);
            check_images(label, s);
            check_packet(label, s, !kd);
            if (strcmp(name, "cornell") == 0 && !kd) check_wavefront(s);
            check_hits(label, s);
            if (kd) check_hits_with(label, s, grid_ray);
            rt_scene_destroy(s);
        }
    check_uploads();
    check_device_options();
    /* A device that does not exist is an error with a reason. */
    rt_scene *s;
    rt_error err;
    CHECK(rt_scene_builtin("cornell", &s, &err) == RT_OK);
    rt_framebuffer fb;
    CHECK(render(s, "opencl:99", RT_AOV_NONE, &fb, NULL) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(error_of("opencl:99"), "no OpenCL device 99");
    rt_scene_destroy(s);
    return TEST_END();
#endif
}
