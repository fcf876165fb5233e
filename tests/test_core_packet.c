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

static int render(rt_scene *s, const char *backend, rt_aov aov, int threads, rt_framebuffer *fb,
                  rt_render_stats *st) {
    rt_render_options o = rt_render_options_default();
    o.backend = backend;
    o.aov = aov;
    o.threads = threads;
    o.stats = st;
    rt_status status = rt_render(s, &o, fb);
    CHECK_MSG(status == RT_OK, "%s: %s", backend, rt_scene_error(s));
    return status == RT_OK;
}

static int render_direct(rt_scene *s, const char *backend, rt_framebuffer *fb) {
    rt_render_options o = rt_render_options_default();
    o.backend = backend;
    o.direct_only = 1;
    o.threads = 2;
    rt_status status = rt_render(s, &o, fb);
    CHECK_MSG(status == RT_OK, "%s: %s", backend, rt_scene_error(s));
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
        if (!rt_pk_select(rt_pk_isa_name(k))) {
            printf("packet build %s: not run, this CPU lacks it\n", rt_pk_isa_name(k));
            continue;
        }
        printf("packet build %s\n", rt_pk_isa_name(k));
        check_scenes(rt_pk_isa_name(k));
        tested++;
    }
    CHECK(tested > 0);
    rt_pk_select(NULL);
    /* An unknown backend is refused with a clear message. */
    rt_scene *s;
    rt_error err;
    rt_scene_builtin("cornell", &s, &err);
    rt_render_options o = rt_render_options_default();
    o.backend = "warp";
    rt_framebuffer fb;
    CHECK(rt_render(s, &o, &fb) == RT_ERROR_UNSUPPORTED);
    CHECK_CONTAINS(rt_scene_error(s), "backend 'warp'");
    rt_scene_destroy(s);
    return TEST_END();
}
