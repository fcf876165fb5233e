/* test_core_packet.c - the packet path renders bit-identical images to the
 * scalar oracle on every built-in scene (memcmp of the float framebuffers),
 * for the image (Whitted and direct-only) and the depth, primitive, instance
 * and normal AOVs, with every instruction-set build of the packet tracer the
 * CPU runs; the oracle's image does not depend on the thread count. Also
 * runs under qemu-aarch64, where the packet tracer is NEON. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "cpu_render.h"
#include "packet_trace.h"
#include "rt.h"
#include "scene/scene_builtin.h"

/* The packet renderers of the instruction-set build under test. */
static rt_renderer *packet_renderer[2]; /* 3 threads, 2 threads */

/* "cpu" on threads threads, or "packet" of the build under test. */
static rt_renderer *renderer_for(const char *backend, int threads) {
    if (strcmp(backend, "packet") == 0) return packet_renderer[threads == 3 ? 0 : 1];
    return test_renderer(backend, threads);
}

static int render(rt_scene *s, const char *backend, rt_aov aov, int threads, rt_framebuffer *fb,
                  rt_render_stats *st) {
    rt_render_options o = rt_render_options_default();
    o.aov = aov;
    o.stats = st;
    rt_renderer *r = renderer_for(backend, threads);
    rt_status status = rt_render(r, s, &o, fb);
    CHECK_MSG(status == RT_OK, "%s: %s", backend, rt_renderer_error(r));
    return status == RT_OK;
}

static int render_direct(rt_scene *s, const char *backend, rt_framebuffer *fb) {
    rt_render_options o = rt_render_options_default();
    o.direct_only = 1;
    rt_renderer *r = renderer_for(backend, 2);
    rt_status status = rt_render(r, s, &o, fb);
    CHECK_MSG(status == RT_OK, "%s: %s", backend, rt_renderer_error(r));
    return status == RT_OK;
}

static int same(const rt_framebuffer *a, const rt_framebuffer *b) {
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           memcmp(a->pixels, b->pixels,
                  sizeof(float) * (size_t)a->width * a->height * a->channels) == 0;
}

/* Every image and AOV of every built-in scene, Whitted and direct-only, on
 * the packet path's current instruction-set build. */
static void check_scenes(const char *isa) {
    const rt_aov aovs[] = {RT_AOV_NONE, RT_AOV_DEPTH, RT_AOV_PRIMID, RT_AOV_INSTID, RT_AOV_NORMAL};
    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        const char *name = rt_builtin_scene_names[i];
        rt_scene *s = test_builtin_scene(
            name, 193, 109); /* odd sizes: packets at the right and bottom edges */
        if (!s) continue;
        for (size_t a = 0; a < sizeof aovs / sizeof aovs[0]; a++) {
            rt_framebuffer c, p;
            rt_render_stats sc, sp;
            if (!render(s, "cpu", aovs[a], 2, &c, &sc)) continue;
            if (render(s, "packet", aovs[a], 3, &p, &sp)) {
                CHECK_MSG(same(&c, &p), "%s: packet (%s) differs from cpu (aov %d)", name, isa,
                          (int)aovs[a]);
                if (aovs[a] == RT_AOV_NONE) {
                    CHECK(sp.packets ==
                          (uint64_t)((193 + RT_PACKET_TILE_W - 1) / RT_PACKET_TILE_W) *
                              ((109 + RT_PACKET_TILE_H - 1) / RT_PACKET_TILE_H));
                    CHECK(sp.packet_box_tests > 0 && sp.rays == sc.rays);
                    CHECK(sc.primary_rays == 193u * 109u && sp.primary_rays == sc.primary_rays);
                }
                rt_framebuffer_free(&p);
            }
            if (aovs[a] == RT_AOV_NONE && render(s, "cpu", aovs[a], 1, &p, NULL)) {
                CHECK_MSG(same(&c, &p), "%s: the image depends on the thread count", name);
                rt_framebuffer_free(&p);
            }
            rt_framebuffer_free(&c);
        }
        /* The benchmark set-up: primary plus shadow rays only. */
        rt_framebuffer c, p;
        if (render_direct(s, "cpu", &c)) {
            if (render_direct(s, "packet", &p)) {
                CHECK_MSG(same(&c, &p), "%s: direct-only packet (%s) differs from cpu", name, isa);
                rt_framebuffer_free(&p);
            }
            rt_framebuffer_free(&c);
        }
        rt_scene_destroy(s);
    }
}

int main(void) {
    /* Each instruction-set build of the packet tracer this CPU runs. */
    int tested = 0;
    for (int k = 0; rt_pk_isa_name(k); k++) {
        if (!rt_pk_variant_find(rt_pk_isa_name(k))) {
            printf("packet build %s: not run, this CPU lacks it\n", rt_pk_isa_name(k));
            continue;
        }
        rt_renderer_options ro = rt_renderer_options_default();
        ro.backend = "packet";
        ro.packet_isa = rt_pk_isa_name(k);
        rt_error err;
        for (int t = 0; t < 2; t++) {
            ro.threads = t == 0 ? 3 : 2;
            packet_renderer[t] = test_renderer_with(&ro, &err);
            CHECK_MSG(packet_renderer[t] != NULL, "packet %s: %s", ro.packet_isa, err.message);
        }
        if (!packet_renderer[0] || !packet_renderer[1]) continue;
        printf("packet build %s\n", rt_pk_isa_name(k));
        check_scenes(rt_pk_isa_name(k));
        tested++;
    }
    CHECK(tested > 0);
    /* An unknown backend or instruction set is refused with a clear message,
     * and so is a device for a CPU backend. */
    rt_renderer_options o = rt_renderer_options_default();
    rt_renderer *r = NULL;
    rt_error err;
    o.backend = "warp";
    CHECK(rt_renderer_create(&o, &r, &err) == RT_ERROR_UNSUPPORTED && r == NULL);
    CHECK_CONTAINS(err.message, "backend 'warp'");
    o.backend = "packet";
    o.packet_isa = "mmx";
    CHECK(rt_renderer_create(&o, &r, &err) == RT_ERROR_UNSUPPORTED && r == NULL);
    CHECK_CONTAINS(err.message, "'mmx'");
    o.backend = "cpu:1";
    o.packet_isa = NULL;
    CHECK(rt_renderer_create(&o, &r, &err) == RT_ERROR_UNSUPPORTED && r == NULL);
    CHECK_CONTAINS(err.message, "takes no device");
    /* A failed switch keeps the backend. */
    o.backend = "packet";
    CHECK(rt_renderer_create(&o, &r, &err) == RT_OK);
    CHECK(rt_renderer_set_backend(r, "warp") == RT_ERROR_UNSUPPORTED);
    CHECK_CONTAINS(rt_renderer_error(r), "backend 'warp'");
    CHECK(strcmp(rt_renderer_backend(r), "packet") == 0);
    rt_renderer_destroy(r);
    return TEST_END();
}
